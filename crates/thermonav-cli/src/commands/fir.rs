//! `thermonav fir`: Kaiser-window low-pass design.

use crate::args::FirArgs;
use crate::failure::Failure;
use crate::fir_design::{describe, design};
use crate::report::{print_json, print_rows};

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
