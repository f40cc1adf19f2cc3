//! The paper's AR(1)-based Gauss-Markov model (its equations 8-10): the AR(1) fit of the
//! conditioned series turned into Tc and σ.

use super::family::{FamilyNames, FitInputs, GaussMarkovEstimate, GaussMarkovFamily};
use crate::stoch::ar::{ArModel, fit_ar};
use crate::stoch::gauss_markov::{Ar1Estimate, ar_based};

/// The AR(1)-based family (`ar_based`).
pub struct ArBased;

const NAMES: FamilyNames = FamilyNames {
    name: "ar_based",
    cli_name: "ar-based",
    help: "The paper's AR(1)-based model",
    label: "AR(1)-based",
};

impl GaussMarkovFamily for ArBased {
    fn names(&self) -> &'static FamilyNames {
        &NAMES
    }

    fn fit(&self, inputs: &FitInputs<'_>) -> Result<Option<GaussMarkovEstimate>, String> {
        let ar1 = fit_ar(inputs.conditioned, 1, inputs.ar_method).map_err(|e| e.to_string())?;
        Ok(Some(from_ar1(&ar1, inputs.dt_s)))
    }
}

/// The AR(1) fit `ar1` of a series sampled every `dt_s` seconds, as the input of
/// [`ar_based`].
pub fn ar1_estimate(ar1: &ArModel, dt_s: f64) -> Ar1Estimate {
    Ar1Estimate {
        c1: ar1.coefficients[0],
        c1_std_error: ar1.std_errors[0],
        innovation_variance: ar1.noise_variance,
        dt_s,
    }
}

/// The AR-based model of an AR(1) fit of a series sampled every `dt_s` seconds, as the bank's
/// `ar_based`.
pub fn from_ar1(ar1: &ArModel, dt_s: f64) -> GaussMarkovEstimate {
    ar_based(&ar1_estimate(ar1, dt_s)).into()
}
