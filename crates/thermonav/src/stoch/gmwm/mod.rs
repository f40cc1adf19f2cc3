//! The Generalized Method of Wavelet Moments (GMWM): a composite noise model (white noise,
//! quantisation noise, random walk, drift and k first-order Gauss-Markov processes) fitted to
//! the whole Haar wavelet variance of a series (Guerrier, Skaloud, Stebler & Victoria-Feser
//! 2013, JASA 108(502)).
//!
//! θ̂ = argmin (ν̂ − ν(θ))ᵀ Ω (ν̂ − ν(θ)), ν̂ the Haar wavelet variance at scales 2^j
//! ([`crate::stoch::wavelet_variance`]), ν(θ) the sum of the processes' closed forms
//! ([`theory`]) and Ω = diag(1/var(ν̂²_j)) from the η₃ chi-square approximation. The
//! optimiser works on the logarithms of the variances and of the correlation times (so every
//! variance stays positive); the Gauss-Markov processes are labelled by increasing correlation
//! time. Starting values are automatic ([`fit_gmwm`]); intervals come from a parametric
//! bootstrap ([`estimate_gmwm`]), and candidate composites are ranked by the Wavelet
//! Information Criterion ([`select_model`]). The selected composite is reported with the
//! processes the record does not resolve left out ([`resolve_selection`]) and the
//! Gauss-Markov processes at the record's edges merged into the white noise or the random walk
//! ([`GmwmEstimate::reported`]). Results are reported in physical units ([`Parameter`]).
//!
//! The R package gmwm (SMAC-Group) is the reference implementation of the method; it is not on
//! this machine (CRAN is unreachable), so the oracles are the closed forms against their slow
//! definitions, recovery and interval coverage on simulated composites, and the exact
//! likelihood of white noise plus one Gauss-Markov process
//! ([`crate::stoch::noisy_gauss_markov`]).

mod bootstrap;
mod fit;
mod mapping;
mod merging;
mod model;
mod resolution;
mod simulate;
pub mod theory;

pub use bootstrap::{
    ADEQUACY_LEVEL, AUTO_CANDIDATES, BootstrapSettings, GmwmEstimate, MAX_BOOTSTRAP_REPLICATES,
    MAX_SKIPPED_SCALES, MIN_BOOTSTRAP_REPLICATES, ModelSelection, ParameterEstimate,
    auto_candidates, estimate_gmwm, fit_from_first_adequate_scale, rank_by_asymptotic_wic,
    select_model,
};
pub use fit::{GmwmFit, fit_gmwm};
pub use mapping::{Fold, MappedNoise, TauBand, band_scales, map_to_filter_states};
pub use merging::{MergedInto, MergedProcess, WHITE_MERGE_SAMPLE_PERIODS};
pub use model::{
    ModelSpec, ModelSpecError, Parameter, PhysicalParameter, Term, composite_wavelet_variance,
    physical_parameters, terms_from_parameters,
};
pub use resolution::{AbsentProcess, RESOLUTION_LEVEL, ResolvedModel, resolve_selection};
pub use simulate::simulate;

/// Why a GMWM fit cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GmwmError {
    /// Not more scales than parameters.
    #[error("{scales} wavelet scales cannot identify {parameters} parameters")]
    TooFewScales {
        /// Scales of the wavelet variance.
        scales: usize,
        /// Parameters of the model.
        parameters: usize,
    },
    /// A scale with zero wavelet variance (a constant series) has no weight.
    #[error("the wavelet variance is zero at scale {scale_samples} samples")]
    ZeroWaveletVariance {
        /// The scale, samples.
        scale_samples: usize,
    },
    /// Bad bootstrap settings.
    #[error(
        "replicates: 0 (no bootstrap) or {} to {} bootstrap replicates, got {replicates}",
        bootstrap::MIN_BOOTSTRAP_REPLICATES,
        bootstrap::MAX_BOOTSTRAP_REPLICATES
    )]
    BootstrapReplicates {
        /// Replicates asked for.
        replicates: usize,
    },
    /// A confidence level outside (0, 1).
    #[error("confidence: the intervals' level must lie in (0, 1), got {confidence}")]
    BootstrapConfidence {
        /// Level asked for.
        confidence: f64,
    },
    /// Too few bootstrap replicates could be refitted to estimate the WIC and the intervals.
    #[error(
        "{model}: only {succeeded} of {asked} bootstrap refits succeeded (at least {} are needed): the composite is not identified on this record",
        bootstrap::MIN_BOOTSTRAP_REPLICATES
    )]
    BootstrapRefits {
        /// The composite.
        model: String,
        /// Refits that succeeded.
        succeeded: usize,
        /// Replicates asked for.
        asked: usize,
    },
    /// The WIC or an interval came out non-finite (a parameter estimated at zero, whose
    /// logarithm the intervals take).
    #[error("{model}: its {what} is not finite (a parameter estimated at zero or beyond range)")]
    NonFiniteEstimate {
        /// The composite.
        model: String,
        /// What (`WIC`, or a parameter's interval).
        what: String,
    },
    /// No candidate model.
    #[error("no candidate model to select from")]
    NoCandidates,
}
