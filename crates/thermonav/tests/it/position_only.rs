//! Issue 18: consistency without heading aiding. The vessel's GNSS gives positions only, so the
//! heading (and the z-gyro bias) are observable only through horizontal accelerations: the
//! turns and speed changes of `harbour_survey`. The reported sd must still cover the error.

use super::navigation::{
    initial, nav_error, nav_variance, navigate_from, nees, profile_uncertainty, sampled_epochs,
    settings, true_model, vessel,
};
use statrs::distribution::{ChiSquared, ContinuousCDF};
use thermonav::imu::Channel;
use thermonav::nav::engine::{
    Aiding, BiasHypotheses, EngineSettings, FilterKind, increments_from_series,
};
use thermonav::nav::navigate::run;
use thermonav::nav::outage::Outages;
use thermonav::nav::solution::Solution;
use thermonav::sensor::adis16364_like;
use thermonav::sim::vessel::VesselRecord;

const POSITION_ONLY: Aiding = Aiding {
    position: true,
    velocity: false,
    heading: false,
};

/// What 12 position-only runs give at the sampled epochs (every 10 s after the first 30 s).
struct Consistency {
    /// Average NEES of position, velocity and attitude over the runs, per epoch.
    anees: Vec<f64>,
    /// Its two-sided 95 % band for that many runs.
    band: (f64, f64),
    /// Heading error over its sd, every run and epoch.
    heading_z: Vec<f64>,
    /// Largest heading error, deg, and the sd the filter gave for it.
    worst_heading_deg: (f64, f64),
}

fn position_only(filter: FilterKind) -> EngineSettings {
    EngineSettings {
        aiding: POSITION_ONLY,
        ..settings(filter, Outages::none())
    }
}

fn navigate(record: &VesselRecord, seed: u64, settings: &EngineSettings) -> Solution {
    navigate_from(record, seed, settings, profile_uncertainty())
}

/// Position-only settings with the z-gyro bias prior split into the default Gaussian sum.
fn with_bias_hypotheses(filter: FilterKind) -> EngineSettings {
    EngineSettings {
        bias_hypotheses: Some(BiasHypotheses::default()),
        ..position_only(filter)
    }
}

fn consistency(settings: &EngineSettings, runs: u64, duration_s: f64) -> Consistency {
    let mut sums: Vec<f64> = Vec::new();
    let mut heading_z = Vec::new();
    let mut worst_heading_deg = (0.0f64, 0.0);
    for seed in 0..runs {
        let record = vessel(100 + seed, duration_s);
        let solution = navigate(&record, seed, settings);
        let sampled = sampled_epochs(&solution);
        if sums.is_empty() {
            sums = vec![0.0; sampled.len()];
        }
        for (sum, epoch) in sums.iter_mut().zip(&sampled) {
            let e = nav_error(&record, &epoch.estimate);
            *sum += nees(&e, &nav_variance(epoch));
            heading_z.push(e[8] / epoch.sd[8]);
            if e[8].abs().to_degrees() > worst_heading_deg.0 {
                worst_heading_deg = (e[8].abs().to_degrees(), epoch.sd[8].to_degrees());
            }
        }
    }
    let n = runs as f64;
    let chi = ChiSquared::new(9.0 * n).unwrap();
    Consistency {
        anees: sums.iter().map(|s| s / n).collect(),
        band: (chi.inverse_cdf(0.025) / n, chi.inverse_cdf(0.975) / n),
        heading_z,
        worst_heading_deg,
    }
}

// Issue 18's target: on 12 simulated position-only runs of 900 s (the transit's speed changes
// and slow turn, two survey lines and two 6°/s U-turns), the average NEES is inside its 95 %
// band at >= 80 % of the sampled epochs (95 % expected of a consistent filter; 80 % because the
// diagonal NEES ignores correlations and neighbouring epochs are correlated). The start is the
// truth perturbed by half an sd, P0 the profile's (the distribution the units' biases are
// drawn from), so any inconsistency is the filter's.
//
// A single filter does not meet it (run print_position_only_runs for the detail): measured
// 2026-12-03, EKF 0 % of epochs inside [6.76, 11.55], mean ANEES 372, heading error / sd RMS
// 18.6; UKF 0 %, 294, 16.4. The z-gyro turn-on bias (sd 1 °/s) turns the heading by tens of
// degrees before the first speed change can reveal it, the filter linearised about that heading
// then settles on a wrong bias with a small sd, and 5 of 12 runs pass 90° of heading error.
// With the bias prior split into the default Gaussian sum (41 members, nav::gaussian_sum),
// measured the same day: EKF 83.9 % inside, mean ANEES 9.77, heading error / sd RMS 1.44; UKF
// 83.9 %, 9.86, 1.46. What is left over: 5-6 % of the heading errors lie beyond 3 sd (0.27 %
// for a Gaussian), the worst 79° at an sd of 17°, in the first two minutes.
#[test]
fn nees_without_heading_aiding_is_consistent() {
    let mut fractions = Vec::new();
    for filter in [FilterKind::Ekf, FilterKind::Ukf] {
        let c = consistency(&with_bias_hypotheses(filter), 12, 900.0);
        let (lo, hi) = c.band;
        let inside =
            c.anees.iter().filter(|v| **v >= lo && **v <= hi).count() as f64 / c.anees.len() as f64;
        let mean = c.anees.iter().sum::<f64>() / c.anees.len() as f64;
        let rms_z =
            (c.heading_z.iter().map(|z| z * z).sum::<f64>() / c.heading_z.len() as f64).sqrt();
        let beyond_3 = c.heading_z.iter().filter(|z| z.abs() > 3.0).count();
        eprintln!(
            "{filter:?}: inside {inside:.3} of [{lo:.2}, {hi:.2}], mean ANEES {mean:.2}, heading \
             error/sd RMS {rms_z:.2}, {beyond_3} of {} beyond 3 sd, worst {:.2} deg at sd {:.2} deg",
            c.heading_z.len(),
            c.worst_heading_deg.0,
            c.worst_heading_deg.1
        );
        eprintln!(
            "{filter:?} ANEES: {:?}",
            c.anees
                .iter()
                .map(|v| (v * 10.0).round() / 10.0)
                .collect::<Vec<_>>()
        );
        fractions.push((filter, inside));
    }
    for (filter, inside) in fractions {
        assert!(inside >= 0.8, "{filter:?}: {inside} inside");
    }
}

// A sum of one member is the single filter, record for record, bit for bit (the split of one
// is the prior itself, and a lone member's epochs and innovations pass through unchanged).
#[test]
fn a_gaussian_sum_of_one_is_the_single_filter() {
    let record = vessel(11, 120.0);
    for filter in [FilterKind::Ekf, FilterKind::Ukf] {
        let one = EngineSettings {
            bias_hypotheses: Some(BiasHypotheses {
                members: 1,
                ..BiasHypotheses::default()
            }),
            ..position_only(filter)
        };
        let single = navigate(&record, 11, &position_only(filter));
        let sum = navigate(&record, 11, &one);
        assert!(single.epochs.len() > 1000 && single.innovations.len() > 100);
        assert_eq!(single.epochs, sum.epochs, "{filter:?}");
        assert_eq!(single.innovations, sum.innovations, "{filter:?}");
    }
}

// Diagnostic (run by hand with --ignored --nocapture): per run, the true z-gyro constant bias
// and the heading error, its sd and the z-gyro bias estimate every 30 s.
#[test]
#[ignore]
fn print_position_only_runs() {
    use thermonav::sim::unit::SimulatedUnit;
    let profile = adis16364_like();
    let filter = match std::env::var("FILTER").as_deref() {
        Ok("ukf") => FilterKind::Ukf,
        _ => FilterKind::Ekf,
    };
    let runs: u64 = std::env::var("RUNS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(12);
    for seed in 0..runs {
        let record = vessel(100 + seed, 900.0);
        let unit = SimulatedUnit { serial: 100 + seed };
        let p = &profile.channels[&Channel::Gz];
        let d = 17.0 - profile.reference_temperature_c;
        let bz = unit.fixed_bias(&profile, Channel::Gz)
            + unit.power_on_offset(&profile, Channel::Gz, 100 + seed, "vessel")
            + p.bias_temperature_coefficient_per_c * d
            + p.bias_temperature_quadratic_per_c2 * d * d;
        let settings = match std::env::var("GAUSSIAN_SUM") {
            Ok(_) => with_bias_hypotheses(filter),
            Err(_) => position_only(filter),
        };
        let solution = navigate(&record, seed, &settings);
        let mut line = format!("seed {seed} true bz {:.3} deg/s:", bz.to_degrees());
        for e in &solution.epochs {
            let t = e.estimate.nav.time.as_seconds();
            if (t % 30.0) > 1e-6 && t > 1e-6 {
                continue;
            }
            let err = nav_error(&record, &e.estimate);
            line += &format!(
                " [{t:.0} psi {:.1}/{:.1} bz {:.3}/{:.3}]",
                err[8].to_degrees(),
                e.sd[8].to_degrees(),
                e.estimate.sensors.gyro_bias_rad_s[2].to_degrees(),
                e.sd[11].to_degrees()
            );
        }
        eprintln!("{line}");
    }
}

// Closed form: with no fix at all, nothing observes the sensor biases, so each bias variance
// must stay at its initial value: the turn-on bias is a constant the filter has not seen,
// whatever the Gauss-Markov wander on top of it (its stationary variance is below the initial
// one). The model used to let it decay to the Gauss-Markov σ² within a few Tc (1 °/s down to
// 0.010 °/s in 10 minutes; a quarter of the sd lost in the 60 s here), after which the filter
// believed a bias it had never estimated. 1e-9 relative: rounding over 600 steps. (60 s: a free
// inertial solution with 1 °/s biases tumbles within minutes.)
#[test]
fn an_unobserved_turn_on_bias_is_not_forgotten() {
    let record = vessel(7, 60.0);
    let (start, uncertainty) = initial(&record, 7);
    let mut increments = increments_from_series(&record.imu);
    increments.retain(|i| i.time.as_seconds() <= 60.0);
    for filter in [FilterKind::Ekf, FilterKind::Ukf] {
        let solution = run(
            &increments,
            &[],
            start,
            uncertainty.covariance(),
            &true_model(),
            &settings(filter, Outages::none()),
            &mut |_| {},
        )
        .unwrap();
        let (first, last) = (solution.epochs[0], *solution.epochs.last().unwrap());
        assert!(last.estimate.nav.time.as_seconds() > 59.9);
        for state in 9..15 {
            assert!(
                (last.sd[state] / first.sd[state] - 1.0).abs() < 1e-9,
                "{filter:?} state {state}: sd {} at the start, {} at the end",
                first.sd[state],
                last.sd[state]
            );
        }
    }
}

/// EKF against UKF without heading aiding through one 60 s outage of the survey, for six
/// seeds: the largest horizontal gap between them, each filter's largest horizontal error (m),
/// and each filter's heading error over its sd at the outage's start.
struct OutageGap {
    gap_m: f64,
    max_error_m: [f64; 2],
    heading_z: [f64; 2],
    heading_deg: [(f64, f64); 2],
}

fn outage_gaps(bias_hypotheses: Option<BiasHypotheses>) -> Vec<OutageGap> {
    use super::navigation::horizontal_error_m;
    let outages = Outages::from_start_duration(&[(640.0, 60.0)]).unwrap();
    let mut gaps = Vec::new();
    for seed in 0..6 {
        let record = vessel(200 + seed, 720.0);
        let run_with = |filter| {
            let s = EngineSettings {
                aiding: POSITION_ONLY,
                bias_hypotheses,
                ..settings(filter, outages.clone())
            };
            navigate(&record, seed, &s)
        };
        let (ekf, ukf) = (run_with(FilterKind::Ekf), run_with(FilterKind::Ukf));
        let mut g = OutageGap {
            gap_m: 0.0,
            max_error_m: [0.0; 2],
            heading_z: [f64::NAN; 2],
            heading_deg: [(0.0, 0.0); 2],
        };
        for (a, b) in ekf.epochs.iter().zip(&ukf.epochs) {
            if !a.in_outage {
                continue;
            }
            if g.heading_z[0].is_nan() {
                for (k, epoch) in [a, b].into_iter().enumerate() {
                    let e = nav_error(&record, &epoch.estimate)[8];
                    g.heading_z[k] = e / epoch.sd[8];
                    g.heading_deg[k] = (e.to_degrees(), epoch.sd[8].to_degrees());
                }
            }
            let d = a.estimate.nav.position.ned_from(&b.estimate.nav.position);
            g.gap_m = g.gap_m.max(d.x().hypot(d.y()));
            g.max_error_m[0] = g.max_error_m[0].max(horizontal_error_m(&record, &a.estimate));
            g.max_error_m[1] = g.max_error_m[1].max(horizontal_error_m(&record, &b.estimate));
        }
        gaps.push(g);
    }
    gaps
}

// Issue 18: without heading aiding the EKF and the UKF agree once the z-gyro bias prior is a
// Gaussian sum. Through a 60 s outage after 640 s of position-only fixes, on six seeds, the
// largest horizontal gap between them is within 10 m (measured 1.3-6.7 m, against largest
// errors of 16-180 m), and each filter's heading error at the outage's start is within 3 of its
// sds (measured within 1.1). As single filters they differed by up to 368 m on the same runs
// (2026-12-03: 88, 368, 43 and 344 m on four of the six seeds), where one of the two had lost
// its heading by 90-150° while reporting an sd of 2-4°.
#[test]
fn ekf_and_ukf_agree_without_heading_aiding_as_gaussian_sums() {
    for (seed, g) in outage_gaps(Some(BiasHypotheses::default()))
        .iter()
        .enumerate()
    {
        assert!(
            g.gap_m < 10.0,
            "seed {seed}: gap {} m (largest errors {:?} m)",
            g.gap_m,
            g.max_error_m
        );
        for (k, z) in g.heading_z.iter().enumerate() {
            assert!(
                z.abs() < 3.0,
                "seed {seed} filter {k}: {:?}",
                g.heading_deg[k]
            );
        }
    }
}

// Diagnostic (run by hand with --ignored --nocapture): the same outage with single filters
// (GAUSSIAN_SUM=1 for the sums).
#[test]
#[ignore]
fn print_ekf_ukf_gap_without_heading_aiding() {
    let sums = std::env::var("GAUSSIAN_SUM")
        .is_ok()
        .then(BiasHypotheses::default);
    for (seed, g) in outage_gaps(sums).iter().enumerate() {
        let [(a, sa), (b, sb)] = g.heading_deg;
        eprintln!(
            "seed {seed}: gap {:.1} m, EKF max {:.1} m, UKF max {:.1} m; heading error at the \
             outage's start: EKF {a:.1} deg (sd {sa:.1}), UKF {b:.1} deg (sd {sb:.1})",
            g.gap_m, g.max_error_m[0], g.max_error_m[1]
        );
    }
}
