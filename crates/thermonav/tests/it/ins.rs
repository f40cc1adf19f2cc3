//! Strapdown mechanization against closed-form motion.

use thermonav::frames::{Body, Ned, Rotation, Vector};
use thermonav::geo::gravity::gravity_ned;
use thermonav::geo::position::Geodetic;
use thermonav::ins::mechanization::mechanize;
use thermonav::ins::state::{Increment, NavState};
use thermonav::time::{Duration, Timestamp};

/// A perfect stationary IMU at a tilted, turned attitude: gyros read the Earth rate and the
/// accelerometers the negative of normal gravity, both resolved in the body frame.
#[test]
fn a_stationary_imu_with_perfect_data_stays_put_for_an_hour() {
    let position = Geodetic::from_degrees(51.08, -114.13, 1100.0);
    let attitude = Rotation::<Body, Ned>::from_euler_zyx(0.03, -0.05, 0.7);
    let to_body = attitude.inverse();
    let rate = (to_body * position.earth_rate_ned()).to_array();
    let gravity = Vector::<Ned>::from_array(gravity_ned(position.latitude_rad, position.height_m));
    let force = (to_body * -gravity).to_array();
    let dt = Duration::from_nanos(5_000_000);
    let mut state = NavState {
        time: Timestamp::from_nanos(0),
        position,
        velocity: Vector::zeros(),
        attitude,
    };
    let mut previous = Increment::from_rates(Timestamp::from_nanos(0), dt, rate, force);
    for k in 1..=720_000_i64 {
        let current = Increment::from_rates(Timestamp::from_nanos(k * 5_000_000), dt, rate, force);
        state = mechanize(&state, &previous, &current);
        previous = current;
    }
    // Closed form: nothing moves. The requirement is millimetres over an hour; the bound is
    // 1 mm horizontally and vertically, 1 µm/s in velocity, 1e-9 rad in attitude.
    let drift = state.position.ned_from(&position);
    assert!(drift.norm() < 1e-3, "drift {:?} m", drift.to_array());
    assert!(
        state.velocity.norm() < 1e-6,
        "velocity {:?}",
        state.velocity.to_array()
    );
    assert!(state.attitude.angle_to(&attitude) < 1e-9);
    assert_eq!(state.time.as_nanos(), 3_600_000_000_000);
}
