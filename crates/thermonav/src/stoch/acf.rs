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

/// Rows processed per block by [`lagged_products`]: the block, centred once into a buffer of
/// 4096 values (32 KiB), stays in L1 while every lag is summed over it, so the data is read
/// from memory once.
const BLOCK: usize = 4096;

/// Rows per piece of the pass: pieces may run on different threads, and their partial sums
/// are added in piece order, so the result does not depend on the number of threads.
const PIECE: usize = 1 << 16;

/// Rows below which the pass stays on the calling thread.
const PARALLEL_ROWS: usize = 1 << 18;

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

/// Products about `centre` for lags 0..=max_lag and the sum of x − centre, in one pass over
/// fixed pieces of [`PIECE`] rows (on the rayon pool for long series), added in piece order.
fn lagged_products_and_sum(x: &[f64], centre: f64, max_lag: usize) -> (Vec<f64>, f64) {
    use rayon::prelude::*;
    let starts: Vec<usize> = (0..x.len()).step_by(PIECE).collect();
    let piece = |&start: &usize| piece_products(x, centre, max_lag, start);
    let partials: Vec<(Vec<f64>, f64)> = if x.len() >= PARALLEL_ROWS {
        starts.par_iter().map(piece).collect()
    } else {
        starts.iter().map(piece).collect()
    };
    let mut sums = vec![0.0; max_lag + 1];
    let mut total = 0.0;
    for (products, piece_total) in &partials {
        sums.iter_mut().zip(products).for_each(|(s, p)| *s += p);
        total += piece_total;
    }
    (sums, total)
}

/// Σ_t (x_t − c)(x_{t+k} − c) for k = 0..=max_lag over the rows t of the piece starting at
/// `start` (t + k < N), and Σ_t (x_t − c): block by block, each block centred once into a
/// buffer that also holds the `max_lag` rows after it.
fn piece_products(x: &[f64], centre: f64, max_lag: usize, start: usize) -> (Vec<f64>, f64) {
    let n = x.len();
    let end = (start + PIECE).min(n);
    let mut sums = vec![0.0; max_lag + 1];
    let mut total = 0.0;
    let mut centred = Vec::with_capacity(BLOCK + max_lag);
    for block in (start..end).step_by(BLOCK) {
        let rows = BLOCK.min(end - block);
        centred.clear();
        let reach = (block + rows + max_lag).min(n);
        centred.extend(x[block..reach].iter().map(|v| v - centre));
        total += sum_of(&centred[..rows]);
        for (k, sum) in sums.iter_mut().enumerate() {
            let stop = rows.min(centred.len().saturating_sub(k));
            if stop > 0 {
                *sum += dot(&centred[..stop], &centred[k..k + stop]);
            }
        }
    }
    (sums, total)
}

/// Independent accumulators in [`dot`] and [`sum_of`]: enough to hide the latency of the
/// additions and let the compiler use full vector registers.
const LANES: usize = 8;

/// Σ a_i b_i with [`LANES`] independent accumulators.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0_f64; LANES];
    let (a8, b8) = (a.chunks_exact(LANES), b.chunks_exact(LANES));
    let tail: f64 = a8
        .remainder()
        .iter()
        .zip(b8.remainder())
        .map(|(p, q)| p * q)
        .sum();
    for (p, q) in a8.zip(b8) {
        for (lane, slot) in acc.iter_mut().enumerate() {
            *slot += p[lane] * q[lane];
        }
    }
    acc.iter().sum::<f64>() + tail
}

/// Σ a_i with [`LANES`] independent accumulators (vectorisable, and more accurate than one
/// chain); also the sums of the Allan deviation's passes.
pub(crate) fn sum_of(a: &[f64]) -> f64 {
    let mut acc = [0.0_f64; LANES];
    let a8 = a.chunks_exact(LANES);
    let tail: f64 = a8.remainder().iter().sum();
    for p in a8 {
        for (lane, slot) in acc.iter_mut().enumerate() {
            *slot += p[lane];
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

    // The pieced, blocked pass (several pieces on the rayon pool, blocks whose lag reach
    // crosses piece and block ends) against a plain double loop, on a series long enough for
    // the parallel path and lengths that leave partial pieces and blocks. Rounding only:
    // 1e-12 of the lag-0 sum.
    #[test]
    fn pieced_products_equal_the_plain_double_loop() {
        for n in [PARALLEL_ROWS + 4099, 3 * BLOCK + 5, 9] {
            let x: Vec<f64> = (0..n)
                .map(|k| (0.013 * k as f64).sin() + 0.3 * ((k * 7919) % 13) as f64)
                .collect();
            let max_lag = 8.min(n - 1);
            let centre = 0.25;
            let (products, total) = lagged_products_and_sum(&x, centre, max_lag);
            let plain_total: f64 = x.iter().map(|v| v - centre).sum();
            assert!((total - plain_total).abs() < 1e-12 * n as f64);
            for (k, p) in products.iter().enumerate() {
                let plain: f64 = (0..n - k)
                    .map(|t| (x[t] - centre) * (x[t + k] - centre))
                    .sum();
                let scale = products[0].abs();
                assert!(
                    (p - plain).abs() < 1e-12 * scale,
                    "n {n} lag {k}: {p} vs {plain}"
                );
            }
        }
    }
}
