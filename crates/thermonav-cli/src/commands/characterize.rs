//! `thermonav characterize`: the temperature model bank from static records.

use super::characterize_streaming::{characterize_streaming, streams};
use crate::args::{CharacterizeArgs, ReadingArg};
use crate::failure::{Classify, Failure};
use crate::report::print_json;
use anyhow::anyhow;
use serde::Serialize;
use std::path::Path;
use thermonav::imu::ImuSeries;
use thermonav::stoch::bank::{GaussMarkovEstimate, ModelBank, TemperatureEntry};
use thermonav::stoch::characterize::{CharacterizeSettings, characterize};
use thermonav_io::{Strictness, read_imu_file, write_json_atomically};

/// Settings of a run from the command line (the rest at their documented defaults).
pub fn settings_of(args: &CharacterizeArgs) -> CharacterizeSettings {
    CharacterizeSettings {
        cutoff_hz: args.cutoff_hz,
        transition_hz: args.transition_hz,
        modelling_rate_hz: args.modelling_rate_hz,
        ..CharacterizeSettings::default()
    }
}

/// The temperature of a record: given, or the mean of its temp_c column.
fn temperature_of(path: &Path, series: &ImuSeries, given: Option<f64>) -> Result<f64, Failure> {
    if let Some(t) = given {
        return Ok(t);
    }
    series.mean_temperature_c().ok_or_else(|| {
        Failure::Usage(anyhow!(
            "{}: no temp_c column; give the temperature with --temperature-c",
            path.display()
        ))
    })
}

/// Characterises one file, whole in memory or streamed as `reading` says.
pub fn characterize_file(
    path: &Path,
    given: Option<f64>,
    settings: &CharacterizeSettings,
    reading: ReadingArg,
) -> Result<TemperatureEntry, Failure> {
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    if streams(path, reading) {
        return characterize_streaming(path, given, settings, &name);
    }
    let series = read_imu_file(path, Strictness::Strict).data()?;
    let temperature_c = temperature_of(path, &series, given)?;
    let (entry, _) = characterize(&series, temperature_c, &name, settings)
        .map_err(|e| anyhow!("{}: {e}", path.display()))
        .data()?;
    Ok(entry)
}

/// Builds the bank of `files` (in parallel) and writes it atomically.
pub fn build_bank(
    files: &[&Path],
    temperatures: &[f64],
    settings: &CharacterizeSettings,
    out: &Path,
) -> Result<ModelBank, Failure> {
    build_bank_reading(files, temperatures, settings, ReadingArg::Auto, out)
}

/// [`build_bank`] with each file read as `reading` says.
pub fn build_bank_reading(
    files: &[&Path],
    temperatures: &[f64],
    settings: &CharacterizeSettings,
    reading: ReadingArg,
    out: &Path,
) -> Result<ModelBank, Failure> {
    use rayon::prelude::*;
    let progress = crate::progress::bar(files.len(), "characterising static records");
    let entries: Vec<Result<TemperatureEntry, Failure>> = files
        .par_iter()
        .enumerate()
        .map(|(k, path)| {
            let entry = characterize_file(path, temperatures.get(k).copied(), settings, reading);
            progress.inc(1);
            entry
        })
        .collect();
    progress.finish_and_clear();
    let entries = entries.into_iter().collect::<Result<Vec<_>, _>>()?;
    let bank = ModelBank::new(entries).data()?;
    write_json_atomically(out, &bank).data()?;
    Ok(bank)
}

#[derive(Debug, Serialize)]
struct Summary<'a> {
    bank: String,
    temperatures_c: Vec<f64>,
    entries: Vec<EntrySummary<'a>>,
}

#[derive(Debug, Serialize)]
struct EntrySummary<'a> {
    temperature_c: f64,
    source: &'a str,
    channels: Vec<ChannelSummary<'a>>,
}

#[derive(Debug, Serialize)]
struct ChannelSummary<'a> {
    channel: &'static str,
    unit: &'a str,
    irregular_ml: &'a GaussMarkovEstimate,
    ar_based: &'a GaussMarkovEstimate,
    acf_fit: &'a GaussMarkovEstimate,
    white_noise_density: Option<f64>,
}

/// Runs `characterize`.
pub fn run(args: &CharacterizeArgs) -> Result<(), Failure> {
    if let Some(manifest) = &args.manifest {
        return super::lot::characterize_lot(args, manifest);
    }
    if !args.temperature_c.is_empty() && args.temperature_c.len() != args.files.len() {
        return Err(Failure::Usage(anyhow!(
            "--temperature-c has {} values for {} files",
            args.temperature_c.len(),
            args.files.len()
        )));
    }
    let files: Vec<&Path> = args.files.iter().map(|p| p.as_path()).collect();
    let bank = build_bank_reading(
        &files,
        &args.temperature_c,
        &settings_of(args),
        args.reading,
        &args.out,
    )?;
    let summary = summarize(&bank, &args.out);
    if args.json {
        return print_json(&summary);
    }
    print_bank_table(&bank);
    println!("\nbank written to {}", args.out.display());
    Ok(())
}

fn summarize<'a>(bank: &'a ModelBank, out: &Path) -> Summary<'a> {
    Summary {
        bank: out.display().to_string(),
        temperatures_c: bank.temperatures_c(),
        entries: bank
            .entries
            .iter()
            .map(|e| EntrySummary {
                temperature_c: e.temperature_c,
                source: &e.source,
                channels: e
                    .channels
                    .iter()
                    .map(|(c, m)| ChannelSummary {
                        channel: c.name(),
                        unit: &m.unit,
                        irregular_ml: &m.gauss_markov.irregular_ml,
                        ar_based: &m.gauss_markov.ar_based,
                        acf_fit: &m.gauss_markov.acf_fit,
                        white_noise_density: m.allan.white_noise_density,
                    })
                    .collect(),
            })
            .collect(),
    }
}

/// "123.4 s [100.2, 150.3]" or "none".
pub fn show_estimate(e: &GaussMarkovEstimate) -> String {
    match e {
        GaussMarkovEstimate::Model {
            correlation_time_s,
            ci95_correlation_time_s: [None, None],
            ..
        } => format!("{correlation_time_s:.1}"),
        GaussMarkovEstimate::Model {
            correlation_time_s,
            ci95_correlation_time_s: [lo, hi],
            ..
        } => {
            let side = |v: &Option<f64>| v.map_or("inf".to_string(), |v| format!("{v:.1}"));
            format!("{correlation_time_s:.1} [{}, {}]", side(lo), side(hi))
        }
        GaussMarkovEstimate::NoEquivalent { .. } => "none".to_string(),
    }
}

/// The bank as a table of correlation times.
pub fn print_bank_table(bank: &ModelBank) {
    println!(
        "{:>7} {:<4} {:>28} {:>28} {:>16}",
        "temp_C", "ch", "Tc exact ML s [95 %]", "Tc AR-based s [95 %]", "Tc ACF fit s"
    );
    for e in &bank.entries {
        for (c, m) in &e.channels {
            let g = &m.gauss_markov;
            println!(
                "{:>7.1} {:<4} {:>28} {:>28} {:>16}",
                e.temperature_c,
                c.name(),
                show_estimate(&g.irregular_ml),
                show_estimate(&g.ar_based),
                show_estimate(&g.acf_fit)
            );
        }
    }
}
