//! The least-squares AR estimators (Kay 1988, §7.5; Marple 1987, ch. 8).
//!
//! Covariance method: minimise Σ_{k=p}^{N−1} (x_k − Σ c_i x_{k−i})² over the data without any
//! windowing. Modified covariance: add the backward errors Σ (x_{k−p} − Σ c_i x_{k−p+i})².
//! The normal equations are accumulated in one pass (O(N p²)) and solved by LU.

use super::{ArError, ArMethod, ArModel};
use nalgebra::{DMatrix, DVector};

/// Whether the regression carries a constant term.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Intercept {
    /// A constant is estimated with the coefficients (as Stata's `regress y L(1/p).y`).
    Included,
    /// No constant (the series is taken as zero-mean).
    Excluded,
}

/// A conditional least-squares AR fit.
#[derive(Debug, Clone, PartialEq)]
pub struct ConditionalOls {
    /// Parameters: the constant first when included, then c_1..c_p.
    pub params: Vec<f64>,
    /// Their standard errors, √diag(s² (XᵀX)⁻¹).
    pub std_errors: Vec<f64>,
    /// Residual sum of squares.
    pub rss: f64,
    /// Number of regression rows, N − p.
    pub n_obs: usize,
    /// s = √(RSS / (N − p − k)), k the number of parameters.
    pub rmse: f64,
}

/// Regressor row k: [1?, x_{k−1}, …, x_{k−p}].
fn forward_row(
    x: &[f64],
    k: usize,
    order: usize,
    intercept: Intercept,
) -> impl Iterator<Item = f64> + '_ {
    let constant = (intercept == Intercept::Included).then_some(1.0);
    constant
        .into_iter()
        .chain((1..=order).map(move |i| x[k - i]))
}

/// Conditional OLS of x_k on its p predecessors (and a constant), k = p..N−1.
///
/// # Errors
/// [`ArError`] for too few samples, non-finite values or a singular system.
pub fn conditional_ols(
    x: &[f64],
    order: usize,
    intercept: Intercept,
) -> Result<ConditionalOls, ArError> {
    let k_params = order + usize::from(intercept == Intercept::Included);
    if order == 0 {
        return Err(ArError::ZeroOrder);
    }
    if x.len() < order + k_params + 1 {
        return Err(ArError::TooShort {
            samples: x.len(),
            order,
            needed: order + k_params + 1,
        });
    }
    if let Some(index) = x.iter().position(|v| !v.is_finite()) {
        return Err(ArError::NonFinite { index });
    }
    let mut xtx = DMatrix::<f64>::zeros(k_params, k_params);
    let mut xty = DVector::<f64>::zeros(k_params);
    let mut row = vec![0.0; k_params];
    for k in order..x.len() {
        row.iter_mut()
            .zip(forward_row(x, k, order, intercept))
            .for_each(|(r, v)| *r = v);
        accumulate_upper(&mut xtx, &mut xty, &row, x[k]);
    }
    mirror(&mut xtx);
    let params = solve(&xtx, &xty, order)?;
    let rss: f64 = (order..x.len())
        .map(|k| {
            x[k] - forward_row(x, k, order, intercept)
                .zip(params.iter())
                .map(|(a, b)| a * b)
                .sum::<f64>()
        })
        .map(|e| e * e)
        .sum();
    let n_obs = x.len() - order;
    let s2 = rss / (n_obs - k_params) as f64;
    let inverse = xtx
        .clone()
        .try_inverse()
        .ok_or(ArError::Singular { order })?;
    Ok(ConditionalOls {
        std_errors: (0..k_params)
            .map(|i| (s2 * inverse[(i, i)]).max(0.0).sqrt())
            .collect(),
        params: params.iter().copied().collect(),
        rss,
        n_obs,
        rmse: s2.sqrt(),
    })
}

fn solve(a: &DMatrix<f64>, b: &DVector<f64>, order: usize) -> Result<DVector<f64>, ArError> {
    let solution = a.clone().lu().solve(b).ok_or(ArError::Singular { order })?;
    if solution.iter().all(|v| v.is_finite()) {
        Ok(solution)
    } else {
        Err(ArError::Singular { order })
    }
}

/// Covariance (forward) or modified covariance (forward + backward) estimate on centred data.
pub(super) fn covariance(c: &[f64], order: usize, backward: bool) -> Result<ArModel, ArError> {
    if c.len() < 2 * order + 1 {
        return Err(ArError::TooShort {
            samples: c.len(),
            order,
            needed: 2 * order + 1,
        });
    }
    let mut a = DMatrix::<f64>::zeros(order, order);
    let mut b = DVector::<f64>::zeros(order);
    let mut row = vec![0.0; order];
    for k in order..c.len() {
        row.iter_mut()
            .enumerate()
            .for_each(|(i, r)| *r = c[k - 1 - i]);
        accumulate_upper(&mut a, &mut b, &row, c[k]);
        if backward {
            row.iter_mut()
                .enumerate()
                .for_each(|(i, r)| *r = c[k - order + 1 + i]);
            accumulate_upper(&mut a, &mut b, &row, c[k - order]);
        }
    }
    mirror(&mut a);
    let coefficients = solve(&a, &b, order)?;
    let rows = (c.len() - order) * if backward { 2 } else { 1 };
    let rss = residual_power(c, coefficients.as_slice(), backward);
    let s2 = rss / (rows - order) as f64;
    let inverse = a.try_inverse().ok_or(ArError::Singular { order })?;
    Ok(ArModel {
        method: if backward {
            ArMethod::ModifiedCovariance
        } else {
            ArMethod::Covariance
        },
        coefficients: coefficients.iter().copied().collect(),
        noise_variance: rss / rows as f64,
        levinson_variance: None,
        reflection: None,
        std_errors: (0..order)
            .map(|i| (s2 * inverse[(i, i)]).max(0.0).sqrt())
            .collect(),
        n_samples: c.len(),
        mean: 0.0,
    })
}

/// Lower triangle and right-hand side of the normal equations (mirrored once at the end).
fn accumulate_upper(a: &mut DMatrix<f64>, b: &mut DVector<f64>, row: &[f64], y: f64) {
    for i in 0..row.len() {
        b[i] += row[i] * y;
        let ri = row[i];
        for j in 0..=i {
            a[(i, j)] += ri * row[j];
        }
    }
}

fn mirror(a: &mut DMatrix<f64>) {
    for i in 0..a.nrows() {
        for j in 0..i {
            a[(j, i)] = a[(i, j)];
        }
    }
}

/// Σ forward squared errors, plus the backward ones for the modified method.
fn residual_power(c: &[f64], coefficients: &[f64], backward: bool) -> f64 {
    let p = coefficients.len();
    (p..c.len())
        .map(|k| {
            let f = c[k]
                - coefficients
                    .iter()
                    .enumerate()
                    .map(|(i, ci)| ci * c[k - 1 - i])
                    .sum::<f64>();
            let b = if backward {
                c[k - p]
                    - coefficients
                        .iter()
                        .enumerate()
                        .map(|(i, ci)| ci * c[k - p + 1 + i])
                        .sum::<f64>()
            } else {
                0.0
            };
            f * f + b * b
        })
        .sum()
}
