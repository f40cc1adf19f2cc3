//! GNSS measurement models: antenna position and velocity at a lever arm, and the heading of
//! a dual-antenna baseline, each as a nonlinear prediction from an [`Estimate`] (for the UKF)
//! and as a residual with its Jacobian in the error state (for the EKF).
//!
//! With Ĉ = (I − [φ×]) C and δr = r̂ − r:
//! - position: r̂_a = r̂ + Ĉ l ⇒ r̂_a − r_a = δr + [(Ĉl)×] φ;
//! - velocity: v̂_a = v̂ + Ĉ(ω̂ × l) ⇒ v̂_a − v_a = δv + [(Ĉ(ω̂×l))×] φ − Ĉ[l×] δb_g
//!   − Ĉ[l×] diag(ω̂) δs_g (the transport term ω_in × (C l), below 1 mm/s for metre lever
//!   arms, is left out of both the prediction and the Jacobian);
//! - heading of the baseline b^n = Ĉ b: ψ = atan2(b_E, b_N), and δψ = (b_N b_D φ_N +
//!   b_E b_D φ_E − (b_N² + b_E²) φ_D) / (b_N² + b_E²), which is −φ_D for a level baseline.

use super::error_state::Estimate;
use crate::frames::{Body, Ned, Vector, skew_matrix};
use crate::geo::position::Geodetic;
use crate::ins::error_model::{STATES, block};
use crate::units::wrap_pi;
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};
use serde::{Deserialize, Serialize};

/// Antenna set-up in the body frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AntennaGeometry {
    /// Primary antenna phase centre relative to the IMU, body axes (forward, right, down), m.
    pub lever_arm_body_m: [f64; 3],
    /// Direction of the dual-antenna baseline in body axes (primary to secondary); the
    /// receiver's heading is this vector's azimuth. Forward (1, 0, 0) when the heading is the
    /// vehicle's.
    pub baseline_body: [f64; 3],
}

impl Default for AntennaGeometry {
    /// Antenna at the IMU, baseline along the body x axis.
    fn default() -> Self {
        Self {
            lever_arm_body_m: [0.0; 3],
            baseline_body: [1.0, 0.0, 0.0],
        }
    }
}

/// The kinds of GNSS measurement.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, serde::Deserialize,
)]
#[serde(rename_all = "snake_case")]
pub enum MeasurementKind {
    /// Antenna position (3).
    Position,
    /// Antenna velocity (3).
    Velocity,
    /// Dual-antenna heading (1).
    Heading,
}

impl MeasurementKind {
    /// Every kind, in the order of its discriminant.
    pub const ALL: [MeasurementKind; 3] = [
        MeasurementKind::Position,
        MeasurementKind::Velocity,
        MeasurementKind::Heading,
    ];

    /// Dimension of the measurement.
    pub fn dimension(self) -> usize {
        match self {
            MeasurementKind::Position | MeasurementKind::Velocity => 3,
            MeasurementKind::Heading => 1,
        }
    }

    /// Name used in outputs.
    pub fn name(self) -> &'static str {
        match self {
            MeasurementKind::Position => "position",
            MeasurementKind::Velocity => "velocity",
            MeasurementKind::Heading => "heading",
        }
    }
}

/// The antenna position of an estimate.
pub fn antenna_position(e: &Estimate, geometry: &AntennaGeometry) -> Geodetic {
    let lever = e.nav.attitude * Vector::<Body>::from_array(geometry.lever_arm_body_m);
    e.nav.position.displaced(&lever)
}

/// The antenna velocity of an estimate turning at body rate `rate_b` (rad/s, corrected), m/s.
pub fn antenna_velocity(
    e: &Estimate,
    geometry: &AntennaGeometry,
    rate_b: &Vector3<f64>,
) -> Vector<Ned> {
    let lever = Vector3::from(geometry.lever_arm_body_m);
    e.nav.velocity + e.nav.attitude * Vector::<Body>::from_raw(rate_b.cross(&lever))
}

/// The azimuth of the antenna baseline, rad, in (−π, π].
pub fn baseline_heading(e: &Estimate, geometry: &AntennaGeometry) -> f64 {
    let b = (e.nav.attitude * Vector::<Body>::from_array(geometry.baseline_body)).to_array();
    b[1].atan2(b[0])
}

/// A linearised measurement: residual y = ẑ − z (predicted minus measured) and its Jacobian
/// H with y ≈ H δx + noise, and the noise covariance R.
#[derive(Debug, Clone, PartialEq)]
pub struct Linearized<const M: usize> {
    /// Predicted minus measured.
    pub residual: SVector<f64, M>,
    /// ∂y/∂δx.
    pub jacobian: SMatrix<f64, M, STATES>,
    /// Measurement noise covariance.
    pub noise: SMatrix<f64, M, M>,
}

/// Position residual and Jacobian for a measured antenna position with NED standard
/// deviations `sd_m`.
pub fn position_linearized(
    e: &Estimate,
    geometry: &AntennaGeometry,
    measured: &Geodetic,
    sd_m: [f64; 3],
) -> Linearized<3> {
    let predicted = antenna_position(e, geometry);
    let residual = predicted.ned_from(measured).raw();
    let lever_n = e.nav.attitude.to_matrix3() * Vector3::from(geometry.lever_arm_body_m);
    let mut h = SMatrix::<f64, 3, STATES>::zeros();
    h.fixed_view_mut::<3, 3>(0, block::POSITION)
        .copy_from(&Matrix3::identity());
    h.fixed_view_mut::<3, 3>(0, block::ATTITUDE)
        .copy_from(&skew_matrix(&lever_n));
    Linearized {
        residual,
        jacobian: h,
        noise: Matrix3::from_diagonal(&Vector3::from(sd_m.map(|s| s * s))),
    }
}

/// Velocity residual and Jacobian for a measured antenna velocity.
pub fn velocity_linearized(
    e: &Estimate,
    geometry: &AntennaGeometry,
    rate_b: &Vector3<f64>,
    measured: &Vector3<f64>,
    sd_m_s: [f64; 3],
) -> Linearized<3> {
    let c = e.nav.attitude.to_matrix3();
    let lever = Vector3::from(geometry.lever_arm_body_m);
    let residual = antenna_velocity(e, geometry, rate_b).raw() - measured;
    let mut h = SMatrix::<f64, 3, STATES>::zeros();
    h.fixed_view_mut::<3, 3>(0, block::VELOCITY)
        .copy_from(&Matrix3::identity());
    h.fixed_view_mut::<3, 3>(0, block::ATTITUDE)
        .copy_from(&skew_matrix(&(c * rate_b.cross(&lever))));
    h.fixed_view_mut::<3, 3>(0, block::GYRO_BIAS)
        .copy_from(&(-c * skew_matrix(&lever)));
    h.fixed_view_mut::<3, 3>(0, block::GYRO_SCALE)
        .copy_from(&(-c * skew_matrix(&lever) * Matrix3::from_diagonal(rate_b)));
    Linearized {
        residual,
        jacobian: h,
        noise: Matrix3::from_diagonal(&Vector3::from(sd_m_s.map(|s| s * s))),
    }
}

/// Heading residual (wrapped to (−π, π]) and Jacobian for a measured baseline azimuth.
pub fn heading_linearized(
    e: &Estimate,
    geometry: &AntennaGeometry,
    measured_rad: f64,
    sd_rad: f64,
) -> Linearized<1> {
    let b = e.nav.attitude.to_matrix3() * Vector3::from(geometry.baseline_body);
    let rho2 = b.x * b.x + b.y * b.y;
    let mut h = SMatrix::<f64, 1, STATES>::zeros();
    h[(0, block::ATTITUDE)] = b.x * b.z / rho2;
    h[(0, block::ATTITUDE + 1)] = b.y * b.z / rho2;
    h[(0, block::ATTITUDE + 2)] = -1.0;
    Linearized {
        residual: SVector::<f64, 1>::new(wrap_pi(baseline_heading(e, geometry) - measured_rad)),
        jacobian: h,
        noise: SMatrix::<f64, 1, 1>::new(sd_rad * sd_rad),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nav::error_state::{ErrorVector, sample_estimate};

    // Each analytic Jacobian equals the central finite difference of the nonlinear
    // prediction under e ⊕ δx (an independent computation). Positions pass through ECEF
    // (~6.4e6 m, rounding ~1e-9 m), so the step is 1e-3 (rounding error ~4e-7 in the
    // quotient); central differences of the rotated lever arm err by |l| step²/6 ≈ 5e-7.
    // Hence the 2e-6 tolerance.
    #[test]
    fn jacobians_match_finite_differences() {
        let e = sample_estimate();
        let g = AntennaGeometry {
            lever_arm_body_m: [0.8, -0.4, -2.5],
            baseline_body: [0.9, 0.3, 0.2],
        };
        let rate = Vector3::new(0.05, -0.02, 0.1);
        let measured = antenna_position(&e, &g);
        let v_meas = antenna_velocity(&e, &g, &rate).raw();
        let psi = baseline_heading(&e, &g);
        let lin_p = position_linearized(&e, &g, &measured, [1.0; 3]);
        let lin_v = velocity_linearized(&e, &g, &rate, &v_meas, [0.1; 3]);
        let lin_h = heading_linearized(&e, &g, psi, 0.01);
        assert!(lin_p.residual.amax() < 1e-9 && lin_v.residual.amax() < 1e-12);
        let step = 1e-3;
        for i in 0..STATES {
            let mut dx = ErrorVector::zeros();
            dx[i] = step;
            let (up, down) = (e.corrected_by(&dx), e.corrected_by(&(-dx)));
            // The filter's ⊕ subtracts position and velocity errors, so the prediction for
            // the estimate is the truth plus H δx: prediction(truth) = prediction(e ⊕ δx).
            let dp = (antenna_position(&down, &g).ned_from(&measured).raw()
                - antenna_position(&up, &g).ned_from(&measured).raw())
                / (2.0 * step);
            // The gyro states enter the velocity through the corrected rate ω̂ = ω + δb + diag(ω) δs.
            let rate_of = |x: &Estimate| {
                Vector3::from_fn(|k, _| {
                    rate[k]
                        - (x.sensors.gyro_bias_rad_s[k] - e.sensors.gyro_bias_rad_s[k])
                        - rate[k] * (x.sensors.gyro_scale[k] - e.sensors.gyro_scale[k])
                })
            };
            let dv = (antenna_velocity(&down, &g, &rate_of(&down)).raw()
                - antenna_velocity(&up, &g, &rate_of(&up)).raw())
                / (2.0 * step);
            let dh =
                wrap_pi(baseline_heading(&down, &g) - baseline_heading(&up, &g)) / (2.0 * step);
            for r in 0..3 {
                assert!(
                    (dp[r] - lin_p.jacobian[(r, i)]).abs() < 2e-6,
                    "position row {r} state {i}"
                );
                assert!(
                    (dv[r] - lin_v.jacobian[(r, i)]).abs() < 2e-6,
                    "velocity row {r} state {i}: {} vs {}",
                    dv[r],
                    lin_v.jacobian[(r, i)]
                );
            }
            assert!(
                (dh - lin_h.jacobian[(0, i)]).abs() < 2e-6,
                "heading state {i}"
            );
        }
    }
}
