//! Arguments of `thermonav gmwm`.

use super::shared::BagTopicArgs;
use clap::Args;
use std::path::PathBuf;
use thermonav::rng::DEFAULT_SEED;
use thermonav::stoch::characterize::DEFAULT_GMWM;

/// Arguments of `gmwm`.
#[derive(Debug, Args)]
pub struct GmwmArgs {
    /// The IMU CSV (rates, raw: white noise must not be filtered away), or a ROS bag (a file
    /// or a ROS 2 bag folder), or an ArduPilot DataFlash log.
    pub file: PathBuf,
    #[command(flatten)]
    pub topics: BagTopicArgs,
    /// The composite, e.g. wn+rw+2gm or wn+qn+gm (wn, qn, rw, dr, gm, kgm), or auto: the
    /// candidate with the smallest Wavelet Information Criterion.
    #[arg(long, default_value_t = DEFAULT_GMWM.to_string())]
    pub model: String,
    /// Parametric-bootstrap replicates for the parameters' intervals and the WIC, 10 to 1000
    /// (each simulates and refits the whole record once); 0, the default: no intervals, the
    /// candidates ranked by the asymptotic WIC (objective + 2 x parameters).
    #[arg(long, default_value_t = thermonav_io::gmwm::DEFAULT_REPLICATES)]
    pub replicates: usize,
    /// Seed of the bootstrap's named random streams.
    #[arg(long, default_value_t = DEFAULT_SEED)]
    pub seed: u64,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}
