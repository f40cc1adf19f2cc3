//! The classical fit of σ² exp(−τ/Tc) to the autocorrelation of the conditioned series.

use super::family::{FamilyNames, FitInputs, GaussMarkovEstimate, GaussMarkovFamily};
use crate::stoch::acf::{Demean, autocovariance};
use crate::stoch::gauss_markov::{LagWindow, fit_autocovariance};

/// The autocorrelation-fit family (`acf_fit`).
pub struct AcfFit;

const NAMES: FamilyNames = FamilyNames {
    name: "acf_fit",
    cli_name: "acf-fit",
    help: "The classical fit to the autocorrelation",
    label: "autocorrelation fit",
};

impl GaussMarkovFamily for AcfFit {
    fn names(&self) -> &'static FamilyNames {
        &NAMES
    }

    fn fit(&self, inputs: &FitInputs<'_>) -> Result<Option<GaussMarkovEstimate>, String> {
        Ok(Some(acf_model(
            inputs.conditioned,
            inputs.dt_s,
            inputs.acf_window,
        )))
    }
}

/// The classical fit of σ² exp(−τ/Tc) to the autocovariance of `conditioned` (sampled every
/// `dt_s` seconds, lags up to a quarter of its length), as the bank's `acf_fit`.
pub fn acf_model(conditioned: &[f64], dt_s: f64, window: LagWindow) -> GaussMarkovEstimate {
    let max_lag = (conditioned.len() / 4)
        .max(2)
        .min(conditioned.len().saturating_sub(1));
    match autocovariance(conditioned, max_lag, Demean::Subtract) {
        Ok(gamma) => fit_autocovariance(&gamma, dt_s, window).into(),
        Err(e) => GaussMarkovEstimate::NoEquivalent {
            reason: e.to_string(),
        },
    }
}
