//! Wavelet shrinkage de-noising of one evenly sampled channel: decompose, threshold the
//! details level by level, reconstruct, same length out.
//!
//! The noise level σ̂ is read once from the finest details ([`noise_sigma_mad`]) and used at
//! every level, which assumes white noise (Donoho & Johnstone 1994); the approximation
//! coefficients are kept as they are. Defaults ([`WaveletDenoise::default`]): db4, the deepest
//! level PyWavelets allows for the length ([`max_level`]), the symmetric extension, the
//! universal threshold, soft thresholding (VisuShrink).

use super::daubechies::Daubechies;
use super::threshold::{ThresholdRule, Thresholding, noise_sigma_mad};
use super::transform::{ExtensionMode, check_level, max_level, wavedec, waverec};
use crate::signal::SignalError;

/// How deep the decomposition goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum DecompositionLevel {
    /// The deepest level for the signal's length ([`max_level`], PyWavelets'
    /// `dwt_max_level`).
    #[default]
    Max,
    /// This level (1 ≤ L ≤ the maximum for the length).
    Fixed(usize),
}

/// Settings of the wavelet de-noising.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct WaveletDenoise {
    /// The wavelet.
    pub wavelet: Daubechies,
    /// Decomposition depth.
    pub level: DecompositionLevel,
    /// Extension at the ends.
    pub mode: ExtensionMode,
    /// Threshold rule.
    pub rule: ThresholdRule,
    /// Soft or hard.
    pub thresholding: Thresholding,
}

impl Default for WaveletDenoise {
    fn default() -> Self {
        Self {
            wavelet: DEFAULT_WAVELET,
            level: DecompositionLevel::Max,
            mode: ExtensionMode::Symmetric,
            rule: ThresholdRule::Universal,
            thresholding: Thresholding::Soft,
        }
    }
}

/// The default wavelet, db4 (8 taps).
pub const DEFAULT_WAVELET: Daubechies = Daubechies::DB4;

/// What the de-noising did: the level used, σ̂ and the threshold of every level.
#[derive(Debug, Clone, PartialEq)]
pub struct Denoised {
    /// The de-noised samples, as many as the input.
    pub values: Vec<f64>,
    /// The decomposition level used.
    pub level: usize,
    /// σ̂, in the unit of the samples.
    pub noise_sigma: f64,
    /// The threshold of each level, finest (level 1) first, in the unit of the samples.
    pub thresholds: Vec<f64>,
}

impl WaveletDenoise {
    /// The level these settings use for `samples` samples.
    ///
    /// # Errors
    /// [`SignalError::WaveletLevel`] when the level is 0 or above the maximum for the length,
    /// [`SignalError::WaveletTooShort`] when the signal is too short for one level.
    pub fn level_for(&self, samples: usize) -> Result<usize, SignalError> {
        let filter_len = self.wavelet.filter_len();
        let level = match self.level {
            DecompositionLevel::Max => max_level(samples, filter_len),
            DecompositionLevel::Fixed(level) => level,
        };
        check_level(level, samples, filter_len)?;
        Ok(level)
    }
}

/// `x` de-noised by wavelet shrinkage with `settings`.
///
/// # Errors
/// [`SignalError::NonFinite`] for a NaN or infinite sample, [`SignalError::WaveletLevel`] or
/// [`SignalError::WaveletTooShort`] for a level the length does not allow.
pub fn denoise(x: &[f64], settings: &WaveletDenoise) -> Result<Denoised, SignalError> {
    let level = settings.level_for(x.len())?;
    let bank = settings.wavelet.filter_bank();
    let mut decomposition = wavedec(x, &bank, settings.mode, level)?;
    let noise_sigma = noise_sigma_mad(decomposition.finest_details());
    let mut thresholds: Vec<f64> = decomposition
        .details_mut()
        .map(|band| {
            let lambda = settings.rule.threshold(band, noise_sigma, x.len());
            settings.thresholding.apply_to(band, lambda);
            lambda
        })
        .collect();
    thresholds.reverse();
    let mut values = waverec(&decomposition, &bank);
    values.truncate(x.len());
    Ok(Denoised {
        values,
        level,
        noise_sigma,
        thresholds,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_the_length_and_a_smooth_signal() {
        let x: Vec<f64> = (0..1001).map(|i| (i as f64 / 150.0).sin()).collect();
        let out = denoise(&x, &WaveletDenoise::default()).unwrap();
        assert_eq!(out.values.len(), x.len());
        assert_eq!(out.level, max_level(1001, 8));
        let worst = x.iter().zip(&out.values).map(|(a, b)| (a - b).abs());
        assert!(worst.fold(0.0, f64::max) < 1e-3);
    }

    #[test]
    fn too_short_or_too_deep_is_refused() {
        let settings = WaveletDenoise {
            level: DecompositionLevel::Fixed(3),
            ..WaveletDenoise::default()
        };
        assert!(matches!(
            denoise(&[1.0; 20], &settings),
            Err(SignalError::WaveletLevel {
                level: 3,
                max_level: 1,
                ..
            })
        ));
        assert!(denoise(&[1.0; 3], &WaveletDenoise::default()).is_err());
        assert!(denoise(&[], &WaveletDenoise::default()).is_err());
    }
}
