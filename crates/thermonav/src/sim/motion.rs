//! Motion definitions and the trajectories they generate.
//!
//! A motion definition is a start (position, speed, heading) and a list of segments, each of a
//! duration with a constant along-track acceleration, turn rate and climb rate, like the peers'
//! motion files (gnss-ins-sim's `motion_def`, PSINS' trajectory profiles). Optional harmonic
//! wave motion adds roll, pitch and heave (a vessel). Speed, heading, climb and waves are
//! evaluated in closed form at each sample time; positions are integrated from the velocities
//! with the mechanization's own position rule ([`update_position`]), so that the ideal IMU
//! derived from the trajectory reproduces it exactly.

use crate::frames::{Body, Ned, Rotation, Vector};
use crate::geo::position::{Geodetic, NAVIGATION_LATITUDE_LIMIT_DEG, within_navigation_latitudes};
use crate::ins::mechanization::update_position;
use crate::ins::state::NavState;
use crate::time::Timestamp;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// One segment of constant along-track acceleration, turn rate and climb rate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MotionSegment {
    /// Length of the segment, s.
    pub duration_s: f64,
    /// Along-track acceleration, m/s².
    pub acceleration_m_s2: f64,
    /// Turn rate (heading rate, positive clockwise seen from above), rad/s.
    pub turn_rate_rad_s: f64,
    /// Vertical speed, positive up, m/s.
    pub climb_rate_m_s: f64,
}

/// A harmonic: amplitude × sin(2π t / period + phase).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Harmonic {
    /// Amplitude (rad for angles, m for heave).
    pub amplitude: f64,
    /// Period, s.
    pub period_s: f64,
    /// Phase, rad.
    pub phase_rad: f64,
}

/// Wave-induced motion of a vessel.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct WaveMotion {
    /// Roll harmonics, rad.
    pub roll: Vec<Harmonic>,
    /// Pitch harmonics, rad.
    pub pitch: Vec<Harmonic>,
    /// Heave harmonics (up positive), m.
    pub heave: Vec<Harmonic>,
}

/// How pitch follows the path.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PitchModel {
    /// The body stays level apart from waves (a vessel).
    Level,
    /// The nose follows the flight-path angle atan(climb / speed) (a car on a slope).
    FollowsPath,
}

/// A whole motion definition.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MotionDefinition {
    /// Start position.
    pub start: StartPoint,
    /// Initial speed, m/s.
    pub initial_speed_m_s: f64,
    /// Initial heading, rad.
    pub initial_heading_rad: f64,
    /// Segments in order.
    pub segments: Vec<MotionSegment>,
    /// Wave motion, if any.
    pub waves: WaveMotion,
    /// Pitch model.
    pub pitch: PitchModel,
}

/// Start position in degrees and metres (the motion file's units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StartPoint {
    /// Latitude, deg.
    pub lat_deg: f64,
    /// Longitude, deg.
    pub lon_deg: f64,
    /// Ellipsoidal height, m.
    pub h_m: f64,
}

/// Why a motion definition is unusable.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MotionError {
    /// No segment.
    #[error("the motion definition has no segment")]
    Empty,
    /// A value that must be finite (and sometimes positive) is not.
    #[error("motion definition: {what} = {value} must be {expected}")]
    Value {
        /// Which value.
        what: String,
        /// The value.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
    /// The path starts or passes beyond [`NAVIGATION_LATITUDE_LIMIT_DEG`].
    #[error(
        "the motion reaches latitude {lat_deg:.4}° at t = {time_s:.3} s: thermonav navigates within ±{NAVIGATION_LATITUDE_LIMIT_DEG}° (the NED mechanisation is singular at the poles)"
    )]
    Polar {
        /// Seconds from the motion's start.
        time_s: f64,
        /// The latitude, °.
        lat_deg: f64,
    },
    /// The speed becomes negative.
    #[error("segment {segment}: speed falls to {speed_m_s:.3} m/s; speeds must stay non-negative")]
    NegativeSpeed {
        /// Segment index (0-based).
        segment: usize,
        /// Speed at its end.
        speed_m_s: f64,
    },
}

/// Kinematics at one instant: speed, heading, climb and the wave terms with their rates.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Kinematics {
    speed_m_s: f64,
    heading_rad: f64,
    climb_m_s: f64,
    roll_rad: f64,
    pitch_rad: f64,
    heave_rate_m_s: f64,
}

impl MotionDefinition {
    /// Checks values and that the speed stays non-negative.
    ///
    /// # Errors
    /// The first [`MotionError`] found.
    pub fn validate(&self) -> Result<(), MotionError> {
        if self.segments.is_empty() {
            return Err(MotionError::Empty);
        }
        let finite = |what: &str, value: f64| {
            if value.is_finite() {
                Ok(())
            } else {
                Err(MotionError::Value {
                    what: what.to_string(),
                    value,
                    expected: "finite",
                })
            }
        };
        finite("start.lat_deg", self.start.lat_deg)?;
        finite("start.lon_deg", self.start.lon_deg)?;
        finite("start.h_m", self.start.h_m)?;
        finite("initial_heading_rad", self.initial_heading_rad)?;
        if !(self.initial_speed_m_s.is_finite() && self.initial_speed_m_s >= 0.0) {
            return Err(MotionError::Value {
                what: "initial_speed_m_s".into(),
                value: self.initial_speed_m_s,
                expected: "finite and non-negative",
            });
        }
        if !within_navigation_latitudes(self.start.lat_deg.to_radians()) {
            return Err(MotionError::Polar {
                time_s: 0.0,
                lat_deg: self.start.lat_deg,
            });
        }
        self.validate_segments()?;
        self.validate_waves()
    }

    fn validate_segments(&self) -> Result<(), MotionError> {
        let mut speed = self.initial_speed_m_s;
        for (k, s) in self.segments.iter().enumerate() {
            if !(s.duration_s.is_finite() && s.duration_s > 0.0) {
                return Err(MotionError::Value {
                    what: format!("segments[{k}].duration_s"),
                    value: s.duration_s,
                    expected: "finite and positive",
                });
            }
            for (name, v) in [
                ("acceleration_m_s2", s.acceleration_m_s2),
                ("turn_rate_rad_s", s.turn_rate_rad_s),
                ("climb_rate_m_s", s.climb_rate_m_s),
            ] {
                if !v.is_finite() {
                    return Err(MotionError::Value {
                        what: format!("segments[{k}].{name}"),
                        value: v,
                        expected: "finite",
                    });
                }
            }
            speed += s.acceleration_m_s2 * s.duration_s;
            if speed < -1e-9 {
                return Err(MotionError::NegativeSpeed {
                    segment: k,
                    speed_m_s: speed,
                });
            }
        }
        Ok(())
    }

    fn validate_waves(&self) -> Result<(), MotionError> {
        let all = self
            .waves
            .roll
            .iter()
            .chain(&self.waves.pitch)
            .chain(&self.waves.heave);
        for h in all {
            if !(h.amplitude.is_finite()
                && h.phase_rad.is_finite()
                && h.period_s.is_finite()
                && h.period_s > 0.0)
            {
                return Err(MotionError::Value {
                    what: "waves harmonic".into(),
                    value: h.period_s,
                    expected: "finite with a positive period",
                });
            }
        }
        Ok(())
    }

    /// Total duration, s.
    pub fn duration_s(&self) -> f64 {
        self.segments.iter().map(|s| s.duration_s).sum()
    }

    /// Kinematics at time `t_s` from the start (held at the last segment's end beyond it).
    fn kinematics(&self, t_s: f64) -> Kinematics {
        let (mut t0, mut speed, mut heading) =
            (0.0, self.initial_speed_m_s, self.initial_heading_rad);
        let mut climb = 0.0;
        for s in &self.segments {
            let tau = (t_s - t0).clamp(0.0, s.duration_s);
            climb = s.climb_rate_m_s;
            if t_s <= t0 + s.duration_s {
                speed += s.acceleration_m_s2 * tau;
                heading += s.turn_rate_rad_s * tau;
                break;
            }
            speed += s.acceleration_m_s2 * s.duration_s;
            heading += s.turn_rate_rad_s * s.duration_s;
            t0 += s.duration_s;
        }
        let speed = speed.max(0.0);
        let path_pitch = match self.pitch {
            PitchModel::Level => 0.0,
            PitchModel::FollowsPath => climb.atan2(speed.max(1e-3)),
        };
        Kinematics {
            speed_m_s: speed,
            heading_rad: heading,
            climb_m_s: climb,
            roll_rad: harmonic_sum(&self.waves.roll, t_s),
            pitch_rad: path_pitch + harmonic_sum(&self.waves.pitch, t_s),
            heave_rate_m_s: harmonic_rate(&self.waves.heave, t_s),
        }
    }
}

fn harmonic_sum(harmonics: &[Harmonic], t_s: f64) -> f64 {
    harmonics
        .iter()
        .map(|h| h.amplitude * (TAU * t_s / h.period_s + h.phase_rad).sin())
        .sum()
}

fn harmonic_rate(harmonics: &[Harmonic], t_s: f64) -> f64 {
    harmonics
        .iter()
        .map(|h| h.amplitude * TAU / h.period_s * (TAU * t_s / h.period_s + h.phase_rad).cos())
        .sum()
}

/// The sampled true trajectory.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    /// States at the sample times, the first at time zero.
    pub states: Vec<NavState>,
}

/// Samples `motion` at `rate_hz` over its whole duration (a regular grid from time zero).
///
/// # Errors
/// [`MotionError`] for an invalid definition or rate.
pub fn generate_trajectory(
    motion: &MotionDefinition,
    rate_hz: f64,
) -> Result<Trajectory, MotionError> {
    if !(rate_hz.is_finite() && rate_hz > 0.0 && rate_hz <= 1e5) {
        return Err(MotionError::Value {
            what: "rate_hz".into(),
            value: rate_hz,
            expected: "finite, positive and at most 100 kHz",
        });
    }
    let n = (motion.duration_s() * rate_hz).floor() as usize + 1;
    let times: Vec<Timestamp> = (0..n)
        .map(|k| Timestamp::from_nanos((k as f64 * 1e9 / rate_hz).round() as i64))
        .collect();
    generate_trajectory_at(motion, &times)
}

/// Samples `motion` at the given times (seconds from the motion's start, strictly increasing;
/// jittered logger times are fine). Positions are integrated from the first time on.
///
/// # Errors
/// [`MotionError`] for an invalid definition or times that do not increase.
pub fn generate_trajectory_at(
    motion: &MotionDefinition,
    times: &[Timestamp],
) -> Result<Trajectory, MotionError> {
    motion.validate()?;
    if let Some(w) = times.windows(2).find(|w| w[1] <= w[0]) {
        return Err(MotionError::Value {
            what: "sample time".into(),
            value: w[1].as_seconds(),
            expected: "strictly increasing",
        });
    }
    let start =
        Geodetic::from_degrees(motion.start.lat_deg, motion.start.lon_deg, motion.start.h_m);
    let mut states: Vec<NavState> = Vec::with_capacity(times.len());
    for &time in times {
        let kin = motion.kinematics(time.as_seconds());
        let velocity = velocity_of(&kin);
        let position = match states.last() {
            Some(prev) => update_position(
                &prev.position,
                &prev.velocity,
                &velocity,
                time.since(prev.time).as_seconds(),
            ),
            None => start,
        };
        if !within_navigation_latitudes(position.latitude_rad) {
            return Err(MotionError::Polar {
                time_s: time.as_seconds(),
                lat_deg: position.latitude_rad.to_degrees(),
            });
        }
        let attitude =
            Rotation::<Body, Ned>::from_euler_zyx(kin.roll_rad, kin.pitch_rad, kin.heading_rad);
        states.push(NavState {
            time,
            position,
            velocity,
            attitude,
        });
    }
    Ok(Trajectory { states })
}

fn velocity_of(kin: &Kinematics) -> Vector<Ned> {
    let (s, c) = kin.heading_rad.sin_cos();
    Vector::new(
        kin.speed_m_s * c,
        kin.speed_m_s * s,
        -(kin.climb_m_s + kin.heave_rate_m_s),
    )
}
