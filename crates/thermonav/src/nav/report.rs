//! What one navigation run ([`super::run`]) reports: the model used, the schedule, the
//! compensation, the start, the outages, the innovation statistics and the last epoch's
//! uncertainty and sensor estimates. The keys are `thermonav integrate --json`'s (which adds
//! the file names) and the Python package's `integrate` result's.

use super::alignment::{CourseBaseline, InitialBiasSource};
use super::engine::{BiasHypotheses, FilterKind};
use super::measurement::MeasurementKind;
use super::outage::Outage;
use super::run::{InitialSource, RunOutcome};
use super::schedule::{CompensationOutcome, ScheduleSummary};
use super::sensor_model::{BankChoice, ImuStochasticModel};
use super::solution::{InnovationStatistics, SolutionEpoch, SolutionSummary};
use crate::imu::Channel;
use crate::stoch::bank::{GaussMarkovSource, Selection};
use crate::units::{STANDARD_GRAVITY_M_S2, rad_per_s_to_deg_per_h};
use serde::Serialize;

/// One channel of the model the filter used.
#[derive(Debug, Clone, Serialize)]
pub struct ChannelModelJson {
    channel: &'static str,
    unit: &'static str,
    bias_correlation_time_s: f64,
    bias_sigma: f64,
    white_noise_density: f64,
    white_noise_density_unit: &'static str,
}

/// The model the filter used.
#[derive(Debug, Clone, Serialize)]
pub struct ModelJson {
    /// Gauss-Markov family.
    pub gauss_markov_source: GaussMarkovSource,
    /// Selection rule.
    pub selection: Selection,
    /// The model's temperature, °C.
    pub temperature_c: f64,
    channels: Vec<ChannelModelJson>,
}

/// The initial bias standard deviations of a run.
#[derive(Debug, Clone, Serialize)]
pub struct InitialBiasJson {
    /// Where they came from.
    pub source: InitialBiasSource,
    /// True when the gyro sds are instead the still span's ([`Self::source`] then holds for
    /// the accelerometers only): see `still_start`.
    pub gyro_from_still_start: bool,
    /// Gyro x, y, z, deg/h.
    pub gyro_deg_h: [f64; 3],
    /// Accelerometer x, y, z, mg.
    pub accel_mg: [f64; 3],
}

/// Innovation statistics of one measurement kind.
#[derive(Debug, Clone, Serialize)]
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
    /// Mean factor the gate's quantile was widened by from the recent NIS level.
    pub mean_gate_scale: f64,
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
            mean_gate_scale: s.mean_gate_scale,
            rms_innovation_ned_m: (s.kind == MeasurementKind::Position).then_some(rms),
            rms_innovation_ned_m_s: (s.kind == MeasurementKind::Velocity).then_some(rms),
            rms_innovation_deg: (s.kind == MeasurementKind::Heading).then_some(rms[0].to_degrees()),
        }
    }
}

/// The last epoch's uncertainty and sensor estimates.
#[derive(Debug, Clone, Serialize)]
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
#[derive(Debug, Clone, Serialize)]
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

/// What a run reports.
#[derive(Debug, Clone, Serialize)]
pub struct RunReport {
    /// The filter.
    pub filter: FilterKind,
    /// The model used (when scheduled: the model at the mean or given temperature, for
    /// reference).
    pub model: ModelJson,
    /// One model or the model at the IMU's temperature at every covariance step.
    pub schedule: ScheduleSummary,
    /// Whether the bank's bias(T) was subtracted from the samples.
    pub compensation: CompensationOutcome,
    /// Where the initial state came from.
    pub initial: InitialSource,
    /// The straight stretch of fixes the initial course came from (distance, time, fixes,
    /// course sd), when the heading was a course over ground.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub course_baseline: Option<CourseBaseline>,
    /// The still span at the record's start that levelled the start and gave the gyro biases
    /// (absent: the platform was not still, or static alignment was off).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub still_start: Option<super::static_alignment::StillStart>,
    /// Whether static alignment was used, and if not, why (`decision` and its numbers).
    pub static_alignment: super::static_alignment::StillDecision,
    /// Where the GNSS position sds came from: the file's, or the default for fixes without.
    pub gnss_sd: crate::gnss::GnssSdUse,
    /// The initial bias standard deviations and where they came from.
    pub initial_bias_sd: InitialBiasJson,
    /// The Gaussian sum the z-gyro bias prior was split into (absent: one filter).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bias_hypotheses: Option<BiasHypotheses>,
    /// Covariance steps per second, Hz.
    pub covariance_rate_hz: f64,
    /// Solution epochs per second, Hz.
    pub output_rate_hz: f64,
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
}

impl RunReport {
    /// The report of a run.
    pub fn of(run: &RunOutcome) -> Self {
        Self::of_summary(run, &SolutionSummary::of(&run.solution))
    }

    /// The report of a run whose records went to a sink that `summary` also saw (the run's
    /// solution then holds no epochs or innovations: [`super::stream`]).
    pub fn of_summary(run: &RunOutcome, summary: &SolutionSummary) -> Self {
        let duration_s = summary.span_s();
        let windows = run.engine.outages.windows();
        Self {
            filter: run.engine.filter,
            model: model_json(&run.models.choice, &run.models.model),
            schedule: run.models.summary(),
            compensation: run.compensation.clone(),
            initial: run.initial,
            course_baseline: run.course_baseline,
            still_start: run.still_start,
            static_alignment: run.still_decision,
            gnss_sd: run.gnss_sd,
            initial_bias_sd: InitialBiasJson {
                source: run.bias_source,
                gyro_from_still_start: run.still_start.is_some(),
                gyro_deg_h: run
                    .uncertainty
                    .gyro_bias_sd_rad_s
                    .map(rad_per_s_to_deg_per_h),
                accel_mg: run
                    .uncertainty
                    .accel_bias_sd_m_s2
                    .map(|a| 1e3 * a / STANDARD_GRAVITY_M_S2),
            },
            bias_hypotheses: run.engine.bias_hypotheses,
            covariance_rate_hz: 1.0 / run.engine.covariance_interval_s,
            output_rate_hz: 1.0 / run.engine.output_interval_s,
            outages: windows.iter().map(OutageJson::from).collect(),
            imu_samples: run.solution.imu_samples,
            duration_s,
            processing_time_s: run.processing_s,
            real_time_factor: real_time_factor(duration_s, run.processing_s),
            innovations: innovation_rows(summary),
            last: summary.last.as_ref().map(final_json),
        }
    }
}

fn real_time_factor(duration_s: f64, processing_s: f64) -> f64 {
    if processing_s > 0.0 {
        duration_s / processing_s
    } else {
        0.0
    }
}

fn innovation_rows(summary: &SolutionSummary) -> Vec<InnovationJson> {
    let statistics = summary.innovation_statistics();
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
