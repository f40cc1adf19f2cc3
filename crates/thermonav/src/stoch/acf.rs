//! Sample autocovariance and autocorrelation of a uniformly sampled series.
//!
//! # Estimator
//! The biased (denominator `N`) sample autocovariance
//!
//! ```text
//! gamma(k) = (1/N) * sum_{t=0}^{N-1-k} (x_t - m) (x_{t+k} - m),   k = 0..=max_lag
//! rho(k)   = gamma(k) / gamma(0)
//! ```
//!
//! with `m` the sample mean ([`Demean::SampleMean`]) or zero ([`Demean::None`]). The denominator
//! `N` for every lag (not `N - k`) keeps the autocovariance sequence positive semi-definite, which
//! Levinson-Durbin (Yule-Walker) needs; it is Box & Jenkins' estimator and the one computed by
//! statsmodels `acf(x, adjusted=False)`, MATLAB `autocorr` and R `acf`.
//!
//! # Algorithms
//! - [`AcfAlgorithm::Direct`]: the defining sums, `O(N * max_lag)`, blocked so that each block of
//!   the series is read once from memory for all lags. Validation, the mean and the centring
//!   happen in that same pass: the blocks are centred on a provisional mean (of every 64th
//!   sample) and the sums are then moved exactly to the sample mean, which costs at most a
//!   factor 65 of rounding and in practice nothing.
//! - [`AcfAlgorithm::Fft`]: Wiener-Khinchin. The centred series is zero-padded to a length
//!   `L >= N + max_lag` (so the circular correlation does not wrap onto the lags that are kept),
//!   transformed with a real FFT, squared in modulus and transformed back: `O(L log L)`.
//! - [`AcfAlgorithm::Auto`]: the direct sums when `max_lag + 1 < 16 log2 L` (about 350 lags for
//!   2^21 samples; always for AR fitting), the FFT otherwise.
//!
//! Both agree with a naive double loop to about `1e-15 * gamma(0)`.

use realfft::RealFftPlanner;
use realfft::num_complex::Complex;
use thiserror::Error;

/// How the series is centred before the lagged products are formed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Demean {
    /// Use the samples as they are (the process is known to have zero mean).
    None,
    /// Subtract the sample mean `(1/N) sum x_t` (the usual choice; statsmodels' default).
    SampleMean,
}

/// Which algorithm evaluates the lagged sums (the result is the same up to rounding).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum AcfAlgorithm {
    /// Choose by cost: direct sums for few lags, FFT for many.
    #[default]
    Auto,
    /// Direct `O(N * max_lag)` sums.
    Direct,
    /// Zero-padded real FFT, `O(N log N)`.
    Fft,
}

/// Invalid input to the autocorrelation functions.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum AcfError {
    /// The series has no samples.
    #[error("the series is empty: at least one sample is needed")]
    Empty,
    /// A sample is NaN or infinite.
    #[error("sample {index} is {value}: every sample must be finite")]
    NonFinite {
        /// Index of the first non-finite sample.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// The requested lag range reaches beyond the series.
    #[error("max_lag {max_lag} is too large for {n_samples} samples: it must be below n_samples")]
    MaxLagTooLarge {
        /// Requested largest lag.
        max_lag: usize,
        /// Length of the series.
        n_samples: usize,
    },
    /// All samples are finite but their sums of squares overflow `f64`.
    #[error(
        "the series is too large in magnitude (largest |x| = {max_abs:e}): its sums overflow; rescale it"
    )]
    Overflow {
        /// Largest absolute sample.
        max_abs: f64,
    },
    /// `gamma(0) = 0`, so the autocorrelation `gamma(k) / gamma(0)` is undefined.
    #[error(
        "the series has zero variance (gamma(0) = 0 over {n_samples} samples): its autocorrelation is undefined"
    )]
    ZeroVariance {
        /// Length of the series.
        n_samples: usize,
    },
}

/// Biased sample autocovariance `gamma(0..=max_lag)` (see the module docs), algorithm chosen by
/// cost.
///
/// # Errors
/// [`AcfError::Empty`], [`AcfError::NonFinite`], [`AcfError::MaxLagTooLarge`] when
/// `max_lag >= x.len()`, [`AcfError::Overflow`] for samples near `1e154` or larger.
///
/// # Example
/// ```
/// use thermonav::stoch::acf::{autocovariance, Demean};
/// let gamma = autocovariance(&[1.0, -1.0, 1.0, -1.0], 1, Demean::None).unwrap();
/// assert_eq!(gamma, vec![1.0, -0.75]);
/// ```
pub fn autocovariance(x: &[f64], max_lag: usize, demean: Demean) -> Result<Vec<f64>, AcfError> {
    autocovariance_with(x, max_lag, demean, AcfAlgorithm::Auto)
}

/// [`autocovariance`] with an explicit algorithm.
///
/// # Errors
/// As [`autocovariance`].
pub fn autocovariance_with(
    x: &[f64],
    max_lag: usize,
    demean: Demean,
    algorithm: AcfAlgorithm,
) -> Result<Vec<f64>, AcfError> {
    Ok(autocovariance_and_mean(x, max_lag, demean, algorithm)?.0)
}

/// Sample autocorrelation `rho(k) = gamma(k) / gamma(0)`, `k = 0..=max_lag`.
///
/// # Errors
/// As [`autocovariance`], plus [`AcfError::ZeroVariance`] for a series that is constant (or
/// all zero with [`Demean::None`]) up to rounding: standard deviation at most `1e-15 |mean|`.
pub fn autocorrelation(x: &[f64], max_lag: usize, demean: Demean) -> Result<Vec<f64>, AcfError> {
    let (gamma, mean) = autocovariance_and_mean(x, max_lag, demean, AcfAlgorithm::Auto)?;
    let gamma0 = gamma[0];
    if is_constant_to_rounding(gamma0, mean) {
        return Err(AcfError::ZeroVariance { n_samples: x.len() });
    }
    Ok(gamma.into_iter().map(|g| g / gamma0).collect())
}

/// True when a variance `gamma0` around `mean` is no larger than the rounding of `mean` itself
/// (standard deviation at most `1e-15 |mean|`, a few units in the last place): the samples are
/// then equal up to rounding, and their "autocorrelation" would be rounding noise.
pub(crate) fn is_constant_to_rounding(gamma0: f64, mean: f64) -> bool {
    gamma0 <= (1e-15 * mean).powi(2)
}

/// The autocovariance and the mean that was removed.
fn autocovariance_and_mean(
    x: &[f64],
    max_lag: usize,
    demean: Demean,
    algorithm: AcfAlgorithm,
) -> Result<(Vec<f64>, f64), AcfError> {
    check_lag_range(x, max_lag)?;
    let products = match resolve_algorithm(algorithm, x.len(), max_lag) {
        AcfAlgorithm::Fft => fft_products_checked(x, demean, max_lag)?,
        _ => centred_lagged_products(x, demean, max_lag)?,
    };
    let n = x.len() as f64;
    Ok((
        products.sums.into_iter().map(|s| s / n).collect(),
        products.mean,
    ))
}

/// Lagged products by FFT after a validating mean pass.
fn fft_products_checked(
    x: &[f64],
    demean: Demean,
    max_lag: usize,
) -> Result<CentredProducts, SeriesFault> {
    let mean = match demean {
        Demean::None => 0.0,
        Demean::SampleMean => checked_mean(x)?,
    };
    let sums = lagged_products_fft(x, mean, max_lag);
    if sums[0].is_finite() {
        Ok(CentredProducts { sums, mean })
    } else {
        Err(locate_fault(x))
    }
}

/// Checks that the series is not empty and longer than `max_lag`.
fn check_lag_range(x: &[f64], max_lag: usize) -> Result<(), AcfError> {
    if x.is_empty() {
        return Err(AcfError::Empty);
    }
    if max_lag >= x.len() {
        return Err(AcfError::MaxLagTooLarge {
            max_lag,
            n_samples: x.len(),
        });
    }
    Ok(())
}

/// Why a series cannot be used, found while summing it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum SeriesFault {
    /// The first NaN or infinite sample.
    NonFinite { index: usize, value: f64 },
    /// All samples finite, but sums overflow `f64`; the largest magnitude.
    Overflow { max_abs: f64 },
}

impl SeriesFault {
    /// The overflow fault of a finite series.
    pub(crate) fn overflow(x: &[f64]) -> Self {
        SeriesFault::Overflow {
            max_abs: x.iter().fold(0.0, |m: f64, v| m.max(v.abs())),
        }
    }
}

impl From<SeriesFault> for AcfError {
    fn from(fault: SeriesFault) -> Self {
        match fault {
            SeriesFault::NonFinite { index, value } => AcfError::NonFinite { index, value },
            SeriesFault::Overflow { max_abs } => AcfError::Overflow { max_abs },
        }
    }
}

/// The sample mean of a non-empty series, validating it in the same pass: a finite total
/// implies finite samples; otherwise the first non-finite sample (or the overflow) is reported.
pub(crate) fn checked_mean(x: &[f64]) -> Result<f64, SeriesFault> {
    let total = blocked_sum(x);
    if total.is_finite() {
        Ok(total / x.len() as f64)
    } else {
        Err(locate_fault(x))
    }
}

/// The fault of a series whose sums came out non-finite: its first non-finite sample, or else
/// an overflow.
fn locate_fault(x: &[f64]) -> SeriesFault {
    match first_non_finite(x) {
        Some((index, value)) => SeriesFault::NonFinite { index, value },
        None => SeriesFault::overflow(x),
    }
}

/// Index and value of the first NaN or infinite sample.
fn first_non_finite(x: &[f64]) -> Option<(usize, f64)> {
    x.iter()
        .enumerate()
        .find(|(_, v)| !v.is_finite())
        .map(|(i, v)| (i, *v))
}

/// Sum in blocks with eight running partial sums per block: the rounding error grows like
/// `block / 8 + N / block` rather than `N`, and the additions pipeline.
fn blocked_sum(x: &[f64]) -> f64 {
    x.chunks(BLOCK).map(sum_in_lanes).sum()
}

/// Sum with eight independent accumulators.
fn sum_in_lanes(x: &[f64]) -> f64 {
    let mut acc = [0.0; LANES];
    let chunks = x.chunks_exact(LANES);
    let tail: f64 = chunks.remainder().iter().sum();
    for c in chunks {
        for k in 0..LANES {
            acc[k] += c[k];
        }
    }
    acc.iter().sum::<f64>() + tail
}

/// Independent accumulators in the inner loops (enough to hide the add latency).
const LANES: usize = 8;

/// Samples per block of the direct sums: a block and its `max_lag` look-ahead stay in cache.
const BLOCK: usize = 2048;

/// Direct sums cost about `N * (max_lag + 1)` multiply-adds (0.21 ns each), the two FFTs about
/// `L log2 L` steps of 3.6 ns (both measured by `benches/ar.rs` on 2^21 samples, x86-64, one
/// core): the crossover there is near 350 lags.
const FFT_COST_FACTOR: f64 = 16.0;

/// Replaces [`AcfAlgorithm::Auto`] by the cheaper of the two algorithms.
fn resolve_algorithm(algorithm: AcfAlgorithm, n: usize, max_lag: usize) -> AcfAlgorithm {
    if algorithm != AcfAlgorithm::Auto {
        return algorithm;
    }
    let len = fft_length(n + max_lag) as f64;
    let direct_cost = n as f64 * (max_lag + 1) as f64;
    if direct_cost <= FFT_COST_FACTOR * len * len.log2() {
        AcfAlgorithm::Direct
    } else {
        AcfAlgorithm::Fft
    }
}

/// Un-normalised lagged products `S(d) = sum_{t=0}^{N-1-d} y_t y_{t+d}`, `d = 0..=max_lag`, of
/// the centred series `y_t = x_t - mean`, and that mean (0 for [`Demean::None`]).
pub(crate) struct CentredProducts {
    /// `S(0..=max_lag)`.
    pub(crate) sums: Vec<f64>,
    /// The mean subtracted.
    pub(crate) mean: f64,
}

/// Validates the series, takes its mean and forms the lagged products of the centred series,
/// reading the series from memory once. Requires `max_lag < x.len()`.
///
/// The pass centres on a provisional `shift` (the mean of every [`STRIDE`]-th sample) and then
/// moves the sums to the exact sample mean algebraically:
/// `S(d) = R(d) - delta (A_d + B_d) + (N - d) delta^2`, with `R` the products of
/// `z = x - shift`, `delta = mean(z)`, `A_d = sum_{t<N-d} z_t`, `B_d = sum_{t>=d} z_t`. The
/// subsample holds `N / STRIDE` samples, so `N delta^2 <= STRIDE N sigma^2` (Chebyshev) and
/// the correction costs at most a factor `1 + STRIDE` of rounding relative to `S(0)`
/// (about 1e-14); in practice `delta` is far below `sigma`.
pub(crate) fn centred_lagged_products(
    x: &[f64],
    demean: Demean,
    max_lag: usize,
) -> Result<CentredProducts, SeriesFault> {
    let shift = match demean {
        Demean::None => 0.0,
        Demean::SampleMean => subsample_mean(x),
    };
    if !shift.is_finite() {
        return Err(locate_fault(x));
    }
    let (mut sums, z_total) = shifted_lagged_products(x, shift, max_lag);
    if !(z_total.is_finite() && sums[0].is_finite()) {
        return Err(locate_fault(x));
    }
    if demean == Demean::None {
        return Ok(CentredProducts { sums, mean: 0.0 });
    }
    let delta = z_total / x.len() as f64;
    move_to_mean(&mut sums, x, shift, z_total, delta);
    Ok(CentredProducts {
        sums,
        mean: shift + delta,
    })
}

/// Subsampling stride of the provisional shift.
const STRIDE: usize = 64;

/// Mean of `x[0], x[STRIDE], x[2 STRIDE], ...` (NaN or infinite if such a sample is).
fn subsample_mean(x: &[f64]) -> f64 {
    let (sum, count) = x
        .iter()
        .step_by(STRIDE)
        .fold((0.0, 0usize), |(s, c), v| (s + v, c + 1));
    sum / count as f64
}

/// Products `R(d)` of `z = x - shift` by blocks, and `sum z`.
fn shifted_lagged_products(x: &[f64], shift: f64, max_lag: usize) -> (Vec<f64>, f64) {
    let n = x.len();
    let interior = n - max_lag;
    let mut sums = vec![0.0; max_lag + 1];
    let mut z_total = 0.0;
    let mut block = Vec::with_capacity(BLOCK + max_lag);
    let mut start = 0;
    while start < interior {
        let end = (start + BLOCK).min(interior);
        block.clear();
        block.extend(x[start..end + max_lag].iter().map(|v| v - shift));
        z_total += sum_in_lanes(&block[..end - start]);
        add_block_products(&block, end - start, &mut sums);
        start = end;
    }
    z_total += x[interior..].iter().map(|v| v - shift).sum::<f64>();
    add_tail_products(x, shift, interior, &mut sums);
    (sums, z_total)
}

/// Turns products of `z = x - shift` into products of `z - delta` (see
/// [`centred_lagged_products`]); `z_total = sum z = N delta`.
fn move_to_mean(sums: &mut [f64], x: &[f64], shift: f64, z_total: f64, delta: f64) {
    let n = x.len();
    let mut head = 0.0; // sum_{t<d} z_t
    let mut tail = 0.0; // sum_{t>=N-d} z_t
    for (lag, sum) in sums.iter_mut().enumerate() {
        if lag > 0 {
            head += x[lag - 1] - shift;
            tail += x[n - lag] - shift;
        }
        let a = z_total - tail;
        let b = z_total - head;
        *sum += -delta * (a + b) + (n - lag) as f64 * delta * delta;
    }
}

/// Adds `sum_{t<len} b_t b_{t+d}` to `sums[d]` for every lag; `block` holds `len + max_lag`
/// centred samples (one block stays in cache while every lag reads it).
fn add_block_products(block: &[f64], len: usize, sums: &mut [f64]) {
    for (lag, sum) in sums.iter_mut().enumerate() {
        *sum += dot(&block[..len], &block[lag..lag + len]);
    }
}

/// Adds the products `y_t y_{t+d}` for `t >= interior`, where not every lag has a partner.
fn add_tail_products(x: &[f64], mean: f64, interior: usize, sums: &mut [f64]) {
    let n = x.len();
    for t in interior..n {
        for (lag, sum) in sums.iter_mut().enumerate().take(n - t) {
            *sum += (x[t] - mean) * (x[t + lag] - mean);
        }
    }
}

/// Dot product with [`LANES`] independent accumulators (lets the compiler vectorise).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; LANES];
    let chunks_a = a.chunks_exact(LANES);
    let chunks_b = b.chunks_exact(LANES);
    let tail: f64 = chunks_a
        .remainder()
        .iter()
        .zip(chunks_b.remainder())
        .map(|(u, v)| u * v)
        .sum();
    for (ca, cb) in chunks_a.zip(chunks_b) {
        for k in 0..LANES {
            acc[k] += ca[k] * cb[k];
        }
    }
    acc.iter().sum::<f64>() + tail
}

/// The lagged products of [`lagged_products`] through a zero-padded real FFT.
fn lagged_products_fft(x: &[f64], mean: f64, max_lag: usize) -> Vec<f64> {
    let len = fft_length(x.len() + max_lag);
    let mut planner = RealFftPlanner::<f64>::new();
    let forward = planner.plan_fft_forward(len);
    let inverse = planner.plan_fft_inverse(len);
    let mut signal = forward.make_input_vec();
    for (padded, v) in signal.iter_mut().zip(x) {
        *padded = v - mean;
    }
    let mut spectrum = forward.make_output_vec();
    forward
        .process(&mut signal, &mut spectrum)
        .expect("buffers were made by the same plan");
    for bin in spectrum.iter_mut() {
        *bin = Complex::new(bin.norm_sqr(), 0.0);
    }
    inverse
        .process(&mut spectrum, &mut signal)
        .expect("buffers were made by the same plan and the spectrum is real");
    let scale = 1.0 / len as f64;
    signal[..=max_lag].iter().map(|v| v * scale).collect()
}

/// Smallest even length `>= min_len` of the form `2^a 3^b 5^c` (fast for RustFFT).
fn fft_length(min_len: usize) -> usize {
    let target = min_len.max(2);
    let mut best = target.next_power_of_two();
    let mut odd_5 = 1usize;
    while odd_5 < best {
        let mut odd = odd_5;
        while odd < best {
            best = best.min(smallest_even_multiple(odd, target));
            odd *= 3;
        }
        odd_5 *= 5;
    }
    best
}

/// Smallest `odd * 2^a >= target` with `a >= 1`.
fn smallest_even_multiple(odd: usize, target: usize) -> usize {
    let mut len = 2 * odd;
    while len < target {
        len *= 2;
    }
    len
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fft_length_is_smooth_even_and_large_enough() {
        // Closed forms: 7 -> 8, 9 -> 10 (2*5), 13 -> 16 (15 is odd), 1000 -> 1000 (2^3 5^3).
        assert_eq!(fft_length(7), 8);
        assert_eq!(fft_length(9), 10);
        assert_eq!(fft_length(13), 16);
        assert_eq!(fft_length(1000), 1000);
        assert_eq!(fft_length(1), 2);
        for min_len in 1..3000 {
            let len = fft_length(min_len);
            assert!(len >= min_len && len % 2 == 0, "{min_len} -> {len}");
        }
    }

    #[test]
    fn sample_mean_of_blocks_covers_every_sample_once() {
        // x_i = i: integer sums are exact in f64, so the mean is exactly (n - 1) / 2 for lengths
        // below, at and across block boundaries.
        for n in [1, 2, BLOCK - 1, BLOCK, BLOCK + 1, 3 * BLOCK + 17] {
            let x: Vec<f64> = (0..n).map(|i| i as f64).collect();
            assert_eq!(checked_mean(&x), Ok((n - 1) as f64 / 2.0), "n = {n}");
        }
    }
}
