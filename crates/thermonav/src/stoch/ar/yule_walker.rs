//! Yule-Walker (autocorrelation method): solve the Yule-Walker equations
//! `sum_j c_j gamma(|i-j|) = gamma(i)`, `i = 1..p`, built on the biased sample autocovariance,
//! by the Levinson-Durbin recursion (Box & Jenkins; Brockwell & Davis 1991, §8.1–8.2).
//!
//! Because the biased autocovariance is positive semi-definite, every partial autocorrelation
//! satisfies `|c_mm| <= 1` and the fitted model is stationary. Innovation variance:
//! `sigma^2 = gamma(0) prod_m (1 - c_mm^2)`, identical to `gamma(0) - sum c_i gamma(i)`; this is
//! statsmodels `yule_walker(method="mle")` (which returns its square root), MATLAB `aryule`'s `e`
//! and spectrum `aryule`'s `P`. R's `ar.yw` reports `sigma^2 N / (N - (p + 1))` instead.

use super::recursion::{Stages, fits_from_stages, step_up};
use super::{ArError, Fit};

/// Fits of orders `0..=lagged.len()-1` from the lagged products `S(d) = sum y_t y_{t+d}` of a
/// series of `n` samples.
pub(super) fn fit_orders(lagged: &[f64], n: usize) -> Result<Vec<Fit>, ArError> {
    let gamma: Vec<f64> = lagged.iter().map(|s| s / n as f64).collect();
    fits_from_stages(&levinson_durbin(&gamma), n)
}

/// Levinson-Durbin on `gamma(0..=p)`: partial autocorrelations and prediction error powers.
/// Stages after a zero power are not meaningful; the caller rejects them.
fn levinson_durbin(gamma: &[f64]) -> Stages {
    let mut coefficients: Vec<f64> = Vec::new();
    let mut pacf = Vec::with_capacity(gamma.len());
    let mut powers = vec![gamma[0]];
    let mut power = gamma[0];
    for m in 1..gamma.len() {
        let predicted: f64 = (1..m).map(|j| coefficients[j - 1] * gamma[m - j]).sum();
        let k = (gamma[m] - predicted) / power;
        coefficients = step_up(&coefficients, k);
        power *= 1.0 - k * k;
        pacf.push(k);
        powers.push(power);
    }
    Stages {
        pacf,
        noise_variances: powers.clone(),
        powers,
    }
}
