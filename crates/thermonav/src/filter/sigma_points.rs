//! Sigma points and weights of the unscented transform.
//!
//! Merwe's scaled points (van der Merwe 2004): λ = α²(n + κ) − n; χ₀ = x,
//! χ_i = x + (√((n+λ)P))_i, χ_{n+i} = x − (√((n+λ)P))_i; W_m0 = λ/(n+λ),
//! W_c0 = W_m0 + 1 − α² + β, W_i = 1/(2(n+λ)). Julier's original points (Julier & Uhlmann
//! 1997): λ = κ, the same points, W_0 = κ/(n+κ), W_i = 1/(2(n+κ)), W_c = W_m.
//! The matrix square root is the Cholesky factor: offset i is column i of the lower factor L
//! of (n+λ)P (equivalently row i of the upper factor Lᵀ, FilterPy's convention).

use super::{FilterError, robust_cholesky};
use nalgebra::{SMatrix, SVector};

/// Which sigma-point set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SigmaPointScheme {
    /// Merwe's scaled points.
    MerweScaled {
        /// Spread α (small: points close to the mean).
        alpha: f64,
        /// Prior knowledge of the distribution (2 is optimal for Gaussians).
        beta: f64,
        /// Secondary scaling κ (often 0 or 3 − n).
        kappa: f64,
    },
    /// Julier's original points.
    Julier {
        /// κ.
        kappa: f64,
    },
}

/// Mean and covariance weights of the 2n + 1 points.
#[derive(Debug, Clone, PartialEq)]
pub struct Weights {
    /// Weights of the mean.
    pub mean: Vec<f64>,
    /// Weights of the covariance.
    pub covariance: Vec<f64>,
}

impl SigmaPointScheme {
    /// λ for dimension `n`.
    pub fn lambda(&self, n: usize) -> f64 {
        let n = n as f64;
        match *self {
            SigmaPointScheme::MerweScaled { alpha, kappa, .. } => alpha * alpha * (n + kappa) - n,
            SigmaPointScheme::Julier { kappa } => kappa,
        }
    }

    /// The weights for dimension `n`.
    pub fn weights(&self, n: usize) -> Weights {
        let lambda = self.lambda(n);
        let c = 1.0 / (2.0 * (n as f64 + lambda));
        let mut mean = vec![c; 2 * n + 1];
        mean[0] = lambda / (n as f64 + lambda);
        let mut covariance = mean.clone();
        if let SigmaPointScheme::MerweScaled { alpha, beta, .. } = *self {
            covariance[0] = mean[0] + 1.0 - alpha * alpha + beta;
        }
        Weights { mean, covariance }
    }

    /// The 2n + 1 sigma points of (x, P).
    ///
    /// # Errors
    /// [`FilterError::NotPositiveDefinite`] when (n+λ)P cannot be factorised even with jitter.
    pub fn points<const N: usize>(
        &self,
        x: &SVector<f64, N>,
        p: &SMatrix<f64, N, N>,
    ) -> Result<Vec<SVector<f64, N>>, FilterError> {
        let scaled = p * (N as f64 + self.lambda(N));
        let (chol, _) = robust_cholesky(&scaled)?;
        let l = chol.l();
        let mut points = Vec::with_capacity(2 * N + 1);
        points.push(*x);
        points.extend((0..N).map(|i| x + l.column(i)));
        points.extend((0..N).map(|i| x - l.column(i)));
        Ok(points)
    }
}

/// The unscented transform: weighted mean and covariance of transformed points, plus additive
/// noise covariance `noise`.
pub fn unscented_transform<const M: usize>(
    points: &[SVector<f64, M>],
    weights: &Weights,
    noise: &SMatrix<f64, M, M>,
) -> (SVector<f64, M>, SMatrix<f64, M, M>) {
    let mean = points
        .iter()
        .zip(&weights.mean)
        .fold(SVector::<f64, M>::zeros(), |acc, (p, w)| acc + p * *w);
    // Accumulated in place, entry by entry, in the order of `acc + (d dᵀ) w`: the same
    // rounding as the matrix expression without its three 21 × 21 temporaries per point.
    let mut cov = *noise;
    for (p, w) in points.iter().zip(&weights.covariance) {
        let d = p - mean;
        for j in 0..M {
            for i in 0..M {
                cov[(i, j)] += d[i] * d[j] * *w;
            }
        }
    }
    (mean, super::symmetrize(&cov))
}
