//! Simulated campaigns written to files: thermal-chamber records with their truth, and a
//! vessel survey (reference, IMU and GNSS CSVs); shared by `simulate` and `demo`.

use crate::failure::{Classify, Failure};
use crate::inputs::load_profile;
use crate::settings::simulation::{ChamberSettings, VesselSettings};
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use thermonav::evaluation::oracle::{OracleError, TrueChannelModel, TrueModel, TrueModelAt};
use thermonav::imu::Channel;
use thermonav::imu::ImuSeries;
use thermonav::nav::sensor_model::ScaleFactorPrior;
use thermonav::sensor::SensorProfile;
use thermonav::sim::chamber::{
    ChamberRun, ChamberTemperature, RunTruth, calgary, simulate_chamber_run,
};
use thermonav::sim::clock::SampleClock;
use thermonav::sim::rover::rover_loops;
use thermonav::sim::temperature_program::TemperatureProgram;
use thermonav::sim::unit::RepeatableCurve;
use thermonav::sim::vessel::{
    GnssHeading, GnssSettings, ImuOffsets, SURVEY_POWER_ON, SurveyTemperature, VesselError,
    VesselRun, harbour_survey, simulate_vessel_with,
};
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::motion::read_motion;
use thermonav_io::temperature_table::read_temperature_table;
use thermonav_io::{write_gnss_file, write_imu_file, write_json_atomically, write_trajectory_file};

/// `profile` with every channel's thermal lag set to `lag_s` (none: as it is), checked.
pub fn with_thermal_lag(
    mut profile: SensorProfile,
    lag_s: Option<f64>,
) -> Result<SensorProfile, Failure> {
    if let Some(lag_s) = lag_s {
        for channel in profile.channels.values_mut() {
            channel.thermal_lag_s = lag_s;
        }
    }
    profile.validate().usage()?;
    Ok(profile)
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
    /// The unit: its serial and the repeatable bias curve of every channel.
    pub unit: UnitTruth,
    /// One entry per temperature of the first power-on (the bank's records), keys as in the
    /// model bank.
    pub temperatures: Vec<RunTruth>,
    /// The CSV written for each temperature of the first power-on.
    pub files: Vec<PathBuf>,
    /// The records of the further power-ons and of the ramp, each with its file.
    pub further_records: Vec<RecordTruth>,
}

/// The unit of a campaign.
#[derive(Debug, Serialize)]
pub struct UnitTruth {
    /// Serial number.
    pub serial: u64,
    /// b(T) = Σ coefficients\[k\] (T − T_ref)^k per channel, without power-on offsets.
    pub repeatable_bias: BTreeMap<Channel, RepeatableCurve>,
}

/// One record beyond the first power-on's.
#[derive(Debug, Serialize)]
pub struct RecordTruth {
    /// The record's truth.
    pub truth: RunTruth,
    /// Its CSV.
    pub file: PathBuf,
}

/// File name of the record at `temperature_c`.
pub fn chamber_file_name(temperature_c: f64) -> String {
    format!("imu_{temperature_c}C.csv")
}

/// Where a record of `temperature` in `power_on` is written, relative to the campaign folder.
fn record_path(temperature: &ChamberTemperature, power_on: u32) -> PathBuf {
    match temperature {
        ChamberTemperature::SetPoint { temperature_c } if power_on > 1 => {
            Path::new(&format!("power_on_{power_on}")).join(chamber_file_name(*temperature_c))
        }
        ChamberTemperature::SetPoint { temperature_c } => chamber_file_name(*temperature_c).into(),
        ChamberTemperature::Ramp(_) => "imu_ramp.csv".into(),
        ChamberTemperature::Program(_) => "imu_program.csv".into(),
    }
}

/// Every record of a campaign: (chamber temperature, power-on), the first power-on first.
fn campaign_records(settings: &ChamberSettings) -> Vec<(ChamberTemperature, u32)> {
    let c = &settings.campaign;
    let set_point_power_ons = if c.temperatures_c.is_empty() {
        0
    } else {
        c.power_ons.max(1)
    };
    let mut records: Vec<(ChamberTemperature, u32)> = (1..=set_point_power_ons)
        .flat_map(|p| {
            c.temperatures_c
                .iter()
                .map(move |&temperature_c| (ChamberTemperature::SetPoint { temperature_c }, p))
        })
        .collect();
    let mut next_power_on = set_point_power_ons + 1;
    if let Some(ramp) = c.ramp {
        records.push((ChamberTemperature::Ramp(ramp), next_power_on));
        next_power_on += 1;
    }
    if let Some(program) = &c.program {
        records.push((ChamberTemperature::Program(program.clone()), next_power_on));
    }
    records
}

/// Simulates and writes the campaign; returns the truth (also written to truth.json).
pub fn run_chamber(settings: &ChamberSettings) -> Result<ChamberTruth, Failure> {
    use rayon::prelude::*;
    let profile = with_thermal_lag(
        load_profile(settings.profile.as_deref())?,
        settings.thermal_lag_s,
    )?;
    create_folder(&settings.out)?;
    let plan = campaign_records(settings);
    let progress = crate::progress::bar(plan.len(), "simulating chamber records");
    let results: Vec<Result<RecordTruth, Failure>> = plan
        .par_iter()
        .map(|(temperature, power_on)| {
            let record = chamber_record(settings, &profile, temperature.clone(), *power_on);
            progress.inc(1);
            record
        })
        .collect();
    progress.finish_and_clear();
    let mut records = results.into_iter().collect::<Result<Vec<_>, _>>()?;
    let further_records = records.split_off(settings.campaign.temperatures_c.len());
    let (temperatures, files) = records.into_iter().map(|r| (r.truth, r.file)).unzip();
    let c = &settings.campaign;
    let truth = ChamberTruth {
        profile: profile.name.clone(),
        seed: settings.seed,
        rate_hz: c.rate_hz,
        duration_s: c.duration_s,
        jitter_us: c.jitter_s * 1e6,
        drop_probability: c.drop_probability,
        unit: UnitTruth {
            serial: settings.unit.serial,
            repeatable_bias: settings.unit.repeatable_curves(&profile),
        },
        temperatures,
        files,
        further_records,
    };
    write_json_atomically(settings.out.join("truth.json"), &truth).data()?;
    Ok(truth)
}

/// Simulates and writes one record of the campaign.
fn chamber_record(
    settings: &ChamberSettings,
    profile: &SensorProfile,
    temperature: ChamberTemperature,
    power_on: u32,
) -> Result<RecordTruth, Failure> {
    let c = &settings.campaign;
    let path = settings.out.join(record_path(&temperature, power_on));
    let run = ChamberRun {
        temperature,
        duration_s: match power_on {
            1 => c.duration_s,
            _ => c.repeat_duration_s.unwrap_or(c.duration_s),
        },
        unit: settings.unit,
        power_on,
        clock: settings.clock,
        site: calgary(),
        wander: settings.campaign.wander,
        seed: settings.seed,
    };
    let record = simulate_chamber_run(profile, &run).usage()?;
    if let Some(folder) = path.parent() {
        create_folder(folder)?;
    }
    write_imu_file(&path, &record.series).data()?;
    Ok(RecordTruth {
        truth: record.truth,
        file: path,
    })
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
    /// Sensor temperature at the end of the survey, °C.
    pub temperature_c: f64,
    /// Coldest and warmest sensor temperature of the record, °C.
    pub sensor_temperature_range_c: [f64; 2],
    duration_s: f64,
    /// IMU rate, Hz.
    pub imu_rate_hz: f64,
    /// The GNSS receiver.
    pub gnss: GnssSettings,
    /// Heading sd of the dual-antenna fixes, deg; `None` for position-only fixes.
    pub heading_sd_deg: Option<f64>,
    /// The rover's speed, m/s, when the motion is the slow rover.
    pub rover_speed_m_s: Option<f64>,
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
    let profile = with_thermal_lag(
        load_profile(settings.profile.as_deref())?,
        settings.thermal_lag_s,
    )?;
    let survey = &settings.survey;
    let motion = match (&settings.motion, settings.vehicle.rover_speed_m_s) {
        (Some(path), _) => read_motion(path).data()?,
        (None, Some(speed_m_s)) => rover_loops(survey.duration_s, speed_m_s),
        (None, None) => harbour_survey(survey.duration_s),
    };
    let temperature = match &settings.temperature_file {
        Some(path) => {
            let table = read_temperature_table(path).data()?;
            SurveyTemperature::Table(TemperatureProgram {
                t_s: table.t_s,
                temperature_c: table.temperature_c,
            })
        }
        None => settings.temperature.clone(),
    };
    let run = VesselRun {
        motion,
        temperature,
        unit: settings.unit,
        clock: SampleClock::new(survey.imu_rate_hz, survey.imu_jitter_s, 0.0).usage()?,
        gnss: settings.vehicle.gnss,
        seed: settings.seed,
    };
    Ok((profile, run))
}

/// A motion file whose path leaves the navigable latitudes is bad data, named; the rest are
/// bad settings.
fn vessel_failure(error: VesselError, motion: Option<&Path>) -> Failure {
    match (error, motion) {
        (VesselError::Motion(e), Some(path)) => Failure::Data(anyhow!("{}: {e}", path.display())),
        (e, _) => Failure::Usage(e.into()),
    }
}

/// Simulates and writes a vessel survey.
pub fn simulate_vessel_files(settings: &VesselSettings) -> Result<VesselSummary, Failure> {
    let (profile, run) = vessel_run(settings)?;
    let duration_s = run.motion.duration_s();
    let offsets = settings.vehicle.offsets;
    let record = simulate_vessel_with(&profile, &run, &offsets)
        .map_err(|e| vessel_failure(e, settings.motion.as_deref()))?;
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
        profile: profile.name.clone(),
        seed: settings.seed,
        temperature_c: run.temperature.at(duration_s),
        sensor_temperature_range_c: temperature_range_c(&record.imu)
            .unwrap_or([run.temperature.at(0.0); 2]),
        duration_s,
        imu_rate_hz: settings.survey.imu_rate_hz,
        gnss: run.gnss,
        heading_sd_deg: heading_sd_deg(&run.gnss),
        rover_speed_m_s: settings.vehicle.rover_speed_m_s,
        files,
    };
    write_json_atomically(settings.out.join("vessel.json"), &summary).data()?;
    let truth = survey_truth(&profile, &run, &record.imu, offsets);
    write_json_atomically(settings.out.join("truth.json"), &truth).data()?;
    Ok(summary)
}

/// The dual-antenna heading's sd, deg; `None` for position-only fixes.
fn heading_sd_deg(gnss: &GnssSettings) -> Option<f64> {
    (gnss.heading == GnssHeading::DualAntenna).then(|| gnss.heading_sd_rad().to_degrees())
}

/// What `simulate vessel` writes to truth.json: the unit, its survey power-on and the true
/// error model at every temperature the survey's samples visit.
#[derive(Debug, Serialize)]
pub struct SurveyTruth {
    /// The sensor profile's name.
    pub profile: String,
    /// The unit: serial and repeatable bias curves (without the survey's power-on offset).
    pub unit: UnitTruth,
    /// The survey power-on's offset per channel, SI unit of the channel.
    pub power_on_offset: BTreeMap<Channel, f64>,
    /// The sensor's temperature through the survey.
    pub temperature: SurveyTemperature,
    /// The true model on a grid of [`TRUTH_GRID_STEP_C`] over the samples' temperatures.
    pub models: Vec<TrueModelAt>,
    /// Per channel, the time constant by which the structure lags the temperature sensor, s
    /// (0: none); the oracle of `evaluate --truth` reads the repeatable error at the lagged
    /// temperature.
    pub thermal_lag_s: BTreeMap<Channel, f64>,
    /// What `--gyro-bias-deg-h` and `--time-offset-s` added to the IMU record (gyro biases in
    /// rad/s; the offset in s, added to the IMU times to put them on the GNSS scale).
    pub imu_offsets: ImuOffsets,
    /// The same gyro biases, deg/h.
    pub added_gyro_bias_deg_h: [f64; 3],
}

/// Step of the truth's temperature grid, °C (the simulator re-reads Tc and σ every 0.1 °C).
pub const TRUTH_GRID_STEP_C: f64 = thermonav::sim::errors::BIAS_PARAMETER_STEP_C;

fn survey_truth(
    profile: &SensorProfile,
    run: &VesselRun,
    imu: &ImuSeries,
    imu_offsets: ImuOffsets,
) -> SurveyTruth {
    let curves = run.unit.repeatable_curves(profile);
    let power_on_offset = Channel::ALL
        .iter()
        .map(|&c| {
            let offset = run
                .unit
                .power_on_offset(profile, c, run.seed, SURVEY_POWER_ON);
            (c, offset)
        })
        .collect();
    let models = true_table(profile, &curves, imu);
    SurveyTruth {
        thermal_lag_s: thermal_lags(profile),
        profile: profile.name.clone(),
        unit: UnitTruth {
            serial: run.unit.serial,
            repeatable_bias: curves,
        },
        power_on_offset,
        temperature: run.temperature.clone(),
        models,
        added_gyro_bias_deg_h: imu_offsets.gyro_bias_rad_s.map(|b| b.to_degrees() * 3600.0),
        imu_offsets,
    }
}

/// The true model of a simulated survey at every temperature its samples visit: the oracle
/// that `evaluate --truth` reads from truth.json.
///
/// # Errors
/// [`OracleError`] for a record without temperatures.
pub fn true_model(
    profile: &SensorProfile,
    run: &VesselRun,
    imu: &ImuSeries,
) -> Result<TrueModel, OracleError> {
    let curves = run.unit.repeatable_curves(profile);
    TrueModel::new(
        true_table(profile, &curves, imu),
        &ScaleFactorPrior::default(),
    )?
    .with_thermal_lags(thermal_lags(profile))
}

/// Every channel's structure lag of `profile`, s.
fn thermal_lags(profile: &SensorProfile) -> BTreeMap<Channel, f64> {
    (profile.channels.iter())
        .map(|(c, p)| (*c, p.thermal_lag_s))
        .collect()
}

/// The true model on the truth grid of the samples' temperatures.
fn true_table(
    profile: &SensorProfile,
    curves: &BTreeMap<Channel, RepeatableCurve>,
    imu: &ImuSeries,
) -> Vec<TrueModelAt> {
    truth_grid(imu)
        .into_iter()
        .map(|t| model_at(profile, curves, t))
        .collect()
}

/// Coldest and warmest temperature of the samples, °C; `None` without any.
fn temperature_range_c(imu: &ImuSeries) -> Option<[f64; 2]> {
    let temperatures = imu.temperature_c.as_deref().unwrap_or(&[]);
    let (low, high) = temperatures
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &t| {
            (l.min(t), h.max(t))
        });
    (low.is_finite() && high.is_finite()).then_some([low, high])
}

/// Grid temperatures covering the samples' range, °C (at most 10 000 points).
fn truth_grid(imu: &ImuSeries) -> Vec<f64> {
    let Some([low, high]) = temperature_range_c(imu) else {
        return Vec::new();
    };
    let first = (low / TRUTH_GRID_STEP_C).floor() as i64;
    let last = (high / TRUTH_GRID_STEP_C).ceil() as i64;
    (first..=last.min(first + 10_000))
        .map(|k| k as f64 * TRUTH_GRID_STEP_C)
        .collect()
}

fn model_at(
    profile: &SensorProfile,
    curves: &BTreeMap<Channel, RepeatableCurve>,
    temperature_c: f64,
) -> TrueModelAt {
    let channels = Channel::ALL
        .iter()
        .filter_map(|&c| {
            let p = profile.channel(c)?;
            let bias = p.bias_at(temperature_c);
            let scale = p.scale_factor_gauss_markov;
            let truth = TrueChannelModel {
                correlation_time_s: bias.correlation_time_s,
                sigma: bias.sigma,
                white_noise_density: p.white_noise_density,
                repeatable_bias: curves.get(&c).map_or(0.0, |k| k.value_at(temperature_c)),
                thermal_scale_factor_ppm: p.scale_factor_temperature_coefficient_ppm_per_c
                    * (temperature_c - profile.reference_temperature_c),
                scale_factor_correlation_time_s: scale.map(|g| g.correlation_time_s),
                scale_factor_sigma: scale.map(|g| g.sigma_ppm * 1e-6),
            };
            Some((c, truth))
        })
        .collect();
    TrueModelAt {
        temperature_c,
        channels,
    }
}
