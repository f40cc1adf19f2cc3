//! Arguments of `thermonav bank`.

use super::shared::{BagTopicArgs, GmSourceArg, SelectArg};
use clap::builder::PossibleValue;
use clap::{Args, Subcommand, ValueEnum};
use std::path::PathBuf;
use std::sync::LazyLock;
use thermonav::stoch::bank::{GaussMarkovSource, Selection};
use thermonav_io::noise_export::NoiseFormat;
use thermonav_io::thermal_parameters::ParameterTarget;

/// Arguments of `bank`.
#[derive(Debug, Args)]
pub struct BankArgs {
    /// What to do with the bank.
    #[command(subcommand)]
    pub action: BankAction,
}

/// Bank actions.
#[derive(Debug, Subcommand)]
pub enum BankAction {
    /// Show the bank, or the model selected for an operating temperature.
    Show(BankShowArgs),
    /// Write the bank as another tool's configuration: its thermal calibration as autopilot
    /// parameters (px4-tc, ardupilot-tcal), or its noise model at a temperature as a filter's
    /// or simulator's noise block (the other formats; see the table in docs/user-guide.md).
    Export(BankExportArgs),
    /// Check the bank's thermal calibration against a record (block means against the
    /// prediction and its 95 % band): how much it removes, and whether its band holds.
    Check(BankCheckArgs),
}

/// Arguments of `bank check`.
#[derive(Debug, Args)]
pub struct BankCheckArgs {
    /// The bank (JSON) with a thermal calibration.
    pub bank: PathBuf,
    /// The record: an IMU CSV with temp_c, a ROS bag, a DataFlash log or a PX4 ULog.
    pub record: PathBuf,
    #[command(flatten)]
    pub topics: BagTopicArgs,
    /// Block length of the block means, s (each block's t_s is its middle).
    #[arg(long, default_value_t = thermonav::stoch::thermal::check::DEFAULT_CHECK_BLOCK_S)]
    pub block_s: f64,
    /// The bank's power-on the record belongs to; default: the bank's only power-on, else a
    /// new power-on (the mean offset, the band with the spread between power-ons).
    #[arg(long)]
    pub power_on: Option<u32>,
    /// Which IMU of a ULog record (the instance of its raw sensor topics).
    #[arg(long, default_value_t = 0)]
    pub instance: u8,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

/// What an export format writes.
#[derive(Debug, Clone, Copy)]
pub enum ExportKind {
    /// The thermal calibration as autopilot parameters.
    Thermal(ParameterTarget),
    /// The noise model at a temperature.
    Noise(NoiseFormat),
}

impl ExportKind {
    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            ExportKind::Thermal(target) => target.name(),
            ExportKind::Noise(format) => format.name(),
        }
    }

    /// Its help on the command line.
    pub fn help(self) -> &'static str {
        match self {
            ExportKind::Thermal(target) => target.help(),
            ExportKind::Noise(format) => format.help(),
        }
    }
}

/// `bank export --format`: an export format, its names and help from thermonav-io (the
/// autopilots' thermal targets first, then the noise formats).
#[derive(Debug, Clone, Copy)]
pub struct ExportFormatArg(pub ExportKind);

static EXPORT_FORMATS: LazyLock<Vec<ExportFormatArg>> = LazyLock::new(|| {
    let thermal = ParameterTarget::ALL.map(ExportKind::Thermal);
    let noise = NoiseFormat::ALL.map(ExportKind::Noise);
    thermal
        .into_iter()
        .chain(noise)
        .map(ExportFormatArg)
        .collect()
});

impl ValueEnum for ExportFormatArg {
    fn value_variants<'a>() -> &'a [Self] {
        &EXPORT_FORMATS
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        Some(PossibleValue::new(self.0.name()).help(self.0.help()))
    }
}

impl From<ExportFormatArg> for ExportKind {
    fn from(format: ExportFormatArg) -> Self {
        format.0
    }
}

/// Arguments of `bank export`.
#[derive(Debug, Args)]
pub struct BankExportArgs {
    /// The bank (JSON); with a thermal calibration for px4-tc and ardupilot-tcal.
    pub bank: PathBuf,
    /// Which tool's configuration.
    #[arg(long, value_enum)]
    pub format: ExportFormatArg,
    /// Output file (never the bank).
    #[arg(long)]
    pub out: PathBuf,
    /// Noise formats: the operating temperature, °C, inside the bank's range (default: the
    /// bank's only entry).
    #[arg(long, allow_negative_numbers = true)]
    pub temperature_c: Option<f64>,
    /// Noise formats: the entry nearest --temperature-c, or linear interpolation between the
    /// two around it.
    #[arg(long, value_enum, default_value_t = Selection::default().into())]
    pub method: SelectArg,
    /// Noise formats: which Gauss-Markov family gives the bias model.
    #[arg(long, value_enum, default_value_t = GaussMarkovSource::default().into())]
    pub model: GmSourceArg,
    /// Kalibr: the IMU's ROS topic.
    #[arg(long, default_value = "/imu0")]
    pub rostopic: String,
    /// KF-GINS: the scale-factor standard deviation (gsstd, asstd), ppm, which a static bank
    /// does not measure.
    #[arg(long)]
    pub scale_factor_std_ppm: Option<f64>,
    /// Which IMU of the autopilot: 0 for the first (PX4 TC_G0/TC_A0, ArduPilot INS_TCAL1),
    /// up to 2 (default: the instance of the ULog sweep the bank was calibrated from, else 0).
    #[arg(long, value_parser = clap::value_parser!(u8).range(0..=2))]
    pub instance: Option<u8>,
    /// PX4 device id of the gyro and the accelerometer (TC_Gn_ID, TC_An_ID), when both are one
    /// (default: the ids of the ULog sweep, else 0, which leaves them for the user to set).
    #[arg(long, conflicts_with_all = ["gyro_device_id", "accel_device_id"])]
    pub device_id: Option<u32>,
    /// PX4 device id of the gyro (TC_Gn_ID).
    #[arg(long)]
    pub gyro_device_id: Option<u32>,
    /// PX4 device id of the accelerometer (TC_An_ID).
    #[arg(long)]
    pub accel_device_id: Option<u32>,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Arguments of `bank show`.
#[derive(Debug, Args)]
pub struct BankShowArgs {
    /// The bank (JSON).
    pub bank: PathBuf,
    /// Operating temperature, °C.
    #[arg(long, allow_negative_numbers = true)]
    pub at_temperature_c: Option<f64>,
    /// Selection rule for --at-temperature-c.
    #[arg(long, value_enum, default_value_t = Selection::default().into())]
    pub method: SelectArg,
    /// Which Gauss-Markov family.
    #[arg(long, value_enum, default_value_t = GaussMarkovSource::default().into())]
    pub model: GmSourceArg,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}
