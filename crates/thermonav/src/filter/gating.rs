//! Chi-square innovation gating: a measurement whose normalised innovation squared
//! NIS = νᵀ S⁻¹ ν exceeds the χ²(m) quantile at the chosen probability is rejected.

use statrs::distribution::{ChiSquared, ContinuousCDF};

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
}
