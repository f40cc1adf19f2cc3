//! AR order selection by information criteria (Akaike 1969, 1974; Schwarz 1978), each computed
//! from the fitted model's `noise_variance` σ̂²_p and the N samples:
//! AIC(p) = N ln σ̂²_p + 2p, BIC(p) = N ln σ̂²_p + p ln N, FPE(p) = σ̂²_p (N + p + 1)/(N − p − 1).

use super::{ArError, ArMethod, ArModel, MAX_AR_ORDER, fit_ar};

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

/// Largest order automatic selection tries unless told (`thermonav ar --max-order`, Python's
/// `max_order`).
pub const DEFAULT_AUTO_MAX_ORDER: usize = 10;

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

impl Order {
    /// Checks the order before any fit: a fixed order, or the largest order `Auto` tries, in
    /// 1..=[`MAX_AR_ORDER`].
    ///
    /// # Errors
    /// [`ArError::ZeroOrder`] for 0, [`ArError::OrderTooHigh`] above [`MAX_AR_ORDER`].
    pub fn validate(&self) -> Result<(), ArError> {
        let order = match *self {
            Order::Fixed(p) => p,
            Order::Auto { max_order, .. } => max_order,
        };
        match order {
            0 => Err(ArError::ZeroOrder),
            p if p > MAX_AR_ORDER => Err(ArError::OrderTooHigh { order: p }),
            _ => Ok(()),
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    // The documented range 1..=MAX_AR_ORDER by its ends, for a fixed order and for auto's
    // largest order.
    #[test]
    fn validate_accepts_orders_from_1_to_the_maximum() {
        let auto = |max_order| Order::Auto {
            criterion: Criterion::Bic,
            max_order,
        };
        for p in [1, 10, MAX_AR_ORDER] {
            assert_eq!(Order::Fixed(p).validate(), Ok(()));
            assert_eq!(auto(p).validate(), Ok(()));
        }
        assert_eq!(Order::Fixed(0).validate(), Err(ArError::ZeroOrder));
        assert_eq!(auto(0).validate(), Err(ArError::ZeroOrder));
        let above = MAX_AR_ORDER + 1;
        assert_eq!(
            Order::Fixed(above).validate(),
            Err(ArError::OrderTooHigh { order: above })
        );
        assert_eq!(
            auto(above).validate(),
            Err(ArError::OrderTooHigh { order: above })
        );
    }
}
