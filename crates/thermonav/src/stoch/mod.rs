//! Stochastic characterisation (the heart of the paper): autocorrelation, autoregressive
//! models, Gauss-Markov models, Allan variance, the Haar wavelet variance and the composite
//! models fitted to it (GMWM); and the deterministic thermal curves
//! (`thermal`).
pub mod acf;
pub mod allan;
pub mod ar;
pub mod bank;
pub mod bank_values;
pub mod characterize;
pub mod gauss_markov;
pub mod gm_family;
pub mod gmwm;
pub mod lot;
pub mod noise_terms;
pub mod noisy_gauss_markov;
pub mod streaming;
pub mod thermal;
pub mod wavelet_variance;
