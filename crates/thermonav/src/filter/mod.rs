//! Generic Kalman filters over small fixed-size states: sigma points, the unscented transform,
//! an unscented Kalman filter, an extended Kalman filter update in Joseph form, and
//! chi-square innovation gating. This module knows nothing of INS, GNSS or IMUs: models are
//! closures from state to state or measurement.
//!
//! Covariances are kept symmetric after every step, and every Cholesky factorisation goes
//! through [`robust_cholesky`], which adds the smallest diagonal jitter that makes a
//! numerically indefinite matrix factorisable and reports it, instead of aborting a run.

pub mod ekf;
pub mod gating;
pub mod sigma_points;
pub mod ukf;

use nalgebra::{Cholesky, SMatrix};

/// Why a filter step failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FilterError {
    /// A covariance has non-finite entries or stays indefinite even with jitter.
    #[error(
        "covariance is not positive definite (largest jitter tried {jitter:e}); the filter has diverged"
    )]
    NotPositiveDefinite {
        /// Largest jitter added to the diagonal.
        jitter: f64,
    },
    /// The innovation covariance cannot be inverted.
    #[error("innovation covariance is singular")]
    SingularInnovation,
    /// A state or covariance became non-finite.
    #[error("non-finite value in the {what}")]
    NonFinite {
        /// Which quantity.
        what: &'static str,
    },
}

/// (P + Pᵀ)/2: removes the asymmetry that rounding leaves after products.
pub fn symmetrize<const N: usize>(p: &SMatrix<f64, N, N>) -> SMatrix<f64, N, N> {
    (p + p.transpose()) * 0.5
}

/// Cholesky factor of `p`, adding jitter ε·(mean diagonal)·10^k, k = 0..8 with ε = 1e-12, to
/// the diagonal when the plain factorisation fails. Returns the factorisation and the jitter
/// used (0 when none was needed).
///
/// # Errors
/// [`FilterError::NotPositiveDefinite`] when `p` has non-finite entries or no jitter up to
/// 1e-4 of its mean diagonal helps.
pub fn robust_cholesky<const N: usize>(
    p: &SMatrix<f64, N, N>,
) -> Result<(Cholesky<f64, nalgebra::Const<N>>, f64), FilterError> {
    if p.iter().any(|v| !v.is_finite()) {
        return Err(FilterError::NotPositiveDefinite { jitter: 0.0 });
    }
    let sym = symmetrize(p);
    if let Some(c) = Cholesky::new(sym) {
        return Ok((c, 0.0));
    }
    let scale = (sym.trace() / N as f64).abs().max(f64::MIN_POSITIVE);
    let mut jitter = 0.0;
    for k in 0..9 {
        jitter = 1e-12 * scale * 10f64.powi(k);
        let mut trial = sym;
        for i in 0..N {
            trial[(i, i)] += jitter;
        }
        if let Some(c) = Cholesky::new(trial) {
            return Ok((c, jitter));
        }
    }
    Err(FilterError::NotPositiveDefinite { jitter })
}
