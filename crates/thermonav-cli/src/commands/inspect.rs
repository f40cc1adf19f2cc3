//! `thermonav inspect`: the sanity check a user runs before modelling.

use crate::args::InspectArgs;
use crate::failure::{Classify, Failure};
use crate::report::{print_json, print_rows};
use serde::Serialize;
use std::path::Path;
use thermonav::imu::{Channel, ImuSeries, SampleKind};
use thermonav::signal::timestamps::{OrderFault, TimingReport, check_timestamps};
use thermonav::time::Timestamp;
use thermonav_io::{Strictness, read_gnss_file, read_imu_file, read_trajectory_file};

/// The JSON document of `inspect --json`.
#[derive(Debug, Serialize)]
pub struct Inspection {
    file: String,
    rows: usize,
    content: &'static str,
    duration_s: f64,
    nominal_rate_hz: Option<f64>,
    median_dt_s: Option<f64>,
    dt_mean_s: Option<f64>,
    dt_std_s: Option<f64>,
    dt_min_s: Option<f64>,
    dt_max_s: Option<f64>,
    gap_count: usize,
    gaps: Vec<GapRow>,
    duplicate_count: usize,
    duplicates: Vec<OrderRow>,
    non_monotonic_count: usize,
    non_monotonic: Vec<OrderRow>,
    non_finite_count: usize,
    channels: Vec<ChannelRow>,
    temperature: Option<TemperatureRange>,
}

/// One gap: where it starts (time and file line of the last sample before it) and how long it is.
#[derive(Debug, Serialize)]
struct GapRow {
    start_line: usize,
    start_s: f64,
    length_s: f64,
}

/// One duplicate or backwards timestamp.
#[derive(Debug, Serialize)]
struct OrderRow {
    line: usize,
    t_s: f64,
    previous_t_s: f64,
}

/// Statistics of one channel, over its finite values.
#[derive(Debug, Serialize)]
struct ChannelRow {
    channel: String,
    unit: &'static str,
    mean: Option<f64>,
    std: Option<f64>,
    non_finite_count: usize,
}

/// Temperature column range, °C.
#[derive(Debug, Serialize)]
struct TemperatureRange {
    min_c: f64,
    max_c: f64,
    mean_c: f64,
}

/// A file's time axis and numeric columns, whatever its format.
pub struct Columns {
    content: &'static str,
    time: Vec<Timestamp>,
    columns: Vec<(String, &'static str, Vec<f64>)>,
    temperature_c: Option<Vec<f64>>,
}

fn imu_columns(series: ImuSeries) -> Columns {
    let kind = series.kind.unwrap_or(SampleKind::Rates);
    let columns = Channel::ALL
        .iter()
        .map(|&c| {
            (
                c.name().to_string(),
                c.si_unit(kind),
                series.channel(c).to_vec(),
            )
        })
        .collect();
    let content = match kind {
        SampleKind::Rates => "imu_rates",
        SampleKind::Increments => "imu_increments",
    };
    Columns {
        content,
        time: series.time,
        columns,
        temperature_c: series.temperature_c,
    }
}

fn column<T>(
    name: &str,
    unit: &'static str,
    rows: &[T],
    value: impl Fn(&T) -> f64,
) -> (String, &'static str, Vec<f64>) {
    (name.to_string(), unit, rows.iter().map(value).collect())
}

fn gnss_columns(fixes: Vec<thermonav::gnss::GnssFix>) -> Columns {
    let mut columns = vec![
        column("lat", "deg", &fixes, |f| f.latitude_rad.to_degrees()),
        column("lon", "deg", &fixes, |f| f.longitude_rad.to_degrees()),
        column("h", "m", &fixes, |f| f.height_m),
    ];
    if fixes.iter().all(|f| f.heading.is_some()) {
        columns.push(column("heading", "deg", &fixes, |f| {
            f.heading.map_or(f64::NAN, |h| h.heading_rad.to_degrees())
        }));
    }
    Columns {
        content: "gnss",
        time: fixes.iter().map(|f| f.time).collect(),
        columns,
        temperature_c: None,
    }
}

fn trajectory_columns(points: Vec<thermonav::trajectory::TrajectoryPoint>) -> Columns {
    let columns = vec![
        column("lat", "deg", &points, |p| p.latitude_rad.to_degrees()),
        column("lon", "deg", &points, |p| p.longitude_rad.to_degrees()),
        column("h", "m", &points, |p| p.height_m),
        column("vn", "m/s", &points, |p| p.velocity_ned_m_s[0]),
        column("ve", "m/s", &points, |p| p.velocity_ned_m_s[1]),
        column("vd", "m/s", &points, |p| p.velocity_ned_m_s[2]),
        column("roll", "deg", &points, |p| p.roll_rad.to_degrees()),
        column("pitch", "deg", &points, |p| p.pitch_rad.to_degrees()),
        column("yaw", "deg", &points, |p| p.yaw_rad.to_degrees()),
    ];
    Columns {
        content: "reference_trajectory",
        time: points.iter().map(|p| p.time).collect(),
        columns,
        temperature_c: None,
    }
}

/// Reads any canonical file leniently, choosing the format by its header.
fn read_columns(path: &Path) -> Result<Columns, Failure> {
    use std::io::{BufRead, Read};
    crate::inputs::readable_twice(path, "inspect")?;
    let mut header = String::new();
    if let Ok(file) = thermonav_io::open_input(path) {
        // A failure here is reported by the reader below, with the file name; the sniff reads
        // at most a line's worth (1 MiB), so an endless input cannot fill memory here.
        let _ = std::io::BufReader::new(file.take(1 << 20)).read_line(&mut header);
    }
    if header.contains("lat_deg") && header.contains("roll_deg") {
        Ok(trajectory_columns(
            read_trajectory_file(path, Strictness::Lenient).data()?,
        ))
    } else if header.contains("lat_deg") {
        Ok(gnss_columns(
            read_gnss_file(path, Strictness::Lenient).data()?,
        ))
    } else {
        Ok(imu_columns(
            read_imu_file(path, Strictness::Lenient).data()?,
        ))
    }
}

/// Runs `inspect`.
pub fn run(args: &InspectArgs) -> Result<(), Failure> {
    let columns = read_columns(&args.file)?;
    let inspection = inspect(&args.file, &columns);
    if args.json {
        print_json(&inspection)
    } else {
        print_text(&inspection);
        Ok(())
    }
}

/// Everything `inspect` reports about a file's columns.
pub fn inspect(file: &Path, data: &Columns) -> Inspection {
    let timing = check_timestamps(&data.time);
    let channels: Vec<ChannelRow> = data
        .columns
        .iter()
        .map(|(name, unit, values)| channel_row(name, unit, values))
        .collect();
    let intervals = timing.intervals;
    Inspection {
        file: file.display().to_string(),
        rows: data.time.len(),
        content: data.content,
        duration_s: timing.duration.map_or(0.0, |d| d.as_seconds()),
        nominal_rate_hz: intervals.map(|s| s.nominal_rate_hz()),
        median_dt_s: intervals.map(|s| s.median.as_seconds()),
        dt_mean_s: intervals.map(|s| s.mean_s),
        dt_std_s: intervals.map(|s| s.std_s),
        dt_min_s: intervals.map(|s| s.min.as_seconds()),
        dt_max_s: intervals.map(|s| s.max.as_seconds()),
        gap_count: timing.gap_count,
        gaps: gap_rows(&timing),
        duplicate_count: timing.duplicate_count,
        duplicates: order_rows(&timing.duplicates),
        non_monotonic_count: timing.reversal_count,
        non_monotonic: order_rows(&timing.reversals),
        non_finite_count: channels.iter().map(|c| c.non_finite_count).sum::<usize>()
            + non_finite_in(data.temperature_c.as_deref().unwrap_or(&[])),
        channels,
        temperature: data.temperature_c.as_deref().and_then(temperature_range),
    }
}

/// File line of a sample index: line 1 is the header.
fn line_of(index: usize) -> usize {
    index + 2
}

/// Seconds since the epoch of the file (the `t_s` column as written).
fn seconds(time: Timestamp) -> f64 {
    time.as_seconds()
}

fn gap_rows(timing: &TimingReport) -> Vec<GapRow> {
    timing
        .gaps
        .iter()
        .map(|g| GapRow {
            start_line: line_of(g.index - 1),
            start_s: seconds(g.start),
            length_s: g.length.as_seconds(),
        })
        .collect()
}

fn order_rows(faults: &[OrderFault]) -> Vec<OrderRow> {
    faults
        .iter()
        .map(|f| OrderRow {
            line: line_of(f.index),
            t_s: seconds(f.time),
            previous_t_s: seconds(f.previous),
        })
        .collect()
}

fn non_finite_in(values: &[f64]) -> usize {
    values.iter().filter(|v| !v.is_finite()).count()
}

fn channel_row(name: &str, unit: &'static str, values: &[f64]) -> ChannelRow {
    let (mean, std) = mean_and_sample_std(values);
    ChannelRow {
        channel: name.to_string(),
        unit,
        mean,
        std,
        non_finite_count: non_finite_in(values),
    }
}

/// Mean and sample standard deviation (1/(n−1), as MATLAB's `std`) of the finite values, by
/// Welford's update; `None` where there are too few finite values.
fn mean_and_sample_std(values: &[f64]) -> (Option<f64>, Option<f64>) {
    let (mut n, mut mean, mut m2) = (0usize, 0.0_f64, 0.0_f64);
    for &v in values.iter().filter(|v| v.is_finite()) {
        n += 1;
        let delta = v - mean;
        mean += delta / n as f64;
        m2 += delta * (v - mean);
    }
    let std = (n > 1).then(|| (m2 / (n - 1) as f64).sqrt());
    ((n > 0).then_some(mean), std)
}

fn temperature_range(values: &[f64]) -> Option<TemperatureRange> {
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let (mean, _) = mean_and_sample_std(&finite);
    Some(TemperatureRange {
        min_c: finite.iter().copied().reduce(f64::min)?,
        max_c: finite.iter().copied().reduce(f64::max)?,
        mean_c: mean?,
    })
}

fn optional(value: Option<f64>, unit: &str, scale: f64) -> String {
    value.map_or_else(|| "n/a".to_string(), |v| format!("{:.6} {unit}", v * scale))
}

/// The text report: the summary rows, then one row per channel.
fn print_text(i: &Inspection) {
    print_rows(&summary_rows(i));
    println!();
    print_channels(&i.channels);
}

/// The rows of the summary: size, timing, faults and temperature.
fn summary_rows(i: &Inspection) -> [(&'static str, String); 13] {
    [
        ("file", i.file.clone()),
        ("rows", i.rows.to_string()),
        ("duration", format!("{:.3} s", i.duration_s)),
        ("nominal rate", optional(i.nominal_rate_hz, "Hz", 1.0)),
        ("median dt", optional(i.median_dt_s, "ms", 1e3)),
        ("dt jitter (std)", optional(i.dt_std_s, "ms", 1e3)),
        ("dt min", optional(i.dt_min_s, "ms", 1e3)),
        ("dt max", optional(i.dt_max_s, "ms", 1e3)),
        (
            "gaps (dt > 1.5 median)",
            format!("{}{}", i.gap_count, first_gap_text(&i.gaps)),
        ),
        ("duplicate timestamps", i.duplicate_count.to_string()),
        (
            "non-monotonic timestamps",
            i.non_monotonic_count.to_string(),
        ),
        ("NaN/inf values", i.non_finite_count.to_string()),
        ("temperature", temperature_text(i.temperature.as_ref())),
    ]
}

/// Where the first gap is and how long it lasts, empty when there is none.
fn first_gap_text(gaps: &[GapRow]) -> String {
    gaps.first()
        .map(|g| {
            format!(
                " (first at t = {:.3} s, line {}, {:.3} ms)",
                g.start_s,
                g.start_line,
                g.length_s * 1e3
            )
        })
        .unwrap_or_default()
}

/// The temperature range and mean, or that the file has no temperature column.
fn temperature_text(t: Option<&TemperatureRange>) -> String {
    t.map_or_else(
        || "no temp_c column".to_string(),
        |t| {
            format!(
                "{:.2} .. {:.2} °C (mean {:.2} °C)",
                t.min_c, t.max_c, t.mean_c
            )
        },
    )
}

/// The channel table: name, unit, mean and standard deviation.
fn print_channels(channels: &[ChannelRow]) {
    println!(
        "{:<8} {:<7} {:>16} {:>16}",
        "channel", "unit", "mean", "std"
    );
    channels.iter().for_each(print_channel_row);
}

/// One channel's row: name, unit, mean and standard deviation.
fn print_channel_row(c: &ChannelRow) {
    println!(
        "{:<8} {:<7} {:>16} {:>16}",
        c.channel,
        c.unit,
        scientific(c.mean),
        scientific(c.std)
    );
}

/// A statistic in scientific notation to nine decimals, or `n/a`.
fn scientific(v: Option<f64>) -> String {
    v.map_or_else(|| "n/a".to_string(), |v| format!("{v:.9e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welford_matches_the_two_pass_formula() {
        // Two-pass by hand: mean 2.5, squared deviations 2.25+0.25+0.25+2.25 = 5, /3.
        let (mean, std) = mean_and_sample_std(&[1.0, 2.0, 3.0, 4.0, f64::NAN]);
        assert_eq!(mean, Some(2.5));
        assert!((std.unwrap() - (5.0_f64 / 3.0).sqrt()).abs() < 1e-15);
        assert_eq!(mean_and_sample_std(&[f64::INFINITY]), (None, None));
    }
}
