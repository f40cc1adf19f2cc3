//! Autoregressive models AR(p), in the paper's sign convention
//! x_k = Σ_{i=1..p} c_i x_{k−i} + w_k (statsmodels' and R's φ; MATLAB and `spectrum` report the
//! A-polynomial a_i = −c_i).
//!
//! Four estimators, as the paper names them. The sample mean is removed first. Each reports
//! `noise_variance`, whose definition follows the peer each estimator is usually compared with:
//!
//! | method | coefficients | `noise_variance` | peers |
//! |---|---|---|---|
//! | Yule-Walker | Levinson-Durbin on the biased autocovariance | γ(0) Π(1 − k_m²) | = statsmodels `yule_walker(method='mle')` σ², = MATLAB `aryule`, `spectrum.aryule`; R `ar.yw` multiplies by N/(N − p − 1) |
//! | Burg | Burg's recursion (harmonic-mean reflection coefficients) | (Σ f² + Σ b²) / (2(N − p)) over the final forward and backward errors | = statsmodels `burg` σ²; `levinson_variance` γ(0)Π(1 − k²) = MATLAB `arburg`, `spectrum.arburg` P |
//! | covariance | least squares of the forward errors over k = p..N−1 | Σ e_f² / (N − p) | MATLAB `arcov` |
//! | modified covariance | least squares of forward and backward errors | (Σ e_f² + Σ e_b²) / (2(N − p)) | MATLAB `armcov` |
//!
//! Standard errors of the coefficients are asymptotic: σ² Γ_p⁻¹ / N with Γ_p the Toeplitz
//! matrix of γ(0..p−1) (Brockwell & Davis 1991, §8.10) for Yule-Walker and Burg, and the
//! least-squares covariance s² (XᵀX)⁻¹ with s² = RSS/(n − p) for the two least-squares methods.

mod burg;
mod least_squares;
mod levinson;
pub mod order;
pub mod whiteness;

pub use least_squares::{ConditionalOls, Intercept, conditional_ols};
pub use levinson::levinson_durbin;

use super::acf::{AcfError, Demean, lagged_products_about_mean};
use nalgebra::DMatrix;

/// The four estimators (the default: Burg, for `thermonav ar`, Python's `ar` and
/// `gauss_markov`, and characterisation's AR-based model).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum ArMethod {
    /// Yule-Walker (biased autocovariance + Levinson-Durbin).
    YuleWalker,
    /// Burg.
    #[default]
    Burg,
    /// Covariance method (forward least squares).
    Covariance,
    /// Modified covariance (forward-backward least squares).
    ModifiedCovariance,
}

impl ArMethod {
    /// All methods, in the paper's order.
    pub const ALL: [ArMethod; 4] = [
        ArMethod::YuleWalker,
        ArMethod::Burg,
        ArMethod::Covariance,
        ArMethod::ModifiedCovariance,
    ];

    /// Command-line and JSON name.
    pub fn name(self) -> &'static str {
        match self {
            ArMethod::YuleWalker => "yule-walker",
            ArMethod::Burg => "burg",
            ArMethod::Covariance => "covariance",
            ArMethod::ModifiedCovariance => "modified-covariance",
        }
    }

    /// The method of a command-line name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// A fitted AR(p) model.
#[derive(Debug, Clone, PartialEq)]
pub struct ArModel {
    /// Estimator used.
    pub method: ArMethod,
    /// Coefficients c_1..c_p (paper sign).
    pub coefficients: Vec<f64>,
    /// Innovation variance (definition per method, see the module docs).
    pub noise_variance: f64,
    /// γ(0) Π(1 − k_m²), for the two lattice methods (Yule-Walker, Burg).
    pub levinson_variance: Option<f64>,
    /// Reflection coefficients in the paper's sign (the partial autocorrelations for
    /// Yule-Walker), for the lattice methods.
    pub reflection: Option<Vec<f64>>,
    /// Asymptotic standard errors of the coefficients.
    pub std_errors: Vec<f64>,
    /// Samples used.
    pub n_samples: usize,
    /// The mean removed before fitting.
    pub mean: f64,
}

/// Why an AR model cannot be fitted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ArError {
    /// Order zero.
    #[error("the AR order must be from 1 to {MAX_AR_ORDER}, not 0")]
    ZeroOrder,
    /// An order above [`MAX_AR_ORDER`].
    #[error(
        "AR order {order} is outside the range from 1 to {MAX_AR_ORDER}: the least-squares and Burg fits cost samples × order², so order 500 on 60 000 samples took 45 s; the inertial noise models of this method use orders below 10"
    )]
    OrderTooHigh {
        /// The order asked for.
        order: usize,
    },
    /// Too few samples.
    #[error("{samples} samples are too few for an AR({order}) model: at least {needed} are needed")]
    TooShort {
        /// Samples given.
        samples: usize,
        /// Order asked.
        order: usize,
        /// Samples needed.
        needed: usize,
    },
    /// A NaN or infinity.
    #[error("sample {index} is not a finite number")]
    NonFinite {
        /// Its index.
        index: usize,
    },
    /// Zero variance.
    #[error("the series is constant: no AR model can be fitted")]
    Constant,
    /// The least-squares normal equations are singular.
    #[error("the least-squares system is singular (the series is too regular for order {order})")]
    Singular {
        /// Order asked.
        order: usize,
    },
}

impl From<AcfError> for ArError {
    fn from(e: AcfError) -> Self {
        match e {
            AcfError::TooShort { samples, max_lag } => ArError::TooShort {
                samples,
                order: max_lag,
                needed: max_lag + 2,
            },
            AcfError::NonFinite { index } => ArError::NonFinite { index },
            AcfError::Constant => ArError::Constant,
        }
    }
}

/// Checks input (order, length, finiteness, variance) and returns the mean to remove, in one
/// pass and without copying the series.
fn validated_mean(x: &[f64], order: usize, demean: Demean) -> Result<f64, ArError> {
    check_order(x, order)?;
    let mut sum = 0.0;
    for (index, v) in x.iter().enumerate() {
        if !v.is_finite() {
            return Err(ArError::NonFinite { index });
        }
        sum += v;
    }
    let mean = match demean {
        Demean::Subtract => sum / x.len() as f64,
        Demean::Keep => 0.0,
    };
    if x.iter().all(|&v| v - mean == 0.0) {
        return Err(ArError::Constant);
    }
    Ok(mean)
}

/// Fits an AR(`order`) model by `method` (sample mean removed).
///
/// # Errors
/// [`ArError`] for order 0, fewer than p + 2 samples (2p + 1 for the least-squares methods), non-finite values, a constant series,
/// or a singular least-squares system.
pub fn fit_ar(x: &[f64], order: usize, method: ArMethod) -> Result<ArModel, ArError> {
    fit_ar_with(x, order, method, Demean::Subtract)
}

/// As [`fit_ar`], choosing whether the mean is removed (`Demean::Keep` reproduces
/// `spectrum`'s and MATLAB's un-demeaned examples).
///
/// # Errors
/// As [`fit_ar`].
pub fn fit_ar_with(
    x: &[f64],
    order: usize,
    method: ArMethod,
    demean: Demean,
) -> Result<ArModel, ArError> {
    check_order(x, order)?;
    // Yule-Walker, Burg and the asymptotic standard errors all start from the lagged products
    // r(0..=p) about the mean: one pass over the data, which also finds non-finite values.
    let (mut model, products) = match method {
        ArMethod::YuleWalker => {
            let (r, mean) = lagged_products_about_mean(x, order, demean)?;
            (
                levinson::yule_walker(&r, x.len(), order)?.with_mean(mean),
                Some(r),
            )
        }
        ArMethod::Burg => {
            let (r, mean) = lagged_products_about_mean(x, order, demean)?;
            (burg::burg(x, mean, &r, order)?.with_mean(mean), Some(r))
        }
        ArMethod::Covariance | ArMethod::ModifiedCovariance => {
            let mean = validated_mean(x, order, demean)?;
            let centred: Vec<f64> = x.iter().map(|v| v - mean).collect();
            let backward = method == ArMethod::ModifiedCovariance;
            (
                least_squares::covariance(&centred, order, backward)?.with_mean(mean),
                None,
            )
        }
    };
    if let Some(r) = products {
        let n = x.len() as f64;
        let gamma: Vec<f64> = r[..order].iter().map(|v| v / n).collect();
        model.std_errors = asymptotic_std_errors(&gamma, model.noise_variance, order, x.len())?;
    }
    Ok(model)
}

/// Order at least 1 and at least p + 2 samples.
/// Highest AR order fitted.
pub const MAX_AR_ORDER: usize = 100;

fn check_order(x: &[f64], order: usize) -> Result<(), ArError> {
    if order == 0 {
        return Err(ArError::ZeroOrder);
    }
    if order > MAX_AR_ORDER {
        return Err(ArError::OrderTooHigh { order });
    }
    let needed = order + 2;
    if x.len() < needed {
        return Err(ArError::TooShort {
            samples: x.len(),
            order,
            needed,
        });
    }
    Ok(())
}

/// √diag(σ² Γ_p⁻¹ / N), Γ_p the Toeplitz matrix of the biased autocovariance γ(0..p−1).
fn asymptotic_std_errors(
    gamma: &[f64],
    variance: f64,
    order: usize,
    n: usize,
) -> Result<Vec<f64>, ArError> {
    let toeplitz = DMatrix::from_fn(order, order, |i, j| gamma[i.abs_diff(j)]);
    let inverse = toeplitz.try_inverse().ok_or(ArError::Singular { order })?;
    let n = n as f64;
    Ok((0..order)
        .map(|i| (variance * inverse[(i, i)] / n).max(0.0).sqrt())
        .collect())
}

impl ArModel {
    fn with_mean(mut self, mean: f64) -> Self {
        self.mean = mean;
        self
    }

    /// Order p.
    pub fn order(&self) -> usize {
        self.coefficients.len()
    }

    /// One-step prediction errors e_k = x_k − x̄ − Σ c_i (x_{k−i} − x̄), k = p..N−1.
    pub fn residuals(&self, x: &[f64]) -> Vec<f64> {
        let p = self.order();
        (p..x.len())
            .map(|k| {
                let prediction: f64 = self
                    .coefficients
                    .iter()
                    .enumerate()
                    .map(|(i, c)| c * (x[k - 1 - i] - self.mean))
                    .sum();
                x[k] - self.mean - prediction
            })
            .collect()
    }
}
