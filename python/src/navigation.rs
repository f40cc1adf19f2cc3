//! `integrate` and `evaluate` from files: the library's run ([`thermonav::nav::run`]) and
//! tournament ([`thermonav::evaluation::scenario`], [`thermonav::evaluation::experiment`]),
//! the calls `thermonav integrate` and `thermonav evaluate` make, with the same defaults and
//! seeded streams. The solution leaves as NumPy arrays named like the CLI's solution and state
//! CSV columns; the reports as the CLI's `--json` documents.

use crate::arrays::array;
use crate::{error, to_python};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};
use thermonav::evaluation::candidates::{ThermalOptions, datasheet_model};
use thermonav::evaluation::experiment::{
    CandidateSource, DEFAULT_MONTE_CARLO, DEFAULT_OUTAGES, Replicates, Tournament,
    TournamentOutcome, TournamentPlan,
};
use thermonav::evaluation::metrics::EpochError;
use thermonav::evaluation::oracle::TrueModel;
use thermonav::evaluation::scenario::{RecordPlan, ScenarioError, scenario_of_records};
use thermonav::nav::engine::{Aiding, EngineSettings, FilterKind};
use thermonav::nav::measurement::AntennaGeometry;
use thermonav::nav::outage::OutageSpec;
use thermonav::nav::report::RunReport;
use thermonav::nav::run::{
    ModelTemperature, NoiseModel, RunError, RunInput, RunSettings, Start, operating_temperature_c,
    prepare,
};
use thermonav::nav::run_options::{
    RunOptions, bias_hypotheses_of, gate_of, interval_of_rate, velocity_sd_of,
};
use thermonav::nav::schedule::{Compensation, Scheduling};
use thermonav::nav::sensor_model::ScaleFactorPrior;
use thermonav::nav::solution::SolutionEpoch;
use thermonav::rng::DEFAULT_SEED;
use thermonav::sensor::SensorProfile;
use thermonav::setting::SettingError;
use thermonav::stoch::bank::{GaussMarkovSource, ModelBank, Selection};
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::solution::{state_column_names, state_values};
use thermonav_io::{
    Strictness, read_gnss_file, read_imu_file, read_trajectory_file, trajectory_column_names,
    trajectory_values,
};

/// A bank or a profile, read.
enum Noise {
    Bank(ModelBank),
    Profile(SensorProfile),
}

impl Noise {
    /// Reads `bank` or `profile` (exactly one).
    fn read(bank: Option<PathBuf>, profile: Option<PathBuf>) -> PyResult<(Self, PathBuf)> {
        match (bank, profile) {
            (Some(p), None) => Ok((Noise::Bank(read_bank(&p)?), p)),
            (None, Some(p)) => Ok((Noise::Profile(read_profile(&p)?), p)),
            _ => Err(error("give bank or profile (one of them)")),
        }
    }

    fn model(&self) -> NoiseModel<'_> {
        match self {
            Noise::Bank(bank) => NoiseModel::Bank(bank),
            Noise::Profile(profile) => NoiseModel::Profile(profile),
        }
    }

    fn source(&self) -> CandidateSource<'_> {
        match self {
            Noise::Bank(bank) => CandidateSource::Bank(bank),
            Noise::Profile(profile) => CandidateSource::Profile(profile),
        }
    }
}

fn read_bank(path: &Path) -> PyResult<ModelBank> {
    thermonav_io::bank::read_bank_file(path).map_err(error)
}

fn read_profile(path: &Path) -> PyResult<SensorProfile> {
    thermonav_io::profile::read_profile(path).map_err(error)
}

/// The records every run reads: IMU, GNSS, noise model.
struct Records {
    series: thermonav::imu::ImuSeries,
    gnss: Vec<thermonav::gnss::GnssFix>,
    noise: Noise,
    noise_path: PathBuf,
}

/// The input files (`noise` = (bank, profile)).
struct Files {
    imu: PathBuf,
    gnss: PathBuf,
    noise: (Option<PathBuf>, Option<PathBuf>),
}

impl Files {
    fn read(&self) -> PyResult<Records> {
        let series = read_imu_file(&self.imu, Strictness::Strict).map_err(error)?;
        let gnss = read_gnss_file(&self.gnss, Strictness::Strict).map_err(error)?;
        let (noise, noise_path) = Noise::read(self.noise.0.clone(), self.noise.1.clone())?;
        Ok(Records {
            series,
            gnss,
            noise,
            noise_path,
        })
    }

    /// `PATH: ` of the input an error is about.
    fn prefix(&self, input: RunInput, records: &Records, reference: Option<&Path>) -> String {
        let path = match input {
            RunInput::Imu => Some(self.imu.as_path()),
            RunInput::Gnss => Some(self.gnss.as_path()),
            RunInput::Noise => Some(records.noise_path.as_path()),
            RunInput::Reference => reference,
            RunInput::Settings | RunInput::Filter => None,
        };
        path.map(|p| format!("{}: ", p.display()))
            .unwrap_or_default()
    }
}

/// A run's or a scenario's refusal, naming the file or the keyword it is about.
fn refusal(message: String, input: RunInput, prefix: String) -> PyErr {
    match input {
        RunInput::Settings => error(format!("outages: {message}")),
        _ => error(format!("{prefix}{message}")),
    }
}

/// One of `names` (the CLI's value names), else an error naming `what`.
fn choice<T: Copy>(what: &str, value: &str, names: &[(&str, T)]) -> PyResult<T> {
    (names.iter().find(|(name, _)| *name == value))
        .map(|(_, v)| *v)
        .ok_or_else(|| {
            let known: Vec<&str> = names.iter().map(|(n, _)| *n).collect();
            error(format!(
                "{what} {value:?}: expected one of {}",
                known.join(", ")
            ))
        })
}

fn gauss_markov_of(model: Option<&str>) -> PyResult<GaussMarkovSource> {
    let Some(model) = model else {
        return Ok(GaussMarkovSource::default());
    };
    let names: Vec<(&str, GaussMarkovSource)> = GaussMarkovSource::in_listing_order()
        .map(|s| (s.name(), s))
        .collect();
    choice("model", model, &names)
}

fn filters_of(filter: &str) -> PyResult<Vec<FilterKind>> {
    let names: [(&str, &[FilterKind]); 3] = [
        ("ekf", &[FilterKind::Ekf]),
        ("ukf", &[FilterKind::Ukf]),
        ("both", &FilterKind::BOTH),
    ];
    choice("filter", filter, &names).map(<[FilterKind]>::to_vec)
}

fn outages_of(outages: Option<&str>, default: OutageSpec) -> PyResult<OutageSpec> {
    let Some(outages) = outages else {
        return Ok(default);
    };
    outages
        .parse()
        .map_err(|e| error(format!("outages {outages:?}: {e}")))
}

/// The antenna geometry: lever arm (m, body forward/right/down) and baseline direction.
fn geometry_of(
    lever_arm_m: Option<[f64; 3]>,
    baseline: Option<[f64; 3]>,
) -> PyResult<AntennaGeometry> {
    let defaults = AntennaGeometry::default();
    let geometry = AntennaGeometry {
        lever_arm_body_m: lever_arm_m.unwrap_or(defaults.lever_arm_body_m),
        baseline_body: baseline.unwrap_or(defaults.baseline_body),
    };
    let all = geometry
        .lever_arm_body_m
        .iter()
        .chain(&geometry.baseline_body);
    if !all.into_iter().all(|v| v.is_finite()) {
        return Err(error("lever_arm_m and baseline must be finite"));
    }
    if geometry.baseline_body[0].hypot(geometry.baseline_body[1]) == 0.0 {
        return Err(error(
            "baseline must have a horizontal component to define a heading",
        ));
    }
    Ok(geometry)
}

/// Which temperature's model: fixed, or the operating temperature (given or the record's),
/// checked by the library's [`ModelTemperature::of`].
fn temperature_of(
    model_temperature_c: Option<f64>,
    operating_temperature_c: Option<f64>,
    select: Option<&str>,
) -> PyResult<ModelTemperature> {
    let names = [
        ("nearest", Selection::Nearest),
        ("linear", Selection::Linear),
    ];
    let selection = match select {
        Some(select) => choice("select", select, &names)?,
        None => Selection::default(),
    };
    ModelTemperature::of(model_temperature_c, operating_temperature_c, selection).map_err(refused)
}

/// The run options of `integrate` and `evaluate` (the CLI's, with the same names: rates in
/// Hz, sd in m/s), each `None` for the library's default ([`RunOptions::default`]).
struct RunKeywords {
    model: Option<String>,
    process_noise_scale: Option<f64>,
    velocity_sd_m_s: Option<Vec<f64>>,
    velocity: Option<bool>,
    heading: Option<bool>,
    gate_probability: Option<f64>,
    gate_window: Option<usize>,
    lever_arm_m: Option<[f64; 3]>,
    baseline: Option<[f64; 3]>,
    covariance_rate_hz: Option<f64>,
    max_imu_gap_s: Option<f64>,
    bias_hypotheses: Option<usize>,
}

impl RunKeywords {
    /// The run options, resolved the one way for both functions.
    fn options(&self) -> PyResult<RunOptions> {
        let d = RunOptions::default();
        let options = RunOptions {
            gauss_markov: gauss_markov_of(self.model.as_deref())?,
            process_noise_scale: self.process_noise_scale.unwrap_or(d.process_noise_scale),
            velocity_sd_m_s: match self.velocity_sd_m_s.as_deref() {
                Some(values) => velocity_sd_of(values).map_err(refused)?,
                None => d.velocity_sd_m_s,
            },
            gate_probability: match self.gate_probability {
                Some(p) => gate_of(p).map_err(refused)?,
                None => d.gate_probability,
            },
            gate_window: self.gate_window.unwrap_or(d.gate_window),
            aiding: Aiding {
                position: true,
                velocity: self.velocity.unwrap_or(d.aiding.velocity),
                heading: self.heading.unwrap_or(d.aiding.heading),
            },
            geometry: geometry_of(self.lever_arm_m, self.baseline)?,
            max_imu_gap_s: self.max_imu_gap_s.unwrap_or(d.max_imu_gap_s),
            covariance_interval_s: match self.covariance_rate_hz {
                Some(r) => interval_of_rate("covariance_rate_hz", r).map_err(refused)?,
                None => d.covariance_interval_s,
            },
            bias_hypotheses: match self.bias_hypotheses {
                Some(n) => bias_hypotheses_of(n).map_err(refused)?,
                None => None,
            },
            static_alignment: d.static_alignment,
        };
        options.validate().map_err(refused)?;
        Ok(options)
    }
}

/// A run option's refusal, in the keyword's name (the library's words).
fn refused(e: SettingError) -> PyErr {
    error(e.to_string())
}

/// `integrate`'s own engine settings, beside the run options': its filter, output rate and
/// smoother.
fn integrate_engine(
    options: &RunOptions,
    filter: FilterKind,
    output_rate_hz: Option<f64>,
    smooth: bool,
) -> PyResult<EngineSettings> {
    let d = EngineSettings::default();
    if smooth && filter != FilterKind::Ekf {
        return Err(error(
            "smooth: the RTS smoother runs on the EKF's covariance; use filter=\"ekf\"",
        ));
    }
    if smooth && options.bias_hypotheses.is_some() {
        return Err(error(
            "bias_hypotheses with smooth: a Gaussian sum has no single forward history to smooth",
        ));
    }
    Ok(EngineSettings {
        filter,
        output_interval_s: match output_rate_hz {
            Some(r) => interval_of_rate("output_rate_hz", r).map_err(refused)?,
            None => d.output_interval_s,
        },
        smooth,
        ..d
    })
}

/// Solution epochs as columns: `t_ns`, `t_s`, the trajectory CSV's (lat_deg .. yaw_deg), the
/// state file's (sd_n_m .. sd_saz_ppm) and `in_outage` (bool).
fn epoch_columns<'py>(py: Python<'py>, epochs: &[SolutionEpoch]) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let times = || epochs.iter().map(|e| e.estimate.nav.time);
    out.set_item("t_ns", array(py, times().map(|t| t.as_nanos()).collect()))?;
    out.set_item("t_s", array(py, times().map(|t| t.as_seconds()).collect()))?;
    let points: Vec<[f64; 9]> = (epochs.iter())
        .map(|e| trajectory_values(&TrajectoryPoint::from_nav_state(&e.estimate.nav)))
        .collect();
    for (k, name) in trajectory_column_names().into_iter().enumerate() {
        out.set_item(name, array(py, points.iter().map(|p| p[k]).collect()))?;
    }
    let states: Vec<Vec<f64>> = epochs.iter().map(|e| state_values(e).collect()).collect();
    for (k, name) in state_column_names().enumerate() {
        out.set_item(name, array(py, states.iter().map(|s| s[k]).collect()))?;
    }
    let in_outage: Vec<bool> = epochs.iter().map(|e| e.in_outage).collect();
    out.set_item("in_outage", array(py, in_outage))?;
    Ok(out)
}

/// The run's report (keys of `integrate --json`), the solution columns and, when smoothed,
/// the smoothed solution's.
fn integrate_result<'py>(
    py: Python<'py>,
    report: &RunReport,
    solution: &thermonav::nav::solution::Solution,
    notes: Vec<String>,
) -> PyResult<Bound<'py, PyAny>> {
    let out = to_python(py, report)?;
    out.set_item("solution", epoch_columns(py, &solution.epochs)?)?;
    let smoothed = match solution.smoothed.is_empty() {
        true => None,
        false => Some(epoch_columns(py, &solution.smoothed)?),
    };
    out.set_item("smoothed", smoothed)?;
    out.set_item("notes", notes)?;
    Ok(out)
}

/// The GNSS/INS filter on an IMU and a GNSS file (module docs of the Python package:
/// `thermonav.integrate`). A keyword left at `None` takes the library's default.
#[pyfunction]
#[allow(clippy::too_many_arguments)] // Python keyword arguments, one per CLI option
#[pyo3(signature = (imu, gnss, bank=None, profile=None, *, model_temperature_c=None, operating_temperature_c=None, select=None, model=None, filter=EngineSettings::default().filter.name(), outages=None, lever_arm_m=None, baseline=None, initial_from=None, covariance_rate_hz=None, output_rate_hz=None, velocity_sd_m_s=None, gate_probability=None, gate_window=None, max_imu_gap_s=None, process_noise_scale=None, bias_hypotheses=None, velocity=None, heading=None, schedule=true, compensation=true, smooth=false))]
pub fn integrate<'py>(
    py: Python<'py>,
    imu: PathBuf,
    gnss: PathBuf,
    bank: Option<PathBuf>,
    profile: Option<PathBuf>,
    model_temperature_c: Option<f64>,
    operating_temperature_c: Option<f64>,
    select: Option<&str>,
    model: Option<String>,
    filter: &str,
    outages: Option<&str>,
    lever_arm_m: Option<[f64; 3]>,
    baseline: Option<[f64; 3]>,
    initial_from: Option<PathBuf>,
    covariance_rate_hz: Option<f64>,
    output_rate_hz: Option<f64>,
    velocity_sd_m_s: Option<Vec<f64>>,
    gate_probability: Option<f64>,
    gate_window: Option<usize>,
    max_imu_gap_s: Option<f64>,
    process_noise_scale: Option<f64>,
    bias_hypotheses: Option<usize>,
    velocity: Option<bool>,
    heading: Option<bool>,
    schedule: bool,
    compensation: bool,
    smooth: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let [filter] = filters_of(filter)?[..] else {
        return Err(error("filter: expected \"ekf\" or \"ukf\""));
    };
    let options = RunKeywords {
        model,
        process_noise_scale,
        velocity_sd_m_s,
        velocity,
        heading,
        gate_probability,
        gate_window,
        lever_arm_m,
        baseline,
        covariance_rate_hz,
        max_imu_gap_s,
        bias_hypotheses,
    }
    .options()?;
    let temperature = temperature_of(model_temperature_c, operating_temperature_c, select)?;
    let settings = RunSettings::of_options(
        &options,
        temperature,
        (Scheduling::when(schedule), Compensation::when(compensation)),
        integrate_engine(&options, filter, output_rate_hz, smooth)?,
        outages_of(outages, OutageSpec::None)?,
    );
    let files = Files {
        imu,
        gnss,
        noise: (bank, profile),
    };
    let (report, solution, notes) =
        py.detach(|| run_files(&files, initial_from.as_deref(), &settings))?;
    let out = integrate_result(py, &report, &solution, notes)?;
    out.set_item("run_options", to_python(py, &options)?)?;
    Ok(out)
}

type RunResult = (RunReport, thermonav::nav::solution::Solution, Vec<String>);

/// Reads the files and runs the filter (without the GIL).
fn run_files(
    files: &Files,
    initial_from: Option<&Path>,
    settings: &RunSettings,
) -> PyResult<RunResult> {
    let records = files.read()?;
    let reference = (initial_from.map(|p| read_trajectory_file(p, Strictness::Strict)))
        .transpose()
        .map_err(error)?;
    let start = reference.as_deref().map_or(Start::Align, Start::Reference);
    let refused = |e: RunError| {
        refusal(
            e.to_string(),
            e.input(),
            files.prefix(e.input(), &records, initial_from),
        )
    };
    let noise = records.noise.model();
    let prepared = prepare(
        records.series.clone(),
        records.gnss.clone(),
        noise,
        start,
        settings,
    )
    .map_err(refused)?;
    let imu_name = files.imu.display();
    let notes = prepared
        .notes
        .iter()
        .map(|n| format!("{imu_name} {n}"))
        .collect();
    let outcome = prepared.run(&mut |_| {}).map_err(refused)?;
    Ok((RunReport::of(&outcome), outcome.solution, notes))
}

/// A model's per-epoch errors inside the outages as columns: `outage` (1, 2, ...) and those
/// of the CLI's error CSVs (t_s, since_outage_start_s, north_m, east_m, horizontal_m,
/// heading_deg).
fn error_columns<'py>(py: Python<'py>, errors: &[Vec<EpochError>]) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let outage: Vec<u32> = (errors.iter().enumerate())
        .flat_map(|(k, e)| std::iter::repeat_n(k as u32 + 1, e.len()))
        .collect();
    out.set_item("outage", array(py, outage))?;
    let rows: Vec<Vec<f64>> = errors.iter().flatten().map(EpochError::values).collect();
    // Without heading errors (a position-only reference) the rows are one shorter.
    let columns = rows.first().map_or(EpochError::COLUMNS.len(), Vec::len);
    for (k, name) in EpochError::COLUMNS[..columns].iter().enumerate() {
        let column: Vec<f64> = rows.iter().filter_map(|r| r.get(k).copied()).collect();
        out.set_item(*name, array(py, column))?;
    }
    Ok(out)
}

/// The report (keys of `evaluation.json`), every model with its error columns (None for a
/// failed run).
fn evaluate_result<'py>(
    py: Python<'py>,
    outcome: &TournamentOutcome,
) -> PyResult<Bound<'py, PyAny>> {
    let out = to_python(py, &outcome.report)?;
    let models = out.get_item("models")?;
    for (k, result) in outcome.main.iter().enumerate() {
        let errors = match &result.outcome {
            Ok(evaluated) => Some(error_columns(py, &evaluated.errors)?),
            Err(_) => None,
        };
        models.get_item(k)?.set_item("errors", errors)?;
    }
    Ok(out)
}

/// The tournament's options besides the files.
struct TournamentKeywords {
    temperature: ModelTemperature,
    options: RunOptions,
    filters: Vec<FilterKind>,
    outages: OutageSpec,
    extra_replicates: usize,
    seed: u64,
    scheduling: Scheduling,
    compensation: Compensation,
}

/// The temperature-model tournament on one data set (module docs of the Python package:
/// `thermonav.evaluate`): every candidate runs with `integrate`'s run keywords. A keyword left
/// at `None` takes the library's default.
#[pyfunction]
#[allow(clippy::too_many_arguments)] // Python keyword arguments, one per CLI option
#[pyo3(signature = (imu, gnss, reference, bank=None, profile=None, *, model_temperature_c=None, operating_temperature_c=None, model=None, filter="both", outages=None, monte_carlo=DEFAULT_MONTE_CARLO, seed=DEFAULT_SEED, lever_arm_m=None, baseline=None, initial_from=None, covariance_rate_hz=None, velocity_sd_m_s=None, gate_probability=None, gate_window=None, max_imu_gap_s=None, process_noise_scale=None, bias_hypotheses=None, velocity=None, heading=None, schedule=true, compensation=true, datasheet=None, truth=None))]
pub fn evaluate<'py>(
    py: Python<'py>,
    imu: PathBuf,
    gnss: PathBuf,
    reference: PathBuf,
    bank: Option<PathBuf>,
    profile: Option<PathBuf>,
    model_temperature_c: Option<f64>,
    operating_temperature_c: Option<f64>,
    model: Option<String>,
    filter: &str,
    outages: Option<&str>,
    monte_carlo: usize,
    seed: u64,
    lever_arm_m: Option<[f64; 3]>,
    baseline: Option<[f64; 3]>,
    initial_from: Option<PathBuf>,
    covariance_rate_hz: Option<f64>,
    velocity_sd_m_s: Option<Vec<f64>>,
    gate_probability: Option<f64>,
    gate_window: Option<usize>,
    max_imu_gap_s: Option<f64>,
    process_noise_scale: Option<f64>,
    bias_hypotheses: Option<usize>,
    velocity: Option<bool>,
    heading: Option<bool>,
    schedule: bool,
    compensation: bool,
    datasheet: Option<PathBuf>,
    truth: Option<PathBuf>,
) -> PyResult<Bound<'py, PyAny>> {
    if monte_carlo == 0 {
        return Err(error("monte_carlo must be at least 1"));
    }
    let options = RunKeywords {
        model,
        process_noise_scale,
        velocity_sd_m_s,
        velocity,
        heading,
        gate_probability,
        gate_window,
        lever_arm_m,
        baseline,
        covariance_rate_hz,
        max_imu_gap_s,
        bias_hypotheses,
    }
    .options()?;
    let keywords = TournamentKeywords {
        temperature: temperature_of(model_temperature_c, operating_temperature_c, None)?,
        options,
        filters: filters_of(filter)?,
        outages: outages_of(outages, DEFAULT_OUTAGES)?,
        extra_replicates: monte_carlo - 1,
        seed,
        scheduling: Scheduling::when(schedule),
        compensation: Compensation::when(compensation),
    };
    let files = Files {
        imu,
        gnss,
        noise: (bank, profile),
    };
    let extra = (reference, initial_from, datasheet, truth);
    let outcome = py.detach(|| tournament_of_files(&files, extra, &keywords))?;
    let out = evaluate_result(py, &outcome)?;
    out.set_item("run_options", to_python(py, &keywords.options)?)?;
    Ok(out)
}

/// The tournament's files beside the records: reference, initial_from, datasheet, truth.
type TournamentFiles = (PathBuf, Option<PathBuf>, Option<PathBuf>, Option<PathBuf>);

/// Reads the files, makes the scenario and runs the tournament (without the GIL).
fn tournament_of_files(
    files: &Files,
    (reference, initial_from, datasheet, truth): TournamentFiles,
    k: &TournamentKeywords,
) -> PyResult<TournamentOutcome> {
    let scale = ScaleFactorPrior::default();
    let truth: Option<TrueModel> = (truth.map(|p| thermonav_io::truth::read_truth_file(p, &scale)))
        .transpose()
        .map_err(error)?;
    let records = files.read()?;
    let points = read_trajectory_file(&reference, Strictness::Strict).map_err(error)?;
    let operating_c = operating_temperature_c(k.temperature.given_c(), &records.series)
        .map_err(|e| error(format!("{}: {e}", files.imu.display())))?;
    let start = (initial_from.as_deref())
        .map(|p| read_trajectory_file(p, Strictness::Strict))
        .transpose()
        .map_err(error)?;
    let plan = RecordPlan {
        oracle: truth.as_ref(),
        ..RecordPlan::calibrated(records.noise.model().thermal(), k.compensation)
    };
    let refused = |e: ScenarioError| {
        let prefix = files.prefix(e.input(), &records, Some(&reference));
        refusal(e.to_string(), e.input(), prefix)
    };
    let main = scenario_of_records(
        &records.series,
        records.gnss.clone(),
        points,
        (&k.options.engine(EngineSettings::default()), &k.outages),
        plan,
    )
    .map_err(refused)?;
    let main = match &start {
        Some(points) => main.started(Start::Reference(points)).map_err(|e| {
            let prefix = files.prefix(e.input(), &records, initial_from.as_deref());
            refusal(e.to_string(), e.input(), prefix)
        })?,
        None => main,
    };
    let profile = datasheet.as_deref().map(read_profile).transpose()?;
    let named = |e| {
        error(format!(
            "{}: {e}",
            datasheet.as_deref().unwrap_or(Path::new("")).display()
        ))
    };
    let plan = TournamentPlan {
        noise: records.noise.source(),
        thermal: ThermalOptions::of_scenario(&main, k.scheduling, k.compensation),
        operating_temperature_c: operating_c,
        source: k.options.gauss_markov,
        filters: k.filters.clone(),
        datasheet: Some(datasheet_model(profile.as_ref(), &scale).map_err(named)?),
        scale,
        oracle: truth.as_ref(),
    };
    let tournament = Tournament::new(&plan)
        .map_err(error)?
        .with_process_noise_scale(k.options.process_noise_scale);
    let replicates = Replicates::ShiftedOutages {
        extra: k.extra_replicates,
        seed: k.seed,
    };
    tournament.run(&main, &replicates, &|| {}).map_err(error)
}
