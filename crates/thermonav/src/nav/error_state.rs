//! The nominal estimate and the error vector between it and the truth.
//!
//! The filters estimate a 21-element error vector δx (layout in
//! [`crate::ins::error_model::block`]) around a nominal [`Estimate`]; after every update the
//! error is folded into the nominal ([`Estimate::corrected_by`], the ⊕ of the error-state
//! literature) and reset to zero (closed-loop feedback). [`Estimate::error_from`] is the
//! inverse (⊖), which the UKF uses to turn propagated sigma points back into errors.

use crate::frames::Vector;
use crate::ins::error_model::{STATES, block};
use crate::ins::state::{Increment, NavState};
use nalgebra::{SVector, UnitQuaternion, Vector3};
use serde::Serialize;

/// The 21-element error vector.
pub type ErrorVector = SVector<f64, STATES>;

/// Estimated sensor errors, removed from every raw increment before mechanization:
/// ω̂ = (ω̃ − b_g) / (1 + s_g), f̂ = (f̃ − b_a) / (1 + s_a), per axis.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct SensorCorrection {
    /// Gyro bias, rad/s.
    pub gyro_bias_rad_s: [f64; 3],
    /// Accelerometer bias, m/s².
    pub accel_bias_m_s2: [f64; 3],
    /// Gyro scale-factor error (dimensionless).
    pub gyro_scale: [f64; 3],
    /// Accelerometer scale-factor error (dimensionless).
    pub accel_scale: [f64; 3],
}

impl SensorCorrection {
    /// The raw increment with these errors removed.
    pub fn correct(&self, raw: &Increment) -> Increment {
        let dt_s = raw.dt_s();
        let fix = |delta: [f64; 3], bias: [f64; 3], scale: [f64; 3]| {
            std::array::from_fn(|k| (delta[k] - bias[k] * dt_s) / (1.0 + scale[k]))
        };
        Increment {
            time: raw.time,
            dt: raw.dt,
            delta_angle: Vector::from_array(fix(
                raw.delta_angle.to_array(),
                self.gyro_bias_rad_s,
                self.gyro_scale,
            )),
            delta_velocity: Vector::from_array(fix(
                raw.delta_velocity.to_array(),
                self.accel_bias_m_s2,
                self.accel_scale,
            )),
        }
    }

    /// A raw gyro rate (rad/s) with these errors removed: (ω̃ − b_g) / (1 + s_g), the rate form
    /// of [`SensorCorrection::correct`].
    pub fn corrected_rate(&self, raw_rate: &Vector3<f64>) -> Vector3<f64> {
        Vector3::from_fn(|k, _| {
            (raw_rate[k] - self.gyro_bias_rad_s[k]) / (1.0 + self.gyro_scale[k])
        })
    }

    fn groups_mut(&mut self) -> [(usize, &mut [f64; 3]); 4] {
        [
            (block::GYRO_BIAS, &mut self.gyro_bias_rad_s),
            (block::ACCEL_BIAS, &mut self.accel_bias_m_s2),
            (block::GYRO_SCALE, &mut self.gyro_scale),
            (block::ACCEL_SCALE, &mut self.accel_scale),
        ]
    }

    fn groups(&self) -> [(usize, [f64; 3]); 4] {
        [
            (block::GYRO_BIAS, self.gyro_bias_rad_s),
            (block::ACCEL_BIAS, self.accel_bias_m_s2),
            (block::GYRO_SCALE, self.gyro_scale),
            (block::ACCEL_SCALE, self.accel_scale),
        ]
    }
}

/// The nominal estimate: navigation state and sensor corrections.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// Position, velocity and attitude.
    pub nav: NavState,
    /// Estimated sensor errors.
    pub sensors: SensorCorrection,
}

fn part(dx: &ErrorVector, start: usize) -> Vector3<f64> {
    dx.fixed_rows::<3>(start).into_owned()
}

impl Estimate {
    /// The estimate corrected by the error δx (⊕): r ← r̂ − δr, v ← v̂ − δv,
    /// C ← exp([φ×]) Ĉ, sensor corrections += their errors.
    pub fn corrected_by(&self, dx: &ErrorVector) -> Estimate {
        let mut out = *self;
        out.nav.position = self
            .nav
            .position
            .displaced(&Vector::from_raw(-part(dx, block::POSITION)));
        out.nav.velocity = self.nav.velocity - Vector::from_raw(part(dx, block::VELOCITY));
        out.nav.attitude = self
            .nav
            .attitude
            .frame_rotated_by_rotation_vector(-part(dx, block::ATTITUDE));
        for (start, values) in out.sensors.groups_mut() {
            for (k, v) in values.iter_mut().enumerate() {
                *v += dx[start + k];
            }
        }
        out
    }

    /// The error δx with `reference.corrected_by(δx) = self` (⊖, exact to rounding: the
    /// position part inverts [`crate::geo::position::Geodetic::displaced`]).
    pub fn error_from(&self, reference: &Estimate) -> ErrorVector {
        let mut dx = ErrorVector::zeros();
        let dr = -self.nav.position.offset_from(&reference.nav.position).raw();
        let dv = reference.nav.velocity.raw() - self.nav.velocity.raw();
        let rotation: UnitQuaternion<f64> = self.nav.attitude.unit_quaternion()
            * reference.nav.attitude.unit_quaternion().inverse();
        dx.fixed_rows_mut::<3>(block::POSITION).copy_from(&dr);
        dx.fixed_rows_mut::<3>(block::VELOCITY).copy_from(&dv);
        dx.fixed_rows_mut::<3>(block::ATTITUDE)
            .copy_from(&rotation.scaled_axis());
        let (own, theirs) = (self.sensors.groups(), reference.sensors.groups());
        for ((start, a), (_, b)) in own.iter().zip(theirs.iter()) {
            for k in 0..3 {
                dx[start + k] = a[k] - b[k];
            }
        }
        dx
    }
}

/// A moving, turned, biased estimate for unit tests.
#[cfg(test)]
pub(crate) fn sample_estimate() -> Estimate {
    use crate::frames::Rotation;
    use crate::geo::position::Geodetic;
    use crate::time::Timestamp;
    Estimate {
        nav: NavState {
            time: Timestamp::from_nanos(0),
            position: Geodetic::from_degrees(51.0, -114.0, 1100.0),
            velocity: Vector::new(3.0, -1.0, 0.2),
            attitude: Rotation::from_euler_zyx(0.05, -0.02, 2.0),
        },
        sensors: SensorCorrection {
            gyro_bias_rad_s: [1e-3, -2e-3, 5e-4],
            accel_bias_m_s2: [0.02, -0.01, 0.03],
            gyro_scale: [1e-4, 0.0, -2e-4],
            accel_scale: [0.0, 3e-4, 1e-4],
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::time::{Duration, Timestamp};

    fn estimate() -> Estimate {
        sample_estimate()
    }

    // ⊖ inverts ⊕: (x ⊕ δx) ⊖ x = δx to rounding (1e-12 relative to each part's size;
    // positions pass through radians of latitude, ~1e-16 × 6.4e6 m ≈ 1e-9 m).
    #[test]
    fn error_from_inverts_corrected_by() {
        let x = estimate();
        let dx = ErrorVector::from_fn(|i, _| {
            0.1 * ((i as f64) * 1.7).sin() * 10f64.powi(-(i as i32 / 9))
        });
        let back = x.corrected_by(&dx).error_from(&x);
        for i in 0..STATES {
            let tolerance = if i < 3 { 1e-8 } else { 1e-12 };
            assert!(
                (back[i] - dx[i]).abs() < tolerance,
                "state {i}: {} vs {}",
                back[i],
                dx[i]
            );
        }
    }

    // An attitude error φ = (0, 0, ε) means the estimate's yaw is ε too small
    // (Ĉ = (I − [φ×]) C): correcting adds ε to the yaw.
    #[test]
    fn attitude_correction_follows_the_psi_angle_convention() {
        let x = estimate();
        let mut dx = ErrorVector::zeros();
        dx[block::ATTITUDE + 2] = 0.01;
        let (_, _, yaw0) = x.nav.attitude.euler_zyx();
        let (_, _, yaw1) = x.corrected_by(&dx).nav.attitude.euler_zyx();
        assert!((yaw1 - yaw0 - 0.01).abs() < 1e-9);
    }

    // Correction removes bias then scale: a raw rate (1 + s) ω + b comes back as ω.
    #[test]
    fn correction_undoes_bias_and_scale() {
        let c = estimate().sensors;
        let (w, f, dt) = ([0.3, -0.2, 0.1], [0.5, 0.1, -9.8], 0.005);
        let raw = Increment::from_rates(
            Timestamp::from_nanos(5_000_000),
            Duration::from_nanos(5_000_000),
            std::array::from_fn(|k| (1.0 + c.gyro_scale[k]) * w[k] + c.gyro_bias_rad_s[k]),
            std::array::from_fn(|k| (1.0 + c.accel_scale[k]) * f[k] + c.accel_bias_m_s2[k]),
        );
        let out = c.correct(&raw);
        for k in 0..3 {
            assert!((out.delta_angle.to_array()[k] - w[k] * dt).abs() < 1e-15);
            assert!((out.delta_velocity.to_array()[k] - f[k] * dt).abs() < 1e-15);
        }
    }
}
