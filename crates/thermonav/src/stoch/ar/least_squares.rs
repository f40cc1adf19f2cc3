//! Least-squares AR estimators over the data without windowing (Marple 1987, ch. 8;
//! Kay 1988, §7.4).
//!
//! - Covariance method (conditional least squares): minimise the forward prediction errors
//!   `sum_{t=p}^{N-1} (y_t - c_0 - sum_i c_i y_{t-i})^2` (`c_0` only with an intercept). This is
//!   the regression of `y_t` on its `p` lags, i.e. statsmodels `AutoReg`, Stata `regress y L(1/p).y`,
//!   and, with an intercept, the OLS partial autocorrelation (statsmodels `pacf_ols`, MATLAB
//!   `parcorr`) as the last coefficient.
//!   `noise_variance = RSS / (N - p)`; covariance of the estimates `noise_variance (X'X)^-1`.
//! - Modified covariance (forward-backward least squares): minimise the forward errors above
//!   plus the backward errors `sum_{t=p}^{N-1} (y_{t-p} - sum_i c_i y_{t-p+i})^2` with the same
//!   coefficients (a stationary process looks the same reversed).
//!   `noise_variance = (RSS_f + RSS_b) / (2 (N - p))`; covariance `2 noise_variance (X'X)^-1`
//!   with `X` the stacked system (see [`super::ArModel::coefficient_std_errors`]).
//!
//! The normal equations come from the windowed Gram matrix ([`super::gram`]) in `O(p^2)` after
//! the one `O(N p)` pass of lagged products; they are solved by Cholesky. The residual sum of
//! squares is the quadratic form `Phi_00 - b' theta`, recomputed from explicit residuals when
//! that would cancel badly.

use nalgebra::{DMatrix, DVector};

use super::gram::{cancels_badly, max_diagonal, windowed_gram, windowed_sums};
use super::{
    ArError, Fit, Intercept, MeanModel, Prepared, backward_prediction_errors, prediction_errors,
};

/// Covariance-method fits of orders `min_order..=max_order`.
pub(super) fn fit_covariance_orders(
    data: &Prepared,
    mean: MeanModel,
    min_order: usize,
    max_order: usize,
) -> Result<Vec<Fit>, ArError> {
    (min_order..=max_order)
        .map(|p| fit_covariance(data, mean == MeanModel::Intercept, p))
        .collect()
}

/// Modified-covariance fits of orders `min_order..=max_order`.
pub(super) fn fit_modified_covariance_orders(
    data: &Prepared,
    min_order: usize,
    max_order: usize,
) -> Result<Vec<Fit>, ArError> {
    (min_order..=max_order)
        .map(|p| fit_modified_covariance(data, p))
        .collect()
}

/// Normal equations `A theta = b` of a least-squares problem, with `target_energy` the sum of
/// squares of the target, `rows` the number of equations and `abs_sum_scale` the Gram scale.
struct NormalEquations {
    a: DMatrix<f64>,
    b: DVector<f64>,
    target_energy: f64,
    scale: f64,
}

/// Covariance method of order `p`, with or without an intercept column (first unknown).
fn fit_covariance(data: &Prepared, intercept: bool, p: usize) -> Result<Fit, ArError> {
    let y = data.y;
    let phi = windowed_gram(y, &data.lagged[..=p], p);
    let equations = covariance_equations(&phi, intercept.then(|| windowed_sums(y, p)), y.len() - p);
    let (theta, inverse) = solve_spd(&equations, p)?;
    let (constant, coefficients) = split_intercept(&theta, intercept);
    let rss = residual_energy(&equations, &theta, &coefficients, || {
        sum_of_squares(&prediction_errors(&y.to_vec(), &coefficients, constant))
    });
    let noise_variance = positive_variance(rss / (y.len() - p) as f64, p)?;
    let covariance = inverse * noise_variance;
    Ok(Fit {
        std_errors: lag_std_errors(&covariance, intercept),
        intercept: intercept
            .then(|| intercept_in_x_units(&covariance, constant, &coefficients, y.mean)),
        coefficients,
        noise_variance,
        recursion_power: None,
        partial_autocorrelation: None,
    })
}

/// Modified covariance (forward-backward) of order `p`.
fn fit_modified_covariance(data: &Prepared, p: usize) -> Result<Fit, ArError> {
    let y = data.y;
    let phi = windowed_gram(y, &data.lagged[..=p], p);
    let equations = forward_backward_equations(&phi);
    let (theta, inverse) = solve_spd(&equations, p)?;
    let coefficients: Vec<f64> = theta.iter().copied().collect();
    let rss = residual_energy(&equations, &theta, &coefficients, || {
        let y_all = y.to_vec();
        sum_of_squares(&prediction_errors(&y_all, &coefficients, 0.0))
            + sum_of_squares(&backward_prediction_errors(&y_all, &coefficients))
    });
    let noise_variance = positive_variance(rss / (2 * (y.len() - p)) as f64, p)?;
    let covariance = inverse * (2.0 * noise_variance);
    Ok(Fit {
        std_errors: lag_std_errors(&covariance, false),
        coefficients,
        noise_variance,
        recursion_power: None,
        partial_autocorrelation: None,
        intercept: None,
    })
}

/// Forward normal equations: regressors `y_{t-1..t-p}` (Gram rows 1..=p), target `y_t` (row 0),
/// optionally preceded by a constant regressor with windowed sums `sums` over `rows` equations.
fn covariance_equations(
    phi: &DMatrix<f64>,
    sums: Option<DVector<f64>>,
    rows: usize,
) -> NormalEquations {
    let p = phi.nrows() - 1;
    let lags = phi.view((1, 1), (p, p)).into_owned();
    let cross = phi.view((1, 0), (p, 1)).column(0).into_owned();
    let (a, b) = match sums {
        None => (lags, cross),
        Some(s) => with_intercept_column(&lags, &cross, &s, rows),
    };
    NormalEquations {
        a,
        b,
        target_energy: phi[(0, 0)],
        scale: max_diagonal(phi),
    }
}

/// Borders the lag block with the constant regressor: `[[rows, s_1..s_p], [s, lags]]` and
/// right-hand side `[s_0, cross]`.
fn with_intercept_column(
    lags: &DMatrix<f64>,
    cross: &DVector<f64>,
    sums: &DVector<f64>,
    rows: usize,
) -> (DMatrix<f64>, DVector<f64>) {
    let p = lags.nrows();
    let a = DMatrix::from_fn(p + 1, p + 1, |i, j| match (i, j) {
        (0, 0) => rows as f64,
        (0, j) => sums[j],
        (i, 0) => sums[i],
        (i, j) => lags[(i - 1, j - 1)],
    });
    let b = DVector::from_fn(p + 1, |i, _| if i == 0 { sums[0] } else { cross[i - 1] });
    (a, b)
}

/// Forward-backward normal equations: `A(i,j) = Phi(i,j) + Phi(p-i,p-j)`,
/// `b(j) = Phi(0,j) + Phi(p,p-j)`, `i, j = 1..=p`; target energy `Phi(0,0) + Phi(p,p)`.
fn forward_backward_equations(phi: &DMatrix<f64>) -> NormalEquations {
    let p = phi.nrows() - 1;
    NormalEquations {
        a: DMatrix::from_fn(p, p, |i, j| {
            phi[(i + 1, j + 1)] + phi[(p - 1 - i, p - 1 - j)]
        }),
        b: DVector::from_fn(p, |j, _| phi[(0, j + 1)] + phi[(p, p - 1 - j)]),
        target_energy: phi[(0, 0)] + phi[(p, p)],
        scale: 2.0 * max_diagonal(phi),
    }
}

/// Solves `A theta = b` by Cholesky; returns `theta` and `A^-1`.
///
/// # Errors
/// [`ArError::Singular`] when `A` is not numerically positive definite or the solution is not
/// finite.
fn solve_spd(
    equations: &NormalEquations,
    order: usize,
) -> Result<(DVector<f64>, DMatrix<f64>), ArError> {
    let k = equations.b.len();
    if k == 0 {
        return Ok((DVector::zeros(0), DMatrix::zeros(0, 0)));
    }
    let cholesky = equations
        .a
        .clone()
        .cholesky()
        .ok_or(ArError::Singular { order })?;
    let theta = cholesky.solve(&equations.b);
    let inverse = cholesky.inverse();
    if theta.iter().chain(inverse.iter()).all(|v| v.is_finite()) {
        Ok((theta, inverse))
    } else {
        Err(ArError::Singular { order })
    }
}

/// Splits `theta` into (constant, lag coefficients).
fn split_intercept(theta: &DVector<f64>, intercept: bool) -> (f64, Vec<f64>) {
    match intercept {
        true => (theta[0], theta.iter().skip(1).copied().collect()),
        false => (0.0, theta.iter().copied().collect()),
    }
}

/// Residual sum of squares `target_energy - b' theta`, or `direct()` (explicit residuals) when
/// that difference cancels badly.
fn residual_energy(
    equations: &NormalEquations,
    theta: &DVector<f64>,
    coefficients: &[f64],
    direct: impl FnOnce() -> f64,
) -> f64 {
    let rss = equations.target_energy - equations.b.dot(theta);
    let abs_sum = 1.0 + coefficients.iter().map(|c| c.abs()).sum::<f64>();
    if cancels_badly(rss, abs_sum, equations.scale) {
        direct()
    } else {
        rss
    }
}

/// Sum of squares.
fn sum_of_squares(v: &[f64]) -> f64 {
    v.iter().map(|e| e * e).sum()
}

/// Rejects a zero (perfect fit) innovation variance.
fn positive_variance(variance: f64, order: usize) -> Result<f64, ArError> {
    if variance > 0.0 && variance.is_finite() {
        Ok(variance)
    } else {
        Err(ArError::ZeroInnovationVariance { order })
    }
}

/// Standard errors of the lag coefficients from the estimates' covariance matrix.
fn lag_std_errors(covariance: &DMatrix<f64>, intercept: bool) -> Vec<f64> {
    let skip = usize::from(intercept);
    covariance
        .diagonal()
        .iter()
        .skip(skip)
        .map(|v| v.max(0.0).sqrt())
        .collect()
}

/// The intercept of the raw series, `c_0(x) = c_0(y) + mean (1 - sum c_i)`, and its standard
/// error `sqrt(g' Cov g)` with `g = (1, -mean, ..., -mean)` (an exact reparametrisation, so the
/// result equals OLS on the raw series).
fn intercept_in_x_units(
    covariance: &DMatrix<f64>,
    constant: f64,
    coefficients: &[f64],
    mean: f64,
) -> Intercept {
    let sum_c: f64 = coefficients.iter().sum();
    let g = DVector::from_fn(
        coefficients.len() + 1,
        |i, _| if i == 0 { 1.0 } else { -mean },
    );
    let variance = (g.transpose() * covariance * &g)[(0, 0)];
    Intercept {
        value: constant + mean * (1.0 - sum_c),
        std_error: variance.max(0.0).sqrt(),
    }
}
