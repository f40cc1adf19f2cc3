//! The AR-based Gauss-Markov model (the paper's contribution, eqs. 8-10).

use serde::{Deserialize, Serialize};

use super::GaussMarkovError;
use super::model::{ConfidenceLevel, CorrelationTimeInterval, GaussMarkov, UpperBound, positive};

/// A fitted AR(1) model `x_k = c1 x_{k-1} + w_k` (eq. 7) of a series sampled every `dt_s`
/// seconds (nominal), as any AR estimator reports it (Yule-Walker, Burg, least squares).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Ar1Estimate {
    c1: f64,
    c1_std_error: f64,
    innovation_variance: f64,
    dt_s: f64,
}

impl Ar1Estimate {
    /// The estimate `c1` with standard error `c1_std_error`, innovation (driving-noise)
    /// variance `innovation_variance` (eq. 6, in the squared unit of the series) and nominal
    /// sampling interval `dt_s` (s). `c1` may take any finite value: whether it has a
    /// Gauss-Markov equivalent is the answer of [`gauss_markov_from_ar1`], not a validation.
    ///
    /// # Errors
    /// [`GaussMarkovError::NonFinite`] for a non-finite `c1`;
    /// [`GaussMarkovError::InvalidStdError`] for a negative or non-finite standard error;
    /// [`GaussMarkovError::NotPositive`] when the variance or `dt_s` is not finite and > 0.
    pub fn new(
        c1: f64,
        c1_std_error: f64,
        innovation_variance: f64,
        dt_s: f64,
    ) -> Result<Self, GaussMarkovError> {
        if !c1.is_finite() {
            return Err(GaussMarkovError::NonFinite {
                name: "c1",
                index: 0,
                value: c1,
            });
        }
        if !(c1_std_error.is_finite() && c1_std_error >= 0.0) {
            return Err(GaussMarkovError::InvalidStdError {
                value: c1_std_error,
            });
        }
        positive("innovation variance", innovation_variance)?;
        positive("sampling interval (s)", dt_s)?;
        Ok(Self {
            c1,
            c1_std_error,
            innovation_variance,
            dt_s,
        })
    }

    /// The AR(1) coefficient `c1`.
    pub fn c1(&self) -> f64 {
        self.c1
    }

    /// The standard error of `c1`.
    pub fn c1_std_error(&self) -> f64 {
        self.c1_std_error
    }

    /// The innovation variance `var(w)`.
    pub fn innovation_variance(&self) -> f64 {
        self.innovation_variance
    }

    /// The nominal sampling interval, s.
    pub fn dt_s(&self) -> f64 {
        self.dt_s
    }
}

/// Why an AR(1) coefficient has no Gauss-Markov equivalent (eq. 10 needs `0 < c1 < 1`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum NoGaussMarkovEquivalent {
    /// `c1 >= 1`: a random walk or a drift, not a stationary process.
    RandomWalkOrDrift {
        /// The coefficient.
        c1: f64,
    },
    /// `c1 <= 0`: no positive correlation between neighbours (alternating or white).
    NoPositiveCorrelation {
        /// The coefficient.
        c1: f64,
    },
}

/// A Gauss-Markov model derived from an AR(1) fit, with the interval of its correlation time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ArGaussMarkovFit {
    /// The model: `Tc = -dt / ln c1`, `sigma^2 = var(w) / (1 - c1^2)`.
    pub model: GaussMarkov,
    /// The interval of `c1` mapped through `Tc(c1)`.
    pub correlation_time_interval: CorrelationTimeInterval,
}

/// The result of [`gauss_markov_from_ar1`]: a model, or the reason there is none.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum ArGaussMarkov {
    /// `0 < c1 < 1`: the equivalent model.
    Model(ArGaussMarkovFit),
    /// `c1` outside (0, 1).
    NoEquivalent(NoGaussMarkovEquivalent),
}

/// The AR-based Gauss-Markov model of El-Diasty & Pagiatakis (2009), eqs. 8-10:
/// `exp(-dt/Tc) = c1`, so `Tc = -dt / ln c1`, and `sigma^2 = var(w) / (1 - c1^2)` (the
/// stationary variance of the AR(1) process).
///
/// The interval maps the normal interval `c1 ± z se(c1)` (`z` the two-sided normal quantile
/// of `level`), clipped to (0, 1), through the increasing function `Tc(c1)`: a lower `c1` bound
/// at or below 0 gives `lower_s = 0`; an upper `c1` bound at or above 1 gives
/// [`UpperBound::Unbounded`]. The interval inherits the accuracy of the normal approximation of
/// `c1`, which is poor near 1.
///
/// Assumptions: the series is zero-mean (or the AR fit removed its mean), sampled at the
/// constant interval `dt`. With jittered sampling `c1` estimates the average `exp(-dt_k/Tc)`
/// and the nominal `dt` then biases `Tc` (Jensen); [`super::fit_gauss_markov_exact_ml`] uses
/// each step's own interval instead. statsmodels users compute the same `Tc` by hand from
/// `yule_walker`/`burg` coefficients (`-dt / log(phi[0])`).
///
/// # Errors
/// [`GaussMarkovError::OutOfRange`] when `sigma^2` or `q` of the resulting model is not
/// representable (for example an enormous innovation variance with `c1` within 1e-16 of 1).
pub fn gauss_markov_from_ar1(
    estimate: &Ar1Estimate,
    level: ConfidenceLevel,
) -> Result<ArGaussMarkov, GaussMarkovError> {
    let c1 = estimate.c1;
    if c1 >= 1.0 {
        return Ok(ArGaussMarkov::NoEquivalent(
            NoGaussMarkovEquivalent::RandomWalkOrDrift { c1 },
        ));
    }
    if c1 <= 0.0 {
        return Ok(ArGaussMarkov::NoEquivalent(
            NoGaussMarkovEquivalent::NoPositiveCorrelation { c1 },
        ));
    }
    let model = GaussMarkov::new(
        correlation_time_from_c1(c1, estimate.dt_s),
        stationary_sigma(c1, estimate.innovation_variance),
    )?;
    Ok(ArGaussMarkov::Model(ArGaussMarkovFit {
        model,
        correlation_time_interval: c1_interval_as_correlation_time(estimate, level),
    }))
}

/// `Tc = -dt / ln c1` (eq. 10) for `0 < c1 < 1`.
fn correlation_time_from_c1(c1: f64, dt_s: f64) -> f64 {
    -dt_s / c1.ln()
}

/// `sqrt(var(w) / (1 - c1^2))`, with `1 - c1^2` formed as `(1 - c1)(1 + c1)` for accuracy near
/// 1 and the square roots taken apart so that no intermediate overflows.
fn stationary_sigma(c1: f64, innovation_variance: f64) -> f64 {
    innovation_variance.sqrt() / ((1.0 - c1) * (1.0 + c1)).sqrt()
}

fn c1_interval_as_correlation_time(
    estimate: &Ar1Estimate,
    level: ConfidenceLevel,
) -> CorrelationTimeInterval {
    let half_width = level.normal_quantile() * estimate.c1_std_error;
    let c1_low = estimate.c1 - half_width;
    let c1_high = estimate.c1 + half_width;
    let lower_s = if c1_low <= 0.0 {
        0.0
    } else {
        correlation_time_from_c1(c1_low, estimate.dt_s)
    };
    let upper_s = correlation_time_from_c1(c1_high.min(1.0), estimate.dt_s);
    // c1_high >= 1 gives ln = 0 and an infinite quotient; so does an enormous dt: both unbounded.
    let upper = if upper_s.is_finite() {
        UpperBound::Finite(upper_s)
    } else {
        UpperBound::Unbounded
    };
    CorrelationTimeInterval {
        lower_s,
        upper,
        level,
    }
}
