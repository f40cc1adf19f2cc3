//! Arguments of `thermonav allan`.

use super::shared::{BagTopicArgs, ImuRotationArgs, SampleRateArgs};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use thermonav::stoch::allan::{DEFAULT_CONFIDENCE, DeviationKind};

/// Allan τ grids.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum TausArg {
    /// m = 1, 2, 4, 8, …
    Octave,
    /// m = 1, 2, 4, 10, 20, 40, …
    Decade,
    /// 20 log-spaced m per decade.
    Dense,
}

/// Arguments of `allan`.
#[derive(Debug, Args)]
pub struct AllanArgs {
    /// The IMU CSV (rates), or a ROS bag (.mcap, .db3, .bag, or a ROS 2 bag folder: its
    /// sensor_msgs/Imu topic, in FRD), or an ArduPilot DataFlash log (.bin: its only IMU
    /// instance).
    pub file: PathBuf,
    #[command(flatten)]
    pub topics: BagTopicArgs,
    #[command(flatten)]
    pub rotation: ImuRotationArgs,
    #[command(flatten)]
    pub rate: SampleRateArgs,
    /// τ grid.
    #[arg(long, value_enum, default_value_t = TausArg::Octave)]
    pub taus: TausArg,
    /// Confidence level of the limits (0.683 is Stable32's).
    #[arg(long, default_value_t = DEFAULT_CONFIDENCE)]
    pub confidence: f64,
    /// Which deviation: adev (overlapping Allan, with confidence limits and IEEE 952 noise
    /// terms), mdev (modified Allan), hdev / ohdev (Hadamard, non-overlapping / overlapping),
    /// tdev (time deviation, rate unit times s) or totdev (total); all but adev come without
    /// limits or terms.
    #[arg(long, default_value_t = DeviationKind::default())]
    pub kind: DeviationKind,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

impl From<TausArg> for thermonav::stoch::allan::TauGrid {
    fn from(t: TausArg) -> Self {
        match t {
            TausArg::Octave => Self::Octave,
            TausArg::Decade => Self::Decade,
            TausArg::Dense => Self::Dense { per_decade: 20 },
        }
    }
}
