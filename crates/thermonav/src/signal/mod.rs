//! Signal conditioning: timestamp checks, Kaiser-window FIR design, zero-phase filtering and
//! decimation (paper step 2: de-noising before stochastic modelling), and wavelet de-noising,
//! the paper's named alternative ([`wavelet`]: the same `&[f64]` in, the same length out).

pub mod convolution;
pub mod decimate;
pub mod kaiser;
pub mod streaming_decimate;
pub mod timestamps;
pub mod wavelet;
pub mod zero_phase;

/// Why a signal-conditioning step cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SignalError {
    /// An invalid filter specification.
    #[error("{message}")]
    Spec {
        /// What is wrong.
        message: String,
    },
    /// The signal is too short for the edge extension.
    #[error(
        "{samples} samples are too few for a {taps}-tap zero-phase filter: at least {needed} are needed"
    )]
    TooShort {
        /// Samples given.
        samples: usize,
        /// Samples needed.
        needed: usize,
        /// Taps of the filter.
        taps: usize,
    },
    /// The one-pass mode needs an odd number of taps.
    #[error("delay-compensated filtering needs an odd number of taps, the filter has {taps}")]
    EvenTaps {
        /// Taps of the filter.
        taps: usize,
    },
    /// A NaN or infinite sample.
    #[error("sample {index} is not a finite number")]
    NonFinite {
        /// Index of the sample.
        index: usize,
    },
    /// A low-pass whose stop band starts above the Nyquist frequency of the decimated rate.
    #[error(
        "the stop band starts at cut-off {cutoff_hz} Hz + half the transition {transition_hz} Hz = {stop_band_hz} Hz, above the Nyquist frequency {nyquist_hz} Hz of the {target_rate_hz} Hz decimated rate: the decimated series would alias"
    )]
    Aliasing {
        /// Cut-off, Hz.
        cutoff_hz: f64,
        /// Transition width, Hz.
        transition_hz: f64,
        /// Start of the stop band, Hz.
        stop_band_hz: f64,
        /// Nyquist frequency of the decimated rate, Hz.
        nyquist_hz: f64,
        /// Decimated rate, Hz.
        target_rate_hz: f64,
    },
    /// A wavelet decomposition level the signal's length does not allow.
    #[error(
        "wavelet level {level} is not possible for {samples} samples and a {filter_len}-tap wavelet: the level must be 1..={max_level} (PyWavelets' dwt_max_level)"
    )]
    WaveletLevel {
        /// Level asked for.
        level: usize,
        /// Deepest level for the length (0: too short for one).
        max_level: usize,
        /// Samples.
        samples: usize,
        /// Taps of the wavelet's filters.
        filter_len: usize,
    },
    /// A signal too short for one level of the wavelet transform.
    #[error(
        "{samples} samples are too few for a wavelet decomposition with a {filter_len}-tap wavelet: at least {needed} are needed"
    )]
    WaveletTooShort {
        /// Samples.
        samples: usize,
        /// Samples needed for one level (taps − 1).
        needed: usize,
        /// Taps of the wavelet's filters.
        filter_len: usize,
    },
    /// Decimation impossible.
    #[error("cannot decimate {input_rate_hz} Hz to {target_rate_hz} Hz: {reason}")]
    Decimation {
        /// Input rate.
        input_rate_hz: f64,
        /// Requested rate.
        target_rate_hz: f64,
        /// Why.
        reason: String,
    },
}
