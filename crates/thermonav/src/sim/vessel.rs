//! A harbour survey vessel: survey lines and turns at 1-6 m/s with wave-induced roll, pitch and
//! heave; the true trajectory, the IMU (ideal increments through the sensor's error model at
//! the operating temperature) and 1 Hz differential GNSS with dual-antenna heading.
//!
//! [`simulate_vessel_with`] adds what a slow vehicle's test needs on top of the sensor's own
//! error model ([`ImuOffsets`]: a turn-on gyro bias per axis and an IMU-GNSS time offset);
//! [`GnssHeading::None`] gives position-only fixes.

use super::clock::SampleClock;
use super::errors::{ChannelErrors, standard_normal};
use super::ideal_imu::ideal_increments;
use super::motion::{
    Harmonic, MotionDefinition, MotionError, MotionSegment, PitchModel, StartPoint, Trajectory,
    WaveMotion, generate_trajectory_at,
};
use super::temperature_program::TemperatureProgram;
use super::unit::SimulatedUnit;
use crate::frames::{Body, Ned, Vector};
use crate::gnss::{GnssFix, HeadingObservation};
use crate::imu::{Channel, ImuSeries, SampleKind};
use crate::ins::state::NavState;
use crate::rng::{SimRng, named_rng};
use crate::sensor::{ProfileError, SensorProfile};
use crate::time::{Duration, NANOS_PER_SECOND, Timestamp};
use serde::Serialize;

/// GNSS receiver and antenna set-up.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GnssSettings {
    /// Fix rate, Hz.
    pub rate_hz: f64,
    /// Position noise (white), north/east/down standard deviations, m.
    pub position_sd_ned_m: [f64; 3],
    /// Primary antenna position in the body frame relative to the IMU, m.
    pub lever_arm_body_m: [f64; 3],
    /// Secondary antenna relative to the primary, body frame, m (the heading baseline).
    pub baseline_body_m: [f64; 3],
    /// Carrier-phase position noise of each antenna across the baseline, m.
    pub baseline_noise_m: f64,
    /// Whether the fixes carry the baseline's heading.
    pub heading: GnssHeading,
}

/// Whether the GNSS fixes carry a heading.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum GnssHeading {
    /// Dual-antenna heading from the baseline (a survey vessel).
    #[default]
    DualAntenna,
    /// Position-only fixes: one antenna (a rover, a car, a handheld receiver); the baseline
    /// settings are then unused.
    None,
}

/// What a run adds to the IMU record on top of the sensor's own error model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct ImuOffsets {
    /// A turn-on gyro bias per body axis x, y, z, added to every gyro sample, rad/s.
    pub gyro_bias_rad_s: [f64; 3],
    /// The IMU-GNSS time offset, s, with the sign of `convert --time-offset-s` and
    /// [`crate::nav::time_offset`]: the value **added** to the IMU times to put them on the
    /// GNSS scale. The IMU's timestamps are written as true time − offset.
    pub time_offset_s: f64,
}

impl Default for GnssSettings {
    /// Differential code (DGPS) positions at 0.5 m horizontal / 1.0 m vertical, antenna 2.5 m
    /// above the IMU, and the paper's 2.37 m fore-aft baseline with 5 mm carrier-phase noise
    /// per antenna (heading sd = √2 · 5 mm / 2.37 m ≈ 0.17°).
    fn default() -> Self {
        Self {
            rate_hz: 1.0,
            position_sd_ned_m: [0.5, 0.5, 1.0],
            lever_arm_body_m: [0.3, 0.0, -2.5],
            baseline_body_m: [2.37, 0.0, 0.0],
            baseline_noise_m: 0.005,
            heading: GnssHeading::DualAntenna,
        }
    }
}

impl GnssSettings {
    /// Heading standard deviation implied by the baseline: √2 σ / |b_horizontal|, rad.
    pub fn heading_sd_rad(&self) -> f64 {
        let b = self.baseline_body_m;
        std::f64::consts::SQRT_2 * self.baseline_noise_m / b[0].hypot(b[1])
    }
}

/// Everything a vessel run produces.
#[derive(Debug, Clone, PartialEq)]
pub struct VesselRecord {
    /// True trajectory at the IMU times (the first state is the start, before the first IMU
    /// sample).
    pub reference: Trajectory,
    /// IMU rates with errors, one sample per trajectory interval.
    pub imu: ImuSeries,
    /// GNSS fixes at the primary antenna.
    pub gnss: Vec<GnssFix>,
}

/// Why a vessel run cannot be simulated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VesselError {
    /// The motion is invalid.
    #[error(transparent)]
    Motion(#[from] MotionError),
    /// The profile is invalid.
    #[error(transparent)]
    Profile(#[from] ProfileError),
    /// The clock or duration is invalid.
    #[error(transparent)]
    Clock(#[from] super::clock::ClockError),
    /// The survey temperature is unusable.
    #[error(
        "survey temperature: values must be finite, a warm-up time constant positive, a table non-empty with increasing times"
    )]
    Temperature,
    /// A GNSS setting is invalid.
    #[error("GNSS setting {what} = {value} must be finite and positive")]
    Gnss {
        /// Which setting.
        what: &'static str,
        /// The value.
        value: f64,
    },
    /// An IMU offset is invalid.
    #[error(
        "IMU offset {what} = {value} must be finite (a time offset at most {MAX_TIME_OFFSET_S} s)"
    )]
    Offset {
        /// Which offset.
        what: &'static str,
        /// The value.
        value: f64,
    },
}

/// The built-in harbour survey: a 300 s transit at 5-6 m/s, then survey lines of 240 s at
/// 2.5 m/s joined by 30 s U-turns (6°/s, alternately to starboard and port), until
/// `duration_s`; roll 3° (6 s) + 1.5° (9.3 s), pitch 1.5° (5.1 s), heave 0.3 m (7 s).
pub fn harbour_survey(duration_s: f64) -> MotionDefinition {
    let seg = |duration_s: f64, acceleration_m_s2: f64, turn_deg_s: f64| MotionSegment {
        duration_s,
        acceleration_m_s2,
        turn_rate_rad_s: turn_deg_s.to_radians(),
        climb_rate_m_s: 0.0,
    };
    let mut segments = vec![
        seg(40.0, 0.1, 0.0),
        seg(60.0, 0.0, 0.5),
        seg(200.0, 0.005, 0.0),
        seg(30.0, -0.116, 0.0),
    ];
    let mut elapsed: f64 = segments.iter().map(|s| s.duration_s).sum();
    let mut k = 0;
    while elapsed < duration_s {
        let line = seg(240.0_f64.min(duration_s - elapsed), 0.0, 0.0);
        elapsed += line.duration_s;
        segments.push(line);
        if elapsed < duration_s {
            let turn = seg(
                30.0_f64.min(duration_s - elapsed),
                0.0,
                if k % 2 == 0 { 6.0 } else { -6.0 },
            );
            elapsed += turn.duration_s;
            segments.push(turn);
        }
        k += 1;
    }
    let h = |amplitude: f64, period_s: f64, phase_rad: f64| Harmonic {
        amplitude,
        period_s,
        phase_rad,
    };
    MotionDefinition {
        start: StartPoint {
            lat_deg: 44.6488,
            lon_deg: -63.5752,
            h_m: 5.0,
        },
        initial_speed_m_s: 1.0,
        initial_heading_rad: 40f64.to_radians(),
        segments,
        waves: WaveMotion {
            roll: vec![
                h(3f64.to_radians(), 6.0, 0.0),
                h(1.5f64.to_radians(), 9.3, 1.1),
            ],
            pitch: vec![h(1.5f64.to_radians(), 5.1, 0.4)],
            heave: vec![h(0.3, 7.0, 0.2)],
        },
        pitch: PitchModel::Level,
    }
}

/// The survey of the paper's field test: 1 h at 17 °C (the temperature between the
/// campaign's set points that the tournament asks about), the IMU at 200 Hz with 50 µs of
/// timestamp jitter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SurveySettings {
    /// Sensor temperature during the survey, °C.
    pub temperature_c: f64,
    /// Survey length, s.
    pub duration_s: f64,
    /// IMU sampling rate, Hz.
    pub imu_rate_hz: f64,
    /// IMU timestamp jitter (standard deviation), s.
    pub imu_jitter_s: f64,
}

impl Default for SurveySettings {
    fn default() -> Self {
        Self {
            temperature_c: 17.0,
            duration_s: 3600.0,
            imu_rate_hz: 200.0,
            imu_jitter_s: 50e-6,
        }
    }
}

/// Time constant of a cold start's warm-up, s: a MEMS unit in its housing warms by self-heating
/// and from the vehicle over a quarter of an hour or so.
pub const DEFAULT_WARM_UP_TIME_CONSTANT_S: f64 = 900.0;

/// The sensor's temperature during a survey.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SurveyTemperature {
    /// Held, °C.
    Constant {
        /// The temperature, °C.
        temperature_c: f64,
    },
    /// A cold start warming up: T(t) = T_settled + (T_start − T_settled) exp(−t/τ).
    WarmUp {
        /// Temperature at switch-on, °C.
        start_c: f64,
        /// Temperature it settles at, °C.
        settled_c: f64,
        /// Time constant τ, s.
        time_constant_s: f64,
    },
    /// A table of (time since the start, temperature), interpolated linearly, the end values
    /// held outside it.
    Table(TemperatureProgram),
}

impl SurveyTemperature {
    /// The temperature `t_s` after the start, °C.
    pub fn at(&self, t_s: f64) -> f64 {
        match self {
            Self::Constant { temperature_c } => *temperature_c,
            Self::WarmUp {
                start_c,
                settled_c,
                time_constant_s,
            } => settled_c + (start_c - settled_c) * (-t_s.max(0.0) / time_constant_s).exp(),
            Self::Table(program) => program.at(t_s),
        }
    }

    /// True when every value is usable: finite, τ > 0, a non-empty table of equal columns
    /// with increasing times.
    pub fn is_valid(&self) -> bool {
        match self {
            Self::Constant { temperature_c } => temperature_c.is_finite(),
            Self::WarmUp {
                start_c,
                settled_c,
                time_constant_s,
            } => {
                start_c.is_finite()
                    && settled_c.is_finite()
                    && time_constant_s.is_finite()
                    && *time_constant_s > 0.0
            }
            Self::Table(program) => program.is_valid(),
        }
    }
}

/// A vessel run: motion, sensor temperature, unit, IMU clock, GNSS set-up, seed.
#[derive(Debug, Clone, PartialEq)]
pub struct VesselRun {
    /// The motion.
    pub motion: MotionDefinition,
    /// Sensor temperature during the run.
    pub temperature: SurveyTemperature,
    /// The unit on board (the same serial as a chamber campaign's is the same unit).
    pub unit: SimulatedUnit,
    /// IMU sampling clock.
    pub clock: SampleClock,
    /// GNSS set-up.
    pub gnss: GnssSettings,
    /// User seed.
    pub seed: u64,
}

/// Simulates a vessel run.
///
/// # Errors
/// [`VesselError`] for an invalid motion, profile, clock or GNSS setting.
pub fn simulate_vessel(
    profile: &SensorProfile,
    run: &VesselRun,
) -> Result<VesselRecord, VesselError> {
    simulate_vessel_with(profile, run, &ImuOffsets::default())
}

/// Simulates a vessel run whose IMU record also carries `offsets`: the gyro biases are
/// added to the gyro samples and the IMU times are moved by −`time_offset_s` (the reference
/// and the GNSS fixes stay on the true, GNSS, time scale).
///
/// # Errors
/// [`VesselError`] for an invalid motion, profile, clock, GNSS setting or offset.
pub fn simulate_vessel_with(
    profile: &SensorProfile,
    run: &VesselRun,
    offsets: &ImuOffsets,
) -> Result<VesselRecord, VesselError> {
    validate_offsets(offsets)?;
    let mut record = simulate_vessel_on_gnss_time(profile, run, offsets)?;
    let back = Duration::from_seconds(-offsets.time_offset_s).unwrap_or(Duration::ZERO);
    for t in &mut record.imu.time {
        *t = t.checked_add(back).unwrap_or(*t);
    }
    Ok(record)
}

/// Largest IMU-GNSS time offset [`simulate_vessel_with`] takes, s (an hour: far beyond any
/// real clock mismatch, and well inside the timestamps' range).
pub const MAX_TIME_OFFSET_S: f64 = 3600.0;

fn validate_offsets(offsets: &ImuOffsets) -> Result<(), VesselError> {
    let t = offsets.time_offset_s;
    if !(t.is_finite() && t.abs() <= MAX_TIME_OFFSET_S) {
        return Err(VesselError::Offset {
            what: "time_offset_s",
            value: t,
        });
    }
    match offsets.gyro_bias_rad_s.iter().find(|b| !b.is_finite()) {
        Some(&value) => Err(VesselError::Offset {
            what: "gyro_bias_rad_s",
            value,
        }),
        None => Ok(()),
    }
}

fn simulate_vessel_on_gnss_time(
    profile: &SensorProfile,
    run: &VesselRun,
    offsets: &ImuOffsets,
) -> Result<VesselRecord, VesselError> {
    profile.validate()?;
    validate_gnss(&run.gnss)?;
    if !run.temperature.is_valid() {
        return Err(VesselError::Temperature);
    }
    let times = run.clock.timestamps(
        run.motion.duration_s(),
        &mut named_rng(run.seed, "vessel/clock"),
    )?;
    let reference = generate_trajectory_at(&run.motion, &times)?;
    let imu = measured_imu(profile, run, &reference, &offsets.gyro_bias_rad_s);
    let gnss = gnss_fixes(
        &reference,
        &run.gnss,
        &mut named_rng(run.seed, "vessel/gnss"),
    );
    Ok(VesselRecord {
        reference,
        imu,
        gnss,
    })
}

fn validate_gnss(g: &GnssSettings) -> Result<(), VesselError> {
    let positive = |what: &'static str, value: f64| {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(VesselError::Gnss { what, value })
        }
    };
    positive("rate_hz", g.rate_hz)?;
    if g.heading == GnssHeading::DualAntenna {
        positive("baseline_noise_m", g.baseline_noise_m)?;
        positive(
            "baseline length",
            g.baseline_body_m[0].hypot(g.baseline_body_m[1]),
        )?;
    }
    for (k, sd) in g.position_sd_ned_m.iter().enumerate() {
        positive(
            ["position_sd_n_m", "position_sd_e_m", "position_sd_d_m"][k],
            *sd,
        )?;
    }
    Ok(())
}

/// The sensor temperature at each of `times`, °C.
pub fn sample_temperatures_c(run: &VesselRun, times: &[Timestamp]) -> Vec<f64> {
    let Some(&start) = times.first() else {
        return Vec::new();
    };
    times
        .iter()
        .map(|t| run.temperature.at(t.since(start).as_seconds()))
        .collect()
}

/// The name of the survey's power-on (for [`SimulatedUnit::power_on_offset`]).
pub const SURVEY_POWER_ON: &str = "vessel";

/// IMU rates through each channel's error model at each sample's temperature, the gyros with
/// `added_gyro_bias_rad_s` on top.
fn measured_imu(
    profile: &SensorProfile,
    run: &VesselRun,
    reference: &Trajectory,
    added_gyro_bias_rad_s: &[f64; 3],
) -> ImuSeries {
    let increments = ideal_increments(reference);
    let mut series = ImuSeries::new(SampleKind::Rates);
    series.time = increments.iter().map(|i| i.time).collect();
    let temperatures = sample_temperatures_c(run, &series.time);
    for channel in Channel::ALL {
        let mut rng: SimRng = named_rng(run.seed, &format!("vessel/{}", channel.name()));
        let p = &profile.channels[&channel];
        let added = match channel.index() {
            k @ 0..3 => added_gyro_bias_rad_s[k],
            _ => 0.0,
        };
        let constant = run.unit.fixed_bias(profile, channel)
            + run
                .unit
                .power_on_offset(profile, channel, run.seed, SURVEY_POWER_ON)
            + added;
        let mut errors = ChannelErrors::new(
            p,
            profile.reference_temperature_c,
            temperatures
                .first()
                .copied()
                .unwrap_or(profile.reference_temperature_c),
            constant,
            &mut rng,
        );
        let axis = channel.index() % 3;
        series.channels[channel.index()] = increments
            .iter()
            .zip(&temperatures)
            .map(|(inc, &temperature_c)| {
                let delta = if channel.index() < 3 {
                    inc.delta_angle
                } else {
                    inc.delta_velocity
                };
                errors.measure(
                    delta.to_array()[axis] / inc.dt_s(),
                    inc.dt_s(),
                    temperature_c,
                    &mut rng,
                )
            })
            .collect();
    }
    series.temperature_c = Some(temperatures);
    series
}

/// The state at time `t` from the nearest earlier state, moved along its velocity.
fn state_at(reference: &Trajectory, t: Timestamp) -> Option<NavState> {
    let k = reference
        .states
        .partition_point(|s| s.time <= t)
        .checked_sub(1)?;
    let s = reference.states[k];
    let dt = t.since(s.time).as_seconds();
    let position = s.position.displaced(&s.velocity.scale(dt));
    Some(NavState {
        time: t,
        position,
        ..s
    })
}

/// Fixes at whole multiples of the GNSS interval within the reference.
fn gnss_fixes(reference: &Trajectory, g: &GnssSettings, rng: &mut SimRng) -> Vec<GnssFix> {
    let (Some(first), Some(last)) = (reference.states.first(), reference.states.last()) else {
        return Vec::new();
    };
    let step_ns = (NANOS_PER_SECOND as f64 / g.rate_hz).round() as i64;
    let step = Duration::from_nanos(step_ns);
    let mut fixes = Vec::new();
    let mut t = Timestamp::from_nanos((first.time.as_nanos() / step_ns + 1) * step_ns);
    while t <= last.time {
        if let Some(state) = state_at(reference, t) {
            fixes.push(gnss_fix(&state, g, rng));
        }
        t += step;
    }
    fixes
}

fn gnss_fix(state: &NavState, g: &GnssSettings, rng: &mut SimRng) -> GnssFix {
    let lever_n = state.attitude * Vector::<Body>::from_array(g.lever_arm_body_m);
    let noise = Vector::<Ned>::from_array(g.position_sd_ned_m.map(|sd| sd * standard_normal(rng)));
    let antenna = state.position.displaced(&(lever_n + noise));
    let heading = match g.heading {
        GnssHeading::DualAntenna => Some(dual_antenna_heading(state, g, rng)),
        GnssHeading::None => None,
    };
    GnssFix {
        time: state.time,
        latitude_rad: antenna.latitude_rad,
        longitude_rad: antenna.longitude_rad,
        height_m: antenna.height_m,
        position_sd_ned_m: Some(g.position_sd_ned_m),
        velocity_ned_m_s: None,
        heading,
    }
}

/// The baseline's heading with the carrier-phase noise across it.
fn dual_antenna_heading(
    state: &NavState,
    g: &GnssSettings,
    rng: &mut SimRng,
) -> HeadingObservation {
    let baseline_n = (state.attitude * Vector::<Body>::from_array(g.baseline_body_m)).to_array();
    let across = g.baseline_noise_m * std::f64::consts::SQRT_2 * standard_normal(rng);
    let length = baseline_n[0].hypot(baseline_n[1]);
    HeadingObservation {
        heading_rad: wrap_pi(baseline_n[1].atan2(baseline_n[0]) + across / length),
        sd_rad: g.heading_sd_rad(),
    }
}

pub use crate::units::wrap_pi;
