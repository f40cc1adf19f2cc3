//! Arguments of `thermonav simulate`.

use clap::{Args, Subcommand, ValueEnum};
use std::path::PathBuf;
use thermonav::rng::DEFAULT_SEED;
use thermonav::sim::chamber::CampaignSettings;
use thermonav::sim::unit::DEFAULT_SERIAL;
use thermonav::sim::vessel::{DEFAULT_WARM_UP_TIME_CONSTANT_S, GnssSettings, SurveySettings};

fn campaign() -> CampaignSettings {
    CampaignSettings::default()
}

/// Arguments of `simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// What to simulate.
    #[command(subcommand)]
    pub what: SimulateWhat,
}

/// Simulations.
#[derive(Debug, Subcommand)]
pub enum SimulateWhat {
    /// Static records in a thermal chamber, one CSV per temperature, plus truth.json.
    Chamber(ChamberArgs),
    /// A harbour survey vessel (or any --motion file): reference trajectory, IMU and GNSS CSVs.
    Vessel(VesselArgs),
    /// Write the built-in sensor profile as TOML (a template for your own).
    Profile(ProfileArgs),
}

/// Arguments of `simulate chamber`.
#[derive(Debug, Args)]
pub struct ChamberArgs {
    /// Output folder.
    #[arg(long)]
    pub out: PathBuf,
    /// Chamber set points, °C.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_values_t = campaign().temperatures_c
    )]
    pub temperatures_c: Vec<f64>,
    /// Record length per temperature, s.
    #[arg(long, default_value_t = campaign().duration_s)]
    pub duration_s: f64,
    /// Sample rate, Hz.
    #[arg(long, default_value_t = campaign().rate_hz)]
    pub rate_hz: f64,
    /// Timestamp jitter (standard deviation), µs.
    #[arg(long, default_value_t = campaign().jitter_s * 1e6)]
    pub jitter_us: f64,
    /// Probability that a sample is dropped.
    #[arg(long, default_value_t = campaign().drop_probability)]
    pub drop_probability: f64,
    /// Power-ons of the unit, each visiting every set point (the first power-on's records
    /// make the bank; repeats go to power_on_N/ and let `characterize --power-on` separate
    /// the power-on offsets from the thermal curve).
    #[arg(long, default_value_t = campaign().power_ons)]
    pub power_ons: u32,
    /// A temperature sweep of the same unit, START:END:RATE in °C, °C and °C/min (e.g.
    /// -40:80:1), written to imu_ramp.csv in a power-on of its own.
    #[arg(long, allow_hyphen_values = true)]
    pub ramp: Option<String>,
    /// A chamber program instead of the set points: a CSV with the header `t_s,temp_c`
    /// (seconds since the start, °C; linear between rows, the end values held), replayed as
    /// one record, imu_program.csv, as long as its last row (e.g. cool, heat, cool at stated
    /// rates with dwells at the turns).
    #[arg(long, conflicts_with_all = ["temperatures_c", "ramp", "power_ons", "duration_s"])]
    pub temperature_file: Option<PathBuf>,
    /// Thermal lag of every channel's MEMS structure behind the temperature sensor, s
    /// (first order; instead of the profile's `thermal_lag_s`). The records' temperature
    /// column is the sensor's.
    #[arg(long, allow_negative_numbers = true)]
    pub thermal_lag_s: Option<f64>,
    /// Serial number of the simulated unit: the same serial is the same unit (the same
    /// repeatable bias curve) in every campaign and survey.
    #[arg(long, default_value_t = DEFAULT_SERIAL)]
    pub unit_serial: u64,
    /// Sensor profile (TOML); default: the built-in ADIS16364-like profile.
    #[arg(long)]
    pub profile: Option<PathBuf>,
    /// Seed of every random draw.
    #[arg(long, default_value_t = DEFAULT_SEED)]
    pub seed: u64,
    /// Print one JSON document (the truth) instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Arguments of `simulate vessel`.
#[derive(Debug, Args)]
pub struct VesselArgs {
    /// Output folder.
    #[arg(long)]
    pub out: PathBuf,
    /// Sensor temperature during the survey, °C.
    #[arg(long, default_value_t = SurveySettings::default().temperature_c, allow_negative_numbers = true)]
    pub temperature_c: f64,
    /// Survey length, s (ignored with --motion, whose segments set the length).
    #[arg(long, default_value_t = SurveySettings::default().duration_s)]
    pub duration_s: f64,
    /// A cold start: the sensor starts at this temperature, °C, and warms (or cools) to
    /// --temperature-c with --warm-up-time-constant-s.
    #[arg(long, allow_negative_numbers = true)]
    pub warm_up_from_c: Option<f64>,
    /// Time constant of the warm-up, s.
    #[arg(long, default_value_t = DEFAULT_WARM_UP_TIME_CONSTANT_S, allow_negative_numbers = true)]
    pub warm_up_time_constant_s: f64,
    /// The sensor's temperature over the survey from a CSV with the header `t_s,temp_c`
    /// (seconds since the start, °C; linear between rows, the end values held), instead of
    /// --temperature-c or a warm-up.
    #[arg(long, conflicts_with_all = ["warm_up_from_c", "temperature_c"])]
    pub temperature_file: Option<PathBuf>,
    /// Thermal lag of every channel's MEMS structure behind the temperature sensor, s
    /// (first order; instead of the profile's `thermal_lag_s`): give the chamber campaign's
    /// value, since it is the same unit.
    #[arg(long, allow_negative_numbers = true)]
    pub thermal_lag_s: Option<f64>,
    /// Serial number of the simulated unit (the same serial as a chamber campaign's is the
    /// same unit, so its calibration applies).
    #[arg(long, default_value_t = DEFAULT_SERIAL)]
    pub unit_serial: u64,
    /// A motion-definition file (TOML: start, segments, optional waves) instead of the
    /// built-in harbour survey: cars and other platforms (see examples/motion/car.toml).
    #[arg(long, conflicts_with = "speed_m_s")]
    pub motion: Option<PathBuf>,
    /// A slow ground rover instead of the harbour survey, at this speed, m/s: 20 s still,
    /// a 5 s pull-away, then 30 s straight legs joined by 90° turns at 6 deg/s, level.
    #[arg(long)]
    pub speed_m_s: Option<f64>,
    /// GNSS fix rate, Hz.
    #[arg(long, default_value_t = GnssSettings::default().rate_hz)]
    pub gnss_rate_hz: f64,
    /// GNSS position noise, m: one value (horizontal sd; the vertical is twice it) or three
    /// (north, east, down sds). Default 0.5, 0.5, 1.0 (differential code).
    #[arg(long, value_delimiter = ',')]
    pub gnss_sd_m: Vec<f64>,
    /// Heading in the GNSS fixes: dual-antenna (the 2.37 m baseline) or none (position-only
    /// fixes from one antenna, as a rover's or a car's).
    #[arg(long, value_enum, default_value_t = GnssHeadingArg::DualAntenna)]
    pub gnss_heading: GnssHeadingArg,
    /// A turn-on gyro bias added to every gyro sample, X,Y,Z body axes, deg/h (on top of the
    /// profile's own biases; written to truth.json).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub gyro_bias_deg_h: Vec<f64>,
    /// The IMU-GNSS time offset, s, with the sign of `convert --time-offset-s` and
    /// `integrate --estimate-time-offset`: the value added to the IMU times puts them on the
    /// GNSS scale (the IMU's timestamps are written as true time − offset; in truth.json).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub time_offset_s: f64,
    /// Sensor profile (TOML); default: the built-in ADIS16364-like profile.
    #[arg(long)]
    pub profile: Option<PathBuf>,
    /// Seed of every random draw.
    #[arg(long, default_value_t = DEFAULT_SEED)]
    pub seed: u64,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

/// `simulate vessel --gnss-heading`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum GnssHeadingArg {
    /// Dual-antenna heading from the baseline.
    DualAntenna,
    /// Position-only fixes.
    None,
}

/// Arguments of `simulate profile`.
#[derive(Debug, Args)]
pub struct ProfileArgs {
    /// Output TOML file.
    #[arg(long)]
    pub out: PathBuf,
}
