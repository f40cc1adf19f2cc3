//! Zero-phase filtering with a linear-phase FIR filter.
//!
//! Both modes extend the signal at each end by odd reflection about its end value,
//! 2 x₀ − x[P..1] before and 2 x_{n−1} − x[n−2..n−P−1] after, with P = 3 N (SciPy's default
//! `padlen` for `filtfilt`), so that edges see a continuation with the right level and slope.
//!
//! - [`ZeroPhaseMode::ForwardBackward`] is SciPy's `filtfilt(h, [1.0], x)` with its defaults:
//!   filter the extended signal forward starting from the steady state of its first value
//!   (`lfilter_zi`), reverse, filter again from the steady state of the new first value,
//!   reverse, drop the extensions. The magnitude response is squared (2 × the attenuation).
//! - [`ZeroPhaseMode::DelayCompensated`] runs one forward pass and reads each output (N−1)/2
//!   samples later, which removes the linear-phase delay exactly for an odd N; the response is
//!   the design's (1 × the attenuation). Even N is refused: use
//!   [`FirFilter::with_odd_taps`](super::kaiser::FirFilter::with_odd_taps).

use super::SignalError;
use super::convolution::convolve;
use super::kaiser::{FirFilter, KaiserSpec};

/// How the delay of the filter is removed (the default: one pass, for `thermonav filter` and
/// Python's `zero_phase` and `decimate`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum ZeroPhaseMode {
    /// One pass, output advanced by the group delay.
    #[default]
    DelayCompensated,
    /// Forward and backward passes (SciPy `filtfilt`).
    ForwardBackward,
}

impl ZeroPhaseMode {
    /// The mode's name on the command line, in Python and in the records: `zero-phase` (one
    /// pass, delay removed) or `filtfilt`.
    pub fn name(self) -> &'static str {
        match self {
            ZeroPhaseMode::DelayCompensated => "zero-phase",
            ZeroPhaseMode::ForwardBackward => "filtfilt",
        }
    }

    /// The mode called `name` ([`ZeroPhaseMode::name`]), if any.
    pub fn from_name(name: &str) -> Option<Self> {
        [Self::DelayCompensated, Self::ForwardBackward]
            .into_iter()
            .find(|m| m.name() == name)
    }
}

/// Half-width of the zero-phase response in samples: an output within this many samples of an
/// end of the record reads the edge extension. (N − 1)/2 for the one-pass mode (the taps
/// centred on the output); N − 1 for forward-backward (the response of the two passes is the
/// filter convolved with itself, 2N − 1 taps).
pub fn edge_samples(filter: &FirFilter, mode: ZeroPhaseMode) -> usize {
    let taps = filter.num_taps();
    match mode {
        ZeroPhaseMode::DelayCompensated => (taps.saturating_sub(1)) / 2,
        ZeroPhaseMode::ForwardBackward => taps.saturating_sub(1),
    }
}

/// The filter as run in `mode`, from the design of `spec`: the one-pass mode needs a
/// whole-sample delay, so an even design gets one more tap ([`FirFilter::with_odd_taps`]);
/// forward-backward runs the design as it is.
pub fn filter_for_mode(designed: FirFilter, spec: &KaiserSpec, mode: ZeroPhaseMode) -> FirFilter {
    match mode {
        ZeroPhaseMode::DelayCompensated => designed.with_odd_taps(spec),
        ZeroPhaseMode::ForwardBackward => designed,
    }
}

/// Samples left out at each end when a filtered record is decimated by `factor`: with
/// decimation (factor > 1) only outputs whose response lies inside the record are kept
/// ([`edge_samples`]; the first output would be the raw first sample); without, every row is
/// (SciPy's `filtfilt`).
pub fn decimation_edge_samples(filter: &FirFilter, mode: ZeroPhaseMode, factor: usize) -> usize {
    if factor > 1 {
        edge_samples(filter, mode)
    } else {
        0
    }
}

/// Filters `x` without phase shift; the output has the length of the input.
///
/// # Errors
/// [`SignalError::TooShort`] when `x` is not longer than the 3 N extension (as SciPy),
/// [`SignalError::EvenTaps`] for the one-pass mode with an even number of taps, and
/// [`SignalError::NonFinite`] for a NaN or infinite sample.
pub fn filter_zero_phase(
    filter: &FirFilter,
    x: &[f64],
    mode: ZeroPhaseMode,
) -> Result<Vec<f64>, SignalError> {
    let taps = filter.taps();
    let pad = 3 * taps.len();
    if x.len() <= pad {
        return Err(SignalError::TooShort {
            samples: x.len(),
            needed: pad + 1,
            taps: taps.len(),
        });
    }
    if let Some(index) = x.iter().position(|v| !v.is_finite()) {
        return Err(SignalError::NonFinite { index });
    }
    let extended = odd_extension(x, pad);
    match mode {
        ZeroPhaseMode::ForwardBackward => Ok(forward_backward(&extended, taps, pad, x.len())),
        ZeroPhaseMode::DelayCompensated => {
            if taps.len() % 2 == 0 {
                return Err(SignalError::EvenTaps { taps: taps.len() });
            }
            let y = convolve(&extended, taps, extended[0]);
            let delay = (taps.len() - 1) / 2;
            Ok(y[pad + delay..pad + delay + x.len()].to_vec())
        }
    }
}

/// x with `pad` samples of odd reflection added at each end.
pub fn odd_extension(x: &[f64], pad: usize) -> Vec<f64> {
    let (first, last) = (x[0], x[x.len() - 1]);
    let n = x.len();
    let mut out = Vec::with_capacity(n + 2 * pad);
    out.extend((1..=pad).rev().map(|k| 2.0 * first - x[k]));
    out.extend_from_slice(x);
    out.extend((1..=pad).map(|k| 2.0 * last - x[n - 1 - k]));
    out
}

fn forward_backward(extended: &[f64], taps: &[f64], pad: usize, n: usize) -> Vec<f64> {
    let forward = convolve(extended, taps, extended[0]);
    let mut reversed: Vec<f64> = forward.into_iter().rev().collect();
    let history = reversed[0];
    reversed = convolve(&reversed, taps, history);
    reversed.reverse();
    reversed[pad..pad + n].to_vec()
}
