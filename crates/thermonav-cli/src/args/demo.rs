//! Arguments of `thermonav demo`.

use clap::Args;
use std::path::PathBuf;
use thermonav::rng::DEFAULT_SEED;

/// Arguments of `demo`.
#[derive(Debug, Args)]
pub struct DemoArgs {
    /// Output folder.
    #[arg(long, default_value = "out/demo")]
    pub out: PathBuf,
    /// A shorter run (seconds instead of minutes).
    #[arg(long)]
    pub quick: bool,
    /// Seed of every random draw.
    #[arg(long, default_value_t = DEFAULT_SEED)]
    pub seed: u64,
    /// Keep the simulated chamber records (DIR/chamber/*.csv and DIR/temperature/chamber/:
    /// about 360 MB with --quick, 2 GB without), which are otherwise removed once their banks
    /// are built (their truth.json files stay).
    #[arg(long)]
    pub keep_records: bool,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}
