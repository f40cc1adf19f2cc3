//! One navigation run on records already read: the noise model chosen from a bank or a
//! profile at a temperature (or scheduled by the IMU's temp_c), the record thermally
//! compensated, the outages laid over the data, the start aligned from GNSS (or taken from a
//! reference trajectory), and the filter run. What `thermonav integrate` and the Python
//! package's `integrate` both do between reading their inputs and writing their outputs.
//!
//! ```no_run
//! # use thermonav::nav::run::*;
//! # use thermonav::nav::report::RunReport;
//! # fn demo(series: thermonav::imu::ImuSeries, gnss: Vec<thermonav::gnss::GnssFix>,
//! #         bank: &thermonav::stoch::bank::ModelBank) -> Result<(), RunError> {
//! let settings = RunSettings::default();
//! let prepared = prepare(series, gnss, NoiseModel::Bank(bank), Start::Align, &settings)?;
//! let outcome = prepared.run(&mut |_| {})?;
//! let report = RunReport::of(&outcome);
//! # Ok(()) }
//! ```

use super::alignment::{
    AlignmentError, CourseBaseline, HeadingSource, InitialBiasSource, InitialUncertainty,
    align_from_gnss, bias_sd_in_quadrature, uncorrected,
};
use super::engine::{EngineSettings, NavError, increments_from_series};
use super::error_state::Estimate;
use super::measurement::AntennaGeometry;
use super::navigate::run_scheduled;
use super::outage::{OutageError, OutageSpec};
use super::run_options::{DEFAULT_PROCESS_NOISE_SCALE, RunOptions};
use super::schedule::{
    Compensation, CompensationOutcome, ModelGrid, ModelSchedule, ScheduleError, ScheduleSummary,
    Scheduling, TemperatureTrack, compensate_record,
};
use super::sensor_model::{BankChoice, ImuStochasticModel, ScaleFactorPrior, SensorModelError};
use super::solution::Solution;
use super::static_alignment::{
    StaticAlignment, StillDecision, StillStart, attitude_at, still_start_decided,
};
use crate::frames::{Body, Vector};
use crate::gnss::GnssFix;
use crate::imu::{Channel, ImuSeries};
use crate::ins::state::{Increment, NavState};
use crate::sensor::SensorProfile;
use crate::setting::{SettingError, finite};
use crate::stoch::bank::{GaussMarkovSource, ModelBank, Selection};
use crate::stoch::thermal::ThermalCalibration;
use crate::time::Timestamp;
use crate::trajectory::TrajectoryPoint;
use serde::Serialize;
use std::time::Instant;

/// Which temperature's model the filter uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ModelTemperature {
    /// The model of this temperature, °C (the nearest bank entry: the paper's "model of T").
    Fixed(f64),
    /// The model for the sensor's operating temperature, °C (given, or the mean of the IMU
    /// record's temp_c), selected by the rule.
    Operating {
        /// Given by the caller.
        given_c: Option<f64>,
        /// Nearest entry or interpolation.
        selection: Selection,
    },
}

impl Default for ModelTemperature {
    /// The operating temperature from the record, nearest entry.
    fn default() -> Self {
        Self::Operating {
            given_c: None,
            selection: Selection::default(),
        }
    }
}

impl ModelTemperature {
    /// The model temperature of a run's options (the same for `integrate`, `evaluate` and the
    /// Python package): the model of `model_temperature_c` (the nearest entry), or the model
    /// for the operating temperature (`operating_temperature_c`, or the record's mean temp_c)
    /// selected by `selection`.
    ///
    /// # Errors
    /// A temperature that is not finite, or both given.
    pub fn of(
        model_temperature_c: Option<f64>,
        operating_temperature_c: Option<f64>,
        selection: Selection,
    ) -> Result<Self, SettingError> {
        match (model_temperature_c, operating_temperature_c) {
            (Some(t), Some(_)) => Err(SettingError {
                name: "model_temperature_c",
                value: t.to_string(),
                expected: "give it or the operating temperature, not both".into(),
            }),
            (Some(t), None) => Ok(Self::Fixed(finite("model_temperature_c", t)?)),
            (None, given) => Ok(Self::Operating {
                given_c: (given.map(|t| finite("operating_temperature_c", t))).transpose()?,
                selection,
            }),
        }
    }

    /// The temperature given, °C: the fixed model's, or the operating temperature when
    /// given (`None`: the record's mean temp_c stands in).
    pub fn given_c(&self) -> Option<f64> {
        match self {
            ModelTemperature::Fixed(t) => Some(*t),
            ModelTemperature::Operating { given_c, .. } => *given_c,
        }
    }

    /// The bank selection rule (nearest for a fixed model).
    pub fn selection(&self) -> Selection {
        match self {
            ModelTemperature::Fixed(_) => Selection::Nearest,
            ModelTemperature::Operating { selection, .. } => *selection,
        }
    }

    /// Scheduling as `requested` while the temperature follows the record; fixed when a
    /// temperature names one model.
    pub fn scheduling(&self, requested: Scheduling) -> Scheduling {
        match self {
            ModelTemperature::Operating { given_c: None, .. } => requested,
            _ => Scheduling::Fixed,
        }
    }
}

/// Where the noise model comes from.
#[derive(Debug, Clone, Copy)]
pub enum NoiseModel<'a> {
    /// A bank from `characterize`.
    Bank(&'a ModelBank),
    /// A sensor profile.
    Profile(&'a SensorProfile),
    /// A sensor profile's noise with a bank's thermal calibration (`--thermal-from`; checked
    /// to cover the profile's channels with [`crate::stoch::thermal::join::check_join`]).
    ProfileWithThermal(&'a SensorProfile, &'a ThermalCalibration),
}

impl<'a> NoiseModel<'a> {
    /// The thermal calibration, if any.
    pub fn thermal(self) -> Option<&'a ThermalCalibration> {
        match self {
            NoiseModel::Bank(bank) => bank.thermal.as_ref(),
            NoiseModel::Profile(_) => None,
            NoiseModel::ProfileWithThermal(_, thermal) => Some(thermal),
        }
    }
}

/// Everything a run is told besides its data (defaults: the CLI's).
#[derive(Debug, Clone)]
pub struct RunSettings {
    /// Which temperature's model (the fixed model, and the reported one when scheduled).
    pub temperature: ModelTemperature,
    /// Whether the model follows the IMU's temp_c.
    pub scheduling: Scheduling,
    /// Whether the bank's bias(T) is subtracted from the samples.
    pub compensation: Compensation,
    /// Gauss-Markov family of a bank.
    pub gauss_markov: GaussMarkovSource,
    /// The filter's settings (the outages are laid over the data by [`prepare`]).
    pub engine: EngineSettings,
    /// The outages as given.
    pub outages: OutageSpec,
    /// Multiplier of the white-noise densities.
    pub process_noise_scale: f64,
}

impl Default for RunSettings {
    fn default() -> Self {
        Self {
            temperature: ModelTemperature::default(),
            scheduling: Scheduling::default(),
            compensation: Compensation::default(),
            gauss_markov: GaussMarkovSource::default(),
            engine: EngineSettings::default(),
            outages: OutageSpec::None,
            process_noise_scale: DEFAULT_PROCESS_NOISE_SCALE,
        }
    }
}

impl RunSettings {
    /// The settings of a run with `options` and the model of `temperature`: scheduled by the
    /// record's temperature as `scheduling` asks while the temperature follows the record
    /// ([`ModelTemperature::scheduling`]), compensated as `compensation` says, the filter's
    /// settings `base`'s (its kind, output rate, smoothing) with the options', and `outages`.
    /// What `integrate` runs, and what `evaluate` estimates the time offset with.
    pub fn of_options(
        options: &RunOptions,
        temperature: ModelTemperature,
        (scheduling, compensation): (Scheduling, Compensation),
        base: EngineSettings,
        outages: OutageSpec,
    ) -> Self {
        Self {
            temperature,
            scheduling: temperature.scheduling(scheduling),
            compensation,
            gauss_markov: options.gauss_markov,
            engine: options.engine(base),
            outages,
            process_noise_scale: options.process_noise_scale,
        }
    }

    /// The options that decide how the filter runs (see [`RunOptions`]).
    pub fn options(&self) -> RunOptions {
        RunOptions::of_engine(&self.engine, self.gauss_markov, self.process_noise_scale)
    }
}

/// How the run starts.
#[derive(Debug, Clone, Copy)]
pub enum Start<'a> {
    /// Aligned from GNSS (dual-antenna heading, or course over ground).
    Align,
    /// From the reference point at (or last before) the first fix, or its first point.
    Reference(&'a [TrajectoryPoint]),
}

/// Where the initial state came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum InitialSource {
    /// The reference trajectory.
    Reference,
    /// Alignment with a dual-antenna heading.
    DualAntennaHeading,
    /// Alignment with the course over ground.
    CourseOverGround,
}

/// Which input a [`RunError`] is about, for the caller to name its file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunInput {
    /// The IMU record.
    Imu,
    /// The GNSS fixes.
    Gnss,
    /// The bank or the profile.
    Noise,
    /// The reference trajectory of [`Start::Reference`].
    Reference,
    /// The settings (the outages).
    Settings,
    /// None in particular (the filter itself).
    Filter,
}

/// Why a run cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RunError {
    /// The noise model cannot be built.
    #[error(transparent)]
    NoiseModel(SensorModelError),
    /// The models over the record's temperature range cannot be built.
    #[error(transparent)]
    ModelGrid(ScheduleError),
    /// The record's temperature track is unusable.
    #[error(transparent)]
    TemperatureTrack(ScheduleError),
    /// No operating temperature given and none in the record.
    #[error("{}", RunError::no_temperature(str::to_string))]
    NoTemperature,
    /// Fewer than two IMU samples.
    #[error("at least two IMU samples are needed")]
    TooShort,
    /// The outages do not fit the data.
    #[error(transparent)]
    Outages(OutageError),
    /// The GNSS fixes give no alignment.
    #[error(transparent)]
    Alignment(AlignmentError),
    /// The reference trajectory is empty.
    #[error("no trajectory point")]
    NoReferencePoint,
    /// The filter refused the data or diverged.
    #[error(transparent)]
    Nav(NavError),
}

/// The settings that give a run its temperature when its record has none (°C), named as
/// Python's keywords.
pub const TEMPERATURE_SETTINGS: [&str; 2] = ["model_temperature_c", "operating_temperature_c"];

impl RunError {
    /// What [`RunError::NoTemperature`] says, with [`TEMPERATURE_SETTINGS`] spelt by `spell`
    /// (the identity for Python's keywords, [`crate::setting::flag`] for the CLI's options).
    pub fn no_temperature(spell: impl Fn(&str) -> String) -> String {
        let [model, operating] = TEMPERATURE_SETTINGS.map(spell);
        format!("no temp_c column; give the temperature ({model} or {operating})")
    }

    /// The input the error is about.
    pub fn input(&self) -> RunInput {
        match self {
            RunError::NoiseModel(_) | RunError::ModelGrid(_) => RunInput::Noise,
            RunError::TemperatureTrack(_) | RunError::NoTemperature | RunError::TooShort => {
                RunInput::Imu
            }
            RunError::Outages(_) => RunInput::Settings,
            RunError::Alignment(_) => RunInput::Gnss,
            RunError::NoReferencePoint => RunInput::Reference,
            RunError::Nav(NavError::ImuGap { .. }) => RunInput::Imu,
            RunError::Nav(NavError::PolarFix { .. }) => RunInput::Gnss,
            RunError::Nav(_) => RunInput::Filter,
        }
    }
}

/// The models of a run: the fixed one (reported; used unless scheduled) and, when
/// scheduled, the temperature track with the models by temperature.
#[derive(Debug, Clone)]
pub struct RunModels {
    /// The fixed model (white noise scaled).
    pub model: ImuStochasticModel,
    /// Its temperature, rule and family.
    pub choice: BankChoice,
    /// The track and the models by temperature, when scheduled.
    pub scheduled: Option<(TemperatureTrack, ModelGrid)>,
}

impl RunModels {
    /// The models of `settings` from `noise` for `series`.
    ///
    /// # Errors
    /// [`RunError::NoiseModel`], [`RunError::NoTemperature`], [`RunError::TemperatureTrack`],
    /// [`RunError::ModelGrid`].
    pub fn of(
        settings: &RunSettings,
        noise: NoiseModel,
        series: &ImuSeries,
    ) -> Result<Self, RunError> {
        let track = || TemperatureTrack::of_series(series);
        Self::of_record(settings, noise, series.mean_temperature_c(), track)
    }

    /// [`RunModels::of`] from what they need of the record: the mean of its temp_c column
    /// and its temperature track (asked for only when the run is scheduled).
    pub(super) fn of_record(
        settings: &RunSettings,
        noise: NoiseModel,
        mean_temperature_c: Option<f64>,
        track: impl FnOnce() -> Result<Option<TemperatureTrack>, ScheduleError>,
    ) -> Result<Self, RunError> {
        let (model, choice) = fixed_model(settings, noise, mean_temperature_c)?;
        let mut model = model.map_err(RunError::NoiseModel)?;
        model.scale_white_noise(settings.process_noise_scale);
        let scheduled = match schedule_track(settings, track)? {
            Some(track) => Some(scheduled_models(settings, noise, track)?),
            None => None,
        };
        Ok(Self {
            model,
            choice,
            scheduled,
        })
    }

    /// The schedule the filter runs with.
    pub fn schedule(&self) -> ModelSchedule<'_> {
        match &self.scheduled {
            Some((track, grid)) => ModelSchedule::ByTemperature { track, grid },
            None => ModelSchedule::Fixed(&self.model),
        }
    }

    /// What the schedule was, for a report.
    pub fn summary(&self) -> ScheduleSummary {
        match &self.scheduled {
            Some((track, grid)) => ScheduleSummary::scheduled(track, grid),
            None => ScheduleSummary::Fixed {
                temperature_c: self.choice.temperature_c,
            },
        }
    }
}

/// The IMU's temperature track when the run is scheduled and the record has temp_c.
fn schedule_track(
    settings: &RunSettings,
    track: impl FnOnce() -> Result<Option<TemperatureTrack>, ScheduleError>,
) -> Result<Option<TemperatureTrack>, RunError> {
    if settings.scheduling == Scheduling::Fixed {
        return Ok(None);
    }
    track().map_err(RunError::TemperatureTrack)
}

/// The track with the models by temperature over its range (white noise scaled).
fn scheduled_models(
    settings: &RunSettings,
    noise: NoiseModel,
    track: TemperatureTrack,
) -> Result<(TemperatureTrack, ModelGrid), RunError> {
    let (scale, range_c) = (ScaleFactorPrior::default(), track.range_c());
    let grid = match noise {
        NoiseModel::Bank(bank) => {
            let selection = settings.temperature.selection();
            ModelGrid::from_bank(bank, selection, settings.gauss_markov, &scale, range_c)
        }
        NoiseModel::Profile(profile) | NoiseModel::ProfileWithThermal(profile, _) => {
            ModelGrid::from_profile(profile, &scale, range_c)
        }
    };
    let mut grid = grid.map_err(RunError::ModelGrid)?;
    grid.scale_white_noise(settings.process_noise_scale);
    Ok((track, grid))
}

type ModelResult = Result<ImuStochasticModel, SensorModelError>;

/// The filter's fixed noise model: from the bank at the chosen temperature, or from the
/// profile.
fn fixed_model(
    settings: &RunSettings,
    noise: NoiseModel,
    mean_temperature_c: Option<f64>,
) -> Result<(ModelResult, BankChoice), RunError> {
    match noise {
        NoiseModel::Profile(profile) | NoiseModel::ProfileWithThermal(profile, _) => {
            Ok(profile_model(settings, profile, mean_temperature_c))
        }
        NoiseModel::Bank(bank) => {
            let choice = bank_choice(settings, mean_temperature_c)?;
            let model = ImuStochasticModel::from_bank(bank, &choice, &ScaleFactorPrior::default());
            Ok((model, choice))
        }
    }
}

/// The profile's model at the given temperature, the record's mean, or its reference.
fn profile_model(
    settings: &RunSettings,
    profile: &SensorProfile,
    mean_temperature_c: Option<f64>,
) -> (ModelResult, BankChoice) {
    let temperature_c = (settings.temperature.given_c())
        .or(mean_temperature_c)
        .unwrap_or(profile.reference_temperature_c);
    let model = profile.stochastic_model(temperature_c, &ScaleFactorPrior::default());
    let choice = BankChoice {
        temperature_c,
        selection: Selection::Nearest,
        source: settings.gauss_markov,
    };
    (model, choice)
}

/// The temperature and rule of the settings, with the record's mean temp_c for an
/// operating temperature not given.
fn bank_choice(
    settings: &RunSettings,
    mean_temperature_c: Option<f64>,
) -> Result<BankChoice, RunError> {
    let (temperature_c, selection) = match settings.temperature {
        ModelTemperature::Fixed(t) => (t, Selection::Nearest),
        ModelTemperature::Operating { given_c, selection } => (
            given_c
                .or(mean_temperature_c)
                .ok_or(RunError::NoTemperature)?,
            selection,
        ),
    };
    Ok(BankChoice {
        temperature_c,
        selection,
        source: settings.gauss_markov,
    })
}

/// The operating temperature, °C: given, or the mean of the record's temp_c column.
///
/// # Errors
/// [`RunError::NoTemperature`] when neither is there.
pub fn operating_temperature_c(given: Option<f64>, series: &ImuSeries) -> Result<f64, RunError> {
    given
        .or_else(|| series.mean_temperature_c())
        .ok_or(RunError::NoTemperature)
}

/// The IMU increments of a series, refusing a series too short to have one.
///
/// # Errors
/// [`RunError::TooShort`].
pub fn increments_of(series: &ImuSeries) -> Result<Vec<Increment>, RunError> {
    let increments = increments_from_series(series);
    match increments.is_empty() {
        true => Err(RunError::TooShort),
        false => Ok(increments),
    }
}

/// `engine` with the outages of `spec` over the span of `increments` (not empty).
///
/// # Errors
/// [`RunError::Outages`] for windows outside the data.
pub fn with_outages(
    engine: &EngineSettings,
    spec: &OutageSpec,
    increments: &[Increment],
) -> Result<EngineSettings, RunError> {
    let span = match (increments.first(), increments.last()) {
        (Some(first), Some(last)) => (first.time, last.time),
        _ => return Err(RunError::TooShort),
    };
    with_outages_over(engine, spec, span)
}

/// [`with_outages`] over the span from the first increment's time to the last's.
///
/// # Errors
/// [`RunError::Outages`] for windows outside the span.
pub fn with_outages_over(
    engine: &EngineSettings,
    spec: &OutageSpec,
    span: (Timestamp, Timestamp),
) -> Result<EngineSettings, RunError> {
    let outages = spec.resolve(span).map_err(RunError::Outages)?;
    Ok(EngineSettings {
        outages,
        ..engine.clone()
    })
}

/// The note of a scheduled run on a record without temp_c (after the record's name).
pub const NO_TEMPERATURE_NOTE: &str = "has no temp_c column: one model for the whole run";

/// A run ready to go: models chosen, record compensated, outages laid, start found.
#[derive(Debug)]
pub struct PreparedRun {
    models: RunModels,
    compensation: CompensationOutcome,
    increments: Vec<Increment>,
    gnss: Vec<GnssFix>,
    engine: EngineSettings,
    start: StartFound,
    uncertainty: InitialUncertainty,
    bias_source: InitialBiasSource,
    /// What the caller may want to tell the user (e.g. no temp_c: one model for the run).
    pub notes: Vec<String>,
}

/// Prepares a run of `series` with `gnss` and the noise model of `noise`.
///
/// # Errors
/// Every [`RunError`] but [`RunError::Nav`]; [`RunError::input`] tells which input.
pub fn prepare(
    mut series: ImuSeries,
    gnss: Vec<GnssFix>,
    noise: NoiseModel,
    start: Start,
    settings: &RunSettings,
) -> Result<PreparedRun, RunError> {
    let models = RunModels::of(settings, noise, &series)?;
    let mut notes = Vec::new();
    if settings.scheduling != Scheduling::Fixed && models.scheduled.is_none() {
        notes.push(NO_TEMPERATURE_NOTE.to_string());
    }
    let compensation = compensate_record(&mut series, noise.thermal(), settings.compensation);
    let (prior, bias_source) = initial_uncertainty(noise, &compensation, &models.model);
    let increments = increments_of(&series)?;
    let engine = with_outages(&settings.engine, &settings.outages, &increments)?;
    let start = initial_estimate(start, &increments, &gnss, &engine)?;
    let uncertainty = start.uncertainty(prior);
    Ok(PreparedRun {
        models,
        compensation,
        increments,
        gnss,
        engine,
        start,
        uncertainty,
        bias_source,
        notes,
    })
}

/// The initial uncertainty of a run: [`initial_uncertainty_of`] with the compensation's
/// outcome.
pub(super) fn initial_uncertainty(
    noise: NoiseModel,
    compensation: &CompensationOutcome,
    model: &ImuStochasticModel,
) -> (InitialUncertainty, InitialBiasSource) {
    let applied = matches!(compensation, CompensationOutcome::Applied { .. });
    initial_uncertainty_of(noise, applied, model)
}

/// The initial uncertainty of a run with `model` on a record compensated with the noise
/// model's thermal calibration (`applied`) or not: [`InitialUncertainty::default`] with the
/// bias sds the noise model states ([`InitialBiasSource`]), axis by axis; an axis it says
/// nothing about keeps the default. `integrate` and every candidate of `evaluate` start from
/// it, so that a candidate runs the run `integrate` makes with its model.
pub fn initial_uncertainty_of(
    noise: NoiseModel,
    applied: bool,
    model: &ImuStochasticModel,
) -> (InitialUncertainty, InitialBiasSource) {
    let mut uncertainty = InitialUncertainty::default();
    let gauss_markov_sd = |c: Channel| match c.index() {
        i @ 0..3 => model.gyro[i].bias.sigma,
        i => model.accel[i - 3].bias.sigma,
    };
    let (stated, source): (Vec<_>, _) = match (noise, noise.thermal()) {
        (NoiseModel::Profile(p) | NoiseModel::ProfileWithThermal(p, _), _) if !applied => {
            let sd = |c: Channel| {
                let ch = p.channel(c)?;
                let parts = [
                    ch.turn_on_bias_sigma,
                    ch.power_on_offset_sigma,
                    gauss_markov_sd(c),
                ];
                Some(bias_sd_in_quadrature(&parts))
            };
            (
                Channel::ALL.map(sd).to_vec(),
                InitialBiasSource::ProfileTurnOn,
            )
        }
        (_, Some(thermal)) if applied => {
            // Without a spread between power-ons (a calibration of one), a profile's
            // power-on sd stands in for it.
            let profile_spread = |c: Channel| match noise {
                NoiseModel::ProfileWithThermal(p, _) => Some(p.channel(c)?.power_on_offset_sigma),
                _ => None,
            };
            let sd = |c: Channel| {
                let calibration = thermal.channels.get(&c)?;
                let spread = calibration
                    .between_power_on_sd
                    .or_else(|| profile_spread(c))?;
                Some(bias_sd_in_quadrature(&[spread, gauss_markov_sd(c)]))
            };
            (
                Channel::ALL.map(sd).to_vec(),
                InitialBiasSource::BankPowerOnSpread,
            )
        }
        _ => (vec![None; 6], InitialBiasSource::Default),
    };
    for (c, sd) in Channel::ALL.iter().zip(&stated) {
        let Some(sd) = sd.filter(|sd| sd.is_finite() && *sd > 0.0) else {
            continue;
        };
        match c.index() {
            i @ 0..3 => uncertainty.gyro_bias_sd_rad_s[i] = sd,
            i => uncertainty.accel_bias_sd_m_s2[i - 3] = sd,
        }
    }
    let source = match stated.iter().any(Option::is_some) {
        true => source,
        false => InitialBiasSource::Default,
    };
    (uncertainty, source)
}

/// The IMU record after the alignment fix that levels the start, s.
pub(super) const LEVELLING_S: f64 = 1.0;

/// The start a run found: the initial estimate, where it came from and what aligned it.
#[derive(Debug, Clone, Copy)]
pub struct StartFound {
    /// The initial estimate (with the still span's gyro biases as its sensor correction).
    pub initial: Estimate,
    /// Where it came from.
    pub source: InitialSource,
    /// The straight stretch of fixes the initial heading came from, when it was a course.
    pub course_baseline: Option<CourseBaseline>,
    /// The still span that levelled the start and gave the gyro biases, if there was one.
    pub still_start: Option<StillStart>,
    /// Whether static alignment was used, and if not, why.
    pub still_decision: StillDecision,
}

impl StartFound {
    /// The initial uncertainty of a run from `prior`: tightened by the still span, if any.
    pub fn uncertainty(&self, prior: InitialUncertainty) -> InitialUncertainty {
        self.still_start.map_or(prior, |s| s.tightened(prior))
    }
}

/// The start: aligned from GNSS (with the course baseline when the heading came from one,
/// levelled from the still span at the record's start when there is one), or the reference
/// point at the first fix.
pub fn initial_estimate(
    start: Start,
    increments: &[Increment],
    gnss: &[GnssFix],
    engine: &EngineSettings,
) -> Result<StartFound, RunError> {
    let Start::Reference(points) = start else {
        let alignment = align_from_gnss(increments, gnss, &engine.geometry, LEVELLING_S)
            .map_err(RunError::Alignment)?;
        let (source, course_baseline) = match alignment.heading_source {
            HeadingSource::DualAntenna => (InitialSource::DualAntennaHeading, None),
            HeadingSource::Course(c) => (InitialSource::CourseOverGround, Some(c)),
        };
        let decided = match engine.static_alignment {
            StaticAlignment::WhenStill => still_start_decided(increments, gnss, alignment.nav.time),
            StaticAlignment::Off => Err(StillDecision::Off),
        };
        let still_decision = match &decided {
            Ok(still) => StillDecision::Used {
                still_s: still.duration_s,
            },
            Err(decision) => *decision,
        };
        let still_start = decided.ok();
        let initial = match &still_start {
            Some(still) => levelled_start(&alignment.nav, still, increments, &engine.geometry),
            None => uncorrected(alignment.nav),
        };
        return Ok(StartFound {
            initial,
            source,
            course_baseline,
            still_start,
            still_decision,
        });
    };
    let first = increments.first().map(|i| i.time);
    let at = gnss.first().map(|f| f.time).or(first);
    let point = (points.iter().rev())
        .find(|p| at.is_some_and(|t| p.time <= t))
        .or(points.first())
        .ok_or(RunError::NoReferencePoint)?;
    Ok(StartFound {
        initial: uncorrected(point.nav_state()),
        source: InitialSource::Reference,
        course_baseline: None,
        still_start: None,
        still_decision: StillDecision::FromReference,
    })
}

/// The GNSS-aligned start `nav` with roll and pitch from the still span carried to its time,
/// its heading kept, the position at the IMU moved with the new attitude's lever arm, and the
/// span's gyro biases as the sensor correction.
fn levelled_start(
    nav: &NavState,
    still: &StillStart,
    increments: &[Increment],
    geometry: &AntennaGeometry,
) -> Estimate {
    let (_, _, yaw) = nav.attitude.euler_zyx();
    let attitude = attitude_at(still, increments, nav.time, yaw);
    let lever = Vector::<Body>::from_array(geometry.lever_arm_body_m);
    let moved = nav.attitude * lever - attitude * lever;
    let mut estimate = uncorrected(NavState {
        attitude,
        position: nav.position.displaced(&moved),
        ..*nav
    });
    estimate.sensors.gyro_bias_rad_s = still.gyro_bias_rad_s;
    estimate
}

impl PreparedRun {
    /// IMU increments to process (for a progress bar's length).
    pub fn imu_samples(&self) -> usize {
        self.increments.len()
    }

    /// The filter's settings, outages laid.
    pub fn engine(&self) -> &EngineSettings {
        &self.engine
    }

    /// Runs the filter; `progress` is told the increments processed.
    ///
    /// # Errors
    /// [`RunError::Nav`].
    pub fn run(self, progress: &mut dyn FnMut(usize)) -> Result<RunOutcome, RunError> {
        let started = Instant::now();
        let solution = run_scheduled(
            &self.increments,
            &self.gnss,
            self.start.initial,
            self.uncertainty.covariance(),
            self.models.schedule(),
            &self.engine,
            progress,
        )
        .map_err(RunError::Nav)?;
        let gnss_sd = crate::gnss::GnssSdUse::of(&self.gnss, self.engine.default_position_sd_m);
        Ok(RunOutcome {
            gnss_sd,
            processing_s: started.elapsed().as_secs_f64(),
            models: self.models,
            compensation: self.compensation,
            engine: self.engine,
            solution,
            initial: self.start.source,
            course_baseline: self.start.course_baseline,
            still_start: self.start.still_start,
            still_decision: self.start.still_decision,
            uncertainty: self.uncertainty,
            bias_source: self.bias_source,
        })
    }
}

/// What one run gave.
#[derive(Debug)]
pub struct RunOutcome {
    /// The models used.
    pub models: RunModels,
    /// What the thermal compensation did.
    pub compensation: CompensationOutcome,
    /// The filter's settings, outages laid.
    pub engine: EngineSettings,
    /// The solution.
    pub solution: Solution,
    /// Where the initial state came from.
    pub initial: InitialSource,
    /// The straight stretch of fixes the initial heading came from, when it was a course.
    pub course_baseline: Option<CourseBaseline>,
    /// The still span that levelled the start and gave the gyro biases, if any.
    pub still_start: Option<StillStart>,
    /// Whether static alignment was used, and if not, why.
    pub still_decision: StillDecision,
    /// Where the GNSS position sds came from.
    pub gnss_sd: crate::gnss::GnssSdUse,
    /// The initial standard deviations of the error states.
    pub uncertainty: InitialUncertainty,
    /// Where the initial bias sds came from.
    pub bias_source: InitialBiasSource,
    /// Wall time of the filter, s.
    pub processing_s: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_model_temperature_is_resolved_and_checked_once() {
        let linear = Selection::Linear;
        assert_eq!(
            ModelTemperature::of(Some(25.0), None, linear).unwrap(),
            ModelTemperature::Fixed(25.0)
        );
        let operating = ModelTemperature::of(None, Some(17.0), linear).unwrap();
        assert_eq!(operating.given_c(), Some(17.0));
        assert_eq!(operating.selection(), linear);
        assert_eq!(
            ModelTemperature::of(None, None, linear).unwrap().given_c(),
            None
        );
        let refused = |m, o| ModelTemperature::of(m, o, linear).unwrap_err().name;
        assert_eq!(refused(Some(f64::NAN), None), "model_temperature_c");
        assert_eq!(
            refused(None, Some(f64::INFINITY)),
            "operating_temperature_c"
        );
        assert_eq!(refused(Some(1.0), Some(2.0)), "model_temperature_c");
    }

    #[test]
    fn a_named_temperature_fixes_the_model() {
        let options = RunOptions::default();
        let settings = |temperature| {
            let switches = (Scheduling::ByTemperature, Compensation::Off);
            let base = EngineSettings::default();
            RunSettings::of_options(&options, temperature, switches, base, OutageSpec::None)
        };
        let fixed = settings(ModelTemperature::Fixed(25.0));
        assert_eq!(fixed.scheduling, Scheduling::Fixed);
        assert_eq!(fixed.compensation, Compensation::Off);
        let followed = settings(ModelTemperature::default());
        assert_eq!(followed.scheduling, Scheduling::ByTemperature);
        assert_eq!(followed.engine, EngineSettings::default());
        assert_eq!(followed.options(), options);
    }
}
