//! GNSS outages: half-open windows [start, end) in which GNSS updates are withheld and the
//! solution is INS-only.

use crate::time::{NANOS_PER_SECOND, Timestamp};
use serde::Serialize;

/// One outage window [start, end).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Outage {
    /// First instant without GNSS.
    pub start: Timestamp,
    /// First instant with GNSS again.
    pub end: Timestamp,
}

impl Outage {
    /// Length, s.
    pub fn duration_s(&self) -> f64 {
        self.end.since(self.start).as_seconds()
    }

    /// True when `t` falls inside the window.
    pub fn contains(&self, t: Timestamp) -> bool {
        self.start <= t && t < self.end
    }
}

/// Why an outage list is unusable.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OutageError {
    /// Zero or negative length.
    #[error("outage starting at {start_s} s has a non-positive duration")]
    Empty {
        /// Start, s.
        start_s: f64,
    },
    /// Two windows overlap.
    #[error(
        "outages overlap: the one starting at {first_start_s} s ends after {second_start_s} s, where the next begins"
    )]
    Overlap {
        /// Earlier window start, s.
        first_start_s: f64,
        /// Later window start, s.
        second_start_s: f64,
    },
    /// A window lies outside the data.
    #[error("outage {start_s}-{end_s} s is not inside the data ({data_start_s}-{data_end_s} s)")]
    OutsideData {
        /// Window start, s.
        start_s: f64,
        /// Window end, s.
        end_s: f64,
        /// First data time, s.
        data_start_s: f64,
        /// Last data time, s.
        data_end_s: f64,
    },
    /// A time that cannot be represented.
    #[error("outage time {0} s is not a finite number of seconds")]
    Time(f64),
}

/// A sorted list of non-overlapping outages.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize)]
pub struct Outages {
    windows: Vec<Outage>,
}

fn timestamp(seconds: f64) -> Result<Timestamp, OutageError> {
    Timestamp::from_seconds(seconds).map_err(|_| OutageError::Time(seconds))
}

impl Outages {
    /// No outage.
    pub fn none() -> Self {
        Self::default()
    }

    /// Outages from (start, duration) pairs in seconds, in any order.
    ///
    /// # Errors
    /// [`OutageError`] for a non-positive duration or overlapping windows.
    pub fn from_start_duration(pairs: &[(f64, f64)]) -> Result<Self, OutageError> {
        let mut windows = Vec::with_capacity(pairs.len());
        for &(start_s, duration_s) in pairs {
            if duration_s.is_nan() || duration_s <= 0.0 {
                return Err(OutageError::Empty { start_s });
            }
            windows.push(Outage {
                start: timestamp(start_s)?,
                end: timestamp(start_s + duration_s)?,
            });
        }
        windows.sort_by_key(|w| w.start);
        for pair in windows.windows(2) {
            if pair[0].end > pair[1].start {
                return Err(OutageError::Overlap {
                    first_start_s: pair[0].start.as_seconds(),
                    second_start_s: pair[1].start.as_seconds(),
                });
            }
        }
        Ok(Self { windows })
    }

    /// `count` outages of `duration_s` every `period_s` from `first_start_s`.
    ///
    /// # Errors
    /// As [`Outages::from_start_duration`].
    pub fn periodic(
        first_start_s: f64,
        duration_s: f64,
        period_s: f64,
        count: usize,
    ) -> Result<Self, OutageError> {
        let pairs: Vec<_> = (0..count)
            .map(|k| (first_start_s + k as f64 * period_s, duration_s))
            .collect();
        Self::from_start_duration(&pairs)
    }

    /// Checks that every window lies within [first, last] of the data.
    ///
    /// # Errors
    /// [`OutageError::OutsideData`] for the first window that does not.
    pub fn check_within(&self, first: Timestamp, last: Timestamp) -> Result<(), OutageError> {
        match self
            .windows
            .iter()
            .find(|w| w.start < first || w.end > last)
        {
            Some(w) => Err(OutageError::OutsideData {
                start_s: w.start.as_seconds(),
                end_s: w.end.as_seconds(),
                data_start_s: first.as_seconds(),
                data_end_s: last.as_seconds(),
            }),
            None => Ok(()),
        }
    }

    /// True when `t` is inside an outage.
    pub fn contains(&self, t: Timestamp) -> bool {
        let k = self.windows.partition_point(|w| w.start <= t);
        k > 0 && self.windows[k - 1].contains(t)
    }

    /// The windows, sorted.
    pub fn windows(&self) -> &[Outage] {
        &self.windows
    }
}

/// Whole seconds as a timestamp (for tests and generators).
pub fn seconds(s: i64) -> Timestamp {
    Timestamp::from_nanos(s * NANOS_PER_SECOND)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn membership_is_half_open_and_overlaps_are_refused() {
        let o = Outages::periodic(100.0, 30.0, 60.0, 3).unwrap();
        assert!(!o.contains(seconds(99)) && o.contains(seconds(100)) && o.contains(seconds(129)));
        assert!(!o.contains(seconds(130)) && o.contains(seconds(160)) && !o.contains(seconds(250)));
        assert!(matches!(
            Outages::from_start_duration(&[(10.0, 20.0), (25.0, 5.0)]),
            Err(OutageError::Overlap { .. })
        ));
        assert!(matches!(
            Outages::from_start_duration(&[(10.0, 0.0)]),
            Err(OutageError::Empty { .. })
        ));
        assert!(o.check_within(seconds(0), seconds(400)).is_ok());
        assert!(o.check_within(seconds(0), seconds(200)).is_err());
    }
}
