//! A small Levenberg-Marquardt minimiser of Σ r_i(θ)² with a central-difference Jacobian
//! (Marquardt 1963, with his scaling of the damping by diag(JᵀJ); Nocedal & Wright 2006, §10.3).
//!
//! Beside it, [`super::nelder_mead`] is two-dimensional; GMWM's fit needs up to a dozen
//! coordinates and has a least-squares structure, which LM exploits.

use nalgebra::{DMatrix, DVector};

/// Settings of the minimiser.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmSettings {
    /// Iterations at most.
    pub max_iterations: usize,
    /// Stop when an accepted step lowers the cost by less than this fraction.
    pub relative_tolerance: f64,
    /// Central-difference step in each coordinate.
    pub step: f64,
}

impl Default for LmSettings {
    fn default() -> Self {
        LmSettings {
            max_iterations: 200,
            relative_tolerance: 1e-12,
            step: 1e-5,
        }
    }
}

/// The minimiser's result.
#[derive(Debug, Clone, PartialEq)]
pub struct LmResult {
    /// The coordinates at the minimum found.
    pub x: Vec<f64>,
    /// Σ r² there.
    pub cost: f64,
    /// Iterations taken.
    pub iterations: usize,
}

/// Residuals r(x) to minimise Σ r_i² over, and their Jacobian.
pub trait LeastSquares {
    /// r(x).
    fn residuals(&self, x: &[f64]) -> Vec<f64>;

    /// The central-difference Jacobian ∂r_i/∂x_k ≈ (r_i(x + h e_k) − r_i(x − h e_k)) / 2h, an
    /// `n_residuals` × `x.len()` matrix. A problem whose residuals at x ± h e_k it can form
    /// more cheaply overrides this with the same values.
    fn jacobian(&self, x: &[f64], n_residuals: usize, step: f64) -> DMatrix<f64> {
        let mut probe = x.to_vec();
        central_differences(x, n_residuals, step, |k, h| {
            probe[k] = x[k] + h;
            let r = self.residuals(&probe);
            probe[k] = x[k];
            r
        })
    }
}

/// A function x ↦ r(x) as a [`LeastSquares`] problem with the generic Jacobian.
impl<F: Fn(&[f64]) -> Vec<f64>> LeastSquares for F {
    fn residuals(&self, x: &[f64]) -> Vec<f64> {
        self(x)
    }
}

/// The `n_residuals` × `x.len()` central-difference Jacobian from `shifted(k, h)`, the residuals
/// at x + h e_k (h = ±`step`).
pub fn central_differences(
    x: &[f64],
    n_residuals: usize,
    step: f64,
    mut shifted: impl FnMut(usize, f64) -> Vec<f64>,
) -> DMatrix<f64> {
    let mut jacobian = DMatrix::zeros(n_residuals, x.len());
    for k in 0..x.len() {
        let up = shifted(k, step);
        let down = shifted(k, -step);
        for i in 0..n_residuals {
            jacobian[(i, k)] = (up[i] - down[i]) / (2.0 * step);
        }
    }
    jacobian
}

/// Σ r², infinite when not finite.
fn cost_of(r: &[f64]) -> f64 {
    let c: f64 = r.iter().map(|v| v * v).sum();
    if c.is_finite() { c } else { f64::INFINITY }
}

/// Minimises Σ r_i(x)² from `start`. Non-finite residuals count as an infinite cost (the step
/// is refused and the damping raised).
pub fn minimise(problem: &impl LeastSquares, start: &[f64], settings: LmSettings) -> LmResult {
    let mut x = start.to_vec();
    let mut r = problem.residuals(&x);
    let mut cost = cost_of(&r);
    let mut lambda = 1e-3;
    let mut iterations = 0;
    while iterations < settings.max_iterations && cost.is_finite() && cost > 0.0 {
        iterations += 1;
        let jacobian = problem.jacobian(&x, r.len(), settings.step);
        let (normal, gradient) = normal_equations(&jacobian, &r);
        let mut improved = false;
        for _ in 0..30 {
            let Some(delta) = damped_step(&normal, &gradient, lambda) else {
                lambda *= 10.0;
                continue;
            };
            let trial: Vec<f64> = x.iter().zip(delta.iter()).map(|(a, d)| a + d).collect();
            let trial_r = problem.residuals(&trial);
            let trial_cost = cost_of(&trial_r);
            if trial_cost < cost {
                let gain = (cost - trial_cost) / cost;
                (x, cost, r) = (trial, trial_cost, trial_r);
                lambda = (lambda / 3.0).max(1e-12);
                improved = gain > settings.relative_tolerance;
                break;
            }
            lambda *= 4.0;
        }
        if !improved {
            break;
        }
    }
    LmResult {
        x,
        cost,
        iterations,
    }
}

fn normal_equations(jacobian: &DMatrix<f64>, r: &[f64]) -> (DMatrix<f64>, DVector<f64>) {
    let residual = DVector::from_column_slice(r);
    (
        jacobian.transpose() * jacobian,
        jacobian.transpose() * residual,
    )
}

/// δ solving (JᵀJ + λ diag(JᵀJ) + λ·10⁻⁹ I) δ = −Jᵀr, or `None` if that matrix is not
/// positive definite or the step is not finite.
fn damped_step(normal: &DMatrix<f64>, gradient: &DVector<f64>, lambda: f64) -> Option<Vec<f64>> {
    let mut damped = normal.clone();
    let scale = normal.diagonal().max().max(1e-300);
    for k in 0..normal.nrows() {
        damped[(k, k)] += lambda * normal[(k, k)] + lambda * 1e-9 * scale;
    }
    let delta = damped.cholesky()?.solve(&(-gradient));
    delta
        .iter()
        .all(|d| d.is_finite())
        .then(|| delta.iter().copied().collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_rosenbrock_minimum() {
        // r = (10 (y − x²), 1 − x): the banana valley, minimum 0 at (1, 1).
        let result = minimise(
            &|p: &[f64]| vec![10.0 * (p[1] - p[0] * p[0]), 1.0 - p[0]],
            &[-1.2, 1.0],
            LmSettings::default(),
        );
        assert!((result.x[0] - 1.0).abs() < 1e-6 && (result.x[1] - 1.0).abs() < 1e-6);
        assert!(result.cost < 1e-12, "cost {}", result.cost);
    }

    #[test]
    fn fits_an_exponential_decay() {
        // y = 3 e^{−0.4 t} sampled exactly: coordinates (ln 3, ln 0.4) recovered to 1e-8.
        let t: Vec<f64> = (0..20).map(f64::from).collect();
        let model = |p: &[f64], t: f64| p[0].exp() * (-p[1].exp() * t).exp();
        let truth = [3f64.ln(), 0.4f64.ln()];
        let data: Vec<f64> = t.iter().map(|&t| model(&truth, t)).collect();
        let residuals = |p: &[f64]| -> Vec<f64> {
            t.iter().zip(&data).map(|(&t, d)| model(p, t) - d).collect()
        };
        let result = minimise(&residuals, &[0.0, 0.0], LmSettings::default());
        assert!((result.x[0] - truth[0]).abs() < 1e-8, "{:?}", result.x);
        assert!((result.x[1] - truth[1]).abs() < 1e-8, "{:?}", result.x);
    }
}
