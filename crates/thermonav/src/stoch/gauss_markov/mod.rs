//! First-order Gauss-Markov (GM) models of sensor errors, obtained three ways, and their exact
//! simulation.
//!
//! - [`GaussMarkov`]: the model itself (eqs. 1-4 of `method.md`): transition `phi(dt)`, exact
//!   driving-noise variance, autocovariance, spectral density.
//! - [`gauss_markov_from_ar1`]: the AR-based GM of El-Diasty & Pagiatakis (2009), eqs. 8-10,
//!   from any AR(1) estimate, with the interval of `Tc` mapped from the interval of `c1`.
//! - [`fit_gauss_markov_exact_ml`]: exact maximum likelihood on irregular timestamps, each step
//!   with its own interval, with a likelihood-ratio interval of `Tc`; the mean is known
//!   ([`MeanModel::Zero`]), profiled ([`MeanModel::Estimated`]) or integrated out (REML,
//!   [`MeanModel::Restricted`], the choice when `Tc` may approach the record length). Unbiased
//!   under jitter and gaps, where the AR(1) route with a nominal interval is not.
//! - [`fit_gauss_markov_to_autocovariance`] and [`e_folding_time`]: the classical fit of an
//!   exponential to the autocovariance, and the 1/e shortcut (the methods the paper improves on).
//! - [`simulate_gauss_markov`]: an exact path at given sampling times, with the caller's RNG.
//!
//! Answers that are not models (an AR(1) coefficient outside (0, 1), a likelihood peaking at
//! the random-walk or white-noise end, an autocovariance that does not decay) are enum
//! variants; faulty input is a [`GaussMarkovError`]. No function returns NaN or an infinity.

mod acf_fit;
mod ar_based;
mod error;
mod exact_ml;
mod intervals;
mod model;
mod search;
mod simulate;

pub use acf_fit::{
    AcfFit, AcfGaussMarkov, EFoldingTime, LagWindow, MIN_FIT_LAGS, ZeroLag, e_folding_time,
    fit_gauss_markov_to_autocovariance,
};
pub use ar_based::{
    Ar1Estimate, ArGaussMarkov, ArGaussMarkovFit, NoGaussMarkovEquivalent, gauss_markov_from_ar1,
};
pub use error::GaussMarkovError;
pub use exact_ml::{
    ExactMlFit, ExactMlOutcome, MIN_ML_SAMPLES, MeanModel, fit_gauss_markov_exact_ml,
    gauss_markov_log_likelihood,
};
pub use intervals::SampleIntervals;
pub use model::{ConfidenceLevel, CorrelationTimeInterval, GaussMarkov, UpperBound};
pub use simulate::simulate_gauss_markov;
