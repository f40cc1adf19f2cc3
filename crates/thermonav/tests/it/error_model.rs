//! The 21-state system matrix F against the nonlinear navigation itself: a small initial error
//! (or sensor error) propagated by two mechanizations, perturbed and unperturbed, must match
//! the linear propagation Φ = Π (I + F dt) to first order.

use nalgebra::{Matrix3, SVector, Vector3};
use thermonav::frames::{Body, Ned, Rotation, Vector};
use thermonav::geo::position::{meridian_radius_m, transverse_radius_m};
use thermonav::ins::error_model::{CorrelationTimes, STATES, system_matrix};
use thermonav::ins::mechanization::mechanize;
use thermonav::ins::state::{Increment, NavState};
use thermonav::sim::ideal_imu::ideal_increments;
use thermonav::sim::motion::{
    MotionDefinition, MotionSegment, PitchModel, StartPoint, WaveMotion, generate_trajectory,
};

type State = SVector<f64, STATES>;

fn motion() -> MotionDefinition {
    let seg = |duration_s: f64, acceleration_m_s2: f64, turn_deg_s: f64, climb_rate_m_s: f64| {
        MotionSegment {
            duration_s,
            acceleration_m_s2,
            turn_rate_rad_s: turn_deg_s.to_radians(),
            climb_rate_m_s,
        }
    };
    MotionDefinition {
        start: StartPoint {
            lat_deg: 45.0,
            lon_deg: 7.0,
            h_m: 300.0,
        },
        initial_speed_m_s: 15.0,
        initial_heading_rad: 0.4,
        segments: vec![seg(12.0, 0.8, 8.0, 0.5)],
        waves: WaveMotion::default(),
        pitch: PitchModel::FollowsPath,
    }
}

/// Error of `estimate` relative to `truth` in the filter's convention.
fn error_of(estimate: &NavState, truth: &NavState) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let (lat, h) = (truth.position.latitude_rad, truth.position.height_m);
    let dr = Vector3::new(
        (meridian_radius_m(lat) + h)
            * (estimate.position.latitude_rad - truth.position.latitude_rad),
        (transverse_radius_m(lat) + h)
            * lat.cos()
            * (estimate.position.longitude_rad - truth.position.longitude_rad),
        -(estimate.position.height_m - truth.position.height_m),
    );
    let dv = (estimate.velocity - truth.velocity).raw();
    // Ĉ = (I − [φ×]) C  ⇒  [φ×] = I − Ĉ Cᵀ (small angles): read φ off the antisymmetric part.
    let c_hat = Matrix3::from_fn(|r, c| estimate.attitude.matrix()[r][c]);
    let c = Matrix3::from_fn(|r, col| truth.attitude.matrix()[r][col]);
    let m = Matrix3::identity() - c_hat * c.transpose();
    let phi = Vector3::new(
        m[(2, 1)] - m[(1, 2)],
        m[(0, 2)] - m[(2, 0)],
        m[(1, 0)] - m[(0, 1)],
    ) / 2.0;
    (dr, dv, phi)
}

/// The truth with an initial navigation error applied.
fn perturbed(truth: &NavState, dx: &State) -> NavState {
    let position = truth
        .position
        .displaced(&Vector::<Ned>::new(dx[0], dx[1], dx[2]));
    let velocity = truth.velocity + Vector::<Ned>::new(dx[3], dx[4], dx[5]);
    // Ĉ = (I − [φ×]) C ≈ exp(−[φ×]) C: rotate the navigation axes by φ.
    let attitude: Rotation<Body, Ned> = truth
        .attitude
        .frame_rotated_by_rotation_vector(Vector3::new(dx[6], dx[7], dx[8]));
    NavState {
        time: truth.time,
        position,
        velocity,
        attitude,
    }
}

/// An increment as a sensor with biases and scale errors (state components 9..21) reports it.
fn corrupted(inc: &Increment, dx: &State) -> Increment {
    let dt = inc.dt_s();
    let gyro = inc.delta_angle.raw();
    let accel = inc.delta_velocity.raw();
    let angle = Vector3::from_fn(|i, _| gyro[i] * (1.0 + dx[15 + i]) + dx[9 + i] * dt);
    let velocity = Vector3::from_fn(|i, _| accel[i] * (1.0 + dx[18 + i]) + dx[12 + i] * dt);
    Increment {
        delta_angle: Vector::from_raw(angle),
        delta_velocity: Vector::from_raw(velocity),
        ..*inc
    }
}

#[test]
fn system_matrix_propagates_errors_like_the_mechanization() {
    let trajectory = generate_trajectory(&motion(), 100.0).unwrap();
    let increments = ideal_increments(&trajectory);
    let steps = 1000; // 10 s
    let tc = CorrelationTimes {
        gyro_bias_s: [300.0; 3],
        accel_bias_s: [200.0; 3],
        gyro_scale_s: [1000.0; 3],
        accel_scale_s: [1000.0; 3],
    };
    // Φ = Π (I + F_k dt) along the truth, with the true rates of each interval.
    let mut transition = nalgebra::SMatrix::<f64, STATES, STATES>::identity();
    for (inc, state) in increments.iter().zip(&trajectory.states).take(steps) {
        let rate = Vector::<Body>::from_raw(inc.delta_angle.raw() / inc.dt_s());
        let force = Vector::<Body>::from_raw(inc.delta_velocity.raw() / inc.dt_s());
        let f = system_matrix(state, &rate, &force, &tc);
        transition =
            (nalgebra::SMatrix::<f64, STATES, STATES>::identity() + f * inc.dt_s()) * transition;
    }
    // Perturbation sizes: small enough for first order, large enough above rounding.
    let sizes = [
        50.0, 50.0, 50.0, 0.05, 0.05, 0.05, 2e-4, 2e-4, 2e-4, 2e-5, 2e-5, 2e-5, 2e-3, 2e-3, 2e-3,
        1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3,
    ];
    let names = [
        "dr_n", "dr_e", "dr_d", "dv_n", "dv_e", "dv_d", "phi_n", "phi_e", "phi_d", "bg_x", "bg_y",
        "bg_z", "ba_x", "ba_y", "ba_z", "sg_x", "sg_y", "sg_z", "sa_x", "sa_y", "sa_z",
    ];
    for j in 0..STATES {
        let mut dx0 = State::zeros();
        dx0[j] = sizes[j];
        let mut estimate = perturbed(&trajectory.states[0], &dx0);
        let mut previous = corrupted(&increments[0], &dx0);
        for inc in increments.iter().take(steps) {
            let current = corrupted(inc, &dx0);
            estimate = mechanize(&estimate, &previous, &current);
            previous = current;
        }
        let (dr, dv, dphi) = error_of(&estimate, &trajectory.states[steps]);
        let actual = [dr, dv, dphi];
        let predicted = transition * dx0;
        for (block, name) in ["position", "velocity", "attitude"].iter().enumerate() {
            let lin = Vector3::new(
                predicted[3 * block],
                predicted[3 * block + 1],
                predicted[3 * block + 2],
            );
            let diff = (actual[block] - lin).norm();
            let scale = actual[block].norm().max(lin.norm());
            // First-order agreement: the nonlinear remainder and the Euler product's O(dt)
            // error are a few per cent of the response; 5 % plus a floor per block far below
            // the smallest physical coupling tested (the 2g/R gravity gradient moves the
            // velocity by ~1e-3 m/s over 10 s for 50 m of height error).
            let floor = [1e-4, 1e-6, 1e-8][block];
            assert!(
                diff <= 0.05 * scale + floor,
                "{} -> {name}: actual {:?} vs linear {:?}",
                names[j],
                actual[block].as_slice(),
                lin.as_slice()
            );
        }
    }
}
