//! Allan variance: the overlapping Allan deviation of a rate series, its confidence intervals
//! (noise identification, Greenhall's equivalent degrees of freedom, chi-square bounds) and the
//! IEEE Std 952 noise-term fit (quantisation, angle/velocity random walk, bias instability,
//! rate random walk, rate ramp).
//!
//! Pipeline: [`overlapping_adev`] -> [`confidence_intervals`] -> [`fit_noise_terms`].
//! All three work in the units of the input series (rad/s for gyros, m/s² for accelerometers);
//! [`NoiseTerms`] converts to the customary units at the edge.
//!
//! References: NIST SP 1065 (Riley, *Handbook of Frequency Stability Analysis*, 2008);
//! IEEE Std 952-1997 Annex C; Greenhall & Riley, "Uncertainty of stability variances based on
//! finite differences", PTTI 2003; Riley & Greenhall, "Power law noise identification using the
//! lag 1 autocorrelation", EFTF 2004; El-Sheimy, Hou & Niu, "Analysis and modeling of inertial
//! sensors using Allan variance", IEEE TIM 57(1), 2008.

mod confidence;
mod deviation;
mod edf;
mod noise_id;
mod noise_terms;

pub use confidence::{
    AdevInterval, ChiSquareQuantile, CiSettings, ONE_SIGMA_CONFIDENCE, chi_square_quantile,
    confidence_intervals, interval_from_edf,
};
pub use deviation::{
    AllanCurve, AllanWarning, MIN_SAMPLES, TauGrid, averaging_factors, max_averaging_factor,
    overlapping_adev,
};
pub use edf::edf_overlapping_adev;
pub use noise_id::{
    ACF_MIN_POINTS, NoiseIdMethod, NoiseIdentification, PowerLawNoise, identify_noise,
};
pub use noise_terms::{
    AccelNoiseReport, FitSettings, GyroNoiseReport, NoiseTermKind, NoiseTerms, TermEstimate,
    fit_noise_terms,
};

/// Errors of the Allan-variance functions.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AllanError {
    /// The series is too short for any averaging factor.
    #[error("need at least {min} samples for an overlapping Allan deviation, got {got}")]
    TooFewSamples {
        /// Samples given.
        got: usize,
        /// Samples needed.
        min: usize,
    },
    /// A sample is NaN or infinite.
    #[error("sample {index} is not finite ({value}); remove or interpolate it first")]
    NonFiniteSample {
        /// Position of the first offending sample.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// The sample rate is not a finite positive number.
    #[error("sample rate must be finite and > 0 Hz, got {0} Hz")]
    InvalidSampleRate(f64),
    /// An explicit averaging factor of zero.
    #[error("averaging factors must be >= 1, got 0")]
    ZeroAveragingFactor,
    /// An explicit averaging factor leaves fewer than two estimator terms.
    #[error(
        "averaging factor {m} is too large: at most {max} for {n_samples} samples (N - 2m + 1 >= 2)"
    )]
    AveragingFactorTooLarge {
        /// Requested factor.
        m: usize,
        /// Largest usable factor.
        max: usize,
        /// Series length.
        n_samples: usize,
    },
    /// A dense tau grid with no points.
    #[error("a dense tau grid needs at least 1 point per decade, got 0")]
    ZeroPointsPerDecade,
    /// A confidence level outside (0, 1).
    #[error("confidence level must lie strictly between 0 and 1, got {0}")]
    InvalidConfidenceLevel(f64),
    /// Equivalent degrees of freedom that are not finite and positive.
    #[error("equivalent degrees of freedom must be finite and > 0, got {0}")]
    InvalidEdf(f64),
    /// The series given for confidence intervals is not the one the curve came from.
    #[error("the curve was computed from {curve} samples but {given} samples were given")]
    SampleCountMismatch {
        /// Samples the curve was computed from.
        curve: usize,
        /// Samples given now.
        given: usize,
    },
    /// The averaged series does not vary, so no noise type can be identified.
    #[error("the series averaged over m = {m} samples is constant: its noise type is undefined")]
    ConstantSeries {
        /// Averaging factor.
        m: usize,
    },
    /// A curve whose vectors disagree in length, or with a non-finite, non-positive or
    /// non-increasing tau, or a negative or non-finite deviation.
    #[error("invalid Allan curve: {0}")]
    InvalidCurve(&'static str),
    /// A fit setting out of range.
    #[error("invalid fit setting: {0}")]
    InvalidFitSetting(&'static str),
}
