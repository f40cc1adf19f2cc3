//! Sample times as real loggers make them: a nominal grid, timestamp jitter, dropped samples.

use crate::time::Timestamp;
use rand::{Rng, RngExt};
use rand_distr::{Distribution, StandardNormal};

/// Largest jitter, as a fraction of the nominal interval: draws are clipped to ±0.45 dt so
/// that consecutive timestamps always increase.
pub const MAX_JITTER_FRACTION: f64 = 0.45;

/// A sampling clock: nominal rate, Gaussian timestamp jitter, independent sample drops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleClock {
    rate_hz: f64,
    jitter_std_s: f64,
    drop_probability: f64,
}

/// Why a clock cannot be built.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum ClockError {
    /// Rate not finite and positive, or above 1 MHz.
    #[error("sample rate {rate_hz} Hz must be finite, positive and at most 1 MHz")]
    Rate {
        /// The value given.
        rate_hz: f64,
    },
    /// Jitter not finite and non-negative.
    #[error("timestamp jitter {jitter_std_s} s must be finite and non-negative")]
    Jitter {
        /// The value given.
        jitter_std_s: f64,
    },
    /// Drop probability outside [0, 0.5].
    #[error("drop probability {probability} must lie in [0, 0.5]")]
    Drop {
        /// The value given.
        probability: f64,
    },
    /// Duration not finite and positive.
    #[error("duration {duration_s} s must be finite and positive")]
    Duration {
        /// The value given.
        duration_s: f64,
    },
}

impl SampleClock {
    /// A clock at `rate_hz` with timestamp jitter of standard deviation `jitter_std_s` and each
    /// sample dropped independently with `drop_probability`.
    ///
    /// # Errors
    /// [`ClockError`] naming the invalid value.
    pub fn new(rate_hz: f64, jitter_std_s: f64, drop_probability: f64) -> Result<Self, ClockError> {
        if !(rate_hz.is_finite() && rate_hz > 0.0 && rate_hz <= 1e6) {
            return Err(ClockError::Rate { rate_hz });
        }
        if !(jitter_std_s.is_finite() && jitter_std_s >= 0.0) {
            return Err(ClockError::Jitter { jitter_std_s });
        }
        if !(0.0..=0.5).contains(&drop_probability) {
            return Err(ClockError::Drop {
                probability: drop_probability,
            });
        }
        Ok(Self {
            rate_hz,
            jitter_std_s,
            drop_probability,
        })
    }

    /// Nominal rate, Hz.
    pub fn rate_hz(&self) -> f64 {
        self.rate_hz
    }

    /// Nominal interval, s.
    pub fn interval_s(&self) -> f64 {
        1.0 / self.rate_hz
    }

    /// Number of grid points in `duration_s` (the grid starts at 0).
    pub fn grid_len(&self, duration_s: f64) -> Result<usize, ClockError> {
        if !(duration_s.is_finite() && duration_s > 0.0) {
            return Err(ClockError::Duration { duration_s });
        }
        Ok((duration_s * self.rate_hz).floor() as usize + 1)
    }

    /// Timestamps over `duration_s`: grid point k at round(k / rate) ns, plus clipped Gaussian
    /// jitter, minus the dropped samples. The first sample is never dropped.
    ///
    /// # Errors
    /// [`ClockError::Duration`] for a duration that is not finite and positive.
    pub fn timestamps(
        &self,
        duration_s: f64,
        rng: &mut impl Rng,
    ) -> Result<Vec<Timestamp>, ClockError> {
        let n = self.grid_len(duration_s)?;
        let limit_s = MAX_JITTER_FRACTION * self.interval_s();
        let mut times = Vec::with_capacity(n);
        for k in 0..n {
            let jitter_s = self.draw_jitter_s(rng, limit_s);
            let dropped =
                k > 0 && self.drop_probability > 0.0 && rng.random_bool(self.drop_probability);
            if !dropped {
                times.push(Timestamp::from_nanos(
                    self.grid_nanos(k) + (jitter_s * 1e9).round() as i64,
                ));
            }
        }
        Ok(times)
    }

    fn grid_nanos(&self, k: usize) -> i64 {
        (k as f64 * 1e9 / self.rate_hz).round() as i64
    }

    fn draw_jitter_s(&self, rng: &mut impl Rng, limit_s: f64) -> f64 {
        if self.jitter_std_s == 0.0 {
            return 0.0;
        }
        let z: f64 = StandardNormal.sample(rng);
        (z * self.jitter_std_s).clamp(-limit_s, limit_s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::named_rng;
    use crate::signal::timestamps::check_timestamps;

    #[test]
    fn a_clean_clock_lies_on_the_exact_grid() {
        let clock = SampleClock::new(200.0, 0.0, 0.0).unwrap();
        let times = clock.timestamps(10.0, &mut named_rng(1, "clock")).unwrap();
        assert_eq!(times.len(), 2001);
        assert!(
            times
                .iter()
                .enumerate()
                .all(|(k, t)| t.as_nanos() == k as i64 * 5_000_000)
        );
    }

    #[test]
    fn jitter_has_the_requested_spread_and_keeps_order() {
        // Independent jitter of std s on each timestamp gives intervals of std √2 s.
        // With 20 000 intervals the sample std is within ~1 % (relative se 1/√(2n) = 0.5 %):
        // 3 % is six standard errors.
        let clock = SampleClock::new(200.0, 50e-6, 0.0).unwrap();
        let times = clock.timestamps(100.0, &mut named_rng(2, "clock")).unwrap();
        let report = check_timestamps(&times);
        let std_s = report.intervals.unwrap().std_s;
        let expected = 2f64.sqrt() * 50e-6;
        assert!((std_s / expected - 1.0).abs() < 0.03, "std {std_s}");
        assert_eq!((report.reversal_count, report.duplicate_count), (0, 0));
    }

    #[test]
    fn drops_appear_as_gaps_at_the_requested_rate() {
        // 100 000 grid points with p = 0.01: about 1000 drops, binomial sd ≈ 31.5; ±150 is
        // nearly five sd. Isolated drops are gaps of two intervals.
        let clock = SampleClock::new(1000.0, 0.0, 0.01).unwrap();
        let times = clock.timestamps(100.0, &mut named_rng(3, "clock")).unwrap();
        let dropped = 100_001 - times.len();
        assert!((850..=1150).contains(&dropped), "dropped {dropped}");
        let report = check_timestamps(&times);
        assert!(report.gap_count > 800 && report.gap_count <= dropped);
    }

    #[test]
    fn invalid_settings_are_refused() {
        assert!(SampleClock::new(0.0, 0.0, 0.0).is_err());
        assert!(SampleClock::new(200.0, -1.0, 0.0).is_err());
        assert!(SampleClock::new(200.0, 0.0, 0.9).is_err());
        let clock = SampleClock::new(200.0, 0.0, 0.0).unwrap();
        assert!(clock.timestamps(f64::NAN, &mut named_rng(1, "c")).is_err());
    }
}
