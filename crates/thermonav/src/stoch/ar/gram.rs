//! Windowed lagged-product (Gram) matrices, from the full lagged products plus end corrections.
//!
//! The covariance-method normal equations, the forward-backward ones and Burg's error energies
//! are all quadratic forms in
//!
//! ```text
//! Phi_m(i, j) = sum_{t=m}^{N-1} y_{t-i} y_{t-j},     i, j = 0..=m,
//! ```
//!
//! the Gram matrix of the vectors `(y_t, y_{t-1}, ..., y_{t-m})` over the window where all are
//! defined. Column 0 is the full lagged product `S(i) = sum_{t=i}^{N-1} y_{t-i} y_t` minus the
//! `m - i` products that fall before the window; every other element follows along its diagonal:
//! `Phi(i+1, j+1) = Phi(i, j) + y_{m-1-i} y_{m-1-j} - y_{N-1-i} y_{N-1-j}` (the window slides by
//! one sample). Cost `O(m^2)` given `S(0..=m)`, instead of `O(N m^2)`.

use nalgebra::{DMatrix, DVector};

use super::Centred;

/// `Phi_m` (see the module docs). Requires `m < y.len()` and `lagged.len() > m`.
pub(super) fn windowed_gram(y: Centred<'_>, lagged: &[f64], m: usize) -> DMatrix<f64> {
    let n = y.len();
    let mut phi = DMatrix::zeros(m + 1, m + 1);
    for i in 0..=m {
        let before_window: f64 = (i..m).map(|t| y.at(t - i) * y.at(t)).sum();
        phi[(i, 0)] = lagged[i] - before_window;
    }
    for j in 1..=m {
        for i in j..=m {
            phi[(i, j)] =
                phi[(i - 1, j - 1)] + y.at(m - i) * y.at(m - j) - y.at(n - i) * y.at(n - j);
        }
    }
    phi.fill_upper_triangle_with_lower_triangle();
    phi
}

/// Windowed sums `s_i = sum_{t=m}^{N-1} y_{t-i}`, `i = 0..=m` (the regressor sums an intercept
/// column needs). Requires `m < y.len()`.
pub(super) fn windowed_sums(y: Centred<'_>, m: usize) -> DVector<f64> {
    let n = y.len();
    let total = y.sum();
    DVector::from_fn(m + 1, |i, _| {
        let before: f64 = (0..m - i).map(|t| y.at(t)).sum();
        let after: f64 = (n - i..n).map(|t| y.at(t)).sum();
        total - before - after
    })
}

/// Largest diagonal element: the scale against which a quadratic form's cancellation is judged.
pub(super) fn max_diagonal(phi: &DMatrix<f64>) -> f64 {
    phi.diagonal().iter().fold(0.0, |acc: f64, v| acc.max(*v))
}

/// A quadratic form in `Phi` that should equal `energy` has lost too much to cancellation when
/// the scale of its terms, `(sum |v_i|)^2 max_i Phi_ii`, exceeds `energy` by more than this:
/// with rounding of relative size 1e-16 in `Phi`, the result keeps about 11 significant digits.
pub(super) const CANCELLATION_LIMIT: f64 = 1e4;

/// True when `energy` (a quadratic form with vectors of absolute sum `abs_sum`) cannot be
/// trusted to about 1e-11 relative, or is not positive.
pub(super) fn cancels_badly(energy: f64, abs_sum: f64, scale: f64) -> bool {
    !(energy > 0.0 && energy * CANCELLATION_LIMIT >= abs_sum * abs_sum * scale)
}
