//! Yule-Walker by the Levinson-Durbin recursion (Brockwell & Davis 1991, §5.2; Kay 1988, §7.3).
//!
//! For m = 1..p: k_m = (γ(m) − Σ_{i<m} c_i γ(m−i)) / E_{m−1}, c_i ← c_i − k_m c_{m−i},
//! c_m = k_m, E_m = E_{m−1}(1 − k_m²), E_0 = γ(0). The k_m are the partial autocorrelations.

use super::{ArError, ArMethod, ArModel};

/// Coefficients (paper sign), reflection coefficients and final prediction-error variance of
/// the AR(p) model with autocovariance `gamma` (γ(0..=p)).
pub fn levinson_durbin(gamma: &[f64], order: usize) -> (Vec<f64>, Vec<f64>, f64) {
    let mut c: Vec<f64> = Vec::with_capacity(order);
    let mut reflection = Vec::with_capacity(order);
    let mut error = gamma[0];
    for m in 1..=order {
        let acc: f64 = c
            .iter()
            .enumerate()
            .map(|(i, ci)| ci * gamma[m - 1 - i])
            .sum();
        let k = if error > 0.0 {
            (gamma[m] - acc) / error
        } else {
            0.0
        };
        let previous = c.clone();
        for i in 0..c.len() {
            c[i] = previous[i] - k * previous[m - 2 - i];
        }
        c.push(k);
        reflection.push(k);
        error *= 1.0 - k * k;
    }
    (c, reflection, error)
}

/// Yule-Walker from the lagged products r(0..=p) of a demeaned series of `n` samples.
pub(super) fn yule_walker(products: &[f64], n: usize, order: usize) -> Result<ArModel, ArError> {
    let gamma: Vec<f64> = products.iter().map(|v| v / n as f64).collect();
    if gamma[0] <= 0.0 {
        return Err(ArError::Constant);
    }
    let (coefficients, reflection, variance) = levinson_durbin(&gamma, order);
    Ok(ArModel {
        method: ArMethod::YuleWalker,
        coefficients,
        noise_variance: variance,
        levinson_variance: Some(variance),
        reflection: Some(reflection),
        std_errors: Vec::new(),
        n_samples: n,
        mean: 0.0,
    })
}
