//! AR order: fixed, or selected by an information criterion.
//!
//! With `N` the number of samples, `p` the order and `sigma^2_p` the estimator's own
//! `noise_variance` at order `p` (see the table in the parent module):
//!
//! ```text
//! AIC(p) = N ln sigma^2_p + 2 p                 (Akaike 1974)
//! BIC(p) = N ln sigma^2_p + p ln N              (Schwarz 1978; Rissanen's MDL has the same form)
//! FPE(p) = sigma^2_p (N + p) / (N - p)          (Akaike 1969; MATLAB's fpe with d = p)
//! ```
//!
//! Constants common to all orders (the Gaussian `N (1 + ln 2 pi)`, a mean parameter) are left
//! out: they do not change which order wins. Candidates are `p = 0..=max_order`, each fitted on
//! all `N` samples with its own window (as spectrum and MATLAB do), not on a common hold-back
//! sample (statsmodels `ar_select_order`); the smallest value wins, ties going to the lower order.

use std::fmt;
use std::str::FromStr;

use super::{ArError, Fit};

/// The order of an AR model: given, or chosen by a criterion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Order {
    /// Exactly this order.
    Fixed(usize),
    /// The order in `0..=max_order` that minimises `criterion`.
    Auto {
        /// Information criterion to minimise.
        criterion: OrderCriterion,
        /// Largest order tried.
        max_order: usize,
    },
}

impl Order {
    /// The largest order that will be fitted.
    pub fn max_order(self) -> usize {
        match self {
            Order::Fixed(p) => p,
            Order::Auto { max_order, .. } => max_order,
        }
    }
}

/// Information criterion for order selection (formulas in the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OrderCriterion {
    /// Akaike information criterion `N ln sigma^2 + 2p`.
    Aic,
    /// Bayesian (Schwarz) information criterion `N ln sigma^2 + p ln N`.
    Bic,
    /// Akaike's final prediction error `sigma^2 (N + p) / (N - p)`.
    Fpe,
}

impl OrderCriterion {
    /// Every criterion, in a fixed order.
    pub const ALL: [OrderCriterion; 3] = [
        OrderCriterion::Aic,
        OrderCriterion::Bic,
        OrderCriterion::Fpe,
    ];

    /// The command-line name: `aic`, `bic` or `fpe`.
    pub fn name(self) -> &'static str {
        match self {
            OrderCriterion::Aic => "aic",
            OrderCriterion::Bic => "bic",
            OrderCriterion::Fpe => "fpe",
        }
    }

    /// The criterion for a fit of order `p` with innovation variance `noise_variance > 0` on
    /// `n_samples > p` samples (both guaranteed by the fits).
    pub(super) fn value(self, n_samples: usize, p: usize, noise_variance: f64) -> f64 {
        let n = n_samples as f64;
        let p_f = p as f64;
        match self {
            OrderCriterion::Aic => n * noise_variance.ln() + 2.0 * p_f,
            OrderCriterion::Bic => n * noise_variance.ln() + p_f * n.ln(),
            OrderCriterion::Fpe => noise_variance * (n + p_f) / (n - p_f),
        }
    }
}

impl fmt::Display for OrderCriterion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for OrderCriterion {
    type Err = ArError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        OrderCriterion::ALL
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or_else(|| ArError::UnknownCriterion { name: s.to_owned() })
    }
}

/// The criterion values behind an automatic order choice.
#[derive(Debug, Clone, PartialEq)]
pub struct OrderSelection {
    /// Criterion minimised.
    pub criterion: OrderCriterion,
    /// `values[p]` is the criterion of the order-`p` fit, `p = 0..=max_order`.
    pub values: Vec<f64>,
}

/// Picks the fit to report: the only one for a fixed order, the criterion's minimum otherwise.
/// `fits` holds orders `0..=max_order` in the automatic case.
pub(super) fn select(
    mut fits: Vec<Fit>,
    order: Order,
    n_samples: usize,
) -> (Fit, Option<OrderSelection>) {
    let Order::Auto { criterion, .. } = order else {
        return (fits.swap_remove(0), None);
    };
    let values: Vec<f64> = fits
        .iter()
        .map(|f| criterion.value(n_samples, f.coefficients.len(), f.noise_variance))
        .collect();
    let best = index_of_minimum(&values);
    (
        fits.swap_remove(best),
        Some(OrderSelection { criterion, values }),
    )
}

/// Index of the first smallest value.
fn index_of_minimum(values: &[f64]) -> usize {
    let mut best = 0;
    for (i, v) in values.iter().enumerate() {
        if *v < values[best] {
            best = i;
        }
    }
    best
}
