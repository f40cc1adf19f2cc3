//! Production lots: `characterize --manifest` (one bank per unit, the units in parallel, and
//! the lot summary when every unit is run) and `lot summarize` (the summary from banks that
//! separate jobs wrote, e.g. a Slurm array with `--unit-index $SLURM_ARRAY_TASK_ID`).

use crate::args::{LotSummarizeArgs, ReadingArg};
use crate::banks::building::{BankInputs, build_bank_reading};
use crate::failure::{Classify, Failure};
use crate::inputs::read_bank;
use crate::report::print_json;
use crate::settings::characterization::{LotJob, UnitChoice};
use crate::thermal::calibration::ThermalInputs;
use anyhow::anyhow;
use serde::Serialize;
use std::path::{Path, PathBuf};
use thermonav::imu::Channel;
use thermonav::stoch::bank::{GaussMarkovSource, ModelBank};
use thermonav::stoch::characterize::CharacterizeSettings;
use thermonav::stoch::lot::{LotSummary, Quantity, UnitBank, summarize_lot};
use thermonav_io::lot::{Conditioning, LotManifest, LotUnit, read_manifest};
use thermonav_io::write_json_atomically;

/// Name of the lot summary in the output folder.
pub const SUMMARY_FILE: &str = "lot-summary.json";

/// Where a unit's bank goes: `DIR/SERIAL/bank.json`.
fn bank_path(dir: &Path, serial: &str) -> PathBuf {
    dir.join(serial).join("bank.json")
}

/// What happened to one unit, for `--json`.
#[derive(Debug, Serialize)]
struct UnitOutcome {
    serial: String,
    bank: Option<String>,
    error: Option<String>,
}

/// The result of `characterize --manifest`, for `--json`.
#[derive(Debug, Serialize)]
struct LotRun<'a> {
    lot: &'a str,
    out_dir: String,
    units: Vec<UnitOutcome>,
    summary_file: Option<String>,
    summary: Option<LotSummary>,
}

/// Runs `characterize --manifest`: the chosen units (all by default) in parallel, each to its
/// own bank; the summary when every unit of the lot ran and succeeded. A failed unit does not
/// stop the others; the run then ends with an error naming every failed unit.
pub fn characterize_lot(job: &LotJob, json: bool) -> Result<(), Failure> {
    let manifest_path = job.manifest.as_path();
    use rayon::prelude::*;
    let manifest = read_manifest(manifest_path).data()?;
    let units = selected_units(&manifest, &job.units, manifest_path)?;
    let settings = lot_settings(job.conditioning.clone(), &manifest.conditioning);
    let results: Vec<Result<ModelBank, String>> = units
        .par_iter()
        .map(|unit| characterize_unit(unit, &settings, job.reading, &job.out))
        .collect();
    let every_unit_done = units.len() == manifest.units.len() && results.iter().all(Result::is_ok);
    let summary = match every_unit_done {
        true => Some(summarize_written_banks(&manifest, &job.out)?),
        false => {
            // Some bank changed or failed: an earlier summary no longer describes the lot
            // (`lot summarize` writes the new one once every unit's job has run).
            remove_if_present(&job.out.join(SUMMARY_FILE))?;
            None
        }
    };
    let outcomes = outcomes_of(&units, &results, &job.out);
    let failures: Vec<&str> = outcomes.iter().filter_map(|o| o.error.as_deref()).collect();
    let failure = (!failures.is_empty()).then(|| {
        Failure::Data(anyhow!(
            "{} of {} units failed:\n  {}",
            failures.len(),
            units.len(),
            failures.join("\n  ")
        ))
    });
    print_lot_run(&manifest, &job.out, json, outcomes, summary)?;
    failure.map_or(Ok(()), Err)
}

/// The units a run asked for: `--unit SERIAL`, `--unit-index N`, or all.
fn selected_units<'m>(
    manifest: &'m LotManifest,
    choice: &UnitChoice,
    manifest_path: &Path,
) -> Result<Vec<&'m LotUnit>, Failure> {
    let serials = || {
        let all: Vec<&str> = manifest.units.iter().map(|u| u.serial.as_str()).collect();
        all.join(", ")
    };
    match choice {
        UnitChoice::Serial(serial) => match manifest.units.iter().find(|u| u.serial == *serial) {
            Some(unit) => Ok(vec![unit]),
            None => Err(Failure::Usage(anyhow!(
                "--unit {serial}: no such unit in {} (its serials: {})",
                manifest_path.display(),
                serials()
            ))),
        },
        UnitChoice::Index(index) => match manifest.units.get(*index) {
            Some(unit) => Ok(vec![unit]),
            None => Err(Failure::Usage(anyhow!(
                "--unit-index {index}: {} has {} units (expected 0 to {})",
                manifest_path.display(),
                manifest.units.len(),
                manifest.units.len().saturating_sub(1)
            ))),
        },
        UnitChoice::All => Ok(manifest.units.iter().collect()),
    }
}

/// The command's settings with the manifest's `[defaults]` in place of its own.
fn lot_settings(mut settings: CharacterizeSettings, given: &Conditioning) -> CharacterizeSettings {
    settings.cutoff_hz = given.cutoff_hz.unwrap_or(settings.cutoff_hz);
    settings.transition_hz = given.transition_hz.unwrap_or(settings.transition_hz);
    settings.modelling_rate_hz = given
        .modelling_rate_hz
        .unwrap_or(settings.modelling_rate_hz);
    settings
}

/// Characterises one unit into `DIR/SERIAL/bank.json`; the error names the unit.
///
/// A unit that fails loses the bank an earlier run wrote for it, so that no summary can mix
/// that stale bank with the new ones, and its folder when that leaves it empty.
fn characterize_unit(
    unit: &LotUnit,
    settings: &CharacterizeSettings,
    reading: ReadingArg,
    dir: &Path,
) -> Result<ModelBank, String> {
    let fail = |what: String| format!("unit {}: {what}", unit.serial);
    let folder = dir.join(&unit.serial);
    std::fs::create_dir_all(&folder).map_err(|e| {
        fail(format!(
            "{}: cannot create the folder: {e}",
            folder.display()
        ))
    })?;
    let files: Vec<&Path> = unit.files.iter().map(PathBuf::as_path).collect();
    let temperatures = unit.temperatures_c.as_deref().unwrap_or(&[]);
    let bank = bank_path(dir, &unit.serial);
    let inputs = BankInputs {
        files: &files,
        temperatures,
        thermal: &ThermalInputs::default(),
    };
    build_bank_reading(&inputs, settings, reading, &bank).map_err(|failure| {
        let stale = remove_if_present(&bank).err().map(|e| format!("; {e}"));
        // The unit's folder goes too when nothing else is in it (remove_dir refuses otherwise).
        let _ = std::fs::remove_dir(&folder);
        fail(format!("{failure}{}", stale.unwrap_or_default()))
    })
}

/// Removes `path` if it exists (a stale output of an earlier run).
fn remove_if_present(path: &Path) -> Result<(), Failure> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(anyhow!(
            "{}: cannot remove the stale file: {e}",
            path.display()
        ))
        .data(),
        _ => Ok(()),
    }
}

/// Each unit's bank path or error.
fn outcomes_of(
    units: &[&LotUnit],
    results: &[Result<ModelBank, String>],
    dir: &Path,
) -> Vec<UnitOutcome> {
    units
        .iter()
        .zip(results)
        .map(|(unit, result)| UnitOutcome {
            serial: unit.serial.clone(),
            bank: result
                .as_ref()
                .ok()
                .map(|_| bank_path(dir, &unit.serial).display().to_string()),
            error: result.as_ref().err().cloned(),
        })
        .collect()
}

/// Summarises the lot and writes `DIR/lot-summary.json` atomically.
fn write_summary(
    lot: &str,
    banks: &[(&str, &ModelBank)],
    dir: &Path,
) -> Result<LotSummary, Failure> {
    let units: Vec<UnitBank<'_>> = banks
        .iter()
        .map(|(serial, bank)| UnitBank { serial, bank })
        .collect();
    let summary = summarize_lot(lot, &units).data()?;
    write_json_atomically(dir.join(SUMMARY_FILE), &summary).data()?;
    Ok(summary)
}

/// Prints the run: JSON, or one line per unit and the summary table.
fn print_lot_run(
    manifest: &LotManifest,
    out: &Path,
    json: bool,
    units: Vec<UnitOutcome>,
    summary: Option<LotSummary>,
) -> Result<(), Failure> {
    let summary_file = summary
        .as_ref()
        .map(|_| out.join(SUMMARY_FILE).display().to_string());
    if json {
        return print_json(&LotRun {
            lot: &manifest.name,
            out_dir: out.display().to_string(),
            units,
            summary_file,
            summary,
        });
    }
    for unit in &units {
        match (&unit.bank, &unit.error) {
            (Some(bank), _) => println!("{:<16} bank written to {bank}", unit.serial),
            (None, _) => println!("{:<16} FAILED (see below)", unit.serial),
        }
    }
    if let (Some(summary), Some(file)) = (&summary, &summary_file) {
        println!();
        print_summary_table(summary);
        println!("\nlot summary written to {file}");
    }
    Ok(())
}

/// Runs `lot summarize`.
pub fn run_summarize(args: &LotSummarizeArgs) -> Result<(), Failure> {
    let manifest = read_manifest(&args.manifest).data()?;
    let summary = summarize_written_banks(&manifest, &args.dir)?;
    if args.json {
        return print_json(&summary);
    }
    print_summary_table(&summary);
    println!(
        "\nlot summary written to {}",
        args.dir.join(SUMMARY_FILE).display()
    );
    Ok(())
}

/// Reads every unit's bank back from `DIR/SERIAL/bank.json`, summarises the lot and writes
/// `DIR/lot-summary.json`. Both the all-units run and `lot summarize` come here, so the summary
/// is always that of the files as written (whatever jobs wrote them).
fn summarize_written_banks(manifest: &LotManifest, dir: &Path) -> Result<LotSummary, Failure> {
    let results: Vec<Result<ModelBank, String>> = manifest
        .units
        .iter()
        .map(|u| {
            read_bank(&bank_path(dir, &u.serial))
                .map_err(|failure| format!("unit {}: {failure}", u.serial))
        })
        .collect();
    let missing: Vec<&str> = results
        .iter()
        .filter_map(|r| r.as_ref().err().map(String::as_str))
        .collect();
    if !missing.is_empty() {
        return Err(Failure::Data(anyhow!(
            "{} of {} banks cannot be used (run those units first):\n  {}",
            missing.len(),
            results.len(),
            missing.join("\n  ")
        )));
    }
    let banks: Vec<(&str, &ModelBank)> = manifest
        .units
        .iter()
        .zip(&results)
        .filter_map(|(u, r)| Some((u.serial.as_str(), r.as_ref().ok()?)))
        .collect();
    write_summary(&manifest.name, &banks, dir)
}

/// The quantities of the table (the JSON has every family and Allan term).
const TABLE_QUANTITIES: [Quantity; 4] = [
    Quantity::CorrelationTime(GaussMarkovSource::IRREGULAR_ML),
    Quantity::Sigma(GaussMarkovSource::IRREGULAR_ML),
    Quantity::WhiteNoiseDensity,
    Quantity::BiasInstability,
];

/// The lot table: per point, channel and quantity, the units with a value (n), median, range,
/// MAD and outliers.
fn print_summary_table(summary: &LotSummary) {
    println!(
        "lot {}: {} units; exact-ML Gauss-Markov and Allan terms (every family in the JSON)",
        summary.lot,
        summary.units.len()
    );
    println!(
        "{:>7} {:<3} {:<40} {:>3} {:>11} {:>11} {:>11} {:>11}  outliers",
        "temp_C", "ch", "quantity", "n", "median", "min", "max", "MAD"
    );
    for point in &summary.points {
        for channel in Channel::ALL {
            let Some(spreads) = point.channels.get(&channel) else {
                continue;
            };
            for quantity in TABLE_QUANTITIES {
                let key = quantity.key(channel.sensor());
                let Some(s) = spreads.get(&key) else {
                    continue;
                };
                let outliers: Vec<&str> = s.outliers.iter().map(|o| o.serial.as_str()).collect();
                println!(
                    "{:>7.1} {:<3} {:<40} {:>3} {:>11} {:>11} {:>11} {:>11}  {}",
                    point.temperature_c,
                    channel.name(),
                    key,
                    s.units_with_value,
                    number(s.median),
                    number(s.min),
                    number(s.max),
                    number(s.mad),
                    outliers.join(",")
                );
            }
        }
    }
    println!("\noutlier rule: {}", summary.outlier_rule);
    println!(
        "{} outlying values in lot-summary.json",
        summary.outliers.len()
    );
}

/// A number in fixed notation when it reads well so, scientific otherwise.
fn number(value: f64) -> String {
    match value.abs() {
        v if v == 0.0 || (0.01..1e5).contains(&v) => format!("{value:.3}"),
        _ => format!("{value:.3e}"),
    }
}
