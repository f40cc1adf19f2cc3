//! The order recursion shared by Yule-Walker and Burg: the step-up from partial
//! autocorrelations (reflection coefficients) to AR coefficients, the model's autocorrelation,
//! and the asymptotic standard errors of the coefficients.

use nalgebra::DMatrix;

use super::{ArError, Fit};

/// Levinson step-up in the paper's sign: `c^(m)_j = c^(m-1)_j - k c^(m-1)_{m-j}`,
/// `c^(m)_m = k`, with `k = c_mm` the partial autocorrelation of stage `m`.
pub(super) fn step_up(previous: &[f64], k: f64) -> Vec<f64> {
    let m = previous.len() + 1;
    let mut next: Vec<f64> = (0..m - 1)
        .map(|j| previous[j] - k * previous[m - 2 - j])
        .collect();
    next.push(k);
    next
}

/// The per-stage results of an order recursion, for orders `0..=p`.
pub(super) struct Stages {
    /// Partial autocorrelations `c_11..c_pp`.
    pub pacf: Vec<f64>,
    /// Recursion powers `P_0..P_p`, `P_m = P_{m-1} (1 - c_mm^2)`.
    pub powers: Vec<f64>,
    /// The estimator's reported innovation variance per order, `0..=p`.
    pub noise_variances: Vec<f64>,
}

/// One [`Fit`] per order `0..=p`, with asymptotic standard errors on `n` samples.
///
/// # Errors
/// [`ArError::ZeroInnovationVariance`] at the first order whose variance is not positive.
pub(super) fn fits_from_stages(stages: &Stages, n: usize) -> Result<Vec<Fit>, ArError> {
    let mut coefficients = Vec::new();
    let mut fits = Vec::with_capacity(stages.powers.len());
    for order in 0..stages.powers.len() {
        if order > 0 {
            coefficients = step_up(&coefficients, stages.pacf[order - 1]);
        }
        fits.push(stage_fit(stages, order, coefficients.clone(), n)?);
    }
    Ok(fits)
}

/// The fit of one order of the recursion.
fn stage_fit(
    stages: &Stages,
    order: usize,
    coefficients: Vec<f64>,
    n: usize,
) -> Result<Fit, ArError> {
    let power = stages.powers[order];
    let noise_variance = stages.noise_variances[order];
    if !(power > 0.0 && noise_variance > 0.0) {
        return Err(ArError::ZeroInnovationVariance { order });
    }
    let pacf = stages.pacf[..order].to_vec();
    Ok(Fit {
        std_errors: asymptotic_std_errors(&pacf, n)?,
        coefficients,
        noise_variance,
        recursion_power: Some(power),
        partial_autocorrelation: Some(pacf),
        intercept: None,
    })
}

/// `sqrt(diag(sigma^2 Gamma_p^-1 / n))` for the AR model with these partial autocorrelations,
/// `Gamma_p` its `p x p` autocovariance matrix and `sigma^2` its innovation variance (the ratio
/// does not depend on the scale, so both come from the normalised recursion, `P_0 = 1`).
/// Brockwell & Davis (1991), Theorem 8.1.1; for AR(1), `sqrt((1 - c^2) / n)`.
pub(super) fn asymptotic_std_errors(pacf: &[f64], n: usize) -> Result<Vec<f64>, ArError> {
    let p = pacf.len();
    if p == 0 {
        return Ok(Vec::new());
    }
    let (rho, power) = model_autocorrelation(pacf);
    let gamma = DMatrix::from_fn(p, p, |i, j| rho[i.abs_diff(j)]);
    let inverse = gamma
        .cholesky()
        .ok_or(ArError::ZeroInnovationVariance { order: p })?
        .inverse();
    Ok((0..p)
        .map(|i| (power * inverse[(i, i)] / n as f64).max(0.0).sqrt())
        .collect())
}

/// Autocorrelation `rho_0..rho_p` of the AR model given by its partial autocorrelations, and
/// its normalised innovation variance `prod (1 - c_mm^2)` (inverse Levinson:
/// `rho_m = c_mm P_{m-1} + sum_{j<m} c^(m-1)_j rho_{m-j}`).
pub(super) fn model_autocorrelation(pacf: &[f64]) -> (Vec<f64>, f64) {
    let mut rho = vec![1.0];
    let mut coefficients: Vec<f64> = Vec::new();
    let mut power = 1.0;
    for &k in pacf {
        let m = rho.len();
        let predicted: f64 = (1..m).map(|j| coefficients[j - 1] * rho[m - j]).sum();
        rho.push(k * power + predicted);
        coefficients = step_up(&coefficients, k);
        power *= 1.0 - k * k;
    }
    (rho, power)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ar2_model_autocorrelation_matches_closed_form() {
        // AR(2) c = (0.5, 0.3): rho_1 = c1 / (1 - c2), rho_2 = c1 rho_1 + c2 (Box & Jenkins 3.2.37);
        // its partial autocorrelations are rho_1 and c2.
        let (c1, c2) = (0.5, 0.3);
        let rho1 = c1 / (1.0 - c2);
        let (rho, _) = model_autocorrelation(&[rho1, c2]);
        assert!((rho[1] - rho1).abs() < 1e-15);
        assert!((rho[2] - (c1 * rho1 + c2)).abs() < 1e-15);
        let c = step_up(&step_up(&[], rho1), c2);
        assert!((c[0] - c1).abs() < 1e-15 && (c[1] - c2).abs() < 1e-15);
    }
}
