//! The GNSS/INS filters on simulated vessel runs whose truth is known: accuracy, NEES/NIS
//! consistency over a Monte Carlo set, EKF-UKF agreement, outages, the covariance rate.

use statrs::distribution::{ChiSquared, ContinuousCDF};
use thermonav::ins::error_model::block;
use thermonav::ins::state::NavState;
use thermonav::nav::alignment::{InitialUncertainty, bias_sd_in_quadrature, uncorrected};
use thermonav::nav::engine::{EngineSettings, FilterKind, increments_from_series};
use thermonav::nav::error_state::{ErrorVector, Estimate};
use thermonav::nav::measurement::AntennaGeometry;
use thermonav::nav::navigate::run;
use thermonav::nav::outage::Outages;
use thermonav::nav::sensor_model::{ImuStochasticModel, ScaleFactorPrior};
use thermonav::nav::solution::{Solution, SolutionEpoch};
use thermonav::sensor::adis16364_like;
use thermonav::sim::clock::SampleClock;
use thermonav::sim::vessel::{
    GnssSettings, VesselRecord, VesselRun, harbour_survey, simulate_vessel,
};

const TEMPERATURE_C: f64 = 17.0;

pub(crate) fn vessel(seed: u64, duration_s: f64) -> VesselRecord {
    let run = VesselRun {
        motion: harbour_survey(duration_s),
        temperature: thermonav::sim::vessel::SurveyTemperature::Constant {
            temperature_c: TEMPERATURE_C,
        },
        // A new unit per seed: the Monte Carlo set then draws the fixed bias from the
        // distribution the filter's initial covariance describes.
        unit: thermonav::sim::unit::SimulatedUnit { serial: seed },
        clock: SampleClock::new(200.0, 0.0, 0.0).unwrap(),
        gnss: GnssSettings::default(),
        seed,
    };
    simulate_vessel(&adis16364_like(), &run).unwrap()
}

pub(crate) fn settings(filter: FilterKind, outages: Outages) -> EngineSettings {
    let g = GnssSettings::default();
    EngineSettings {
        filter,
        geometry: AntennaGeometry {
            lever_arm_body_m: g.lever_arm_body_m,
            baseline_body: g.baseline_body_m,
        },
        outages,
        ..EngineSettings::default()
    }
}

/// The true model of the simulated sensor at the run's temperature.
pub(crate) fn true_model() -> ImuStochasticModel {
    adis16364_like()
        .stochastic_model(TEMPERATURE_C, &ScaleFactorPrior::default())
        .unwrap()
}

/// The initial estimate: the true start state perturbed by a draw from the initial
/// covariance's position, velocity and attitude parts (fixed pseudo-random signs, so each seed
/// starts differently but reproducibly).
pub(crate) fn initial(record: &VesselRecord, seed: u64) -> (Estimate, InitialUncertainty) {
    let uncertainty = InitialUncertainty::default();
    let truth = record.reference.states[0];
    let mut dx = ErrorVector::zeros();
    let sign = |i: usize| {
        if (seed.wrapping_mul(2654435761).wrapping_add(i as u64 * 40503) >> 7) % 2 == 0 {
            1.0
        } else {
            -1.0
        }
    };
    for i in 0..3 {
        dx[block::POSITION + i] = 0.5 * uncertainty.position_sd_m[i] * sign(i);
        dx[block::VELOCITY + i] = 0.5 * uncertainty.velocity_sd_m_s[i] * sign(3 + i);
        dx[block::ATTITUDE + i] = 0.5 * uncertainty.attitude_sd_rad[i] * sign(6 + i);
    }
    (uncorrected(truth).corrected_by(&dx), uncertainty)
}

pub(crate) fn navigate(record: &VesselRecord, seed: u64, settings: &EngineSettings) -> Solution {
    navigate_from(record, seed, settings, InitialUncertainty::default())
}

/// The initial uncertainty `integrate --profile` gives the simulated sensor: the default with
/// each bias sd the profile's turn-on, power-on and Gauss-Markov sds in quadrature, the
/// distribution each simulated unit's bias is drawn from (the default's 10 mg accelerometer
/// sd is nearly four times the profile's 2.7 mg).
pub(crate) fn profile_uncertainty() -> InitialUncertainty {
    let profile = adis16364_like();
    let model = true_model();
    let mut u = InitialUncertainty::default();
    for c in thermonav::imu::Channel::ALL {
        let p = &profile.channels[&c];
        let k = c.index();
        let (gm, sd) = match k {
            0..3 => (model.gyro[k].bias.sigma, &mut u.gyro_bias_sd_rad_s[k]),
            _ => (
                model.accel[k - 3].bias.sigma,
                &mut u.accel_bias_sd_m_s2[k - 3],
            ),
        };
        *sd = bias_sd_in_quadrature(&[p.turn_on_bias_sigma, p.power_on_offset_sigma, gm]);
    }
    u
}

/// [`navigate`] with the initial covariance of `uncertainty` (the start is the same).
pub(crate) fn navigate_from(
    record: &VesselRecord,
    seed: u64,
    settings: &EngineSettings,
    uncertainty: InitialUncertainty,
) -> Solution {
    let (start, _) = initial(record, seed);
    let increments = increments_from_series(&record.imu);
    run(
        &increments,
        &record.gnss,
        start,
        uncertainty.covariance(),
        &true_model(),
        settings,
        &mut |_| {},
    )
    .unwrap()
}

pub(crate) fn truth_at(record: &VesselRecord, time: thermonav::time::Timestamp) -> NavState {
    let states = &record.reference.states;
    let k = states.partition_point(|s| s.time < time);
    assert_eq!(states[k].time, time, "solution epochs fall on IMU epochs");
    states[k]
}

/// The true navigation error δx (position, velocity, attitude) of an estimate.
pub(crate) fn nav_error(record: &VesselRecord, estimate: &Estimate) -> [f64; 9] {
    let truth = Estimate {
        nav: truth_at(record, estimate.nav.time),
        sensors: estimate.sensors,
    };
    let dx = truth.error_from(estimate);
    std::array::from_fn(|i| dx[i])
}

pub(crate) fn horizontal_error_m(record: &VesselRecord, estimate: &Estimate) -> f64 {
    let e = nav_error(record, estimate);
    e[0].hypot(e[1])
}

// With GNSS every second (0.5 m position noise, 0.17° heading), the aided solution of either
// filter stays within a few position sigmas of the truth: below 1.5 m horizontally at every
// epoch after the first 60 s of convergence, and the heading within 0.5°.
#[test]
fn aided_solution_tracks_the_truth() {
    let record = vessel(11, 600.0);
    for filter in [FilterKind::Ekf, FilterKind::Ukf] {
        let solution = navigate(&record, 11, &settings(filter, Outages::none()));
        let late = solution
            .epochs
            .iter()
            .filter(|e| e.estimate.nav.time.as_seconds() > 60.0);
        let (mut worst_h, mut worst_psi) = (0.0f64, 0.0f64);
        for epoch in late {
            worst_h = worst_h.max(horizontal_error_m(&record, &epoch.estimate));
            worst_psi = worst_psi.max(nav_error(&record, &epoch.estimate)[8].abs());
        }
        assert!(
            worst_h < 1.5,
            "{filter:?}: worst horizontal error {worst_h} m"
        );
        assert!(
            worst_psi.to_degrees() < 0.5,
            "{filter:?}: worst heading error {} deg",
            worst_psi.to_degrees()
        );
        // The covariance stays positive definite: every variance finite and positive.
        assert!(
            solution
                .epochs
                .iter()
                .all(|e| e.sd.iter().all(|s| s.is_finite() && *s > 0.0))
        );
        let stats = solution.innovation_statistics();
        assert!(
            stats.iter().all(|s| s.rejected * 100 <= s.offered),
            "{filter:?}: {stats:?}"
        );
    }
}

/// Average NEES of the position, velocity and attitude errors at common epochs of several
/// runs, with the two-sided 95 % bounds for that many runs (Bar-Shalom et al. 2001 §5.4).
/// P0 is the profile's ([`profile_uncertainty`]): the engine keeps an initial bias variance
/// above the Gauss-Markov σ² as a turn-on bias, so an overstated prior (the default's 10 mg)
/// would stay overstated and make the filter conservative (0.83 of epochs inside with it).
fn anees(filter: FilterKind, runs: u64, duration_s: f64) -> (Vec<f64>, f64, f64) {
    let mut sums: Vec<f64> = Vec::new();
    for seed in 0..runs {
        let record = vessel(100 + seed, duration_s);
        let solution = navigate_from(
            &record,
            seed,
            &settings(filter, Outages::none()),
            profile_uncertainty(),
        );
        let sampled = sampled_epochs(&solution);
        if sums.is_empty() {
            sums = vec![0.0; sampled.len()];
        }
        for (sum, epoch) in sums.iter_mut().zip(&sampled) {
            let e = nav_error(&record, &epoch.estimate);
            *sum += nees(&e, &nav_variance(epoch));
        }
    }
    let n = runs as f64;
    let chi = ChiSquared::new(9.0 * n).unwrap();
    let (lo, hi) = (chi.inverse_cdf(0.025) / n, chi.inverse_cdf(0.975) / n);
    (sums.iter().map(|s| s / n).collect(), lo, hi)
}

/// The epochs the consistency tests sample: one every 10 s after the first 30 s.
pub(crate) fn sampled_epochs(solution: &Solution) -> Vec<&SolutionEpoch> {
    let sampled = |e: &&SolutionEpoch| {
        let t = e.estimate.nav.time.as_seconds();
        t > 30.0 && (t % 10.0) < 1e-6
    };
    solution.epochs.iter().filter(sampled).collect()
}

/// The variances of the position, velocity and attitude errors at an epoch (the diagonal of
/// P: the solution reports standard deviations only).
pub(crate) fn nav_variance(epoch: &SolutionEpoch) -> [f64; 9] {
    std::array::from_fn(|i| epoch.sd[i] * epoch.sd[i])
}

/// NEES with the diagonal of P (the solution reports standard deviations only): for the
/// nearly decoupled north/east/down errors of an aided solution this is the usual test of
/// each component's variance.
pub(crate) fn nees(e: &[f64; 9], variance: &[f64; 9]) -> f64 {
    e.iter().zip(variance).map(|(e, v)| e * e / v).sum()
}

// Filter consistency: the average NEES over 12 Monte Carlo runs stays inside its 95 %
// chi-square band at most sampled epochs (95 % expected; 85 % required, because the
// diagonal NEES ignores correlations and neighbouring epochs are correlated), and the
// time-average is within 30 % of 9.
#[test]
fn nees_is_consistent_over_a_monte_carlo_set() {
    for filter in [FilterKind::Ekf, FilterKind::Ukf] {
        let (values, lo, hi) = anees(filter, 12, 300.0);
        let inside =
            values.iter().filter(|v| **v >= lo && **v <= hi).count() as f64 / values.len() as f64;
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        assert!(
            inside >= 0.85,
            "{filter:?}: {inside} of epochs inside [{lo}, {hi}]: {values:?}"
        );
        assert!(
            (mean / 9.0 - 1.0).abs() < 0.3,
            "{filter:?}: mean ANEES {mean}"
        );
    }
}

// NIS of every aiding source is chi-square: its mean over a 10-minute run is within 20 % of
// the measurement dimension (600 position NIS have a relative standard error of
// √(2/3)/√600 ≈ 3 %, so 20 % leaves room for the model's approximations, not for a wrong R).
#[test]
fn nis_matches_the_measurement_dimension() {
    let record = vessel(5, 600.0);
    for filter in [FilterKind::Ekf, FilterKind::Ukf] {
        let solution = navigate(&record, 5, &settings(filter, Outages::none()));
        for s in solution.innovation_statistics() {
            let ratio = s.mean_nis / s.dimension as f64;
            assert!(
                (ratio - 1.0).abs() < 0.2,
                "{filter:?} {:?}: mean NIS {}",
                s.kind,
                s.mean_nis
            );
        }
    }
}

// The paper's premise: UKF and EKF agree closely on the same run. Through a 60 s outage,
// their positions differ by far less than either's error (under 10 % of the drift, or 0.2 m).
#[test]
fn ukf_and_ekf_agree_through_an_outage() {
    let record = vessel(21, 400.0);
    let outages = Outages::from_start_duration(&[(250.0, 60.0)]).unwrap();
    let ekf = navigate(&record, 21, &settings(FilterKind::Ekf, outages.clone()));
    let ukf = navigate(&record, 21, &settings(FilterKind::Ukf, outages));
    for (a, b) in ekf.epochs.iter().zip(&ukf.epochs) {
        assert_eq!(a.estimate.nav.time, b.estimate.nav.time);
        let t = a.estimate.nav.time.as_seconds();
        if !(250.0..310.0).contains(&t) {
            continue;
        }
        let gap = a.estimate.nav.position.ned_from(&b.estimate.nav.position);
        let drift = horizontal_error_m(&record, &a.estimate);
        let d = gap.x().hypot(gap.y());
        assert!(
            d < (0.1 * drift).max(0.2),
            "t {t}: EKF-UKF {d} m, drift {drift} m"
        );
    }
}

// An outage withholds updates: no innovation inside it, the position standard deviation
// grows through it, and the error at its end stays within 3.5 sigma of that covariance.
#[test]
fn outages_withhold_updates_and_the_covariance_covers_the_drift() {
    let record = vessel(3, 400.0);
    let outages = Outages::from_start_duration(&[(200.0, 60.0)]).unwrap();
    let solution = navigate(&record, 3, &settings(FilterKind::Ekf, outages));
    assert!(solution.innovations.iter().all(|r| {
        let t = r.time.as_seconds();
        !(200.0..260.0).contains(&t)
    }));
    let at = |s: f64| {
        solution
            .epochs
            .iter()
            .find(|e| (e.estimate.nav.time.as_seconds() - s).abs() < 1e-6)
            .unwrap()
    };
    let (before, end) = (at(199.0), at(259.0));
    assert!(end.sd[0] > 3.0 * before.sd[0] && end.in_outage && !before.in_outage);
    let e = nav_error(&record, &end.estimate);
    for (axis, (error, sd)) in e.iter().zip(end.sd).take(2).enumerate() {
        assert!(error.abs() < 3.5 * sd, "axis {axis}: {error} vs sd {sd}");
    }
}

// The covariance propagation rate: 10 Hz (the default) against every IMU sample (200 Hz) on
// the same run. At the end of a 60 s outage (drift ~100 m, sigma ~80 m) the horizontal
// positions differ by under 1 % of the drift and the position sigmas by under 1 %: far below
// the run-to-run spread of the drift itself (its sigma).
#[test]
fn covariance_rate_does_not_change_the_result() {
    let record = vessel(8, 320.0);
    let outages = Outages::from_start_duration(&[(250.0, 60.0)]).unwrap();
    let end_of_outage = |s: &Solution| {
        *s.epochs
            .iter()
            .find(|e| (e.estimate.nav.time.as_seconds() - 309.9).abs() < 1e-6)
            .unwrap()
    };
    for filter in [FilterKind::Ekf, FilterKind::Ukf] {
        let coarse = navigate(&record, 8, &settings(filter, outages.clone()));
        let fine_settings = EngineSettings {
            covariance_interval_s: 0.004,
            ..settings(filter, outages.clone())
        };
        let fine = navigate(&record, 8, &fine_settings);
        let (a, b) = (end_of_outage(&coarse), end_of_outage(&fine));
        let gap = a.estimate.nav.position.ned_from(&b.estimate.nav.position);
        let drift = horizontal_error_m(&record, &b.estimate);
        assert!(drift > 10.0, "the outage must produce a drift to compare");
        assert!(
            gap.x().hypot(gap.y()) < 0.01 * drift,
            "{filter:?}: gap {gap:?}, drift {drift}"
        );
        assert!(
            (a.sd[0] / b.sd[0] - 1.0).abs() < 0.01,
            "{filter:?}: sd {} vs {}",
            a.sd[0],
            b.sd[0]
        );
    }
}

// The Monte Carlo helper's pseudo-random start really perturbs the state.
#[test]
fn initial_perturbation_is_nonzero() {
    let record = vessel(1, 30.0);
    let (start, _) = initial(&record, 1);
    let truth = record.reference.states[0];
    assert!(start.nav.position.ned_from(&truth.position).norm() > 0.5);
}

// A divergence is detected and reported, never printed as numbers: an accelerometer stuck at
// 1000 g drives the speed past any vehicle's within seconds, and the run stops with an error
// naming the filter and the time.
#[test]
fn divergence_is_reported_not_printed() {
    let mut record = vessel(2, 60.0);
    let n = record.imu.len();
    record.imu.channels[3] = vec![9806.65; n];
    for filter in [FilterKind::Ekf, FilterKind::Ukf] {
        let (start, uncertainty) = initial(&record, 2);
        let result = run(
            &increments_from_series(&record.imu),
            &record.gnss,
            start,
            uncertainty.covariance(),
            &true_model(),
            &settings(filter, Outages::none()),
            &mut |_| {},
        );
        let error = result
            .expect_err("a 1000 g accelerometer must diverge")
            .to_string();
        assert!(
            error.contains(filter.name()) && error.contains("diverged at t ="),
            "{error}"
        );
    }
}

// GNSS velocity updates end to end: fixes carry the antenna velocity v + C(ω × l) of the
// simulated truth (ω from consecutive true attitudes) plus 0.05 m/s white noise; the velocity
// NIS must average its dimension (3) within 20 % and the position solution stay aided.
#[test]
fn velocity_updates_are_consistent() {
    use rand_distr::{Distribution, StandardNormal};
    let mut record = vessel(31, 300.0);
    let g = GnssSettings::default();
    let lever =
        thermonav::frames::Vector::<thermonav::frames::Body>::from_array(g.lever_arm_body_m);
    let mut rng = thermonav::rng::named_rng(31, "test/gnss-velocity");
    let states = record.reference.states.clone();
    for fix in &mut record.gnss {
        let k = states
            .partition_point(|s| s.time < fix.time)
            .min(states.len() - 2);
        let (s0, s1) = (states[k], states[k + 1]);
        let dt = s1.time.since(s0.time).as_seconds();
        let turn = (s0.attitude.inverse() * s1.attitude)
            .unit_quaternion()
            .scaled_axis()
            / dt;
        let rate = thermonav::frames::Vector::<thermonav::frames::Body>::from_raw(turn);
        let v = s0.velocity + s0.attitude * rate.cross(&lever);
        let noise: [f64; 3] = std::array::from_fn(|_| {
            let z: f64 = StandardNormal.sample(&mut rng);
            0.05 * z
        });
        fix.velocity_ned_m_s = Some(std::array::from_fn(|i| v.to_array()[i] + noise[i]));
    }
    let s = EngineSettings {
        velocity_sd_m_s: [0.05; 3],
        ..settings(FilterKind::Ekf, Outages::none())
    };
    let solution = navigate(&record, 31, &s);
    let stats = solution.innovation_statistics();
    let velocity = stats
        .iter()
        .find(|s| s.kind == thermonav::nav::measurement::MeasurementKind::Velocity)
        .expect("velocity updates ran");
    assert!(velocity.offered >= 290, "{velocity:?}");
    assert!((velocity.mean_nis / 3.0 - 1.0).abs() < 0.2, "{velocity:?}");
}

/// The horizontal errors, m, of the epochs in `epochs` that fall on truth samples and inside
/// `[from_s, to_s)`.
fn horizontal_errors_m(
    record: &VesselRecord,
    epochs: &[thermonav::nav::solution::SolutionEpoch],
    (from_s, to_s): (f64, f64),
) -> Vec<f64> {
    let states = &record.reference.states;
    epochs
        .iter()
        .filter(|e| (from_s..to_s).contains(&e.estimate.nav.time.as_seconds()))
        .filter(|e| {
            let k = states.partition_point(|s| s.time < e.estimate.nav.time);
            k < states.len() && states[k].time == e.estimate.nav.time
        })
        .map(|e| horizontal_error_m(record, &e.estimate))
        .collect()
}

// Issue 18: the RTS smoother. On a simulated survey with two 60 s outages, the smoothed
// solution is closer to the truth than the forward one with GNSS (RMS after convergence) and
// in each outage its largest error is below the forward filter's largest, by a wide margin
// (the backward pass ties both ends of the outage to GNSS); its covariance is never above
// the forward one (P_s <= P_f is a property of the recursion) and still covers its error.
#[test]
fn the_smoother_beats_the_forward_filter_with_gnss_and_in_outages() {
    let record = vessel(5, 600.0);
    let outages = Outages::from_start_duration(&[(200.0, 60.0), (400.0, 60.0)]).unwrap();
    let settings = EngineSettings {
        smooth: true,
        ..settings(FilterKind::Ekf, outages)
    };
    let solution = navigate(&record, 5, &settings);
    let (forward, smoothed) = (&solution.epochs, &solution.smoothed);
    assert!(
        smoothed.len() > 5000,
        "one epoch per covariance step: {}",
        smoothed.len()
    );
    let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt();
    let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    let aided = (60.0, 200.0);
    let (f, s) = (
        horizontal_errors_m(&record, forward, aided),
        horizontal_errors_m(&record, smoothed, aided),
    );
    assert!(f.len() > 1000 && s.len() > 1000, "{} {}", f.len(), s.len());
    eprintln!(
        "aided RMS: smoothed {:.3} m, forward {:.3} m",
        rms(&s),
        rms(&f)
    );
    assert!(
        rms(&s) < rms(&f),
        "aided RMS: smoothed {} m, forward {} m",
        rms(&s),
        rms(&f)
    );
    for window in [(200.0, 260.0), (400.0, 460.0)] {
        let (f, s) = (
            horizontal_errors_m(&record, forward, window),
            horizontal_errors_m(&record, smoothed, window),
        );
        eprintln!(
            "outage {window:?}: max smoothed {:.2} m, forward {:.2} m",
            max(&s),
            max(&f)
        );
        assert!(
            max(&s) < 0.5 * max(&f),
            "outage {window:?}: smoothed max {} m, forward max {} m",
            max(&s),
            max(&f)
        );
    }
    let forward_at = |t| forward.iter().find(|e| e.estimate.nav.time == t);
    let mut compared = 0;
    for e in smoothed {
        if let Some(f) = forward_at(e.estimate.nav.time) {
            compared += 1;
            for i in 0..9 {
                assert!(
                    e.sd[i] <= f.sd[i] * (1.0 + 1e-9),
                    "state {i} at {:?}",
                    e.estimate.nav.time
                );
            }
        }
    }
    assert!(compared > 1000, "{compared}");
    let mid_outage = smoothed
        .iter()
        .find(|e| (e.estimate.nav.time.as_seconds() - 230.0).abs() < 0.05)
        .unwrap();
    let error = nav_error(&record, &mid_outage.estimate);
    for axis in 0..2 {
        assert!(
            error[axis].abs() < 3.5 * mid_outage.sd[axis],
            "axis {axis}: {error:?} vs {:?}",
            mid_outage.sd
        );
    }
}

// Smoothing needs the EKF's covariance: the UKF is refused with the reason.
#[test]
fn the_smoother_refuses_the_ukf() {
    let record = vessel(5, 30.0);
    let settings = EngineSettings {
        smooth: true,
        ..settings(FilterKind::Ukf, Outages::none())
    };
    let (start, uncertainty) = initial(&record, 5);
    let increments = increments_from_series(&record.imu);
    let error = run(
        &increments,
        &record.gnss,
        start,
        uncertainty.covariance(),
        &true_model(),
        &settings,
        &mut |_| {},
    )
    .unwrap_err();
    assert!(
        error.to_string().contains("RTS smoother runs on the EKF"),
        "{error}"
    );
}
