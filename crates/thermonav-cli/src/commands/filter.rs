//! `thermonav filter`: Kaiser low-pass every channel, optionally decimate, record what was done.

use crate::args::{FilterArgs, ModeArg};
use crate::failure::{Classify, Failure};
use crate::fir_design::{FirDesign, describe, design};
use crate::report::{print_json, print_rows};
use anyhow::anyhow;
use serde::Serialize;
use std::path::Path;
use thermonav::imu::ImuSeries;
use thermonav::signal::decimate::{decimate_valid, decimation_factor};
use thermonav::signal::kaiser::FirFilter;
use thermonav::signal::timestamps::{TimingReport, check_timestamps};
use thermonav::signal::zero_phase::{
    ZeroPhaseMode, decimation_edge_samples, filter_for_mode, filter_zero_phase,
};
use thermonav_io::{Strictness, read_imu_file, write_imu_file, write_json_atomically};

/// The sidecar JSON written next to the output (and printed by `--json`).
#[derive(Debug, Serialize)]
pub struct FilterRecord {
    input: String,
    output: String,
    thermonav_version: &'static str,
    rows_in: usize,
    rows_out: usize,
    input_nominal_rate_hz: f64,
    input_gap_count: usize,
    mode: &'static str,
    filter: FirDesign,
    decimation_factor: usize,
    output_rate_hz: f64,
    /// Input samples left out at each end (outputs that would read the edge extension).
    edge_samples_dropped: usize,
    temperature_column: &'static str,
}

/// Runs `filter`.
pub fn run(args: &FilterArgs) -> Result<(), Failure> {
    crate::settings::analysis::check_filter(args)?;
    let series = read_imu_file(&args.input, Strictness::Strict).data()?;
    let timing = check_timestamps(&series.time);
    let nominal_rate_hz = nominal_rate_of(&timing, &args.input)?;
    let design_rate_hz = args.fs_hz.unwrap_or(nominal_rate_hz);
    let (spec, designed) = design(design_rate_hz, &args.kaiser)?;
    let mode = args.mode.into();
    let filter = filter_for_mode(designed, &spec, mode);
    let factor = resolve_decimation(args, &filter)?;
    let filtered = filter_series(&series, &filter, mode, factor).data()?;
    let record = FilterRecord {
        input: args.input.display().to_string(),
        output: args.out.display().to_string(),
        thermonav_version: env!("CARGO_PKG_VERSION"),
        rows_in: series.len(),
        rows_out: filtered.len(),
        input_nominal_rate_hz: nominal_rate_hz,
        input_gap_count: timing.gap_count,
        mode: mode_name(args.mode),
        filter: describe(&filter, &args.kaiser),
        decimation_factor: factor,
        output_rate_hz: design_rate_hz / factor as f64,
        edge_samples_dropped: decimation_edge_samples(&filter, mode, factor),
        temperature_column: "not filtered; decimated with the samples",
    };
    write_outputs(&args.out, &filtered, &record)?;
    warn_about_gaps(&args.input, timing.gap_count);
    report(args.json, &record)
}

/// The input's nominal sample rate; an error when it has fewer than two samples.
fn nominal_rate_of(timing: &TimingReport, input: &Path) -> Result<f64, Failure> {
    timing
        .intervals
        .map(|s| s.nominal_rate_hz())
        .ok_or_else(|| Failure::Data(anyhow!("{}: fewer than two samples", input.display())))
}

/// The warning that the filter treats a record with gaps as evenly spaced.
fn warn_about_gaps(input: &Path, gap_count: usize) {
    if gap_count > 0 {
        eprintln!(
            "warning: {} has {} gaps longer than 1.5 sampling intervals; the filter treats the samples as evenly spaced",
            input.display(),
            gap_count
        );
    }
}

/// The name of `--mode` as the record gives it.
fn mode_name(mode: ModeArg) -> &'static str {
    match mode {
        ModeArg::ZeroPhase => "zero-phase",
        ModeArg::Filtfilt => "filtfilt",
    }
}

/// The decimation factor (1 without `--decimate-to-hz`); the anti-alias rule was checked with
/// the other arguments, before reading (`settings::analysis::check_filter`).
fn resolve_decimation(args: &FilterArgs, filter: &FirFilter) -> Result<usize, Failure> {
    let Some(target_hz) = args.decimate_to_hz else {
        return Ok(1);
    };
    decimation_factor(filter.sample_rate_hz(), target_hz).usage()
}

/// Filters every channel and keeps every `factor`-th sample, leaving out with decimation the
/// outputs nearer an end than the filter's response (they would come from the edge
/// extension; the first would be the raw first sample); the temperature column is carried
/// along unfiltered.
pub fn filter_series(
    series: &ImuSeries,
    filter: &FirFilter,
    mode: ZeroPhaseMode,
    factor: usize,
) -> Result<ImuSeries, thermonav::signal::SignalError> {
    let edge = decimation_edge_samples(filter, mode, factor);
    let mut out = ImuSeries {
        time: decimate_valid(&series.time, edge, factor),
        temperature_c: (series.temperature_c.as_ref()).map(|t| decimate_valid(t, edge, factor)),
        kind: series.kind,
        ..ImuSeries::default()
    };
    for (column, input) in out.channels.iter_mut().zip(&series.channels) {
        *column = decimate_valid(&filter_zero_phase(filter, input, mode)?, edge, factor);
    }
    Ok(out)
}

/// Writes the filtered series and its JSON record.
fn write_outputs(out: &Path, series: &ImuSeries, record: &FilterRecord) -> Result<(), Failure> {
    write_imu_file(out, series).data()?;
    write_json_atomically(crate::settings::analysis::json_sidecar(out), record).data()
}

/// Prints the record, as JSON with `--json`.
fn report(json: bool, record: &FilterRecord) -> Result<(), Failure> {
    if json {
        return print_json(record);
    }
    print_rows(&summary_rows(record));
    Ok(())
}

/// The text summary: input, filter, decimation, output and where the record is.
fn summary_rows(record: &FilterRecord) -> [(&'static str, String); 5] {
    [
        (
            "input",
            format!(
                "{} ({} rows, {:.3} Hz)",
                record.input, record.rows_in, record.input_nominal_rate_hz
            ),
        ),
        (
            "filter",
            format!(
                "Kaiser low-pass, {} taps, beta {:.4}, {}",
                record.filter.num_taps, record.filter.beta, record.mode
            ),
        ),
        (
            "decimation",
            format!(
                "x{} -> {:.3} Hz",
                record.decimation_factor, record.output_rate_hz
            ),
        ),
        (
            "output",
            format!("{} ({} rows)", record.output, record.rows_out),
        ),
        (
            "record",
            crate::settings::analysis::json_sidecar(Path::new(&record.output))
                .display()
                .to_string(),
        ),
    ]
}
