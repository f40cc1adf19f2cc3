//! Arguments of `thermonav filter`.

use super::shared::{DenoiseArg, wavelet_default, with_default};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use thermonav::signal::kaiser::{DEFAULT_RIPPLE_DB, DEFAULT_TRANSITION_HZ};
use thermonav::signal::wavelet::daubechies::Daubechies;
use thermonav::signal::wavelet::threshold::{ThresholdRule, Thresholding};
use thermonav::signal::wavelet::transform::ExtensionMode;
use thermonav::signal::zero_phase::ZeroPhaseMode;

/// How the filter's delay is removed.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ModeArg {
    /// One forward pass with the linear-phase group delay removed.
    ZeroPhase,
    /// Forward-backward filtering, as SciPy's filtfilt (squared magnitude response).
    Filtfilt,
}

/// Threshold rules of the wavelet de-noising.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ThresholdArg {
    /// σ √(2 ln n), σ from the median absolute finest detail / 0.6745 (VisuShrink).
    Universal,
    /// Stein's unbiased risk estimate minimised per level, at most the band's universal one.
    Sure,
    /// SURE, or the band's universal threshold where the band is sparse (SureShrink, 1995).
    SureHybrid,
}

/// Soft or hard thresholding.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ThresholdingArg {
    /// sign(x) max(|x| − λ, 0).
    Soft,
    /// x where |x| ≥ λ, else 0.
    Hard,
}

/// Extension of the signal beyond its ends (PyWavelets' modes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ExtensionArg {
    /// Half-sample symmetric reflection.
    Symmetric,
    /// Periodic (an orthogonal transform; the ends meet).
    Periodization,
}

/// Arguments of `filter`.
#[derive(Debug, Args)]
pub struct FilterArgs {
    /// The IMU CSV to filter.
    pub input: PathBuf,
    /// De-noising method.
    #[arg(long, value_enum, default_value_t = DenoiseArg::Kaiser)]
    pub method: DenoiseArg,
    /// Options of --method kaiser.
    #[command(flatten)]
    pub kaiser: FilterKaiserArgs,
    /// Options of --method wavelet.
    #[command(flatten)]
    pub wavelet: WaveletArgs,
    /// Output CSV; a sidecar OUT.json records what was done.
    #[arg(long)]
    pub out: PathBuf,
    /// Print one JSON document (the sidecar) instead of text.
    #[arg(long)]
    pub json: bool,
}

/// The options of `filter --method kaiser` (refused with the wavelet method).
#[derive(Debug, Args, Clone, Copy)]
pub struct FilterKaiserArgs {
    /// Kaiser: pass-band edge (cut-off), Hz (required with --method kaiser).
    #[arg(long)]
    pub cutoff_hz: Option<f64>,
    #[arg(long, help = with_default("Kaiser: width of the transition band, Hz", DEFAULT_TRANSITION_HZ))]
    pub transition_hz: Option<f64>,
    #[arg(long, allow_negative_numbers = true, help = with_default("Kaiser: stop-band attenuation and pass-band ripple, dB (positive)", DEFAULT_RIPPLE_DB))]
    pub ripple_db: Option<f64>,
    #[arg(long, value_enum, help = with_default("Kaiser: zero-phase mode", ZeroPhaseMode::default().name()))]
    pub mode: Option<ModeArg>,
    /// Kaiser: decimate to this rate after filtering, Hz (must divide the input rate).
    #[arg(long)]
    pub decimate_to_hz: Option<f64>,
    /// Kaiser: sampling rate used for the design, Hz (default: the nominal rate of the file).
    #[arg(long)]
    pub fs_hz: Option<f64>,
}

/// The options of `filter --method wavelet` (refused with the Kaiser method).
#[derive(Debug, Args, Clone, Copy)]
pub struct WaveletArgs {
    #[arg(long, help = with_default("Wavelet: Daubechies wavelet db1..db10 (haar = db1)", wavelet_default().wavelet))]
    pub wavelet: Option<Daubechies>,
    /// Wavelet: decomposition level, 1 to PyWavelets' dwt_max_level for the record's length
    /// and the wavelet [default: that maximum].
    #[arg(long)]
    pub level: Option<usize>,
    #[arg(long, value_enum, help = with_default("Wavelet: threshold rule", wavelet_default().rule.name()))]
    pub threshold: Option<ThresholdArg>,
    #[arg(long, value_enum, help = with_default("Wavelet: thresholding", wavelet_default().thresholding.name()))]
    pub thresholding: Option<ThresholdingArg>,
    #[arg(long, value_enum, help = with_default("Wavelet: extension at the ends", wavelet_default().mode.name()))]
    pub extension: Option<ExtensionArg>,
}

impl From<ThresholdArg> for ThresholdRule {
    fn from(t: ThresholdArg) -> Self {
        match t {
            ThresholdArg::Universal => Self::Universal,
            ThresholdArg::Sure => Self::Sure,
            ThresholdArg::SureHybrid => Self::SureHybrid,
        }
    }
}

impl From<ThresholdingArg> for Thresholding {
    fn from(t: ThresholdingArg) -> Self {
        match t {
            ThresholdingArg::Soft => Self::Soft,
            ThresholdingArg::Hard => Self::Hard,
        }
    }
}

impl From<ExtensionArg> for ExtensionMode {
    fn from(e: ExtensionArg) -> Self {
        match e {
            ExtensionArg::Symmetric => Self::Symmetric,
            ExtensionArg::Periodization => Self::Periodization,
        }
    }
}

impl From<ModeArg> for ZeroPhaseMode {
    fn from(m: ModeArg) -> Self {
        match m {
            ModeArg::ZeroPhase => Self::DelayCompensated,
            ModeArg::Filtfilt => Self::ForwardBackward,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_mode_is_called_as_the_library_calls_it() {
        for mode in ModeArg::value_variants() {
            let name = mode.to_possible_value().unwrap().get_name().to_string();
            assert_eq!(ZeroPhaseMode::from(*mode).name(), name);
            assert_eq!(ZeroPhaseMode::from_name(&name), Some((*mode).into()));
        }
    }
}
