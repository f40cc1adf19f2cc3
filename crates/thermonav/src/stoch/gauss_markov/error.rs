//! The one error type of the Gauss-Markov module.

/// Why a Gauss-Markov computation refused its input.
///
/// Outcomes that are answers rather than faults (an AR(1) coefficient with no Gauss-Markov
/// equivalent, a likelihood maximum on the random-walk edge, an autocovariance that does not
/// decay) are not errors: they are variants of each function's outcome enum.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GaussMarkovError {
    /// A parameter that must be a finite positive number was not.
    #[error("{name} must be finite and > 0, got {value}")]
    NotPositive {
        /// Which parameter.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// A derived quantity does not fit in an `f64` (overflow or underflow).
    #[error("{quantity} = {value} is outside the range an f64 can represent usefully")]
    OutOfRange {
        /// Which quantity.
        quantity: &'static str,
        /// Its value (possibly infinite or zero).
        value: f64,
    },
    /// A sample (value or time) was NaN or infinite.
    #[error("{name}[{index}] must be finite, got {value}")]
    NonFinite {
        /// Which input sequence.
        name: &'static str,
        /// Position of the first offending sample.
        index: usize,
        /// The value found there.
        value: f64,
    },
    /// Fewer samples than the computation needs.
    #[error("need at least {needed} samples, got {got}")]
    TooShort {
        /// Minimum number of samples.
        needed: usize,
        /// Number given.
        got: usize,
    },
    /// Times and values differ in length.
    #[error("times and values must have the same length, got {times} times and {values} values")]
    LengthMismatch {
        /// Number of times.
        times: usize,
        /// Number of values.
        values: usize,
    },
    /// Sample times that do not increase strictly.
    #[error(
        "times must increase strictly: t[{index}] = {current_s} s is not after the previous {previous_s} s"
    )]
    NonIncreasingTime {
        /// Index of the later sample of the offending pair.
        index: usize,
        /// The earlier time, in seconds.
        previous_s: f64,
        /// The later time, in seconds.
        current_s: f64,
    },
    /// The values do not vary (about zero or about their mean, as the mean model says).
    #[error("the values have zero spread about {about}; a Gauss-Markov model needs variation")]
    ZeroVariance {
        /// What the spread was measured about: "zero" or "their mean".
        about: &'static str,
    },
    /// A standard error that is negative or not finite.
    #[error("the standard error of c1 must be finite and >= 0, got {value}")]
    InvalidStdError {
        /// The value given.
        value: f64,
    },
    /// A confidence level outside (0, 1).
    #[error("a confidence level must lie strictly between 0 and 1, got {value}")]
    InvalidConfidenceLevel {
        /// The value given.
        value: f64,
    },
    /// A correlation threshold of a lag window outside (0, 1).
    #[error(
        "the autocorrelation threshold of the lag window must lie strictly between 0 and 1, got {value}"
    )]
    InvalidRhoThreshold {
        /// The value given.
        value: f64,
    },
    /// The lag window keeps too few lags for a two-parameter fit.
    #[error("the lag window keeps {got} usable lags; the fit needs at least {needed}")]
    TooFewLags {
        /// Minimum number of lags.
        needed: usize,
        /// Number kept.
        got: usize,
    },
}
