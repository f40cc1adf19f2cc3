//! A tournament's [`Scenario`] from records already read: the IMU record compensated under a
//! plan beside the raw one (and with the truth's bias subtracted for the oracle), the outages
//! laid over the data, the reference checked to cover them, the inputs checked, and the start
//! taken from the reference at the first fix (or, with [`Scenario::started`], as `integrate`
//! starts: aligned from GNSS, or from another trajectory). What `thermonav evaluate` and the
//! Python package's `evaluate` both do between reading their files and running the
//! tournament.

use super::metrics::{MetricsError, Reference, check_reference_covers};
use super::oracle::{OracleError, TrueModel};
use crate::gnss::GnssFix;
use crate::imu::ImuSeries;
use crate::ins::error_model::SystemMatrix;
use crate::ins::state::Increment;
use crate::nav::alignment::{InitialUncertainty, uncorrected};
use crate::nav::engine::{EngineSettings, NavError, check_inputs, increments_from_series};
use crate::nav::error_state::Estimate;
use crate::nav::outage::OutageSpec;
use crate::nav::run::{RunError, RunInput, Start, initial_estimate, with_outages};
use crate::nav::schedule::{
    Compensation, CompensationOutcome, ScheduleError, TemperatureTrack, compensate_record,
};
use crate::nav::static_alignment::StillStart;
use crate::stoch::thermal::ThermalCalibration;
use crate::trajectory::{ReferenceContent, TrajectoryPoint};

/// The data and settings every candidate is run on.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// IMU increments.
    pub increments: Vec<Increment>,
    /// The increments of the record with the thermal calibration's bias(T) subtracted, for
    /// the compensated candidates; `None` when the record was not compensated.
    pub compensated_increments: Option<Vec<Increment>>,
    /// The increments of the record with the true repeatable bias subtracted, for the
    /// oracle (see [`super::oracle`]); `None` without a truth.
    pub oracle_increments: Option<Vec<Increment>>,
    /// The IMU's temperature over time, for the scheduled candidates; `None` without temp_c.
    pub temperature: Option<TemperatureTrack>,
    /// GNSS fixes.
    pub gnss: Vec<GnssFix>,
    /// Reference trajectory (covering every outage).
    pub reference: Vec<TrajectoryPoint>,
    /// What the reference holds: position only, the runs start aligned and no heading is
    /// scored.
    pub reference_content: ReferenceContent,
    /// Initial estimate.
    pub initial: Estimate,
    /// The still span the runs' start was levelled from, which tightens every candidate's
    /// initial uncertainty ([`Scenario::initial_covariance`]); `None` without one.
    pub still_start: Option<StillStart>,
    /// Filter settings, outages included (the filter kind is set per run).
    pub settings: EngineSettings,
}

impl Scenario {
    /// The initial covariance of a run from `prior` (a candidate's
    /// [`super::candidates::Candidate::initial`]): tightened by the still start, as
    /// `integrate` tightens its own.
    pub fn initial_covariance(&self, prior: InitialUncertainty) -> SystemMatrix {
        let tightened = self.still_start.map_or(prior, |s| s.tightened(prior));
        tightened.covariance()
    }

    /// The reference the runs are scored against.
    pub fn reference(&self) -> Reference<'_> {
        Reference {
            points: &self.reference,
            content: self.reference_content,
        }
    }

    /// The scenario against a reference of positions only: no heading is scored. Its runs
    /// still start from the reference's point until [`Scenario::started`] starts them
    /// otherwise (aligned, since such a reference holds no attitude).
    pub fn scoring_positions_only(self) -> Self {
        Self {
            reference_content: ReferenceContent::PositionOnly,
            ..self
        }
    }

    /// The scenario with every run started as `start` says, as `integrate` starts its run:
    /// aligned from GNSS ([`Start::Align`]: GNSS heading or course over ground, levelled from
    /// a still start as the settings' static alignment says), or from a trajectory's point at
    /// the first fix ([`Start::Reference`], `integrate --initial-from`); each candidate's
    /// initial covariance is then tightened by a still start ([`Scenario::initial_covariance`]).
    ///
    /// # Errors
    /// [`ScenarioError::Run`] when the data cannot be aligned or the trajectory is empty.
    pub fn started(self, start: Start) -> Result<Self, ScenarioError> {
        let found = initial_estimate(start, &self.increments, &self.gnss, &self.settings)
            .map_err(ScenarioError::Run)?;
        Ok(Self {
            initial: found.initial,
            still_start: found.still_start,
            ..self
        })
    }
}

/// The IMU side of a scenario, from a record.
#[derive(Debug, Clone)]
pub struct ScenarioImu {
    /// Increments of the record as read.
    pub increments: Vec<Increment>,
    /// Increments of the compensated record, when compensated.
    pub compensated_increments: Option<Vec<Increment>>,
    /// Increments of the record compensated with the truth, when given one.
    pub oracle_increments: Option<Vec<Increment>>,
    /// The temperature over time, when the record has one.
    pub temperature: Option<TemperatureTrack>,
    /// What the compensation did.
    pub compensation: CompensationOutcome,
}

impl ScenarioImu {
    /// The increments of `series`, its temperature track, and the increments of the record
    /// compensated with `thermal` under `compensation`.
    ///
    /// # Errors
    /// [`ScheduleError::NonFiniteTemperature`] for a bad temp_c value.
    pub fn of(
        series: &ImuSeries,
        thermal: Option<&ThermalCalibration>,
        compensation: Compensation,
    ) -> Result<Self, ScheduleError> {
        let temperature = TemperatureTrack::of_series(series)?;
        let mut compensated = series.clone();
        let outcome = compensate_record(&mut compensated, thermal, compensation);
        Ok(Self {
            increments: increments_from_series(series),
            compensated_increments: outcome
                .applied()
                .then(|| increments_from_series(&compensated)),
            oracle_increments: None,
            temperature,
            compensation: outcome,
        })
    }

    /// Adds the increments of `series` with `truth`'s repeatable bias subtracted, for the
    /// oracle candidates.
    ///
    /// # Errors
    /// [`OracleError::NoTemperature`] when the record has no usable temperatures.
    pub fn with_oracle(
        mut self,
        series: &ImuSeries,
        truth: &TrueModel,
    ) -> Result<Self, OracleError> {
        let mut compensated = series.clone();
        truth.compensate(&mut compensated)?;
        self.oracle_increments = Some(increments_from_series(&compensated));
        Ok(self)
    }
}

/// How a scenario's records are made: the bank's calibration (if any) under the switch, and
/// the simulator's truth for the oracle's record (if any).
#[derive(Debug, Clone, Copy)]
pub struct RecordPlan<'a> {
    /// The bank's thermal calibration.
    pub thermal: Option<&'a ThermalCalibration>,
    /// Whether it is applied.
    pub compensation: Compensation,
    /// The truth of a simulated survey.
    pub oracle: Option<&'a TrueModel>,
}

impl<'a> RecordPlan<'a> {
    /// The plan without an oracle.
    pub fn calibrated(thermal: Option<&'a ThermalCalibration>, compensation: Compensation) -> Self {
        Self {
            thermal,
            compensation,
            oracle: None,
        }
    }
}

/// Why a scenario cannot be made; [`ScenarioError::input`] tells which input it is about.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ScenarioError {
    /// The record's temperatures are unusable.
    #[error(transparent)]
    Temperature(ScheduleError),
    /// The truth cannot compensate the record.
    #[error(transparent)]
    Oracle(OracleError),
    /// Too short a record, outages outside the data.
    #[error(transparent)]
    Run(RunError),
    /// The reference does not cover an outage.
    #[error(transparent)]
    Reference(MetricsError),
    /// The filter refuses the inputs.
    #[error(transparent)]
    Nav(NavError),
    /// No GNSS fix.
    #[error("the GNSS file has no fix")]
    NoFix,
    /// The reference has no point to start from.
    #[error("the reference trajectory has no point")]
    EmptyReference,
}

impl ScenarioError {
    /// The input the error is about ([`RunInput::Filter`] for the GNSS file's lack of fixes,
    /// whose message names it).
    pub fn input(&self) -> RunInput {
        match self {
            ScenarioError::Temperature(_) | ScenarioError::Oracle(_) => RunInput::Imu,
            ScenarioError::Run(e) => e.input(),
            ScenarioError::Reference(_) | ScenarioError::EmptyReference => RunInput::Reference,
            ScenarioError::Nav(e) => RunError::Nav(e.clone()).input(),
            ScenarioError::NoFix => RunInput::Filter,
        }
    }
}

/// The IMU side of a scenario from its record (the oracle's record only when it has
/// temperatures: without, the oracle is left out with its reason).
///
/// # Errors
/// [`ScenarioError::Temperature`], [`ScenarioError::Oracle`].
pub fn scenario_imu(series: &ImuSeries, plan: RecordPlan) -> Result<ScenarioImu, ScenarioError> {
    let imu = ScenarioImu::of(series, plan.thermal, plan.compensation)
        .map_err(ScenarioError::Temperature)?;
    match plan.oracle {
        Some(truth) if imu.temperature.is_some() => imu
            .with_oracle(series, truth)
            .map_err(ScenarioError::Oracle),
        _ => Ok(imu),
    }
}

/// A scenario from in-memory data, started from the reference at the first fix with the
/// default initial covariance. A reference that starts after the first fix is accepted (as
/// `integrate --initial-from` does): the runs start at its first point, and only the outages
/// inside its span can be scored ([`check_reference_covers`] refuses the others).
///
/// # Errors
/// [`ScenarioError::NoFix`], [`ScenarioError::EmptyReference`].
pub fn scenario_of(
    imu: ScenarioImu,
    gnss: Vec<GnssFix>,
    reference: Vec<TrajectoryPoint>,
    settings: EngineSettings,
) -> Result<Scenario, ScenarioError> {
    let initial = initial_from_reference(&reference, &gnss)?;
    Ok(Scenario {
        increments: imu.increments,
        compensated_increments: imu.compensated_increments,
        oracle_increments: imu.oracle_increments,
        temperature: imu.temperature,
        gnss,
        reference,
        reference_content: ReferenceContent::Full,
        initial: uncorrected(initial.nav_state()),
        still_start: None,
        settings,
    })
}

/// The reference point at (or last before) the first GNSS fix, or the reference's first
/// point when it starts later: the common starting state.
fn initial_from_reference(
    reference: &[TrajectoryPoint],
    gnss: &[GnssFix],
) -> Result<TrajectoryPoint, ScenarioError> {
    let start = gnss.first().map(|f| f.time).ok_or(ScenarioError::NoFix)?;
    (reference.iter().rev())
        .find(|p| p.time <= start)
        .or(reference.first())
        .copied()
        .ok_or(ScenarioError::EmptyReference)
}

/// The scenario of the records: the IMU side under `records`, `engine` with the outages of
/// `outages` over the data, the reference checked to cover them and the inputs checked.
///
/// # Errors
/// Every [`ScenarioError`].
pub fn scenario_of_records(
    series: &ImuSeries,
    gnss: Vec<GnssFix>,
    reference: Vec<TrajectoryPoint>,
    (engine, outages): (&EngineSettings, &OutageSpec),
    records: RecordPlan,
) -> Result<Scenario, ScenarioError> {
    let imu = scenario_imu(series, records)?;
    let engine = with_outages(engine, outages, &imu.increments).map_err(ScenarioError::Run)?;
    check_reference_covers(&reference, engine.outages.windows())
        .map_err(ScenarioError::Reference)?;
    check_inputs(&imu.increments, &gnss, &engine).map_err(ScenarioError::Nav)?;
    scenario_of(imu, gnss, reference, engine)
}
