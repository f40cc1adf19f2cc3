//! Exact time: integer nanoseconds.
//!
//! Timestamps are stored as `i64` nanoseconds from an arbitrary epoch chosen by the data source
//! (±292 years of range). Arithmetic on sampling intervals is done in integer nanoseconds, so a
//! 3-hour 200 Hz log accumulates no rounding in its time axis; conversion to `f64` seconds happens
//! only where a formula needs it.
//!
//! **Arithmetic.** `Timestamp − Timestamp = Duration`, `Timestamp ± Duration = Timestamp`,
//! `Duration ± Duration = Duration` and `−Duration` are exact integer operations. The
//! operators never panic: at the ends of the `i64` range (±292 years, which no data source
//! reaches) they saturate, like [`Timestamp::since`]. Where an input could come from a user
//! and saturating would hide a fault, use the `checked_*` forms, which return `None` on
//! overflow.
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
use std::iter::Sum;
use std::ops::{Add, AddAssign, Neg, Sub, SubAssign};

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

    /// The span from `earlier` to `self` (negative when `earlier` is later), saturated at the
    /// ends of the `i64` range; the same as `self - earlier`.
    pub const fn since(self, earlier: Timestamp) -> Duration {
        Duration::from_nanos(self.nanos.saturating_sub(earlier.nanos))
    }

    /// The span from `earlier` to `self`, or `None` when it does not fit in `i64`
    /// nanoseconds.
    pub const fn checked_since(self, earlier: Timestamp) -> Option<Duration> {
        match self.nanos.checked_sub(earlier.nanos) {
            Some(nanos) => Some(Duration::from_nanos(nanos)),
            None => None,
        }
    }

    /// `self + span`, or `None` beyond the `i64` range.
    pub const fn checked_add(self, span: Duration) -> Option<Timestamp> {
        match self.nanos.checked_add(span.nanos) {
            Some(nanos) => Some(Timestamp::from_nanos(nanos)),
            None => None,
        }
    }

    /// `self − span`, or `None` beyond the `i64` range.
    pub const fn checked_sub(self, span: Duration) -> Option<Timestamp> {
        match self.nanos.checked_sub(span.nanos) {
            Some(nanos) => Some(Timestamp::from_nanos(nanos)),
            None => None,
        }
    }
}

impl Duration {
    /// The empty span.
    pub const ZERO: Duration = Duration::from_nanos(0);

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

    /// Whether the span is longer than zero.
    pub const fn is_positive(self) -> bool {
        self.nanos > 0
    }

    /// Whether the span is shorter than zero.
    pub const fn is_negative(self) -> bool {
        self.nanos < 0
    }

    /// `self + other`, or `None` beyond the `i64` range.
    pub const fn checked_add(self, other: Duration) -> Option<Duration> {
        match self.nanos.checked_add(other.nanos) {
            Some(nanos) => Some(Duration::from_nanos(nanos)),
            None => None,
        }
    }

    /// `self − other`, or `None` beyond the `i64` range.
    pub const fn checked_sub(self, other: Duration) -> Option<Duration> {
        match self.nanos.checked_sub(other.nanos) {
            Some(nanos) => Some(Duration::from_nanos(nanos)),
            None => None,
        }
    }

    /// `−self`, or `None` for the most negative span (whose negation does not fit).
    pub const fn checked_neg(self) -> Option<Duration> {
        match self.nanos.checked_neg() {
            Some(nanos) => Some(Duration::from_nanos(nanos)),
            None => None,
        }
    }

    /// `factor` times the span, or `None` beyond the `i64` range.
    pub const fn checked_mul(self, factor: i64) -> Option<Duration> {
        match self.nanos.checked_mul(factor) {
            Some(nanos) => Some(Duration::from_nanos(nanos)),
            None => None,
        }
    }
}

impl Sub for Timestamp {
    type Output = Duration;

    /// The span from `earlier` to `self`; saturates at the ends of the `i64` range.
    fn sub(self, earlier: Timestamp) -> Duration {
        self.since(earlier)
    }
}

impl Add<Duration> for Timestamp {
    type Output = Timestamp;

    /// Saturates at the ends of the `i64` range ([`Timestamp::checked_add`] reports it).
    fn add(self, span: Duration) -> Timestamp {
        Timestamp::from_nanos(self.nanos.saturating_add(span.nanos))
    }
}

impl Sub<Duration> for Timestamp {
    type Output = Timestamp;

    /// Saturates at the ends of the `i64` range ([`Timestamp::checked_sub`] reports it).
    fn sub(self, span: Duration) -> Timestamp {
        Timestamp::from_nanos(self.nanos.saturating_sub(span.nanos))
    }
}

impl AddAssign<Duration> for Timestamp {
    fn add_assign(&mut self, span: Duration) {
        *self = *self + span;
    }
}

impl SubAssign<Duration> for Timestamp {
    fn sub_assign(&mut self, span: Duration) {
        *self = *self - span;
    }
}

impl Add for Duration {
    type Output = Duration;

    /// Saturates at the ends of the `i64` range ([`Duration::checked_add`] reports it).
    fn add(self, other: Duration) -> Duration {
        Duration::from_nanos(self.nanos.saturating_add(other.nanos))
    }
}

impl Sub for Duration {
    type Output = Duration;

    /// Saturates at the ends of the `i64` range ([`Duration::checked_sub`] reports it).
    fn sub(self, other: Duration) -> Duration {
        Duration::from_nanos(self.nanos.saturating_sub(other.nanos))
    }
}

impl AddAssign for Duration {
    fn add_assign(&mut self, other: Duration) {
        *self = *self + other;
    }
}

impl SubAssign for Duration {
    fn sub_assign(&mut self, other: Duration) {
        *self = *self - other;
    }
}

impl Neg for Duration {
    type Output = Duration;

    /// The most negative span becomes the most positive one ([`Duration::checked_neg`]
    /// reports it).
    fn neg(self) -> Duration {
        Duration::from_nanos(self.nanos.saturating_neg())
    }
}

impl Sum for Duration {
    /// The exact total (saturated at the ends of the `i64` range).
    fn sum<I: Iterator<Item = Duration>>(spans: I) -> Duration {
        spans.fold(Duration::ZERO, |total, span| total + span)
    }
}

impl<'a> Sum<&'a Duration> for Duration {
    fn sum<I: Iterator<Item = &'a Duration>>(spans: I) -> Duration {
        spans.copied().sum()
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
        assert_eq!(b - a, b.since(a));
        assert_eq!(a.checked_since(b), Some(Duration::from_nanos(-5_000_000)));
    }

    #[test]
    fn timestamp_and_duration_arithmetic_is_exact_integer_arithmetic() {
        let t = Timestamp::from_nanos(1_000_000_005);
        let d = Duration::from_nanos(5_000_000);
        assert_eq!((t + d).as_nanos(), 1_005_000_005);
        assert_eq!((t - d).as_nanos(), 995_000_005);
        assert_eq!((t + d) - t, d);
        assert_eq!((t - d) + d, t);
        assert_eq!(t.checked_add(d), Some(t + d));
        assert_eq!(t.checked_sub(d), Some(t - d));
        assert_eq!((d + d).as_nanos(), 10_000_000);
        assert_eq!((d - d), Duration::ZERO);
        assert_eq!((-d).as_nanos(), -5_000_000);
        assert_eq!(d.checked_mul(3), Some(Duration::from_nanos(15_000_000)));
        let mut u = t;
        u += d;
        u -= d + d;
        assert_eq!(u, t - d);
        let mut e = d;
        e += d;
        e -= Duration::from_nanos(1);
        assert_eq!(e.as_nanos(), 9_999_999);
        assert!(d.is_positive() && !d.is_negative());
        assert!((-d).is_negative() && !Duration::ZERO.is_positive());
    }

    #[test]
    fn a_sum_of_intervals_is_exact() {
        // The 3-hour 200 Hz log of DESIGN.md: 2.16 million intervals of 5 ms are 10 800 s
        // exactly.
        let total: Duration = std::iter::repeat_n(Duration::from_nanos(5_000_000), 2_160_000).sum();
        assert_eq!(total.as_nanos(), 10_800 * NANOS_PER_SECOND);
        let spans = [Duration::from_nanos(3), Duration::from_nanos(-1)];
        assert_eq!(spans.iter().sum::<Duration>().as_nanos(), 2);
    }

    #[test]
    fn overflow_is_refused_by_the_checked_forms_and_saturated_by_the_operators() {
        let (max, min) = (
            Timestamp::from_nanos(i64::MAX),
            Timestamp::from_nanos(i64::MIN),
        );
        let one = Duration::from_nanos(1);
        assert_eq!(max.checked_add(one), None);
        assert_eq!(min.checked_sub(one), None);
        assert_eq!(max.checked_since(min), None);
        assert_eq!(
            min.checked_add(one),
            Some(Timestamp::from_nanos(i64::MIN + 1))
        );
        assert_eq!(max + one, max);
        assert_eq!(min - one, min);
        assert_eq!((max - min).as_nanos(), i64::MAX);
        assert_eq!((min - max).as_nanos(), i64::MIN);
        let (dmax, dmin) = (
            Duration::from_nanos(i64::MAX),
            Duration::from_nanos(i64::MIN),
        );
        assert_eq!(dmax.checked_add(one), None);
        assert_eq!(dmin.checked_sub(one), None);
        assert_eq!(dmin.checked_neg(), None);
        assert_eq!(dmax.checked_neg(), Some(Duration::from_nanos(-i64::MAX)));
        assert_eq!(dmax.checked_mul(2), None);
        assert_eq!(dmax + one, dmax);
        assert_eq!(dmin - one, dmin);
        assert_eq!(-dmin, dmax);
    }
}
