//! `thermonav simulate`: chamber records, a vessel survey, or the built-in profile as TOML.

use crate::args::{ChamberArgs, ProfileArgs, SimulateArgs, SimulateWhat, VesselArgs};
use crate::campaign::{
    ChamberTruth, RecordTruth, VesselSummary, run_chamber, simulate_vessel_files,
};
use crate::failure::{Classify, Failure};
use crate::report::{print_json, print_rows};
use crate::settings::simulation::{chamber, vessel};
use anyhow::anyhow;
use std::path::Path;
use thermonav::sensor::adis16364_like;
use thermonav::sim::chamber::{ChamberTemperature, RunTruth};
use thermonav_io::profile::profile_to_toml;
use thermonav_io::write_atomically;

/// Runs `simulate`.
pub fn run(args: &SimulateArgs) -> Result<(), Failure> {
    match &args.what {
        SimulateWhat::Chamber(a) => run_chamber(&chamber(a)?).and_then(|t| report_chamber(a, &t)),
        SimulateWhat::Vessel(a) => run_vessel(a),
        SimulateWhat::Profile(a) => run_profile(a),
    }
}

/// Prints what the chamber campaign wrote and the true models, as JSON with `--json`.
fn report_chamber(args: &ChamberArgs, truth: &ChamberTruth) -> Result<(), Failure> {
    if args.json {
        return print_json(truth);
    }
    if !truth.files.is_empty() {
        println!(
            "{} records of {} s at {} Hz written to {} (profile: {})",
            truth.files.len(),
            args.duration_s,
            args.rate_hz,
            args.out.display(),
            truth.profile
        );
        print_truth_table(truth);
    }
    for record in &truth.further_records {
        print_further_record(record, args.rate_hz);
    }
    Ok(())
}

/// One line on a record beyond the set points: its file, its temperatures and its lag.
fn print_further_record(record: &RecordTruth, rate_hz: f64) {
    let lags: Vec<String> = record
        .truth
        .channels
        .iter()
        .map(|(c, t)| format!("{} {} s", c.name(), t.thermal_lag_s))
        .collect();
    println!(
        "{} ({}, power-on {}, {rate_hz} Hz; thermal lag {})",
        record.file.display(),
        chamber_words(&record.truth.chamber),
        record.truth.power_on,
        lags.join(", ")
    );
}

/// The chamber temperature of a record, in words.
fn chamber_words(chamber: &ChamberTemperature) -> String {
    match chamber {
        ChamberTemperature::SetPoint { temperature_c } => format!("held at {temperature_c} °C"),
        ChamberTemperature::Ramp(r) => format!(
            "ramp {} to {} °C at {} °C/min",
            r.start_c, r.end_c, r.rate_c_per_min
        ),
        ChamberTemperature::Program(p) => {
            format!("program of {} rows over {} s", p.t_s.len(), p.end_s())
        }
    }
}

/// The true correlation time and sigma of every channel at every temperature.
fn print_truth_table(truth: &ChamberTruth) {
    println!(
        "{:>7} {:<4} {:>12} {:>14}",
        "temp_C", "ch", "true Tc s", "true sigma"
    );
    truth.temperatures.iter().for_each(print_truth_rows);
}

/// The rows of one temperature: one per channel.
fn print_truth_rows(run: &RunTruth) {
    for (c, t) in &run.channels {
        println!(
            "{:>7.1} {:<4} {:>12.1} {:>14.4e}",
            run.temperature_c,
            c.name(),
            t.gauss_markov.correlation_time_s,
            t.gauss_markov.sigma
        );
    }
}

/// Simulates the vessel survey and says what it wrote, as JSON with `--json`.
fn run_vessel(args: &VesselArgs) -> Result<(), Failure> {
    let summary = simulate_vessel_files(&vessel(args)?)?;
    if args.json {
        return print_json(&summary);
    }
    print_rows(&vessel_rows(&summary));
    Ok(())
}

/// The survey's files, sensor temperature and heading accuracy.
fn vessel_rows(summary: &VesselSummary) -> [(&'static str, String); 6] {
    [
        (
            "reference trajectory",
            summary.files.reference.display().to_string(),
        ),
        (
            "IMU",
            format!(
                "{} ({} Hz)",
                summary.files.imu.display(),
                summary.imu_rate_hz
            ),
        ),
        ("GNSS", gnss_text(summary)),
        ("motion", motion_text(summary)),
        ("sensor temperature", sensor_temperature(summary)),
        ("GNSS heading", heading_text(summary)),
    ]
}

/// The GNSS file, rate and position sds.
fn gnss_text(summary: &VesselSummary) -> String {
    let [n, e, d] = summary.gnss.position_sd_ned_m;
    format!(
        "{} ({} Hz, position sd {n}, {e}, {d} m north, east, down)",
        summary.files.gnss.display(),
        summary.gnss.rate_hz
    )
}

/// The built-in motion used.
fn motion_text(summary: &VesselSummary) -> String {
    match summary.rover_speed_m_s {
        Some(v) => format!("slow rover at {v} m/s (still start, 30 s legs, 90 deg turns)"),
        None => "harbour survey or --motion file".to_string(),
    }
}

/// The dual-antenna heading's sd, or that the fixes carry none.
fn heading_text(summary: &VesselSummary) -> String {
    match summary.heading_sd_deg {
        Some(sd) => format!("dual antenna, sd {sd:.3} deg (2.37 m baseline)"),
        None => "none (position-only fixes)".to_string(),
    }
}

/// The survey's temperature, or its range when it changes.
fn sensor_temperature(summary: &VesselSummary) -> String {
    match summary.sensor_temperature_range_c {
        [low, high] if low == high => format!("{low} °C"),
        [low, high] => format!(
            "{low:.1} to {high:.1} °C (settling at {} °C)",
            summary.temperature_c
        ),
    }
}

/// Writes the built-in sensor profile as TOML.
fn run_profile(args: &ProfileArgs) -> Result<(), Failure> {
    crate::settings::paths::Io::new()
        .output("profile", &args.out)
        .check()?;
    let text = profile_to_toml(&adis16364_like())
        .map_err(|e| anyhow!("cannot write the profile: {e}"))
        .data()?;
    write_profile(&args.out, &text)?;
    println!("profile written to {}", args.out.display());
    Ok(())
}

/// Writes the profile's TOML under a comment line saying what it is.
fn write_profile(out: &Path, text: &str) -> Result<(), Failure> {
    let header = "# thermonav sensor profile: the built-in ADIS16364-like default. Units are in the key names.\n";
    write_atomically(out, |f| {
        use std::io::Write;
        f.write_all(header.as_bytes())?;
        f.write_all(text.as_bytes())?;
        Ok(())
    })
    .data()
}
