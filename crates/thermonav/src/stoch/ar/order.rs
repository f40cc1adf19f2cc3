//! AR order selection by information criteria (Akaike 1969, 1974; Schwarz 1978), each computed
//! from the fitted model's `noise_variance` σ̂²_p and the N samples:
//! AIC(p) = N ln σ̂²_p + 2p, BIC(p) = N ln σ̂²_p + p ln N, FPE(p) = σ̂²_p (N + p + 1)/(N − p − 1).

use super::{ArError, ArMethod, ArModel, fit_ar};

/// An information criterion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Criterion {
    /// Akaike's information criterion.
    Aic,
    /// Bayesian (Schwarz) information criterion.
    Bic,
    /// Akaike's final prediction error.
    Fpe,
}

/// Fixed order or automatic selection.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    /// This order.
    Fixed(usize),
    /// The order in 1..=max_order minimising the criterion.
    Auto {
        /// The criterion.
        criterion: Criterion,
        /// Largest order tried.
        max_order: usize,
    },
}

impl Criterion {
    /// The criterion's value for an order-p model with noise variance σ² on N samples.
    pub fn value(self, variance: f64, order: usize, n: usize) -> f64 {
        let (p, n) = (order as f64, n as f64);
        match self {
            Criterion::Aic => n * variance.ln() + 2.0 * p,
            Criterion::Bic => n * variance.ln() + p * n.ln(),
            Criterion::Fpe => variance * (n + p + 1.0) / (n - p - 1.0),
        }
    }

    /// Command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Criterion::Aic => "aic",
            Criterion::Bic => "bic",
            Criterion::Fpe => "fpe",
        }
    }
}

/// Fits at a fixed order or selects the best order by the criterion.
///
/// # Errors
/// [`ArError`] from the fits (the first failing order stops the search).
pub fn fit_ar_order(x: &[f64], order: Order, method: ArMethod) -> Result<ArModel, ArError> {
    match order {
        Order::Fixed(p) => fit_ar(x, p, method),
        Order::Auto {
            criterion,
            max_order,
        } => {
            let mut best: Option<(f64, ArModel)> = None;
            for p in 1..=max_order.max(1) {
                let model = fit_ar(x, p, method)?;
                let score =
                    criterion.value(model.noise_variance.max(f64::MIN_POSITIVE), p, x.len());
                if best.as_ref().is_none_or(|(s, _)| score < *s) {
                    best = Some((score, model));
                }
            }
            best.map(|(_, m)| m).ok_or(ArError::ZeroOrder)
        }
    }
}
