//! Wavelet de-noising, the paper's named alternative to the Kaiser low-pass: decompose with a
//! Daubechies wavelet, shrink the detail coefficients level by level, reconstruct (Donoho &
//! Johnstone 1994, "Ideal spatial adaptation by wavelet shrinkage", Biometrika 81(3); 1995,
//! "Adapting to unknown smoothness via wavelet shrinkage", JASA 90(432)).
//!
//! - [`daubechies`]: the filters db1..db10 from their definition (spectral factorisation);
//! - [`transform`]: the multilevel discrete wavelet transform, equal to PyWavelets'
//!   `wavedec`/`waverec` for its modes `symmetric` (its default) and `periodization`, the only
//!   two here;
//! - [`threshold`]: soft and hard thresholding (`pywt.threshold`), the noise level from the
//!   median absolute deviation, the universal (VisuShrink) and SURE (SureShrink, with and
//!   without the hybrid rule) thresholds;
//! - [`denoise`]: the three steps together, same length out as in.
//!
//! Like the Kaiser path it takes `&[f64]` evenly spaced samples and gives the same length out.

pub mod daubechies;
pub mod denoise;
pub mod threshold;
pub mod transform;
