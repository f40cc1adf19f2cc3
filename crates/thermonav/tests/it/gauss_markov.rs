//! Gauss-Markov estimation: the classical ACF fit against SciPy, and the unequal-sampling
//! argument of the paper made rigorous: exact maximum likelihood with each step's own dt is
//! unbiased where AR(1) with the nominal dt is not.

use crate::oracle_json;
use rand::RngExt;
use rand_distr::{Distribution, StandardNormal};
use thermonav::rng::named_rng;
use thermonav::stoch::gauss_markov::{GaussMarkovOutcome, LagWindow, fit_autocovariance};
use thermonav::stoch::noisy_gauss_markov::{NoisyGaussMarkovOutcome, fit_noisy_gauss_markov};

// curve_fit solves the same least-squares problem by Levenberg-Marquardt; both converge to the
// same minimum to ~1e-8 relative (the problem is well conditioned; tolerances 1e-14 there).
#[test]
fn acf_fit_matches_scipy_curve_fit() {
    let oracle = oracle_json("gm_acf_fit.json");
    let gamma: Vec<f64> = oracle["gamma"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let out = fit_autocovariance(&gamma, 0.5, LagWindow::Fixed(60));
    let GaussMarkovOutcome::Model { model, .. } = out else {
        panic!("{out:?}")
    };
    let tc = oracle["correlation_time_s"].as_f64().unwrap();
    let s2 = oracle["sigma_squared"].as_f64().unwrap();
    assert!(
        (model.correlation_time_s / tc - 1.0).abs() < 1e-8,
        "{} vs {tc}",
        model.correlation_time_s
    );
    assert!((model.sigma * model.sigma / s2 - 1.0).abs() < 1e-8);
}

/// A Gauss-Markov record on a 200 Hz grid from which 20 % of the samples are dropped, as a
/// logger that misses samples does. Returns (times, values).
fn dropped_record(tc_s: f64, seconds: f64, seed: u64) -> (Vec<f64>, Vec<f64>) {
    let mut rng = named_rng(seed, "gm-dropped");
    let (mut times, mut values) = (Vec::new(), Vec::new());
    let mut x: f64 = StandardNormal.sample(&mut rng);
    let mut last_t = 0.0;
    for k in 0..(seconds * 200.0) as usize {
        let t = k as f64 * 0.005;
        if k > 0 && rng.random_bool(0.2) {
            continue;
        }
        let phi = (-(t - last_t) / tc_s).exp();
        let z: f64 = StandardNormal.sample(&mut rng);
        x = phi * x + (1.0 - phi * phi).sqrt() * z;
        times.push(t);
        values.push(x);
        last_t = t;
    }
    (times, values)
}

// Tc = 2 s, 600 s per record, 8 seeds. With 20 % drops the interval is 5 ms × G, G geometric
// (P(G = g) = 0.8 · 0.2^(g−1)), so the lag-1 correlation is E[φ] = Σ 0.8·0.2^(g−1) e^(−0.0025 g),
// and AR(1) with the nominal 5 ms returns Tc_naive = −0.005 / ln E[φ] ≈ 1.60 s: a 20 % bias
// (Jensen plus the ignored gaps). The mean naive estimate over the seeds must sit within 5 % of
// that closed form, i.e. far from the truth. The exact likelihood, using each dt_k, must cover
// the truth with its 95 % interval in at least 6 of 8 records (P ≤ 1 % otherwise) and average
// within 10 % (per-record relative se ≈ √(2 Tc / T) ≈ 8 %, so ≈ 3 % for the mean).
#[test]
fn exact_likelihood_is_unbiased_where_nominal_dt_ar1_is_not() {
    let tc = 2.0;
    let expected_phi: f64 = (1..60)
        .map(|g| 0.8 * 0.2f64.powi(g - 1) * (-0.0025 * g as f64).exp())
        .sum();
    let naive_closed_form = -0.005 / expected_phi.ln();
    let (mut naive_sum, mut exact_sum, mut covered) = (0.0, 0.0, 0);
    for seed in 0..8 {
        let (times, values) = dropped_record(tc, 600.0, seed);
        let c1 = values.windows(2).map(|w| w[0] * w[1]).sum::<f64>()
            / values[..values.len() - 1]
                .iter()
                .map(|v| v * v)
                .sum::<f64>();
        naive_sum += -0.005 / c1.ln();
        let NoisyGaussMarkovOutcome::Model(fit) = fit_noisy_gauss_markov(&times, &values).unwrap()
        else {
            panic!("seed {seed}")
        };
        exact_sum += fit.correlation_time_s;
        let [lo, hi] = fit.ci95_correlation_time_s;
        covered += usize::from(lo.is_some_and(|l| l <= tc) && hi.is_none_or(|h| tc <= h));
    }
    let (naive, exact) = (naive_sum / 8.0, exact_sum / 8.0);
    assert!(
        (naive / naive_closed_form - 1.0).abs() < 0.05,
        "naive {naive} vs closed form {naive_closed_form}"
    );
    assert!(
        naive < 0.85 * tc,
        "the nominal-dt AR(1) should be biased low: {naive}"
    );
    assert!((exact / tc - 1.0).abs() < 0.10, "exact {exact}");
    assert!(covered >= 6, "covered {covered}/8");
}
