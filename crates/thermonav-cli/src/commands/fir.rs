//! `thermonav fir`: Kaiser-window low-pass design.

use crate::args::{FirArgs, KaiserArgs};
use crate::failure::{Classify, Failure};
use crate::report::{print_json, print_rows};
use serde::Serialize;
use thermonav::signal::kaiser::{FirFilter, KaiserSpec, design_kaiser_lowpass};

/// The JSON document of `fir --json`.
#[derive(Debug, Serialize)]
pub struct FirDesign {
    sample_rate_hz: f64,
    cutoff_hz: f64,
    transition_hz: f64,
    ripple_db: f64,
    pub num_taps: usize,
    pub beta: f64,
    group_delay_s: f64,
    taps: Vec<f64>,
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

/// Runs `fir`.
pub fn run(args: &FirArgs) -> Result<(), Failure> {
    let (_, filter) = design(args.fs_hz, &args.kaiser)?;
    let described = describe(&filter, &args.kaiser);
    if args.json {
        return print_json(&described);
    }
    print_rows(&[
        ("sample rate", format!("{} Hz", described.sample_rate_hz)),
        ("cut-off", format!("{} Hz", described.cutoff_hz)),
        (
            "transition width",
            format!("{} Hz", described.transition_hz),
        ),
        (
            "ripple / attenuation",
            format!("{} dB", described.ripple_db),
        ),
        ("taps", described.num_taps.to_string()),
        ("Kaiser beta", format!("{:.6}", described.beta)),
        ("group delay", format!("{:.6} s", described.group_delay_s)),
    ]);
    Ok(())
}
