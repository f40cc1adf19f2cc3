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
//! ζ, the mid-interval position and Δv_g come from the same functions the mechanization uses, from the trajectory's
//! states, so the round trip is exact to rounding.

use super::motion::Trajectory;
use crate::frames::{Ned, Vector, skew_matrix};
use crate::ins::mechanization::{
    frame_rotation, gravity_coriolis_increment, mid_interval_position,
};
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

/// The increment that takes `before` to `after`, given the increment before it (`None` for the
/// first: the mechanization is then called with the current increment as the previous one).
fn invert_step(before: &NavState, after: &NavState, previous: Option<&Increment>) -> Increment {
    let span = after.time - before.time;
    let dt = span.as_seconds();
    let zeta_attitude = attitude_frame_rotation(before, after, dt);
    let relative = before.attitude.inverse().unit_quaternion()
        * nalgebra::UnitQuaternion::from_scaled_axis(zeta_attitude)
        * after.attitude.unit_quaternion();
    let phi = relative.scaled_axis();
    let delta_angle = match previous {
        Some(p) => solve(
            Matrix3::identity() + skew_matrix(&p.delta_angle.raw()) / 12.0,
            phi,
        ),
        None => phi,
    };
    let compensated = compensated_velocity_increment(before, after, dt);
    let delta_velocity = match previous {
        Some(p) => {
            let (dth0, dv0) = (p.delta_angle.raw(), p.delta_velocity.raw());
            let a =
                Matrix3::identity() + 0.5 * skew_matrix(&delta_angle) + skew_matrix(&dth0) / 12.0;
            solve(a, compensated - dv0.cross(&delta_angle) / 12.0)
        }
        None => solve(
            Matrix3::identity() + 0.5 * skew_matrix(&delta_angle),
            compensated,
        ),
    };
    Increment {
        time: after.time,
        dt: span,
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
    let mean_velocity = (before.velocity + after.velocity).scale(0.5);
    frame_rotation(
        &before.position.midpoint(&after.position),
        &mean_velocity,
        dt,
    )
}

/// Δv' in body axes: the compensated specific-force increment of the velocity update.
fn compensated_velocity_increment(before: &NavState, after: &NavState, dt: f64) -> Vector3<f64> {
    let mid = mid_interval_position(before, dt);
    let zeta = frame_rotation(&mid, &before.velocity, dt);
    let specific_force_part = after.velocity.raw()
        - before.velocity.raw()
        - gravity_coriolis_increment(&mid, &before.velocity, dt);
    let resolved = solve(
        Matrix3::identity() - 0.5 * skew_matrix(&zeta),
        specific_force_part,
    );
    (before.attitude.inverse() * Vector::<Ned>::from_raw(resolved)).raw()
}
