//! Arguments of `thermonav inspect`.

use clap::Args;
use std::path::PathBuf;

/// Arguments of `inspect`.
#[derive(Debug, Args)]
pub struct InspectArgs {
    /// The IMU, GNSS or reference (trajectory) CSV to inspect, recognised by its header.
    pub file: PathBuf,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}
