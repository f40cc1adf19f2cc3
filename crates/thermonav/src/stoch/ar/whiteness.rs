//! The Ljung-Box portmanteau test of residual whiteness (Ljung & Box 1978):
//! Q = n (n + 2) Σ_{k=1}^{h} ρ̂_k² / (n − k), compared with χ² on h − p degrees of freedom
//! (p fitted coefficients; statsmodels `acorr_ljungbox(resid, lags=[h], model_df=p)`).

use crate::stoch::acf::{AcfError, Demean, autocorrelation};
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// Result of the test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LjungBox {
    /// Q statistic.
    pub statistic: f64,
    /// Lags summed, h.
    pub lags: usize,
    /// Degrees of freedom, h − p.
    pub dof: usize,
    /// P(χ²_dof ≥ Q); `None` when h ≤ p leaves no degree of freedom.
    pub p_value: Option<f64>,
}

/// Ljung-Box test of `residuals` at `lags`, with `fitted` parameters removed from the degrees of
/// freedom.
///
/// # Errors
/// [`AcfError`] when the residuals are too short, not finite or constant.
pub fn ljung_box(residuals: &[f64], lags: usize, fitted: usize) -> Result<LjungBox, AcfError> {
    let rho = autocorrelation(residuals, lags, Demean::Subtract)?;
    let n = residuals.len() as f64;
    let statistic = n
        * (n + 2.0)
        * (1..=lags)
            .map(|k| rho[k] * rho[k] / (n - k as f64))
            .sum::<f64>();
    let dof = lags.saturating_sub(fitted);
    let p_value = (dof > 0)
        .then(|| ChiSquared::new(dof as f64).ok())
        .flatten()
        .map(|chi| chi.sf(statistic));
    Ok(LjungBox {
        statistic,
        lags,
        dof,
        p_value,
    })
}
