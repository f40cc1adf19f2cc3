//! The Gauss-Markov families of the bank, one module each behind [`GaussMarkovFamily`]:
//! AR(1)-based (the paper's), exact maximum likelihood on the irregular timestamps (the
//! default, see DESIGN.md), the classical autocorrelation fit, and the bias state of the GMWM
//! composite.
//!
//! A family's module says how files and the command line name it, how it is labelled, how it
//! is fitted and which white noise goes with it; [`FAMILIES`] registers it. Callers name a
//! family by [`GaussMarkovSource`] and ask it, never match on it. The bank keeps a channel's
//! estimates in [`GaussMarkovModels`], one key per family in the order of [`FAMILIES`].
//!
//! Adding a family: a module here implementing [`GaussMarkovFamily`], declared below, and its
//! line in [`FAMILIES`].

pub mod acf_fit;
pub mod ar_based;
mod family;
pub mod gmwm;
pub mod irregular_ml;
mod source;

pub use family::{FamilyNames, FitInputs, GaussMarkovEstimate, GaussMarkovFamily};
pub use source::{GaussMarkovModels, GaussMarkovSource};

/// Every family, in the order the bank writes them (the command line lists the default
/// first, then the others in this order).
pub static FAMILIES: &[&dyn GaussMarkovFamily] = &[
    &ar_based::ArBased,
    &irregular_ml::IrregularMl,
    &acf_fit::AcfFit,
    &gmwm::Gmwm,
];
