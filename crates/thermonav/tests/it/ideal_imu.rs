//! The ideal IMU inverts the mechanization; checked by a round trip and against the
//! continuous-time closed form of a steady run.

use thermonav::frames::{Ned, Vector};
use thermonav::geo::gravity::gravity_ned;
use thermonav::ins::mechanization::mechanize;
use thermonav::sim::ideal_imu::ideal_increments;
use thermonav::sim::motion::{
    Harmonic, MotionDefinition, MotionSegment, PitchModel, StartPoint, WaveMotion,
    generate_trajectory,
};

fn segment(
    duration_s: f64,
    acceleration_m_s2: f64,
    turn_deg_s: f64,
    climb_rate_m_s: f64,
) -> MotionSegment {
    MotionSegment {
        duration_s,
        acceleration_m_s2,
        turn_rate_rad_s: turn_deg_s.to_radians(),
        climb_rate_m_s,
    }
}

fn wavy_survey() -> MotionDefinition {
    let h = |amplitude: f64, period_s: f64, phase_rad: f64| Harmonic {
        amplitude,
        period_s,
        phase_rad,
    };
    let mut segments = vec![segment(60.0, 0.05, 0.0, 0.0)];
    for k in 0..13 {
        segments.push(segment(240.0, 0.0, 0.0, 0.0));
        segments.push(segment(30.0, 0.0, if k % 2 == 0 { 6.0 } else { -6.0 }, 0.0));
    }
    MotionDefinition {
        start: StartPoint {
            lat_deg: 44.65,
            lon_deg: -63.57,
            h_m: 10.0,
        },
        initial_speed_m_s: 1.0,
        initial_heading_rad: 0.3,
        segments,
        waves: WaveMotion {
            roll: vec![
                h(3f64.to_radians(), 6.0, 0.0),
                h(1.5f64.to_radians(), 9.3, 1.0),
            ],
            pitch: vec![h(1.5f64.to_radians(), 5.1, 0.4)],
            heave: vec![h(0.3, 7.0, 0.2)],
        },
        pitch: PitchModel::Level,
    }
}

/// Perfect increments through the mechanization must reproduce the trajectory; the
/// requirement is centimetres over an hour, and since the inverse is exact the bound is 1 mm.
#[test]
fn perfect_imu_reproduces_an_hour_of_wavy_survey_lines() {
    let trajectory = generate_trajectory(&wavy_survey(), 200.0).unwrap();
    assert!(trajectory.states.len() > 690_000);
    let increments = ideal_increments(&trajectory);
    let mut state = trajectory.states[0];
    let mut previous = increments[0];
    let mut worst_m: f64 = 0.0;
    for (k, current) in increments.iter().enumerate() {
        state = mechanize(&state, &previous, current);
        previous = *current;
        if k % 2000 == 0 {
            worst_m = worst_m.max(
                state
                    .position
                    .ned_from(&trajectory.states[k + 1].position)
                    .norm(),
            );
        }
    }
    let last = trajectory.states.last().unwrap();
    let error = state.position.ned_from(&last.position).norm();
    assert!(
        error < 1e-3 && worst_m < 1e-3,
        "end {error} m, worst {worst_m} m"
    );
    assert!(state.attitude.angle_to(&last.attitude) < 1e-9);
    assert!((state.velocity - last.velocity).norm() < 1e-6);
}

/// Independent oracle: a level run north at constant speed has, in continuous time,
/// f^n = (2 ω_ie + ω_en) × v − g^n and ω_ib^b = C_n^b (ω_ie + ω_en). The two-sample
/// discretisation differs from it by O(dt²) terms, far below 1e-7 m/s² and 1e-10 rad/s here.
#[test]
fn steady_run_matches_the_continuous_closed_form() {
    let motion = MotionDefinition {
        start: StartPoint {
            lat_deg: 30.0,
            lon_deg: 10.0,
            h_m: 100.0,
        },
        initial_speed_m_s: 20.0,
        initial_heading_rad: 0.0,
        segments: vec![segment(10.0, 0.0, 0.0, 0.0)],
        waves: WaveMotion::default(),
        pitch: PitchModel::Level,
    };
    let trajectory = generate_trajectory(&motion, 100.0).unwrap();
    let increments = ideal_increments(&trajectory);
    let k = 500;
    let state = trajectory.states[k];
    let inc = increments[k];
    let omega_ie = state.position.earth_rate_ned();
    let omega_en = state.position.transport_rate_ned(&state.velocity);
    let g = Vector::<Ned>::from_array(gravity_ned(
        state.position.latitude_rad,
        state.position.height_m,
    ));
    let force_n = (omega_ie.scale(2.0) + omega_en).cross(&state.velocity) - g;
    let force_b = state.attitude.inverse() * force_n;
    let rate_b = state.attitude.inverse() * (omega_ie + omega_en);
    let measured_force = inc.delta_velocity.scale(1.0 / inc.dt_s());
    let measured_rate = inc.delta_angle.scale(1.0 / inc.dt_s());
    assert!(
        (measured_force - force_b).norm() < 1e-7,
        "{:?} vs {:?}",
        measured_force.to_array(),
        force_b.to_array()
    );
    assert!(
        (measured_rate - rate_b).norm() < 1e-10,
        "{:?} vs {:?}",
        measured_rate.to_array(),
        rate_b.to_array()
    );
}
