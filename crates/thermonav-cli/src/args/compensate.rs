//! Arguments of `thermonav compensate`.

use super::shared::BagTopicArgs;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `compensate`.
#[derive(Debug, Args)]
pub struct CompensateArgs {
    /// The record: an IMU CSV with temp_c, a ROS bag, a DataFlash log or a PX4 ULog.
    pub record: PathBuf,
    #[command(flatten)]
    pub topics: BagTopicArgs,
    /// The bank whose thermal calibration is taken off.
    #[arg(long)]
    pub bank: PathBuf,
    /// The bank's power-on the record belongs to (its fitted offset is taken off); default:
    /// the bank's only power-on, else the mean offset.
    #[arg(long)]
    pub power_on: Option<u32>,
    /// Which IMU of a ULog record (the instance of its raw sensor topics).
    #[arg(long, default_value_t = 0)]
    pub instance: u8,
    /// The compensated record (canonical IMU CSV); OUT.csv.json says what was taken off.
    #[arg(long)]
    pub out: PathBuf,
    /// Print the sidecar as one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}
