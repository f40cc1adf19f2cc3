//! Issue 18, item 4: the IMU-GNSS time offset estimated from the innovations' likelihood.
//! Oracle: a simulated vessel whose IMU clock is made to read late or early by a known amount;
//! the offset that puts it back on the GNSS time scale is the negated shift.

use super::navigation::settings;
use thermonav::nav::engine::FilterKind;
use thermonav::nav::outage::Outages;
use thermonav::nav::run::{ModelTemperature, NoiseModel, RunSettings, Start};
use thermonav::nav::time_offset::{
    TimeOffsetEstimate, TimeOffsetSearch, estimate_time_offset, shifted,
};
use thermonav::sensor::adis16364_like;
use thermonav::sim::clock::SampleClock;
use thermonav::sim::unit::SimulatedUnit;
use thermonav::sim::vessel::{
    GnssSettings, SurveyTemperature, VesselRecord, VesselRun, harbour_survey, simulate_vessel,
};

/// A 300 s vessel run with RTK-grade fixes (2 cm horizontal, 5 Hz, as on the car drive): at
/// 2.5 m/s an offset of 10 ms moves the antenna 2.5 cm along the track, so the offset is
/// resolved to a few ms. With the default 0.5 m DGPS fixes at 1 Hz the same 10 ms is a
/// twentieth of a fix's sd and the likelihood is flat within ±0.1 s (seen with
/// `print_log_likelihood_scan`): the offset is not observable there, whatever the search.
fn rtk_vessel(seed: u64) -> VesselRecord {
    let run = VesselRun {
        motion: harbour_survey(300.0),
        temperature: SurveyTemperature::Constant {
            temperature_c: 17.0,
        },
        unit: SimulatedUnit { serial: seed },
        clock: SampleClock::new(200.0, 0.0, 0.0).unwrap(),
        gnss: GnssSettings {
            rate_hz: 5.0,
            position_sd_ned_m: [0.02, 0.02, 0.04],
            ..GnssSettings::default()
        },
        seed,
    };
    simulate_vessel(&adis16364_like(), &run).unwrap()
}

/// The estimate on a 300 s vessel run (seed `seed`) whose IMU times were moved by `shift_s`.
fn estimate_for(shift_s: f64, seed: u64, filter: FilterKind) -> TimeOffsetEstimate {
    let record = rtk_vessel(seed);
    let late = shifted(&record.imu, shift_s);
    let run = run_settings(filter);
    let profile = adis16364_like();
    estimate_time_offset(
        &late,
        &record.gnss,
        NoiseModel::Profile(&profile),
        Start::Align,
        &run,
        &TimeOffsetSearch::default(),
    )
    .unwrap()
}

fn run_settings(filter: FilterKind) -> RunSettings {
    RunSettings {
        temperature: ModelTemperature::Fixed(17.0),
        engine: settings(filter, Outages::none()),
        ..RunSettings::default()
    }
}

// The simulated IMU and GNSS share one clock, so the true offset is −shift. The tolerance is
// the larger of 3 reported sds and 3 ms: the golden-section search stops at a 2 ms interval,
// so an estimate can sit up to 1 ms from the likelihood's maximum on top of its own error.
#[test]
fn the_offset_of_a_shifted_imu_clock_is_found() {
    for (shift_s, seed, filter) in [
        (0.080, 1, FilterKind::Ekf),
        (-0.150, 2, FilterKind::Ekf),
        (0.0, 3, FilterKind::Ekf),
        (0.120, 4, FilterKind::Ukf),
    ] {
        let e = estimate_for(shift_s, seed, filter);
        let sd = e
            .time_offset_sd_s
            .expect("the offset is observable on a turning vessel");
        let error = e.time_offset_s + shift_s;
        println!(
            "shift {shift_s:+.3} s {filter:?}: estimate {:+.4} s, sd {:.4} s, error {:+.4} s, {} runs",
            e.time_offset_s, sd, error, e.runs
        );
        assert!(
            error.abs() < (3.0 * sd).max(0.003),
            "shift {shift_s} s: estimate {} s, sd {sd} s",
            e.time_offset_s
        );
        // The sd is a real uncertainty, not a token: below 20 ms on 300 s of 5 Hz RTK fixes.
        assert!(sd > 0.0 && sd < 0.020, "{sd}");
    }
}

/// Issue 38 row 13: a slow rover (0.4 m/s, 20 Hz 0.7 m position-only fixes) whose IMU clock
/// reads 0.12 s early, so that the offset that puts it on the GNSS scale is +0.12 s.
fn slow_rover(seed: u64, duration_s: f64, offset_s: f64) -> VesselRecord {
    use thermonav::sim::rover::rover_loops;
    use thermonav::sim::vessel::{GnssHeading, ImuOffsets, simulate_vessel_with};
    let run = VesselRun {
        motion: rover_loops(duration_s, 0.4),
        temperature: SurveyTemperature::Constant {
            temperature_c: 17.0,
        },
        unit: SimulatedUnit { serial: seed },
        clock: SampleClock::new(200.0, 0.0, 0.0).unwrap(),
        gnss: GnssSettings {
            rate_hz: 20.0,
            position_sd_ned_m: [0.7, 0.7, 1.4],
            heading: GnssHeading::None,
            ..GnssSettings::default()
        },
        seed,
    };
    let offsets = ImuOffsets {
        gyro_bias_rad_s: [0.0, 0.0, -100f64.to_radians() / 3600.0],
        time_offset_s: offset_s,
    };
    simulate_vessel_with(&adis16364_like(), &run, &offsets).unwrap()
}

// The user's symptom was a 17 ms sd for an offset the data do not determine. On the slow
// rover the likelihood-ratio interval must cover the simulated offset, be far wider than
// that (no sd at all when it is open, else above 50 ms: at 0.4 m/s a 50 ms offset moves
// the antenna 2 cm against 0.7 m fixes), and say when it is not closed. A short run and one
// seed keep CI fast; the 20-seed coverage is bench/slow_rover.py's (docs/user-guide.md).
#[test]
fn the_slow_rover_interval_covers_the_offset_and_is_honestly_wide() {
    let offset_s = 0.12;
    let record = slow_rover(5, 150.0, offset_s);
    let profile = adis16364_like();
    let e = estimate_time_offset(
        &record.imu,
        &record.gnss,
        NoiseModel::Profile(&profile),
        Start::Align,
        &run_settings(FilterKind::Ekf),
        &TimeOffsetSearch::default(),
    )
    .unwrap();
    println!(
        "estimate {:+.3} s in [{:?}, {:?}], {:?}, dispersion {:.2}, {} runs",
        e.time_offset_s, e.lower, e.upper, e.observability, e.dispersion, e.runs
    );
    assert!(
        e.lower.offset_s() <= offset_s && offset_s <= e.upper.offset_s(),
        "{e:?}"
    );
    match e.time_offset_sd_s {
        Some(sd) => assert!(sd > 0.05, "{sd}"),
        None => assert!(e.warning.is_some() && (e.lower.is_open() || e.upper.is_open())),
    }
    // Consistent filter: the NIS per degree of freedom is near 1 (6000 fixes: ±10 %).
    assert!((e.dispersion - 1.0).abs() < 0.1, "{}", e.dispersion);
}

/// The log-likelihood against the offset on one run (a diagnostic: `--ignored --nocapture`).
#[test]
#[ignore]
fn print_log_likelihood_scan() {
    use thermonav::nav::time_offset::log_likelihood_at;
    let record = rtk_vessel(3);
    let profile = adis16364_like();
    for filter in [FilterKind::Ekf] {
        let run = run_settings(filter);
        for k in -10..=4 {
            let offset_s = 0.02 * f64::from(k);
            let ll = log_likelihood_at(
                &record.imu,
                &record.gnss,
                NoiseModel::Profile(&profile),
                Start::Align,
                &run,
                offset_s,
            )
            .unwrap();
            println!("{filter:?} offset {offset_s:+.3} s: log-likelihood {ll:.2}");
        }
    }
}
