//! Raw command-line arguments (clap). They are resolved into validated settings by each command.

use crate::thermal_calibration::{DEFAULT_SITE_HEIGHT_M, DEFAULT_SITE_LATITUDE_DEG};
use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use thermonav::evaluation::experiment::DEFAULT_OUTAGES;
use thermonav::mounting::Mounting;
use thermonav::nav::engine::EngineSettings;
use thermonav::nav::outage::OutageSpec;
use thermonav::nav::run_options::RunOptions;
use thermonav::nav::time_offset::TimeOffsetSearch;
use thermonav::rng::DEFAULT_SEED;
use thermonav::signal::wavelet::daubechies::Daubechies;
use thermonav::signal::wavelet::denoise::WaveletDenoise;
use thermonav::signal::wavelet::threshold::{ThresholdRule, Thresholding};
use thermonav::signal::wavelet::transform::ExtensionMode;
use thermonav::sim::chamber::CampaignSettings;
use thermonav::sim::unit::DEFAULT_SERIAL;
use thermonav::sim::vessel::{DEFAULT_WARM_UP_TIME_CONSTANT_S, GnssSettings, SurveySettings};
use thermonav::stoch::allan::{DEFAULT_CONFIDENCE, DeviationKind};
use thermonav::stoch::bank::{GaussMarkovSource, Selection};
use thermonav::stoch::characterize::{CharacterizeSettings, DEFAULT_GMWM};

fn engine() -> EngineSettings {
    EngineSettings::default()
}

fn run_options() -> RunOptions {
    RunOptions::default()
}

fn campaign() -> CampaignSettings {
    CampaignSettings::default()
}

fn conditioning() -> CharacterizeSettings {
    CharacterizeSettings::default()
}

fn wavelet_default() -> WaveletDenoise {
    WaveletDenoise::default()
}

/// `text` with its default, for an optional argument whose default is applied by the settings.
fn with_default(text: &str, default: impl std::fmt::Display) -> String {
    format!("{text} [default: {default}]")
}

/// The command-line name of a value.
fn value_name(value: impl ValueEnum) -> String {
    value
        .to_possible_value()
        .map_or_else(String::new, |v| v.get_name().to_string())
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

/// Kaiser transition width of `fir` and `filter`, Hz.
pub const DEFAULT_TRANSITION_HZ: f64 = 1.0;
/// Kaiser attenuation of `fir` and `filter`, dB.
pub const DEFAULT_RIPPLE_DB: f64 = 60.0;
/// Zero-phase mode of `filter`.
pub const DEFAULT_FILTER_MODE: ModeArg = ModeArg::ZeroPhase;

/// Temperature-dependent stochastic modelling of MEMS IMU errors and GNSS/INS filtering.
#[derive(Debug, Parser)]
#[command(name = "thermonav", version, about, long_about = None)]
pub struct Cli {
    /// No progress bars or step messages on stderr (results and errors are still printed).
    #[arg(long, global = true)]
    pub quiet: bool,
    /// The subcommand to run.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run the main job on built-in simulated data and write everything under --out.
    Demo(DemoArgs),
    /// Sanity-check an IMU, GNSS or reference CSV (chosen by its header): rate, jitter, gaps, ordering, NaN/inf, channel statistics.
    Inspect(InspectArgs),
    /// Design a Kaiser-window FIR low-pass filter (SciPy kaiserord + firwin).
    Fir(FirArgs),
    /// Low-pass filter (and optionally decimate) every channel of an IMU CSV.
    Filter(FilterArgs),
    /// Overlapping Allan deviation per channel, confidence limits and IEEE 952 noise terms.
    Allan(AllanArgs),
    /// AR model per channel and its Gauss-Markov equivalent.
    Ar(ArArgs),
    /// Composite noise model per channel fitted to the Haar wavelet variance (GMWM).
    Gmwm(GmwmArgs),
    /// Build the temperature model bank from static records (one per temperature).
    Characterize(CharacterizeArgs),
    /// Read a model bank.
    Bank(BankArgs),
    /// Production lots: summarise the banks that `characterize --manifest` wrote.
    Lot(LotArgs),
    /// Simulate thermal-chamber records, a vessel survey, or write the built-in sensor profile.
    Simulate(SimulateArgs),
    /// GNSS/INS integration (21-state EKF or UKF) with the bank's noise model at a temperature.
    Integrate(IntegrateArgs),
    /// The temperature-model tournament: every bank model through the filter, GNSS outages,
    /// errors against a reference, ranking and its Monte Carlo significance.
    Evaluate(Box<EvaluateArgs>),
    /// Convert a foreign file (RTKLIB .pos, NMEA, KF-GINS, raw IMU + .tag, PX4 ULog, ROS bags,
    /// ArduPilot DataFlash) to a canonical CSV.
    Convert(ConvertArgs),
    /// Build DIR/report.html (one self-contained page) from what demo or evaluate wrote there.
    Report(ReportArgs),
    /// Draw a figure as SVG (or PNG, by the --out extension) from a file thermonav wrote.
    Plot(PlotArgs),
    /// Take a bank's thermal calibration (the bias at each sample's temperature, through the
    /// channel's thermal lag where it has one, and the power-on offset) off every sample of a
    /// record, gravity kept; writes the canonical IMU CSV and OUT.csv.json.
    Compensate(CompensateArgs),
}

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

/// Which filters a tournament runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FiltersArg {
    /// The EKF only.
    Ekf,
    /// The UKF only.
    Ukf,
    /// Both (the UKF is reported first, as in the paper).
    Both,
}

/// Arguments of `evaluate`.
#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct EvaluateArgs {
    /// `merge`: the shards of a `--shard` run into one evaluation.
    #[command(subcommand)]
    pub action: Option<EvaluateAction>,
    /// The IMU CSV (with --gnss and --bank or --profile: our filters run; without them, only
    /// the --solution files are scored).
    #[arg(long, requires = "gnss", required_unless_present = "solution")]
    pub imu: Option<PathBuf>,
    #[command(flatten)]
    pub rotation: ImuRotationArgs,
    /// The GNSS CSV.
    #[arg(long, requires = "imu")]
    pub gnss: Option<PathBuf>,
    /// The reference, covering every outage: our trajectory CSV, a GNSS CSV, an RTKLIB .pos or
    /// a KF-GINS .nav, told by the content. With attitude (trajectory CSV, .nav) the runs start
    /// from it and heading is scored; fixes (GNSS CSV, .pos) score position only and the runs
    /// align from GNSS. It may start after the first GNSS fix (the runs then start at its
    /// first point, as integrate --initial-from).
    #[arg(long, required = true)]
    pub reference: Option<PathBuf>,
    /// The temperature model bank (JSON).
    #[arg(long, conflicts_with = "profile", requires = "imu")]
    pub bank: Option<PathBuf>,
    /// Instead of a bank: a sensor profile (TOML) for a sensor without a chamber campaign; the
    /// candidates are then the profile at its table temperatures and at the operating
    /// temperature, and the profile scheduled by temperature.
    #[arg(long, requires = "imu")]
    pub profile: Option<PathBuf>,
    /// The thermal calibration of this bank (one from `characterize --sweep` alone, say)
    /// with the noise models of --bank, whose own calibration it replaces; refused when the
    /// two differ in channels or units.
    #[arg(long, requires = "imu")]
    pub thermal_from: Option<PathBuf>,
    /// An outside solution (repeatable) scored with the same outage metrics, as a row of kind
    /// "outside" beside our candidates (not ranked). The scoring assumes that the solution was
    /// computed with GNSS withheld in the same --outages, which must then be given.
    #[arg(long)]
    pub solution: Vec<PathBuf>,
    /// Format of each --solution, in order (one value: every solution); default from the
    /// extension: .csv our trajectory CSV, .nav KF-GINS (week + seconds of week), .pos RTKLIB
    /// (GPST; heading = course over ground). NaveGo: write its solution as our trajectory CSV.
    #[arg(long, value_enum, value_delimiter = ',')]
    pub solution_format: Vec<SolutionFormatArg>,
    /// Label of each --solution, in order (default: the file's name).
    #[arg(long)]
    pub solution_label: Vec<String>,
    /// Leave out the candidates scheduled by the IMU's temp_c.
    #[arg(long)]
    pub no_schedule: bool,
    /// Leave out the candidates on the thermally compensated record.
    #[arg(long)]
    pub no_compensation: bool,
    /// A simulated survey's truth.json (`simulate vessel`): adds the oracle candidates, the
    /// true model scheduled by temperature on the raw record and on the record without the
    /// true bias(T), ranked apart, and every model's gap to the better of them.
    #[arg(long)]
    pub truth: Option<PathBuf>,
    #[command(flatten)]
    pub run: RunOptionArgs,
    /// Filters to run.
    #[arg(long, value_enum, default_value_t = FiltersArg::Both)]
    pub filter: FiltersArg,
    /// Outages: spread:COUNT,DURATION, START+DURATION[,...] or every:FIRST,DURATION,PERIOD,COUNT,
    /// in seconds on the files' t_s scale; after rel: (rel:265+10) in seconds from the first
    /// IMU sample (from the reference's first point when no IMU is given). Required with
    /// --solution.
    #[arg(long, help = with_default("Outages: spread:COUNT,DURATION, START+DURATION[,...] or every:FIRST,DURATION,PERIOD,COUNT, in seconds on the files' t_s scale; after rel: (rel:265+10) in seconds from the first IMU sample (from the reference's first point when no IMU is given). Required with --solution", DEFAULT_OUTAGES))]
    pub outages: Option<OutageSpec>,
    /// Monte Carlo replicates over shifted outage start times (1 = no Monte Carlo).
    #[arg(long, default_value_t = 1)]
    pub monte_carlo: usize,
    /// Seed of the outage shifts.
    #[arg(long, default_value_t = DEFAULT_SEED)]
    pub seed: u64,
    /// The data-sheet candidate from this sensor profile (TOML, as `simulate profile`
    /// writes): its model at its reference temperature. Default: the ADIS16364 data sheet
    /// (ARW, in-run bias stability / 0.62, a 1 h correlation time).
    #[arg(long)]
    pub datasheet: Option<PathBuf>,
    /// Run one slice of the tournament's runs (replicate x model), I/N with I in 1..=N, or
    /// auto/N to take I from $SLURM_ARRAY_TASK_ID (`sbatch --array=1-N`): writes
    /// OUT/shard-I-of-N.json instead of evaluation.json; `evaluate merge` joins the shards.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Output folder (evaluation.json and errors/*.csv).
    #[arg(long, required = true)]
    pub out: Option<PathBuf>,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Actions of `evaluate` beside the tournament itself.
#[derive(Debug, Subcommand)]
pub enum EvaluateAction {
    /// Merge the shard files of `evaluate --shard` runs into OUT/evaluation.json and
    /// OUT/errors/*.csv, the same files, byte for byte, as one unsharded run into OUT.
    Merge(EvaluateMergeArgs),
}

/// Arguments of `evaluate merge`.
#[derive(Debug, Args)]
pub struct EvaluateMergeArgs {
    /// Folders holding the shard files (shard-I-of-N.json), or the shard files themselves.
    #[arg(required = true)]
    pub shards: Vec<PathBuf>,
    /// Output folder (evaluation.json and errors/*.csv).
    #[arg(long)]
    pub out: PathBuf,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Formats `convert --to` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ToFormatArg {
    /// KF-GINS text files (IMU increments, GNSS, .nav).
    KfGins,
}

/// Formats of outside solutions (`evaluate --solution-format`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SolutionFormatArg {
    /// Our trajectory CSV (t_s,lat_deg,lon_deg,h_m,vn_m_s,ve_m_s,vd_m_s,roll_deg,pitch_deg,yaw_deg).
    Csv,
    /// KF-GINS navigation result (.nav): week, seconds of week, lat, lon, h, vn, ve, vd, roll,
    /// pitch, yaw (deg, yaw 0..360).
    KfGinsNav,
    /// RTKLIB solution (.pos) with velocities; the heading is the course over ground.
    RtklibPos,
}

impl From<SolutionFormatArg> for thermonav_io::outside_solution::SolutionFormat {
    fn from(f: SolutionFormatArg) -> Self {
        match f {
            SolutionFormatArg::Csv => Self::Csv,
            SolutionFormatArg::KfGinsNav => Self::KfGinsNav,
            SolutionFormatArg::RtklibPos => Self::RtklibPos,
        }
    }
}

/// The navigation filters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FilterArg {
    /// Error-state extended Kalman filter (Joseph form).
    Ekf,
    /// Error-state unscented Kalman filter.
    Ukf,
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

/// Arguments of `integrate`.
#[derive(Debug, Args)]
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
    #[arg(long, required_unless_present = "profile", conflicts_with = "profile")]
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
    #[arg(long, value_enum, default_value_t = FilterArg::Ekf)]
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
    #[arg(long, default_value = "adev")]
    pub kind: DeviationKind,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Arguments of `gmwm`.
#[derive(Debug, Args)]
pub struct GmwmArgs {
    /// The IMU CSV (rates, raw: white noise must not be filtered away), or a ROS bag (a file
    /// or a ROS 2 bag folder), or an ArduPilot DataFlash log.
    pub file: PathBuf,
    #[command(flatten)]
    pub topics: BagTopicArgs,
    /// The composite, e.g. wn+rw+2gm or wn+qn+gm (wn, qn, rw, dr, gm, kgm), or auto: the
    /// candidate with the smallest Wavelet Information Criterion.
    #[arg(long, default_value = "auto")]
    pub model: String,
    /// Parametric-bootstrap replicates for the parameters' intervals and the WIC, 10 to 1000
    /// (each simulates and refits the whole record once); 0, the default: no intervals, the
    /// candidates ranked by the asymptotic WIC (objective + 2 x parameters).
    #[arg(long, default_value_t = thermonav_io::gmwm::DEFAULT_REPLICATES)]
    pub replicates: usize,
    /// Seed of the bootstrap's named random streams.
    #[arg(long, default_value_t = DEFAULT_SEED)]
    pub seed: u64,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

/// AR estimators.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ArMethodArg {
    /// Yule-Walker (Levinson-Durbin on the biased autocovariance).
    YuleWalker,
    /// Burg.
    Burg,
    /// Covariance method (forward least squares).
    Covariance,
    /// Modified covariance (forward-backward least squares).
    ModifiedCovariance,
}

/// Arguments of `ar`.
#[derive(Debug, Args)]
pub struct ArArgs {
    /// The IMU CSV (rates); filter and decimate it first with `thermonav filter` as the paper does.
    pub file: PathBuf,
    /// Estimator.
    #[arg(long, value_enum, default_value_t = ArMethodArg::Burg)]
    pub method: ArMethodArg,
    /// Order: a number, or `auto` (BIC over 1..=--max-order).
    #[arg(long, default_value = "1")]
    pub order: String,
    /// Largest order tried by `--order auto`.
    #[arg(long, default_value_t = 10)]
    pub max_order: usize,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
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

/// Export formats.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ExportFormatArg {
    /// PX4 TC_* thermal compensation, a QGroundControl .params file.
    Px4Tc,
    /// ArduPilot INS_TCAL1_* temperature calibration, a Mission Planner/MAVProxy .param file.
    ArdupilotTcal,
    /// Kalibr imu.yaml (noise densities and random walks, continuous).
    Kalibr,
    /// KF-GINS imunoise: block (arw, vrw, gbstd, abstd, gsstd, asstd, corrtime).
    KfGins,
    /// OB_GINS imumodel: block (arw, vrw, gbstd, abstd, corrtime).
    ObGins,
    /// gnss-ins-sim imu_err dictionary (Python).
    GnssInsSim,
    /// PX4 EKF2_GYR/ACC(_B)_NOISE parameters, a QGroundControl .params file.
    Px4Ekf2,
    /// ArduPilot EK3_*_P_NSE parameters, a .parm file.
    ArdupilotEk3,
    /// MATLAB gyroparams/accelparams/imuSensor script.
    Matlab,
    /// ROS sensor_msgs/Imu covariances (YAML).
    RosImuCovariance,
}

/// What an export format writes.
#[derive(Debug, Clone, Copy)]
pub enum ExportKind {
    /// The thermal calibration as autopilot parameters.
    Thermal(thermonav_io::thermal_parameters::ParameterTarget),
    /// The noise model at a temperature.
    Noise(thermonav_io::noise_export::NoiseFormat),
}

impl From<ExportFormatArg> for ExportKind {
    fn from(format: ExportFormatArg) -> Self {
        use thermonav_io::noise_export::NoiseFormat as N;
        use thermonav_io::thermal_parameters::ParameterTarget as T;
        match format {
            ExportFormatArg::Px4Tc => Self::Thermal(T::Px4Tc),
            ExportFormatArg::ArdupilotTcal => Self::Thermal(T::ArdupilotTcal),
            ExportFormatArg::Kalibr => Self::Noise(N::Kalibr),
            ExportFormatArg::KfGins => Self::Noise(N::KfGins),
            ExportFormatArg::ObGins => Self::Noise(N::ObGins),
            ExportFormatArg::GnssInsSim => Self::Noise(N::GnssInsSim),
            ExportFormatArg::Px4Ekf2 => Self::Noise(N::Px4Ekf2),
            ExportFormatArg::ArdupilotEk3 => Self::Noise(N::ArdupilotEk3),
            ExportFormatArg::Matlab => Self::Noise(N::Matlab),
            ExportFormatArg::RosImuCovariance => Self::Noise(N::RosImuCovariance),
        }
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

/// Arguments of `lot`.
#[derive(Debug, Args)]
pub struct LotArgs {
    /// What to do with the lot.
    #[command(subcommand)]
    pub action: LotAction,
}

/// Lot actions.
#[derive(Debug, Subcommand)]
pub enum LotAction {
    /// Build DIR/lot-summary.json from DIR/SERIAL/bank.json of every unit of the manifest
    /// (written by separate `characterize --manifest --unit-index N` jobs).
    Summarize(LotSummarizeArgs),
}

/// Arguments of `lot summarize`.
#[derive(Debug, Args)]
pub struct LotSummarizeArgs {
    /// The folder the unit jobs wrote (their --out).
    pub dir: PathBuf,
    /// The lot manifest (TOML).
    #[arg(long)]
    pub manifest: PathBuf,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Model selection rules.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum SelectArg {
    /// The entry at the nearest temperature.
    Nearest,
    /// Linear interpolation of Tc and sigma between the bracketing entries.
    Linear,
}

/// Gauss-Markov model families in the bank.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum GmSourceArg {
    /// Exact likelihood of Gauss-Markov + white noise on the irregular timestamps.
    IrregularMl,
    /// The paper's AR(1)-based model.
    ArBased,
    /// The classical fit to the autocorrelation.
    AcfFit,
    /// The bias state of the GMWM composite, with the composite's white noise.
    Gmwm,
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

/// Arguments of `demo`.
#[derive(Debug, Args)]
pub struct DemoArgs {
    /// Output folder.
    #[arg(long, default_value = "out/demo")]
    pub out: PathBuf,
    /// A shorter run (seconds instead of minutes).
    #[arg(long)]
    pub quick: bool,
    /// Seed of every random draw.
    #[arg(long, default_value_t = DEFAULT_SEED)]
    pub seed: u64,
    /// Keep the simulated chamber records (DIR/chamber/*.csv and DIR/temperature/chamber/:
    /// about 360 MB with --quick, 2 GB without), which are otherwise removed once their banks
    /// are built (their truth.json files stay).
    #[arg(long)]
    pub keep_records: bool,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Arguments of `inspect`.
#[derive(Debug, Args)]
pub struct InspectArgs {
    /// The IMU, GNSS or reference (trajectory) CSV to inspect, recognised by its header.
    pub file: PathBuf,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Kaiser low-pass specification shared by `fir` and `filter`.
#[derive(Debug, Args, Clone, Copy)]
pub struct KaiserArgs {
    /// Pass-band edge (cut-off), Hz.
    #[arg(long)]
    pub cutoff_hz: f64,
    /// Width of the transition band, Hz.
    #[arg(long, default_value_t = DEFAULT_TRANSITION_HZ)]
    pub transition_hz: f64,
    /// Stop-band attenuation and pass-band ripple, dB (positive).
    #[arg(long, default_value_t = DEFAULT_RIPPLE_DB, allow_negative_numbers = true)]
    pub ripple_db: f64,
}

/// Arguments of `fir`.
#[derive(Debug, Args)]
pub struct FirArgs {
    /// Sampling rate, Hz.
    #[arg(long)]
    pub fs_hz: f64,
    /// The filter specification.
    #[command(flatten)]
    pub kaiser: KaiserArgs,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

/// How the filter's delay is removed.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ModeArg {
    /// One forward pass with the linear-phase group delay removed.
    ZeroPhase,
    /// Forward-backward filtering, as SciPy's filtfilt (squared magnitude response).
    Filtfilt,
}

/// How a record is de-noised (`filter --method`, `characterize --denoise`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DenoiseArg {
    /// Kaiser-window low-pass, zero phase (the paper's).
    Kaiser,
    /// Wavelet shrinkage with a Daubechies wavelet (the paper's named alternative).
    Wavelet,
}

/// Threshold rules of the wavelet de-noising.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ThresholdArg {
    /// σ √(2 ln n), σ from the median absolute finest detail / 0.6745 (VisuShrink).
    Universal,
    /// Stein's unbiased risk estimate minimised per level, at most the band's universal one.
    Sure,
    /// SURE, or the band's universal threshold where the band is sparse (SureShrink, 1995).
    SureHybrid,
}

/// Soft or hard thresholding.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ThresholdingArg {
    /// sign(x) max(|x| − λ, 0).
    Soft,
    /// x where |x| ≥ λ, else 0.
    Hard,
}

/// Extension of the signal beyond its ends (PyWavelets' modes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ExtensionArg {
    /// Half-sample symmetric reflection.
    Symmetric,
    /// Periodic (an orthogonal transform; the ends meet).
    Periodization,
}

/// Arguments of `filter`.
#[derive(Debug, Args)]
pub struct FilterArgs {
    /// The IMU CSV to filter.
    pub input: PathBuf,
    /// De-noising method.
    #[arg(long, value_enum, default_value_t = DenoiseArg::Kaiser)]
    pub method: DenoiseArg,
    /// Options of --method kaiser.
    #[command(flatten)]
    pub kaiser: FilterKaiserArgs,
    /// Options of --method wavelet.
    #[command(flatten)]
    pub wavelet: WaveletArgs,
    /// Output CSV; a sidecar OUT.json records what was done.
    #[arg(long)]
    pub out: PathBuf,
    /// Print one JSON document (the sidecar) instead of text.
    #[arg(long)]
    pub json: bool,
}

/// The options of `filter --method kaiser` (refused with the wavelet method).
#[derive(Debug, Args, Clone, Copy)]
pub struct FilterKaiserArgs {
    /// Kaiser: pass-band edge (cut-off), Hz (required with --method kaiser).
    #[arg(long)]
    pub cutoff_hz: Option<f64>,
    #[arg(long, help = with_default("Kaiser: width of the transition band, Hz", DEFAULT_TRANSITION_HZ))]
    pub transition_hz: Option<f64>,
    #[arg(long, allow_negative_numbers = true, help = with_default("Kaiser: stop-band attenuation and pass-band ripple, dB (positive)", DEFAULT_RIPPLE_DB))]
    pub ripple_db: Option<f64>,
    #[arg(long, value_enum, help = with_default("Kaiser: zero-phase mode", value_name(DEFAULT_FILTER_MODE)))]
    pub mode: Option<ModeArg>,
    /// Kaiser: decimate to this rate after filtering, Hz (must divide the input rate).
    #[arg(long)]
    pub decimate_to_hz: Option<f64>,
    /// Kaiser: sampling rate used for the design, Hz (default: the nominal rate of the file).
    #[arg(long)]
    pub fs_hz: Option<f64>,
}

/// The options of `filter --method wavelet` (refused with the Kaiser method).
#[derive(Debug, Args, Clone, Copy)]
pub struct WaveletArgs {
    #[arg(long, help = with_default("Wavelet: Daubechies wavelet db1..db10 (haar = db1)", wavelet_default().wavelet))]
    pub wavelet: Option<Daubechies>,
    /// Wavelet: decomposition level, 1 to PyWavelets' dwt_max_level for the record's length
    /// and the wavelet [default: that maximum].
    #[arg(long)]
    pub level: Option<usize>,
    #[arg(long, value_enum, help = with_default("Wavelet: threshold rule", wavelet_default().rule.name()))]
    pub threshold: Option<ThresholdArg>,
    #[arg(long, value_enum, help = with_default("Wavelet: thresholding", wavelet_default().thresholding.name()))]
    pub thresholding: Option<ThresholdingArg>,
    #[arg(long, value_enum, help = with_default("Wavelet: extension at the ends", wavelet_default().mode.name()))]
    pub extension: Option<ExtensionArg>,
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
    #[arg(long, default_value_t = 18)]
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
    #[arg(long, value_enum, value_delimiter = ',', default_values_t = [GmSourceArg::IrregularMl, GmSourceArg::ArBased, GmSourceArg::AcfFit])]
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

/// Arguments of `report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// The folder demo (or characterize + evaluate) wrote: DIR/bank.json (required:
    /// characterize --out DIR/bank.json); optional: DIR/demo.json,
    /// DIR/evaluation/evaluation.json with its errors/ (evaluate --out DIR/evaluation),
    /// DIR/vessel/reference.csv (the survey figure), DIR/solution/solution.innovations.csv
    /// (integrate --out DIR/solution/solution.csv; the innovations figure). Or a folder
    /// evaluate wrote (evaluate --out DIR: DIR/evaluation.json with its errors/): the
    /// tournament alone, without the bank's sections.
    pub dir: PathBuf,
}

impl From<GmSourceArg> for thermonav::stoch::bank::GaussMarkovSource {
    fn from(m: GmSourceArg) -> Self {
        match m {
            GmSourceArg::IrregularMl => Self::IrregularMl,
            GmSourceArg::ArBased => Self::ArBased,
            GmSourceArg::AcfFit => Self::AcfFit,
            GmSourceArg::Gmwm => Self::Gmwm,
        }
    }
}

impl From<GaussMarkovSource> for GmSourceArg {
    fn from(m: GaussMarkovSource) -> Self {
        match m {
            GaussMarkovSource::IrregularMl => Self::IrregularMl,
            GaussMarkovSource::ArBased => Self::ArBased,
            GaussMarkovSource::AcfFit => Self::AcfFit,
            GaussMarkovSource::Gmwm => Self::Gmwm,
        }
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

impl From<FilterArg> for thermonav::nav::engine::FilterKind {
    fn from(f: FilterArg) -> Self {
        match f {
            FilterArg::Ekf => Self::Ekf,
            FilterArg::Ukf => Self::Ukf,
        }
    }
}

impl FiltersArg {
    /// The filters of the choice, UKF first (the paper's filter).
    pub fn kinds(self) -> Vec<thermonav::nav::engine::FilterKind> {
        use thermonav::nav::engine::FilterKind;
        match self {
            FiltersArg::Ekf => vec![FilterKind::Ekf],
            FiltersArg::Ukf => vec![FilterKind::Ukf],
            FiltersArg::Both => FilterKind::BOTH.to_vec(),
        }
    }
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

impl From<ArMethodArg> for thermonav::stoch::ar::ArMethod {
    fn from(m: ArMethodArg) -> Self {
        match m {
            ArMethodArg::YuleWalker => Self::YuleWalker,
            ArMethodArg::Burg => Self::Burg,
            ArMethodArg::Covariance => Self::Covariance,
            ArMethodArg::ModifiedCovariance => Self::ModifiedCovariance,
        }
    }
}

impl From<ThresholdArg> for ThresholdRule {
    fn from(t: ThresholdArg) -> Self {
        match t {
            ThresholdArg::Universal => Self::Universal,
            ThresholdArg::Sure => Self::Sure,
            ThresholdArg::SureHybrid => Self::SureHybrid,
        }
    }
}

impl From<ThresholdingArg> for Thresholding {
    fn from(t: ThresholdingArg) -> Self {
        match t {
            ThresholdingArg::Soft => Self::Soft,
            ThresholdingArg::Hard => Self::Hard,
        }
    }
}

impl From<ExtensionArg> for ExtensionMode {
    fn from(e: ExtensionArg) -> Self {
        match e {
            ExtensionArg::Symmetric => Self::Symmetric,
            ExtensionArg::Periodization => Self::Periodization,
        }
    }
}

impl From<ModeArg> for thermonav::signal::zero_phase::ZeroPhaseMode {
    fn from(m: ModeArg) -> Self {
        match m {
            ModeArg::ZeroPhase => Self::DelayCompensated,
            ModeArg::Filtfilt => Self::ForwardBackward,
        }
    }
}
