//! Timestamp checks: nominal rate, jitter, gaps, duplicates and reversals.
//!
//! The paper's argument rests on unequal sampling intervals, so the first thing a user checks is
//! how unequal they are. All arithmetic is on integer nanoseconds; seconds appear only in the
//! report.
//!
//! Definitions (stated once, used by `thermonav inspect`):
//! - interval `dt_k = t_k - t_{k-1}` for k = 1..n;
//! - nominal interval: the median of the positive intervals (robust to gaps and jitter);
//! - jitter: mean, standard deviation (population, 1/n), minimum and maximum of the positive
//!   intervals;
//! - gap: a positive interval longer than 1.5 × the nominal interval;
//! - duplicate: `dt_k = 0`; reversal (non-monotonic): `dt_k < 0`.

use crate::time::{Duration, Timestamp};

/// How many gaps, duplicates and reversals are listed individually; the counts are always exact.
pub const MAX_LISTED_EVENTS: usize = 100;

/// A gap: an interval longer than 1.5 × the nominal interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gap {
    /// Index of the sample after the gap (0-based, into the series).
    pub index: usize,
    /// Time of the last sample before the gap.
    pub start: Timestamp,
    /// Length of the gap.
    pub length: Duration,
}

/// A sample whose time is not after its predecessor's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrderFault {
    /// Index of the offending sample (0-based).
    pub index: usize,
    /// Its time.
    pub time: Timestamp,
    /// The predecessor's time.
    pub previous: Timestamp,
}

/// Statistics of the positive sampling intervals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntervalStats {
    /// Median positive interval: the nominal sampling interval.
    pub median: Duration,
    /// Mean positive interval, s.
    pub mean_s: f64,
    /// Population standard deviation of the positive intervals, s.
    pub std_s: f64,
    /// Shortest positive interval.
    pub min: Duration,
    /// Longest positive interval.
    pub max: Duration,
}

impl IntervalStats {
    /// Nominal sample rate, Hz (inverse of the median interval).
    pub fn nominal_rate_hz(&self) -> f64 {
        1.0 / self.median.as_seconds()
    }
}

/// Everything `inspect` says about a time axis.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TimingReport {
    /// Number of samples.
    pub samples: usize,
    /// Last time minus first time (zero for fewer than two samples).
    pub duration: Option<Duration>,
    /// Interval statistics; `None` when there is no positive interval.
    pub intervals: Option<IntervalStats>,
    /// Number of gaps (exact) and the first [`MAX_LISTED_EVENTS`] of them.
    pub gap_count: usize,
    /// Listed gaps.
    pub gaps: Vec<Gap>,
    /// Number of duplicate timestamps (exact) and the first ones.
    pub duplicate_count: usize,
    /// Listed duplicates.
    pub duplicates: Vec<OrderFault>,
    /// Number of timestamps earlier than their predecessor (exact) and the first ones.
    pub reversal_count: usize,
    /// Listed reversals.
    pub reversals: Vec<OrderFault>,
}

/// Checks a time axis: nominal rate, jitter, gaps, duplicates and reversals.
pub fn check_timestamps(times: &[Timestamp]) -> TimingReport {
    let mut report = TimingReport {
        samples: times.len(),
        duration: duration_of(times),
        intervals: interval_stats(times),
        ..TimingReport::default()
    };
    let gap_threshold = report.intervals.map(|s| gap_threshold_nanos(s.median));
    for (k, pair) in times.windows(2).enumerate() {
        record_interval(&mut report, k + 1, pair[0], pair[1], gap_threshold);
    }
    report
}

fn duration_of(times: &[Timestamp]) -> Option<Duration> {
    match (times.first(), times.last()) {
        (Some(first), Some(last)) => Some(last.since(*first)),
        _ => None,
    }
}

/// 1.5 × the median, in nanoseconds, exact in integers: dt > 1.5 m  <=>  2 dt > 3 m.
fn gap_threshold_nanos(median: Duration) -> i128 {
    3 * i128::from(median.as_nanos())
}

fn record_interval(
    report: &mut TimingReport,
    index: usize,
    previous: Timestamp,
    time: Timestamp,
    gap_threshold: Option<i128>,
) {
    let dt = time.since(previous);
    let fault = OrderFault {
        index,
        time,
        previous,
    };
    if dt.as_nanos() == 0 {
        report.duplicate_count += 1;
        push_listed(&mut report.duplicates, fault);
    } else if dt.as_nanos() < 0 {
        report.reversal_count += 1;
        push_listed(&mut report.reversals, fault);
    } else if gap_threshold.is_some_and(|limit| 2 * i128::from(dt.as_nanos()) > limit) {
        report.gap_count += 1;
        let gap = Gap {
            index,
            start: previous,
            length: dt,
        };
        push_listed(&mut report.gaps, gap);
    }
}

fn push_listed<T>(list: &mut Vec<T>, item: T) {
    if list.len() < MAX_LISTED_EVENTS {
        list.push(item);
    }
}

/// Positive intervals of a time axis, in nanoseconds.
pub fn positive_intervals_nanos(times: &[Timestamp]) -> Vec<i64> {
    times
        .windows(2)
        .map(|pair| pair[1].since(pair[0]).as_nanos())
        .filter(|&dt| dt > 0)
        .collect()
}

/// Median, mean, standard deviation and extremes of the positive intervals.
pub fn interval_stats(times: &[Timestamp]) -> Option<IntervalStats> {
    let mut intervals = positive_intervals_nanos(times);
    if intervals.is_empty() {
        return None;
    }
    let (mean_s, std_s) = mean_and_std_seconds(&intervals);
    let min = *intervals.iter().min()?;
    let max = *intervals.iter().max()?;
    Some(IntervalStats {
        median: Duration::from_nanos(median_nanos(&mut intervals)),
        mean_s,
        std_s,
        min: Duration::from_nanos(min),
        max: Duration::from_nanos(max),
    })
}

/// Median of a non-empty slice (the lower middle element for even lengths, so the result is an
/// actual interval of the data). Reorders the slice.
fn median_nanos(values: &mut [i64]) -> i64 {
    let middle = (values.len() - 1) / 2;
    *values.select_nth_unstable(middle).1
}

/// Mean and population standard deviation in seconds, accumulated around the first value so the
/// sum of squares does not cancel catastrophically.
fn mean_and_std_seconds(values: &[i64]) -> (f64, f64) {
    let pivot = values[0];
    let n = values.len() as f64;
    let (sum, sum_sq) = values.iter().fold((0.0_f64, 0.0_f64), |(s, q), &v| {
        let d = (v - pivot) as f64;
        (s + d, q + d * d)
    });
    let mean_offset = sum / n;
    let variance = (sum_sq / n - mean_offset * mean_offset).max(0.0);
    let to_s = 1e-9;
    ((pivot as f64 + mean_offset) * to_s, variance.sqrt() * to_s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(nanos: &[i64]) -> Vec<Timestamp> {
        nanos.iter().copied().map(Timestamp::from_nanos).collect()
    }

    #[test]
    fn regular_axis_has_exact_rate_and_no_faults() {
        let times: Vec<_> = (0..1000)
            .map(|k| Timestamp::from_nanos(k * 5_000_000))
            .collect();
        let report = check_timestamps(&times);
        let stats = report.intervals.unwrap();
        assert_eq!(stats.median.as_nanos(), 5_000_000);
        assert_eq!(stats.nominal_rate_hz(), 200.0);
        assert_eq!(stats.std_s, 0.0);
        assert_eq!(report.duration.unwrap().as_nanos(), 999 * 5_000_000);
        assert_eq!(
            (
                report.gap_count,
                report.duplicate_count,
                report.reversal_count
            ),
            (0, 0, 0)
        );
    }

    #[test]
    fn gaps_duplicates_and_reversals_are_found_where_they_are() {
        // intervals: 10, 10, 16 (gap: > 15), 0 (duplicate), 10, -5 (reversal), 15 (not a gap)
        let times = axis(&[0, 10, 20, 36, 36, 46, 41, 56]);
        let report = check_timestamps(&times);
        assert_eq!(report.gap_count, 1);
        assert_eq!(report.gaps[0].index, 3);
        assert_eq!(report.gaps[0].length.as_nanos(), 16);
        assert_eq!(report.duplicate_count, 1);
        assert_eq!(report.duplicates[0].index, 4);
        assert_eq!(report.reversal_count, 1);
        assert_eq!(report.reversals[0].index, 6);
        assert_eq!(report.reversals[0].previous.as_nanos(), 46);
    }

    #[test]
    fn jitter_statistics_match_a_hand_computation() {
        // positive intervals 4, 6, 4, 6 ns: mean 5, population std 1, median (lower) 4.
        let times = axis(&[0, 4, 10, 14, 20]);
        let stats = interval_stats(&times).unwrap();
        assert!((stats.mean_s - 5e-9).abs() < 1e-24);
        assert!((stats.std_s - 1e-9).abs() < 1e-22);
        assert_eq!(stats.median.as_nanos(), 4);
        assert_eq!((stats.min.as_nanos(), stats.max.as_nanos()), (4, 6));
    }

    #[test]
    fn too_few_samples_give_no_interval_statistics() {
        assert!(check_timestamps(&[]).intervals.is_none());
        assert!(check_timestamps(&axis(&[7])).intervals.is_none());
        assert_eq!(
            check_timestamps(&axis(&[7])).duration.unwrap().as_nanos(),
            0
        );
    }
}
