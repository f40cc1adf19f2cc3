//! Simulated campaigns written to files: thermal-chamber records with their truth, and a
//! vessel survey (reference, IMU and GNSS CSVs); shared by `simulate` and `demo`.

use crate::failure::{Classify, Failure};
use crate::settings::simulation::{ChamberSettings, VesselSettings};
use anyhow::anyhow;
use serde::Serialize;
use std::path::{Path, PathBuf};
use thermonav::sensor::{SensorProfile, adis16364_like};
use thermonav::sim::chamber::{ChamberRun, RunTruth, calgary, simulate_chamber_run};
use thermonav::sim::clock::SampleClock;
use thermonav::sim::vessel::{GnssSettings, VesselRun, harbour_survey, simulate_vessel};
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::motion::read_motion;
use thermonav_io::profile::read_profile;
use thermonav_io::{write_gnss_file, write_imu_file, write_json_atomically, write_trajectory_file};

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
    /// The sensor profile's name.
    pub profile: String,
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
pub fn run_chamber(settings: &ChamberSettings) -> Result<ChamberTruth, Failure> {
    use rayon::prelude::*;
    let profile = load_profile(settings.profile.as_deref())?;
    create_folder(&settings.out)?;
    let set_points = &settings.campaign.temperatures_c;
    let progress = crate::progress::bar(set_points.len(), "simulating chamber records");
    let results: Vec<Result<(RunTruth, PathBuf), Failure>> = set_points
        .par_iter()
        .map(|&t| {
            let record = chamber_record(settings, &profile, t);
            progress.inc(1);
            record
        })
        .collect();
    progress.finish_and_clear();
    let (temperatures, files) = results
        .into_iter()
        .collect::<Result<Vec<_>, _>>()?
        .into_iter()
        .unzip();
    let c = &settings.campaign;
    let truth = ChamberTruth {
        profile: profile.name.clone(),
        seed: settings.seed,
        rate_hz: c.rate_hz,
        duration_s: c.duration_s,
        jitter_us: c.jitter_s * 1e6,
        drop_probability: c.drop_probability,
        temperatures,
        files,
    };
    write_json_atomically(settings.out.join("truth.json"), &truth).data()?;
    Ok(truth)
}

/// Simulates and writes the record at one set point.
fn chamber_record(
    settings: &ChamberSettings,
    profile: &SensorProfile,
    set_point_c: f64,
) -> Result<(RunTruth, PathBuf), Failure> {
    let run = ChamberRun {
        set_point_c,
        duration_s: settings.campaign.duration_s,
        clock: settings.clock,
        site: calgary(),
        wander: settings.campaign.wander,
        seed: settings.seed,
    };
    let record = simulate_chamber_run(profile, &run).usage()?;
    let path = settings.out.join(chamber_file_name(set_point_c));
    write_imu_file(&path, &record.series).data()?;
    Ok((record.truth, path))
}

/// Creates `dir` and its parents.
pub fn create_folder(dir: &Path) -> Result<(), Failure> {
    std::fs::create_dir_all(dir)
        .map_err(|e| anyhow!("{}: cannot create: {e}", dir.display()))
        .data()
}

/// What `simulate vessel` writes to vessel.json.
#[derive(Debug, Serialize)]
pub struct VesselSummary {
    profile: String,
    seed: u64,
    /// Sensor temperature, °C.
    pub temperature_c: f64,
    duration_s: f64,
    imu_rate_hz: f64,
    gnss: GnssSettings,
    /// Heading sd of the dual-antenna fixes, deg.
    pub heading_sd_deg: f64,
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

/// The sensor profile and the vessel run that `settings` describe.
pub fn vessel_run(settings: &VesselSettings) -> Result<(SensorProfile, VesselRun), Failure> {
    let profile = load_profile(settings.profile.as_deref())?;
    let survey = &settings.survey;
    let motion = match &settings.motion {
        Some(path) => read_motion(path).data()?,
        None => harbour_survey(survey.duration_s),
    };
    let run = VesselRun {
        motion,
        temperature_c: survey.temperature_c,
        clock: SampleClock::new(survey.imu_rate_hz, survey.imu_jitter_s, 0.0).usage()?,
        gnss: GnssSettings::default(),
        seed: settings.seed,
    };
    Ok((profile, run))
}

/// Simulates and writes a vessel survey.
pub fn simulate_vessel_files(settings: &VesselSettings) -> Result<VesselSummary, Failure> {
    let (profile, run) = vessel_run(settings)?;
    let duration_s = run.motion.duration_s();
    let record = simulate_vessel(&profile, &run).usage()?;
    create_folder(&settings.out)?;
    let files = VesselFiles {
        reference: settings.out.join("reference.csv"),
        imu: settings.out.join("imu.csv"),
        gnss: settings.out.join("gnss.csv"),
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
        seed: settings.seed,
        temperature_c: settings.survey.temperature_c,
        duration_s,
        imu_rate_hz: settings.survey.imu_rate_hz,
        gnss: run.gnss,
        heading_sd_deg: run.gnss.heading_sd_rad().to_degrees(),
        files,
    };
    write_json_atomically(settings.out.join("vessel.json"), &summary).data()?;
    Ok(summary)
}
