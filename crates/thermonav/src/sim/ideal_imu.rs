//! The ideal IMU of a trajectory: the increments that the project's own strapdown
//! mechanization turns back into that trajectory.
//!
//! Each step of [`mechanize`](crate::ins::mechanization::mechanize) is inverted exactly:
//! - attitude: C_k = exp(−[ζ×]) C_{k−1} exp([φ×]) gives φ = log(C_{k−1}ᵀ exp([ζ×]) C_k), and the
//!   coning relation φ = Δθ + (1/12) Δθ₋ × Δθ is a linear system (I + [Δθ₋×]/12) Δθ = φ;
//! - velocity: v_k = v_{k−1} + (I − ½[ζ×]) C_{k−1} Δv' + Δv_g gives Δv', and the sculling
//!   relation Δv' = Δv + ½ Δθ × Δv + (1/12)(Δθ₋ × Δv + Δv₋ × Δθ) is linear in Δv;
//! - position needs nothing: trajectories integrate it with the mechanization's own rule.
//!
//! ζ and Δv_g are computed by the same functions the mechanization uses, from the trajectory's
//! states, so the round trip is exact to rounding.

use super::motion::Trajectory;
use crate::frames::{Ned, Vector};
use crate::geo::gravity::gravity_ned;
use crate::geo::position::Geodetic;
use crate::ins::mechanization::navigation_frame_rate;
use crate::ins::state::{Increment, NavState};
use nalgebra::{Matrix3, Vector3};

/// Increments for every interval of the trajectory (one fewer than its states).
pub fn ideal_increments(trajectory: &Trajectory) -> Vec<Increment> {
    let mut increments: Vec<Increment> =
        Vec::with_capacity(trajectory.states.len().saturating_sub(1));
    for pair in trajectory.states.windows(2) {
        let previous = increments.last().copied();
        increments.push(invert_step(&pair[0], &pair[1], previous.as_ref()));
    }
    increments
}

fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// The increment that takes `before` to `after`, given the increment before it (`None` for the
/// first: the mechanization is then called with the current increment as the previous one).
fn invert_step(before: &NavState, after: &NavState, previous: Option<&Increment>) -> Increment {
    let dt = after.time.since(before.time).as_seconds();
    let zeta_attitude = attitude_frame_rotation(before, after, dt);
    let relative = before.attitude.inverse().unit_quaternion()
        * nalgebra::UnitQuaternion::from_scaled_axis(zeta_attitude)
        * after.attitude.unit_quaternion();
    let phi = relative.scaled_axis();
    let delta_angle = match previous {
        Some(p) => solve(Matrix3::identity() + skew(&p.delta_angle.raw()) / 12.0, phi),
        None => phi,
    };
    let compensated = compensated_velocity_increment(before, after, dt);
    let delta_velocity = match previous {
        Some(p) => {
            let (dth0, dv0) = (p.delta_angle.raw(), p.delta_velocity.raw());
            let a = Matrix3::identity() + 0.5 * skew(&delta_angle) + skew(&dth0) / 12.0;
            solve(a, compensated - dv0.cross(&delta_angle) / 12.0)
        }
        None => solve(Matrix3::identity() + 0.5 * skew(&delta_angle), compensated),
    };
    Increment {
        time: after.time,
        dt_s: dt,
        delta_angle: Vector::from_raw(delta_angle),
        delta_velocity: Vector::from_raw(delta_velocity),
    }
}

fn solve(a: Matrix3<f64>, b: Vector3<f64>) -> Vector3<f64> {
    // These matrices are the identity plus terms of the size of one increment (≪ 1): always
    // invertible for any physical motion.
    a.lu().solve(&b).unwrap_or(b)
}

/// ζ of the attitude update: the navigation-frame rotation at the mean of the two states.
fn attitude_frame_rotation(before: &NavState, after: &NavState, dt: f64) -> Vector3<f64> {
    let mid = Geodetic {
        latitude_rad: 0.5 * (before.position.latitude_rad + after.position.latitude_rad),
        longitude_rad: 0.5 * (before.position.longitude_rad + after.position.longitude_rad),
        height_m: 0.5 * (before.position.height_m + after.position.height_m),
    };
    let mean_velocity = (before.velocity + after.velocity).scale(0.5);
    navigation_frame_rate(&mid, &mean_velocity).scale(dt).raw()
}

/// Δv' in body axes: the compensated specific-force increment of the velocity update.
fn compensated_velocity_increment(before: &NavState, after: &NavState, dt: f64) -> Vector3<f64> {
    let rates = before.position.rates(&before.velocity);
    let half = 0.5 * dt;
    let mid = Geodetic {
        latitude_rad: before.position.latitude_rad + rates[0] * half,
        longitude_rad: before.position.longitude_rad + rates[1] * half,
        height_m: before.position.height_m + rates[2] * half,
    };
    let zeta = navigation_frame_rate(&mid, &before.velocity)
        .scale(dt)
        .raw();
    let omega_ie = mid.earth_rate_ned().raw();
    let omega_en = mid.transport_rate_ned(&before.velocity).raw();
    let gravity = Vector3::from(gravity_ned(mid.latitude_rad, mid.height_m));
    let coriolis = (2.0 * omega_ie + omega_en).cross(&before.velocity.raw());
    let specific_force_part =
        after.velocity.raw() - before.velocity.raw() - (gravity - coriolis) * dt;
    let resolved = solve(Matrix3::identity() - 0.5 * skew(&zeta), specific_force_part);
    (before.attitude.inverse() * Vector::<Ned>::from_raw(resolved)).raw()
}
