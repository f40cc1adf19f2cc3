//! Arguments of `thermonav plot`.

use super::shared::{BagTopicArgs, GmSourceArg};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use thermonav::nav::outage::OutageSpec;

/// Figures drawn by `plot`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum PlotKind {
    /// Allan deviation per channel from `allan --json` output, or from a model bank entry
    /// (--temperature-c).
    Allan,
    /// Correlation time versus temperature with 95 % intervals, from a model bank.
    CorrelationTime,
    /// Autocovariance of one channel of an IMU CSV with the fitted Gauss-Markov curve.
    Autocorrelation,
    /// East versus north of a trajectory (a reference in any form --reference takes, or an
    /// `integrate` solution), the parts inside --outages highlighted.
    Trajectory,
    /// North, east and heading errors in the first outage, one line per model, from an
    /// `evaluate` report (evaluation.json) for the filter --filter.
    OutageErrors,
    /// RMS error (--metric) against the model's temperature, from evaluation.json.
    RmsTemperature,
    /// Innovations with ±3σ bounds, from an `integrate` STEM.innovations.csv.
    Innovations,
    /// Bias against temperature from a bank's thermal calibration: the repeatable curve with
    /// its simultaneous 95 % band and the observations by power-on, offsets removed.
    ThermalBias,
    /// A bank's thermal calibration against a record (`bank check`): block means, prediction
    /// and band against time and against temperature (the bank is the input; the record is
    /// --record).
    ThermalCheck,
}

/// The error metric of `plot rms-temperature`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum MetricArg {
    /// Mean of per-outage RMS north error, m.
    North,
    /// Mean of per-outage RMS east error, m.
    East,
    /// Mean of per-outage RMS heading error, deg.
    Heading,
}

/// Units of inertial quantities on figures.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum UnitsArg {
    /// rad/s and m/s².
    Si,
    /// deg/h and mg.
    Navigation,
}

/// Arguments of `plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    /// The figure.
    #[arg(value_enum)]
    pub kind: PlotKind,
    /// Its input: `allan --json` output or a bank (allan), a bank (correlation-time,
    /// thermal-bias), an IMU
    /// CSV of rates, filtered and decimated as for `ar` (autocorrelation), a trajectory CSV
    /// (trajectory).
    pub input: PathBuf,
    /// The figure file: FILE.svg, or FILE.png (rasterised with the bundled DejaVu Sans).
    #[arg(long)]
    pub out: PathBuf,
    /// Units of rates and Allan deviations.
    #[arg(long, value_enum, default_value_t = UnitsArg::Navigation)]
    pub units: UnitsArg,
    /// The bank entry nearest this temperature, °C (allan from a bank with several entries).
    #[arg(long, allow_negative_numbers = true)]
    pub temperature_c: Option<f64>,
    /// Gauss-Markov families drawn (correlation-time).
    #[arg(long, value_enum, value_delimiter = ',', default_values_t = GmSourceArg::always_fitted())]
    pub families: Vec<GmSourceArg>,
    /// The channel (autocorrelation: default gx; thermal-bias: default every calibrated one).
    #[arg(long)]
    pub channel: Option<String>,
    /// Longest lag shown, s (autocorrelation).
    #[arg(long, default_value_t = 300.0)]
    pub max_lag_s: f64,
    /// GNSS outages to highlight, as for `integrate` (trajectory).
    #[arg(long, default_value = "none")]
    pub outages: OutageSpec,
    /// trajectory: the IMU record the solution came from; `--outages` then spans it as
    /// `integrate` does (`rel:` from its first IMU increment), else the solution's points.
    #[arg(long)]
    pub imu: Option<PathBuf>,
    /// Filter whose models to draw (outage-errors): ukf or ekf; default the report's first.
    #[arg(long)]
    pub filter: Option<String>,
    /// Metric of rms-temperature.
    #[arg(long, value_enum, default_value_t = MetricArg::North)]
    pub metric: MetricArg,
    /// Figure title (default: one naming the input).
    #[arg(long)]
    pub title: Option<String>,
    /// thermal-check: the record checked (an IMU CSV with temp_c, a bag, a DataFlash log or a
    /// ULog).
    #[arg(long)]
    pub record: Option<PathBuf>,
    #[command(flatten)]
    pub topics: BagTopicArgs,
    /// thermal-check: the block length, s.
    #[arg(long, default_value_t = thermonav::stoch::thermal::check::DEFAULT_CHECK_BLOCK_S)]
    pub block_s: f64,
}
