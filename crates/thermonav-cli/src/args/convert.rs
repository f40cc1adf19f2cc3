//! Arguments of `thermonav convert`.

use super::shared::{BagTopicArgs, ImuRotationArgs};
use clap::{Args, ValueEnum};
use std::path::PathBuf;

/// Formats `convert --to` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ToFormatArg {
    /// KF-GINS text files (IMU increments, GNSS, .nav).
    KfGins,
}

/// Foreign formats read by `convert`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ForeignFormatArg {
    /// RTKLIB solution (.pos), lat/lon/height or ECEF form, GPST times → GNSS CSV.
    RtklibPos,
    /// NMEA 0183 log (GGA, RMC, VTG, HDT, THS) → GNSS CSV.
    Nmea,
    /// KF-GINS IMU text file (time, angle and velocity increments) → IMU CSV (increments).
    KfGinsImu,
    /// KF-GINS GNSS text file (7 or 13 columns) → GNSS CSV.
    KfGinsGnss,
    /// KF-GINS navigation result / truth (.nav) → trajectory CSV.
    KfGinsNav,
    /// Raw IMU CSV (g, deg/s, ms tick) timed by its RTKLIB .tag file → IMU CSV (rates).
    RawImuTag,
    /// PX4 ULog (.ulg): sensor_combined or vehicle_imu → IMU CSV (--out, with temp_c when
    /// logged), vehicle_gps_position or sensor_gps → GNSS CSV (--gnss-out), OUT.json sidecar.
    Px4Ulog,
    /// ROS 2 bag, MCAP storage (.mcap): sensor_msgs/Imu → IMU CSV in FRD (--out, temp_c from
    /// sensor_msgs/Temperature), NavSatFix → GNSS CSV (--gnss-out), OUT.json sidecar.
    Ros2Mcap,
    /// ROS 2 bag, SQLite storage (.db3): as ros2-mcap.
    Ros2Db3,
    /// ROS 1 bag v2.0 (.bag): as ros2-mcap.
    Ros1Bag,
    /// ArduPilot DataFlash log (.bin): IMU (one instance, FRD, temp_c from its T) → IMU CSV
    /// (--out), GPS (with GPA accuracies) → GNSS CSV (--gnss-out), OUT.json sidecar.
    Dataflash,
}

/// Axes of a raw IMU file's output.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ImuFrameArg {
    /// As recorded by the sensor (rotate to forward-right-down before navigating).
    Sensor,
    /// Forward-right-down by the rtklibexplorer drive's mounting (x and z negated).
    DriveFrd,
}

/// Arguments of `convert`.
#[derive(Debug, Args)]
pub struct ConvertArgs {
    /// The foreign file.
    pub input: PathBuf,
    /// Its format; detected from the content when omitted and unambiguous.
    #[arg(long, value_enum, conflicts_with = "to")]
    pub format: Option<ForeignFormatArg>,
    /// The other way: INPUT is one of our CSVs (IMU, GNSS or trajectory, told by its header)
    /// written in this tool's format. kf-gins: IMU increments (rates are turned into
    /// increments; the first rate sample has no interval and is left out), the 7-column GNSS
    /// file (needs sd_n_m,sd_e_m,sd_u_m) or a .nav, times as GPS seconds of week (the week is
    /// printed, for --gps-week when reading back).
    #[arg(long, value_enum)]
    pub to: Option<ToFormatArg>,
    /// The canonical CSV to write (atomically; nothing is written on error); px4-ulog: the IMU.
    #[arg(long)]
    pub out: PathBuf,
    /// px4-ulog, ROS bags, dataflash: also write the GNSS fixes to this canonical GNSS CSV.
    #[arg(long)]
    pub gnss_out: Option<PathBuf>,
    #[command(flatten)]
    pub topics: BagTopicArgs,
    /// ROS bags: the sensor_msgs/NavSatFix topic for --gnss-out (default: the only one).
    #[arg(long)]
    pub gnss_topic: Option<String>,
    /// dataflash: the IMU instance (the I column of IMU records; IMU2, IMU3 of older logs are 1
    /// and 2) (default: the only one; several are listed).
    #[arg(long)]
    pub imu_instance: Option<u64>,
    /// raw-imu-tag: the time-tag file (default: INPUT.tag).
    #[arg(long)]
    pub tag: Option<PathBuf>,
    #[command(flatten)]
    pub rotation: ImuRotationArgs,
    /// raw-imu-tag: axes of the output.
    #[arg(long, value_enum, default_value_t = ImuFrameArg::Sensor)]
    pub imu_frame: ImuFrameArg,
    /// raw-imu-tag: seconds added to every time (the drive's author uses -0.125).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub time_offset_s: f64,
    /// rtklib-pos: keep only these quality flags Q (1 fix, 2 float, …), e.g. --quality 1.
    #[arg(long, value_delimiter = ',')]
    pub quality: Vec<u8>,
    /// kf-gins-imu, kf-gins-gnss: GPS week of the seconds-of-week times (put on the GPST scale).
    #[arg(long)]
    pub gps_week: Option<u32>,
    /// nmea, px4-ulog: GPST minus UTC, s.
    #[arg(long, default_value_t = thermonav_io::gpst::GPST_MINUS_UTC_S)]
    pub leap_seconds: i64,
    /// nmea: UTC date of the first epoch (YYYY-MM-DD) when the log has no RMC sentence.
    #[arg(long)]
    pub date: Option<String>,
    /// nmea: keep HDT/THS headings with this standard deviation, deg.
    #[arg(long)]
    pub heading_sd_deg: Option<f64>,
    /// nmea: turn speed and course into a velocity with down = 0.
    #[arg(long)]
    pub level_velocity: bool,
    /// Keep NaN values and non-increasing times; skip NMEA lines with bad checksums.
    #[arg(long)]
    pub lenient: bool,
}
