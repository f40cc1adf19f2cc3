//! Arguments of `thermonav fir`.

use clap::Args;
use thermonav::signal::kaiser::{DEFAULT_RIPPLE_DB, DEFAULT_TRANSITION_HZ};

/// Kaiser low-pass specification shared by `fir` and `filter`.
#[derive(Debug, Args, Clone, Copy)]
pub struct KaiserArgs {
    /// Pass-band edge (cut-off), Hz.
    #[arg(long)]
    pub cutoff_hz: f64,
    /// Width of the transition band, Hz.
    #[arg(long, default_value_t = DEFAULT_TRANSITION_HZ)]
    pub transition_hz: f64,
    /// Stop-band attenuation and pass-band ripple, dB (positive).
    #[arg(long, default_value_t = DEFAULT_RIPPLE_DB, allow_negative_numbers = true)]
    pub ripple_db: f64,
}

/// Arguments of `fir`.
#[derive(Debug, Args)]
pub struct FirArgs {
    /// Sampling rate, Hz.
    #[arg(long)]
    pub fs_hz: f64,
    /// The filter specification.
    #[command(flatten)]
    pub kaiser: KaiserArgs,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}
