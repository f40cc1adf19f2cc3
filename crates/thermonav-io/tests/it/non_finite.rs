//! Issue 20, "finite in, finite out": every writer is fed one NaN or infinity among finite
//! values and must refuse it with nothing left behind (no file, no temporary), where before
//! serde_json wrote `null` and the CSV writers `NaN`.

use std::path::Path;
use thermonav::frames::{Rotation, Vector};
use thermonav::geo::position::Geodetic;
use thermonav::gnss::GnssFix;
use thermonav::imu::{ImuSample, ImuSeries, SampleKind};
use thermonav::ins::error_model::STATES;
use thermonav::ins::state::NavState;
use thermonav::nav::alignment::uncorrected;
use thermonav::nav::measurement::MeasurementKind;
use thermonav::nav::solution::{InnovationRecord, SolutionEpoch};
use thermonav::time::Timestamp;
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::solution::{write_innovations_file, write_solution_states_file};
use thermonav_io::thermal_parameters::{
    Parameter, ParameterFile, ParameterTarget, ParameterValue, write_parameter_file,
};
use thermonav_io::{
    WriteError, write_gnss_file, write_imu_file, write_json_atomically, write_trajectory_file,
};

const SPOILERS: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

/// Runs `write` into a fresh folder and checks the refusal: an error that says why, and an
/// empty folder.
fn refused(what: &str, write: impl Fn(&Path) -> Result<(), WriteError>) {
    let dir = tempfile::tempdir().unwrap();
    let error = write(&dir.path().join("out")).expect_err(what).to_string();
    assert!(
        error.contains("thermonav writes no NaN or infinity"),
        "{what}: {error}"
    );
    assert!(error.contains("out"), "{what}: the file is named: {error}");
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "{what}: left {left:?}");
}

fn at(t_s: f64) -> Timestamp {
    Timestamp::from_nanos((t_s * 1e9) as i64)
}

fn imu_with(bad: f64) -> ImuSeries {
    let mut series = ImuSeries::new(SampleKind::Rates);
    for k in 0..5 {
        let value = if k == 3 { bad } else { 0.01 };
        series.push(&ImuSample {
            time: at(0.01 * k as f64),
            gyro: [0.0, value, 0.0],
            accel: [0.0, 0.0, -9.8],
            temperature_c: Some(20.0),
        });
    }
    series
}

fn fix_with(bad: f64) -> GnssFix {
    GnssFix {
        time: at(1.0),
        latitude_rad: 0.7,
        longitude_rad: -1.1,
        height_m: bad,
        position_sd_ned_m: Some([0.5, 0.5, 1.0]),
        velocity_ned_m_s: None,
        heading: None,
    }
}

fn point_with(bad: f64) -> TrajectoryPoint {
    TrajectoryPoint {
        time: at(1.0),
        latitude_rad: 0.7,
        longitude_rad: -1.1,
        height_m: 5.0,
        velocity_ned_m_s: [1.0, bad, 0.0],
        roll_rad: 0.0,
        pitch_rad: 0.0,
        yaw_rad: 0.3,
    }
}

fn epoch_with(bad: f64) -> SolutionEpoch {
    let mut sd = [1.0; STATES];
    sd[7] = bad;
    SolutionEpoch {
        estimate: uncorrected(NavState {
            time: at(1.0),
            position: Geodetic::from_degrees(44.6, -63.6, 5.0),
            velocity: Vector::zeros(),
            attitude: Rotation::from_euler_zyx(0.0, 0.0, 0.3),
        }),
        sd,
        in_outage: false,
    }
}

fn innovation_with(bad: f64) -> InnovationRecord {
    InnovationRecord {
        time: at(1.0),
        kind: MeasurementKind::Position,
        innovation: [0.1, 0.2, 0.3],
        sd: [1.0; 3],
        nis: bad,
        log_likelihood: 0.0,
        gate_scale: 1.0,
        accepted: true,
        forced: false,
    }
}

fn parameters_with(bad: f64) -> ParameterFile {
    ParameterFile {
        target: ParameterTarget::Px4Tc,
        parameters: vec![Parameter {
            name: "TC_G0_X0_0".into(),
            value: ParameterValue::Real(bad as f32),
        }],
        comments: vec![],
        sensors: vec![],
    }
}

#[test]
fn every_writer_refuses_a_number_that_is_not_finite() {
    for bad in SPOILERS {
        refused("IMU CSV", |p| write_imu_file(p, &imu_with(bad)));
        refused("GNSS CSV", |p| {
            write_gnss_file(p, &[fix_with(1.0), fix_with(bad)])
        });
        refused("trajectory CSV", |p| {
            write_trajectory_file(p, &[point_with(bad)])
        });
        refused("state file", |p| {
            write_solution_states_file(p, &[epoch_with(bad)])
        });
        refused("innovations", |p| {
            write_innovations_file(p, &[innovation_with(bad)])
        });
        refused("parameter file", |p| {
            write_parameter_file(p, &parameters_with(bad))
        });
        refused("JSON", |p| write_json_atomically(p, &[1.0, bad]));
    }
}

#[test]
fn the_same_writers_write_finite_values() {
    let dir = tempfile::tempdir().unwrap();
    let path = |name: &str| dir.path().join(name);
    write_imu_file(path("imu.csv"), &imu_with(0.02)).unwrap();
    write_gnss_file(path("gnss.csv"), &[fix_with(3.0)]).unwrap();
    write_trajectory_file(path("ref.csv"), &[point_with(0.5)]).unwrap();
    write_solution_states_file(path("s.csv"), &[epoch_with(0.1)]).unwrap();
    write_innovations_file(path("i.csv"), &[innovation_with(2.0)]).unwrap();
    write_parameter_file(&path("p.params"), &parameters_with(1e-3)).unwrap();
    write_json_atomically(path("d.json"), &[1.0, 2.5]).unwrap();
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 7);
}
