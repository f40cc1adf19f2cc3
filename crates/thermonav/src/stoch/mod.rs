//! Stochastic characterisation (the heart of the paper): autocorrelation, autoregressive
//! models, Gauss-Markov models and Allan variance.

pub mod acf;
pub mod ar;
