//! Burg's method (Burg 1967; Marple 1987, §8.5): at each stage `m` choose the reflection
//! coefficient that minimises the sum of the forward and backward prediction error energies
//! over `t = m..N-1`, then update the coefficients by the Levinson step-up. The model is always
//! stationary (`|c_mm| <= 1`) and no window is applied to the data.
//!
//! With the order-`(m-1)` forward errors `f_t` and backward errors `b_t`, the stage's partial
//! autocorrelation is `c_mm = 2 sum f_t b_{t-1} / sum (f_t^2 + b_{t-1}^2)`. Both sums are
//! quadratic forms in the prediction polynomial with the windowed Gram matrix ([`super::gram`]),
//! so after one `O(N p)` pass of lagged products every stage costs `O(m^2)` (Vos 2013). When a
//! sum would cancel badly (error energy below 1e-4 of the signal energy it comes from, as for
//! heavily low-passed data), the remaining stages run the classical recursion on explicit error
//! sequences instead (`O(N)` per stage).
//!
//! Innovation variance (see the parent module's table): `noise_variance` is the mean squared
//! forward and backward error of the order-`p` model, `(1 - c_pp^2) D_p / (2 (N - p))` with
//! `D_p` the stage's denominator: statsmodels' `burg` `sigma2`. The recursion power
//! `P_p = (sum y^2 / N) prod (1 - c_mm^2)` is spectrum's and MATLAB's `arburg` variance.

use nalgebra::{DMatrix, DVector};

use super::gram::{cancels_badly, max_diagonal, windowed_gram};
use super::recursion::{Stages, fits_from_stages, step_up};
use super::{ArError, Centred, Fit, backward_prediction_errors, prediction_errors};

/// Fits of orders `0..=lagged.len()-1` of the centred series `y`, given its lagged products.
pub(super) fn fit_orders(y: Centred<'_>, lagged: &[f64]) -> Result<Vec<Fit>, ArError> {
    fits_from_stages(&burg_stages(y, lagged), y.len())
}

/// Burg's recursion up to order `lagged.len() - 1`.
fn burg_stages(y: Centred<'_>, lagged: &[f64]) -> Stages {
    let n = y.len();
    let p = lagged.len() - 1;
    let power0 = lagged[0] / n as f64;
    let mut stages = Stages {
        pacf: Vec::with_capacity(p),
        powers: vec![power0],
        noise_variances: vec![power0],
    };
    let mut coefficients = Vec::with_capacity(p);
    for m in 1..=p {
        let phi = windowed_gram(y, &lagged[..=m], m);
        let (num, den) = gram_sums(&phi, &coefficients);
        let abs_sum = 1.0 + coefficients.iter().map(|c: &f64| c.abs()).sum::<f64>();
        if cancels_badly(den / 2.0, abs_sum, max_diagonal(&phi)) {
            continue_on_error_sequences(y, &coefficients, m..=p, &mut stages);
            break;
        }
        let k = 2.0 * num / den;
        record_stage(&mut stages, k, den, n - m);
        coefficients = step_up(&coefficients, k);
    }
    stages
}

/// `(sum f_t b_{t-1}, sum f_t^2 + b_{t-1}^2)` over `t = m..N-1` as quadratic forms in
/// `Phi_m`: `f_t = alpha' u_t`, `b_{t-1} = beta' u_t` with `u_t = (y_t, ..., y_{t-m})`,
/// `alpha = (1, -c_1, ..., -c_{m-1}, 0)` and `beta` its reverse.
fn gram_sums(phi: &DMatrix<f64>, coefficients: &[f64]) -> (f64, f64) {
    let m = coefficients.len() + 1;
    let alpha = DVector::from_fn(m + 1, |i, _| match i {
        0 => 1.0,
        i if i < m => -coefficients[i - 1],
        _ => 0.0,
    });
    let beta = DVector::from_fn(m + 1, |i, _| alpha[m - i]);
    let phi_alpha = phi * &alpha;
    let phi_beta = phi * &beta;
    (
        beta.dot(&phi_alpha),
        alpha.dot(&phi_alpha) + beta.dot(&phi_beta),
    )
}

/// Appends stage results: partial autocorrelation `k`, recursion power, and the mean squared
/// forward and backward error `(1 - k^2) den / (2 window)` of the new order.
fn record_stage(stages: &mut Stages, k: f64, den: f64, window: usize) {
    let shrink = 1.0 - k * k;
    let power = stages.powers.last().copied().unwrap_or(0.0) * shrink;
    stages.pacf.push(k);
    stages.powers.push(power);
    stages
        .noise_variances
        .push(shrink * den / (2 * window) as f64);
}

/// The classical recursion on explicit forward/backward error sequences, from the model of
/// order `stage_range.start() - 1` with `coefficients`.
fn continue_on_error_sequences(
    y: Centred<'_>,
    coefficients: &[f64],
    stage_range: std::ops::RangeInclusive<usize>,
    stages: &mut Stages,
) {
    let y_all = y.to_vec();
    let mut forward = prediction_errors(&y_all, coefficients, 0.0);
    let mut backward = backward_prediction_errors(&y_all, coefficients);
    for m in stage_range {
        let (num, den) = sequence_sums(&forward, &backward);
        let k = if den > 0.0 { 2.0 * num / den } else { 0.0 };
        record_stage(stages, k, den, y.len() - m);
        advance_errors(&mut forward, &mut backward, k);
    }
}

/// `(sum f_j b_{j-1}, sum f_j^2 + b_{j-1}^2)`, `j = 1..len`.
fn sequence_sums(forward: &[f64], backward: &[f64]) -> (f64, f64) {
    forward[1..]
        .iter()
        .zip(backward)
        .fold((0.0, 0.0), |(num, den), (f, b)| {
            (num + f * b, den + f * f + b * b)
        })
}

/// Errors of the next order: `f'_j = f_{j+1} - k b_j`, `b'_j = b_j - k f_{j+1}`; one shorter.
fn advance_errors(forward: &mut Vec<f64>, backward: &mut Vec<f64>, k: f64) {
    for j in 1..forward.len() {
        let (f, b) = (forward[j], backward[j - 1]);
        forward[j - 1] = f - k * b;
        backward[j - 1] = b - k * f;
    }
    forward.pop();
    backward.pop();
}
