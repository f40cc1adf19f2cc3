//! The filter scheduled by temperature and the thermal compensation, against closed forms
//! and the fixed-model runs they must reduce to.

use std::collections::BTreeMap;
use thermonav::imu::{Channel, ImuSample, ImuSeries, SampleKind};
use thermonav::ins::error_model::block;
use thermonav::nav::alignment::{InitialUncertainty, uncorrected};
use thermonav::nav::engine::{EngineSettings, FilterKind, increments_from_series};
use thermonav::nav::measurement::AntennaGeometry;
use thermonav::nav::navigate::{run, run_scheduled};
use thermonav::nav::schedule::{ModelGrid, ModelSchedule, TemperatureTrack};
use thermonav::nav::sensor_model::{ImuStochasticModel, ScaleFactorPrior};
use thermonav::nav::solution::Solution;
use thermonav::sensor::adis16364_like;
use thermonav::sim::clock::SampleClock;
use thermonav::sim::unit::SimulatedUnit;
use thermonav::sim::vessel::{
    GnssSettings, SurveyTemperature, VesselRecord, VesselRun, harbour_survey, simulate_vessel,
};
use thermonav::stoch::thermal::{FitSettings, PowerOnRecord, ThermalCalibration, calibrate};
use thermonav::time::{Duration, Timestamp};

const SURVEY_C: f64 = 17.0;

fn vessel(duration_s: f64) -> VesselRecord {
    let run = VesselRun {
        motion: harbour_survey(duration_s),
        temperature: SurveyTemperature::Constant {
            temperature_c: SURVEY_C,
        },
        unit: SimulatedUnit::default(),
        clock: SampleClock::new(200.0, 0.0, 0.0).unwrap(),
        gnss: GnssSettings::default(),
        seed: 11,
    };
    simulate_vessel(&adis16364_like(), &run).unwrap()
}

fn settings(filter: FilterKind) -> EngineSettings {
    let g = GnssSettings::default();
    EngineSettings {
        filter,
        geometry: AntennaGeometry {
            lever_arm_body_m: g.lever_arm_body_m,
            baseline_body: g.baseline_body_m,
        },
        ..EngineSettings::default()
    }
}

fn profile_model(temperature_c: f64) -> ImuStochasticModel {
    adis16364_like()
        .stochastic_model(temperature_c, &ScaleFactorPrior::default())
        .unwrap()
}

fn profile_grid(range_c: [f64; 2]) -> ModelGrid {
    ModelGrid::from_profile(&adis16364_like(), &ScaleFactorPrior::default(), range_c).unwrap()
}

/// One run from the true start over the record's first `span_s`, with the fixes or without
/// (free inertial).
fn navigate(
    record: &VesselRecord,
    with_gnss: bool,
    schedule: ModelSchedule,
    filter: FilterKind,
    span_s: f64,
) -> Solution {
    let p0 = InitialUncertainty::default().covariance();
    navigate_from(record, with_gnss, schedule, filter, span_s, p0)
}

/// [`navigate`] from the initial covariance `p0`.
fn navigate_from(
    record: &VesselRecord,
    with_gnss: bool,
    schedule: ModelSchedule,
    filter: FilterKind,
    span_s: f64,
    p0: thermonav::ins::error_model::SystemMatrix,
) -> Solution {
    let end = record.reference.states[0].time + Duration::from_seconds(span_s).unwrap();
    let mut increments = increments_from_series(&record.imu);
    increments.retain(|i| i.time <= end);
    let gnss = if with_gnss { &record.gnss[..] } else { &[] };
    let settings = EngineSettings {
        // Free inertial: the covariance at every sample, so each epoch shows it up to date.
        covariance_interval_s: if with_gnss { 0.1 } else { 1e-3 },
        ..settings(filter)
    };
    run_scheduled(
        &increments,
        gnss,
        uncorrected(record.reference.states[0]),
        p0,
        schedule,
        &settings,
        &mut |_| {},
    )
    .unwrap()
}

// A record at one constant temperature has a one-point grid holding the model at exactly
// that temperature, so the scheduled run performs the fixed run's arithmetic on the same
// numbers: every epoch's position is equal to the last bit (tolerance zero: any difference
// would mean the schedule changed the model).
#[test]
fn a_constant_temperature_schedule_is_the_fixed_model_at_that_temperature() {
    let record = vessel(60.0);
    let track = TemperatureTrack::of_series(&record.imu).unwrap().unwrap();
    assert_eq!(track.range_c(), [SURVEY_C, SURVEY_C]);
    let grid = profile_grid(track.range_c());
    assert_eq!(grid.points(), 1);
    for filter in [FilterKind::Ekf, FilterKind::Ukf] {
        let model = profile_model(SURVEY_C);
        let fixed = navigate(&record, true, ModelSchedule::Fixed(&model), filter, 60.0);
        let scheduled = navigate(
            &record,
            true,
            ModelSchedule::ByTemperature {
                track: &track,
                grid: &grid,
            },
            filter,
            60.0,
        );
        assert_eq!(fixed.epochs.len(), scheduled.epochs.len());
        for (a, b) in fixed.epochs.iter().zip(&scheduled.epochs) {
            let (p, q) = (a.estimate.nav.position, b.estimate.nav.position);
            assert_eq!(a.estimate.nav.time, b.estimate.nav.time);
            assert_eq!(p.latitude_rad, q.latitude_rad, "{filter:?}");
            assert_eq!(p.longitude_rad, q.longitude_rad, "{filter:?}");
            assert_eq!(p.height_m, q.height_m, "{filter:?}");
        }
    }
}

/// The closed form of a Gauss-Markov state's variance from `p0` over `elapsed_s` under
/// (Tc, σ): σ² + (p0 − σ²) e^{−2t/Tc}, whatever the steps (the exact discretisation composes).
fn gm_variance(p0: f64, sigma: f64, tc_s: f64, elapsed_s: f64) -> f64 {
    sigma * sigma + (p0 - sigma * sigma) * (-2.0 * elapsed_s / tc_s).exp()
}

// Without GNSS the bias states' variances evolve on their own (their rows of F and Φ hold
// only −1/Tc and e^{−Δt/Tc}, and the white noise enters velocity and attitude only), so each
// follows the closed form above: under model(A) up to the step, from there under model(B).
// Before the step the scheduled run must equal the run with model(A) fixed in every state.
// The covariance is propagated at every sample; the step (s, e] takes the temperature at s,
// so model(B) rules from the first sample at or after the temperature step on. The biases
// start at model(A)'s stationary variance: an initial variance above it is a turn-on bias that
// the engine keeps as a constant (nearly: its correlation time is stretched by (σ² + c²)/σ²),
// which would hide the switch of (Tc, σ) this test is about.
#[test]
fn a_temperature_step_switches_from_model_a_to_model_b() {
    let (cold_c, warm_c) = (10.0, 30.0);
    let record = vessel(60.0);
    let t0 = record.reference.states[0].time;
    let step = t0 + Duration::from_seconds(8.0).unwrap();
    let temperatures: Vec<f64> = record
        .imu
        .time
        .iter()
        .map(|&t| if t < step { cold_c } else { warm_c })
        .collect();
    let track = TemperatureTrack::new(&record.imu.time, &temperatures).unwrap();
    let step = record.imu.time[record.imu.time.partition_point(|&t| t < step)];
    // The covariance grows over the increments' time, which starts at the first sample at or
    // after the initial time (no increment covers the time before it).
    let times = &record.imu.time;
    let first = times.partition_point(|&t| t <= t0);
    let t0 = if first == 0 {
        times[0]
    } else {
        t0.max(times[first - 1])
    };
    assert_eq!(track.segments(), 2);
    let grid = profile_grid(track.range_c());
    let schedule = ModelSchedule::ByTemperature {
        track: &track,
        grid: &grid,
    };
    let (a, b) = (profile_model(cold_c), profile_model(warm_c));
    assert_ne!(
        a.gyro[0].bias.correlation_time_s, b.gyro[0].bias.correlation_time_s,
        "the two models must differ for the test to mean anything"
    );
    let bias_models = |m: &ImuStochasticModel| [m.gyro, m.accel].concat();
    let mut p0 = InitialUncertainty::default().covariance();
    for (i, axis) in bias_models(&a).iter().enumerate() {
        p0[(block::GYRO_BIAS + i, block::GYRO_BIAS + i)] = axis.bias.sigma.powi(2);
    }
    // 16 s: free inertial with a MEMS unit's turn-on biases soon trips the speed check.
    let scheduled = navigate_from(&record, false, schedule, FilterKind::Ekf, 16.0, p0);
    let fixed_a = navigate_from(
        &record,
        false,
        ModelSchedule::Fixed(&a),
        FilterKind::Ekf,
        16.0,
        p0,
    );
    let mut checked_after = 0;
    for (k, epoch) in scheduled.epochs.iter().enumerate() {
        let t = epoch.estimate.nav.time;
        if t <= step {
            assert_eq!(epoch.sd, fixed_a.epochs[k].sd, "before the step, t = {t:?}");
        }
        for (i, (axis_a, axis_b)) in bias_models(&a).iter().zip(bias_models(&b)).enumerate() {
            let state = block::GYRO_BIAS + i;
            let p_start = p0[(state, state)];
            let (ga, gb) = (axis_a.bias, axis_b.bias);
            let before = |s: f64| gm_variance(p_start, ga.sigma, ga.correlation_time_s, s.max(0.0));
            let expected = if t <= step {
                before(t.since(t0).as_seconds())
            } else {
                let at_step = before(step.since(t0).as_seconds());
                let s = t.since(step).as_seconds();
                gm_variance(at_step, gb.sigma, gb.correlation_time_s, s)
            };
            let got = epoch.sd[state].powi(2);
            assert!(
                (got / expected - 1.0).abs() < 1e-9,
                "state {state} at {:.1} s: {got} against {expected}",
                t.since(t0).as_seconds()
            );
        }
        checked_after += usize::from(t > step);
    }
    assert!(checked_after > 50, "epochs after the step: {checked_after}");
}

/// A calibration whose every channel's curve is b(T) = b0 + b1 (T − 20) + b2 (T − 20)² on
/// [0, 40] °C (the structure from a fit, the coefficients set by hand).
fn known_calibration(b: [f64; 3]) -> ThermalCalibration {
    let records: Vec<PowerOnRecord> = (0..9)
        .map(|k| PowerOnRecord {
            power_on: 0,
            temperature_c: -20.0 + 10.0 * k as f64,
            value: 1e-3 * k as f64 + if k % 2 == 0 { 1e-6 } else { -1e-6 },
        })
        .collect();
    let observations: BTreeMap<Channel, Vec<PowerOnRecord>> =
        Channel::ALL.iter().map(|&c| (c, records.clone())).collect();
    let mut calibration = calibrate(&observations, FitSettings::default()).unwrap();
    for channel in calibration.channels.values_mut() {
        let curve = &mut channel.bias;
        curve.reference_temperature_c = 20.0;
        curve.order = 2;
        curve.coefficients = b.to_vec();
        curve.temperature_range_c = [0.0, 40.0];
    }
    calibration
}

fn series(kind: SampleKind, value: impl Fn(f64, f64) -> f64) -> (ImuSeries, Vec<f64>) {
    let dt_s = 0.01;
    let temperatures: Vec<f64> = (0..11).map(|k| -5.0 + 5.0 * k as f64).collect();
    let mut s = ImuSeries::new(kind);
    for (k, &t) in temperatures.iter().enumerate() {
        let v = value(t, dt_s);
        s.push(&ImuSample {
            time: Timestamp::from_nanos(10_000_000 * k as i64),
            gyro: [v; 3],
            accel: [v; 3],
            temperature_c: Some(t),
        });
    }
    (s, temperatures)
}

// Samples made as c + b(T) (rates) or (c + b(T)) Δt (increments), b the closed-form
// quadratic held at its range's ends, come out as c or c Δt; the samples outside [0, 40] °C
// (−5 and 45 °C) are counted as clamped.
#[test]
fn compensation_removes_a_known_curve_from_rates_and_increments() {
    let b = [2e-3, -4e-5, 3e-6];
    let curve = |t: f64| {
        let d = t.clamp(0.0, 40.0) - 20.0;
        b[0] + b[1] * d + b[2] * d * d
    };
    let calibration = known_calibration(b);
    let c = 0.25;
    for kind in [SampleKind::Rates, SampleKind::Increments] {
        let per = |dt: f64| if kind == SampleKind::Rates { 1.0 } else { dt };
        let (mut s, temperatures) = series(kind, |t, dt| (c + curve(t)) * per(dt));
        let done = calibration.compensate(&mut s).unwrap();
        assert_eq!((done.samples, done.clamped_samples), (11, 2));
        for channel in Channel::ALL {
            for (k, v) in s.channel(channel).iter().enumerate() {
                let expected = c * per(0.01);
                assert!(
                    (v - expected).abs() < 1e-15,
                    "{kind:?} {channel:?} at {} °C: {v} against {expected}",
                    temperatures[k]
                );
            }
        }
    }
}

// The old fixed-model entry point stays the schedule's fixed case.
#[test]
fn run_is_run_scheduled_with_a_fixed_model() {
    let record = vessel(60.0);
    let model = profile_model(SURVEY_C);
    let increments = increments_from_series(&record.imu);
    let start = uncorrected(record.reference.states[0]);
    let p0 = InitialUncertainty::default().covariance();
    let s = settings(FilterKind::Ekf);
    let old = run(
        &increments,
        &record.gnss,
        start,
        p0,
        &model,
        &s,
        &mut |_| {},
    )
    .unwrap();
    let span_s = 1e6;
    let new = navigate(
        &record,
        true,
        ModelSchedule::Fixed(&model),
        FilterKind::Ekf,
        span_s,
    );
    assert_eq!(old.epochs, new.epochs);
}
