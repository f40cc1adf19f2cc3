//! Sample autocovariance and autocorrelation by FFT.
//!
//! The biased estimator γ(k) = (1/N) Σ_{t=0}^{N−1−k} (x_t − x̄)(x_{t+k} − x̄), k = 0..K
//! (Box & Jenkins; the one statsmodels `acovf(adjusted=False)`, R `acf` and MATLAB `autocorr`
//! use): it is positive semi-definite, which Yule-Walker needs. ρ(k) = γ(k)/γ(0). Computed as
//! the inverse FFT of |X(f)|² with zero padding to at least 2N (no circular wrap), O(N log N),
//! for millions of samples.

use realfft::RealFftPlanner;

/// Whether the sample mean is removed first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Demean {
    /// Subtract the sample mean (the usual choice).
    Subtract,
    /// Use the data as they are (a process known to have zero mean).
    Keep,
}

/// Why an autocovariance cannot be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AcfError {
    /// Too few samples for the lags asked.
    #[error("{samples} samples are too few for {max_lag} lags (need more samples than lags)")]
    TooShort {
        /// Samples.
        samples: usize,
        /// Lags asked.
        max_lag: usize,
    },
    /// A NaN or infinity.
    #[error("sample {index} is not a finite number")]
    NonFinite {
        /// Its index.
        index: usize,
    },
    /// Zero variance: the autocorrelation is undefined.
    #[error("the series is constant: its autocorrelation is undefined")]
    Constant,
}

fn prepare(x: &[f64], max_lag: usize, demean: Demean) -> Result<Vec<f64>, AcfError> {
    check(x, max_lag)?;
    let mean = match demean {
        Demean::Subtract => x.iter().sum::<f64>() / x.len() as f64,
        Demean::Keep => 0.0,
    };
    Ok(x.iter().map(|v| v - mean).collect())
}

/// Up to this many lags the direct sum (O(N K), vectorised) beats the FFT (O(N log N)).
pub const DIRECT_MAX_LAG: usize = 32;

/// γ(0..=max_lag), biased: by direct lagged sums for a few lags, by FFT for many.
///
/// # Errors
/// [`AcfError`] for too few samples or non-finite values.
pub fn autocovariance(x: &[f64], max_lag: usize, demean: Demean) -> Result<Vec<f64>, AcfError> {
    if max_lag <= DIRECT_MAX_LAG {
        check(x, max_lag)?;
        let mean = match demean {
            Demean::Subtract => x.iter().sum::<f64>() / x.len() as f64,
            Demean::Keep => 0.0,
        };
        let n = x.len() as f64;
        return Ok(lagged_products(x, mean, max_lag)
            .iter()
            .map(|v| v / n)
            .collect());
    }
    autocovariance_fft(prepare(x, max_lag, demean)?, max_lag)
}

/// Rows processed per block by [`lagged_products`]: 4096 values (32 KiB) stay in L1/L2 while
/// every lag is summed over them, so the data is read from memory once.
const BLOCK: usize = 4096;

/// Σ_t (x_t − m)(x_{t+k} − m) for k = 0..=max_lag in one blocked pass over x.
pub fn lagged_products(x: &[f64], mean: f64, max_lag: usize) -> Vec<f64> {
    lagged_products_and_sum(x, mean, max_lag).0
}

/// Lagged products about the sample mean (or zero) and that mean, in ONE blocked pass: the
/// products are accumulated about a provisional centre c = x₀ and corrected exactly,
/// Σ(x_t−μ)(x_{t+k}−μ) = P_k − δ(A_k + B_k) + (N−k)δ², δ = μ − c, with P_k the products about c
/// and A_k, B_k the sums of x − c over t < N−k and t ≥ k. Since |δ| is of the order of the
/// data's spread, the correction loses no significant digits.
///
/// # Errors
/// [`AcfError`] for too few samples, a non-finite value (located by a second scan), or zero
/// variance.
pub fn lagged_products_about_mean(
    x: &[f64],
    max_lag: usize,
    demean: Demean,
) -> Result<(Vec<f64>, f64), AcfError> {
    if x.len() <= max_lag || x.is_empty() {
        return Err(AcfError::TooShort {
            samples: x.len(),
            max_lag,
        });
    }
    let centre = match demean {
        Demean::Subtract => x[0],
        Demean::Keep => 0.0,
    };
    let (products, sum) = lagged_products_and_sum(x, centre, max_lag);
    if !(sum.is_finite() && products.iter().all(|p| p.is_finite())) {
        let index = x.iter().position(|v| !v.is_finite()).unwrap_or(0);
        return Err(AcfError::NonFinite { index });
    }
    let n = x.len();
    let delta = match demean {
        Demean::Subtract => sum / n as f64,
        Demean::Keep => 0.0,
    };
    let head: Vec<f64> = x[..=max_lag].iter().map(|v| v - centre).collect();
    let tail: Vec<f64> = x[n - max_lag - 1..].iter().map(|v| v - centre).collect();
    let corrected: Vec<f64> = products
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let a = sum - tail[tail.len() - k..].iter().sum::<f64>();
            let b = sum - head[..k].iter().sum::<f64>();
            p - delta * (a + b) + (n - k) as f64 * delta * delta
        })
        .collect();
    if corrected[0] <= 0.0 {
        return Err(AcfError::Constant);
    }
    Ok((corrected, centre + delta))
}

/// Products about `centre` for lags 0..=max_lag and the sum of x − centre, in one pass: the
/// data go through the cache in blocks, and every lag is summed while a block is there.
fn lagged_products_and_sum(x: &[f64], centre: f64, max_lag: usize) -> (Vec<f64>, f64) {
    let n = x.len();
    let mut sums = vec![0.0; max_lag + 1];
    let mut total = 0.0;
    let mut start = 0;
    while start < n {
        let end = (start + BLOCK).min(n);
        total += x[start..end].iter().map(|v| v - centre).sum::<f64>();
        for (k, sum) in sums.iter_mut().enumerate() {
            let stop = end.min(n - k);
            if stop > start {
                *sum += centred_dot(&x[start..stop], &x[start + k..stop + k], centre);
            }
        }
        start = end;
    }
    (sums, total)
}

/// Σ (a_i − c)(b_i − c) with four independent accumulators.
fn centred_dot(a: &[f64], b: &[f64], c: f64) -> f64 {
    let mut acc = [0.0_f64; 4];
    let (a4, b4) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = a4
        .remainder()
        .iter()
        .zip(b4.remainder())
        .map(|(p, q)| (p - c) * (q - c))
        .sum();
    for (p, q) in a4.zip(b4) {
        for (lane, slot) in acc.iter_mut().enumerate() {
            *slot += (p[lane] - c) * (q[lane] - c);
        }
    }
    acc.iter().sum::<f64>() + tail
}

fn check(x: &[f64], max_lag: usize) -> Result<(), AcfError> {
    if x.len() <= max_lag || x.is_empty() {
        return Err(AcfError::TooShort {
            samples: x.len(),
            max_lag,
        });
    }
    match x.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(AcfError::NonFinite { index }),
        None => Ok(()),
    }
}

fn autocovariance_fft(centred: Vec<f64>, max_lag: usize) -> Result<Vec<f64>, AcfError> {
    let n = centred.len();
    let size = (2 * n).next_power_of_two();
    let mut planner = RealFftPlanner::<f64>::new();
    let forward = planner.plan_fft_forward(size);
    let inverse = planner.plan_fft_inverse(size);
    let mut buffer = centred;
    buffer.resize(size, 0.0);
    let mut spectrum = forward.make_output_vec();
    // Buffer lengths match the plans by construction: these calls cannot fail.
    let _ = forward.process(&mut buffer, &mut spectrum);
    for s in spectrum.iter_mut() {
        *s = rustfft::num_complex::Complex::new(s.norm_sqr(), 0.0);
    }
    let _ = inverse.process(&mut spectrum, &mut buffer);
    let scale = 1.0 / (size as f64 * n as f64);
    Ok(buffer[..=max_lag].iter().map(|v| v * scale).collect())
}

/// γ(0..=max_lag) by the direct O(N K) sum: the slow, obviously correct reference.
///
/// # Errors
/// As [`autocovariance`].
pub fn autocovariance_direct(
    x: &[f64],
    max_lag: usize,
    demean: Demean,
) -> Result<Vec<f64>, AcfError> {
    let c = prepare(x, max_lag, demean)?;
    let n = c.len() as f64;
    Ok((0..=max_lag)
        .map(|k| {
            c[..c.len() - k]
                .iter()
                .zip(&c[k..])
                .map(|(a, b)| a * b)
                .sum::<f64>()
                / n
        })
        .collect())
}

/// ρ(0..=max_lag) = γ(k)/γ(0).
///
/// # Errors
/// As [`autocovariance`], plus [`AcfError::Constant`] for zero variance.
pub fn autocorrelation(x: &[f64], max_lag: usize, demean: Demean) -> Result<Vec<f64>, AcfError> {
    let gamma = autocovariance(x, max_lag, demean)?;
    if gamma[0] <= 0.0 {
        return Err(AcfError::Constant);
    }
    Ok(gamma.iter().map(|g| g / gamma[0]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    // The one-pass products about a provisional centre, corrected to the mean, against the
    // two-pass reference (subtract the mean, then sum), on data far from zero (offset 1e4,
    // spread 1): the correction is exact algebra, so only rounding remains, 1e-9 relative.
    #[test]
    fn one_pass_products_about_the_mean_equal_the_two_pass_ones() {
        let x: Vec<f64> = (0..10_000)
            .map(|k| 1e4 + (0.37 * k as f64).sin() + 0.1 * (k % 7) as f64)
            .collect();
        let (fast, mean) = lagged_products_about_mean(&x, 6, Demean::Subtract).unwrap();
        let reference = autocovariance_direct(&x, 6, Demean::Subtract).unwrap();
        let exact_mean = x.iter().sum::<f64>() / x.len() as f64;
        assert!((mean - exact_mean).abs() < 1e-9);
        for (k, (a, b)) in fast.iter().zip(&reference).enumerate() {
            let b = b * x.len() as f64;
            assert!(
                ((a - b) / reference[0] / x.len() as f64).abs() < 1e-9,
                "lag {k}: {a} vs {b}"
            );
        }
        assert_eq!(
            lagged_products_about_mean(&[3.0; 20], 2, Demean::Subtract),
            Err(AcfError::Constant)
        );
        assert_eq!(
            lagged_products_about_mean(&[1.0, f64::NAN, 2.0, 3.0], 1, Demean::Subtract),
            Err(AcfError::NonFinite { index: 1 })
        );
    }
}
