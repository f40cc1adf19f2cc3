//! Argument types and help texts that several commands share.

use clap::builder::PossibleValue;
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use std::sync::LazyLock;
use thermonav::mounting::Mounting;
use thermonav::nav::run_options::RunOptions;
use thermonav::nav::time_offset::TimeOffsetSearch;
use thermonav::signal::wavelet::denoise::WaveletDenoise;
use thermonav::stoch::bank::{GaussMarkovSource, Selection};

fn run_options() -> RunOptions {
    RunOptions::default()
}

pub(super) fn wavelet_default() -> WaveletDenoise {
    WaveletDenoise::default()
}

/// `text` with its default, for an optional argument whose default is applied by the settings.
pub(super) fn with_default(text: &str, default: impl std::fmt::Display) -> String {
    format!("{text} [default: {default}]")
}

/// The options that decide how one filter run goes, the same in `integrate` (its one run)
/// and `evaluate` (every candidate's run): resolved by `settings::navigation::run_options`
/// into the library's `RunOptions`, whose defaults these are.
#[derive(Debug, Args)]
pub struct RunOptionArgs {
    /// The sensor's operating temperature, °C: integrate selects its model there with
    /// --select, evaluate stands its interpolated candidate there. Without it (or
    /// --model-temperature-c), the mean of the IMU file's temp_c column.
    #[arg(long, allow_hyphen_values = true)]
    pub operating_temperature_c: Option<f64>,
    /// Use the bank's model at this temperature, °C (the paper's "model of temperature T"):
    /// integrate runs the entry nearest it, fixed; evaluate's candidates that stand at one
    /// temperature (interpolated, compensated entry, profile) stand there, beside the entries
    /// at their own, and its --estimate-time-offset runs with integrate's model.
    #[arg(
        long,
        conflicts_with = "operating_temperature_c",
        allow_hyphen_values = true
    )]
    pub model_temperature_c: Option<f64>,
    /// How to select the model at the operating temperature (integrate's run; in evaluate, the
    /// run --estimate-time-offset searches with: the tournament runs the nearest entries and
    /// the interpolated model as candidates of their own).
    #[arg(long, value_enum, default_value_t = Selection::default().into())]
    pub select: SelectArg,
    /// Start from this trajectory's state at the first GNSS epoch instead of aligning from GNSS
    /// and the accelerometers (in evaluate, instead of starting from --reference, or aligning
    /// when it holds positions only): a trajectory CSV or a KF-GINS .nav, one with attitude.
    #[arg(long)]
    pub initial_from: Option<PathBuf>,
    /// Do not level the start and take the gyro biases from the platform standing still at
    /// the record's start (by default done when the fixes stay put for 5 s or more before the
    /// alignment fix; the run's report says so). Only a run that aligns from GNSS is levelled:
    /// one started from --initial-from (or from evaluate's --reference with attitude) is not.
    #[arg(long)]
    pub no_static_alignment: bool,
    /// Estimate the IMU-GNSS time offset (added to the IMU times, as convert
    /// --time-offset-s) that maximises the innovations' likelihood over the run, within
    /// ±--time-offset-bracket-s, and run at it when the data determine it (otherwise at the
    /// times as given, with a warning); reported with its interval. Reads the record whole.
    /// In evaluate the offset is estimated once, with the run integrate makes with the same
    /// options (the likelihood is one model's), and every candidate runs on the record
    /// shifted by it, so that the models are compared on the same data; not with --shard.
    #[arg(long)]
    pub estimate_time_offset: bool,
    /// Half-width of the offsets --estimate-time-offset searches, s (at most 10).
    #[arg(long, default_value_t = TimeOffsetSearch::default().bracket_s)]
    pub time_offset_bracket_s: f64,
    /// Which Gauss-Markov family of the bank drives the bias states.
    #[arg(long, value_enum, default_value_t = run_options().gauss_markov.into())]
    pub model: GmSourceArg,
    /// Multiplies the white-noise densities (ARW, VRW) of the model (in evaluate, of every
    /// candidate but the oracle): vibration on a vehicle raises the effective noise above a
    /// static record's (1 = the model as characterised).
    #[arg(long, default_value_t = run_options().process_noise_scale)]
    pub process_noise_scale: f64,
    /// Standard deviation of GNSS velocities, m/s (the canonical GNSS CSV carries none): one
    /// value for all three axes, or north,east,down.
    #[arg(long, value_delimiter = ',', default_values_t = run_options().velocity_sd_m_s)]
    pub velocity_sd_m_s: Vec<f64>,
    /// Ignore GNSS velocities.
    #[arg(long)]
    pub no_velocity: bool,
    /// Ignore dual-antenna headings.
    #[arg(long)]
    pub no_heading: bool,
    /// Probability of the chi-square innovation gate (e.g. 0.9999), or 1 to accept every
    /// update.
    #[arg(long, default_value_t = run_options().gate_probability.unwrap_or(1.0))]
    pub gate_probability: f64,
    /// The gate's quantile is widened by the median NIS of this many recent updates of the same
    /// kind over its expected median (at most 100x), so that a run of fixes whose stated noise
    /// is too small is not thrown away while isolated outliers still are; 0 keeps the plain gate.
    #[arg(long, default_value_t = run_options().gate_window)]
    pub gate_window: usize,
    /// Primary antenna relative to the IMU in body axes (forward,right,down), m.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, default_values_t = run_options().geometry.lever_arm_body_m)]
    pub lever_arm_m: Vec<f64>,
    /// Dual-antenna baseline direction in body axes (primary to secondary).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, default_values_t = run_options().geometry.baseline_body)]
    pub baseline: Vec<f64>,
    /// Covariance propagation rate, Hz (the nominal state is mechanized at every IMU sample).
    #[arg(long, default_value_t = 1.0 / run_options().covariance_interval_s)]
    pub covariance_rate_hz: f64,
    /// Longest IMU interval the filter crosses, s: a longer gap in the record is refused
    /// (naming where it is) instead of being dead-reckoned on one held rate.
    #[arg(long, default_value_t = run_options().max_imu_gap_s)]
    pub max_imu_gap_s: f64,
    /// Split the z-gyro bias prior into a Gaussian sum of this many filters run in lockstep
    /// (odd, at least 9; weighted by their innovations, the unlikely ones dropped) so that the
    /// heading's sd stays honest when nothing observes the heading directly: position-only
    /// GNSS with a large turn-on gyro bias. Costs up to that many filters until the heading
    /// has been seen (in evaluate, for every candidate). 1 (the default) runs one filter. Not
    /// with integrate's --smooth.
    #[arg(long, default_value_t = 1)]
    pub bias_hypotheses: usize,
}

/// Model selection rules.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum SelectArg {
    /// The entry at the nearest temperature.
    Nearest,
    /// Linear interpolation of Tc and sigma between the bracketing entries.
    Linear,
}

/// Gauss-Markov model families in the bank: the values and their help come from the
/// library's registry (`thermonav::stoch::gm_family`), the default first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GmSourceArg(pub GaussMarkovSource);

/// Every registered family, as the command line lists them.
static GM_SOURCES: LazyLock<Vec<GmSourceArg>> = LazyLock::new(|| {
    GaussMarkovSource::in_listing_order()
        .map(GmSourceArg)
        .collect()
});

impl GmSourceArg {
    /// The families every bank has, as the command line lists them (plot's default).
    pub fn always_fitted() -> Vec<Self> {
        GM_SOURCES
            .iter()
            .copied()
            .filter(|s| s.0.always_fitted())
            .collect()
    }
}

impl ValueEnum for GmSourceArg {
    fn value_variants<'a>() -> &'a [Self] {
        &GM_SOURCES
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        Some(PossibleValue::new(self.0.cli_name()).help(self.0.help()))
    }
}

/// How a record is de-noised (`filter --method`, `characterize --denoise`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DenoiseArg {
    /// Kaiser-window low-pass, zero phase (the paper's).
    Kaiser,
    /// Wavelet shrinkage with a Daubechies wavelet (the paper's named alternative).
    Wavelet,
}

/// `--imu-rotation`, shared by every command that reads an IMU record.
#[derive(Debug, Clone, Args)]
pub struct ImuRotationArgs {
    /// The IMU's mounting in the body (forward-right-down), applied to the gyro and
    /// accelerometer vectors (rates or increments) as the file is read: an axis mapping such
    /// as -y,x,z (body axis i is the signed IMU axis: body x = IMU -y, body y = IMU x; a
    /// rotation, never a reflection) or rpy:ROLL,PITCH,YAW, the IMU's roll, pitch and yaw
    /// relative to the body in degrees (ZYX, C_s^b = Rz(yaw) Ry(pitch) Rx(roll)). Default: the
    /// file's axes are the body's.
    #[arg(long, allow_hyphen_values = true, value_name = "MAPPING|rpy:R,P,Y")]
    pub imu_rotation: Option<Mounting>,
}

/// `--topic` and `--temperature-topic`, shared by every command that reads an IMU record that
/// may be a ROS bag (a file, or a ROS 2 bag folder with its metadata.yaml).
#[derive(Debug, Clone, Default, Args)]
pub struct BagTopicArgs {
    /// ROS bags: the sensor_msgs/Imu topic (default: the only one holding messages; several
    /// are listed).
    #[arg(long)]
    pub topic: Option<String>,
    /// ROS bags: the sensor_msgs/Temperature topic for temp_c (default: the only one holding
    /// messages, if any).
    #[arg(long)]
    pub temperature_topic: Option<String>,
}

/// `--rate-hz` of the static analyses: the sample rate of a record without times.
#[derive(Debug, Clone, Args)]
pub struct SampleRateArgs {
    /// The sample rate of an IMU file without a t_s column, Hz: sample k is at k/RATE s from
    /// 0. A file with t_s is refused with it (its own times are used, never replaced).
    #[arg(long)]
    pub rate_hz: Option<f64>,
}

impl From<GmSourceArg> for GaussMarkovSource {
    fn from(m: GmSourceArg) -> Self {
        m.0
    }
}

impl From<GaussMarkovSource> for GmSourceArg {
    fn from(m: GaussMarkovSource) -> Self {
        Self(m)
    }
}

impl From<Selection> for SelectArg {
    fn from(m: Selection) -> Self {
        match m {
            Selection::Nearest => Self::Nearest,
            Selection::Linear => Self::Linear,
        }
    }
}

impl From<SelectArg> for thermonav::stoch::bank::Selection {
    fn from(m: SelectArg) -> Self {
        match m {
            SelectArg::Nearest => Self::Nearest,
            SelectArg::Linear => Self::Linear,
        }
    }
}
