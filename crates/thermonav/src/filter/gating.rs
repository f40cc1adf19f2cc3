//! Chi-square innovation gating: a measurement whose normalised innovation squared
//! NIS = νᵀ S⁻¹ ν exceeds the χ²(m) quantile at the chosen probability is rejected.
//!
//! [`ScaledGate`] widens that quantile by the recent level of the NIS: a real filter's stated
//! measurement noise is often too small for a while (RTK fixes stated at 1 cm on a vibrating
//! car, lever-arm and timing residuals in turns), and a fixed gate then throws away good fixes
//! in runs. Outliers stand far above their neighbours' level and are still rejected.

use crate::statistics::median_of_sorted;
use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::collections::VecDeque;

/// The most a [`ScaledGate`] widens its quantile: beyond a hundred times its expected level,
/// the NIS says the filter has lost its measurements, and the recovery rule of the caller
/// (take an update after a run of rejections) is the remedy, not a wider gate.
pub const MAX_GATE_SCALE: f64 = 100.0;

/// A gate at probability `probability` for `dof`-dimensional measurements.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChiSquareGate {
    threshold: f64,
}

impl ChiSquareGate {
    /// The gate passing a fraction `probability` of consistent innovations (e.g. 0.999).
    /// Returns `None` for a probability outside (0, 1) or zero degrees of freedom.
    pub fn new(dof: usize, probability: f64) -> Option<Self> {
        if dof == 0 || !(probability > 0.0 && probability < 1.0) {
            return None;
        }
        let chi = ChiSquared::new(dof as f64).ok()?;
        Some(Self {
            threshold: chi.inverse_cdf(probability),
        })
    }

    /// The NIS threshold.
    pub fn threshold(&self) -> f64 {
        self.threshold
    }

    /// True when a measurement with this NIS passes.
    pub fn accepts(&self, nis: f64) -> bool {
        nis.is_finite() && nis <= self.threshold
    }
}

/// What a [`ScaledGate`] decided about one NIS.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GateVerdict {
    /// The factor the quantile was widened by (1 = the plain chi-square gate).
    pub scale: f64,
    /// True when NIS ≤ scale × quantile.
    pub passed: bool,
}

/// A chi-square gate whose quantile is multiplied by the recent NIS level: the median of
/// the last `window` NIS values of the same measurement (accepted or not) over the median of
/// χ²(m), at least 1 and at most [`MAX_GATE_SCALE`]. The median, not the mean, so that the
/// outliers being rejected do not widen the gate; a window of 0 keeps the plain gate.
#[derive(Debug, Clone, PartialEq)]
pub struct ScaledGate {
    gate: ChiSquareGate,
    chi_square_median: f64,
    recent: VecDeque<f64>,
    window: usize,
}

impl ScaledGate {
    /// The gate of [`ChiSquareGate::new`] scaled over the last `window` values; `None` as
    /// there.
    pub fn new(dof: usize, probability: f64, window: usize) -> Option<Self> {
        let gate = ChiSquareGate::new(dof, probability)?;
        let chi_square_median = ChiSquared::new(dof as f64).ok()?.inverse_cdf(0.5);
        Some(Self {
            gate,
            chi_square_median,
            recent: VecDeque::with_capacity(window),
            window,
        })
    }

    /// The factor the next NIS will be judged with.
    pub fn scale(&self) -> f64 {
        if self.recent.is_empty() {
            return 1.0;
        }
        let mut recent: Vec<f64> = self.recent.iter().copied().collect();
        recent.sort_by(f64::total_cmp);
        let level = median_of_sorted(&recent) / self.chi_square_median;
        level.clamp(1.0, MAX_GATE_SCALE)
    }

    /// Judges `nis` against the scaled quantile, then adds it to the window (a non-finite
    /// NIS fails and is not kept).
    pub fn judge(&mut self, nis: f64) -> GateVerdict {
        let scale = self.scale();
        let passed = nis.is_finite() && nis <= scale * self.gate.threshold();
        if nis.is_finite() && self.window > 0 {
            if self.recent.len() == self.window {
                self.recent.pop_front();
            }
            self.recent.push_back(nis);
        }
        GateVerdict { scale, passed }
    }

    /// The unscaled quantile.
    pub fn threshold(&self) -> f64 {
        self.gate.threshold()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Published χ² quantiles (Abramowitz & Stegun table 26.8): χ²₁(0.99) = 6.635,
    // χ²₂(0.999) = 13.816, χ²₃(0.95) = 7.815. Tables give 3 decimals.
    #[test]
    fn thresholds_match_the_tables() {
        assert!((ChiSquareGate::new(1, 0.99).unwrap().threshold() - 6.635).abs() < 1e-3);
        assert!((ChiSquareGate::new(2, 0.999).unwrap().threshold() - 13.816).abs() < 1e-3);
        assert!((ChiSquareGate::new(3, 0.95).unwrap().threshold() - 7.815).abs() < 1e-3);
        assert!(ChiSquareGate::new(0, 0.9).is_none() && ChiSquareGate::new(2, 1.0).is_none());
        assert!(!ChiSquareGate::new(1, 0.99).unwrap().accepts(f64::NAN));
    }

    // χ²₃ median 2.365974 (the 0.5 quantile; A&S 26.8 gives 2.366). A window of NIS values
    // all at 3 × that median widens the 0.9999 quantile (21.108) three times; a window at the
    // expected level leaves it alone; an outlier far above the level is refused whatever the
    // window, and does not move the median of the others.
    #[test]
    fn the_gate_widens_by_the_recent_median_level_only() {
        let mut gate = ScaledGate::new(3, 0.9999, 5).unwrap();
        assert!((gate.threshold() - 21.108).abs() < 1e-3);
        assert_eq!(gate.scale(), 1.0);
        let level = 2.365974;
        for _ in 0..5 {
            gate.judge(3.0 * level);
        }
        assert!((gate.scale() - 3.0).abs() < 1e-5);
        let verdict = gate.judge(1e4);
        assert!(!verdict.passed && (verdict.scale - 3.0).abs() < 1e-5);
        assert!((gate.scale() - 3.0).abs() < 1e-5, "one outlier in five");
        assert!(gate.judge(50.0).passed, "50 < 3 x 21.1");
        for _ in 0..5 {
            gate.judge(0.1);
        }
        assert_eq!(gate.scale(), 1.0, "never narrower than the plain gate");
        assert!(!gate.judge(21.2).passed && gate.judge(21.0).passed);
        let mut huge = ScaledGate::new(1, 0.9999, 3).unwrap();
        for _ in 0..3 {
            huge.judge(1e12);
        }
        assert_eq!(huge.scale(), MAX_GATE_SCALE);
        let mut plain = ScaledGate::new(3, 0.9999, 0).unwrap();
        plain.judge(1e3);
        assert_eq!(plain.scale(), 1.0);
        assert!(!plain.judge(f64::NAN).passed);
    }
}
