//! Arguments of `thermonav characterize`.

use super::shared::{BagTopicArgs, DenoiseArg, ImuRotationArgs, SampleRateArgs, wavelet_default};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use thermonav::stoch::characterize::{CharacterizeSettings, DEFAULT_GMWM};
use thermonav::stoch::thermal::{DEFAULT_SITE_HEIGHT_M, DEFAULT_SITE_LATITUDE_DEG};

fn conditioning() -> CharacterizeSettings {
    CharacterizeSettings::default()
}

/// The help of `characterize --denoise`, with the wavelet settings it uses.
fn denoise_help() -> String {
    let w = wavelet_default();
    format!(
        "De-noising before AR modelling: the Kaiser low-pass (--cutoff-hz, --transition-hz), or wavelet shrinkage ({}, deepest level, {}, {} threshold, {}; in memory only), then decimation to --modelling-rate-hz; the bank records which",
        w.wavelet,
        w.mode.name(),
        w.rule.name(),
        w.thresholding.name()
    )
}

/// Arguments of `characterize`.
#[derive(Debug, Args)]
pub struct CharacterizeArgs {
    /// Static IMU CSVs, one per temperature point; or ROS bags (.mcap, .db3, .bag, or ROS 2
    /// bag folders: the sensor_msgs/Imu topic, in FRD, temp_c from the sensor_msgs/Temperature
    /// topic); or ArduPilot DataFlash logs (.bin: the only IMU instance, temp_c from its T).
    #[arg(required_unless_present_any = ["manifest", "sweep"], conflicts_with = "manifest")]
    pub files: Vec<PathBuf>,
    #[command(flatten)]
    pub topics: BagTopicArgs,
    #[command(flatten)]
    pub rotation: ImuRotationArgs,
    #[command(flatten)]
    pub rate: SampleRateArgs,
    /// Temperatures of the files, °C, comma-separated (default: the mean of each file's temp_c).
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        conflicts_with = "manifest"
    )]
    pub temperature_c: Vec<f64>,
    /// Output bank (JSON); with --manifest, the output folder (DIR/SERIAL/bank.json and
    /// DIR/lot-summary.json).
    #[arg(long)]
    pub out: PathBuf,
    /// A production-lot manifest (TOML): characterise its units, one bank each, and summarise
    /// the lot when every unit is run.
    #[arg(long)]
    pub manifest: Option<PathBuf>,
    /// With --manifest: only the unit with this serial.
    #[arg(long, requires = "manifest", conflicts_with = "unit_index")]
    pub unit: Option<String>,
    /// With --manifest: only the unit at this 0-based position (e.g. $SLURM_ARRAY_TASK_ID).
    #[arg(long, requires = "manifest")]
    pub unit_index: Option<usize>,
    #[arg(long, value_enum, default_value_t = DenoiseArg::Kaiser, help = denoise_help())]
    pub denoise: DenoiseArg,
    /// The composite fitted to each channel's wavelet variance (GMWM) and mapped onto the
    /// filter's white noise and bias state (`--model gmwm` of integrate and evaluate): a model
    /// such as wn+rw+2gm, auto (the candidate of least objective + 2 × parameters, no
    /// bootstrap), or off.
    #[arg(long, default_value_t = DEFAULT_GMWM.to_string())]
    pub gmwm: String,
    /// Kaiser cut-off of the conditioning before AR modelling, Hz.
    #[arg(long, default_value_t = conditioning().cutoff_hz)]
    pub cutoff_hz: f64,
    /// Kaiser transition width, Hz.
    #[arg(long, default_value_t = conditioning().transition_hz)]
    pub transition_hz: f64,
    /// Rate of the conditioned series, Hz.
    #[arg(long, default_value_t = conditioning().modelling_rate_hz)]
    pub modelling_rate_hz: f64,
    /// How each record is read: whole into memory, or streamed in pieces in bounded memory
    /// (for long logs); auto streams files of at least 1 GiB.
    #[arg(long, value_enum, default_value_t = ReadingArg::Auto)]
    pub reading: ReadingArg,
    /// A further power-on of the same unit for the thermal calibration: its static records,
    /// comma-separated (the positional records are one power-on; repeat the option for more).
    /// Two or more power-ons, one at two or more temperatures, let the per-power-on offsets
    /// be told apart from the repeatable bias curve.
    #[arg(long, conflicts_with = "manifest")]
    pub power_on: Vec<PowerOnFiles>,
    /// A temperature sweep of the same unit (a static log with temp_c while it warms or
    /// cools, in any orientation: a CSV, a bag, a DataFlash log, or a PX4 ULog: its raw
    /// sensor_gyro and sensor_accel with their temperature and device ids), fitted by block
    /// means; comma-separated files are pieces of one power-on; repeat for more power-ons.
    /// Sweeps alone (no static records) give a bank of the thermal calibration only, its
    /// model chosen on held-out legs, with a thermal-lag term where it predicts better.
    #[arg(long, conflicts_with = "manifest")]
    pub sweep: Vec<SweepFiles>,
    /// Block length of a sweep's block means, s (default: the shorter of 300 s and the time
    /// the temperature takes to move 1 °C, at least 10 samples).
    #[arg(long)]
    pub sweep_block_s: Option<f64>,
    /// Which IMU of a PX4 ULog sweep: the instance (multi_id) of its raw sensor_gyro and
    /// sensor_accel topics.
    #[arg(long, default_value_t = 0)]
    pub sweep_instance: u8,
    /// Latitude of the chamber, deg: the gravity a level unit's az reads is taken off its
    /// thermal curve.
    #[arg(long, default_value_t = DEFAULT_SITE_LATITUDE_DEG, allow_negative_numbers = true)]
    pub chamber_latitude_deg: f64,
    /// Height of the chamber, m.
    #[arg(long, default_value_t = DEFAULT_SITE_HEIGHT_M, allow_negative_numbers = true)]
    pub chamber_height_m: f64,
    /// Print one JSON document (a summary) instead of text.
    #[arg(long)]
    pub json: bool,
}

/// The pieces of one temperature sweep (one power-on), comma-separated.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepFiles(pub Vec<PathBuf>);

impl std::str::FromStr for SweepFiles {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let files: PowerOnFiles = text
            .parse()
            .map_err(|_| "give the sweep's files, comma-separated".to_string())?;
        Ok(Self(files.0))
    }
}

/// The static records of one power-on, comma-separated.
#[derive(Debug, Clone, PartialEq)]
pub struct PowerOnFiles(pub Vec<PathBuf>);

impl std::str::FromStr for PowerOnFiles {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let files: Vec<PathBuf> = text
            .split(',')
            .filter(|s| !s.is_empty())
            .map(PathBuf::from)
            .collect();
        if files.is_empty() {
            return Err("give the power-on's records, comma-separated".into());
        }
        Ok(Self(files))
    }
}

/// How `characterize` reads a record.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ReadingArg {
    /// Streaming for files of at least 1 GiB, in memory otherwise.
    Auto,
    /// The whole record in memory.
    InMemory,
    /// In pieces, in memory independent of the record length (see the user guide, docs/user-guide.md).
    Streaming,
}
