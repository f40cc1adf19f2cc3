//! One `integrate` run from its settings: the 21-state GNSS/INS filter on an IMU and a GNSS
//! file with the bank's (or a profile's) noise model at the chosen temperature; writes the
//! solution trajectory, its state and innovation files, and returns the summary. Shared by
//! `integrate` and `demo`; the run itself is the library's [`thermonav::nav::run`].

use crate::failure::{Classify, Failure};
use crate::inputs::load_profile;
use crate::inputs::{read_bank, read_thermal_calibration};
use crate::settings::navigation::{IntegrateSettings, NoiseSource, SolutionFiles};
use anyhow::anyhow;
use serde::Serialize;
use std::path::{Path, PathBuf};
use thermonav::evaluation::experiment::CandidateSource;
use thermonav::imu::{Channel, ImuSeries, SampleKind};
use thermonav::nav::run::{
    NoiseModel, PreparedRun, RunError, RunInput, RunOutcome, RunReport, Start,
    operating_temperature_c, prepare,
};
use thermonav::nav::solution::{Solution, SolutionEpoch};
use thermonav::nav::stream::is_streamable;
use thermonav::nav::time_offset::{TimeOffsetEstimate, estimate_time_offset, shifted};
use thermonav::sensor::SensorProfile;
use thermonav::stoch::bank::ModelBank;
use thermonav::stoch::thermal::ThermalCalibration;
use thermonav::stoch::thermal::join::{ThermalJoinError, check_join};
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::solution::{write_innovations_file, write_solution_states_file};
use thermonav_io::{
    Strictness, read_gnss_file, read_imu_file_with, read_trajectory_file, write_trajectory_file,
};

/// Runs the filter on the files of `settings`, writes the outputs and returns the summary.
pub fn integrate(settings: &IntegrateSettings) -> Result<Summary, Failure> {
    let noise = load_noise(&settings.noise, settings.thermal_from.as_deref())?;
    // The offset search runs the filter many times on the record read once.
    let survey = match settings.in_memory || settings.time_offset_search.is_some() {
        true => None,
        false => Some(crate::integration_stream::survey(settings)?),
    };
    match survey.filter(|s| is_streamable(noise.model(), &settings.run, s)) {
        Some(survey) => crate::integration_stream::integrate(settings, &noise, &survey),
        None => integrate_in_memory(settings, &noise),
    }
}

/// [`integrate`] with the record read whole and the solution kept until it is written.
fn integrate_in_memory(
    settings: &IntegrateSettings,
    noise: &LoadedNoise,
) -> Result<Summary, Failure> {
    let series =
        read_imu_file_with(&settings.imu, Strictness::Strict, &settings.imu_options).data()?;
    let gnss = read_gnss_file(&settings.gnss, Strictness::Strict).data()?;
    let reference = match &settings.initial_from {
        Some(path) => Some(read_trajectory_file(path, Strictness::Strict).data()?),
        None => None,
    };
    let start = reference.as_deref().map_or(Start::Align, Start::Reference);
    let time_offset = match &settings.time_offset_search {
        Some(search) => Some(
            estimate_time_offset(&series, &gnss, noise.model(), start, &settings.run, search)
                .map_err(|e| run_failure(e, settings))?,
        ),
        None => None,
    };
    let series = match &time_offset {
        Some(estimate) => shifted(&series, estimate.time_offset_s),
        None => series,
    };
    let prepared = prepare(series, gnss, noise.model(), start, &settings.run)
        .map_err(|e| run_failure(e, settings))?;
    for note in &prepared.notes {
        eprintln!("note: {} {note}", settings.imu.display());
    }
    let outcome = run_with_progress(prepared).map_err(|e| run_failure(e, settings))?;
    write_outputs(&settings.outputs, &outcome.solution)?;
    let mut summary = summarize(settings, ImuReading::Whole, RunReport::of(&outcome));
    summary.time_offset = time_offset;
    Ok(summary)
}

/// A refused run, naming the file (or the option) it is about.
pub(crate) fn run_failure(error: RunError, s: &IntegrateSettings) -> Failure {
    let named = match error.input() {
        _ if error == RunError::NoTemperature => return no_temperature(&s.imu),
        RunInput::Settings => return Failure::Usage(anyhow!("--outages: {error}")),
        RunInput::Imu => prefix(&s.imu),
        RunInput::Gnss => prefix(&s.gnss),
        RunInput::Noise => prefix(s.noise.path()),
        RunInput::Reference => s.initial_from.as_deref().map(prefix).unwrap_or_default(),
        RunInput::Filter => String::new(),
    };
    Failure::Data(anyhow!("{named}{error}"))
}

/// A record without temp_c and no temperature given: a usage error naming the options.
fn no_temperature(imu: &Path) -> Failure {
    Failure::Usage(anyhow!(
        "{}no temp_c column; give the temperature (--model-temperature-c or --operating-temperature-c)",
        prefix(imu)
    ))
}

fn run_with_progress(prepared: PreparedRun) -> Result<RunOutcome, RunError> {
    let label = format!("integrating ({})", prepared.engine().filter.name());
    let bar = crate::progress::bar(prepared.imu_samples(), &label);
    let outcome = prepared.run(&mut |n| bar.set_position(n as u64))?;
    bar.finish_and_clear();
    Ok(outcome)
}

/// `PATH: `, the start of a message about a file.
fn prefix(path: &Path) -> String {
    format!("{}: ", path.display())
}

/// The noise model's source, read.
pub enum LoadedNoise {
    /// A bank (with the calibration of `--thermal-from`, when given).
    Bank(ModelBank),
    /// A sensor profile.
    Profile(SensorProfile),
    /// A sensor profile with the calibration of `--thermal-from`.
    ProfileWithThermal(SensorProfile, ThermalCalibration),
}

/// Reads the bank or the profile, and joins the thermal calibration of `thermal_from` to it.
pub fn load_noise(
    noise: &NoiseSource,
    thermal_from: Option<&Path>,
) -> Result<LoadedNoise, Failure> {
    let thermal = thermal_from.map(read_thermal_calibration).transpose()?;
    let refused = |e: ThermalJoinError| {
        let (option, path) = match noise {
            NoiseSource::Bank(p) => ("--bank", p),
            NoiseSource::Profile(p) => ("--profile", p),
        };
        let from = thermal_from.map_or_else(String::new, |p| p.display().to_string());
        Failure::Usage(anyhow!(
            "--thermal-from {from} cannot join {option} {}: {e}",
            path.display()
        ))
    };
    match (noise, thermal) {
        (NoiseSource::Bank(path), None) => Ok(LoadedNoise::Bank(read_bank(path)?)),
        (NoiseSource::Bank(path), Some(thermal)) => Ok(LoadedNoise::Bank(
            read_bank(path)?
                .with_thermal_from(thermal)
                .map_err(refused)?,
        )),
        (NoiseSource::Profile(path), None) => Ok(LoadedNoise::Profile(load_profile(Some(path))?)),
        (NoiseSource::Profile(path), Some(thermal)) => {
            let profile = load_profile(Some(path))?;
            let units = Channel::ALL
                .iter()
                .filter(|c| profile.channel(**c).is_some())
                .map(|&c| (c, c.si_unit(SampleKind::Rates).to_string()))
                .collect();
            check_join(&units, &thermal).map_err(refused)?;
            Ok(LoadedNoise::ProfileWithThermal(profile, thermal))
        }
    }
}

impl LoadedNoise {
    /// Where a tournament's candidates come from.
    pub fn source(&self) -> CandidateSource<'_> {
        match self {
            LoadedNoise::Bank(bank) => CandidateSource::Bank(bank),
            LoadedNoise::Profile(profile) | LoadedNoise::ProfileWithThermal(profile, _) => {
                CandidateSource::Profile(profile)
            }
        }
    }

    /// Where a run's noise model comes from.
    pub fn model(&self) -> NoiseModel<'_> {
        match self {
            LoadedNoise::Bank(bank) => NoiseModel::Bank(bank),
            LoadedNoise::Profile(profile) => NoiseModel::Profile(profile),
            LoadedNoise::ProfileWithThermal(profile, thermal) => {
                NoiseModel::ProfileWithThermal(profile, thermal)
            }
        }
    }

    /// The bank's thermal calibration, if any.
    pub fn thermal(&self) -> Option<&ThermalCalibration> {
        self.model().thermal()
    }
}

/// The operating temperature: given, or the mean of the IMU file's temp_c column.
pub fn operating_temperature(
    given: Option<f64>,
    series: &ImuSeries,
    imu: &Path,
) -> Result<f64, Failure> {
    operating_temperature_c(given, series).map_err(|_| no_temperature(imu))
}

fn write_outputs(files: &SolutionFiles, solution: &Solution) -> Result<(), Failure> {
    write_epochs(&files.solution, &files.states, &solution.epochs)?;
    if let Some([trajectory, states]) = &files.smoothed {
        write_epochs(trajectory, states, &solution.smoothed)?;
    }
    write_innovations_file(&files.innovations, &solution.innovations).data()
}

/// A solution's trajectory CSV and its state file.
pub(crate) fn write_epochs(
    trajectory: &Path,
    states: &Path,
    epochs: &[SolutionEpoch],
) -> Result<(), Failure> {
    let points: Vec<TrajectoryPoint> = epochs
        .iter()
        .map(|e| TrajectoryPoint::from_nav_state(&e.estimate.nav))
        .collect();
    write_trajectory_file(trajectory, &points).data()?;
    write_solution_states_file(states, epochs).data()
}

/// What `integrate` reports: the files read, the run's report, the files written.
#[derive(Debug, Serialize)]
pub struct Summary {
    imu: PathBuf,
    /// The `--imu-rotation` the IMU record was turned by, when given.
    #[serde(skip_serializing_if = "Option::is_none")]
    imu_rotation: Option<String>,
    gnss: PathBuf,
    bank: Option<PathBuf>,
    profile: Option<PathBuf>,
    /// `--thermal-from`: the bank whose thermal calibration compensated the record.
    #[serde(skip_serializing_if = "Option::is_none")]
    thermal_from: Option<PathBuf>,
    /// How the IMU record was read: `streamed` (bounded memory, the files written as the
    /// filter went) or `whole` (a bank's thermal compensation, or `--in-memory`).
    pub imu_reading: ImuReading,
    /// With `--estimate-time-offset`: the offset added to the IMU times for the run, its sd
    /// and the search.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time_offset: Option<TimeOffsetEstimate>,
    /// The run's report.
    #[serde(flatten)]
    pub run: RunReport,
    /// The files written.
    pub files: SolutionFiles,
}

/// How `integrate` read the IMU record.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ImuReading {
    /// As a stream, twice, with the outputs written as the filter went.
    Streamed,
    /// Whole, with the solution kept until written.
    Whole,
}

pub(crate) fn summarize(
    settings: &IntegrateSettings,
    imu_reading: ImuReading,
    run: RunReport,
) -> Summary {
    let (bank, profile) = match &settings.noise {
        NoiseSource::Bank(p) => (Some(p.clone()), None),
        NoiseSource::Profile(p) => (None, Some(p.clone())),
    };
    Summary {
        imu: settings.imu.clone(),
        imu_rotation: crate::settings::imu::rotation_text(&settings.imu_options),
        gnss: settings.gnss.clone(),
        bank,
        profile,
        thermal_from: settings.thermal_from.clone(),
        imu_reading,
        time_offset: None,
        run,
        files: settings.outputs.clone(),
    }
}
