//! The 21-state error model of the strapdown solution (psi-angle form in NED; Shin 2001 §3,
//! Groves 2013 §14.2), used by the EKF's covariance propagation:
//!
//! δx = [δr (north, east, down position error, m), δv (m/s), φ (attitude error, rad),
//!       b_g (rad/s), b_a (m/s²), s_g, s_a (scale-factor errors, dimensionless)].
//!
//! Conventions: the estimated attitude is Ĉ_b^n = (I − [φ×]) C_b^n; the IMU error model is
//! ω̃ = (1 + s_g) ω + b_g + noise, f̃ = (1 + s_a) f + b_a + noise, per axis; biases and scale
//! factors are first-order Gauss-Markov states with correlation times from the model bank.
//! δṙ = F_rr δr + δv; δv̇ = F_vr δr + F_vv δv + [f^n×] φ + C_b^n (b_a + diag(f^b) s_a) + w_v;
//! φ̇ = F_φr δr + F_φv δv − [ω_in^n×] φ − C_b^n (b_g + diag(ω_ib^b) s_g) + w_φ.
//! The analytic blocks are checked against a finite-difference Jacobian of the nonlinear
//! navigation equations in the tests.

use super::state::NavState;
use crate::frames::{Body, Vector, skew_matrix};
use crate::geo::position::{meridian_radius_m, transverse_radius_m};
use crate::geo::wgs84::EARTH_RATE_RAD_S;
use nalgebra::{Matrix3, SMatrix, Vector3};

/// Number of error states.
pub const STATES: usize = 21;
/// The 21 × 21 system matrix.
pub type SystemMatrix = SMatrix<f64, STATES, STATES>;

/// Offsets of the state blocks.
pub mod block {
    /// Position error, m (north, east, down).
    pub const POSITION: usize = 0;
    /// Velocity error, m/s.
    pub const VELOCITY: usize = 3;
    /// Attitude error φ, rad.
    pub const ATTITUDE: usize = 6;
    /// Gyro bias, rad/s.
    pub const GYRO_BIAS: usize = 9;
    /// Accelerometer bias, m/s².
    pub const ACCEL_BIAS: usize = 12;
    /// Gyro scale factor (dimensionless).
    pub const GYRO_SCALE: usize = 15;
    /// Accelerometer scale factor (dimensionless).
    pub const ACCEL_SCALE: usize = 18;
}

/// Correlation times of the six Gauss-Markov error groups, per axis, s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CorrelationTimes {
    /// Gyro bias, per axis.
    pub gyro_bias_s: [f64; 3],
    /// Accelerometer bias, per axis.
    pub accel_bias_s: [f64; 3],
    /// Gyro scale factor, per axis.
    pub gyro_scale_s: [f64; 3],
    /// Accelerometer scale factor, per axis.
    pub accel_scale_s: [f64; 3],
}

fn put(f: &mut SystemMatrix, row: usize, col: usize, m: &Matrix3<f64>) {
    f.fixed_view_mut::<3, 3>(row, col).copy_from(m);
}

/// The system matrix F at a state, with the measured (corrected) angular rate ω_ib^b and
/// specific force f^b of the current interval.
pub fn system_matrix(
    state: &NavState,
    rate_b: &Vector<Body>,
    force_b: &Vector<Body>,
    tc: &CorrelationTimes,
) -> SystemMatrix {
    use block::*;
    let mut f = SystemMatrix::zeros();
    let k = Kinematic::new(state);
    let c_bn = state.attitude.to_matrix3();
    let force_n = c_bn * force_b.raw();
    put(&mut f, POSITION, POSITION, &k.f_rr());
    put(&mut f, POSITION, VELOCITY, &Matrix3::identity());
    put(&mut f, VELOCITY, POSITION, &k.f_vr());
    put(&mut f, VELOCITY, VELOCITY, &k.f_vv());
    put(&mut f, VELOCITY, ATTITUDE, &skew_matrix(&force_n));
    put(&mut f, ATTITUDE, POSITION, &k.f_phi_r());
    put(&mut f, ATTITUDE, VELOCITY, &k.f_phi_v());
    put(&mut f, ATTITUDE, ATTITUDE, &(-skew_matrix(&k.omega_in())));
    put(&mut f, VELOCITY, ACCEL_BIAS, &c_bn);
    put(
        &mut f,
        VELOCITY,
        ACCEL_SCALE,
        &(c_bn * Matrix3::from_diagonal(&force_b.raw())),
    );
    put(&mut f, ATTITUDE, GYRO_BIAS, &(-c_bn));
    put(
        &mut f,
        ATTITUDE,
        GYRO_SCALE,
        &(-c_bn * Matrix3::from_diagonal(&rate_b.raw())),
    );
    let groups = [
        (GYRO_BIAS, tc.gyro_bias_s),
        (ACCEL_BIAS, tc.accel_bias_s),
        (GYRO_SCALE, tc.gyro_scale_s),
        (ACCEL_SCALE, tc.accel_scale_s),
    ];
    for (start, times) in groups {
        for axis in 0..3 {
            f[(start + axis, start + axis)] = -1.0 / times[axis];
        }
    }
    f
}

/// Latitude, height, velocity and radii of a state, with the blocks built from them.
struct Kinematic {
    lat: f64,
    rm: f64,
    rn: f64,
    v: Vector3<f64>,
    gravity: f64,
    /// ∂γ/∂φ, m/s² per rad: normal gravity grows towards the poles, so a north position error
    /// is also a vertical specific-force error (a term KF-GINS-style models drop; the
    /// mechanization keeps it, so the model does too).
    gravity_latitude_gradient: f64,
}

impl Kinematic {
    fn new(state: &NavState) -> Self {
        let lat = state.position.latitude_rad;
        let h = state.position.height_m;
        Self {
            lat,
            rm: meridian_radius_m(lat) + h,
            rn: transverse_radius_m(lat) + h,
            v: state.velocity.raw(),
            gravity: crate::geo::gravity::normal_gravity_m_s2(lat, h),
            gravity_latitude_gradient: {
                let d = 1e-5;
                let g = |l: f64| crate::geo::gravity::normal_gravity_m_s2(l, h);
                (g(lat + d) - g(lat - d)) / (2.0 * d)
            },
        }
    }

    fn omega_in(&self) -> Vector3<f64> {
        let (s, c) = self.lat.sin_cos();
        let (vn, ve) = (self.v.x, self.v.y);
        Vector3::new(
            EARTH_RATE_RAD_S * c + ve / self.rn,
            -vn / self.rm,
            -EARTH_RATE_RAD_S * s - ve * self.lat.tan() / self.rn,
        )
    }

    fn f_rr(&self) -> Matrix3<f64> {
        let (vn, ve, vd) = (self.v.x, self.v.y, self.v.z);
        let t = self.lat.tan();
        Matrix3::new(
            -vd / self.rm,
            0.0,
            vn / self.rm,
            ve * t / self.rn,
            -(vd + vn * t) / self.rn,
            ve / self.rn,
            0.0,
            0.0,
            0.0,
        )
    }

    fn f_vr(&self) -> Matrix3<f64> {
        let (vn, ve, vd) = (self.v.x, self.v.y, self.v.z);
        let (s, c) = self.lat.sin_cos();
        let t = self.lat.tan();
        let sec2 = 1.0 / (c * c);
        let (rm, rn, w) = (self.rm, self.rn, EARTH_RATE_RAD_S);
        let gp = self.gravity;
        Matrix3::new(
            -2.0 * ve * w * c / rm - ve * ve * sec2 / (rm * rn),
            0.0,
            vn * vd / (rm * rm) - ve * ve * t / (rn * rn),
            2.0 * w * (vn * c - vd * s) / rm + vn * ve * sec2 / (rm * rn),
            0.0,
            (ve * vd + vn * ve * t) / (rn * rn),
            2.0 * w * ve * s / rm + self.gravity_latitude_gradient / rm,
            0.0,
            -ve * ve / (rn * rn) - vn * vn / (rm * rm) + 2.0 * gp / ((rm * rn).sqrt()),
        )
    }

    fn f_vv(&self) -> Matrix3<f64> {
        let (vn, ve, vd) = (self.v.x, self.v.y, self.v.z);
        let (s, c) = self.lat.sin_cos();
        let t = self.lat.tan();
        let (rm, rn, w) = (self.rm, self.rn, EARTH_RATE_RAD_S);
        Matrix3::new(
            vd / rm,
            -2.0 * (w * s + ve * t / rn),
            vn / rm,
            2.0 * w * s + ve * t / rn,
            (vd + vn * t) / rn,
            2.0 * w * c + ve / rn,
            -2.0 * vn / rm,
            -2.0 * (w * c + ve / rn),
            0.0,
        )
    }

    fn f_phi_r(&self) -> Matrix3<f64> {
        let (vn, ve) = (self.v.x, self.v.y);
        let (s, c) = self.lat.sin_cos();
        let t = self.lat.tan();
        let (rm, rn, w) = (self.rm, self.rn, EARTH_RATE_RAD_S);
        Matrix3::new(
            -w * s / rm,
            0.0,
            ve / (rn * rn),
            0.0,
            0.0,
            -vn / (rm * rm),
            -w * c / rm - ve / (c * c * rm * rn),
            0.0,
            -ve * t / (rn * rn),
        )
    }

    fn f_phi_v(&self) -> Matrix3<f64> {
        Matrix3::new(
            0.0,
            1.0 / self.rn,
            0.0,
            -1.0 / self.rm,
            0.0,
            0.0,
            0.0,
            -self.lat.tan() / self.rn,
            0.0,
        )
    }
}
