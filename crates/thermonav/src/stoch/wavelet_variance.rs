//! The Haar wavelet variance (maximal-overlap discrete wavelet transform, MODWT) and its
//! confidence intervals: the moments that the GMWM estimator ([`crate::stoch::gmwm`]) fits.
//!
//! At level j the Haar MODWT wavelet filter has width L_j = τ_j = 2^j samples: h_{j,l} = −1/τ_j
//! for l < τ_j/2 and +1/τ_j for τ_j/2 ≤ l < τ_j. Its coefficients
//!
//! W_{j,t} = Σ_l h_{j,l} y_{t−l} = (ȳ_recent − ȳ_older) / 2, two adjacent means of m = τ_j/2 samples,
//!
//! are unaffected by the boundary for t = L_j − 1, …, N − 1 (M_j = N − L_j + 1 of them), and the
//! unbiased estimator is ν̂²_j = (1/M_j) Σ_t W²_{j,t} (Percival 1995; Percival & Walden 2000,
//! §8.3). Since the overlapping Allan variance at factor m is the mean of (ȳ_recent − ȳ_older)²/2
//! over the same M_j windows, **ν̂²(τ_j) = AVAR(m = τ_j/2)/2 exactly**: the Haar wavelet variance
//! at scale 2^j samples is half the overlapping Allan variance at averaging time 2^(j−1)
//! samples (allantools `oadev(y, rate, data_type='freq', taus=[2^(j−1)/rate])`). The estimate is
//! therefore computed with the blocked Allan sweep of [`crate::stoch::allan`].
//!
//! Confidence intervals use the chi-square approximation with Percival & Walden's η₃
//! equivalent degrees of freedom, η_j = max(M_j / 2^j, 1) (2000, eq. 314c), as the R package
//! gmwm does: \[η ν̂² / χ²_{η}(1 − α/2), η ν̂² / χ²_{η}(α/2)\]. The same η gives the variance
//! of the estimate, var(ν̂²_j) ≈ 2 ν⁴_j / η_j, which GMWM's weight matrix inverts.

use serde::Serialize;

use crate::stoch::allan::{AllanCurve, overlapping_adev};
use crate::stoch::allan::{AllanError, ChiSquareQuantile, TauGrid, chi_square_quantile};

/// Why a wavelet variance cannot be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WaveletVarianceError {
    /// Fewer samples than the first scale needs.
    #[error("{samples} samples are too few for a wavelet variance (at least 4 are needed)")]
    TooShort {
        /// Samples given.
        samples: usize,
    },
    /// A confidence level outside (0, 1).
    #[error("confidence level must lie strictly between 0 and 1, got {0}")]
    ConfidenceLevel(f64),
    /// Bad input found by the Allan sweep (non-finite sample, bad rate).
    #[error(transparent)]
    Input(#[from] AllanError),
}

/// The Haar wavelet variance of one series at scales τ_j = 2^j samples, j = 1..J.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WaveletVariance {
    /// Scale τ_j = 2^j, samples.
    pub scale_samples: Vec<usize>,
    /// Scale τ_j × dt, s.
    pub scale_s: Vec<f64>,
    /// ν̂²_j, unit of the data squared.
    pub variance: Vec<f64>,
    /// M_j = N − 2^j + 1 coefficients averaged.
    pub n_coefficients: Vec<usize>,
    /// η_j = max(M_j / 2^j, 1), equivalent degrees of freedom.
    pub edf: Vec<f64>,
    /// Lower confidence limit of ν²_j, unit of the data squared.
    pub ci_low: Vec<f64>,
    /// Upper confidence limit of ν²_j, unit of the data squared.
    pub ci_high: Vec<f64>,
    /// Confidence level of the limits (e.g. 0.95).
    pub confidence: f64,
    /// Samples of the series.
    pub n_samples: usize,
    /// Sampling interval dt, s.
    pub dt_s: f64,
}

impl WaveletVariance {
    /// The same wavelet variance without its first `skipped` scales (for a fit that leaves out
    /// the scales a sensor's internal filter shapes).
    pub fn without_first_scales(&self, skipped: usize) -> WaveletVariance {
        let k = skipped.min(self.variance.len());
        WaveletVariance {
            scale_samples: self.scale_samples[k..].to_vec(),
            scale_s: self.scale_s[k..].to_vec(),
            variance: self.variance[k..].to_vec(),
            n_coefficients: self.n_coefficients[k..].to_vec(),
            edf: self.edf[k..].to_vec(),
            ci_low: self.ci_low[k..].to_vec(),
            ci_high: self.ci_high[k..].to_vec(),
            ..self.clone()
        }
    }

    /// var(ν̂²_j) ≈ 2 ν̂⁴_j / η_j, unit of the data to the fourth power.
    pub fn estimate_variance(&self) -> Vec<f64> {
        self.variance
            .iter()
            .zip(&self.edf)
            .map(|(v, eta)| 2.0 * v * v / eta)
            .collect()
    }
}

/// The largest level J with 2^J ≤ N/2 (so that every scale averages at least N/2 coefficients).
pub fn max_level(n_samples: usize) -> usize {
    if n_samples < 4 {
        return 0;
    }
    (n_samples / 2).ilog2() as usize
}

/// The Haar MODWT wavelet variance of rate samples `y` at `sample_rate_hz`, levels 1..=J with
/// J = `levels` or, when `None`, [`max_level`]; limits at `confidence`.
///
/// # Errors
/// [`WaveletVarianceError`] for fewer than 4 samples, a confidence level outside (0, 1), a bad
/// rate or a non-finite sample.
///
/// # Example
/// ```
/// use thermonav::stoch::wavelet_variance::haar_wavelet_variance;
/// let y = [1.0, -1.0, 1.0, -1.0, 1.0, -1.0];
/// let wv = haar_wavelet_variance(&y, 1.0, None, 0.95).unwrap();
/// assert_eq!(wv.scale_samples, vec![2]);
/// // Each coefficient (y_t − y_{t−1})/2 is ±1.
/// assert!((wv.variance[0] - 1.0).abs() < 1e-12);
/// ```
pub fn haar_wavelet_variance(
    y: &[f64],
    sample_rate_hz: f64,
    levels: Option<usize>,
    confidence: f64,
) -> Result<WaveletVariance, WaveletVarianceError> {
    if !(confidence > 0.0 && confidence < 1.0) {
        return Err(WaveletVarianceError::ConfidenceLevel(confidence));
    }
    let levels = levels.unwrap_or(max_level(y.len())).min(max_level(y.len()));
    if levels == 0 {
        return Err(WaveletVarianceError::TooShort { samples: y.len() });
    }
    let factors: Vec<usize> = (0..levels).map(|j| 1 << j).collect();
    let curve = overlapping_adev(y, sample_rate_hz, &TauGrid::Explicit(factors))?;
    Ok(from_allan_curve(&curve, confidence).expect("the factors are 1, 2, 4, ..."))
}

/// The Haar wavelet variance read off an overlapping Allan curve that holds the averaging
/// factors 1, 2, 4, ..., 2^(J−1) (an octave curve): ν²(τ_j = 2^j) = σ²_A(m = 2^(j−1))/2, with
/// the same number of coefficients, at the levels j ≤ [`max_level`]. `None` when the curve
/// lacks factor 1 or the confidence level is outside (0, 1).
pub fn from_allan_curve(curve: &AllanCurve, confidence: f64) -> Option<WaveletVariance> {
    if !(confidence > 0.0 && confidence < 1.0) {
        return None;
    }
    let levels = max_level(curve.n_samples);
    let picked: Vec<usize> = (0..levels)
        .map_while(|j| curve.averaging_factor.iter().position(|&m| m == 1 << j))
        .collect();
    if picked.is_empty() {
        return None;
    }
    let variance: Vec<f64> = picked
        .iter()
        .map(|&i| curve.adev[i].powi(2) / 2.0)
        .collect();
    let scale_samples: Vec<usize> = picked
        .iter()
        .map(|&i| 2 * curve.averaging_factor[i])
        .collect();
    let n_coefficients: Vec<usize> = picked.iter().map(|&i| curve.n_terms[i]).collect();
    let edf: Vec<f64> = scale_samples
        .iter()
        .zip(&n_coefficients)
        .map(|(&tau, &m)| (m as f64 / tau as f64).max(1.0))
        .collect();
    let (ci_low, ci_high) = chi_square_limits(&variance, &edf, confidence);
    Some(WaveletVariance {
        scale_s: scale_samples
            .iter()
            .map(|&t| t as f64 * curve.tau0_s)
            .collect(),
        scale_samples,
        variance,
        n_coefficients,
        edf,
        ci_low,
        ci_high,
        confidence,
        n_samples: curve.n_samples,
        dt_s: curve.tau0_s,
    })
}

fn chi_square_limits(variance: &[f64], edf: &[f64], confidence: f64) -> (Vec<f64>, Vec<f64>) {
    let tail = (1.0 - confidence) / 2.0;
    let quantile = |p: f64, eta: f64| {
        chi_square_quantile(p, eta, ChiSquareQuantile::Exact).expect("p in (0, 1) and eta >= 1")
    };
    variance
        .iter()
        .zip(edf)
        .map(|(&v, &eta)| {
            (
                eta * v / quantile(1.0 - tail, eta),
                eta * v / quantile(tail, eta),
            )
        })
        .unzip()
}
