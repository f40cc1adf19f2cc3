//! `thermonav simulate`: chamber records, a vessel survey, or the built-in profile as TOML.

use crate::args::{ChamberArgs, ProfileArgs, SimulateArgs, SimulateWhat, VesselArgs};
use crate::failure::{Classify, Failure};
use crate::report::{print_json, print_rows};
use anyhow::anyhow;
use serde::Serialize;
use std::path::{Path, PathBuf};
use thermonav::sensor::{SensorProfile, adis16364_like};
use thermonav::sim::chamber::{ChamberRun, ChamberWander, RunTruth, calgary, simulate_chamber_run};
use thermonav::sim::clock::SampleClock;
use thermonav::sim::vessel::{GnssSettings, VesselRun, harbour_survey, simulate_vessel};
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::motion::read_motion;
use thermonav_io::profile::{profile_to_toml, read_profile};
use thermonav_io::{
    write_atomically, write_gnss_file, write_imu_file, write_json_atomically, write_trajectory_file,
};

/// Runs `simulate`.
pub fn run(args: &SimulateArgs) -> Result<(), Failure> {
    match &args.what {
        SimulateWhat::Chamber(a) => run_chamber(a).and_then(|truth| report_chamber(a, &truth)),
        SimulateWhat::Vessel(a) => run_vessel(a),
        SimulateWhat::Profile(a) => run_profile(a),
    }
}

/// The profile of `--profile`, or the built-in one.
pub fn load_profile(path: Option<&Path>) -> Result<SensorProfile, Failure> {
    match path {
        Some(p) => read_profile(p).data(),
        None => Ok(adis16364_like()),
    }
}

/// What `simulate chamber` writes to truth.json.
#[derive(Debug, Serialize)]
pub struct ChamberTruth {
    profile: String,
    seed: u64,
    rate_hz: f64,
    duration_s: f64,
    jitter_us: f64,
    drop_probability: f64,
    /// One entry per temperature, keys as in the model bank.
    pub temperatures: Vec<RunTruth>,
    /// The CSV written for each temperature.
    pub files: Vec<PathBuf>,
}

/// File name of the record at `temperature_c`.
pub fn chamber_file_name(temperature_c: f64) -> String {
    format!("imu_{temperature_c}C.csv")
}

/// Simulates and writes the campaign; returns the truth (also written to truth.json).
pub fn run_chamber(args: &ChamberArgs) -> Result<ChamberTruth, Failure> {
    use rayon::prelude::*;
    let profile = load_profile(args.profile.as_deref())?;
    let clock =
        SampleClock::new(args.rate_hz, args.jitter_us * 1e-6, args.drop_probability).usage()?;
    if args.temperatures_c.is_empty() || args.temperatures_c.iter().any(|t| !t.is_finite()) {
        return Err(Failure::Usage(anyhow!(
            "--temperatures-c needs finite temperatures"
        )));
    }
    std::fs::create_dir_all(&args.out)
        .map_err(|e| anyhow!("{}: cannot create: {e}", args.out.display()))
        .data()?;
    let wander = ChamberWander {
        sigma_c: 0.05,
        correlation_time_s: 600.0,
    };
    let progress = crate::progress::bar(args.temperatures_c.len(), "simulating chamber records");
    let results: Vec<Result<(RunTruth, PathBuf), Failure>> = args
        .temperatures_c
        .par_iter()
        .map(|&t| {
            let run = ChamberRun {
                set_point_c: t,
                duration_s: args.duration_s,
                clock,
                site: calgary(),
                wander,
                seed: args.seed,
            };
            let record = simulate_chamber_run(&profile, &run).usage()?;
            let path = args.out.join(chamber_file_name(t));
            write_imu_file(&path, &record.series).data()?;
            progress.inc(1);
            Ok((record.truth, path))
        })
        .collect();
    progress.finish_and_clear();
    let (temperatures, files) = results
        .into_iter()
        .collect::<Result<Vec<_>, _>>()?
        .into_iter()
        .unzip();
    let truth = ChamberTruth {
        profile: profile.name.clone(),
        seed: args.seed,
        rate_hz: args.rate_hz,
        duration_s: args.duration_s,
        jitter_us: args.jitter_us,
        drop_probability: args.drop_probability,
        temperatures,
        files,
    };
    write_json_atomically(args.out.join("truth.json"), &truth).data()?;
    Ok(truth)
}

fn report_chamber(args: &ChamberArgs, truth: &ChamberTruth) -> Result<(), Failure> {
    if args.json {
        return print_json(truth);
    }
    println!(
        "{} records of {} s at {} Hz written to {} (profile: {})",
        truth.files.len(),
        args.duration_s,
        args.rate_hz,
        args.out.display(),
        truth.profile
    );
    println!(
        "{:>7} {:<4} {:>12} {:>14}",
        "temp_C", "ch", "true Tc s", "true sigma"
    );
    for run in &truth.temperatures {
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
    Ok(())
}

/// What `simulate vessel` writes to vessel.json.
#[derive(Debug, Serialize)]
pub struct VesselSummary {
    profile: String,
    seed: u64,
    temperature_c: f64,
    duration_s: f64,
    imu_rate_hz: f64,
    gnss: GnssSettings,
    heading_sd_deg: f64,
    /// Files written.
    pub files: VesselFiles,
}

/// Paths of the vessel outputs.
#[derive(Debug, Serialize)]
pub struct VesselFiles {
    /// Reference trajectory CSV.
    pub reference: PathBuf,
    /// IMU CSV.
    pub imu: PathBuf,
    /// GNSS CSV.
    pub gnss: PathBuf,
}

/// The sensor profile and the vessel run that `args` describe.
pub fn vessel_run(args: &VesselArgs) -> Result<(SensorProfile, VesselRun), Failure> {
    let profile = load_profile(args.profile.as_deref())?;
    let motion = match &args.motion {
        Some(path) => read_motion(path).data()?,
        None if args.duration_s.is_finite() && args.duration_s >= 60.0 => {
            harbour_survey(args.duration_s)
        }
        None => {
            return Err(Failure::Usage(anyhow!(
                "--duration-s {} must be at least 60 s",
                args.duration_s
            )));
        }
    };
    let run = VesselRun {
        motion,
        temperature_c: args.temperature_c,
        clock: SampleClock::new(200.0, 50e-6, 0.0).usage()?,
        gnss: GnssSettings::default(),
        seed: args.seed,
    };
    Ok((profile, run))
}

/// Simulates and writes a vessel survey.
pub fn simulate_vessel_files(args: &VesselArgs) -> Result<VesselSummary, Failure> {
    let (profile, run) = vessel_run(args)?;
    let duration_s = run.motion.duration_s();
    let record = simulate_vessel(&profile, &run).usage()?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| anyhow!("{}: cannot create: {e}", args.out.display()))
        .data()?;
    let files = VesselFiles {
        reference: args.out.join("reference.csv"),
        imu: args.out.join("imu.csv"),
        gnss: args.out.join("gnss.csv"),
    };
    let points: Vec<TrajectoryPoint> = record
        .reference
        .states
        .iter()
        .map(TrajectoryPoint::from_nav_state)
        .collect();
    write_trajectory_file(&files.reference, &points).data()?;
    write_imu_file(&files.imu, &record.imu).data()?;
    write_gnss_file(&files.gnss, &record.gnss).data()?;
    let summary = VesselSummary {
        profile: profile.name,
        seed: args.seed,
        temperature_c: args.temperature_c,
        duration_s,
        imu_rate_hz: 200.0,
        gnss: run.gnss,
        heading_sd_deg: run.gnss.heading_sd_rad().to_degrees(),
        files,
    };
    write_json_atomically(args.out.join("vessel.json"), &summary).data()?;
    Ok(summary)
}

fn run_vessel(args: &VesselArgs) -> Result<(), Failure> {
    let summary = simulate_vessel_files(args)?;
    if args.json {
        return print_json(&summary);
    }
    print_rows(&[
        (
            "reference trajectory",
            summary.files.reference.display().to_string(),
        ),
        ("IMU (200 Hz)", summary.files.imu.display().to_string()),
        ("GNSS (1 Hz)", summary.files.gnss.display().to_string()),
        (
            "sensor temperature",
            format!("{} °C", summary.temperature_c),
        ),
        (
            "heading sd (2.37 m baseline)",
            format!("{:.3} deg", summary.heading_sd_deg),
        ),
    ]);
    Ok(())
}

fn run_profile(args: &ProfileArgs) -> Result<(), Failure> {
    let text = profile_to_toml(&adis16364_like())
        .map_err(|e| anyhow!("cannot write the profile: {e}"))
        .data()?;
    let header = "# thermonav sensor profile: the built-in ADIS16364-like default. Units are in the key names.\n";
    write_atomically(&args.out, |f| {
        use std::io::Write;
        f.write_all(header.as_bytes())?;
        f.write_all(text.as_bytes())?;
        Ok(())
    })
    .data()?;
    println!("profile written to {}", args.out.display());
    Ok(())
}
