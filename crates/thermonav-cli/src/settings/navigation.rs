//! Settings of `integrate` and `evaluate`.

use super::antenna_geometry;
use super::paths::Io;
use crate::args::{EvaluateArgs, IntegrateArgs, RunOptionArgs};
use crate::failure::Failure;
use anyhow::anyhow;
use std::path::{Path, PathBuf};
use thermonav::evaluation::experiment::{DEFAULT_OUTAGES, MAX_REPLICATES};
use thermonav::evaluation::shard::Shard;
use thermonav::nav::engine::{Aiding, EngineSettings, FilterKind};
use thermonav::nav::outage::OutageSpec;
use thermonav::nav::run_options::{
    RunOptions, bias_hypotheses_of, gate_of, interval_of_rate, velocity_sd_of,
};
use thermonav::nav::schedule::{Compensation, Scheduling};
use thermonav::nav::static_alignment::StaticAlignment;
use thermonav::nav::time_offset::TimeOffsetSearch;
use thermonav_io::ImuOptions;
use thermonav_io::outside_solution::SolutionFormat;

pub use thermonav::nav::run::ModelTemperature;
use thermonav::nav::run::RunSettings;

/// Where the noise model comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum NoiseSource {
    /// A bank from `characterize`.
    Bank(PathBuf),
    /// A sensor profile (TOML), at the model temperature or its reference temperature.
    Profile(PathBuf),
}

impl NoiseSource {
    /// The file.
    pub fn path(&self) -> &Path {
        noise_path(self)
    }
}

/// The three files of one `integrate` run (also reported as `files` in its summary).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SolutionFiles {
    /// The solution trajectory CSV.
    pub solution: PathBuf,
    /// STEM.states.csv beside it.
    pub states: PathBuf,
    /// STEM.innovations.csv beside it.
    pub innovations: PathBuf,
    /// With `--smooth`: the RTS-smoothed trajectory STEM.smoothed.csv and its states
    /// STEM.smoothed.states.csv.
    pub smoothed: Option<[PathBuf; 2]>,
}

impl SolutionFiles {
    /// The solution at `solution` and its two sidecars beside it.
    pub fn beside(solution: &Path) -> Self {
        Self {
            solution: solution.to_path_buf(),
            states: sidecar(solution, "states"),
            innovations: sidecar(solution, "innovations"),
            smoothed: None,
        }
    }

    /// With the smoothed trajectory and its states beside the solution too.
    pub fn smoothed(self) -> Self {
        let smoothed = [
            sidecar(&self.solution, "smoothed"),
            sidecar(&self.solution, "smoothed.states"),
        ];
        Self {
            smoothed: Some(smoothed),
            ..self
        }
    }

    /// Every file written, each named by what it is.
    pub fn named(&self) -> Vec<(&'static str, &Path)> {
        let mut files = vec![
            ("solution", self.solution.as_path()),
            ("state file", self.states.as_path()),
            ("innovations file", self.innovations.as_path()),
        ];
        if let Some([trajectory, states]) = &self.smoothed {
            files.push(("smoothed solution", trajectory.as_path()));
            files.push(("smoothed state file", states.as_path()));
        }
        files
    }
}

/// STEM.SUFFIX.csv beside `out`.
fn sidecar(out: &Path, suffix: &str) -> PathBuf {
    let stem = out
        .file_stem()
        .map_or_else(|| "solution".into(), |s| s.to_string_lossy().into_owned());
    out.with_file_name(format!("{stem}.{suffix}.csv"))
}

/// Everything `integrate` needs, validated.
#[derive(Debug, Clone)]
pub struct IntegrateSettings {
    /// The IMU CSV.
    pub imu: PathBuf,
    /// How it is read (`--imu-rotation`).
    pub imu_options: ImuOptions,
    /// The GNSS CSV.
    pub gnss: PathBuf,
    /// The noise model's source.
    pub noise: NoiseSource,
    /// The run's settings: model temperature, schedule, compensation, family, filter,
    /// outages as given, white-noise scale.
    pub run: RunSettings,
    /// Start from this reference trajectory instead of aligning.
    pub initial_from: Option<PathBuf>,
    /// `--thermal-from`: the bank whose thermal calibration joins the noise model.
    pub thermal_from: Option<PathBuf>,
    /// What is written.
    pub outputs: SolutionFiles,
    /// Read the record whole and keep the solution in memory (`--in-memory`) rather than
    /// stream them.
    pub in_memory: bool,
    /// `--estimate-time-offset`: how the IMU-GNSS offset is searched for.
    pub time_offset_search: Option<TimeOffsetSearch>,
}

/// Resolves `integrate`.
pub fn integrate(args: &IntegrateArgs) -> Result<IntegrateSettings, Failure> {
    if args.smooth && FilterKind::from(args.filter) != FilterKind::Ekf {
        return Err(Failure::Usage(anyhow!(
            "--smooth: the RTS smoother runs on the EKF's covariance; drop --filter ukf"
        )));
    }
    let outputs = match args.smooth {
        true => SolutionFiles::beside(&args.out).smoothed(),
        false => SolutionFiles::beside(&args.out),
    };
    let noise = noise_source(&args.bank, &args.profile)?;
    let options = run_options(&args.run)?;
    let temperature = model_temperature(&args.run)?;
    let time_offset_search = time_offset_search(&args.run)?;
    let io = Io::new()
        .input("--imu", &args.imu)
        .input("--gnss", &args.gnss);
    let io = with_noise(io, &noise).optional_inputs([
        ("--initial-from", args.run.initial_from.as_ref()),
        ("--thermal-from", args.thermal_from.as_ref()),
    ]);
    let io = outputs
        .named()
        .into_iter()
        .fold(io, |io, (what, path)| io.output(what, path));
    io.check()?;
    Ok(IntegrateSettings {
        imu: args.imu.clone(),
        imu_options: super::imu::rotation_only(&args.rotation),
        gnss: args.gnss.clone(),
        noise,
        run: RunSettings::of_options(
            &options,
            temperature,
            (
                Scheduling::when(!args.no_schedule),
                Compensation::when(!args.no_compensation),
            ),
            integrate_engine(args, &options)?,
            args.outages.clone(),
        ),
        initial_from: args.run.initial_from.clone(),
        thermal_from: args.thermal_from.clone(),
        outputs,
        in_memory: args.in_memory,
        time_offset_search,
    })
}

/// `--estimate-time-offset` with its bracket, checked by the library's
/// [`TimeOffsetSearch::with_bracket`].
fn time_offset_search(args: &RunOptionArgs) -> Result<Option<TimeOffsetSearch>, Failure> {
    match args.estimate_time_offset {
        true => TimeOffsetSearch::with_bracket(args.time_offset_bracket_s)
            .map(Some)
            .map_err(Failure::from),
        false => Ok(None),
    }
}

fn noise_source(bank: &Option<PathBuf>, profile: &Option<PathBuf>) -> Result<NoiseSource, Failure> {
    match (bank, profile) {
        (Some(bank), None) => Ok(NoiseSource::Bank(bank.clone())),
        (None, Some(profile)) => Ok(NoiseSource::Profile(profile.clone())),
        _ => Err(Failure::Usage(anyhow!("give --bank or --profile"))),
    }
}

fn noise_option(noise: &NoiseSource) -> &'static str {
    match noise {
        NoiseSource::Bank(_) => "--bank",
        NoiseSource::Profile(_) => "--profile",
    }
}

/// `io` reading the noise model's file (none for a built-in profile).
fn with_noise(io: Io, noise: &NoiseSource) -> Io {
    match noise_path(noise) {
        p if crate::inputs::is_builtin_profile(p) => io,
        p => io.input(noise_option(noise), p),
    }
}

fn noise_path(noise: &NoiseSource) -> &Path {
    match noise {
        NoiseSource::Bank(p) | NoiseSource::Profile(p) => p,
    }
}

/// `--model-temperature-c`, `--operating-temperature-c` and `--select`, checked by the
/// library's [`ModelTemperature::of`].
fn model_temperature(args: &RunOptionArgs) -> Result<ModelTemperature, Failure> {
    let (model, operating) = (args.model_temperature_c, args.operating_temperature_c);
    Ok(ModelTemperature::of(model, operating, args.select.into())?)
}

/// The run options of `integrate` and `evaluate`, resolved the one way for both: shaped here,
/// checked by the library's [`RunOptions::validate`].
pub fn run_options(args: &RunOptionArgs) -> Result<RunOptions, Failure> {
    let options = RunOptions {
        gauss_markov: args.model.into(),
        process_noise_scale: args.process_noise_scale,
        velocity_sd_m_s: velocity_sd_of(&args.velocity_sd_m_s)?,
        gate_probability: gate_of(args.gate_probability)?,
        gate_window: args.gate_window,
        aiding: Aiding {
            position: true,
            velocity: !args.no_velocity,
            heading: !args.no_heading,
        },
        geometry: antenna_geometry(&args.lever_arm_m, &args.baseline)?,
        max_imu_gap_s: args.max_imu_gap_s,
        covariance_interval_s: interval_of_rate("covariance_rate_hz", args.covariance_rate_hz)?,
        bias_hypotheses: bias_hypotheses_of(args.bias_hypotheses)?,
        static_alignment: match args.no_static_alignment {
            true => StaticAlignment::Off,
            false => StaticAlignment::default(),
        },
    };
    options.validate()?;
    Ok(options)
}

/// `integrate`'s own engine settings, beside the run options': its filter, output rate and
/// smoother.
fn integrate_engine(args: &IntegrateArgs, options: &RunOptions) -> Result<EngineSettings, Failure> {
    if options.bias_hypotheses.is_some() && args.smooth {
        return Err(Failure::Usage(anyhow!(
            "--bias-hypotheses with --smooth: a Gaussian sum has no single forward history to smooth"
        )));
    }
    Ok(EngineSettings {
        filter: args.filter.into(),
        output_interval_s: interval_of_rate("output_rate_hz", args.output_rate_hz)?,
        smooth: args.smooth,
        ..EngineSettings::default()
    })
}

/// The three input files of a tournament.
#[derive(Debug, Clone, PartialEq)]
pub struct ScenarioFiles {
    /// IMU CSV.
    pub imu: PathBuf,
    /// How it is read (`--imu-rotation`).
    pub imu_options: ImuOptions,
    /// GNSS CSV.
    pub gnss: PathBuf,
    /// Reference trajectory CSV.
    pub reference: PathBuf,
}

/// Our filters' side of `evaluate`: the data and where the candidates come from.
#[derive(Debug, Clone)]
pub struct FilterRun {
    /// The data.
    pub files: ScenarioFiles,
    /// The candidates' source: a bank or a sensor profile.
    pub noise: NoiseSource,
    /// `--thermal-from`: the bank whose thermal calibration joins the noise models.
    pub thermal_from: Option<PathBuf>,
    /// `--initial-from`: the trajectory every run starts from instead of the reference.
    pub initial_from: Option<PathBuf>,
}

/// One outside solution to score.
#[derive(Debug, Clone, PartialEq)]
pub struct OutsideInput {
    /// Its file.
    pub path: PathBuf,
    /// Its format.
    pub format: SolutionFormat,
    /// Its label in tables and JSON.
    pub label: String,
}

/// Everything `evaluate` needs, validated.
#[derive(Debug, Clone)]
pub struct EvaluateSettings {
    /// Our filters' data and candidates, when they run.
    pub run: Option<FilterRun>,
    /// The reference trajectory.
    pub reference: PathBuf,
    /// The outside solutions.
    pub solutions: Vec<OutsideInput>,
    /// Whether the scheduled candidates compete.
    pub scheduling: Scheduling,
    /// Whether the compensated candidates compete.
    pub compensation: Compensation,
    /// How every candidate's run goes.
    pub options: RunOptions,
    /// The model temperature: where the candidates that stand at one temperature stand (the
    /// temperature given, or the IMU's mean temp_c), and the model of the run the time offset
    /// is searched with.
    pub temperature: ModelTemperature,
    /// `--estimate-time-offset`: how the IMU-GNSS offset is searched for, once, before the
    /// tournament.
    pub time_offset_search: Option<TimeOffsetSearch>,
    /// Filters, in report order.
    pub filters: Vec<FilterKind>,
    /// Outages as given.
    pub outages: OutageSpec,
    /// Replicates beside the main run (shifted outages).
    pub extra_replicates: usize,
    /// Seed of the shifts.
    pub seed: u64,
    /// The profile of the data-sheet candidate (none: the ADIS16364 data sheet).
    pub datasheet: Option<PathBuf>,
    /// A simulated survey's truth, for the oracle candidates.
    pub truth: Option<PathBuf>,
    /// Output folder.
    pub out: PathBuf,
    /// The slice of the runs to run (`--shard`), when not all.
    pub shard: Option<Shard>,
}

impl EvaluateSettings {
    /// The run `integrate` makes with these options and outages (with the one filter of
    /// `--filter`, or integrate's default when both run): the run the time offset is searched
    /// with.
    pub fn integrate_run(&self) -> RunSettings {
        let filter = match self.filters.as_slice() {
            [only] => *only,
            _ => EngineSettings::default().filter,
        };
        let base = EngineSettings {
            filter,
            ..EngineSettings::default()
        };
        let switches = (self.scheduling, self.compensation);
        let outages = self.outages.clone();
        RunSettings::of_options(&self.options, self.temperature, switches, base, outages)
    }
}

/// The outages of `evaluate`: as given, required with outside solutions (their solver had its
/// own), [`DEFAULT_OUTAGES`] otherwise.
fn evaluate_outages(args: &EvaluateArgs) -> Result<OutageSpec, Failure> {
    match (&args.outages, args.solution.is_empty()) {
        (Some(spec), _) => Ok(spec.clone()),
        (None, true) => Ok(DEFAULT_OUTAGES),
        (None, false) => Err(Failure::Usage(anyhow!(
            "--solution needs --outages: the outages the outside solver withheld GNSS in (scoring assumes them)"
        ))),
    }
}

/// Our filters' side, when --imu is given.
fn filter_run(args: &EvaluateArgs, reference: &Path) -> Result<Option<FilterRun>, Failure> {
    let (Some(imu), Some(gnss)) = (&args.imu, &args.gnss) else {
        return Ok(None);
    };
    let files = ScenarioFiles {
        imu: imu.clone(),
        imu_options: super::imu::rotation_only(&args.rotation),
        gnss: gnss.clone(),
        reference: reference.to_path_buf(),
    };
    let noise = noise_source(&args.bank, &args.profile)?;
    if args.thermal_from.is_some() && matches!(noise, NoiseSource::Profile(_)) {
        return Err(Failure::Usage(anyhow!(
            "--thermal-from with --profile: the tournament's compensated candidates are a bank's entries; give --bank (integrate takes --profile with --thermal-from)"
        )));
    }
    Ok(Some(FilterRun {
        files,
        noise,
        thermal_from: args.thermal_from.clone(),
        initial_from: args.run.initial_from.clone(),
    }))
}

/// The --solution files with their formats and labels.
fn outside_inputs(args: &EvaluateArgs) -> Result<Vec<OutsideInput>, Failure> {
    let n = args.solution.len();
    let counts = [args.solution_format.len(), args.solution_label.len()];
    if counts.iter().any(|&c| c > 1 && c != n) || counts[1] == 1 && n > 1 {
        return Err(Failure::Usage(anyhow!(
            "give one --solution-format (for all) or one per --solution, and one --solution-label per --solution ({n} solutions)"
        )));
    }
    let inputs = args.solution.iter().enumerate().map(|(k, path)| {
        let given = args.solution_format.get(k).or(args.solution_format.first());
        let format = match given {
            Some(&f) => f.into(),
            None => SolutionFormat::of_path(path).ok_or_else(|| {
                anyhow!("{}: cannot tell the format from the extension (.csv, .nav, .pos); give --solution-format", path.display())
            })?,
        };
        let label = args.solution_label.get(k).cloned().unwrap_or_else(|| file_label(path));
        Ok(OutsideInput { path: path.clone(), format, label })
    });
    inputs
        .collect::<anyhow::Result<Vec<_>>>()
        .map_err(Failure::Usage)
}

/// A file's name, as a label.
fn file_label(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

/// Resolves `evaluate`.
pub fn evaluate(args: &EvaluateArgs) -> Result<EvaluateSettings, Failure> {
    let reference = required(&args.reference, "--reference")?;
    let settings = EvaluateSettings {
        run: filter_run(args, &reference)?,
        reference,
        solutions: outside_inputs(args)?,
        scheduling: Scheduling::when(!args.no_schedule),
        compensation: Compensation::when(!args.no_compensation),
        options: run_options(&args.run)?,
        temperature: model_temperature(&args.run)?,
        time_offset_search: time_offset_search(&args.run)?,
        filters: args.filter.kinds(),
        outages: evaluate_outages(args)?,
        extra_replicates: replicates(args.monte_carlo)? - 1,
        seed: args.seed,
        datasheet: args.datasheet.clone(),
        truth: args.truth.clone(),
        out: required(&args.out, "--out")?,
        shard: shard_of(args)?,
    };
    evaluate_io(&settings).check()?;
    Ok(settings)
}

/// What `evaluate` reads and writes.
fn evaluate_io(s: &EvaluateSettings) -> Io {
    let paths: Vec<PathBuf> = s.solutions.iter().map(|o| o.path.clone()).collect();
    let io = match &s.run {
        Some(run) => tournament_io(&run.files, &run.noise, &s.out).optional_inputs([
            ("--datasheet", s.datasheet.as_ref()),
            ("--truth", s.truth.as_ref()),
            ("--thermal-from", run.thermal_from.as_ref()),
            ("--initial-from", run.initial_from.as_ref()),
        ]),
        None => Io::new()
            .input("--reference", &s.reference)
            .output("report", &s.out.join("evaluation.json"))
            .output_folder("per-model error folder", &s.out.join("errors")),
    };
    io.inputs("--solution", &paths)
}

/// What a tournament reads and writes.
pub fn tournament_io(files: &ScenarioFiles, noise: &NoiseSource, out: &Path) -> Io {
    let io = Io::new()
        .input("--imu", &files.imu)
        .input("--gnss", &files.gnss)
        .input("--reference", &files.reference);
    with_noise(io, noise)
        .output("report", &out.join("evaluation.json"))
        .output_folder("per-model error folder", &out.join("errors"))
}

/// An option clap requires (unless `evaluate merge` is given, which does not come here).
fn required(value: &Option<PathBuf>, name: &str) -> Result<PathBuf, Failure> {
    value
        .clone()
        .ok_or_else(|| Failure::Usage(anyhow!("{name} is required")))
}

/// The environment variable `--shard auto/N` takes the shard's index from.
pub const SHARD_INDEX_VARIABLE: &str = "SLURM_ARRAY_TASK_ID";

/// `--shard I/N` or `auto/N` (I from [`SHARD_INDEX_VARIABLE`]); refused with `--solution`
/// (outside solutions are scored by the unsharded run only).
fn shard_of(args: &EvaluateArgs) -> Result<Option<Shard>, Failure> {
    let Some(text) = &args.shard else {
        return Ok(None);
    };
    if args.imu.is_none() {
        return Err(Failure::Usage(anyhow!(
            "--shard needs --imu: only our filters' runs are sharded"
        )));
    }
    if !args.solution.is_empty() {
        return Err(Failure::Usage(anyhow!(
            "--shard with --solution: outside solutions are scored only by an unsharded run"
        )));
    }
    if args.run.estimate_time_offset {
        return Err(Failure::Usage(anyhow!(
            "--shard with --estimate-time-offset: estimate the offset once (integrate --estimate-time-offset), shift the record by it (convert --time-offset-s), and shard the tournament on the shifted record"
        )));
    }
    let index = std::env::var(SHARD_INDEX_VARIABLE).ok();
    parse_shard(text, index.as_deref())
        .map(Some)
        .map_err(Failure::Usage)
}

/// `I/N` (1-based) or `auto/N` with I from `auto_index` (the environment's value).
pub fn parse_shard(text: &str, auto_index: Option<&str>) -> anyhow::Result<Shard> {
    let expected = "expected I/N with 1 <= I <= N, or auto/N";
    let (index, count) = text
        .split_once('/')
        .ok_or_else(|| anyhow!("--shard {text}: {expected}"))?;
    let count: usize = (count.trim().parse()).map_err(|_| {
        anyhow!("--shard {text}: the count {count:?} is not a whole number ({expected})")
    })?;
    let index = match index.trim() {
        "auto" => auto_index.ok_or_else(|| {
            anyhow!("--shard {text}: ${SHARD_INDEX_VARIABLE} is not set (run it as a Slurm array task, or give I/N)")
        })?,
        given => given,
    };
    let index: usize = (index.trim().parse()).map_err(|_| {
        anyhow!("--shard {text}: the index {index:?} is not a whole number ({expected})")
    })?;
    Shard::new(index, count).map_err(|e| anyhow!("--shard {text}: {e}"))
}

fn replicates(count: usize) -> Result<usize, Failure> {
    match count {
        0 => Err(Failure::Usage(anyhow!("--monte-carlo must be at least 1"))),
        n if n > MAX_REPLICATES => Err(Failure::Usage(anyhow!(
            "--monte-carlo {n}: at most {MAX_REPLICATES} replicates are run (each runs every model through every filter)"
        ))),
        n => Ok(n),
    }
}
