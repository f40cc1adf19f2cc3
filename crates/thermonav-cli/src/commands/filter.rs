//! `thermonav filter`: de-noise every channel (the Kaiser low-pass, optionally decimated, or
//! wavelet shrinkage), record what was done.

use crate::failure::{Classify, Failure};
use crate::fir_design::{FirDesign, describe};
use crate::report::{print_json, print_rows};
use crate::settings::analysis::{
    FilterPlan, KaiserPlan, json_sidecar, resolve_filter, wavelet_level,
};
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;
use thermonav::imu::{Channel, ImuSeries, SampleKind};
use thermonav::signal::decimate::decimate_valid;
use thermonav::signal::kaiser::FirFilter;
use thermonav::signal::timestamps::{TimingReport, check_timestamps};
use thermonav::signal::wavelet::denoise::{Denoised, WaveletDenoise, denoise};
use thermonav::signal::zero_phase::{ZeroPhaseMode, decimation_edge_samples, filter_zero_phase};
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
    output_rate_hz: f64,
    /// What was done: `"method": "kaiser"` or `"wavelet"` and its own fields.
    #[serde(flatten)]
    method: MethodRecord,
    temperature_column: &'static str,
}

/// The method and what it did.
#[derive(Debug, Serialize)]
#[serde(tag = "method", rename_all = "lowercase")]
enum MethodRecord {
    Kaiser(KaiserRecord),
    Wavelet(WaveletRecord),
}

/// The Kaiser low-pass as run.
#[derive(Debug, Serialize)]
struct KaiserRecord {
    mode: &'static str,
    filter: FirDesign,
    decimation_factor: usize,
    /// Input samples left out at each end (outputs that would read the edge extension).
    edge_samples_dropped: usize,
}

/// The wavelet shrinkage as run: its settings and, per channel, σ̂ and the thresholds.
#[derive(Debug, Serialize)]
struct WaveletRecord {
    wavelet: String,
    level: usize,
    extension: &'static str,
    threshold: &'static str,
    thresholding: &'static str,
    channels: ChannelRecords,
}

/// σ̂ and the threshold of every level (finest first), in `unit`.
#[derive(Debug, Serialize)]
struct WaveletChannelRecord {
    unit: &'static str,
    noise_sigma: f64,
    thresholds_finest_first: Vec<f64>,
}

/// A de-noised series and the record of how.
type Conditioned = (ImuSeries, MethodRecord);

/// The de-noised series and what was done to each channel.
type Shrunk = (ImuSeries, ChannelRecords);

/// σ̂ and thresholds per channel name.
type ChannelRecords = BTreeMap<&'static str, WaveletChannelRecord>;

/// Runs `filter`.
pub fn run(args: &crate::args::FilterArgs) -> Result<(), Failure> {
    let plan = resolve_filter(args)?;
    let series = read_imu_file(&args.input, Strictness::Strict).data()?;
    let timing = check_timestamps(&series.time);
    let nominal_rate_hz = nominal_rate_of(&timing, &args.input)?;
    let (filtered, method) = match &plan {
        FilterPlan::Kaiser(k) => run_kaiser(k, &series, nominal_rate_hz)?,
        FilterPlan::Wavelet(w) => run_wavelet(w, &series, &args.input)?,
    };
    let record = FilterRecord {
        input: args.input.display().to_string(),
        output: args.out.display().to_string(),
        thermonav_version: env!("CARGO_PKG_VERSION"),
        rows_in: series.len(),
        rows_out: filtered.len(),
        input_nominal_rate_hz: nominal_rate_hz,
        input_gap_count: timing.gap_count,
        output_rate_hz: method.output_rate_hz(nominal_rate_hz),
        method,
        temperature_column: "not filtered; decimated with the samples",
    };
    write_outputs(&args.out, &filtered, &record)?;
    warn_about_gaps(&args.input, timing.gap_count);
    report(args.json, &record)
}

/// The Kaiser path: design at the file's rate (or --fs-hz), filter, decimate.
fn run_kaiser(plan: &KaiserPlan, x: &ImuSeries, rate_hz: f64) -> Result<Conditioned, Failure> {
    let (filter, factor) = plan.design_at(rate_hz)?;
    let filtered = filter_series(x, &filter, plan.mode, factor).data()?;
    Ok((filtered, kaiser_record(plan, &filter, factor)))
}

fn kaiser_record(plan: &KaiserPlan, filter: &FirFilter, factor: usize) -> MethodRecord {
    MethodRecord::Kaiser(KaiserRecord {
        mode: plan.mode.name(),
        filter: describe(filter, &plan.kaiser),
        decimation_factor: factor,
        edge_samples_dropped: decimation_edge_samples(filter, plan.mode, factor),
    })
}

/// The wavelet path: every channel shrunk at the record's rate, same rows out.
fn run_wavelet(w: &WaveletDenoise, x: &ImuSeries, input: &Path) -> Result<Conditioned, Failure> {
    let level = wavelet_level(w, x.len(), input)?;
    let (out, channels) = shrink_channels(w, x)?;
    Ok((
        out,
        MethodRecord::Wavelet(wavelet_record(w, level, channels)),
    ))
}

/// Every channel de-noised, and what was done to each.
fn shrink_channels(w: &WaveletDenoise, x: &ImuSeries) -> Result<Shrunk, Failure> {
    let (mut out, mut channels) = (x.clone(), BTreeMap::new());
    for channel in Channel::ALL {
        let shrunk = denoise(x.channel(channel), w).data()?;
        channels.insert(channel.name(), channel_record(channel, x.kind, &shrunk));
        out.channels[channel.index()] = shrunk.values;
    }
    Ok((out, channels))
}

fn channel_record(c: Channel, kind: Option<SampleKind>, d: &Denoised) -> WaveletChannelRecord {
    WaveletChannelRecord {
        unit: c.si_unit(kind.unwrap_or(SampleKind::Rates)),
        noise_sigma: d.noise_sigma,
        thresholds_finest_first: d.thresholds.clone(),
    }
}

fn wavelet_record(w: &WaveletDenoise, level: usize, channels: ChannelRecords) -> WaveletRecord {
    WaveletRecord {
        wavelet: w.wavelet.to_string(),
        level,
        extension: w.mode.name(),
        threshold: w.rule.name(),
        thresholding: w.thresholding.name(),
        channels,
    }
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
    write_json_atomically(json_sidecar(out), record).data()
}

/// Prints the record, as JSON with `--json`.
fn report(json: bool, record: &FilterRecord) -> Result<(), Failure> {
    if json {
        return print_json(record);
    }
    print_rows(&summary_rows(record));
    Ok(())
}

impl MethodRecord {
    /// The method in one line.
    fn describe(&self) -> String {
        match self {
            MethodRecord::Kaiser(k) => k.describe(),
            MethodRecord::Wavelet(w) => w.describe(),
        }
    }

    /// The decimation factor (1 for the wavelet method).
    fn decimation_factor(&self) -> usize {
        match self {
            MethodRecord::Kaiser(k) => k.decimation_factor,
            MethodRecord::Wavelet(_) => 1,
        }
    }

    /// The output rate, Hz, from the input's nominal rate.
    fn output_rate_hz(&self, input_rate_hz: f64) -> f64 {
        match self {
            MethodRecord::Kaiser(k) => k.filter.sample_rate_hz / k.decimation_factor as f64,
            MethodRecord::Wavelet(_) => input_rate_hz,
        }
    }
}

impl KaiserRecord {
    fn describe(&self) -> String {
        let f = &self.filter;
        format!(
            "Kaiser low-pass, {} taps, beta {:.4}, {}",
            f.num_taps, f.beta, self.mode
        )
    }
}

impl WaveletRecord {
    fn describe(&self) -> String {
        format!(
            "wavelet shrinkage, {} level {}, {} extension, {} threshold, {}",
            self.wavelet, self.level, self.extension, self.threshold, self.thresholding
        )
    }
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
        ("filter", record.method.describe()),
        (
            "decimation",
            format!(
                "x{} -> {:.3} Hz",
                record.method.decimation_factor(),
                record.output_rate_hz
            ),
        ),
        (
            "output",
            format!("{} ({} rows)", record.output, record.rows_out),
        ),
        (
            "record",
            json_sidecar(Path::new(&record.output))
                .display()
                .to_string(),
        ),
    ]
}
