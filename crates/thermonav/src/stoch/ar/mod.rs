//! Autoregressive AR(p) models: Yule-Walker, Burg, covariance and modified covariance
//! estimators, order selection, coefficient standard errors and the Ljung-Box residual test.
//!
//! # Model and sign convention
//! Equation (5) of the method notes (the paper's and statsmodels' convention):
//!
//! ```text
//! y_k = sum_{i=1..p} c_i y_{k-i} + w_k,     y_k = x_k - mean   (or x_k - intercept - ...)
//! ```
//!
//! `coefficients[i-1] = c_i`. MATLAB (`aryule`, `arburg`, `ar`) and the Python package `spectrum`
//! report the A-polynomial `A(z) = 1 + a_1 z^-1 + ... + a_p z^-p` with `a_i = -c_i`; their
//! reflection coefficients `k_m` are likewise the negatives of our partial autocorrelations
//! `c_{m,m}`. R (`ar.yw`, `ar.burg`) and statsmodels use our sign.
//!
//! # Innovation variance
//! Every estimator reports in [`ArModel::noise_variance`] a mean squared one-step prediction error
//! (method notes, equation 6), but the estimators differ in which errors and which denominator:
//!
//! | method | `noise_variance` | same as | differs from |
//! |---|---|---|---|
//! | Yule-Walker | `gamma(0) prod_m (1 - c_mm^2)` = `gamma(0) - sum c_i gamma(i)` (biased `gamma`) | statsmodels `yule_walker(method="mle")` `sigma**2`; spectrum `aryule` `P`; MATLAB `aryule` `e` | R `ar.yw` `var.pred`, which multiplies by `N / (N - (p+1))` |
//! | Burg | `(sum f_t^2 + sum b_t^2) / (2 (N-p))` over the order-`p` forward and backward errors, `t = p..N-1` | statsmodels `burg` `sigma2` (e.g. 21.9145 on spectrum's test vector) | spectrum `arburg` `P` and MATLAB `arburg` `e`: the recursion `P_0 prod (1-k_m^2)`, `P_0 = sum y^2 / N` (22.4469 there), which we report in [`ArModel::recursion_power`] |
//! | covariance | `RSS / (N - p)`, forward errors `t = p..N-1` | statsmodels `AutoReg(...).fit().sigma2`; Stata's `bse` use it | Stata's RMSE and gretl use `RSS / (N - p - k)`, `k` = number of regressors |
//! | modified covariance | `(RSS_f + RSS_b) / (2 (N - p))` | the minimised forward-backward error energy per equation | |
//!
//! `N` is the number of samples given. Order selection ([`Order::Auto`]) uses each method's own
//! `noise_variance`.
//!
//! # Mean
//! [`MeanModel::SampleMean`] (the default of [`fit_ar`]) subtracts the sample mean first, as
//! statsmodels (`demean=True`), R and MATLAB's examples do. [`MeanModel::Zero`] uses the samples
//! as they are (spectrum's convention). [`MeanModel::Intercept`] estimates a constant jointly with
//! the coefficients by least squares (Stata's `regress` on lags, statsmodels `AutoReg(trend="c")`);
//! it exists for the covariance method only.
//!
//! # Cost
//! All four estimators are `O(N p + p^3)` in time: one blocked pass computes the lagged products
//! `S(d) = sum y_t y_{t+d}`, `d = 0..=p`; every windowed sum the estimators need (the least-squares
//! normal equations, Burg's forward/backward error energies as quadratic forms in the prediction
//! polynomial) is then `S(d)` corrected by at most `p` products at each end of the series
//! (Vos 2013, "A fast implementation of Burg's method"). When such a quadratic form would cancel
//! badly (prediction error energy below 1e-4 of the signal energy it is computed from), the
//! estimator falls back to explicit error sequences for that step (one more `O(N p)` pass).

mod burg;
mod diagnostics;
mod gram;
mod least_squares;
mod order;
mod recursion;
mod yule_walker;

use std::fmt;
use std::str::FromStr;

use thiserror::Error;

use crate::stoch::acf::{self, Demean, SeriesFault};

pub use diagnostics::{LjungBox, ljung_box};
pub use order::{Order, OrderCriterion, OrderSelection};

/// AR estimator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ArMethod {
    /// Biased autocovariance + Levinson-Durbin recursion (the autocorrelation method).
    YuleWalker,
    /// Burg's method: reflection coefficients minimising forward + backward error energy.
    Burg,
    /// Forward least squares over the data without windowing (conditional least squares).
    Covariance,
    /// Forward-backward least squares over the data without windowing.
    ModifiedCovariance,
}

impl ArMethod {
    /// Every method, in a fixed order.
    pub const ALL: [ArMethod; 4] = [
        ArMethod::YuleWalker,
        ArMethod::Burg,
        ArMethod::Covariance,
        ArMethod::ModifiedCovariance,
    ];

    /// The command-line name: `yule-walker`, `burg`, `covariance` or `modified-covariance`.
    pub fn name(self) -> &'static str {
        match self {
            ArMethod::YuleWalker => "yule-walker",
            ArMethod::Burg => "burg",
            ArMethod::Covariance => "covariance",
            ArMethod::ModifiedCovariance => "modified-covariance",
        }
    }
}

impl fmt::Display for ArMethod {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ArMethod {
    type Err = ArError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ArMethod::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| ArError::UnknownMethod { name: s.to_owned() })
    }
}

/// How the process mean is handled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MeanModel {
    /// The process has zero mean: the samples are used as they are.
    Zero,
    /// Subtract the sample mean before estimating.
    SampleMean,
    /// Estimate a constant `c_0` jointly: `x_k = c_0 + sum c_i x_{k-i} + w_k`
    /// ([`ArMethod::Covariance`] only).
    Intercept,
}

/// An estimated constant term of the AR recursion, in the units of the series.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Intercept {
    /// `c_0` in `x_k = c_0 + sum c_i x_{k-i} + w_k`.
    pub value: f64,
    /// Its standard error (same definition as the coefficients').
    pub std_error: f64,
}

/// What to fit: order (fixed or selected), estimator and mean handling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArSpec {
    /// Fixed order or selection rule.
    pub order: Order,
    /// Estimator.
    pub method: ArMethod,
    /// Mean handling.
    pub mean: MeanModel,
}

impl ArSpec {
    /// A specification that removes the sample mean.
    pub fn new(order: Order, method: ArMethod) -> Self {
        ArSpec {
            order,
            method,
            mean: MeanModel::SampleMean,
        }
    }

    /// The same specification with another mean handling.
    pub fn with_mean(self, mean: MeanModel) -> Self {
        ArSpec { mean, ..self }
    }
}

/// A fitted AR(p) model. Every number is finite.
#[derive(Debug, Clone, PartialEq)]
pub struct ArModel {
    /// Estimator used.
    pub method: ArMethod,
    /// Order `p` (`coefficients.len()`); 0 means white noise around the mean.
    pub order: usize,
    /// `c_1..c_p` of `y_k = sum c_i y_{k-i} + w_k` (paper / statsmodels sign).
    pub coefficients: Vec<f64>,
    /// Asymptotic standard errors of `c_1..c_p` (see [`ArModel::coefficients`] and the docs of
    /// each method below).
    ///
    /// - Yule-Walker, Burg: `sqrt(diag(sigma^2 Gamma_p^-1 / N))`, `Gamma_p` the `p x p` Toeplitz
    ///   autocovariance matrix of the fitted model (for Yule-Walker the sample one), `sigma^2`
    ///   the matching recursion power (Brockwell & Davis 1991, Thm 8.1.1). For AR(1) this is
    ///   `sqrt((1 - c_1^2) / N)`. R's `ar.yw` `asy.var.coef` uses its `var.pred`, so its
    ///   standard errors are larger by `sqrt(N / (N - p - 1))`.
    /// - covariance: `sqrt(diag(noise_variance (X'X)^-1))` over the regressors actually used
    ///   (statsmodels `AutoReg` `bse`, Stata's `bse`; gretl's are larger by
    ///   `sqrt((N-p) / (N-p-k))`).
    /// - modified covariance: `sqrt(diag(2 noise_variance (X_fb'X_fb)^-1))`: the stacked
    ///   forward-backward system has `2 (N-p)` rows but the backward rows carry no independent
    ///   information asymptotically, so the factor 2 restores the forward-only variance.
    pub coefficient_std_errors: Vec<f64>,
    /// Innovation (driving-noise) variance `var(w)`; definition per method in the module docs.
    pub noise_variance: f64,
    /// Order-recursive prediction error power `P_p = P_0 prod_{m<=p} (1 - c_mm^2)` of the
    /// Yule-Walker and Burg recursions (`P_0 = gamma(0)`, i.e. `sum y^2 / N`): spectrum's and
    /// MATLAB's `arburg` variance. Equals `noise_variance` for Yule-Walker; `None` for the
    /// least-squares methods.
    pub recursion_power: Option<f64>,
    /// Partial autocorrelations `c_11, c_22, ..., c_pp` of the Yule-Walker or Burg recursion
    /// (negated, these are MATLAB's / spectrum's reflection coefficients); `None` for the
    /// least-squares methods.
    pub partial_autocorrelation: Option<Vec<f64>>,
    /// Mean handling used.
    pub mean_model: MeanModel,
    /// The value subtracted from the series before the recursion: the sample mean for
    /// [`MeanModel::SampleMean`], 0 otherwise.
    pub mean: f64,
    /// The estimated constant for [`MeanModel::Intercept`].
    pub intercept: Option<Intercept>,
    /// Number of samples the model was fitted on.
    pub n_samples: usize,
    /// Criterion values per candidate order when the order was selected.
    pub selection: Option<OrderSelection>,
}

impl ArModel {
    /// One-step forward prediction errors
    /// `e_k = (x_k - mean) - sum c_i (x_{k-i} - mean) - c_0`, `k = p..N-1` (length `N - p`),
    /// using the model's mean handling. For a covariance-method fit on the same series these
    /// are the regression residuals.
    ///
    /// # Errors
    /// [`ArError::NonFinite`] or [`ArError::TooShort`] when `x.len() <= p`.
    pub fn residuals(&self, x: &[f64]) -> Result<Vec<f64>, ArError> {
        if x.len() <= self.order {
            return Err(ArError::TooShort {
                method: self.method,
                order: self.order,
                n_samples: x.len(),
                min_samples: self.order + 1,
            });
        }
        validated_mean(x)?;
        let constant = self.intercept.map_or(0.0, |c| c.value);
        let y: Vec<f64> = x.iter().map(|v| v - self.mean).collect();
        Ok(prediction_errors(&y, &self.coefficients, constant))
    }

    /// Ljung-Box whiteness test of [`ArModel::residuals`] on `x`, with `lags` autocorrelation
    /// lags and the `p` coefficients as fitted parameters (`lags - p` degrees of freedom).
    ///
    /// # Errors
    /// As [`ArModel::residuals`] and [`ljung_box`].
    pub fn ljung_box(&self, x: &[f64], lags: usize) -> Result<LjungBox, ArError> {
        ljung_box(&self.residuals(x)?, lags, self.order)
    }
}

/// `e_k = y_k - constant - sum c_i y_{k-i}`, `k = p..N-1`.
fn prediction_errors(y: &[f64], coefficients: &[f64], constant: f64) -> Vec<f64> {
    let p = coefficients.len();
    (p..y.len())
        .map(|k| {
            let predicted: f64 = coefficients
                .iter()
                .enumerate()
                .map(|(i, c)| c * y[k - 1 - i])
                .sum();
            y[k] - constant - predicted
        })
        .collect()
}

/// `e_s = y_s - sum_i c_i y_{s+i}`, `s = 0..N-1-p`: backward prediction errors.
fn backward_prediction_errors(y: &[f64], coefficients: &[f64]) -> Vec<f64> {
    let p = coefficients.len();
    (0..y.len() - p)
        .map(|s| {
            let predicted: f64 = coefficients
                .iter()
                .enumerate()
                .map(|(i, c)| c * y[s + 1 + i])
                .sum();
            y[s] - predicted
        })
        .collect()
}

/// Invalid input or a degenerate fit.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ArError {
    /// A sample is NaN or infinite.
    #[error("sample {index} is {value}: every sample must be finite")]
    NonFinite {
        /// Index of the first non-finite sample.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// Not enough samples for the order and method.
    #[error("{method} AR({order}) needs at least {min_samples} samples, got {n_samples}")]
    TooShort {
        /// Estimator.
        method: ArMethod,
        /// Requested (largest) order.
        order: usize,
        /// Samples given.
        n_samples: usize,
        /// Samples needed.
        min_samples: usize,
    },
    /// The series is constant up to rounding (standard deviation at most 1e-15 of the mean), or
    /// identically zero with [`MeanModel::Zero`]: nothing to model.
    #[error(
        "the series has zero variance over {n_samples} samples (constant, or all zero with MeanModel::Zero): an AR model is undefined"
    )]
    ZeroVariance {
        /// Samples given.
        n_samples: usize,
    },
    /// Sums of squares overflow `f64` (samples of magnitude near 1e154 or more).
    #[error(
        "the series is too large in magnitude (largest |x| = {max_abs:e}): its sum of squares overflows; rescale it"
    )]
    Overflow {
        /// Largest absolute sample.
        max_abs: f64,
    },
    /// The intercept variant exists only for the covariance method.
    #[error(
        "MeanModel::Intercept is only available with the covariance method, not {method}: use MeanModel::SampleMean"
    )]
    InterceptUnsupported {
        /// Estimator requested.
        method: ArMethod,
    },
    /// The least-squares normal equations are singular (e.g. a sum of fewer than `p/2`
    /// sinusoids): the order is too high for the series.
    #[error("the AR({order}) normal equations are singular: the order is too high for this series")]
    Singular {
        /// Order being fitted.
        order: usize,
    },
    /// The series is perfectly predictable at this order: zero innovation variance.
    #[error(
        "the AR({order}) innovation variance is zero (the series is perfectly predictable): reduce the order"
    )]
    ZeroInnovationVariance {
        /// Order being fitted.
        order: usize,
    },
    /// Unknown command-line name of an estimator.
    #[error(
        "unknown AR method '{name}': expected yule-walker, burg, covariance or modified-covariance"
    )]
    UnknownMethod {
        /// The name given.
        name: String,
    },
    /// Unknown command-line name of an order criterion.
    #[error("unknown order criterion '{name}': expected aic, bic or fpe")]
    UnknownCriterion {
        /// The name given.
        name: String,
    },
    /// Ljung-Box lag count outside `1..n`.
    #[error("Ljung-Box with {lags} lags needs 1 <= lags < {n_residuals} (number of residuals)")]
    InvalidLags {
        /// Lags requested.
        lags: usize,
        /// Residuals given.
        n_residuals: usize,
    },
    /// Ljung-Box with no degrees of freedom left.
    #[error(
        "Ljung-Box with {lags} lags and {fitted_params} fitted parameters has no degrees of freedom: use more lags"
    )]
    NoDegreesOfFreedom {
        /// Lags requested.
        lags: usize,
        /// Parameters fitted.
        fitted_params: usize,
    },
}

/// Fits an AR model with the sample mean removed.
///
/// # Errors
/// See [`fit_ar_with`].
///
/// # Example
/// ```
/// use thermonav::stoch::ar::{fit_ar, ArMethod, Order};
/// // y_k = 0.5 y_{k-1} + w_k, a short deterministic sample
/// let x = [1.0, 0.7, -0.2, 0.4, 1.1, 0.3, -0.5, -0.1, 0.6, 0.2];
/// let model = fit_ar(&x, Order::Fixed(1), ArMethod::Burg).unwrap();
/// assert_eq!(model.coefficients.len(), 1);
/// assert!(model.noise_variance > 0.0);
/// ```
pub fn fit_ar(x: &[f64], order: Order, method: ArMethod) -> Result<ArModel, ArError> {
    fit_ar_with(x, &ArSpec::new(order, method))
}

/// Fits an AR model as specified.
///
/// # Errors
/// - [`ArError::NonFinite`]: a NaN or infinite sample.
/// - [`ArError::TooShort`]: fewer samples than the (largest) order needs: `p + 1` for
///   Yule-Walker and Burg, `2p + 1` (+1 with intercept) for covariance, `p + ceil((p+1)/2)` for
///   modified covariance (more equations than unknowns), and at least 2.
/// - [`ArError::ZeroVariance`]: a constant series (or all zero with [`MeanModel::Zero`]).
/// - [`ArError::Overflow`]: samples so large (near `1e154`) that their squares overflow.
/// - [`ArError::InterceptUnsupported`]: [`MeanModel::Intercept`] with another method than
///   covariance.
/// - [`ArError::Singular`]: rank-deficient least-squares normal equations.
/// - [`ArError::ZeroInnovationVariance`]: the series is perfectly predictable at the order
///   (with [`Order::Auto`], at any candidate order).
pub fn fit_ar_with(x: &[f64], spec: &ArSpec) -> Result<ArModel, ArError> {
    let data = Prepared::new(x, spec)?;
    let fits = match spec.order {
        Order::Fixed(p) => vec![data.fit_orders(spec, p, p)?.remove(0)],
        Order::Auto { max_order, .. } => data.fit_orders(spec, 0, max_order)?,
    };
    let (fit, selection) = order::select(fits, spec.order, x.len());
    Ok(data.into_model(fit, spec, selection))
}

/// One candidate fit, before it becomes an [`ArModel`].
#[derive(Debug, Clone)]
struct Fit {
    coefficients: Vec<f64>,
    std_errors: Vec<f64>,
    noise_variance: f64,
    recursion_power: Option<f64>,
    partial_autocorrelation: Option<Vec<f64>>,
    intercept: Option<Intercept>,
}

/// The series seen through its mean handling, `y_t = x_t - mean`, computed when read (the
/// estimators read all of it once, through the lagged products, and otherwise only its ends).
#[derive(Debug, Clone, Copy)]
struct Centred<'a> {
    x: &'a [f64],
    mean: f64,
}

impl Centred<'_> {
    /// Number of samples `N`.
    fn len(&self) -> usize {
        self.x.len()
    }

    /// `y_t`.
    fn at(&self, t: usize) -> f64 {
        self.x[t] - self.mean
    }

    /// All of `y`, for the rare passes that need explicit error sequences.
    fn to_vec(self) -> Vec<f64> {
        self.x.iter().map(|v| v - self.mean).collect()
    }

    /// `sum_t y_t`.
    fn sum(&self) -> f64 {
        self.x.iter().map(|v| v - self.mean).sum()
    }
}

/// Validated series with its lagged products `S(0..=max_order)`.
struct Prepared<'a> {
    y: Centred<'a>,
    lagged: Vec<f64>,
}

impl<'a> Prepared<'a> {
    /// Validates `x` for the spec (one pass) and computes the lagged products (one pass).
    fn new(x: &'a [f64], spec: &ArSpec) -> Result<Self, ArError> {
        if spec.mean == MeanModel::Intercept && spec.method != ArMethod::Covariance {
            return Err(ArError::InterceptUnsupported {
                method: spec.method,
            });
        }
        let max_order = spec.order.max_order();
        check_length(x.len(), max_order, spec)?;
        let products = acf::centred_lagged_products(x, demean_of(spec.mean), max_order)?;
        let (lagged, mean) = (products.sums, products.mean);
        if acf::is_constant_to_rounding(lagged[0] / x.len() as f64, mean) {
            return Err(ArError::ZeroVariance { n_samples: x.len() });
        }
        Ok(Prepared {
            y: Centred { x, mean },
            lagged,
        })
    }

    /// Fits orders `min_order..=max_order` with the spec's method.
    fn fit_orders(
        &self,
        spec: &ArSpec,
        min_order: usize,
        max_order: usize,
    ) -> Result<Vec<Fit>, ArError> {
        let n = self.y.len();
        let fits = match spec.method {
            ArMethod::YuleWalker => yule_walker::fit_orders(&self.lagged[..=max_order], n)?,
            ArMethod::Burg => burg::fit_orders(self.y, &self.lagged[..=max_order])?,
            ArMethod::Covariance => {
                return least_squares::fit_covariance_orders(self, spec.mean, min_order, max_order);
            }
            ArMethod::ModifiedCovariance => {
                return least_squares::fit_modified_covariance_orders(self, min_order, max_order);
            }
        };
        Ok(fits.into_iter().skip(min_order).collect())
    }

    /// Wraps the chosen fit with the bookkeeping of the spec.
    fn into_model(self, fit: Fit, spec: &ArSpec, selection: Option<OrderSelection>) -> ArModel {
        let mean = match spec.mean {
            MeanModel::SampleMean => self.y.mean,
            MeanModel::Zero | MeanModel::Intercept => 0.0,
        };
        ArModel {
            method: spec.method,
            order: fit.coefficients.len(),
            coefficients: fit.coefficients,
            coefficient_std_errors: fit.std_errors,
            noise_variance: fit.noise_variance,
            recursion_power: fit.recursion_power,
            partial_autocorrelation: fit.partial_autocorrelation,
            mean_model: spec.mean,
            mean,
            intercept: fit.intercept,
            n_samples: self.y.len(),
            selection,
        }
    }
}

impl From<SeriesFault> for ArError {
    fn from(fault: SeriesFault) -> Self {
        match fault {
            SeriesFault::NonFinite { index, value } => ArError::NonFinite { index, value },
            SeriesFault::Overflow { max_abs } => ArError::Overflow { max_abs },
        }
    }
}

/// The acf centring of a mean model. The intercept fit works on the centred series (for
/// conditioning) and converts back.
fn demean_of(mean: MeanModel) -> Demean {
    match mean {
        MeanModel::Zero => Demean::None,
        MeanModel::SampleMean | MeanModel::Intercept => Demean::SampleMean,
    }
}

/// The sample mean of a non-empty series, rejecting NaN, infinities and overflow.
fn validated_mean(x: &[f64]) -> Result<f64, ArError> {
    Ok(acf::checked_mean(x)?)
}

/// Rejects series too short for the (largest) order.
fn check_length(n_samples: usize, order: usize, spec: &ArSpec) -> Result<(), ArError> {
    let min_samples = min_samples(spec.method, spec.mean, order);
    if n_samples < min_samples {
        return Err(ArError::TooShort {
            method: spec.method,
            order,
            n_samples,
            min_samples,
        });
    }
    Ok(())
}

/// Fewest samples for which the estimator of order `p` is defined with at least one more
/// equation than unknowns.
pub fn min_samples(method: ArMethod, mean: MeanModel, p: usize) -> usize {
    let intercept = usize::from(mean == MeanModel::Intercept);
    let needed = match method {
        ArMethod::YuleWalker | ArMethod::Burg => p.saturating_add(1),
        ArMethod::Covariance => p.saturating_mul(2).saturating_add(1 + intercept),
        ArMethod::ModifiedCovariance => p.saturating_add(p / 2 + 1),
    };
    needed.max(2)
}
