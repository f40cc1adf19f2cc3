//! `thermonav integrate`: the 21-state GNSS/INS filter on an IMU and a GNSS file, with the
//! bank's noise model at a chosen temperature; writes the solution trajectory and its state
//! file, and reports the innovation statistics.

use super::bank::{read_bank, selection_of, source_of};
use crate::args::{FilterArg, IntegrateArgs};
use crate::failure::{Classify, Failure};
use crate::report::{print_json, print_rows};
use anyhow::anyhow;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;
use thermonav::gnss::GnssFix;
use thermonav::imu::{Channel, ImuSeries};
use thermonav::ins::state::Increment;
use thermonav::nav::alignment::{InitialUncertainty, align_from_gnss, uncorrected};
use thermonav::nav::engine::{
    Aiding, EngineSettings, FilterKind, increments_from_series, run as run_filter,
};
use thermonav::nav::error_state::Estimate;
use thermonav::nav::measurement::{AntennaGeometry, MeasurementKind};
use thermonav::nav::outage::{Outage, Outages};
use thermonav::nav::sensor_model::{BankChoice, ImuStochasticModel, ScaleFactorPrior};
use thermonav::nav::solution::{InnovationStatistics, Solution};
use thermonav::stoch::bank::GaussMarkovSource;
use thermonav::time::Timestamp;
use thermonav::trajectory::TrajectoryPoint;
use thermonav::units::{STANDARD_GRAVITY_M_S2, rad_per_s_to_deg_per_h};
use thermonav_io::profile::read_profile;
use thermonav_io::solution::{write_innovations_file, write_solution_states_file};
use thermonav_io::{
    Strictness, read_gnss_file, read_imu_file, read_trajectory_file, write_trajectory_file,
};

/// Runs `integrate`.
pub fn run(args: &IntegrateArgs) -> Result<(), Failure> {
    let summary = integrate_files(args)?;
    if args.json {
        return print_json(&summary);
    }
    print_summary(&summary);
    Ok(())
}

/// Runs the filter on the files of `args`, writes the outputs and returns the summary.
pub fn integrate_files(args: &IntegrateArgs) -> Result<Summary, Failure> {
    let mut settings = engine_settings(args)?;
    let series = read_imu_file(&args.imu, Strictness::Strict).data()?;
    let gnss = read_gnss_file(&args.gnss, Strictness::Strict).data()?;
    let (mut model, choice) = noise_model(args, &series)?;
    model.scale_white_noise(args.process_noise_scale);
    let (increments, first, last) = increments_with_span(&series, &args.imu)?;
    settings.outages = outages_in(&args.outages, first, last)?;
    let (initial, initial_source) = initial_estimate(args, &increments, &gnss, &settings)?;
    let bar = crate::progress::bar(
        increments.len(),
        &format!("integrating ({})", settings.filter.name()),
    );
    let started = Instant::now();
    let solution = run_filter(
        &increments,
        &gnss,
        initial,
        InitialUncertainty::default().covariance(),
        &model,
        &settings,
        &mut |n| bar.set_position(n as u64),
    )
    .map_err(|e| anyhow!("{e}"))
    .data()?;
    let processing_s = started.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let files = write_outputs(&args.out, &solution)?;
    let summary = summarize(
        args,
        &choice,
        &model,
        &settings,
        &solution,
        initial_source,
        processing_s,
        files,
    );
    Ok(summary)
}

fn engine_settings(args: &IntegrateArgs) -> Result<EngineSettings, Failure> {
    for (name, value) in [
        ("--covariance-rate-hz", args.covariance_rate_hz),
        ("--output-rate-hz", args.output_rate_hz),
        ("--velocity-sd-m-s", args.velocity_sd_m_s),
        ("--process-noise-scale", args.process_noise_scale),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return Err(Failure::Usage(anyhow!(
                "{name} {value} must be a positive number"
            )));
        }
    }
    Ok(EngineSettings {
        filter: match args.filter {
            FilterArg::Ekf => FilterKind::Ekf,
            FilterArg::Ukf => FilterKind::Ukf,
        },
        covariance_interval_s: 1.0 / args.covariance_rate_hz,
        gate_probability: gate_of(args.gate_probability)?,
        velocity_sd_m_s: [args.velocity_sd_m_s; 3],
        output_interval_s: 1.0 / args.output_rate_hz,
        geometry: antenna_geometry(&args.lever_arm_m, &args.baseline)?,
        aiding: Aiding {
            position: true,
            velocity: !args.no_velocity,
            heading: !args.no_heading,
        },
        ..EngineSettings::default()
    })
}

/// The gate from `--gate-probability`: `None` (accept all) at 1.
fn gate_of(probability: f64) -> Result<Option<f64>, Failure> {
    if probability == 1.0 {
        Ok(None)
    } else if probability > 0.0 && probability < 1.0 {
        Ok(Some(probability))
    } else {
        Err(Failure::Usage(anyhow!(
            "--gate-probability {probability} must be in (0, 1], 1 meaning no gate"
        )))
    }
}

/// The antenna set-up from `--lever-arm-m` and `--baseline`.
pub fn antenna_geometry(lever_arm_m: &[f64], baseline: &[f64]) -> Result<AntennaGeometry, Failure> {
    let triple = |name: &str, v: &[f64]| -> Result<[f64; 3], Failure> {
        match v {
            [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok([*x, *y, *z]),
            _ => Err(Failure::Usage(anyhow!("{name} takes three finite numbers"))),
        }
    };
    let baseline = triple("--baseline", baseline)?;
    if baseline[0].hypot(baseline[1]) == 0.0 {
        return Err(Failure::Usage(anyhow!(
            "--baseline must have a horizontal component to define a heading"
        )));
    }
    Ok(AntennaGeometry {
        lever_arm_body_m: triple("--lever-arm-m", lever_arm_m)?,
        baseline_body: baseline,
    })
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
pub fn outages_in(spec: &str, first: Timestamp, last: Timestamp) -> Result<Outages, Failure> {
    let outages = Outages::from_spec(spec, (first, last))
        .and_then(|o| o.check_within(first, last).map(|()| o))
        .map_err(|e| anyhow!("--outages: {e}"))
        .usage()?;
    Ok(outages)
}

/// The filter's noise model: from the bank at the chosen temperature, or from the profile.
fn noise_model(
    args: &IntegrateArgs,
    series: &ImuSeries,
) -> Result<(ImuStochasticModel, BankChoice), Failure> {
    let scale = ScaleFactorPrior::default();
    if let Some(path) = &args.profile {
        let profile = read_profile(path).data()?;
        let temperature_c = args
            .model_temperature_c
            .or(args.operating_temperature_c)
            .or_else(|| series.mean_temperature_c())
            .unwrap_or(profile.reference_temperature_c);
        let model = profile
            .stochastic_model(temperature_c, &scale)
            .map_err(|e| anyhow!("{}: {e}", path.display()))
            .data()?;
        let choice = BankChoice {
            temperature_c,
            selection: thermonav::stoch::bank::Selection::Nearest,
            source: source_of(args.model),
        };
        return Ok((model, choice));
    }
    let path = args
        .bank
        .as_ref()
        .ok_or_else(|| Failure::Usage(anyhow!("give --bank or --profile")))?;
    let bank = read_bank(path)?;
    let choice = bank_choice(args, series)?;
    let model = ImuStochasticModel::from_bank(&bank, &choice, &scale)
        .map_err(|e| anyhow!("{}: {e}", path.display()))
        .data()?;
    Ok((model, choice))
}

/// The temperature and rule from the arguments, or the IMU file's mean temp_c.
fn bank_choice(args: &IntegrateArgs, series: &ImuSeries) -> Result<BankChoice, Failure> {
    let source = source_of(args.model);
    if let Some(t) = args.model_temperature_c {
        return Ok(BankChoice {
            temperature_c: t,
            selection: thermonav::stoch::bank::Selection::Nearest,
            source,
        });
    }
    let temperature_c = operating_temperature(args.operating_temperature_c, series, &args.imu)?;
    Ok(BankChoice {
        temperature_c,
        selection: selection_of(args.select),
        source,
    })
}

/// The operating temperature: given, or the mean of the IMU file's temp_c column.
pub fn operating_temperature(
    given: Option<f64>,
    series: &ImuSeries,
    imu: &Path,
) -> Result<f64, Failure> {
    match (given, series.mean_temperature_c()) {
        (Some(t), _) if t.is_finite() => Ok(t),
        (Some(t), _) => Err(Failure::Usage(anyhow!(
            "temperature {t} °C is not a finite number"
        ))),
        (None, Some(mean)) => Ok(mean),
        (None, None) => Err(Failure::Usage(anyhow!(
            "{}: no temp_c column; give the temperature (--model-temperature-c or --operating-temperature-c)",
            imu.display()
        ))),
    }
}

/// Where the initial state came from.
#[derive(Debug, Clone, Copy, Serialize)]
#[serde(rename_all = "snake_case")]
enum InitialSource {
    Reference,
    DualAntennaHeading,
    CourseOverGround,
}

fn initial_estimate(
    args: &IntegrateArgs,
    increments: &[Increment],
    gnss: &[GnssFix],
    settings: &EngineSettings,
) -> Result<(Estimate, InitialSource), Failure> {
    if let Some(path) = &args.initial_from {
        let points = read_trajectory_file(path, Strictness::Strict).data()?;
        let start = gnss.first().map_or(increments[0].time, |f| f.time);
        let point = points
            .iter()
            .rev()
            .find(|p| p.time <= start)
            .or(points.first())
            .ok_or_else(|| Failure::Data(anyhow!("{}: no trajectory point", path.display())))?;
        return Ok((uncorrected(point.nav_state()), InitialSource::Reference));
    }
    let alignment = align_from_gnss(increments, gnss, &settings.geometry, 1.0)
        .map_err(|e| anyhow!("{}: {e}", args.gnss.display()))
        .data()?;
    let source = match alignment.heading_source {
        thermonav::nav::alignment::HeadingSource::DualAntenna => InitialSource::DualAntennaHeading,
        thermonav::nav::alignment::HeadingSource::Course => InitialSource::CourseOverGround,
    };
    Ok((uncorrected(alignment.nav), source))
}

#[derive(Debug, Serialize)]
struct Files {
    solution: PathBuf,
    states: PathBuf,
    innovations: PathBuf,
}

/// STEM.SUFFIX.csv beside the solution.
pub fn beside(out: &Path, suffix: &str) -> PathBuf {
    let stem = out
        .file_stem()
        .map_or_else(|| "solution".into(), |s| s.to_string_lossy().into_owned());
    out.with_file_name(format!("{stem}.{suffix}.csv"))
}

fn write_outputs(out: &Path, solution: &Solution) -> Result<Files, Failure> {
    let points: Vec<TrajectoryPoint> = solution
        .epochs
        .iter()
        .map(|e| TrajectoryPoint::from_nav_state(&e.estimate.nav))
        .collect();
    let states = beside(out, "states");
    let innovations = beside(out, "innovations");
    write_trajectory_file(out, &points).data()?;
    write_solution_states_file(&states, &solution.epochs).data()?;
    write_innovations_file(&innovations, &solution.innovations).data()?;
    Ok(Files {
        solution: out.to_path_buf(),
        states,
        innovations,
    })
}

#[derive(Debug, Serialize)]
struct ChannelModelJson {
    channel: &'static str,
    unit: &'static str,
    bias_correlation_time_s: f64,
    bias_sigma: f64,
    white_noise_density: f64,
    white_noise_density_unit: &'static str,
}

#[derive(Debug, Serialize)]
struct ModelJson {
    gauss_markov_source: GaussMarkovSource,
    selection: thermonav::stoch::bank::Selection,
    temperature_c: f64,
    channels: Vec<ChannelModelJson>,
}

#[derive(Debug, Serialize)]
struct InnovationJson {
    kind: MeasurementKind,
    dimension: usize,
    offered: usize,
    rejected: usize,
    forced: usize,
    mean_nis: f64,
    fraction_nis_in_95: f64,
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

#[derive(Debug, Serialize)]
struct FinalJson {
    time_s: f64,
    sd_position_ned_m: [f64; 3],
    sd_velocity_ned_m_s: [f64; 3],
    sd_attitude_ned_deg: [f64; 3],
    gyro_bias_deg_h: [f64; 3],
    accel_bias_mg: [f64; 3],
    gyro_scale_factor_ppm: [f64; 3],
    accel_scale_factor_ppm: [f64; 3],
}

#[derive(Debug, Serialize)]
struct OutageJson {
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
    filter: FilterKind,
    imu: PathBuf,
    gnss: PathBuf,
    bank: Option<PathBuf>,
    profile: Option<PathBuf>,
    model: ModelJson,
    initial: InitialSource,
    covariance_rate_hz: f64,
    output_rate_hz: f64,
    outages: Vec<OutageJson>,
    imu_samples: usize,
    duration_s: f64,
    processing_time_s: f64,
    real_time_factor: f64,
    innovations: Vec<InnovationJson>,
    #[serde(rename = "final")]
    last: Option<FinalJson>,
    files: Files,
}

#[allow(clippy::too_many_arguments)]
fn summarize(
    args: &IntegrateArgs,
    choice: &BankChoice,
    model: &ImuStochasticModel,
    settings: &EngineSettings,
    solution: &Solution,
    initial: InitialSource,
    processing_s: f64,
    files: Files,
) -> Summary {
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
    let duration_s = match (solution.epochs.first(), solution.epochs.last()) {
        (Some(a), Some(b)) => b.estimate.nav.time.since(a.estimate.nav.time).as_seconds(),
        _ => 0.0,
    };
    Summary {
        filter: settings.filter,
        imu: args.imu.clone(),
        gnss: args.gnss.clone(),
        bank: args.bank.clone(),
        profile: args.profile.clone(),
        model: ModelJson {
            gauss_markov_source: choice.source,
            selection: choice.selection,
            temperature_c: choice.temperature_c,
            channels,
        },
        initial,
        covariance_rate_hz: 1.0 / settings.covariance_interval_s,
        output_rate_hz: 1.0 / settings.output_interval_s,
        outages: settings
            .outages
            .windows()
            .iter()
            .map(OutageJson::from)
            .collect(),
        imu_samples: solution.imu_samples,
        duration_s,
        processing_time_s: processing_s,
        real_time_factor: if processing_s > 0.0 {
            duration_s / processing_s
        } else {
            0.0
        },
        innovations: solution
            .innovation_statistics()
            .iter()
            .map(InnovationJson::from)
            .collect(),
        last: solution.epochs.last().map(final_json),
        files,
    }
}

fn final_json(e: &thermonav::nav::solution::SolutionEpoch) -> FinalJson {
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

fn print_summary(s: &Summary) {
    let three = |v: [f64; 3], digits: usize| {
        format!("{:.digits$}, {:.digits$}, {:.digits$}", v[0], v[1], v[2])
    };
    let mut rows = vec![
        ("filter", s.filter.name().to_string()),
        (
            "model",
            format!(
                "{:?} at {:.1} °C ({:?})",
                s.model.gauss_markov_source, s.model.temperature_c, s.model.selection
            ),
        ),
        ("initial state", format!("{:?}", s.initial)),
        ("outages", s.outages.len().to_string()),
        ("IMU samples", s.imu_samples.to_string()),
        ("duration", format!("{:.1} s", s.duration_s)),
        (
            "processing",
            format!(
                "{:.2} s ({:.0}x real time)",
                s.processing_time_s, s.real_time_factor
            ),
        ),
    ];
    for i in &s.innovations {
        rows.push((
            i.kind.name(),
            format!(
                "{} updates, {} rejected ({} forced in after a run of rejections), mean NIS {:.2} (expected {}), {:.0} % inside the 95 % band",
                i.offered,
                i.rejected,
                i.forced,
                i.mean_nis,
                i.dimension,
                100.0 * i.fraction_nis_in_95
            ),
        ));
    }
    if let Some(f) = &s.last {
        rows.push((
            "final sd position N,E,D",
            format!("{} m", three(f.sd_position_ned_m, 3)),
        ));
        rows.push((
            "final sd attitude N,E,D",
            format!("{} deg", three(f.sd_attitude_ned_deg, 3)),
        ));
        rows.push((
            "gyro bias x,y,z",
            format!("{} deg/h", three(f.gyro_bias_deg_h, 1)),
        ));
        rows.push((
            "accel bias x,y,z",
            format!("{} mg", three(f.accel_bias_mg, 2)),
        ));
    }
    rows.push(("solution", s.files.solution.display().to_string()));
    rows.push(("states", s.files.states.display().to_string()));
    rows.push(("innovations", s.files.innovations.display().to_string()));
    print_rows(&rows);
}
