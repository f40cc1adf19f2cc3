//! One strapdown step in NED (Savage 1998; Shin 2001 §2.2; Groves 2013 §5.4-5.5), from the
//! increments of the current and the previous sample (the two-sample corrections assume the
//! angular rate and specific force vary linearly over two intervals):
//!
//! 1. Velocity. The specific-force increment gets the rotation and sculling compensation
//!    Δv_b' = Δv + ½ Δθ × Δv + (1/12)(Δθ₋ × Δv + Δv₋ × Δθ), is resolved with the previous
//!    attitude corrected by half the navigation frame's rotation over the step,
//!    Δv_f = (I − ½[ζ×]) C_b^n Δv_b', ζ = (ω_ie + ω_en) dt, and the gravity / Coriolis
//!    increment Δv_g = (g − (2 ω_ie + ω_en) × v) dt uses position and velocity extrapolated to
//!    mid-interval.
//! 2. Position: latitude, longitude and height from the mean of the old and new velocity, with
//!    the radii at mid-interval.
//! 3. Attitude: the body rotation vector with coning compensation φ = Δθ + (1/12) Δθ₋ × Δθ, and
//!    the navigation frame's rotation ζ at mid-interval: C_b^n ← exp(−[ζ×]) C_b^n exp([φ×]).

use super::state::{Increment, NavState};
use crate::frames::{Ned, Vector};
use crate::geo::gravity::gravity_ned;
use crate::geo::position::Geodetic;

/// Advances `state` over `current` (the interval ending at `current.time`), using `previous`
/// (the interval before it) for the coning and sculling terms. For the first sample, pass the
/// current increment as `previous` as well (the correction terms then vanish).
pub fn mechanize(state: &NavState, previous: &Increment, current: &Increment) -> NavState {
    let dt = current.dt_s();
    let velocity = update_velocity(state, previous, current);
    let position = update_position(&state.position, &state.velocity, &velocity, dt);
    let mean_velocity = (state.velocity + velocity).scale(0.5);
    let zeta = frame_rotation(&state.position.midpoint(&position), &mean_velocity, dt);
    let phi = current.delta_angle.raw()
        + previous.delta_angle.raw().cross(&current.delta_angle.raw()) / 12.0;
    let attitude = state
        .attitude
        .rotated_by_rotation_vector(phi)
        .frame_rotated_by_rotation_vector(zeta);
    NavState {
        time: current.time,
        position,
        velocity,
        attitude,
    }
}

/// ω_in^n = ω_ie^n + ω_en^n at a position and velocity, rad/s.
pub fn navigation_frame_rate(position: &Geodetic, velocity: &Vector<Ned>) -> Vector<Ned> {
    position.earth_rate_ned() + position.transport_rate_ned(velocity)
}

/// ζ = ω_in^n dt, the navigation frame's rotation over a step, rad.
pub fn frame_rotation(
    position: &Geodetic,
    velocity: &Vector<Ned>,
    dt: f64,
) -> nalgebra::Vector3<f64> {
    navigation_frame_rate(position, velocity).scale(dt).raw()
}

/// The position half a step ahead along the current velocity (first order): where the
/// velocity update evaluates gravity, Coriolis and ζ.
pub fn mid_interval_position(state: &NavState, dt: f64) -> Geodetic {
    state.position.displaced(&state.velocity.scale(0.5 * dt))
}

/// The gravity and Coriolis part of the velocity increment, (g − (2 ω_ie + ω_en) × v) dt, at
/// the mid-interval position with the velocity at the start of the step.
pub fn gravity_coriolis_increment(
    mid: &Geodetic,
    velocity: &Vector<Ned>,
    dt: f64,
) -> nalgebra::Vector3<f64> {
    let omega_ie = mid.earth_rate_ned().raw();
    let omega_en = mid.transport_rate_ned(velocity).raw();
    let gravity = nalgebra::Vector3::from(gravity_ned(mid.latitude_rad, mid.height_m));
    (gravity - (2.0 * omega_ie + omega_en).cross(&velocity.raw())) * dt
}

fn update_velocity(state: &NavState, previous: &Increment, current: &Increment) -> Vector<Ned> {
    let dt = current.dt_s();
    let (dth, dv) = (current.delta_angle.raw(), current.delta_velocity.raw());
    let (dth0, dv0) = (previous.delta_angle.raw(), previous.delta_velocity.raw());
    let compensated = dv + 0.5 * dth.cross(&dv) + (dth0.cross(&dv) + dv0.cross(&dth)) / 12.0;
    let mid = mid_interval_position(state, dt);
    let zeta = frame_rotation(&mid, &state.velocity, dt);
    let resolved = (state.attitude * Vector::from_raw(compensated)).raw();
    let specific_force_part = resolved - 0.5 * zeta.cross(&resolved);
    Vector::from_raw(
        state.velocity.raw()
            + specific_force_part
            + gravity_coriolis_increment(&mid, &state.velocity, dt),
    )
}

/// The position update of [`mechanize`]: latitude, longitude and height from the mean of the
/// old and new NED velocity, with the radii at mid-interval. Trajectory generators integrate
/// positions with this same rule so that the ideal IMU inverts the mechanization exactly.
pub fn update_position(
    position: &Geodetic,
    v_old: &Vector<Ned>,
    v_new: &Vector<Ned>,
    dt: f64,
) -> Geodetic {
    let mean = (*v_old + *v_new).scale(0.5);
    let height_m = position.height_m - mean.z() * dt;
    let mid_height = 0.5 * (position.height_m + height_m);
    let rn = crate::geo::position::meridian_radius_m(position.latitude_rad) + mid_height;
    let latitude_rad = position.latitude_rad + mean.x() / rn * dt;
    let mid_lat = 0.5 * (position.latitude_rad + latitude_rad);
    let re = crate::geo::position::transverse_radius_m(mid_lat) + mid_height;
    let longitude_rad = position.longitude_rad + mean.y() / (re * mid_lat.cos()) * dt;
    Geodetic {
        latitude_rad,
        longitude_rad,
        height_m,
    }
}
