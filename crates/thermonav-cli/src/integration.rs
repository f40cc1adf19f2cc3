//! One `integrate` run from its settings: the 21-state GNSS/INS filter on an IMU and a GNSS
//! file with the bank's (or a profile's) noise model at the chosen temperature; writes the
//! solution trajectory, its state and innovation files, and returns the summary. Shared by
//! `integrate` and `demo`.

use crate::campaign::load_profile;
use crate::failure::{Classify, Failure};
use crate::inputs::read_bank;
use crate::settings::navigation::{
    IntegrateSettings, ModelTemperature, NoiseSource, SolutionFiles,
};
use anyhow::anyhow;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;
use thermonav::evaluation::experiment::CandidateSource;
use thermonav::gnss::GnssFix;
use thermonav::imu::{Channel, ImuSeries};
use thermonav::ins::state::Increment;
use thermonav::nav::alignment::{HeadingSource, InitialUncertainty, align_from_gnss, uncorrected};
use thermonav::nav::engine::{
    EngineSettings, FilterKind, NavError, increments_from_series, run_scheduled,
};
use thermonav::nav::error_state::Estimate;
use thermonav::nav::measurement::MeasurementKind;
use thermonav::nav::outage::{Outage, OutageSpec, Outages};
use thermonav::nav::schedule::{
    CompensationOutcome, ModelGrid, ModelSchedule, ScheduleSummary, Scheduling, TemperatureTrack,
    compensate_record,
};
use thermonav::nav::sensor_model::{
    BankChoice, ImuStochasticModel, ScaleFactorPrior, SensorModelError,
};
use thermonav::nav::solution::{InnovationStatistics, Solution, SolutionEpoch};
use thermonav::sensor::SensorProfile;
use thermonav::stoch::bank::ModelBank;
use thermonav::stoch::bank::{GaussMarkovSource, Selection};
use thermonav::stoch::thermal::ThermalCalibration;
use thermonav::time::Timestamp;
use thermonav::trajectory::TrajectoryPoint;
use thermonav::units::{STANDARD_GRAVITY_M_S2, rad_per_s_to_deg_per_h};
use thermonav_io::solution::{write_innovations_file, write_solution_states_file};
use thermonav_io::{
    Strictness, read_gnss_file, read_imu_file, read_trajectory_file, write_trajectory_file,
};

/// The data of a run, read.
struct Inputs {
    increments: Vec<Increment>,
    gnss: Vec<GnssFix>,
    span: (Timestamp, Timestamp),
}

/// Runs the filter on the files of `settings`, writes the outputs and returns the summary.
pub fn integrate(settings: &IntegrateSettings) -> Result<Summary, Failure> {
    let mut series = read_imu_file(&settings.imu, Strictness::Strict).data()?;
    let gnss = read_gnss_file(&settings.gnss, Strictness::Strict).data()?;
    let noise = load_noise(&settings.noise)?;
    let models = RunModels::of(settings, &noise, &series)?;
    let compensation = compensate_record(&mut series, noise.thermal(), settings.compensation);
    let (increments, first, last) = increments_with_span(&series, &settings.imu)?;
    let inputs = Inputs {
        increments,
        gnss,
        span: (first, last),
    };
    let engine = EngineSettings {
        outages: outages_in(&settings.outages, inputs.span.0, inputs.span.1)?,
        ..settings.engine.clone()
    };
    let (initial, initial_source) = initial_estimate(settings, &inputs, &engine)?;
    let started = Instant::now();
    let solution = run_with_progress(&inputs, initial, models.schedule(), &engine)
        .map_err(|e| nav_failure(e, &settings.imu, &settings.gnss))?;
    let processing_s = started.elapsed().as_secs_f64();
    write_outputs(&settings.outputs, &solution)?;
    let run = Run {
        models: &models,
        compensation,
        engine: &engine,
        solution: &solution,
        initial: initial_source,
        processing_s,
    };
    Ok(summarize(settings, &run))
}

fn run_with_progress(
    inputs: &Inputs,
    initial: Estimate,
    schedule: ModelSchedule,
    engine: &EngineSettings,
) -> Result<Solution, NavError> {
    let label = format!("integrating ({})", engine.filter.name());
    let bar = crate::progress::bar(inputs.increments.len(), &label);
    let solution = run_scheduled(
        &inputs.increments,
        &inputs.gnss,
        initial,
        InitialUncertainty::default().covariance(),
        schedule,
        engine,
        &mut |n| bar.set_position(n as u64),
    )?;
    bar.finish_and_clear();
    Ok(solution)
}

/// A failed run as bad data, naming the file that a refusal of its data is about.
pub fn nav_failure(error: NavError, imu: &Path, gnss: &Path) -> Failure {
    let file = match error {
        NavError::ImuGap { .. } => Some(imu),
        NavError::PolarFix { .. } => Some(gnss),
        _ => None,
    };
    let named = file
        .map(|f| format!("{}: ", f.display()))
        .unwrap_or_default();
    Failure::Data(anyhow!("{named}{error}"))
}

/// The noise model's source, read.
pub enum LoadedNoise {
    /// A bank.
    Bank(ModelBank),
    /// A sensor profile.
    Profile(SensorProfile),
}

/// Reads the bank or the profile.
pub fn load_noise(noise: &NoiseSource) -> Result<LoadedNoise, Failure> {
    match noise {
        NoiseSource::Bank(path) => Ok(LoadedNoise::Bank(read_bank(path)?)),
        NoiseSource::Profile(path) => Ok(LoadedNoise::Profile(load_profile(Some(path))?)),
    }
}

impl LoadedNoise {
    /// Where a tournament's candidates come from.
    pub fn source(&self) -> CandidateSource<'_> {
        match self {
            LoadedNoise::Bank(bank) => CandidateSource::Bank(bank),
            LoadedNoise::Profile(profile) => CandidateSource::Profile(profile),
        }
    }

    /// The bank's thermal calibration, if any.
    pub fn thermal(&self) -> Option<&ThermalCalibration> {
        match self {
            LoadedNoise::Bank(bank) => bank.thermal.as_ref(),
            LoadedNoise::Profile(_) => None,
        }
    }
}

/// The models of a run: the fixed one (reported; used unless scheduled) and, when
/// scheduled, the temperature track with the models by temperature.
struct RunModels {
    model: ImuStochasticModel,
    choice: BankChoice,
    scheduled: Option<(TemperatureTrack, ModelGrid)>,
}

impl RunModels {
    fn of(
        settings: &IntegrateSettings,
        noise: &LoadedNoise,
        series: &ImuSeries,
    ) -> Result<Self, Failure> {
        let (mut model, choice) = noise_model(settings, noise, series)?;
        model.scale_white_noise(settings.process_noise_scale);
        let scheduled = match schedule_track(settings, series)? {
            Some(track) => Some(scheduled_models(settings, noise, track)?),
            None => None,
        };
        Ok(Self {
            model,
            choice,
            scheduled,
        })
    }

    fn schedule(&self) -> ModelSchedule<'_> {
        match &self.scheduled {
            Some((track, grid)) => ModelSchedule::ByTemperature { track, grid },
            None => ModelSchedule::Fixed(&self.model),
        }
    }

    fn summary(&self) -> ScheduleSummary {
        match &self.scheduled {
            Some((track, grid)) => ScheduleSummary::scheduled(track, grid),
            None => ScheduleSummary::Fixed {
                temperature_c: self.choice.temperature_c,
            },
        }
    }
}

/// The IMU's temperature track when the run is scheduled; `None` when fixed, or (with a
/// note on stderr) when the file has no temp_c.
fn schedule_track(
    settings: &IntegrateSettings,
    series: &ImuSeries,
) -> Result<Option<TemperatureTrack>, Failure> {
    if settings.scheduling == Scheduling::Fixed {
        return Ok(None);
    }
    let imu = settings.imu.display();
    let track = TemperatureTrack::of_series(series)
        .map_err(|e| anyhow!("{imu}: {e}"))
        .data()?;
    if track.is_none() {
        eprintln!("note: {imu} has no temp_c column: one model for the whole run");
    }
    Ok(track)
}

/// The track with the models by temperature over its range (white noise scaled).
fn scheduled_models(
    settings: &IntegrateSettings,
    noise: &LoadedNoise,
    track: TemperatureTrack,
) -> Result<(TemperatureTrack, ModelGrid), Failure> {
    let (scale, range_c) = (ScaleFactorPrior::default(), track.range_c());
    let grid = match noise {
        LoadedNoise::Bank(bank) => {
            let selection = settings.temperature.selection();
            ModelGrid::from_bank(bank, selection, settings.gauss_markov, &scale, range_c)
        }
        LoadedNoise::Profile(profile) => ModelGrid::from_profile(profile, &scale, range_c),
    };
    let mut grid = grid
        .map_err(|e| anyhow!("{}: {e}", settings.noise.path().display()))
        .data()?;
    grid.scale_white_noise(settings.process_noise_scale);
    Ok((track, grid))
}

/// The IMU increments of a series and the span they cover, refusing a series too short to
/// have one.
pub fn increments_with_span(
    series: &ImuSeries,
    path: &Path,
) -> Result<(Vec<Increment>, Timestamp, Timestamp), Failure> {
    let increments = increments_from_series(series);
    match (increments.first(), increments.last()) {
        (Some(first), Some(last)) => {
            let (first, last) = (first.time, last.time);
            Ok((increments, first, last))
        }
        _ => Err(Failure::Data(anyhow!(
            "{}: at least two IMU samples are needed",
            path.display()
        ))),
    }
}

/// The outages of a specification over the data span, each inside the data.
pub fn outages_in(
    spec: &OutageSpec,
    first: Timestamp,
    last: Timestamp,
) -> Result<Outages, Failure> {
    spec.resolve((first, last))
        .map_err(|e| anyhow!("--outages: {e}"))
        .usage()
}

/// The filter's fixed noise model: from the bank at the chosen temperature, or from the
/// profile.
fn noise_model(
    settings: &IntegrateSettings,
    noise: &LoadedNoise,
    series: &ImuSeries,
) -> Result<(ImuStochasticModel, BankChoice), Failure> {
    let (model, choice) = match noise {
        LoadedNoise::Profile(profile) => profile_model(settings, profile, series),
        LoadedNoise::Bank(bank) => bank_model(settings, bank, series)?,
    };
    let path = settings.noise.path().display();
    Ok((model.map_err(|e| anyhow!("{path}: {e}")).data()?, choice))
}

type ModelResult = Result<ImuStochasticModel, SensorModelError>;

fn profile_model(
    settings: &IntegrateSettings,
    profile: &SensorProfile,
    series: &ImuSeries,
) -> (ModelResult, BankChoice) {
    let temperature_c = match settings.temperature {
        ModelTemperature::Fixed(t) => Some(t),
        ModelTemperature::Operating { given_c, .. } => given_c,
    }
    .or_else(|| series.mean_temperature_c())
    .unwrap_or(profile.reference_temperature_c);
    let model = profile.stochastic_model(temperature_c, &ScaleFactorPrior::default());
    let choice = BankChoice {
        temperature_c,
        selection: Selection::Nearest,
        source: settings.gauss_markov,
    };
    (model, choice)
}

fn bank_model(
    settings: &IntegrateSettings,
    bank: &ModelBank,
    series: &ImuSeries,
) -> Result<(ModelResult, BankChoice), Failure> {
    let choice = bank_choice(settings, series)?;
    let model = ImuStochasticModel::from_bank(bank, &choice, &ScaleFactorPrior::default());
    Ok((model, choice))
}

/// The temperature and rule of the settings, with the IMU file's mean temp_c for an
/// operating temperature not given.
fn bank_choice(settings: &IntegrateSettings, series: &ImuSeries) -> Result<BankChoice, Failure> {
    let (temperature_c, selection) = match settings.temperature {
        ModelTemperature::Fixed(t) => (t, Selection::Nearest),
        ModelTemperature::Operating { given_c, selection } => (
            operating_temperature(given_c, series, &settings.imu)?,
            selection,
        ),
    };
    Ok(BankChoice {
        temperature_c,
        selection,
        source: settings.gauss_markov,
    })
}

/// The operating temperature: given, or the mean of the IMU file's temp_c column.
pub fn operating_temperature(
    given: Option<f64>,
    series: &ImuSeries,
    imu: &Path,
) -> Result<f64, Failure> {
    given.or_else(|| series.mean_temperature_c()).ok_or_else(|| {
        Failure::Usage(anyhow!(
            "{}: no temp_c column; give the temperature (--model-temperature-c or --operating-temperature-c)",
            imu.display()
        ))
    })
}

/// Where the initial state came from.
#[derive(Debug, Clone, Copy, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum InitialSource {
    /// The reference trajectory (`--initial-from`).
    Reference,
    /// Alignment with a dual-antenna heading.
    DualAntennaHeading,
    /// Alignment with the course over ground.
    CourseOverGround,
}

fn initial_estimate(
    settings: &IntegrateSettings,
    inputs: &Inputs,
    engine: &EngineSettings,
) -> Result<(Estimate, InitialSource), Failure> {
    if let Some(path) = &settings.initial_from {
        return reference_start(path, inputs);
    }
    let alignment = align_from_gnss(&inputs.increments, &inputs.gnss, &engine.geometry, 1.0)
        .map_err(|e| anyhow!("{}: {e}", settings.gnss.display()))
        .data()?;
    let source = match alignment.heading_source {
        HeadingSource::DualAntenna => InitialSource::DualAntennaHeading,
        HeadingSource::Course => InitialSource::CourseOverGround,
    };
    Ok((uncorrected(alignment.nav), source))
}

/// The reference point at (or last before) the first fix, or its first point.
fn reference_start(path: &Path, inputs: &Inputs) -> Result<(Estimate, InitialSource), Failure> {
    let points = read_trajectory_file(path, Strictness::Strict).data()?;
    let start = inputs.gnss.first().map_or(inputs.span.0, |f| f.time);
    let point = points
        .iter()
        .rev()
        .find(|p| p.time <= start)
        .or(points.first())
        .ok_or_else(|| Failure::Data(anyhow!("{}: no trajectory point", path.display())))?;
    Ok((uncorrected(point.nav_state()), InitialSource::Reference))
}

fn write_outputs(files: &SolutionFiles, solution: &Solution) -> Result<(), Failure> {
    write_epochs(&files.solution, &files.states, &solution.epochs)?;
    if let Some([trajectory, states]) = &files.smoothed {
        write_epochs(trajectory, states, &solution.smoothed)?;
    }
    write_innovations_file(&files.innovations, &solution.innovations).data()
}

/// A solution's trajectory CSV and its state file.
fn write_epochs(trajectory: &Path, states: &Path, epochs: &[SolutionEpoch]) -> Result<(), Failure> {
    let points: Vec<TrajectoryPoint> = epochs
        .iter()
        .map(|e| TrajectoryPoint::from_nav_state(&e.estimate.nav))
        .collect();
    write_trajectory_file(trajectory, &points).data()?;
    write_solution_states_file(states, epochs).data()
}

/// One channel of the model the filter used.
#[derive(Debug, Serialize)]
pub struct ChannelModelJson {
    channel: &'static str,
    unit: &'static str,
    bias_correlation_time_s: f64,
    bias_sigma: f64,
    white_noise_density: f64,
    white_noise_density_unit: &'static str,
}

/// The model the filter used.
#[derive(Debug, Serialize)]
pub struct ModelJson {
    /// Gauss-Markov family.
    pub gauss_markov_source: GaussMarkovSource,
    /// Selection rule.
    pub selection: Selection,
    /// The model's temperature, °C.
    pub temperature_c: f64,
    channels: Vec<ChannelModelJson>,
}

/// Innovation statistics of one measurement kind.
#[derive(Debug, Serialize)]
pub struct InnovationJson {
    /// Measurement kind.
    pub kind: MeasurementKind,
    /// Its dimension (the expected mean NIS).
    pub dimension: usize,
    /// Updates offered.
    pub offered: usize,
    /// Updates rejected by the gate.
    pub rejected: usize,
    /// Updates forced in after a run of rejections.
    pub forced: usize,
    /// Mean normalised innovation squared.
    pub mean_nis: f64,
    /// Share of NIS inside the 95 % band.
    pub fraction_nis_in_95: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    rms_innovation_ned_m: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rms_innovation_ned_m_s: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rms_innovation_deg: Option<f64>,
}

impl From<&InnovationStatistics> for InnovationJson {
    fn from(s: &InnovationStatistics) -> Self {
        let rms = s.rms_innovation;
        Self {
            kind: s.kind,
            dimension: s.dimension,
            offered: s.offered,
            rejected: s.rejected,
            forced: s.forced,
            mean_nis: s.mean_nis,
            fraction_nis_in_95: s.fraction_nis_in_95,
            rms_innovation_ned_m: (s.kind == MeasurementKind::Position).then_some(rms),
            rms_innovation_ned_m_s: (s.kind == MeasurementKind::Velocity).then_some(rms),
            rms_innovation_deg: (s.kind == MeasurementKind::Heading).then_some(rms[0].to_degrees()),
        }
    }
}

/// The last epoch's uncertainty and sensor estimates.
#[derive(Debug, Serialize)]
pub struct FinalJson {
    time_s: f64,
    /// Position sd, NED, m.
    pub sd_position_ned_m: [f64; 3],
    sd_velocity_ned_m_s: [f64; 3],
    /// Attitude sd, NED, deg.
    pub sd_attitude_ned_deg: [f64; 3],
    /// Gyro biases, deg/h.
    pub gyro_bias_deg_h: [f64; 3],
    /// Accelerometer biases, mg.
    pub accel_bias_mg: [f64; 3],
    gyro_scale_factor_ppm: [f64; 3],
    accel_scale_factor_ppm: [f64; 3],
}

/// An outage window, s.
#[derive(Debug, Serialize)]
pub struct OutageJson {
    start_s: f64,
    end_s: f64,
}

impl From<&Outage> for OutageJson {
    fn from(o: &Outage) -> Self {
        Self {
            start_s: o.start.as_seconds(),
            end_s: o.end.as_seconds(),
        }
    }
}

/// What `integrate` reports.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// The filter.
    pub filter: FilterKind,
    imu: PathBuf,
    gnss: PathBuf,
    bank: Option<PathBuf>,
    profile: Option<PathBuf>,
    /// The model used (when scheduled: the model at the mean or given temperature, for
    /// reference).
    pub model: ModelJson,
    /// One model or the model at the IMU's temperature at every covariance step.
    pub schedule: ScheduleSummary,
    /// Whether the bank's bias(T) was subtracted from the samples.
    pub compensation: CompensationOutcome,
    /// Where the initial state came from.
    pub initial: InitialSource,
    covariance_rate_hz: f64,
    output_rate_hz: f64,
    /// The outages.
    pub outages: Vec<OutageJson>,
    /// IMU samples processed.
    pub imu_samples: usize,
    /// Span of the solution, s.
    pub duration_s: f64,
    /// Wall time of the filter, s.
    pub processing_time_s: f64,
    /// Data time over wall time.
    pub real_time_factor: f64,
    /// Innovation statistics per kind.
    pub innovations: Vec<InnovationJson>,
    /// The last epoch.
    #[serde(rename = "final")]
    pub last: Option<FinalJson>,
    /// The files written.
    pub files: SolutionFiles,
}

/// What one filter run gave, for its summary.
struct Run<'a> {
    models: &'a RunModels,
    compensation: CompensationOutcome,
    engine: &'a EngineSettings,
    solution: &'a Solution,
    initial: InitialSource,
    processing_s: f64,
}

fn summarize(settings: &IntegrateSettings, run: &Run) -> Summary {
    let (bank, profile) = match &settings.noise {
        NoiseSource::Bank(p) => (Some(p.clone()), None),
        NoiseSource::Profile(p) => (None, Some(p.clone())),
    };
    let duration_s = solution_span_s(run.solution);
    Summary {
        filter: run.engine.filter,
        imu: settings.imu.clone(),
        gnss: settings.gnss.clone(),
        bank,
        profile,
        model: model_json(&run.models.choice, &run.models.model),
        schedule: run.models.summary(),
        compensation: run.compensation.clone(),
        initial: run.initial,
        covariance_rate_hz: 1.0 / run.engine.covariance_interval_s,
        output_rate_hz: 1.0 / run.engine.output_interval_s,
        outages: run
            .engine
            .outages
            .windows()
            .iter()
            .map(OutageJson::from)
            .collect(),
        imu_samples: run.solution.imu_samples,
        duration_s,
        processing_time_s: run.processing_s,
        real_time_factor: real_time_factor(duration_s, run.processing_s),
        innovations: innovation_rows(run.solution),
        last: run.solution.epochs.last().map(final_json),
        files: settings.outputs.clone(),
    }
}

fn solution_span_s(solution: &Solution) -> f64 {
    match (solution.epochs.first(), solution.epochs.last()) {
        (Some(a), Some(b)) => b.estimate.nav.time.since(a.estimate.nav.time).as_seconds(),
        _ => 0.0,
    }
}

fn real_time_factor(duration_s: f64, processing_s: f64) -> f64 {
    if processing_s > 0.0 {
        duration_s / processing_s
    } else {
        0.0
    }
}

fn innovation_rows(solution: &Solution) -> Vec<InnovationJson> {
    let statistics = solution.innovation_statistics();
    statistics.iter().map(InnovationJson::from).collect()
}

fn model_json(choice: &BankChoice, model: &ImuStochasticModel) -> ModelJson {
    let channels = Channel::ALL
        .iter()
        .zip(model.gyro.iter().chain(&model.accel))
        .map(|(c, axis)| {
            let gyro = c.index() < 3;
            ChannelModelJson {
                channel: c.name(),
                unit: if gyro { "rad/s" } else { "m/s^2" },
                bias_correlation_time_s: axis.bias.correlation_time_s,
                bias_sigma: axis.bias.sigma,
                white_noise_density: axis.white_noise_density,
                white_noise_density_unit: if gyro { "rad/s^0.5" } else { "m/s^1.5" },
            }
        })
        .collect();
    ModelJson {
        gauss_markov_source: choice.source,
        selection: choice.selection,
        temperature_c: choice.temperature_c,
        channels,
    }
}

fn final_json(e: &SolutionEpoch) -> FinalJson {
    let sd = |start: usize, factor: f64| std::array::from_fn(|k| e.sd[start + k] * factor);
    let s = &e.estimate.sensors;
    FinalJson {
        time_s: e.estimate.nav.time.as_seconds(),
        sd_position_ned_m: sd(0, 1.0),
        sd_velocity_ned_m_s: sd(3, 1.0),
        sd_attitude_ned_deg: sd(6, 1f64.to_degrees()),
        gyro_bias_deg_h: s.gyro_bias_rad_s.map(rad_per_s_to_deg_per_h),
        accel_bias_mg: s
            .accel_bias_m_s2
            .map(|a| a / STANDARD_GRAVITY_M_S2 * 1000.0),
        gyro_scale_factor_ppm: s.gyro_scale.map(|v| v * 1e6),
        accel_scale_factor_ppm: s.accel_scale.map(|v| v * 1e6),
    }
}
