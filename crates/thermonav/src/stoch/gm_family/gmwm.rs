//! The bias state of the GMWM composite ([`crate::stoch::gmwm::map_to_filter_states`]), with
//! the composite's white noise: fitted only when the characterisation asks for GMWM.

use super::family::{FamilyNames, FitInputs, GaussMarkovEstimate, GaussMarkovFamily};

/// The GMWM family (`gmwm`).
pub struct Gmwm;

const NAMES: FamilyNames = FamilyNames {
    name: "gmwm",
    cli_name: "gmwm",
    help: "The bias state of the GMWM composite, with the composite's white noise",
    label: "GMWM bias state",
};

impl GaussMarkovFamily for Gmwm {
    fn names(&self) -> &'static FamilyNames {
        &NAMES
    }

    fn when_absent(&self) -> Option<&'static str> {
        Some(
            "the bank has no GMWM model (characterized with --gmwm off, or before GMWM entered \
             the bank)",
        )
    }

    fn fit(&self, inputs: &FitInputs<'_>) -> Result<Option<GaussMarkovEstimate>, String> {
        Ok(inputs.gmwm_bias.cloned())
    }

    /// The composite's mapped density: its white noise plus the Gauss-Markov processes shorter
    /// than the bias state (none without a composite).
    fn white_noise_density(&self, allan: Option<f64>, composite: Option<f64>) -> Option<f64> {
        let _ = allan;
        composite
    }

    /// A composite with no process slower than the white-noise band (white noise alone, or
    /// with a drift the mapping drops) maps to a bias state of σ = 0.
    fn sigma_may_be_zero(&self) -> bool {
        true
    }
}
