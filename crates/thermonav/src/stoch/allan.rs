//! Overlapping Allan deviation of rate data, its confidence intervals, and the IEEE Std 952
//! noise terms read off the curve.
//!
//! For a rate series y sampled at τ₀ with N samples, let S_i = Σ_{j<i} y_j (S₀ = 0, N + 1
//! values). The overlapping Allan variance at τ = m τ₀ (NIST SP 1065 eq. 14, written with the
//! phase x = τ₀ S) is
//!
//! σ²(τ) = Σ_{i=0}^{n−1} (S_{i+2m} − 2 S_{i+m} + S_i)² / (2 m² n),  n = N − 2m + 1 terms,
//!
//! which is allantools' `oadev(y, rate, data_type='freq')` and Stable32's "Overlapping Allan"
//! (the `#` column is n). The mean of y is removed first (the second difference cancels it
//! exactly; removing it keeps S small and the sums accurate). O(N) per τ.
//!
//! Confidence intervals: the noise type α at each τ is identified by the lag-1 autocorrelation
//! of the m-averaged rates when at least 30 averages exist and by the B1 ratio otherwise (Riley &
//! Greenhall 2004; Stable32's rule),
//! the equivalent degrees of freedom come from the closed forms of Howe, Allan & Barnes (1981)
//! as tabulated in NIST SP 1065 §5.2.3, and the bounds are σ √(edf/χ²_{edf}(1 − (1−p)/2)) and
//! σ √(edf/χ²_{edf}((1−p)/2)). Stable32 uses Greenhall's EDF algorithm instead; on the OCXO
//! reference the two give limits within 0.5 % of each other (see the tests).

use rayon::prelude::*;
use serde::Serialize;
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// Which averaging factors m to evaluate.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TauGrid {
    /// m = 1, 2, 4, … (allantools 'octave').
    Octave,
    /// m = 1, 2, 4, 10, 20, 40, … (allantools 'decade').
    Decade,
    /// About `per_decade` log-spaced m per decade (distinct integers).
    Dense {
        /// Points per decade.
        per_decade: usize,
    },
    /// These m.
    Explicit(Vec<usize>),
}

/// An Allan deviation curve.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AllanCurve {
    /// Averaging times τ = m τ₀, s.
    pub tau_s: Vec<f64>,
    /// Averaging factors m.
    pub averaging_factor: Vec<usize>,
    /// Overlapping Allan deviation, unit of the data.
    pub adev: Vec<f64>,
    /// Number of terms n = N − 2m + 1.
    pub n_terms: Vec<usize>,
    /// Samples N.
    pub n_samples: usize,
    /// Sampling interval τ₀, s.
    pub tau0_s: f64,
}

/// Why an Allan curve cannot be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AllanError {
    /// Too few samples.
    #[error("{samples} samples are too few for an Allan deviation (at least 3 are needed)")]
    TooShort {
        /// Samples given.
        samples: usize,
    },
    /// A NaN or infinity.
    #[error("sample {index} is not a finite number")]
    NonFinite {
        /// Its index.
        index: usize,
    },
    /// Bad sampling rate.
    #[error("sample rate {rate_hz} Hz must be finite and positive")]
    Rate {
        /// The value.
        rate_hz: f64,
    },
    /// No averaging factor fits the record.
    #[error("no averaging factor of the requested grid fits {samples} samples")]
    EmptyGrid {
        /// Samples given.
        samples: usize,
    },
}

impl TauGrid {
    /// The averaging factors for N samples: those with at least one term (2m ≤ N), sorted,
    /// distinct.
    pub fn factors(&self, n: usize) -> Vec<usize> {
        let phase_len = n + 1;
        let mut m: Vec<usize> = match self {
            TauGrid::Octave => (0..=usize::BITS - phase_len.leading_zeros())
                .map(|k| 1usize << k)
                .collect(),
            TauGrid::Decade => {
                let decades = (phase_len as f64).log10().floor() as u32;
                (0..=decades)
                    .flat_map(|k| [1, 2, 4].map(|f| f * 10usize.pow(k)))
                    .collect()
            }
            TauGrid::Dense { per_decade } => {
                let per = (*per_decade).max(1) as f64;
                let top = (n as f64 / 2.0).log10();
                (0..=(top * per).ceil() as usize)
                    .map(|j| 10f64.powf(j as f64 / per).round() as usize)
                    .collect()
            }
            TauGrid::Explicit(list) => list.clone(),
        };
        m.retain(|&m| m >= 1 && 2 * m <= n);
        m.sort_unstable();
        m.dedup();
        m
    }
}

/// The overlapping Allan deviation of rate samples `y` at `sample_rate_hz` on `grid`.
///
/// # Errors
/// [`AllanError`] for fewer than 3 samples, non-finite values, a bad rate, or a grid with no
/// factor that fits.
pub fn overlapping_adev(
    y: &[f64],
    sample_rate_hz: f64,
    grid: &TauGrid,
) -> Result<AllanCurve, AllanError> {
    if !(sample_rate_hz.is_finite() && sample_rate_hz > 0.0) {
        return Err(AllanError::Rate {
            rate_hz: sample_rate_hz,
        });
    }
    if y.len() < 3 {
        return Err(AllanError::TooShort { samples: y.len() });
    }
    if let Some(index) = y.iter().position(|v| !v.is_finite()) {
        return Err(AllanError::NonFinite { index });
    }
    let factors = grid.factors(y.len());
    if factors.is_empty() {
        return Err(AllanError::EmptyGrid { samples: y.len() });
    }
    let sums = centred_cumulative_sum(y);
    let tau0_s = 1.0 / sample_rate_hz;
    let n = y.len();
    Ok(AllanCurve {
        tau_s: factors.iter().map(|&m| m as f64 * tau0_s).collect(),
        adev: factors
            .par_iter()
            .map(|&m| overlapping_avar_at(&sums, m).sqrt())
            .collect(),
        n_terms: factors.iter().map(|&m| n - 2 * m + 1).collect(),
        averaging_factor: factors,
        n_samples: n,
        tau0_s,
    })
}

/// S_i = Σ_{j<i} (y_j − ȳ), i = 0..=N.
fn centred_cumulative_sum(y: &[f64]) -> Vec<f64> {
    let mean = y.iter().sum::<f64>() / y.len() as f64;
    let mut sums = Vec::with_capacity(y.len() + 1);
    let mut s = 0.0;
    sums.push(0.0);
    for v in y {
        s += v - mean;
        sums.push(s);
    }
    sums
}

/// σ²(m τ₀) from the cumulative sums (τ₀ cancels: S is in rate × samples). Four independent
/// accumulators let the compiler vectorise the sum of squared second differences.
fn overlapping_avar_at(sums: &[f64], m: usize) -> f64 {
    let terms = sums.len() - 2 * m;
    let (a, b, c) = (
        &sums[..terms],
        &sums[m..m + terms],
        &sums[2 * m..2 * m + terms],
    );
    let mut acc = [0.0_f64; 4];
    let (a4, b4, c4) = (a.chunks_exact(4), b.chunks_exact(4), c.chunks_exact(4));
    let tail: f64 = a4
        .remainder()
        .iter()
        .zip(b4.remainder())
        .zip(c4.remainder())
        .map(|((x, y), z)| (z - 2.0 * y + x).powi(2))
        .sum();
    for ((x, y), z) in a4.zip(b4).zip(c4) {
        for (lane, slot) in acc.iter_mut().enumerate() {
            let d = z[lane] - 2.0 * y[lane] + x[lane];
            *slot += d * d;
        }
    }
    (acc.iter().sum::<f64>() + tail) / (2.0 * (m * m) as f64 * terms as f64)
}

/// Confidence limits of an Allan curve.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AllanIntervals {
    /// Confidence level p (e.g. 0.683).
    pub level: f64,
    /// Identified power-law noise exponent α per τ (2 white PM … −2 random-walk FM).
    pub alpha: Vec<i32>,
    /// Equivalent degrees of freedom per τ.
    pub edf: Vec<f64>,
    /// Lower limit of the deviation.
    pub low: Vec<f64>,
    /// Upper limit of the deviation.
    pub high: Vec<f64>,
}

/// Smallest number of m-averages for the lag-1 autocorrelation noise identification.
pub const MIN_AVERAGES_FOR_NOISE_ID: usize = 30;

/// Confidence limits at `level` (0 < level < 1) for the curve of `y`.
pub fn confidence_intervals(y: &[f64], curve: &AllanCurve, level: f64) -> AllanIntervals {
    let level = if level > 0.0 && level < 1.0 {
        level
    } else {
        0.683
    };
    let n_phase = curve.n_samples + 1;
    let alpha: Vec<i32> = curve
        .averaging_factor
        .iter()
        .zip(&curve.adev)
        .map(|(&m, &adev)| {
            if curve.n_samples / m >= MIN_AVERAGES_FOR_NOISE_ID {
                lag1_noise_id(y, m)
            } else {
                b1_noise_id(y, m, adev)
            }
        })
        .collect();
    let edf: Vec<f64> = curve
        .averaging_factor
        .iter()
        .zip(&alpha)
        .map(|(&m, &a)| edf_overlapping_adev(n_phase, m, a))
        .collect();
    let (low, high) = curve
        .adev
        .iter()
        .zip(&edf)
        .map(|(&s, &e)| chi_square_limits(s, e, level))
        .unzip();
    AllanIntervals {
        level,
        alpha,
        edf,
        low,
        high,
    }
}

/// α by the lag-1 autocorrelation of the m-averaged rates, differenced until the statistic
/// δ = r₁/(1 + r₁) drops below 0.25 (at most twice): α = −round(2δ) − 2d for rate data.
pub fn lag1_noise_id(y: &[f64], m: usize) -> i32 {
    let mut z: Vec<f64> = y
        .chunks_exact(m.max(1))
        .map(|c| c.iter().sum::<f64>() / m as f64)
        .collect();
    let mut d = 0;
    loop {
        let delta = lag1(&z).map_or(0.0, |r| r / (1.0 + r));
        if delta < 0.25 || d >= 2 {
            return (-(2.0 * delta).round() as i32 - 2 * d).clamp(-2, 2);
        }
        z = z.windows(2).map(|w| w[1] - w[0]).collect();
        d += 1;
    }
}

/// α by Barnes' B1 ratio (NIST SP 1065 §5.2.6), for τ with few averages: B1 = the sample
/// variance of the N non-overlapping m-averages over the Allan variance, compared with its
/// expectation N(1 − N^μ) / (2(N − 1)(1 − 2^μ)) (μ = −α − 1; N ln N / (2(N − 1) ln 2) at μ = 0)
/// for α = 1, 0, −1, −2; the nearest in ln B1 wins.
pub fn b1_noise_id(y: &[f64], m: usize, adev: f64) -> i32 {
    let z: Vec<f64> = y
        .chunks_exact(m.max(1))
        .map(|c| c.iter().sum::<f64>() / m as f64)
        .collect();
    let n = z.len();
    if n < 2 || adev <= 0.0 {
        return 0;
    }
    let mean = z.iter().sum::<f64>() / n as f64;
    let variance = z.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1) as f64;
    let observed = (variance / (adev * adev)).max(f64::MIN_POSITIVE).ln();
    let nf = n as f64;
    let expected = |alpha: i32| {
        let mu = f64::from(-alpha - 1);
        let b1 = if mu == 0.0 {
            nf * nf.ln() / (2.0 * (nf - 1.0) * 2f64.ln())
        } else {
            nf * (1.0 - nf.powf(mu)) / (2.0 * (nf - 1.0) * (1.0 - 2f64.powf(mu)))
        };
        b1.max(f64::MIN_POSITIVE).ln()
    };
    [1, 0, -1, -2]
        .into_iter()
        .min_by(|&a, &b| {
            (expected(a) - observed)
                .abs()
                .total_cmp(&(expected(b) - observed).abs())
        })
        .unwrap_or(0)
}

fn lag1(z: &[f64]) -> Option<f64> {
    if z.len() < 3 {
        return None;
    }
    let mean = z.iter().sum::<f64>() / z.len() as f64;
    let c0: f64 = z.iter().map(|v| (v - mean) * (v - mean)).sum();
    let c1: f64 = z.windows(2).map(|w| (w[0] - mean) * (w[1] - mean)).sum();
    (c0 > 0.0).then(|| c1 / c0)
}

/// EDF of the overlapping Allan variance for N phase points, factor m and noise α
/// (Howe, Allan & Barnes 1981; NIST SP 1065 table 5).
pub fn edf_overlapping_adev(n_phase: usize, m: usize, alpha: i32) -> f64 {
    let (n, m) = (n_phase as f64, m as f64);
    let edf = match alpha {
        2 => (n + 1.0) * (n - 2.0 * m) / (2.0 * (n - m)),
        1 => (((n - 1.0) / (2.0 * m)).ln() * ((2.0 * m + 1.0) * (n - 1.0) / 4.0).ln())
            .sqrt()
            .exp(),
        0 => {
            (3.0 * (n - 1.0) / (2.0 * m) - 2.0 * (n - 2.0) / n) * 4.0 * m * m / (4.0 * m * m + 5.0)
        }
        -1 if m == 1.0 => 2.0 * (n - 2.0) / (2.3 * n - 4.9),
        -1 => 5.0 * n * n / (4.0 * m * (n + 3.0 * m)),
        _ => {
            (n - 2.0) / m * ((n - 1.0).powi(2) - 3.0 * m * (n - 1.0) + 4.0 * m * m)
                / (n - 3.0).powi(2)
        }
    };
    if edf.is_finite() && edf > 0.0 {
        edf
    } else {
        1.0
    }
}

/// σ √(edf/χ²(1 − (1−p)/2)), σ √(edf/χ²((1−p)/2)).
fn chi_square_limits(sigma: f64, edf: f64, level: f64) -> (f64, f64) {
    let Ok(chi) = ChiSquared::new(edf) else {
        return (sigma, sigma);
    };
    let tail = (1.0 - level) / 2.0;
    let low = sigma * (edf / chi.inverse_cdf(1.0 - tail)).sqrt();
    let high = sigma * (edf / chi.inverse_cdf(tail)).sqrt();
    (low, if high.is_finite() { high } else { sigma })
}
