//! The navigation run: strapdown mechanization at the IMU rate, covariance propagation at a
//! chosen rate, GNSS updates at their epochs, closed-loop feedback.
//!
//! **Time alignment.** An IMU interval that contains a GNSS epoch is split there (the
//! increments shared in proportion to time), so every update happens at the fix's own time
//! (KF-GINS does the same).
//!
//! **Covariance propagation rate.** The nominal state is mechanized at every IMU sample; the
//! covariance is propagated once per `covariance_interval_s` (and at every GNSS epoch) over the
//! accumulated interval. The EKF uses Φ = I + FΔt + ½(FΔt)² with F at the interval's start and
//! the mean corrected rates; the UKF mechanizes each of its 2n + 1 sigma points once over the
//! interval with the summed increments and differences them against the nominal start state
//! propagated the same way, so the coarse step's own error cancels and only the error
//! dynamics remain. The default 0.1 s is checked against per-sample propagation in the tests.
//!
//! **Feedback.** After every update (and, for the UKF, after every prediction, whose mean
//! error is not exactly zero) the error estimate is folded into the nominal
//! ([`Estimate::corrected_by`]) and reset to zero.

use super::error_filter::{
    ChosenFilter, ErrorEkf, ErrorStateFilter, ErrorUkf, Measurement, Updated,
};
use super::error_state::{ErrorVector, Estimate};
use super::measurement::{
    AntennaGeometry, Linearized, MeasurementKind, antenna_position, antenna_velocity,
    baseline_heading, heading_linearized, position_linearized, velocity_linearized,
};
use super::outage::Outages;
use super::process_model::ProcessStep;
use super::schedule::ModelSchedule;
use super::smoother::ForwardHistory;
use super::solution::{InnovationRecord, SolutionEpoch, SolutionSink};
use crate::filter::gating::ScaledGate;
use crate::filter::sigma_points::SigmaPointScheme;
use crate::frames::Vector;
use crate::geo::position::{Geodetic, NAVIGATION_LATITUDE_LIMIT_DEG, within_navigation_latitudes};
use crate::gnss::GnssFix;
use crate::imu::{ImuSample, ImuSeries, SampleKind};
use crate::ins::error_model::{STATES, SystemMatrix};
use crate::ins::mechanization::mechanize;
use crate::ins::state::Increment;
use crate::time::{Duration, Timestamp};
use crate::units::wrap_pi;
use nalgebra::{SMatrix, SVector, Vector3};
use serde::{Deserialize, Serialize};
use std::convert::Infallible;

/// Which filter carries the error state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FilterKind {
    /// Error-state extended Kalman filter, Joseph-form updates.
    Ekf,
    /// Error-state unscented Kalman filter.
    Ukf,
}

impl FilterKind {
    /// Both filters in the order a tournament reports them (`evaluate --filter both`).
    pub const BOTH: [FilterKind; 2] = [FilterKind::Ukf, FilterKind::Ekf];

    /// Name used in outputs.
    pub fn name(self) -> &'static str {
        match self {
            FilterKind::Ekf => "ekf",
            FilterKind::Ukf => "ukf",
        }
    }
}

/// Which GNSS measurements to use when a fix carries them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Aiding {
    /// Antenna position.
    pub position: bool,
    /// Antenna velocity.
    pub velocity: bool,
    /// Dual-antenna heading.
    pub heading: bool,
}

impl Default for Aiding {
    fn default() -> Self {
        Self {
            position: true,
            velocity: true,
            heading: true,
        }
    }
}

/// Settings of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EngineSettings {
    /// The filter.
    pub filter: FilterKind,
    /// Longest interval over which the covariance is propagated in one step, s.
    pub covariance_interval_s: f64,
    /// Probability of the chi-square innovation gate; `None` accepts every update.
    pub gate_probability: Option<f64>,
    /// After this many consecutive rejections of one measurement kind, the next update of
    /// that kind is applied whatever its NIS (and counted as forced): a filter whose model
    /// lets its covariance become too small would otherwise reject every later fix and run
    /// free.
    pub gate_recovery_after: usize,
    /// The gate's quantile is widened by the median NIS of this many recent updates of the
    /// same kind over its expected median ([`ScaledGate`]); 0 keeps the plain chi-square gate.
    pub gate_window: usize,
    /// Antennas.
    pub geometry: AntennaGeometry,
    /// Measurements used.
    pub aiding: Aiding,
    /// GNSS outages.
    pub outages: Outages,
    /// Interval between solution epochs, s.
    pub output_interval_s: f64,
    /// Sigma points of the UKF.
    #[serde(skip)]
    pub sigma_points: SigmaPointScheme,
    /// Position standard deviation used when a fix gives none, north/east/down, m.
    pub default_position_sd_m: [f64; 3],
    /// Velocity standard deviation of GNSS velocities, m/s.
    pub velocity_sd_m_s: [f64; 3],
    /// Keep the forward history and run the RTS smoother after the forward pass (EKF only;
    /// at most [`MAX_SMOOTHED_STEPS`](super::smoother::MAX_SMOOTHED_STEPS) covariance steps).
    pub smooth: bool,
    /// Longest IMU interval the filter crosses, s: a longer gap is refused
    /// ([`NavError::ImuGap`]) rather than dead-reckoned on one held rate.
    pub max_imu_gap_s: f64,
    /// Split the z-gyro bias prior into a Gaussian sum of filters run in lockstep
    /// ([`super::gaussian_sum`]): for runs in which nothing observes the heading directly
    /// (position-only GNSS). `None` runs one filter.
    pub bias_hypotheses: Option<BiasHypotheses>,
    /// Level the start and take the gyro biases from a still platform at the record's start
    /// ([`super::static_alignment`]); used by the runs that align from GNSS.
    pub static_alignment: super::static_alignment::StaticAlignment,
}

impl Default for EngineSettings {
    /// EKF, covariance at 10 Hz, gate at 0.9999 scaled by the last 5 NIS, all aiding, solution at 10 Hz, Merwe points
    /// with α = 1, β = 2, κ = 0 (all covariance weights non-negative, so the predicted
    /// covariance is positive semi-definite by construction).
    fn default() -> Self {
        Self {
            filter: FilterKind::Ekf,
            covariance_interval_s: 0.1,
            gate_probability: Some(0.9999),
            gate_recovery_after: 5,
            gate_window: 5,
            geometry: AntennaGeometry::default(),
            aiding: Aiding::default(),
            outages: Outages::none(),
            output_interval_s: 0.1,
            sigma_points: SigmaPointScheme::MerweScaled {
                alpha: 1.0,
                beta: 2.0,
                kappa: 0.0,
            },
            default_position_sd_m: [1.0, 1.0, 2.0],
            velocity_sd_m_s: [0.05, 0.05, 0.1],
            max_imu_gap_s: 1.0,
            smooth: false,
            bias_hypotheses: None,
            static_alignment: super::static_alignment::StaticAlignment::default(),
        }
    }
}

/// Most members of a Gaussian sum. The run's time grows with the members (1001 took 12 s on
/// a 330 s survey, so about 40 ms per member per 330 s), and 31, 41 and 61 members gave the
/// same consistency on the position-only vessel runs: 201, five times the default, leaves room
/// for a wider prior and keeps an hour's survey near half a minute per hundred members.
pub const MAX_BIAS_HYPOTHESES: usize = 201;

/// How the z-gyro bias prior is split.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BiasHypotheses {
    /// Members of the sum (odd, so that one sits at the prior's mean; 1 is a single filter).
    pub members: usize,
    /// The grid spans ±`span_sd` prior sds.
    pub span_sd: f64,
    /// A member whose normalised weight falls below this is dropped.
    pub prune_below: f64,
}

impl Default for BiasHypotheses {
    /// 41 members over ±3 sd, 0.15 sd apart, each with an sd of 0.20 prior sds (the grid's
    /// truncation at ±3 sd leaves that much to the members): a 1 °/s prior gives members
    /// 0.15 °/s apart, so that a member near the truth drifts by about 12° (one sd) in the
    /// minute a vessel may run before its first speed change shows the heading.
    /// Dropped below a weight of 1e-8. (On the position-only vessel runs of
    /// `tests/it/position_only.rs`, 31, 41 and 61 members gave 79-84 % of epochs inside the
    /// NEES band, against 0 % for one filter.)
    fn default() -> Self {
        Self {
            members: 41,
            span_sd: 3.0,
            prune_below: 1e-8,
        }
    }
}

/// Why a run failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NavError {
    /// The filter diverged.
    #[error("the {filter} diverged at t = {time_s:.3} s: {reason}")]
    Diverged {
        /// Filter name.
        filter: &'static str,
        /// Time of the failure, s.
        time_s: f64,
        /// What failed.
        reason: String,
    },
    /// A Gaussian sum's member count that cannot be split, or that is beyond
    /// [`MAX_BIAS_HYPOTHESES`].
    #[error(
        "a Gaussian sum over the z-gyro bias takes 1 or an odd count of members from 9 to {MAX_BIAS_HYPOTHESES} (fewer would sit more than one prior sd apart), got {0}"
    )]
    BiasHypotheses(usize),
    /// A setting is out of range.
    #[error("setting {what} = {value} must be finite and positive")]
    Setting {
        /// Which setting.
        what: &'static str,
        /// The value.
        value: f64,
    },
    /// No IMU sample after the initial time.
    #[error("no IMU sample after the initial time {0:.3} s")]
    NoImu(f64),
    /// A GNSS fix beyond [`NAVIGATION_LATITUDE_LIMIT_DEG`].
    #[error(
        "the GNSS fix at t = {time_s:.3} s is at latitude {latitude_deg:.4}°: thermonav navigates within ±{NAVIGATION_LATITUDE_LIMIT_DEG}° (the NED mechanisation is singular at the poles)"
    )]
    PolarFix {
        /// Time of the fix, s.
        time_s: f64,
        /// Its latitude, °.
        latitude_deg: f64,
    },
    /// The solution beyond [`NAVIGATION_LATITUDE_LIMIT_DEG`].
    #[error(
        "the solution reached latitude {latitude_deg:.4}° at t = {time_s:.3} s: thermonav navigates within ±{NAVIGATION_LATITUDE_LIMIT_DEG}° (the NED mechanisation is singular at the poles)"
    )]
    PolarSolution {
        /// When, s.
        time_s: f64,
        /// The latitude, °.
        latitude_deg: f64,
    },
    /// Smoothing asked of a filter or a run it does not cover.
    #[error("cannot smooth: {0}")]
    Smoothing(String),
    /// An IMU interval longer than [`EngineSettings::max_imu_gap_s`].
    #[error(
        "the IMU record has a gap of {length_s:.3} s after t = {start_s:.3} s, longer than the {limit_s} s the filter bridges (dead reckoning on a held rate over a gap is not navigation); cut the run at the gap or raise --max-imu-gap-s to bridge it"
    )]
    ImuGap {
        /// Time of the last sample before the gap, s.
        start_s: f64,
        /// Length of the gap, s.
        length_s: f64,
        /// The limit, s.
        limit_s: f64,
    },
}

/// IMU increments from a series: each sample covers the interval since the previous one (the
/// first sample, which has no interval, starts the series). Rates are held over the interval.
pub fn increments_from_series(series: &ImuSeries) -> Vec<Increment> {
    let kind = series.kind.unwrap_or(SampleKind::Rates);
    (1..series.len())
        .map(|k| {
            let value = |c: usize| series.channels[c][k];
            let sample = ImuSample {
                time: series.time[k],
                gyro: [value(0), value(1), value(2)],
                accel: [value(3), value(4), value(5)],
                temperature_c: None,
            };
            increment_of_sample(kind, series.time[k - 1], &sample)
        })
        .collect()
}

/// The increment of `sample` (rates or increments, as `kind` says) over the interval since
/// the previous sample's time `previous`: what [`increments_from_series`] makes of each sample.
pub fn increment_of_sample(kind: SampleKind, previous: Timestamp, sample: &ImuSample) -> Increment {
    let dt = sample.time - previous;
    match kind {
        SampleKind::Rates => Increment::from_rates(sample.time, dt, sample.gyro, sample.accel),
        SampleKind::Increments => Increment {
            time: sample.time,
            dt,
            delta_angle: Vector::from_array(sample.gyro),
            delta_velocity: Vector::from_array(sample.accel),
        },
    }
}

/// The increments of a stream of samples, as [`increments_from_series`] makes them of a
/// series: one per sample after the first; the stream's errors passed on (and the stream
/// ended after the first).
pub fn increments_of_samples<E>(
    kind: SampleKind,
    samples: impl IntoIterator<Item = Result<ImuSample, E>>,
) -> impl Iterator<Item = Result<Increment, E>> {
    let mut previous: Option<Timestamp> = None;
    let mut failed = false;
    samples.into_iter().filter_map(move |sample| {
        if failed {
            return None;
        }
        match sample {
            Err(e) => {
                failed = true;
                Some(Err(e))
            }
            Ok(sample) => {
                let before = previous.replace(sample.time)?;
                Some(Ok(increment_of_sample(kind, before, &sample)))
            }
        }
    })
}

pub(crate) fn check_settings(settings: &EngineSettings) -> Result<(), NavError> {
    for (what, value) in [
        ("covariance_interval_s", settings.covariance_interval_s),
        ("output_interval_s", settings.output_interval_s),
        ("max_imu_gap_s", settings.max_imu_gap_s),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return Err(NavError::Setting { what, value });
        }
    }
    Ok(())
}

/// The data a run refuses before its first step: an IMU interval longer than
/// [`EngineSettings::max_imu_gap_s`] or a GNSS fix beyond the navigable latitudes.
///
/// # Errors
/// [`NavError::ImuGap`] or [`NavError::PolarFix`] for the first such interval or fix.
pub fn check_inputs(
    increments: &[Increment],
    gnss: &[GnssFix],
    settings: &EngineSettings,
) -> Result<(), NavError> {
    check_imu_gaps(increments, settings.max_imu_gap_s)?;
    check_fix_latitudes(gnss)
}

/// The first IMU interval longer than `limit_s`, refused.
pub(crate) fn check_imu_gaps(increments: &[Increment], limit_s: f64) -> Result<(), NavError> {
    match increments.iter().find(|i| i.dt_s() > limit_s) {
        Some(gap) => Err(NavError::ImuGap {
            start_s: gap.start().as_seconds(),
            length_s: gap.dt_s(),
            limit_s,
        }),
        None => Ok(()),
    }
}

/// The first GNSS fix beyond the navigable latitudes, refused.
pub(crate) fn check_fix_latitudes(gnss: &[GnssFix]) -> Result<(), NavError> {
    match gnss
        .iter()
        .find(|f| !within_navigation_latitudes(f.latitude_rad))
    {
        Some(fix) => Err(NavError::PolarFix {
            time_s: fix.time.as_seconds(),
            latitude_deg: fix.latitude_rad.to_degrees(),
        }),
        None => Ok(()),
    }
}

/// The increment split at `at` (strictly inside its interval) into the parts before and
/// after, shared in proportion to time. The interval is split exactly (the two durations add
/// up to the whole to the nanosecond); the shares of the increments are computed from those
/// exact durations.
fn split(inc: &Increment, at: Timestamp) -> (Increment, Increment) {
    let after = inc.time - at;
    let share = 1.0 - after.as_seconds() / inc.dt_s();
    let part = |fraction: f64, time: Timestamp, dt: Duration| Increment {
        time,
        dt,
        delta_angle: inc.delta_angle.scale(fraction),
        delta_velocity: inc.delta_velocity.scale(fraction),
    };
    (
        part(share, at, inc.dt - after),
        part(1.0 - share, inc.time, after),
    )
}

/// Raw increments accumulated since the last covariance propagation.
#[derive(Debug, Clone, Copy)]
struct Window {
    start: Estimate,
    raw: Increment,
}

impl Window {
    fn at(start: Estimate) -> Self {
        Self {
            start,
            raw: Increment {
                time: start.nav.time,
                dt: Duration::ZERO,
                delta_angle: Vector::zeros(),
                delta_velocity: Vector::zeros(),
            },
        }
    }

    fn add(&mut self, raw: &Increment) {
        self.raw.time = raw.time;
        self.raw.dt += raw.dt;
        self.raw.delta_angle = self.raw.delta_angle + raw.delta_angle;
        self.raw.delta_velocity = self.raw.delta_velocity + raw.delta_velocity;
    }
}

pub(crate) struct Run<'a, 's> {
    estimate: Estimate,
    core: ChosenFilter,
    /// What stands in `core` while the filter is moved out by value for a prediction.
    stand_in: Option<ChosenFilter>,
    window: Window,
    previous: Increment,
    last_raw_rate: Vector3<f64>,
    schedule: ModelSchedule<'a>,
    settings: &'a EngineSettings,
    gates: [Option<ScaledGate>; 3],
    consecutive_rejections: [usize; 3],
    sink: &'s mut dyn SolutionSink,
    /// The last epoch recorded, held back from the sink until the updates at its time are
    /// done ([`Run::refresh_last_epoch`]) and the next epoch (or the end) comes.
    pending: Option<SolutionEpoch>,
    history: Option<ForwardHistory>,
    next_output: Timestamp,
    output_step: Duration,
    covariance_step: Duration,
}

/// What a filter starts from: the initial estimate and covariance, the noise models and the
/// settings.
#[derive(Debug, Clone)]
pub struct Filtering<'a> {
    /// The initial estimate (its time is the run's start).
    pub initial: Estimate,
    /// Its covariance.
    pub p0: SystemMatrix,
    /// The noise models.
    pub schedule: ModelSchedule<'a>,
    /// The settings.
    pub settings: &'a EngineSettings,
}

/// What a streamed run returns besides what went to its sink.
#[derive(Debug, Clone, PartialEq)]
pub struct StreamTail {
    /// IMU samples processed.
    pub imu_samples: usize,
    /// The smoothed solution (empty unless [`EngineSettings::smooth`]).
    pub smoothed: Vec<SolutionEpoch>,
}

/// Why a streamed run failed: the filter, or the stream of increments.
#[derive(Debug, Clone, PartialEq)]
pub enum StreamError<E> {
    /// The filter refused the data or diverged.
    Nav(NavError),
    /// The increments could not be read.
    Input(E),
}

impl<E> From<NavError> for StreamError<E> {
    fn from(error: NavError) -> Self {
        StreamError::Nav(error)
    }
}

impl StreamError<Infallible> {
    /// The filter's error (an infallible stream has no other).
    pub fn into_nav(self) -> NavError {
        match self {
            StreamError::Nav(e) => e,
            StreamError::Input(never) => match never {},
        }
    }
}

impl<'a, 's> Run<'a, 's> {
    pub(crate) fn new(
        filtering: Filtering<'a>,
        sink: &'s mut dyn SolutionSink,
    ) -> Result<Self, NavError> {
        let Filtering {
            initial,
            p0,
            schedule,
            settings,
        } = filtering;
        let core = match settings.filter {
            FilterKind::Ekf => ChosenFilter::Ekf(ErrorEkf::new(p0)),
            FilterKind::Ukf => ChosenFilter::Ukf(ErrorUkf::new(p0, settings.sigma_points)),
        };
        let gate = |kind: MeasurementKind| {
            settings
                .gate_probability
                .and_then(|p| ScaledGate::new(kind.dimension(), p, settings.gate_window))
        };
        let exact = |what, value| {
            Duration::from_seconds(value).map_err(|_| NavError::Setting { what, value })
        };
        let covariance_step = exact("covariance_interval_s", settings.covariance_interval_s)?;
        let output_step = exact("output_interval_s", settings.output_interval_s)?;
        if !output_step.is_positive() {
            // Below half a nanosecond: the output schedule would never advance.
            return Err(NavError::Setting {
                what: "output_interval_s",
                value: settings.output_interval_s,
            });
        }
        let mut run = Self {
            estimate: initial,
            core,
            stand_in: Some(ChosenFilter::stand_in()),
            window: Window::at(initial),
            previous: Window::at(initial).raw,
            last_raw_rate: Vector3::zeros(),
            schedule,
            settings,
            gates: MeasurementKind::ALL.map(gate),
            consecutive_rejections: [0; 3],
            sink,
            pending: None,
            history: settings.smooth.then(ForwardHistory::default),
            next_output: initial.nav.time,
            output_step,
            covariance_step,
        };
        run.record();
        Ok(run)
    }

    /// One increment after the start: split at the fixes inside it, stepped, updated.
    pub(crate) fn feed<'g>(
        &mut self,
        inc: Increment,
        start: Timestamp,
        fixes: &mut std::iter::Peekable<impl Iterator<Item = &'g GnssFix>>,
    ) -> Result<(), NavError> {
        let mut raw = inc;
        if raw.start() < start {
            raw = split(&raw, start).1;
        }
        while let Some(fix) = fixes.next_if(|f| f.time <= raw.time) {
            if fix.time > self.estimate.nav.time && fix.time < raw.time {
                let (before, after) = split(&raw, fix.time);
                self.step(&before)?;
                raw = after;
            } else if fix.time == raw.time {
                self.step(&raw)?;
                raw.dt = Duration::ZERO;
            }
            self.update(fix)?;
        }
        if raw.dt.is_positive() {
            self.step(&raw)?;
        }
        Ok(())
    }

    /// The end of the record: the last propagation and epoch, the smoother, the last epoch
    /// to the sink.
    pub(crate) fn finish(mut self) -> Result<Vec<SolutionEpoch>, NavError> {
        self.propagate()?;
        self.record();
        let mut smoothed = Vec::new();
        if let (Some(history), ChosenFilter::Ekf(ekf)) = (&mut self.history, &self.core) {
            // The last updates came after the last step's end: the history ends filtered.
            history.begin(self.estimate, *ekf.covariance());
            smoothed = history
                .smooth(&self.settings.outages)
                .map_err(|e| NavError::Smoothing(e.to_string()))?;
        }
        if let Some(last) = self.pending.take() {
            self.sink.epoch(&last);
        }
        Ok(smoothed)
    }

    fn diverged(&self, reason: impl ToString) -> NavError {
        NavError::Diverged {
            filter: self.settings.filter.name(),
            time_s: self.estimate.nav.time.as_seconds(),
            reason: reason.to_string(),
        }
    }

    /// One IMU interval: mechanize the nominal, accumulate the window, propagate when due.
    fn step(&mut self, raw: &Increment) -> Result<(), NavError> {
        if let (Some(history), ChosenFilter::Ekf(ekf), false) = (
            &mut self.history,
            &self.core,
            self.window.raw.dt.is_positive(),
        ) {
            history.begin(self.estimate, *ekf.covariance());
        }
        let corrected = self.estimate.sensors.correct(raw);
        let previous = if self.previous.dt.is_positive() {
            self.previous
        } else {
            corrected
        };
        self.estimate.nav = mechanize(&self.estimate.nav, &previous, &corrected);
        self.previous = corrected;
        self.last_raw_rate = raw.delta_angle.raw() / raw.dt_s();
        self.window.add(raw);
        self.check_nominal()?;
        if self.window.raw.dt >= self.covariance_step {
            self.propagate()?;
        }
        if self.estimate.nav.time >= self.next_output {
            self.record();
        }
        Ok(())
    }

    fn check_nominal(&self) -> Result<(), NavError> {
        let nav = &self.estimate.nav;
        let finite = [
            nav.position.latitude_rad,
            nav.position.longitude_rad,
            nav.position.height_m,
        ]
        .iter()
        .chain(&nav.velocity.to_array())
        .all(|v| v.is_finite());
        if !finite {
            return Err(self.diverged("the navigation state is not finite"));
        }
        if !within_navigation_latitudes(nav.position.latitude_rad) {
            return Err(NavError::PolarSolution {
                time_s: nav.time.as_seconds(),
                latitude_deg: nav.position.latitude_rad.to_degrees(),
            });
        }
        if nav.velocity.norm() > 3000.0 {
            return Err(self.diverged(format!(
                "the estimated speed reached {:.0} m/s",
                nav.velocity.norm()
            )));
        }
        Ok(())
    }

    /// Standard deviations of the error states now.
    fn current_sd(&self) -> [f64; STATES] {
        let p = self.core.covariance();
        std::array::from_fn(|i| p[(i, i)].max(0.0).sqrt())
    }

    /// Appends a solution epoch at the current time and schedules the next.
    fn record(&mut self) {
        let sd = self.current_sd();
        let time = self.estimate.nav.time;
        if self.pending.map(|e| e.estimate.nav.time) == Some(time) {
            return;
        }
        let epoch = SolutionEpoch {
            estimate: self.estimate,
            sd,
            in_outage: self.settings.outages.contains(time),
        };
        if let Some(done) = self.pending.replace(epoch) {
            self.sink.epoch(&done);
        }
        while self.next_output <= time {
            match self.next_output.checked_add(self.output_step) {
                Some(next) => self.next_output = next,
                // At the end of the time range: record every later epoch.
                None => break,
            }
        }
    }

    /// Propagates the covariance over the accumulated window.
    fn propagate(&mut self) -> Result<(), NavError> {
        if !self.window.raw.dt.is_positive() {
            return Ok(());
        }
        let start = self.window.start;
        let model = self.schedule.model_at(start.nav.time);
        let step = ProcessStep::new(&start, &self.window.raw, model);
        // Taken out by value, the stand-in holding its place (a run whose prediction fails
        // stops, so the stand-in is never used as a filter).
        let Some(stand_in) = self.stand_in.take() else {
            return Err(self.diverged("a failed prediction was not the end of the run"));
        };
        let core = std::mem::replace(&mut self.core, stand_in);
        let predicted = core.predict(&step).map_err(|e| self.diverged(e))?;
        self.stand_in = Some(std::mem::replace(&mut self.core, predicted.filter));
        if let (Some(history), ChosenFilter::Ekf(ekf)) = (&mut self.history, &self.core) {
            history.end(
                step.transition().to_matrix(),
                self.estimate,
                *ekf.covariance(),
            );
        }
        if let Some(shift) = predicted.shift {
            self.estimate = self.estimate.corrected_by(&shift);
        }
        self.window = Window::at(self.estimate);
        Ok(())
    }

    /// The GNSS updates at one fix (none inside an outage).
    fn update(&mut self, fix: &GnssFix) -> Result<(), NavError> {
        self.propagate()?;
        if self.settings.outages.contains(fix.time) {
            return Ok(());
        }
        let aiding = self.settings.aiding;
        let geometry = self.settings.geometry;
        if aiding.position {
            let measured = Geodetic {
                latitude_rad: fix.latitude_rad,
                longitude_rad: fix.longitude_rad,
                height_m: fix.height_m,
            };
            let sd = fix
                .position_sd_ned_m
                .unwrap_or(self.settings.default_position_sd_m);
            let lin = position_linearized(&self.estimate, &geometry, &measured, sd);
            let origin = antenna_position(&self.estimate, &geometry);
            let z = measured.ned_from(&origin).raw();
            let nominal = self.estimate;
            self.apply(MeasurementKind::Position, lin, z, move |dx| {
                antenna_position(&nominal.corrected_by(dx), &geometry)
                    .ned_from(&origin)
                    .raw()
            })?;
        }
        if let (true, Some(v)) = (aiding.velocity, fix.velocity_ned_m_s) {
            let measured = Vector3::from(v);
            let nominal = self.estimate;
            let raw_rate = self.last_raw_rate;
            let rate = nominal.sensors.corrected_rate(&raw_rate);
            let lin = velocity_linearized(
                &nominal,
                &geometry,
                &rate,
                &measured,
                self.settings.velocity_sd_m_s,
            );
            let predicted = antenna_velocity(&nominal, &geometry, &rate).raw();
            let z = measured - predicted;
            self.apply(MeasurementKind::Velocity, lin, z, move |dx| {
                let point = nominal.corrected_by(dx);
                let rate = point.sensors.corrected_rate(&raw_rate);
                antenna_velocity(&point, &geometry, &rate).raw() - predicted
            })?;
        }
        if let (true, Some(h)) = (aiding.heading, fix.heading) {
            let nominal = self.estimate;
            let lin = heading_linearized(&nominal, &geometry, h.heading_rad, h.sd_rad);
            let predicted = baseline_heading(&nominal, &geometry);
            let z = SVector::<f64, 1>::new(wrap_pi(h.heading_rad - predicted));
            self.apply(MeasurementKind::Heading, lin, z, move |dx| {
                SVector::<f64, 1>::new(wrap_pi(
                    baseline_heading(&nominal.corrected_by(dx), &geometry) - predicted,
                ))
            })?;
        }
        self.window = Window::at(self.estimate);
        self.refresh_last_epoch();
        Ok(())
    }

    /// An epoch recorded at this fix's time, before its updates, shows the updated state.
    fn refresh_last_epoch(&mut self) {
        let (time, sd) = (self.estimate.nav.time, self.current_sd());
        if let Some(last) = &mut self.pending {
            if last.estimate.nav.time == time {
                last.estimate = self.estimate;
                last.sd = sd;
            }
        }
    }

    /// One gated update: the EKF from the linearisation, the UKF from the nonlinear model
    /// `h` (the measurement `z` relative to the nominal prediction, so that ẑ(0) = 0).
    fn apply<const M: usize>(
        &mut self,
        kind: MeasurementKind,
        lin: Linearized<M>,
        z: SVector<f64, M>,
        h: impl Fn(&ErrorVector) -> SVector<f64, M>,
    ) -> Result<(), NavError> {
        let measurement = Measurement {
            linearized: lin,
            z,
            model: &h,
        };
        let Updated {
            filter,
            correction: x,
            innovation,
            covariance: s,
            nis,
        } = self
            .core
            .clone()
            .update(&measurement)
            .map_err(|e| self.diverged(e))?;
        let verdict = self.gates[kind as usize].as_mut().map(|g| g.judge(nis));
        let passed = verdict.is_none_or(|v| v.passed);
        let streak = &mut self.consecutive_rejections[kind as usize];
        let forced = !passed && *streak >= self.settings.gate_recovery_after;
        *streak = if passed || forced { 0 } else { *streak + 1 };
        let accepted = passed || forced;
        self.sink.innovation(&InnovationRecord {
            time: self.estimate.nav.time,
            kind,
            innovation: std::array::from_fn(|k| if k < M { innovation[k] } else { 0.0 }),
            sd: std::array::from_fn(|k| {
                if k < M {
                    s[(k, k)].max(0.0).sqrt()
                } else {
                    0.0
                }
            }),
            nis,
            log_likelihood: innovation_log_likelihood(&s, nis),
            gate_scale: verdict.map_or(1.0, |v| v.scale),
            accepted,
            forced,
        });
        if accepted {
            self.core = filter;
            self.estimate = self.estimate.corrected_by(&x);
        }
        Ok(())
    }
}

/// ln N(ν; 0, S) from the NIS and S: −(NIS + ln det S + m ln 2π)/2. When S is not positive
/// definite (rounding at a degenerate update) the density is taken as zero.
fn innovation_log_likelihood<const M: usize>(s: &SMatrix<f64, M, M>, nis: f64) -> f64 {
    match s.cholesky() {
        Some(c) => {
            let log_det = 2.0 * c.l().diagonal().iter().map(|v| v.ln()).sum::<f64>();
            -0.5 * (nis + log_det + M as f64 * (2.0 * std::f64::consts::PI).ln())
        }
        None => f64::NEG_INFINITY,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_split_shares_the_interval_exactly_and_the_increments_in_proportion() {
        // 5 ms ending at t = 1 s + 5 ms, split 1 ms + 1 ns after its start: the durations are
        // 1 000 001 ns and 3 999 999 ns, adding up to the whole to the nanosecond.
        let end = Timestamp::from_nanos(1_005_000_000);
        let inc = Increment::from_rates(
            end,
            Duration::from_nanos(5_000_000),
            [0.2, -0.4, 1.0],
            [1.0, 2.0, -9.8],
        );
        let at = Timestamp::from_nanos(1_001_000_001);
        let (before, after) = split(&inc, at);
        assert_eq!((before.time, after.time), (at, end));
        assert_eq!(before.dt, Duration::from_nanos(1_000_001));
        assert_eq!(after.dt, Duration::from_nanos(3_999_999));
        assert_eq!(before.dt + after.dt, inc.dt);
        assert_eq!(before.start(), inc.start());
        let share = 1_000_001.0 / 5_000_000.0;
        for k in 0..3 {
            let whole = inc.delta_angle.to_array()[k];
            assert!((before.delta_angle.to_array()[k] - share * whole).abs() < 1e-15);
            assert!((after.delta_angle.to_array()[k] - (1.0 - share) * whole).abs() < 1e-15);
            let whole = inc.delta_velocity.to_array()[k];
            assert!((before.delta_velocity.to_array()[k] - share * whole).abs() < 1e-15);
        }
    }
}
