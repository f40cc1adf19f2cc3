//! Exact time: integer nanoseconds.
//!
//! Timestamps are stored as `i64` nanoseconds from an arbitrary epoch chosen by the data source
//! (±292 years of range). Arithmetic on sampling intervals is done in integer nanoseconds, so a
//! 3-hour 200 Hz log accumulates no rounding in its time axis; conversion to `f64` seconds happens
//! only where a formula needs it.
//!
//! ## Mix-ups that do not build
//!
//! A [`Timestamp`] is a point in time and a [`Duration`] a span; neither is a bare number.
//! Each example that must not compile is followed by the same code written correctly.
//!
//! The span between two epochs needs two epochs, not an epoch and a span:
//!
//! ```compile_fail
//! use thermonav::time::{Duration, Timestamp};
//! let fix = Timestamp::from_nanos(12_000_000_000);
//! let interval = Duration::from_nanos(5_000_000);
//! let age = fix.since(interval); // a span where an epoch is expected
//! ```
//!
//! ```
//! use thermonav::time::{Duration, Timestamp};
//! let fix = Timestamp::from_nanos(12_000_000_000);
//! let sample = Timestamp::from_nanos(11_995_000_000);
//! let age: Duration = fix.since(sample);
//! assert_eq!(age, Duration::from_nanos(5_000_000));
//! ```
//!
//! An epoch compares with epochs only, never with a span:
//!
//! ```compile_fail
//! use thermonav::time::{Duration, Timestamp};
//! let t = Timestamp::from_nanos(3_000_000_000);
//! let limit = Duration::from_nanos(2_000_000_000);
//! let late = t > limit; // is 3 s after the epoch later than "2 s long"?
//! ```
//!
//! ```
//! use thermonav::time::{Duration, Timestamp};
//! let (start, t) = (Timestamp::from_nanos(0), Timestamp::from_nanos(3_000_000_000));
//! let limit = Duration::from_nanos(2_000_000_000);
//! assert!(t.since(start) > limit && t > start);
//! ```
//!
//! Seconds as `f64` become time once, through a checked conversion, wherever they enter:
//!
//! ```compile_fail
//! use thermonav::nav::outage::Outage;
//! let outage = Outage { start: 210.0, end: 270.0 }; // f64 seconds where epochs are expected
//! ```
//!
//! ```
//! use thermonav::nav::outage::Outage;
//! use thermonav::time::Timestamp;
//! let outage = Outage {
//!     start: Timestamp::from_seconds(210.0)?,
//!     end: Timestamp::from_seconds(270.0)?,
//! };
//! assert_eq!(outage.duration_s(), 60.0);
//! # Ok::<(), thermonav::time::TimeRangeError>(())
//! ```

use serde::{Deserialize, Serialize};

/// Nanoseconds in one second.
pub const NANOS_PER_SECOND: i64 = 1_000_000_000;

/// A point in time, in integer nanoseconds from the data source's epoch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct Timestamp {
    nanos: i64,
}

/// A signed span of time, in integer nanoseconds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct Duration {
    nanos: i64,
}

/// Why a number of seconds cannot become a [`Timestamp`] or [`Duration`].
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("{seconds} s is not a finite time within ±9.2e9 s")]
pub struct TimeRangeError {
    /// The offending value, in seconds.
    pub seconds: f64,
}

fn seconds_to_nanos(seconds: f64) -> Result<i64, TimeRangeError> {
    let nanos = (seconds * NANOS_PER_SECOND as f64).round();
    // i64::MAX as f64 rounds up to 2^63, so the strict comparison keeps the cast in range.
    if nanos.is_finite() && nanos.abs() < i64::MAX as f64 {
        Ok(nanos as i64)
    } else {
        Err(TimeRangeError { seconds })
    }
}

impl Timestamp {
    /// The timestamp `nanos` nanoseconds after the epoch.
    pub const fn from_nanos(nanos: i64) -> Self {
        Self { nanos }
    }

    /// The timestamp nearest to `seconds` after the epoch (rounded to the nanosecond).
    ///
    /// # Errors
    /// [`TimeRangeError`] when `seconds` is NaN, infinite or beyond ±9.2e9 s.
    pub fn from_seconds(seconds: f64) -> Result<Self, TimeRangeError> {
        seconds_to_nanos(seconds).map(Self::from_nanos)
    }

    /// Nanoseconds since the epoch.
    pub const fn as_nanos(self) -> i64 {
        self.nanos
    }

    /// Seconds since the epoch, as `f64` (exact to the nanosecond below ~104 days).
    pub fn as_seconds(self) -> f64 {
        self.nanos as f64 / NANOS_PER_SECOND as f64
    }

    /// The span from `earlier` to `self` (negative when `earlier` is later).
    pub const fn since(self, earlier: Timestamp) -> Duration {
        Duration::from_nanos(self.nanos.saturating_sub(earlier.nanos))
    }
}

impl Duration {
    /// The span of `nanos` nanoseconds.
    pub const fn from_nanos(nanos: i64) -> Self {
        Self { nanos }
    }

    /// The span nearest to `seconds` (rounded to the nanosecond).
    ///
    /// # Errors
    /// [`TimeRangeError`] when `seconds` is NaN, infinite or beyond ±9.2e9 s.
    pub fn from_seconds(seconds: f64) -> Result<Self, TimeRangeError> {
        seconds_to_nanos(seconds).map(Self::from_nanos)
    }

    /// Length in nanoseconds.
    pub const fn as_nanos(self) -> i64 {
        self.nanos
    }

    /// Length in seconds, as `f64`.
    pub fn as_seconds(self) -> f64 {
        self.nanos as f64 / NANOS_PER_SECOND as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seconds_round_to_the_nearest_nanosecond() {
        // 0.005 s is not exact in binary; rounding must still give 5 ms exactly.
        assert_eq!(Duration::from_seconds(0.005).unwrap().as_nanos(), 5_000_000);
        assert_eq!(
            Timestamp::from_seconds(-1.5).unwrap().as_nanos(),
            -1_500_000_000
        );
    }

    #[test]
    fn non_finite_and_huge_seconds_are_rejected() {
        assert!(Timestamp::from_seconds(f64::NAN).is_err());
        assert!(Timestamp::from_seconds(f64::INFINITY).is_err());
        assert!(Timestamp::from_seconds(1e10).is_err());
    }

    #[test]
    fn span_between_timestamps_is_exact() {
        let a = Timestamp::from_nanos(1_000_000_005);
        let b = Timestamp::from_nanos(1_005_000_005);
        assert_eq!(b.since(a).as_nanos(), 5_000_000);
        assert_eq!(a.since(b).as_nanos(), -5_000_000);
    }
}
