//! GMWM: recovery of known composites, agreement with the exact likelihood of white noise plus
//! one Gauss-Markov process, coverage of the bootstrap intervals, and WIC selection.
//!
//! The three composites of the issue, in per-sample units (dt = 1 sample) and chosen so that
//! every process dominates the wavelet variance over at least two scales (a process that
//! dominates nowhere is not identified by any wavelet-moment method, and its interval then
//! says so by being unbounded):
//! - WN + GM: σ² = 1; Tc = 100 samples, s² = 0.5;
//! - WN + QN + GM: σ² = 1; Q² = 4; Tc = 200 samples, s² = 1;
//! - WN + RW + 2 GM: σ² = 1; γ² = 10⁻³; Tc = 5 and 100 samples, s² = 1 and 1.

use statrs::distribution::{Binomial, DiscreteCDF};
use thermonav::rng::named_rng;
use thermonav::stoch::gmwm::{
    BootstrapSettings, GmwmEstimate, ModelSpec, Term, estimate_gmwm, physical_parameters,
    select_model, simulate,
};
use thermonav::stoch::noisy_gauss_markov::{NoisyGaussMarkovOutcome, fit_noisy_gauss_markov};
use thermonav::stoch::wavelet_variance::haar_wavelet_variance;

fn gm(tc: f64, variance: f64) -> Term {
    Term::GaussMarkov {
        correlation_samples: tc,
        variance,
    }
}

fn wn_gm() -> Vec<Term> {
    vec![Term::White { variance: 1.0 }, gm(100.0, 0.5)]
}

fn wn_qn_gm() -> Vec<Term> {
    vec![
        Term::White { variance: 1.0 },
        Term::Quantisation { variance: 4.0 },
        gm(200.0, 1.0),
    ]
}

fn wn_rw_2gm() -> Vec<Term> {
    vec![
        Term::White { variance: 1.0 },
        Term::RandomWalk { variance: 1e-3 },
        gm(5.0, 1.0),
        gm(100.0, 1.0),
    ]
}

/// A record of `n` samples of `truth` from stream `name`/`seed`, fitted as `model` with
/// `replicates` bootstrap replicates, dt = 1 s.
fn estimate(truth: &[Term], model: &str, n: usize, seed: u64, replicates: usize) -> GmwmEstimate {
    let mut rng = named_rng(seed, &format!("gmwm-test/{model}"));
    let y = simulate(truth, n, &mut rng);
    let wv = haar_wavelet_variance(&y, 1.0, None, 0.95).unwrap();
    let settings = BootstrapSettings {
        replicates,
        seed,
        confidence: 0.95,
    };
    estimate_gmwm(&wv, model.parse().unwrap(), settings).unwrap()
}

/// Each estimate is within `relative` of the truth and inside its own interval (whether the
/// intervals hold the truth often enough is the coverage tests' question).
fn assert_recovers(truth: &[Term], estimate: &GmwmEstimate, relative: &[f64]) {
    let expected = physical_parameters(truth, 1.0);
    for ((p, t), tol) in estimate.parameters.iter().zip(&expected).zip(relative) {
        assert_eq!(p.kind, t.kind);
        let name = p.kind.name();
        let (low, high) = (p.ci_low.unwrap(), p.ci_high.unwrap());
        assert!(low < p.value && p.value < high, "{name}: {p:?}");
        assert!(
            (p.value / t.value - 1.0).abs() < *tol,
            "{name}: {} vs {}",
            p.value,
            t.value
        );
    }
}

// Recovery on long records (one fixed seed each). The relative tolerances are about three
// times the bootstrap's half-width of each interval at these lengths: loose enough for one
// seed, tight enough to catch a wrong closed form or a wrong unit (factors of 2 and more).
#[test]
fn recovers_white_noise_plus_gauss_markov() {
    let e = estimate(&wn_gm(), "wn+gm", 1 << 18, 1, 50);
    assert_recovers(&wn_gm(), &e, &[0.01, 0.3, 0.1]);
}

#[test]
fn recovers_white_plus_quantisation_noise_plus_gauss_markov() {
    let e = estimate(&wn_qn_gm(), "wn+qn+gm", 1 << 18, 1, 50);
    assert_recovers(&wn_qn_gm(), &e, &[0.02, 0.02, 0.3, 0.1]);
}

#[test]
fn recovers_white_noise_random_walk_and_two_gauss_markov_processes() {
    let e = estimate(&wn_rw_2gm(), "wn+rw+2gm", 1 << 18, 1, 50);
    assert_recovers(&wn_rw_2gm(), &e, &[0.02, 0.3, 0.3, 0.1, 0.3, 0.15]);
}

#[test]
fn agrees_with_the_exact_likelihood_on_white_noise_plus_gauss_markov() {
    // 2¹⁴ samples at 1 Hz of WN (density 1/√Hz) + GM (Tc = 100 s, σ = √0.5): the exact
    // maximum-likelihood fit (Kalman filter, noisy_gauss_markov) and GMWM estimate the same
    // model; each Tc lies in the other's interval, and the likelihood's σ and density lie in
    // GMWM's intervals (the likelihood reports no interval for those).
    let truth = wn_gm();
    let mut rng = named_rng(3, "gmwm-test/irregular-ml");
    let y = simulate(&truth, 1 << 14, &mut rng);
    let times: Vec<f64> = (0..y.len()).map(|k| k as f64).collect();
    let NoisyGaussMarkovOutcome::Model(ml) = fit_noisy_gauss_markov(&times, &y).unwrap() else {
        panic!("the likelihood finds the Gauss-Markov process");
    };
    let wv = haar_wavelet_variance(&y, 1.0, None, 0.95).unwrap();
    let settings = BootstrapSettings {
        replicates: 100,
        ..BootstrapSettings::default()
    };
    let e = estimate_gmwm(&wv, "wn+gm".parse().unwrap(), settings).unwrap();
    let [density, tc, sigma] = [0, 1, 2].map(|k| e.parameters[k]);
    let inside = |x: f64, p: &thermonav::stoch::gmwm::ParameterEstimate| {
        p.ci_low.unwrap() <= x && x <= p.ci_high.unwrap()
    };
    assert!(inside(ml.correlation_time_s, &tc), "{ml:?} vs {tc:?}");
    let [low, high] = ml.ci95_correlation_time_s;
    assert!(low.unwrap() <= tc.value && tc.value <= high.unwrap_or(f64::INFINITY));
    assert!(inside(ml.sigma, &sigma), "{ml:?} vs {sigma:?}");
    assert!(
        inside(ml.white_noise_density, &density),
        "{ml:?} vs {density:?}"
    );
}

/// Counts, over `seeds` records of `n` samples, how often each parameter's 95 % interval holds
/// the truth, and asserts that a two-sided binomial test against 0.95 does not reject any count
/// at the 1 % level.
fn assert_coverage(truth: &[Term], model: &str, n: usize, seeds: u64) {
    let expected = physical_parameters(truth, 1.0);
    let mut covered = vec![0u64; expected.len()];
    for seed in 1..=seeds {
        let e = estimate(truth, model, n, seed, 100);
        for (count, (p, t)) in covered.iter_mut().zip(e.parameters.iter().zip(&expected)) {
            *count += u64::from(p.ci_low.unwrap() <= t.value && t.value <= p.ci_high.unwrap());
        }
    }
    let binomial = Binomial::new(0.95, seeds).unwrap();
    for (count, t) in covered.iter().zip(&expected) {
        let p_low = binomial.cdf(*count);
        let p_high = 1.0 - binomial.cdf(count.saturating_sub(1));
        let p_value = (2.0 * p_low.min(p_high)).min(1.0);
        println!(
            "{model} {}: {count} of {seeds}, p = {p_value:.3}",
            t.kind.name()
        );
        assert!(
            p_value > 0.01,
            "{model} {}: {count} of {seeds}",
            t.kind.name()
        );
    }
}

// Coverage with seeds 1..=100 (the reduced version) and 1..=200 (the version), each
// replicate refitted with every automatic start. They pass; ignored only for time (B = 100
// bootstrap fits per seed: about 9 minutes for the four on the 2-core machine under load).
// Measured (seeds 1..=100): wn+gm: density 96, Tc 92, σ 90; wn+qn+gm: density 95, Q 91,
// Tc 89, σ 89 (p = 0.023, the lowest); wn+rw+2gm: density 96, K 96, Tc₁ 97, σ₁ 94, Tc₂ 93,
// σ₂ 92. Run them with `cargo test --release -p thermonav gmwm -- --ignored --nocapture`.
#[test]
#[ignore = "about 1 minute"]
fn intervals_cover_white_noise_plus_gauss_markov() {
    assert_coverage(&wn_gm(), "wn+gm", 1 << 15, 100);
}

#[test]
#[ignore = "about 1 minute"]
fn intervals_cover_white_plus_quantisation_noise_plus_gauss_markov() {
    assert_coverage(&wn_qn_gm(), "wn+qn+gm", 1 << 15, 100);
}

#[test]
#[ignore = "about 2 minutes"]
fn intervals_cover_white_noise_random_walk_and_two_gauss_markov_processes() {
    assert_coverage(&wn_rw_2gm(), "wn+rw+2gm", 1 << 16, 100);
}

#[test]
#[ignore = "200 seeds of three composites with 100 replicates each: minutes"]
fn intervals_cover_the_three_composites_over_200_seeds() {
    assert_coverage(&wn_gm(), "wn+gm", 1 << 15, 200);
    assert_coverage(&wn_qn_gm(), "wn+qn+gm", 1 << 15, 200);
    assert_coverage(&wn_rw_2gm(), "wn+rw+2gm", 1 << 16, 200);
}

#[test]
fn the_wavelet_information_criterion_prefers_the_true_composite_to_smaller_ones() {
    // WN + GM, 2¹⁶ samples: white noise alone and white noise + random walk leave the
    // Gauss-Markov bump unexplained, and their WIC is larger.
    let truth = wn_gm();
    let mut rng = named_rng(5, "gmwm-test/wic");
    let y = simulate(&truth, 1 << 16, &mut rng);
    let wv = haar_wavelet_variance(&y, 1.0, None, 0.95).unwrap();
    let candidates: Vec<ModelSpec> = ["wn", "wn+rw", "wn+gm"]
        .iter()
        .map(|s| s.parse().unwrap())
        .collect();
    let selection = select_model(&wv, &candidates, BootstrapSettings::default()).unwrap();
    assert!(
        selection.not_fitted.is_empty(),
        "{:?}",
        selection.not_fitted
    );
    let ranked = selection.ranked;
    assert_eq!(ranked[0].fit.model.to_string(), "wn+gm");
    assert!(ranked.iter().all(|e| e.wic.is_finite() && e.optimism > 0.0));
}

#[test]
fn model_specifications_parse_and_print() {
    let spec: ModelSpec = "WN+rw+2gm".parse().unwrap();
    assert_eq!((spec.n_terms(), spec.n_parameters()), (4, 6));
    assert_eq!(spec.to_string(), "wn+rw+2gm");
    assert_eq!(
        "gm+qn+wn".parse::<ModelSpec>().unwrap().to_string(),
        "wn+qn+gm"
    );
    for bad in ["", "wn+wn", "xx", "0gm", "gm+2gm"] {
        assert!(bad.parse::<ModelSpec>().is_err(), "{bad}");
    }
}

// `characterize` carries the default composite (the automatic choice) per channel. The wiring is checked
// against the direct path (the wavelet variance computed from the raw channel, fitted and
// mapped here), and the mapped white-noise density against the simulated unit's (the
// ADIS16364-like profile, 1 h at 50 Hz, 10 °C): within 5 %, the target for the demo
// campaign (the white density's own sampling error on 180 000 samples is about 0.3 %, the
// rest is the profile's output quantisation, which adds white-like noise of step²/12).
#[test]
fn characterize_carries_the_composite_and_its_white_noise_matches_the_simulated_unit() {
    use thermonav::sensor::adis16364_like;
    use thermonav::stoch::characterize::{CharacterizeSettings, characterize};
    use thermonav::stoch::gmwm::{
        TauBand, auto_candidates, fit_from_first_adequate_scale, map_to_filter_states,
    };
    let series = crate::streaming::chamber_record(3600.0);
    let (entry, _) = characterize(&series, 10.0, "sim", &CharacterizeSettings::default()).unwrap();
    let profile = adis16364_like();
    for channel in thermonav::imu::Channel::ALL {
        let model = &entry.channels[&channel];
        let summary = model.gmwm.as_ref().expect("a GMWM summary");
        let wv = haar_wavelet_variance(series.channel(channel), 50.0, None, 0.95).unwrap();
        let (direct, skipped) = fit_from_first_adequate_scale(&wv, &auto_candidates()).unwrap();
        assert_eq!(skipped, 0, "no internal filter in the simulation");
        assert_eq!(summary.first_scale_s, wv.scale_s[0]);
        assert_eq!(summary.model, direct.model.to_string());
        let record_s = series.len() as f64 / 50.0;
        let mapped = map_to_filter_states(&direct.terms, direct.dt_s, record_s, TauBand::default());
        assert!((summary.objective / direct.objective - 1.0).abs() < 1e-9);
        assert!((summary.white_noise_density / mapped.white_noise_density - 1.0).abs() < 1e-9);
        let truth = profile.channels[&channel].white_noise_density;
        let ratio = summary.white_noise_density / truth;
        let allan_ratio = model.allan.white_noise_density.unwrap() / truth;
        eprintln!(
            "{}: {} GMWM N / simulated {ratio:.4}, Allan N / simulated {allan_ratio:.4}, objective {:.1} over {} scales",
            channel.name(),
            summary.model,
            summary.objective,
            summary.scales
        );
        assert!((ratio - 1.0).abs() < 0.05, "{}: {ratio}", channel.name());
    }
}

// A sensor's internal averaging: white noise (σ = 1 per sample) through a 4-sample moving
// average, plus a Gauss-Markov process (Tc = 300 samples, s² = 0.01). The average has unit
// gain at zero frequency, so the white-noise density beyond its memory is unchanged: N² = σ²
// per sample (closed form). The first scales are below white noise in a shape no composite
// has; the fit leaves them out, describes the rest, and the mapped density is within 3 % of
// the truth (its sampling error on 2^20 samples is under 1 %), while a fit from the first
// scale is rejected by its own objective.
#[test]
fn an_internal_moving_average_is_left_out_and_the_density_kept() {
    use thermonav::stoch::gmwm::{
        TauBand, auto_candidates, fit_from_first_adequate_scale, map_to_filter_states,
    };
    let n = 1 << 20;
    let mut rng = named_rng(7, "gmwm-test/moving-average");
    let white = simulate(&[Term::White { variance: 1.0 }], n + 3, &mut rng);
    let slow = simulate(&[gm(300.0, 0.01)], n, &mut rng);
    let y: Vec<f64> = (0..n)
        .map(|t| white[t..t + 4].iter().sum::<f64>() / 4.0 + slow[t])
        .collect();
    let wv = haar_wavelet_variance(&y, 1.0, None, 0.95).unwrap();
    let (fit, skipped) = fit_from_first_adequate_scale(&wv, &auto_candidates()).unwrap();
    assert!(skipped >= 1, "the averaged scales are left out");
    let mapped = map_to_filter_states(
        &fit.terms,
        1.0,
        n as f64,
        TauBand {
            shortest_s: 16.0,
            longest_s: 2000.0,
        },
    );
    eprintln!(
        "skipped {skipped} scales, {} objective {:.1} over {} scales, N {:.4}",
        fit.model,
        fit.objective,
        fit.scale_samples.len(),
        mapped.white_noise_density
    );
    assert!((mapped.white_noise_density - 1.0).abs() < 0.03);
}

// Why no composite describes the ADIS16405 accelerometers. Write τ·ν²(τ) of a composite as
// Q(τ) + I(τ): quantisation noise's part Q halves per octave and every other process's part I
// never falls (`theory`'s test). A fall from scale j to j + 1 is then at most Q(j)/2, so
// Q(j) ≥ 2·fall and Q(j − 1) = 2 Q(j) ≥ 4·fall, which cannot exceed τ·ν² at j − 1. On both runs
// the accelerometers' curves rise to 1.28 s and fall beyond it by more than that, even
// taking each estimate at the end of its 95 % interval least favourable to the argument; the
// gyros' do not (gz only at its first scales, which the fit leaves out). The target for
// the accelerometers (implied curve inside the band at 90 % of the scales) is therefore out of
// reach of any sum of white, quantisation, random-walk, drift and Gauss-Markov processes.
#[test]
fn adis_accelerometer_curves_are_no_composites_wavelet_variance() {
    for run in [1, 2] {
        let columns = crate::allan::adis_16405_run(run);
        for (c, name) in ["gx", "gy", "gz", "ax", "ay", "az"].iter().enumerate() {
            let wv = haar_wavelet_variance(&columns[c], 100.0, None, 0.95).unwrap();
            let f = |v: &[f64], j: usize| v[j] * wv.scale_s[j];
            let impossible_at: Vec<f64> = (1..wv.variance.len() - 1)
                .filter(|&j| {
                    let fall = f(&wv.ci_low, j) - f(&wv.ci_high, j + 1);
                    fall > 0.0 && 4.0 * fall > f(&wv.ci_high, j - 1)
                })
                .map(|j| wv.scale_s[j])
                .collect();
            match *name {
                "ax" | "ay" | "az" => assert!(
                    impossible_at.contains(&1.28),
                    "run {run} {name}: {impossible_at:?}"
                ),
                "gz" => assert!(impossible_at.iter().all(|&s| s < 0.16), "{impossible_at:?}"),
                _ => assert!(
                    impossible_at.is_empty(),
                    "run {run} {name}: {impossible_at:?}"
                ),
            }
        }
    }
}

// Issue 37 row 10: a candidate that cannot be estimated is named with its reason, never
// ranked with a NaN WIC. On 2^7 samples (7 scales) the five-parameter wn+qn+rw+gm has too few
// scales; wn+gm (3 parameters) is still estimated.
#[test]
fn a_candidate_that_cannot_be_estimated_is_named_with_its_reason() {
    let mut rng = named_rng(7, "gmwm-test/not-fitted");
    let y = simulate(
        &[Term::White { variance: 1.0 }, gm(4.0, 0.5)],
        1 << 7,
        &mut rng,
    );
    let wv = haar_wavelet_variance(&y, 1.0, None, 0.95).unwrap();
    let candidates: Vec<ModelSpec> = ["wn+gm", "wn+qn+rw+2gm"]
        .iter()
        .map(|s| s.parse().unwrap())
        .collect();
    let selection = select_model(&wv, &candidates, BootstrapSettings::default()).unwrap();
    assert!(selection.ranked.iter().all(|e| e.wic.is_finite()));
    assert_eq!(selection.ranked.len() + selection.not_fitted.len(), 2);
    let (model, reason) = selection
        .not_fitted
        .iter()
        .find(|(m, _)| m.to_string() == "wn+qn+rw+2gm")
        .expect("the seven-parameter composite cannot be identified on 7 scales");
    assert!(
        reason.to_string().contains("cannot identify 7 parameters"),
        "{model}: {reason}"
    );
}

#[test]
fn bootstrap_settings_are_checked_with_the_setting_named() {
    let too_few = BootstrapSettings {
        replicates: 5,
        ..BootstrapSettings::default()
    };
    let text = too_few.validate().unwrap_err().to_string();
    assert_eq!(
        text,
        "replicates: 0 (no bootstrap) or 10 to 1000 bootstrap replicates, got 5"
    );
    let too_many = BootstrapSettings {
        replicates: 1_000_000_000,
        ..BootstrapSettings::default()
    };
    assert!(too_many.validate().is_err());
    let level = BootstrapSettings {
        confidence: 1.0,
        ..BootstrapSettings::default()
    };
    assert!(
        level
            .validate()
            .unwrap_err()
            .to_string()
            .starts_with("confidence:")
    );
    assert!(BootstrapSettings::default().validate().is_ok());
}

// Without a bootstrap (replicates 0, gmwm's default) the fit is the bootstrap's fit, its WIC
// the asymptotic objective + 2p (closed form), and no interval is claimed.
#[test]
fn without_a_bootstrap_the_wic_is_the_objective_plus_twice_the_parameters() {
    let mut rng = named_rng(5, "gmwm-test/no-bootstrap");
    let y = simulate(&wn_gm(), 1 << 14, &mut rng);
    let wv = haar_wavelet_variance(&y, 1.0, None, 0.95).unwrap();
    let model: ModelSpec = "wn+gm".parse().unwrap();
    let none = BootstrapSettings {
        replicates: 0,
        ..BootstrapSettings::default()
    };
    let quick = estimate_gmwm(&wv, model, none).unwrap();
    let full = estimate_gmwm(&wv, model, BootstrapSettings::default()).unwrap();
    assert_eq!(quick.fit, full.fit);
    assert_eq!(quick.wic, quick.fit.objective + 2.0 * 3.0);
    assert_eq!(quick.replicates, 0);
    assert!(
        quick
            .parameters
            .iter()
            .all(|p| p.ci_low.is_none() && p.ci_high.is_none())
    );
    assert!(
        full.parameters
            .iter()
            .all(|p| p.ci_low.is_some() && p.ci_high.is_some())
    );
}
