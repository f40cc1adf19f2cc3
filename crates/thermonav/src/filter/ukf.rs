//! An unscented Kalman filter over a fixed-size state (Wan & van der Merwe 2000), with
//! additive process and measurement noise, in the arrangement of FilterPy's
//! `UnscentedKalmanFilter`: the update draws fresh sigma points from the predicted (x, P), so
//! that the process noise added in the prediction is represented in the points.
//!
//! Residual and mean functions are linear here; states with angles on a manifold (the INS
//! attitude) are handled by running the UKF on an error state whose mean is zero and folding
//! the estimate into the nominal state after each update.

use super::sigma_points::{SigmaPointScheme, Weights, unscented_transform};
use super::{FilterError, symmetrize};
use nalgebra::{SMatrix, SVector};

/// The filter: state estimate, covariance and sigma-point scheme.
#[derive(Debug, Clone)]
pub struct Ukf<const N: usize> {
    /// State estimate.
    pub x: SVector<f64, N>,
    /// State covariance.
    pub p: SMatrix<f64, N, N>,
    scheme: SigmaPointScheme,
    weights: Weights,
}

/// What an update did: the innovation, its covariance and the normalised innovation squared.
#[derive(Debug, Clone, PartialEq)]
pub struct Innovation<const M: usize> {
    /// z − ẑ.
    pub residual: SVector<f64, M>,
    /// Innovation covariance S.
    pub covariance: SMatrix<f64, M, M>,
    /// NIS = νᵀ S⁻¹ ν.
    pub nis: f64,
}

impl<const N: usize> Ukf<N> {
    /// A filter at (x, P) with the given sigma-point scheme.
    pub fn new(x: SVector<f64, N>, p: SMatrix<f64, N, N>, scheme: SigmaPointScheme) -> Self {
        Self {
            x,
            p,
            weights: scheme.weights(N),
            scheme,
        }
    }

    /// Propagates the sigma points through `f` and adds `q`.
    ///
    /// # Errors
    /// [`FilterError`] when P cannot be factorised or the result is not finite.
    pub fn predict(
        &mut self,
        f: impl Fn(&SVector<f64, N>) -> SVector<f64, N>,
        q: &SMatrix<f64, N, N>,
    ) -> Result<(), FilterError> {
        let points: Vec<_> = self
            .scheme
            .points(&self.x, &self.p)?
            .iter()
            .map(f)
            .collect();
        let (x, p) = unscented_transform(&points, &self.weights, q);
        check_finite(&x, &p)?;
        (self.x, self.p) = (x, p);
        Ok(())
    }

    /// Updates with measurement `z` of model `h` and noise `r`; returns the innovation.
    ///
    /// # Errors
    /// [`FilterError`] when the innovation covariance is singular or the result not finite.
    pub fn update<const M: usize>(
        &mut self,
        z: &SVector<f64, M>,
        h: impl Fn(&SVector<f64, N>) -> SVector<f64, M>,
        r: &SMatrix<f64, M, M>,
    ) -> Result<Innovation<M>, FilterError> {
        let points = self.scheme.points(&self.x, &self.p)?;
        let measured: Vec<SVector<f64, M>> = points.iter().map(h).collect();
        let (z_hat, s) = unscented_transform(&measured, &self.weights, r);
        let cross = cross_covariance(&points, &self.x, &measured, &z_hat, &self.weights);
        let s_inv = s.try_inverse().ok_or(FilterError::SingularInnovation)?;
        let gain = cross * s_inv;
        let residual = z - z_hat;
        let x = self.x + gain * residual;
        let p = symmetrize(&(self.p - gain * s * gain.transpose()));
        check_finite(&x, &p)?;
        (self.x, self.p) = (x, p);
        let nis = (residual.transpose() * s_inv * residual)[(0, 0)];
        Ok(Innovation {
            residual,
            covariance: s,
            nis,
        })
    }
}

fn cross_covariance<const N: usize, const M: usize>(
    points: &[SVector<f64, N>],
    x: &SVector<f64, N>,
    measured: &[SVector<f64, M>],
    z_hat: &SVector<f64, M>,
    weights: &Weights,
) -> SMatrix<f64, N, M> {
    points
        .iter()
        .zip(measured)
        .zip(&weights.covariance)
        .fold(SMatrix::<f64, N, M>::zeros(), |acc, ((p, m), w)| {
            acc + (p - x) * (m - z_hat).transpose() * *w
        })
}

/// Errors when a state or covariance holds a NaN or an infinity.
pub fn check_finite<const N: usize>(
    x: &SVector<f64, N>,
    p: &SMatrix<f64, N, N>,
) -> Result<(), FilterError> {
    if x.iter().any(|v| !v.is_finite()) {
        return Err(FilterError::NonFinite { what: "state" });
    }
    if p.iter().any(|v| !v.is_finite()) {
        return Err(FilterError::NonFinite { what: "covariance" });
    }
    Ok(())
}
