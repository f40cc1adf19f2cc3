//! The exact maximum likelihood of Gauss-Markov plus white noise on the irregular timestamps
//! ([`fit_noisy_gauss_markov`]), on block means of the raw record: the default family.

use super::family::{FamilyNames, FitInputs, GaussMarkovEstimate, GaussMarkovFamily};
use crate::stoch::noisy_gauss_markov::{NoisyGaussMarkovOutcome, fit_noisy_gauss_markov};

/// The exact-likelihood family (`irregular_ml`).
pub struct IrregularMl;

const NAMES: FamilyNames = FamilyNames {
    name: "irregular_ml",
    cli_name: "irregular-ml",
    help: "Exact likelihood of Gauss-Markov + white noise on the irregular timestamps",
    label: "exact ML (irregular t)",
};

impl GaussMarkovFamily for IrregularMl {
    fn names(&self) -> &'static FamilyNames {
        &NAMES
    }

    fn fit(&self, inputs: &FitInputs<'_>) -> Result<Option<GaussMarkovEstimate>, String> {
        Ok(Some(from_block_means(
            inputs.block_times_s,
            inputs.block_means,
        )))
    }
}

/// Exact GM + white likelihood on block means of the raw record at their mean times.
pub fn from_block_means(times_s: &[f64], means: &[f64]) -> GaussMarkovEstimate {
    match fit_noisy_gauss_markov(times_s, means) {
        Ok(NoisyGaussMarkovOutcome::Model(fit)) => GaussMarkovEstimate::Model {
            correlation_time_s: fit.correlation_time_s,
            sigma: fit.sigma,
            ci95_correlation_time_s: fit.ci95_correlation_time_s,
        },
        Ok(NoisyGaussMarkovOutcome::NoEquivalent { reason }) => {
            GaussMarkovEstimate::NoEquivalent { reason }
        }
        Err(e) => GaussMarkovEstimate::NoEquivalent {
            reason: e.to_string(),
        },
    }
}
