//! Arguments of `thermonav integrate`.

use super::shared::{ImuRotationArgs, RunOptionArgs};
use clap::{ArgGroup, Args, ValueEnum};
use std::path::PathBuf;
use thermonav::nav::engine::{EngineSettings, FilterKind};
use thermonav::nav::outage::OutageSpec;

fn engine() -> EngineSettings {
    EngineSettings::default()
}

/// The navigation filters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FilterArg {
    /// Error-state extended Kalman filter (Joseph form).
    Ekf,
    /// Error-state unscented Kalman filter.
    Ukf,
}

/// Arguments of `integrate`.
#[derive(Debug, Args)]
#[command(group(ArgGroup::new("noise_model").required(true).args(["bank", "profile"])))]
pub struct IntegrateArgs {
    /// The IMU CSV (rates or increments).
    #[arg(long)]
    pub imu: PathBuf,
    #[command(flatten)]
    pub rotation: ImuRotationArgs,
    /// The GNSS CSV (position; optional velocity, heading and standard deviations).
    #[arg(long)]
    pub gnss: PathBuf,
    /// The temperature model bank (JSON, from `characterize`).
    #[arg(long)]
    pub bank: Option<PathBuf>,
    /// Instead of a bank: a sensor profile (TOML, as `simulate profile` writes) whose noise
    /// model is used at the model temperature (its reference temperature by default): for a
    /// sensor without a chamber campaign, from its data sheet or a peer's configuration.
    #[arg(long)]
    pub profile: Option<PathBuf>,
    /// The thermal calibration of this bank (one from `characterize --sweep` alone, say)
    /// with the noise model of --bank or --profile: the record is compensated with it; any
    /// calibration of --bank is replaced. Refused when the two differ in channels or units.
    #[arg(long)]
    pub thermal_from: Option<PathBuf>,
    /// The filter (evaluate's --filter takes ukf, ekf or both).
    #[arg(long, value_enum, default_value_t = engine().filter.into())]
    pub filter: FilterArg,
    #[command(flatten)]
    pub run: RunOptionArgs,
    /// GNSS outages: START+DURATION[,START+DURATION...], every:FIRST,DURATION,PERIOD,COUNT or
    /// spread:COUNT,DURATION (seconds on the files' t_s scale).
    #[arg(long, default_value = "none")]
    pub outages: OutageSpec,
    /// Solution output rate, Hz. Integrate only: it samples the solution file, not the run; a
    /// tournament scores its errors at the default rate.
    #[arg(long, default_value_t = 1.0 / engine().output_interval_s)]
    pub output_rate_hz: f64,
    /// One model for the whole run (at the mean or given temperature) instead of the model at
    /// the IMU's temp_c at every covariance step. A given --model-temperature-c or
    /// --operating-temperature-c also fixes the model.
    #[arg(long)]
    pub no_schedule: bool,
    /// Also run the RTS smoother (EKF only) and write the smoothed trajectory and its
    /// states beside the solution, as STEM.smoothed.csv and STEM.smoothed.states.csv.
    /// Integrate only: the forward run is unchanged (a tournament scores a smoothed
    /// trajectory given as evaluate --solution).
    #[arg(long)]
    pub smooth: bool,
    /// Read the whole IMU record and keep the whole solution in memory before writing
    /// (the path `integrate` takes when a bank's thermal compensation applies); for tests
    /// and memory comparisons.
    #[arg(long, hide = true)]
    pub in_memory: bool,
    /// Do not subtract the bank's thermal bias calibration bias(T) from the IMU samples.
    #[arg(long)]
    pub no_compensation: bool,
    /// The solution trajectory CSV; the state file is written beside it as STEM.states.csv.
    #[arg(long)]
    pub out: PathBuf,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

impl From<FilterArg> for FilterKind {
    fn from(f: FilterArg) -> Self {
        match f {
            FilterArg::Ekf => Self::Ekf,
            FilterArg::Ukf => Self::Ukf,
        }
    }
}

impl From<FilterKind> for FilterArg {
    fn from(f: FilterKind) -> Self {
        match f {
            FilterKind::Ekf => Self::Ekf,
            FilterKind::Ukf => Self::Ukf,
        }
    }
}
