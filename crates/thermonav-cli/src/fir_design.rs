//! Kaiser-window low-pass designs from the command line's specification, and their
//! description (`fir --json`, the `filter` sidecar).

use crate::args::KaiserArgs;
use crate::failure::{Classify, Failure};
use serde::Serialize;
use thermonav::signal::kaiser::{FirFilter, KaiserSpec, design_kaiser_lowpass};

/// The JSON document of `fir --json`.
#[derive(Debug, Serialize)]
pub struct FirDesign {
    /// Sampling rate of the design, Hz.
    pub sample_rate_hz: f64,
    /// Pass-band edge, Hz.
    pub cutoff_hz: f64,
    /// Transition width, Hz.
    pub transition_hz: f64,
    /// Ripple and attenuation, dB.
    pub ripple_db: f64,
    /// Number of taps.
    pub num_taps: usize,
    /// Kaiser window parameter.
    pub beta: f64,
    /// Group delay, s.
    pub group_delay_s: f64,
    /// The taps.
    pub taps: Vec<f64>,
}

/// Validates the specification and designs the filter; a bad specification is a usage error.
pub fn design(
    sample_rate_hz: f64,
    kaiser: &KaiserArgs,
) -> Result<(KaiserSpec, FirFilter), Failure> {
    let spec = KaiserSpec::new(
        sample_rate_hz,
        kaiser.cutoff_hz,
        kaiser.transition_hz,
        kaiser.ripple_db,
    )
    .usage()?;
    let filter = design_kaiser_lowpass(&spec).usage()?;
    Ok((spec, filter))
}

/// Describes a designed filter for JSON output.
pub fn describe(filter: &FirFilter, kaiser: &KaiserArgs) -> FirDesign {
    FirDesign {
        sample_rate_hz: filter.sample_rate_hz(),
        cutoff_hz: kaiser.cutoff_hz,
        transition_hz: kaiser.transition_hz,
        ripple_db: kaiser.ripple_db,
        num_taps: filter.num_taps(),
        beta: filter.beta(),
        group_delay_s: filter.group_delay_s(),
        taps: filter.taps().to_vec(),
    }
}
