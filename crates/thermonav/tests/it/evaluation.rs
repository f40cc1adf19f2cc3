//! Outage metrics against a hand computation on a constructed case.

use thermonav::evaluation::metrics::{Reference, evaluate_solution};
use thermonav::frames::{Rotation, Vector};
use thermonav::geo::position::Geodetic;
use thermonav::ins::error_model::STATES;
use thermonav::ins::state::NavState;
use thermonav::nav::alignment::uncorrected;
use thermonav::nav::outage::Outages;
use thermonav::nav::solution::SolutionEpoch;
use thermonav::time::Timestamp;
use thermonav::trajectory::TrajectoryPoint;

fn at(seconds: f64) -> Timestamp {
    Timestamp::from_seconds(seconds).unwrap()
}

// A reference moving north at 10 m/s with yaw 179.5°, sampled every second; a solution at
// every 0.5 s whose error is known by construction: in the outage [10, 20) s the north error
// is 0.1 k² (k = seconds into the outage), the east error −2 m, the yaw −179.5° (a +1° error
// across the ±180° cut); in [50, 60) s the error is (3, 4) m and no heading error. Expected
// figures are summed by hand below from those formulas. Offsets are applied with the
// first-order `displaced` and measured with the exact ECEF route, which differ by
// |offset|²/R < 2e-5 m: hence 1e-4 m.
#[test]
fn outage_metrics_equal_a_hand_computation() {
    let origin = Geodetic::from_degrees(45.0, -63.0, 0.0);
    let reference_yaw = 179.5f64.to_radians();
    let true_position = |t: f64| origin.displaced(&Vector::new(10.0 * t, 0.0, 0.0));
    let reference: Vec<TrajectoryPoint> = (0..=100)
        .map(|s| {
            let p = true_position(s as f64);
            TrajectoryPoint {
                time: at(s as f64),
                latitude_rad: p.latitude_rad,
                longitude_rad: p.longitude_rad,
                height_m: 0.0,
                velocity_ned_m_s: [10.0, 0.0, 0.0],
                roll_rad: 0.0,
                pitch_rad: 0.0,
                yaw_rad: reference_yaw,
            }
        })
        .collect();
    let error_at = |t: f64| -> (f64, f64, f64) {
        if (10.0..20.0).contains(&t) {
            (0.1 * (t - 10.0).powi(2), -2.0, 1.0)
        } else if (50.0..60.0).contains(&t) {
            (3.0, 4.0, 0.0)
        } else {
            (0.0, 0.0, 0.0)
        }
    };
    let epochs: Vec<SolutionEpoch> = (0..200)
        .map(|k| {
            let t = 0.5 * k as f64;
            let (n, e, heading_deg) = error_at(t);
            let yaw = reference_yaw + heading_deg.to_radians();
            SolutionEpoch {
                estimate: uncorrected(NavState {
                    time: at(t),
                    position: true_position(t).displaced(&Vector::new(n, e, 0.0)),
                    velocity: Vector::zeros(),
                    attitude: Rotation::from_euler_zyx(0.0, 0.0, yaw),
                }),
                sd: [1.0; STATES],
                in_outage: false,
            }
        })
        .collect();
    let outages = Outages::from_start_duration(&[(10.0, 10.0), (50.0, 10.0)]).unwrap();
    let (metrics, errors) =
        evaluate_solution(Reference::full(&reference), &epochs, outages.windows()).unwrap();

    // Outage 1: k = 0, 0.5, …, 9.5 (20 epochs).
    let ks: Vec<f64> = (0..20).map(|i| 0.5 * i as f64).collect();
    let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt();
    let north1: Vec<f64> = ks.iter().map(|k| 0.1 * k * k).collect();
    let horizontal1: Vec<f64> = north1.iter().map(|n| n.hypot(2.0)).collect();
    let first = &metrics.per_outage[0];
    assert_eq!((first.epochs, errors[0].len()), (20, 20));
    assert!((first.rms_north_m - rms(&north1)).abs() < 1e-4);
    assert!((first.rms_east_m - 2.0).abs() < 1e-4);
    assert!((first.rms_horizontal_m - rms(&horizontal1)).abs() < 1e-4);
    assert!((first.rms_heading_deg.unwrap() - 1.0).abs() < 1e-9);
    assert!((first.max_north_m - 0.1 * 9.5 * 9.5).abs() < 1e-4);
    assert!((first.max_horizontal_m - (0.1f64 * 9.5 * 9.5).hypot(2.0)).abs() < 1e-4);
    let second = &metrics.per_outage[1];
    assert!(
        (second.rms_horizontal_m - 5.0).abs() < 1e-4
            && second.rms_heading_deg.unwrap().abs() < 1e-9
    );
    // The paper's overall figure: the mean of per-outage RMS; KF-GINS's: RMS of the maxima.
    assert!((metrics.rms_north_m - (rms(&north1) + 3.0) / 2.0).abs() < 1e-4);
    assert!((metrics.rms_heading_deg.unwrap() - 0.5).abs() < 1e-9);
    let max1 = (0.1f64 * 9.5 * 9.5).hypot(2.0);
    assert!((metrics.max_drift_horizontal_m - ((max1 * max1 + 25.0) / 2.0).sqrt()).abs() < 1e-4);
    assert!((errors[0][3].since_outage_start_s - 1.5).abs() < 1e-12);
}

// A reference that ends before an outage does is refused with the spans named.
#[test]
fn reference_must_cover_every_outage() {
    let p = Geodetic::from_degrees(45.0, -63.0, 0.0);
    let point = |s: f64| TrajectoryPoint {
        time: at(s),
        latitude_rad: p.latitude_rad,
        longitude_rad: p.longitude_rad,
        height_m: 0.0,
        velocity_ned_m_s: [0.0; 3],
        roll_rad: 0.0,
        pitch_rad: 0.0,
        yaw_rad: 0.0,
    };
    let reference = vec![point(0.0), point(15.0)];
    let epochs: Vec<SolutionEpoch> = (0..40)
        .map(|k| {
            let mut nav = reference[0].nav_state();
            nav.time = at(0.5 * k as f64);
            SolutionEpoch {
                estimate: uncorrected(nav),
                sd: [1.0; STATES],
                in_outage: false,
            }
        })
        .collect();
    let outages = Outages::from_start_duration(&[(10.0, 10.0)]).unwrap();
    let error =
        evaluate_solution(Reference::full(&reference), &epochs, outages.windows()).unwrap_err();
    assert!(
        error
            .to_string()
            .contains("does not cover the outage 10.000-20.000 s"),
        "{error}"
    );
}
