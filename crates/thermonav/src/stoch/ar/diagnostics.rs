//! Residual diagnostics: the Ljung-Box portmanteau test of whiteness.

use statrs::distribution::{ChiSquared, ContinuousCDF};

use super::ArError;
use crate::stoch::acf::{self, AcfError, Demean};

/// Result of a Ljung-Box test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LjungBox {
    /// `Q = n (n + 2) sum_{k=1}^{h} rho_k^2 / (n - k)`.
    pub statistic: f64,
    /// Number of autocorrelation lags `h`.
    pub lags: usize,
    /// `h - fitted_params`, the chi-square degrees of freedom.
    pub degrees_of_freedom: usize,
    /// `P(chi^2_dof > Q)`: small values reject whiteness.
    pub p_value: f64,
}

/// Ljung-Box test (Ljung & Box 1978) that `residuals` are white, using the sample
/// autocorrelation `rho_k` (mean removed, denominator `n`) at lags `1..=lags`. For residuals of
/// an AR(p) fit pass `fitted_params = p`, so that `Q` is referred to chi-square with
/// `lags - p` degrees of freedom. Same statistic as statsmodels
/// `acorr_ljungbox(residuals, lags=[lags], model_df=fitted_params)`.
///
/// # Errors
/// [`ArError::NonFinite`], [`ArError::InvalidLags`] unless `1 <= lags < n`,
/// [`ArError::NoDegreesOfFreedom`] unless `lags > fitted_params`, [`ArError::ZeroVariance`] for
/// constant residuals, [`ArError::Overflow`].
pub fn ljung_box(
    residuals: &[f64],
    lags: usize,
    fitted_params: usize,
) -> Result<LjungBox, ArError> {
    let n_residuals = residuals.len();
    if lags == 0 || lags >= n_residuals {
        return Err(ArError::InvalidLags { lags, n_residuals });
    }
    if lags <= fitted_params {
        return Err(ArError::NoDegreesOfFreedom {
            lags,
            fitted_params,
        });
    }
    let rho = acf::autocorrelation(residuals, lags, Demean::SampleMean).map_err(|e| match e {
        AcfError::NonFinite { index, value } => ArError::NonFinite { index, value },
        AcfError::Overflow { max_abs } => ArError::Overflow { max_abs },
        AcfError::ZeroVariance { n_samples } => ArError::ZeroVariance { n_samples },
        AcfError::Empty | AcfError::MaxLagTooLarge { .. } => {
            ArError::InvalidLags { lags, n_residuals }
        }
    })?;
    let statistic = ljung_box_statistic(&rho, n_residuals);
    let degrees_of_freedom = lags - fitted_params;
    Ok(LjungBox {
        statistic,
        lags,
        degrees_of_freedom,
        p_value: chi_square_survival(statistic, degrees_of_freedom),
    })
}

/// `n (n + 2) sum_{k>=1} rho_k^2 / (n - k)`.
fn ljung_box_statistic(rho: &[f64], n: usize) -> f64 {
    let n_f = n as f64;
    let sum: f64 = rho
        .iter()
        .enumerate()
        .skip(1)
        .map(|(k, r)| r * r / (n_f - k as f64))
        .sum();
    n_f * (n_f + 2.0) * sum
}

/// `P(chi^2_dof > q)` for `dof >= 1`.
fn chi_square_survival(q: f64, dof: usize) -> f64 {
    ChiSquared::new(dof as f64).map_or(0.0, |d| d.sf(q))
}
