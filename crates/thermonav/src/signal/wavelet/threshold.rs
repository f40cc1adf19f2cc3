//! Shrinking wavelet coefficients: the thresholding functions and the threshold rules.
//!
//! Thresholding, as `pywt.threshold` (substitute 0): soft η_S(x) = sign(x) max(|x| − λ, 0);
//! hard η_H(x) = x when |x| ≥ λ, else 0 (PyWavelets keeps |x| = λ).
//!
//! Noise level: σ̂ = median(|d₁|) / 0.6745, the median absolute value of the finest detail
//! coefficients d₁ (about zero, not about their median: Donoho & Johnstone 1994, §4.2), 0.6745
//! being the normal quartile Φ⁻¹(0.75) to four digits as they give it.
//!
//! Rules (Donoho & Johnstone 1994, "Ideal spatial adaptation by wavelet shrinkage",
//! Biometrika 81(3); 1995, "Adapting to unknown smoothness via wavelet shrinkage", JASA
//! 90(432)), for a band of d coefficients x_i = d_i / σ̂ of a signal of n samples:
//! - universal (VisuShrink): λ = σ̂ √(2 ln n), the same at every level;
//! - SURE: λ = σ̂ t_S, t_S minimising Stein's unbiased risk estimate of soft thresholding
//!   SURE(t) = d − 2 #{i : |x_i| ≤ t} + Σ_i min(|x_i|, t)² over 0 ≤ t ≤ √(2 ln d) (the
//!   minimum lies at 0 or at one of the |x_i|); level by level;
//! - SURE hybrid (the 1995 paper's SureShrink): where the band looks sparse,
//!   s² = (Σ x_i² − d)/d ≤ γ = (log₂ d)^{3/2} / √d, the universal threshold of the band
//!   σ̂ √(2 ln d), else the SURE one.
//!
//! SURE is the risk of soft thresholding; with hard thresholding its threshold is used as is
//! (as MATLAB's `thselect` does).

/// How coefficients below the threshold are removed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Thresholding {
    /// sign(x) max(|x| − λ, 0): continuous, shrinks what it keeps.
    #[default]
    Soft,
    /// x where |x| ≥ λ, 0 elsewhere: keeps what it keeps unchanged.
    Hard,
}

/// How the threshold of a detail band is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum ThresholdRule {
    /// σ̂ √(2 ln n) (VisuShrink).
    #[default]
    Universal,
    /// Stein's unbiased risk estimate minimised per level (SureShrink without the sparse test).
    Sure,
    /// SURE, or the band's universal threshold where the band is sparse (SureShrink, 1995).
    SureHybrid,
}

/// The normal quartile Φ⁻¹(0.75) as Donoho & Johnstone round it.
pub const MAD_TO_SIGMA: f64 = 0.6745;

impl Thresholding {
    /// The name used on the command line and in records.
    pub fn name(self) -> &'static str {
        match self {
            Thresholding::Soft => "soft",
            Thresholding::Hard => "hard",
        }
    }

    /// One coefficient thresholded at `lambda` ≥ 0.
    pub fn apply(self, x: f64, lambda: f64) -> f64 {
        match self {
            Thresholding::Soft => x.signum() * (x.abs() - lambda).max(0.0),
            Thresholding::Hard if x.abs() >= lambda => x,
            Thresholding::Hard => 0.0,
        }
    }

    /// Every coefficient of `band` thresholded at `lambda`, in place.
    pub fn apply_to(self, band: &mut [f64], lambda: f64) {
        for x in band {
            *x = self.apply(*x, lambda);
        }
    }
}

impl ThresholdRule {
    /// The name used on the command line and in records.
    pub fn name(self) -> &'static str {
        match self {
            ThresholdRule::Universal => "universal",
            ThresholdRule::Sure => "sure",
            ThresholdRule::SureHybrid => "sure-hybrid",
        }
    }

    /// The threshold of detail band `band` of a signal of `signal_len` samples with noise
    /// standard deviation `sigma` (0 when σ̂ is 0: nothing to shrink).
    pub fn threshold(self, band: &[f64], sigma: f64, signal_len: usize) -> f64 {
        if sigma <= 0.0 || band.is_empty() {
            return 0.0;
        }
        match self {
            ThresholdRule::Universal => universal_threshold(sigma, signal_len),
            ThresholdRule::Sure => sigma * sure_threshold_unit(&normalised(band, sigma)),
            ThresholdRule::SureHybrid => sigma * hybrid_threshold_unit(&normalised(band, sigma)),
        }
    }
}

/// σ̂ = median(|d|) / 0.6745 of the finest details `d` (0 for none).
pub fn noise_sigma_mad(finest_details: &[f64]) -> f64 {
    let mut magnitudes: Vec<f64> = finest_details.iter().map(|v| v.abs()).collect();
    median_in_place(&mut magnitudes) / MAD_TO_SIGMA
}

/// σ √(2 ln n), 0 for n ≤ 1.
pub fn universal_threshold(sigma: f64, samples: usize) -> f64 {
    sigma * unit_universal(samples)
}

/// √(2 ln n), 0 for n ≤ 1.
fn unit_universal(samples: usize) -> f64 {
    if samples <= 1 {
        0.0
    } else {
        (2.0 * (samples as f64).ln()).sqrt()
    }
}

/// The median (the mean of the two middle values for an even count); 0 for none.
fn median_in_place(values: &mut [f64]) -> f64 {
    let n = values.len();
    if n == 0 {
        return 0.0;
    }
    let (_, &mut upper, _) = values.select_nth_unstable_by(n / 2, f64::total_cmp);
    if n % 2 == 1 {
        return upper;
    }
    let lower = values[..n / 2]
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    (lower + upper) / 2.0
}

fn normalised(band: &[f64], sigma: f64) -> Vec<f64> {
    band.iter().map(|v| v / sigma).collect()
}

/// t_S for unit-variance coefficients: SURE minimised over {0} ∪ {|x_i|} ∩ [0, √(2 ln d)],
/// from the sorted magnitudes and their running sum of squares (O(d log d)).
pub fn sure_threshold_unit(x: &[f64]) -> f64 {
    let d = x.len();
    let bound = unit_universal(d);
    let mut squares: Vec<f64> = x.iter().map(|v| v * v).collect();
    squares.sort_unstable_by(f64::total_cmp);
    let (mut best_t, mut best_risk) = (0.0, sure_risk_at_zero(&squares));
    let mut below = 0.0;
    for (k, &s) in squares.iter().enumerate() {
        let t = s.sqrt();
        if t > bound {
            break;
        }
        below += s;
        let risk = d as f64 - 2.0 * (k + 1) as f64 + below + (d - k - 1) as f64 * s;
        if risk < best_risk {
            (best_t, best_risk) = (t, risk);
        }
    }
    best_t
}

/// SURE(0) = d − 2 #{x_i = 0}.
fn sure_risk_at_zero(sorted_squares: &[f64]) -> f64 {
    let zeros = sorted_squares.iter().take_while(|&&s| s == 0.0).count();
    sorted_squares.len() as f64 - 2.0 * zeros as f64
}

/// Donoho & Johnstone's hybrid for unit-variance coefficients: √(2 ln d) where
/// (Σ x² − d)/d ≤ (log₂ d)^{3/2}/√d, else [`sure_threshold_unit`].
pub fn hybrid_threshold_unit(x: &[f64]) -> f64 {
    let d = x.len() as f64;
    let energy = (x.iter().map(|v| v * v).sum::<f64>() - d) / d;
    let sparse_bound = d.log2().powf(1.5) / d.sqrt();
    if energy <= sparse_bound {
        unit_universal(x.len())
    } else {
        sure_threshold_unit(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn soft_and_hard_match_pywavelets_at_the_threshold() {
        // pywt.threshold([-2, -1, 0, 1, 1.5, 2], 1, 'hard') = [-2, -1, 0, 1, 1.5, 2];
        // 'soft' = [-1, -0, 0, 0, 0.5, 1].
        let x = [-2.0, -1.0, 0.0, 1.0, 1.5, 2.0];
        let hard: Vec<f64> = x
            .iter()
            .map(|&v| Thresholding::Hard.apply(v, 1.0))
            .collect();
        let soft: Vec<f64> = x
            .iter()
            .map(|&v| Thresholding::Soft.apply(v, 1.0))
            .collect();
        assert_eq!(hard, x.to_vec());
        assert_eq!(soft, vec![-1.0, 0.0, 0.0, 0.0, 0.5, 1.0]);
    }

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median_in_place(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median_in_place(&mut [4.0, 1.0, 3.0, 2.0]), 2.5);
        assert_eq!(median_in_place(&mut []), 0.0);
    }

    #[test]
    fn zero_noise_means_no_shrinkage() {
        for rule in [
            ThresholdRule::Universal,
            ThresholdRule::Sure,
            ThresholdRule::SureHybrid,
        ] {
            assert_eq!(rule.threshold(&[1.0, 2.0], 0.0, 100), 0.0);
        }
    }
}
