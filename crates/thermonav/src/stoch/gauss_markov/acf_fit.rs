//! The classical Gauss-Markov model fitted to a sampled autocovariance (the method the paper
//! improves on), and the 1/e shortcut.

use nalgebra::{Matrix2, Vector2};
use serde::{Deserialize, Serialize};

use super::GaussMarkovError;
use super::intervals::{require_finite, require_samples};
use super::model::{GaussMarkov, positive};

/// Fewest lags a two-parameter fit accepts.
pub const MIN_FIT_LAGS: usize = 2;
/// Levenberg-Marquardt iteration limit (the problem has two parameters and converges
/// quadratically near its solution; the limit only guards pathological input).
const MAX_ITERATIONS: usize = 200;
/// Relative step size at which the iteration is converged.
const STEP_TOLERANCE: f64 = 1e-15;
/// Damping beyond which no descent step exists at `f64` precision: converged.
const MAX_DAMPING: f64 = 1e16;
/// A fitted `Tc` beyond this multiple of the longest lag in the window is not a decay.
const MAX_TC_OVER_WINDOW: f64 = 1e6;

/// Which lags of the autocovariance enter the fit (always starting at lag 0 or 1, see
/// [`ZeroLag`], and contiguous).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum LagWindow {
    /// The lags before the first lag `k >= 1` whose autocovariance is <= 0 (all lags if none).
    FirstZeroCrossing,
    /// The lags before the first lag `k >= 1` whose autocorrelation `gamma(k)/gamma(0)` falls
    /// below the threshold, which must lie in (0, 1) (for example `exp(-2)`: two correlation
    /// times).
    UntilRhoBelow(f64),
    /// Lags `0..=max_lag` (or all lags, if fewer).
    MaxLag(usize),
}

/// Whether the lag-0 value enters the fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ZeroLag {
    /// Fit from lag 0.
    Include,
    /// Fit from lag 1: white noise on top of the Gauss-Markov process adds its variance to
    /// lag 0 only, and would otherwise pull the fit.
    Exclude,
}

/// A Gauss-Markov model fitted to an autocovariance by least squares.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AcfFit {
    /// The fitted model (`sigma^2` is the fitted amplitude at lag 0).
    pub model: GaussMarkov,
    /// First lag fitted (0 or 1).
    pub first_lag: usize,
    /// Last lag fitted.
    pub last_lag: usize,
    /// Sum of squared residuals at the solution.
    pub residual_sum_of_squares: f64,
    /// Levenberg-Marquardt iterations taken.
    pub iterations: usize,
}

/// The answer of [`fit_gauss_markov_to_autocovariance`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum AcfGaussMarkov {
    /// A decaying exponential fits.
    Fitted(AcfFit),
    /// The autocovariance in the window does not decay (the log-linear slope is >= 0, or the
    /// fit runs to a non-positive amplitude or to a correlation time beyond a million times the
    /// window): no Gauss-Markov model.
    NotDecaying,
}

/// The textbook shortcut: the lag at which the autocorrelation first falls to 1/e.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum EFoldingTime {
    /// The crossing, s: the correlation time of a Gauss-Markov model.
    Crossed {
        /// The interpolated lag of the crossing, s.
        correlation_time_s: f64,
    },
    /// The autocorrelation stays above 1/e over all the lags given.
    NotReached {
        /// The longest lag given, s.
        max_lag_s: f64,
    },
}

/// The classical Gauss-Markov fit: `gamma(k dt) ~ sigma^2 exp(-k dt / Tc)` by unweighted
/// nonlinear least squares over the lags of `window` (Gelb 1974; the reference method of
/// El-Diasty & Pagiatakis 2009, who replace it by the AR-based model).
///
/// `autocovariance[k]` is the autocovariance at lag `k dt` (any estimator: biased, unbiased,
/// FFT); `lag_dt_s` is the lag spacing. The fit starts from the log-linear least-squares fit
/// `ln gamma = ln sigma^2 - tau/Tc` over the positive values in the window and is refined by
/// Levenberg-Marquardt in `(sigma^2, ln Tc)` (a Gauss-Newton step with diagonal damping),
/// which minimises the same sum of squares as SciPy's `curve_fit(lambda t, s2, tc: s2 *
/// exp(-t/tc), ...)`. Assumes the autocovariance of a zero-mean stationary process; the
/// estimate inherits the bias of the autocovariance estimator and the arbitrariness of the
/// window, which is why the AR-based and likelihood methods exist.
///
/// # Errors
/// [`GaussMarkovError::TooShort`] (fewer than 2 lags), [`GaussMarkovError::NonFinite`],
/// [`GaussMarkovError::NotPositive`] for `gamma(0) <= 0` or a bad `lag_dt_s`,
/// [`GaussMarkovError::InvalidRhoThreshold`], [`GaussMarkovError::TooFewLags`] when the window
/// keeps fewer than 2 lags or fewer than 2 positive values, [`GaussMarkovError::OutOfRange`]
/// when the fitted model is not representable.
pub fn fit_gauss_markov_to_autocovariance(
    autocovariance: &[f64],
    lag_dt_s: f64,
    window: LagWindow,
    zero_lag: ZeroLag,
) -> Result<AcfGaussMarkov, GaussMarkovError> {
    validate_autocovariance(autocovariance, lag_dt_s)?;
    let first_lag = match zero_lag {
        ZeroLag::Include => 0,
        ZeroLag::Exclude => 1,
    };
    let last_lag = last_lag_of(window, autocovariance)?;
    let kept = (last_lag + 1).saturating_sub(first_lag);
    if kept < MIN_FIT_LAGS {
        return Err(GaussMarkovError::TooFewLags {
            needed: MIN_FIT_LAGS,
            got: kept,
        });
    }
    let points = LagPoints::new(&autocovariance[first_lag..=last_lag], first_lag, lag_dt_s);
    let Some(start) = log_linear_fit(&points)? else {
        return Ok(AcfGaussMarkov::NotDecaying);
    };
    let solution = levenberg_marquardt(&points, start);
    let longest_lag_s = last_lag as f64 * lag_dt_s;
    let correlation_time_s = solution.parameters.ln_tc.exp();
    if solution.parameters.amplitude <= 0.0
        || correlation_time_s > MAX_TC_OVER_WINDOW * longest_lag_s
    {
        return Ok(AcfGaussMarkov::NotDecaying);
    }
    Ok(AcfGaussMarkov::Fitted(AcfFit {
        model: GaussMarkov::new(correlation_time_s, solution.parameters.amplitude.sqrt())?,
        first_lag,
        last_lag,
        residual_sum_of_squares: 2.0 * solution.cost,
        iterations: solution.iterations,
    }))
}

/// The textbook shortcut: `Tc` is the lag where `rho(k) = gamma(k)/gamma(0)` first falls to
/// `1/e` or below. Between the two lags that bracket the crossing, `ln rho` is interpolated
/// linearly (exact for an exponential autocorrelation); if the lag after the crossing has
/// `rho <= 0`, `rho` itself is interpolated linearly.
///
/// # Errors
/// [`GaussMarkovError::TooShort`], [`GaussMarkovError::NonFinite`],
/// [`GaussMarkovError::NotPositive`] for `gamma(0) <= 0` or a bad `lag_dt_s`.
pub fn e_folding_time(
    autocovariance: &[f64],
    lag_dt_s: f64,
) -> Result<EFoldingTime, GaussMarkovError> {
    validate_autocovariance(autocovariance, lag_dt_s)?;
    let rho = |k: usize| autocovariance[k] / autocovariance[0];
    let target = (-1.0_f64).exp();
    let Some(k) = (1..autocovariance.len()).find(|&k| rho(k) <= target) else {
        return Ok(EFoldingTime::NotReached {
            max_lag_s: (autocovariance.len() - 1) as f64 * lag_dt_s,
        });
    };
    let (before, after) = (rho(k - 1), rho(k));
    let fraction = if after > 0.0 {
        (before.ln() + 1.0) / (before.ln() - after.ln())
    } else {
        (before - target) / (before - after)
    };
    Ok(EFoldingTime::Crossed {
        correlation_time_s: (k as f64 - 1.0 + fraction) * lag_dt_s,
    })
}

fn validate_autocovariance(autocovariance: &[f64], lag_dt_s: f64) -> Result<(), GaussMarkovError> {
    require_samples(autocovariance.len(), MIN_FIT_LAGS)?;
    require_finite("autocovariance", autocovariance)?;
    positive("autocovariance at lag 0", autocovariance[0])?;
    positive("lag spacing (s)", lag_dt_s)?;
    Ok(())
}

/// The last lag the window keeps (inclusive).
fn last_lag_of(window: LagWindow, autocovariance: &[f64]) -> Result<usize, GaussMarkovError> {
    let last = autocovariance.len() - 1;
    let before_first = |outside: &dyn Fn(f64) -> bool| {
        (1..=last)
            .find(|&k| outside(autocovariance[k]))
            .map_or(last, |k| k - 1)
    };
    match window {
        LagWindow::FirstZeroCrossing => Ok(before_first(&|g| g <= 0.0)),
        LagWindow::UntilRhoBelow(threshold) => {
            if !(threshold > 0.0 && threshold < 1.0) {
                return Err(GaussMarkovError::InvalidRhoThreshold { value: threshold });
            }
            Ok(before_first(&|g| g / autocovariance[0] < threshold))
        }
        LagWindow::MaxLag(max_lag) => Ok(max_lag.min(last)),
    }
}

/// The fitted lags: times `tau_k` (s) and autocovariances `gamma_k`.
struct LagPoints {
    tau_s: Vec<f64>,
    gamma: Vec<f64>,
}

impl LagPoints {
    fn new(gamma: &[f64], first_lag: usize, lag_dt_s: f64) -> Self {
        let tau_s = (0..gamma.len())
            .map(|i| (first_lag + i) as f64 * lag_dt_s)
            .collect();
        Self {
            tau_s,
            gamma: gamma.to_vec(),
        }
    }
}

/// The two parameters, `sigma^2` (amplitude) and `ln Tc`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ExponentialParameters {
    amplitude: f64,
    ln_tc: f64,
}

/// Least-squares line through `(tau, ln gamma)` over the positive `gamma`: `Some` start when
/// it decays, `None` when its slope is >= 0.
fn log_linear_fit(points: &LagPoints) -> Result<Option<ExponentialParameters>, GaussMarkovError> {
    let (tau, ln_gamma): (Vec<f64>, Vec<f64>) = points
        .tau_s
        .iter()
        .zip(&points.gamma)
        .filter(|(_, g)| **g > 0.0)
        .map(|(t, g)| (*t, g.ln()))
        .unzip();
    if tau.len() < MIN_FIT_LAGS {
        return Err(GaussMarkovError::TooFewLags {
            needed: MIN_FIT_LAGS,
            got: tau.len(),
        });
    }
    let n = tau.len() as f64;
    let tau_mean = tau.iter().sum::<f64>() / n;
    let ln_mean = ln_gamma.iter().sum::<f64>() / n;
    let sxx: f64 = tau.iter().map(|t| (t - tau_mean).powi(2)).sum();
    let sxy: f64 = tau
        .iter()
        .zip(&ln_gamma)
        .map(|(t, y)| (t - tau_mean) * (y - ln_mean))
        .sum();
    let slope = sxy / sxx;
    if slope >= 0.0 {
        return Ok(None);
    }
    Ok(Some(ExponentialParameters {
        amplitude: (ln_mean - slope * tau_mean).exp(),
        ln_tc: -(-slope).ln(),
    }))
}

/// The least-squares state at one parameter point.
struct Linearisation {
    cost: f64,
    normal_matrix: Matrix2<f64>,
    gradient: Vector2<f64>,
}

/// Half the sum of squared residuals `r_k = A exp(-tau_k/Tc) - gamma_k`, `J^T J` and `J^T r`
/// with `J` the Jacobian in `(A, ln Tc)`: `[exp(-tau/Tc), A exp(-tau/Tc) tau/Tc]`.
fn linearise(points: &LagPoints, p: ExponentialParameters) -> Linearisation {
    let tc = p.ln_tc.exp();
    let mut lin = Linearisation {
        cost: 0.0,
        normal_matrix: Matrix2::zeros(),
        gradient: Vector2::zeros(),
    };
    for (tau, gamma) in points.tau_s.iter().zip(&points.gamma) {
        let decay = (-tau / tc).exp();
        let residual = p.amplitude * decay - gamma;
        let jacobian = Vector2::new(decay, p.amplitude * decay * tau / tc);
        lin.cost += 0.5 * residual * residual;
        lin.normal_matrix += jacobian * jacobian.transpose();
        lin.gradient += jacobian * residual;
    }
    lin
}

/// Half the sum of squared residuals only.
fn cost(points: &LagPoints, p: ExponentialParameters) -> f64 {
    let tc = p.ln_tc.exp();
    let sum: f64 = points
        .tau_s
        .iter()
        .zip(&points.gamma)
        .map(|(tau, gamma)| (p.amplitude * (-tau / tc).exp() - gamma).powi(2))
        .sum();
    0.5 * sum
}

struct LeastSquaresSolution {
    parameters: ExponentialParameters,
    cost: f64,
    iterations: usize,
}

/// Levenberg-Marquardt with Marquardt's diagonal scaling: solve
/// `(J^T J + lambda diag(J^T J)) delta = -J^T r`, accept a step that lowers the cost and
/// divide `lambda` by 10, else multiply it by 10. Stops when the accepted step is below
/// `1e-15` relative, or when no damping yields a descent (the cost is minimal to rounding).
fn levenberg_marquardt(points: &LagPoints, start: ExponentialParameters) -> LeastSquaresSolution {
    let mut p = start;
    let mut lin = linearise(points, p);
    let mut damping = 1e-3;
    let mut iterations = 0;
    while iterations < MAX_ITERATIONS && damping < MAX_DAMPING {
        iterations += 1;
        let Some(step) = damped_step(&lin, damping) else {
            damping *= 10.0;
            continue;
        };
        let trial = ExponentialParameters {
            amplitude: p.amplitude + step[0],
            ln_tc: p.ln_tc + step[1],
        };
        let trial_cost = cost(points, trial);
        if trial_cost.is_nan() || trial_cost >= lin.cost {
            damping *= 10.0;
            continue;
        }
        p = trial;
        lin = linearise(points, p);
        damping = (damping / 10.0).max(1e-12);
        if converged(step, p) {
            break;
        }
    }
    LeastSquaresSolution {
        parameters: p,
        cost: lin.cost,
        iterations,
    }
}

fn damped_step(lin: &Linearisation, damping: f64) -> Option<Vector2<f64>> {
    let mut matrix = lin.normal_matrix;
    for i in 0..2 {
        matrix[(i, i)] *= 1.0 + damping;
    }
    let step = matrix.lu().solve(&(-lin.gradient))?;
    step.iter().all(|s| s.is_finite()).then_some(step)
}

fn converged(step: Vector2<f64>, p: ExponentialParameters) -> bool {
    step[0].abs() <= STEP_TOLERANCE * p.amplitude.abs()
        && step[1].abs() <= STEP_TOLERANCE * p.ln_tc.abs().max(1.0)
}
