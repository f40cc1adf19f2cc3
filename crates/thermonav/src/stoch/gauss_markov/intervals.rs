//! Validated sampling intervals of a possibly irregular series.

use crate::time::{NANOS_PER_SECOND, Timestamp};

use super::GaussMarkovError;
use super::model::positive;

/// The intervals `dt_k = t_k - t_{k-1}` (s, all finite and > 0) between consecutive samples of
/// a series of `dt.len() + 1` samples. Built once from times; the Gauss-Markov likelihood and
/// simulator use each step's own `dt_k`.
#[derive(Debug, Clone, PartialEq)]
pub struct SampleIntervals {
    dt_s: Vec<f64>,
    span_s: f64,
}

impl SampleIntervals {
    /// Intervals between times given in seconds.
    ///
    /// Differences of large absolute `f64` times lose precision (a Unix time of 1.7e9 s has a
    /// resolution of 2.4e-7 s): give times relative to the start, or use
    /// [`SampleIntervals::from_timestamps`].
    ///
    /// # Errors
    /// [`GaussMarkovError::TooShort`] for no time, [`GaussMarkovError::NonFinite`] for a NaN or
    /// infinite time, [`GaussMarkovError::NonIncreasingTime`] when a time is not after its
    /// predecessor, [`GaussMarkovError::OutOfRange`] when an interval or the span overflows.
    pub fn from_times_s(times_s: &[f64]) -> Result<Self, GaussMarkovError> {
        require_samples(times_s.len(), 1)?;
        require_finite("times_s", times_s)?;
        let dt_s = times_s
            .windows(2)
            .enumerate()
            .map(|(k, pair)| interval_s(k + 1, pair[0], pair[1]))
            .collect::<Result<Vec<_>, _>>()?;
        Self::from_intervals(dt_s)
    }

    /// Intervals between exact timestamps (differences taken in integer nanoseconds).
    ///
    /// # Errors
    /// [`GaussMarkovError::TooShort`] for no timestamp, [`GaussMarkovError::NonIncreasingTime`]
    /// when a timestamp is not after its predecessor.
    pub fn from_timestamps(times: &[Timestamp]) -> Result<Self, GaussMarkovError> {
        require_samples(times.len(), 1)?;
        let dt_s = times
            .windows(2)
            .enumerate()
            .map(|(k, pair)| timestamp_interval_s(k + 1, pair[0], pair[1]))
            .collect::<Result<Vec<_>, _>>()?;
        Self::from_intervals(dt_s)
    }

    /// `sample_count` samples `dt_s` seconds apart.
    ///
    /// # Errors
    /// [`GaussMarkovError::TooShort`] for zero samples, [`GaussMarkovError::NotPositive`] when
    /// `dt_s` is not finite and > 0, [`GaussMarkovError::OutOfRange`] when the span overflows.
    pub fn regular(sample_count: usize, dt_s: f64) -> Result<Self, GaussMarkovError> {
        require_samples(sample_count, 1)?;
        positive("sampling interval (s)", dt_s)?;
        Self::from_intervals(vec![dt_s; sample_count - 1])
    }

    fn from_intervals(dt_s: Vec<f64>) -> Result<Self, GaussMarkovError> {
        let span_s = dt_s.iter().sum::<f64>();
        if !span_s.is_finite() {
            return Err(GaussMarkovError::OutOfRange {
                quantity: "time span (s)",
                value: span_s,
            });
        }
        Ok(Self { dt_s, span_s })
    }

    /// The intervals `dt_k`, s (one fewer than the samples).
    pub fn dt_s(&self) -> &[f64] {
        &self.dt_s
    }

    /// Number of samples (`dt_s().len() + 1`).
    pub fn sample_count(&self) -> usize {
        self.dt_s.len() + 1
    }

    /// Time from the first to the last sample, s (0 for a single sample).
    pub fn span_s(&self) -> f64 {
        self.span_s
    }

    /// The shortest interval, s (`None` for a single sample).
    pub fn min_dt_s(&self) -> Option<f64> {
        self.dt_s.iter().copied().reduce(f64::min)
    }

    /// The mean interval `span / (n - 1)`, s (`None` for a single sample).
    pub fn mean_dt_s(&self) -> Option<f64> {
        (!self.dt_s.is_empty()).then(|| self.span_s / self.dt_s.len() as f64)
    }
}

/// `Err(TooShort)` when fewer than `needed` samples are given.
pub(crate) fn require_samples(got: usize, needed: usize) -> Result<(), GaussMarkovError> {
    if got < needed {
        Err(GaussMarkovError::TooShort { needed, got })
    } else {
        Ok(())
    }
}

/// `Err(NonFinite)` at the first NaN or infinite entry of `values`.
pub(crate) fn require_finite(name: &'static str, values: &[f64]) -> Result<(), GaussMarkovError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(GaussMarkovError::NonFinite {
            name,
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}

/// `t_k - t_{k-1}` for finite times, checked to be > 0 and finite.
fn interval_s(index: usize, previous_s: f64, current_s: f64) -> Result<f64, GaussMarkovError> {
    let dt_s = current_s - previous_s;
    if dt_s <= 0.0 {
        return Err(GaussMarkovError::NonIncreasingTime {
            index,
            previous_s,
            current_s,
        });
    }
    if !dt_s.is_finite() {
        return Err(GaussMarkovError::OutOfRange {
            quantity: "sampling interval (s)",
            value: dt_s,
        });
    }
    Ok(dt_s)
}

fn timestamp_interval_s(
    index: usize,
    previous: Timestamp,
    current: Timestamp,
) -> Result<f64, GaussMarkovError> {
    let dt_ns = current.since(previous).as_nanos();
    if dt_ns <= 0 {
        return Err(GaussMarkovError::NonIncreasingTime {
            index,
            previous_s: previous.as_seconds(),
            current_s: current.as_seconds(),
        });
    }
    Ok(dt_ns as f64 / NANOS_PER_SECOND as f64)
}
