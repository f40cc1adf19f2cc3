//! `thermonav convert FILE.csv --to kf-gins`: one of our canonical CSVs written as the KF-GINS
//! text file of the same content (see [`thermonav_io::kf_gins_write`]): an IMU CSV as KF-GINS IMU
//! increments, a GNSS CSV as its 7-column GNSS file, a trajectory CSV as a `.nav` result. Which
//! one is told by the CSV's header. The whole input is read before the output is written
//! atomically.

use crate::args::ConvertArgs;
use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use std::io::BufRead;
use std::path::Path;
use thermonav_io::kf_gins_write::{
    WeekTime, write_kf_gins_gnss_file, write_kf_gins_imu_file, write_kf_gins_nav_file,
};
use thermonav_io::{Strictness, read_gnss_file, read_imu_file, read_trajectory_file};

/// Which canonical CSV the input is.
enum Canonical {
    Imu,
    Gnss,
    Trajectory,
}

/// Converts the canonical CSV `args.input` to KF-GINS; says how many of what it wrote.
pub fn convert(args: &ConvertArgs, strictness: Strictness) -> Result<(usize, String), Failure> {
    let (input, out) = (&args.input, &args.out);
    let (count, what, week) = match canonical_kind(input)? {
        Canonical::Imu => {
            let series = read_imu_file(input, strictness).data()?;
            let week = write_kf_gins_imu_file(out, &series).data()?;
            let rows = imu_rows(&series);
            (rows, "KF-GINS IMU increments", week)
        }
        Canonical::Gnss => {
            let fixes = read_gnss_file(input, strictness).data()?;
            (
                fixes.len(),
                "KF-GINS GNSS fixes",
                write_kf_gins_gnss_file(out, &fixes).data()?,
            )
        }
        Canonical::Trajectory => {
            let points = read_trajectory_file(input, strictness).data()?;
            (
                points.len(),
                "KF-GINS .nav epochs",
                write_kf_gins_nav_file(out, &points).data()?,
            )
        }
    };
    Ok((count, format!("{what} ({})", week_note(week))))
}

/// Rows written for a series: every increment sample, or one fewer than the rate samples.
fn imu_rows(series: &thermonav::imu::ImuSeries) -> usize {
    match series.kind {
        Some(thermonav::imu::SampleKind::Increments) => series.len(),
        _ => series.len().saturating_sub(1),
    }
}

/// How the times were written, and the reader's option that puts them back.
fn week_note(week: WeekTime) -> String {
    match week {
        WeekTime::Week(w) => format!("seconds of GPS week {w}: read back with --gps-week {w}"),
        WeekTime::SecondsOfWeek => "times as seconds of week, as they were".into(),
    }
}

/// The kind of canonical CSV told by the header of `input`.
fn canonical_kind(input: &Path) -> Result<Canonical, Failure> {
    let file = std::fs::File::open(input)
        .map_err(|e| anyhow!("{}: cannot open: {e}", input.display()))
        .data()?;
    let mut header = String::new();
    std::io::BufReader::new(file)
        .read_line(&mut header)
        .map_err(|e| anyhow!("{}: cannot read: {e}", input.display()))
        .data()?;
    let columns: Vec<&str> = header.trim().split(',').map(str::trim).collect();
    let has = |name: &str| columns.contains(&name);
    match (has("yaw_deg"), has("lat_deg"), has("t_s")) {
        (true, _, _) => Ok(Canonical::Trajectory),
        (false, true, _) => Ok(Canonical::Gnss),
        (false, false, true) => Ok(Canonical::Imu),
        _ => Err(anyhow!(
            "{}:1: --to kf-gins takes one of our CSVs: expected a header with t_s (IMU), t_s,lat_deg,... (GNSS) or t_s,...,yaw_deg (trajectory), found \"{}\"",
            input.display(),
            header.trim()
        ))
        .usage(),
    }
}
