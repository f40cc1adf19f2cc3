//! Initial alignment: coarse levelling from the mean specific force, heading from a
//! dual-antenna baseline or from the GNSS course, position and velocity from the first fixes,
//! and the initial covariance.
//!
//! Levelling (Groves 2013 §5.6.2): at rest the accelerometers sense f^b = −C_n^b g^n, so
//! roll φ = atan2(−f_y, −f_z) and pitch θ = atan2(f_x, √(f_y² + f_z²)). On a moving vehicle
//! the mean over a short span still levels to within the mean horizontal acceleration over g;
//! the initial attitude uncertainty should say so.

use super::error_state::{Estimate, SensorCorrection};
use super::measurement::AntennaGeometry;
use crate::frames::{Body, Rotation, Vector};
use crate::geo::position::Geodetic;
use crate::gnss::GnssFix;
use crate::ins::error_model::{STATES, SystemMatrix, block};
use crate::ins::state::{Increment, NavState};
use crate::time::Duration;
use serde::Serialize;

/// Slowest course over ground trusted for the initial heading, m/s (at 1 m/s and 1 Hz a 1 cm
/// position noise is already 0.6° of course).
pub const MIN_COURSE_SPEED_M_S: f64 = 1.0;

/// Roll and pitch (rad) from a mean specific force in body axes (m/s²).
pub fn level(mean_specific_force_b: [f64; 3]) -> (f64, f64) {
    let [fx, fy, fz] = mean_specific_force_b;
    ((-fy).atan2(-fz), fx.atan2(fy.hypot(fz)))
}

/// Where the initial heading came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum HeadingSource {
    /// The first fix's dual-antenna heading.
    DualAntenna,
    /// The course over ground between the first two fixes.
    Course,
}

/// Why the alignment failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AlignmentError {
    /// Fewer than two GNSS fixes at or after the first IMU sample.
    #[error(
        "alignment needs two GNSS fixes at or after the first IMU sample ({imu_start_s:.3} s); the GNSS file has {fixes}, {after_imu_start} of them from then on{}",
        span_note(*first_fix_s, *last_fix_s)
    )]
    TooFewFixes {
        /// Fixes in the file.
        fixes: usize,
        /// Fixes at or after the first IMU sample.
        after_imu_start: usize,
        /// Time of the first IMU sample, s (NaN without IMU data).
        imu_start_s: f64,
        /// Time of the first fix, s.
        first_fix_s: Option<f64>,
        /// Time of the last fix, s.
        last_fix_s: Option<f64>,
    },
    /// No IMU data in the levelling span.
    #[error("no IMU sample in the {0} s after the first GNSS fix to level with")]
    NoImu(f64),
    /// Neither a dual-antenna heading nor enough speed for a course.
    #[error(
        "no initial heading: no fix during the IMU record has a dual-antenna heading, and the vehicle never reaches 1 m/s between fixes (fastest {speed_m_s:.2} m/s)"
    )]
    NoHeading {
        /// Largest speed between consecutive fixes.
        speed_m_s: f64,
    },
}

/// " (fixes from A to B s: check that both files share one time scale)", or nothing.
fn span_note(first_fix_s: Option<f64>, last_fix_s: Option<f64>) -> String {
    match (first_fix_s, last_fix_s) {
        (Some(a), Some(b)) => {
            format!(" (fixes from {a:.3} to {b:.3} s: check that both files share one time scale)")
        }
        _ => String::new(),
    }
}

/// The aligned initial state and how its heading was found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Alignment {
    /// The initial state at the first fix's time.
    pub nav: NavState,
    /// Heading source.
    pub heading_source: HeadingSource,
}

fn geodetic(fix: &GnssFix) -> Geodetic {
    Geodetic {
        latitude_rad: fix.latitude_rad,
        longitude_rad: fix.longitude_rad,
        height_m: fix.height_m,
    }
}

/// Aligns at the first GNSS fix during the IMU record that has a dual-antenna heading or is
/// followed by a move of at least [`MIN_COURSE_SPEED_M_S`] (a vehicle parked at the start is
/// waited for): attitude levelled from the IMU samples in `levelling_s` after it, heading
/// from its dual-antenna heading or the course to the next fix, velocity from its velocity or
/// that course, position at the IMU (the antenna position less the lever arm).
///
/// # Errors
/// [`AlignmentError`] when the data cannot give one of these.
pub fn align_from_gnss(
    imu: &[Increment],
    gnss: &[GnssFix],
    geometry: &AntennaGeometry,
    levelling_s: f64,
) -> Result<Alignment, AlignmentError> {
    let imu_start = imu.first().map(|i| i.time);
    let usable: Vec<&[GnssFix]> = gnss
        .windows(2)
        .filter(|w| imu_start.is_some_and(|t| w[0].time >= t))
        .collect();
    if usable.is_empty() {
        let start = imu_start.map_or(f64::NAN, |t| t.as_seconds());
        return Err(AlignmentError::TooFewFixes {
            fixes: gnss.len(),
            after_imu_start: gnss
                .iter()
                .filter(|f| imu_start.is_some_and(|t| f.time >= t))
                .count(),
            imu_start_s: start,
            first_fix_s: gnss.first().map(|f| f.time.as_seconds()),
            last_fix_s: gnss.last().map(|f| f.time.as_seconds()),
        });
    }
    let course_of = |w: &[GnssFix]| {
        let dt = w[1].time.since(w[0].time).as_seconds();
        geodetic(&w[1]).ned_from(&geodetic(&w[0])).scale(1.0 / dt)
    };
    let speed = |w: &[GnssFix]| {
        let c = course_of(w);
        c.x().hypot(c.y())
    };
    let Some(pair) = usable
        .iter()
        .find(|w| w[0].heading.is_some() || speed(w) >= MIN_COURSE_SPEED_M_S)
    else {
        let fastest = usable.iter().map(|w| speed(w)).fold(0.0, f64::max);
        return Err(AlignmentError::NoHeading { speed_m_s: fastest });
    };
    let first = &pair[0];
    let span: Vec<_> = imu
        .iter()
        .filter(|i| i.time > first.time && i.time.since(first.time).as_seconds() <= levelling_s)
        .collect();
    let total_dt: Duration = span.iter().map(|i| i.dt).sum();
    if span.is_empty() || !total_dt.is_positive() {
        return Err(AlignmentError::NoImu(levelling_s));
    }
    let mean_force = span
        .iter()
        .fold(Vector::<Body>::zeros(), |acc, i| acc + i.delta_velocity)
        .scale(1.0 / total_dt.as_seconds());
    let (roll, pitch) = level(mean_force.to_array());
    let p0 = geodetic(first);
    let course = course_of(pair);
    let (yaw, heading_source) = match first.heading {
        Some(h) => {
            let b = geometry.baseline_body;
            (h.heading_rad - b[1].atan2(b[0]), HeadingSource::DualAntenna)
        }
        None => (course.y().atan2(course.x()), HeadingSource::Course),
    };
    let attitude = Rotation::from_euler_zyx(roll, pitch, yaw);
    let lever = attitude * Vector::<Body>::from_array(geometry.lever_arm_body_m);
    let velocity = first
        .velocity_ned_m_s
        .map(Vector::from_array)
        .unwrap_or(course);
    Ok(Alignment {
        nav: NavState {
            time: first.time,
            position: p0.displaced(&(-lever)),
            velocity,
            attitude,
        },
        heading_source,
    })
}

/// Initial standard deviations of the 21 error states.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct InitialUncertainty {
    /// Position, north/east/down, m.
    pub position_sd_m: [f64; 3],
    /// Velocity, north/east/down, m/s.
    pub velocity_sd_m_s: [f64; 3],
    /// Attitude error about north/east/down (≈ roll, pitch, heading when level), rad.
    pub attitude_sd_rad: [f64; 3],
    /// Gyro bias, rad/s (turn-on bias: not in a static model bank).
    pub gyro_bias_sd_rad_s: f64,
    /// Accelerometer bias, m/s².
    pub accel_bias_sd_m_s2: f64,
    /// Gyro scale-factor error (dimensionless).
    pub gyro_scale_sd: f64,
    /// Accelerometer scale-factor error (dimensionless).
    pub accel_scale_sd: f64,
}

impl Default for InitialUncertainty {
    /// A consumer MEMS IMU aligned on a moving vehicle with code GNSS: 2 m, 0.5 m/s, 2° in
    /// roll and pitch, 5° in heading, 1 °/s and 10 mg turn-on biases (ADIS16364 data sheet:
    /// ±3 °/s, ±8 mg), 1000 ppm scale factors.
    fn default() -> Self {
        Self {
            position_sd_m: [2.0, 2.0, 3.0],
            velocity_sd_m_s: [0.5; 3],
            attitude_sd_rad: [2f64.to_radians(), 2f64.to_radians(), 5f64.to_radians()],
            gyro_bias_sd_rad_s: 1f64.to_radians(),
            accel_bias_sd_m_s2: 0.01 * crate::units::STANDARD_GRAVITY_M_S2,
            gyro_scale_sd: 1e-3,
            accel_scale_sd: 1e-3,
        }
    }
}

impl InitialUncertainty {
    /// The diagonal initial covariance.
    pub fn covariance(&self) -> SystemMatrix {
        let mut sd = [0.0; STATES];
        let mut put = |start: usize, v: [f64; 3]| sd[start..start + 3].copy_from_slice(&v);
        put(block::POSITION, self.position_sd_m);
        put(block::VELOCITY, self.velocity_sd_m_s);
        put(block::ATTITUDE, self.attitude_sd_rad);
        put(block::GYRO_BIAS, [self.gyro_bias_sd_rad_s; 3]);
        put(block::ACCEL_BIAS, [self.accel_bias_sd_m_s2; 3]);
        put(block::GYRO_SCALE, [self.gyro_scale_sd; 3]);
        put(block::ACCEL_SCALE, [self.accel_scale_sd; 3]);
        SystemMatrix::from_diagonal(&nalgebra::SVector::from(sd.map(|s| s * s)))
    }
}

/// An estimate with no sensor correction at a navigation state.
pub fn uncorrected(nav: NavState) -> Estimate {
    Estimate {
        nav,
        sensors: SensorCorrection::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geo::gravity::normal_gravity_m_s2;

    // Closed form: a body at roll φ, pitch θ under gravity g senses
    // f = (g sin θ, −g sin φ cos θ, −g cos φ cos θ); levelling must return (φ, θ).
    #[test]
    fn levelling_recovers_roll_and_pitch() {
        let g = normal_gravity_m_s2(0.8, 0.0);
        for (roll, pitch) in [(0.0, 0.0), (0.2, -0.1), (-1.0, 0.7), (2.5, 0.3)] {
            let f = [
                g * f64::sin(pitch),
                -g * f64::sin(roll) * f64::cos(pitch),
                -g * f64::cos(roll) * f64::cos(pitch),
            ];
            let (r, p) = level(f);
            assert!((r - roll).abs() < 1e-12 && (p - pitch).abs() < 1e-12);
        }
    }
}
