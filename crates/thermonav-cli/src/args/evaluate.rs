//! Arguments of `thermonav evaluate`.

use super::shared::{ImuRotationArgs, RunOptionArgs, with_default};
use clap::{Args, Subcommand, ValueEnum};
use std::path::PathBuf;
use thermonav::evaluation::experiment::{DEFAULT_MONTE_CARLO, DEFAULT_OUTAGES};
use thermonav::nav::outage::OutageSpec;
use thermonav::rng::DEFAULT_SEED;

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
    #[arg(long, default_value_t = DEFAULT_MONTE_CARLO)]
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
