//! What an `integrate` run gives back, whether it read the IMU record as a stream
//! ([`crate::navigation::stream`]) or whole ([`crate::navigation::integration`]): the summary it reports, the
//! solution files it writes, and a refused run's failure naming the file or option it is about.

use crate::banks::loaded_noise::RecordNote;
use crate::failure::{Classify, Failure};
use crate::inputs::{no_temperature, prefix};
use crate::settings::navigation::{IntegrateSettings, NoiseSource, SolutionFiles};
use anyhow::anyhow;
use serde::Serialize;
use std::path::{Path, PathBuf};
use thermonav::nav::report::RunReport;
use thermonav::nav::run::{RunError, RunInput};
use thermonav::nav::run_options::RunOptions;
use thermonav::nav::solution::SolutionEpoch;
use thermonav::nav::time_offset::TimeOffsetEstimate;
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::solution::write_solution_states_file;
use thermonav_io::write_trajectory_file;

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
    /// How the bank's records differ from the IMU record (its sample rate beyond the
    /// tolerance): notes, printed as the run starts; empty when nothing differs.
    pub record_notes: Vec<RecordNote>,
    /// How the IMU record was read: `streamed` (bounded memory, the files written as the
    /// filter went) or `whole` (a bank's thermal compensation, or `--in-memory`).
    pub imu_reading: ImuReading,
    /// With `--estimate-time-offset`: the offset added to the IMU times for the run, its sd
    /// and the search.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time_offset: Option<TimeOffsetEstimate>,
    /// How the run went (the options `evaluate` repeats for every candidate's run).
    pub run_options: RunOptions,
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
        record_notes: vec![],
        imu_reading,
        time_offset: None,
        run_options: settings.run.options(),
        run,
        files: settings.outputs.clone(),
    }
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
