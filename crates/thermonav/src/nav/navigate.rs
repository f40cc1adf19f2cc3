//! The entry points of a navigation run over increments and fixes already made: the settings
//! and the data checked, then one error-state filter ([`super::engine`]) or, when the settings
//! split the z-gyro bias prior, a Gaussian sum of them ([`super::gaussian_sum`]). On a whole
//! record ([`run`], [`run_scheduled`]) or on a stream of increments in bounded memory
//! ([`run_streaming`]).

use super::engine::{
    EngineSettings, FilterKind, Filtering, NavError, Run, StreamError, StreamTail,
    check_fix_latitudes, check_imu_gaps, check_inputs, check_settings,
};
use super::error_state::Estimate;
use super::gaussian_sum::run_gaussian_sum;
use super::schedule::ModelSchedule;
use super::sensor_model::ImuStochasticModel;
use super::smoother::MAX_SMOOTHED_STEPS;
use super::solution::{Solution, SolutionSink};
use crate::gnss::GnssFix;
use crate::ins::error_model::SystemMatrix;
use crate::ins::state::Increment;
use crate::time::Timestamp;
use std::convert::Infallible;

/// Runs the filter from `initial` (with covariance `p0`) over the increments after its time,
/// updating with the fixes after its time. `progress` is called with the number of IMU
/// samples processed, every few thousand.
///
/// # Errors
/// [`NavError`] for bad settings, no data after the start, the data [`check_inputs`]
/// refuses, or a divergence.
pub fn run(
    increments: &[Increment],
    gnss: &[GnssFix],
    initial: Estimate,
    p0: SystemMatrix,
    model: &ImuStochasticModel,
    settings: &EngineSettings,
    progress: &mut dyn FnMut(usize),
) -> Result<Solution, NavError> {
    let schedule = ModelSchedule::Fixed(model);
    run_scheduled(increments, gnss, initial, p0, schedule, settings, progress)
}

/// [`run`] with the model of every covariance step taken from `schedule` (see
/// [`super::schedule`]): the model at the sensor temperature at the step's start.
///
/// # Errors
/// As [`run`].
pub fn run_scheduled(
    increments: &[Increment],
    gnss: &[GnssFix],
    initial: Estimate,
    p0: SystemMatrix,
    schedule: ModelSchedule,
    settings: &EngineSettings,
    progress: &mut dyn FnMut(usize),
) -> Result<Solution, NavError> {
    check_settings(settings)?;
    let start = initial.nav.time;
    let first = increments.partition_point(|i| i.time <= start);
    if first == increments.len() {
        return Err(NavError::NoImu(start.as_seconds()));
    }
    check_inputs(&increments[first..], gnss, settings)?;
    if settings.smooth {
        check_smoothable(&increments[first..], gnss, settings)?;
    }
    let mut solution = Solution {
        epochs: Vec::new(),
        innovations: Vec::new(),
        imu_samples: 0,
        smoothed: Vec::new(),
    };
    let filtering = Filtering {
        initial,
        p0,
        schedule,
        settings,
    };
    let records = increments[first..].iter().map(|i| Ok::<_, Infallible>(*i));
    let tail = run_streaming(filtering, records, gnss, None, &mut solution, progress)
        .map_err(StreamError::into_nav)?;
    solution.imu_samples = tail.imu_samples;
    solution.smoothed = tail.smoothed;
    Ok(solution)
}

/// [`run_scheduled`] over a stream of increments, in memory bounded whatever the record's
/// length: each solution epoch and innovation goes to `sink` as it is made (the epoch at a
/// fix's time after that fix's updates), nothing is kept. Increments at or before the start are
/// skipped; the checks [`check_inputs`] makes on a whole record are made increment by
/// increment (a gap is refused when it arrives). `last_time`, the time of the record's last
/// sample, lets a smoothed run be checked before it starts (as [`run_scheduled`] does); `None`
/// skips that check.
///
/// # Errors
/// [`StreamError::Input`] for the first increment the stream fails on; [`StreamError::Nav`] as
/// [`run_scheduled`].
pub fn run_streaming<E>(
    filtering: Filtering,
    increments: impl IntoIterator<Item = Result<Increment, E>>,
    gnss: &[GnssFix],
    last_time: Option<Timestamp>,
    sink: &mut dyn SolutionSink,
    progress: &mut dyn FnMut(usize),
) -> Result<StreamTail, StreamError<E>> {
    let settings = filtering.settings;
    if let Some(hypotheses) = &settings.bias_hypotheses {
        return run_gaussian_sum(filtering, hypotheses, increments, gnss, sink, progress);
    }
    check_settings(settings)?;
    check_fix_latitudes(gnss)?;
    let start = filtering.initial.nav.time;
    let carried = filtering
        .schedule
        .keeping_turn_on_bias(&filtering.p0, start);
    let filtering = Filtering {
        schedule: carried.schedule(),
        ..filtering
    };
    let mut run = Run::new(filtering, sink)?;
    let mut fixes = gnss.iter().filter(|f| f.time > start).peekable();
    let mut n = 0;
    for inc in increments {
        let inc = inc.map_err(StreamError::Input)?;
        if inc.time <= start {
            continue;
        }
        if let (0, Some(end), true) = (n, last_time, settings.smooth) {
            check_smoothable_span(end.since(inc.start()).as_seconds(), gnss, settings)?;
        }
        check_imu_gaps(std::slice::from_ref(&inc), settings.max_imu_gap_s)?;
        run.feed(inc, start, &mut fixes)?;
        if n % 4096 == 0 {
            progress(n);
        }
        n += 1;
    }
    if n == 0 {
        return Err(NavError::NoImu(start.as_seconds()).into());
    }
    let smoothed = run.finish()?;
    progress(n);
    Ok(StreamTail {
        imu_samples: n,
        smoothed,
    })
}

/// Smoothing needs the EKF's covariance and a history within [`MAX_SMOOTHED_STEPS`]: the
/// steps are the record's span over the covariance interval plus one per fix (an update ends
/// a step early).
fn check_smoothable(
    increments: &[Increment],
    gnss: &[GnssFix],
    settings: &EngineSettings,
) -> Result<(), NavError> {
    let span_s = match (increments.first(), increments.last()) {
        (Some(a), Some(b)) => (b.time - a.start()).as_seconds(),
        _ => 0.0,
    };
    check_smoothable_span(span_s, gnss, settings)
}

/// [`check_smoothable`] of a record spanning `span_s` from the start of its first interval
/// after the run's start.
fn check_smoothable_span(
    span_s: f64,
    gnss: &[GnssFix],
    settings: &EngineSettings,
) -> Result<(), NavError> {
    if settings.filter != FilterKind::Ekf {
        return Err(NavError::Smoothing(format!(
            "the RTS smoother runs on the EKF's covariance, not the {}'s",
            settings.filter.name()
        )));
    }
    let steps = (span_s / settings.covariance_interval_s).ceil() as usize + gnss.len();
    match steps <= MAX_SMOOTHED_STEPS {
        true => Ok(()),
        false => Err(NavError::Smoothing(format!(
            "about {steps} covariance steps, more than the {MAX_SMOOTHED_STEPS} whose history is kept (11 KB each): lower --covariance-rate-hz or smooth a shorter run"
        ))),
    }
}
