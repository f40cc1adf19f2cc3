//! What every Gauss-Markov family of the bank is ([`GaussMarkovFamily`]), the estimate it
//! leaves in the bank ([`GaussMarkovEstimate`]) and what it is fitted from ([`FitInputs`]).

use crate::stoch::ar::ArMethod;
use crate::stoch::gauss_markov::{GaussMarkovOutcome, LagWindow};
use serde::{Deserialize, Serialize};

/// A Gauss-Markov estimate, or the reason there is none.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum GaussMarkovEstimate {
    /// A first-order Gauss-Markov model.
    Model {
        /// Correlation time Tc, s.
        correlation_time_s: f64,
        /// Standard deviation σ, channel unit.
        sigma: f64,
        /// 95 % interval of Tc, s; `None` for an unbounded side.
        ci95_correlation_time_s: [Option<f64>; 2],
    },
    /// No Gauss-Markov equivalent (e.g. AR c₁ ≥ 1: random walk or drift).
    NoEquivalent {
        /// Why, in words.
        reason: String,
    },
}

impl From<GaussMarkovOutcome> for GaussMarkovEstimate {
    /// A Gauss-Markov outcome as the bank keeps it.
    fn from(outcome: GaussMarkovOutcome) -> Self {
        match outcome {
            GaussMarkovOutcome::Model {
                model,
                ci95_correlation_time_s,
            } => Self::Model {
                correlation_time_s: model.correlation_time_s,
                sigma: model.sigma,
                ci95_correlation_time_s,
            },
            GaussMarkovOutcome::NoEquivalent { reason } => Self::NoEquivalent { reason },
        }
    }
}

/// What the families of one channel are fitted from (prepared by
/// [`crate::stoch::characterize`]).
#[derive(Debug, Clone, Copy)]
pub struct FitInputs<'a> {
    /// The de-noised series at the modelling rate.
    pub conditioned: &'a [f64],
    /// Its sampling interval, s.
    pub dt_s: f64,
    /// The AR estimator.
    pub ar_method: ArMethod,
    /// The lag window of the autocorrelation fit.
    pub acf_window: LagWindow,
    /// Mean times of the raw record's blocks, s.
    pub block_times_s: &'a [f64],
    /// The raw record's block means.
    pub block_means: &'a [f64],
    /// The bias state of the channel's GMWM composite, when one was fitted (the composite is
    /// fitted once per channel: the bank also keeps it whole, `ChannelModel::gmwm`).
    pub gmwm_bias: Option<&'a GaussMarkovEstimate>,
}

/// How a family is named and described.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FamilyNames {
    /// Its name in files (the bank's key, `evaluation.json`, Python's `model=`):
    /// `irregular_ml`.
    pub name: &'static str,
    /// Its value on the command line (`--model`, `--families`) and in exported text:
    /// `irregular-ml`.
    pub cli_name: &'static str,
    /// One line on it for the command line's help.
    pub help: &'static str,
    /// Its legend name in figures.
    pub label: &'static str,
}

/// One Gauss-Markov family: how the bank, the files and the command line name it, how it is
/// fitted and what the filter takes with it. Each family is one module of
/// [`crate::stoch::gm_family`], listed once in its registry.
pub trait GaussMarkovFamily: Sync {
    /// How files, the command line and figures name it.
    fn names(&self) -> &'static FamilyNames;

    /// `None` when every bank has it (a bank file without it is refused); otherwise the reason
    /// given when a bank lacks it.
    fn when_absent(&self) -> Option<&'static str> {
        None
    }

    /// Its estimate of one channel; `Ok(None)` when it was not fitted (only for a family with
    /// [`GaussMarkovFamily::when_absent`]).
    ///
    /// # Errors
    /// Why the channel cannot be modelled at all, in words.
    fn fit(&self, inputs: &FitInputs<'_>) -> Result<Option<GaussMarkovEstimate>, String>;

    /// The white-noise density the filter takes beside this family's bias state, from the
    /// Allan curve's `allan` and the GMWM composite's mapped `composite` (channel unit·√s):
    /// the Allan curve's unless the family says otherwise.
    fn white_noise_density(&self, allan: Option<f64>, composite: Option<f64>) -> Option<f64> {
        let _ = composite;
        allan
    }

    /// True when its model may have σ = 0 (no bias process), which a bank's value checks then
    /// accept; false for the families whose fit always finds one.
    fn sigma_may_be_zero(&self) -> bool {
        false
    }
}
