//! Exact maximum likelihood on irregular times: against SciPy's dense-covariance likelihood,
//! and on seeded simulations against the nominal-dt AR(1) route it improves on.

use rand::SeedableRng;
use rand_chacha::ChaCha20Rng;
use rand_distr::{Distribution, Exp};
use thermonav::stoch::gauss_markov::{
    ConfidenceLevel, ExactMlFit, ExactMlOutcome, GaussMarkov, GaussMarkovError, MeanModel,
    SampleIntervals, UpperBound, fit_gauss_markov_exact_ml, gauss_markov_log_likelihood,
    simulate_gauss_markov,
};
use thermonav::time::Timestamp;

use super::{numbers, oracle_json, relative_error};

const LEVEL: ConfidenceLevel = ConfidenceLevel::NINETY_FIVE_PERCENT;

fn fitted(outcome: ExactMlOutcome) -> ExactMlFit {
    match outcome {
        ExactMlOutcome::Fitted(fit) => fit,
        other => panic!("expected a fit, got {other:?}"),
    }
}

fn upper_s(fit: &ExactMlFit) -> f64 {
    match fit.correlation_time_interval.upper {
        UpperBound::Finite(upper_s) => upper_s,
        UpperBound::Unbounded => panic!("finite upper bound expected: {fit:?}"),
    }
}

/// `tools/oracles/gm_exact_ml.py`: an irregular series (exponential jitter plus 50-ms gaps)
/// and SciPy's dense multivariate-normal likelihood, its maximum and its LR interval.
struct ScipyOracle {
    json: serde_json::Value,
    intervals: SampleIntervals,
    values: Vec<f64>,
}

fn scipy_oracle() -> ScipyOracle {
    let json = oracle_json("gm_exact_ml.json");
    let intervals = SampleIntervals::from_times_s(&numbers(&json["times_s"])).unwrap();
    let values = numbers(&json["values"]);
    ScipyOracle {
        json,
        intervals,
        values,
    }
}

#[test]
fn log_likelihood_equals_the_dense_multivariate_normal_density() {
    let oracle = scipy_oracle();
    let fixed = &oracle.json["fixed_parameters"];
    let get = |key: &str| fixed[key].as_f64().unwrap();
    let model = GaussMarkov::new(get("tc_s"), get("sigma")).unwrap();
    let ours = gauss_markov_log_likelihood(&model, get("mean"), &oracle.intervals, &oracle.values)
        .unwrap();
    // Markov factorisation vs Cholesky of the 400 x 400 covariance: both sum ~400 terms of
    // O(1), rounding ~1e-13 relative; 1e-10 is far below any modelling error.
    assert!(
        relative_error(ours, get("log_likelihood")) < 1e-10,
        "{ours}"
    );
}

#[test]
fn maximum_and_interval_match_scipy_for_both_mean_models() {
    let oracle = scipy_oracle();
    for (mean_model, key) in [
        (MeanModel::Zero, "zero_mean"),
        (MeanModel::Estimated, "estimated_mean"),
        (MeanModel::Restricted, "restricted_mean"),
    ] {
        let expected = &oracle.json[key];
        let get = |name: &str| expected[name].as_f64().unwrap();
        let fit = fitted(
            fit_gauss_markov_exact_ml(&oracle.intervals, &oracle.values, mean_model, LEVEL)
                .unwrap(),
        );
        // The profile log-likelihood is flat at its peak: SciPy's bounded Brent works on
        // function values and locates the argmax only to about sqrt(2 eps |l| / I) ~ 6e-8 in
        // ln Tc here (|l| ~ 227, I ~ 32; ours finds the zero of the analytic slope, to
        // ~1e-12), hence 2e-6 on Tc, sigma and the mean (which depend smoothly on Tc).
        assert!(
            relative_error(fit.model.correlation_time_s(), get("tc_s")) < 2e-6,
            "{key}"
        );
        assert!(
            relative_error(fit.model.sigma(), get("sigma")) < 2e-6,
            "{key}"
        );
        assert!((fit.mean - get("mean")).abs() < 2e-6, "{key}");
        // The maximum value is insensitive to the argmax error (second order, ~1e-13); the
        // two likelihoods' rounding is ~1e-14 relative: 1e-12.
        assert!(
            relative_error(fit.log_likelihood, get("log_likelihood")) < 1e-12,
            "{key}"
        );
        // The LR bounds sit where the profile has slope ~10, so the likelihoods' rounding
        // (~1e-12 absolute) moves them by ~1e-13, and both root finders stop at 1e-14..1e-12
        // in ln Tc: 1e-10.
        let interval = fit.correlation_time_interval;
        assert!(
            relative_error(interval.lower_s, get("lr_lower_s")) < 1e-10,
            "{key}"
        );
        assert!(
            relative_error(upper_s(&fit), get("lr_upper_s")) < 1e-10,
            "{key}"
        );
    }
}

/// How sampling intervals are drawn in a bias experiment.
#[derive(Clone, Copy)]
enum Sampling {
    /// Poisson sampling: independent exponential intervals with this mean, s.
    ExponentialGaps { mean_dt_s: f64 },
    /// Intervals alternating between two values, s.
    Alternating { short_s: f64, long_s: f64 },
}

impl Sampling {
    fn intervals(self, n: usize, rng: &mut ChaCha20Rng) -> SampleIntervals {
        let mut times = Vec::with_capacity(n);
        let mut t = 0.0;
        for k in 0..n {
            times.push(t);
            t += match self {
                Sampling::ExponentialGaps { mean_dt_s } => {
                    Exp::new(1.0 / mean_dt_s).unwrap().sample(rng)
                }
                Sampling::Alternating { short_s, long_s } => {
                    if k % 2 == 0 {
                        short_s
                    } else {
                        long_s
                    }
                }
            };
        }
        SampleIntervals::from_times_s(&times).unwrap()
    }

    fn mean_dt_s(self) -> f64 {
        match self {
            Sampling::ExponentialGaps { mean_dt_s } => mean_dt_s,
            Sampling::Alternating { short_s, long_s } => 0.5 * (short_s + long_s),
        }
    }

    /// `E[exp(-dt/Tc)]`, the limit of the lag-1 least-squares coefficient (closed form).
    fn mean_phi(self, tc_s: f64) -> f64 {
        match self {
            Sampling::ExponentialGaps { mean_dt_s } => 1.0 / (1.0 + mean_dt_s / tc_s),
            Sampling::Alternating { short_s, long_s } => {
                0.5 * ((-short_s / tc_s).exp() + (-long_s / tc_s).exp())
            }
        }
    }

    /// The limit of the nominal-dt AR(1) correlation time: `-E[dt] / ln E[exp(-dt/Tc)]`.
    fn naive_limit_s(self, tc_s: f64) -> f64 {
        -self.mean_dt_s() / self.mean_phi(tc_s).ln()
    }
}

/// The AR(1) route with a nominal interval, written out plainly: least-squares lag-1
/// coefficient through the origin (the series is zero-mean) and `Tc = -dt_nominal / ln c1`.
fn naive_ar1_correlation_time(values: &[f64], nominal_dt_s: f64) -> f64 {
    let cross: f64 = values.windows(2).map(|p| p[0] * p[1]).sum();
    let square: f64 = values[..values.len() - 1].iter().map(|x| x * x).sum();
    -nominal_dt_s / (cross / square).ln()
}

struct BiasExperiment {
    ml_tc_s: Vec<f64>,
    naive_tc_s: Vec<f64>,
    covered: usize,
}

fn run_bias_experiment(
    sampling: Sampling,
    model: &GaussMarkov,
    n: usize,
    seeds: u64,
) -> BiasExperiment {
    let mut experiment = BiasExperiment {
        ml_tc_s: Vec::new(),
        naive_tc_s: Vec::new(),
        covered: 0,
    };
    for seed in 0..seeds {
        let mut rng = ChaCha20Rng::seed_from_u64(1000 + seed);
        let intervals = sampling.intervals(n, &mut rng);
        let values = simulate_gauss_markov(&intervals, model, &mut rng);
        let fit = fitted(
            fit_gauss_markov_exact_ml(&intervals, &values, MeanModel::Estimated, LEVEL).unwrap(),
        );
        experiment.covered += usize::from(
            fit.correlation_time_interval
                .contains(model.correlation_time_s()),
        );
        experiment.ml_tc_s.push(fit.model.correlation_time_s());
        experiment
            .naive_tc_s
            .push(naive_ar1_correlation_time(&values, sampling.mean_dt_s()));
    }
    experiment
}

/// Mean and standard error of the mean of replicate estimates.
fn mean_and_standard_error(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let variance = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (variance / n).sqrt())
}

#[test]
fn exact_ml_is_unbiased_under_poisson_sampling_where_nominal_ar1_is_not() {
    // Tc = 10 ms sampled at exponential intervals of mean 5 ms (Poisson sampling: the extreme
    // of jitter, coefficient of variation 1, as with dropped or event-driven samples).
    // The lag-1 least-squares coefficient tends to E[exp(-dt/Tc)] = 1/(1 + 5/10) = 2/3, which
    // exceeds exp(-E[dt]/Tc) = 0.607 by Jensen's inequality; with the nominal 5 ms the AR(1)
    // route then converges to Tc = 5 ms / ln 1.5 = 12.33 ms: +23.3 %, whatever the length of
    // the record. The exact likelihood uses each dt_k and has no such bias.
    let sampling = Sampling::ExponentialGaps { mean_dt_s: 0.005 };
    let model = GaussMarkov::new(0.010, 0.7).unwrap();
    let experiment = run_bias_experiment(sampling, &model, 5000, 20);

    let (ml_mean, ml_se) = mean_and_standard_error(&experiment.ml_tc_s);
    let (naive_mean, naive_se) = mean_and_standard_error(&experiment.naive_tc_s);
    let naive_limit = sampling.naive_limit_s(0.010);
    assert!(relative_error(naive_limit, 0.005 / 1.5_f64.ln()) < 1e-12);
    // Unbiased: the mean of 20 ML estimates lies within 4 standard errors of the truth (the
    // ML small-sample bias, O(Tc/span) ~ 1e-3 relative, is far below one standard error).
    assert!(
        (ml_mean - 0.010).abs() < 4.0 * ml_se,
        "ML {ml_mean} +- {ml_se}"
    );
    // Biased: the nominal-dt route converges to its closed-form limit (within 4 standard
    // errors; the O(1/n) bias of least squares, ~0.2 %, is below one standard error)...
    assert!(
        (naive_mean - naive_limit).abs() < 4.0 * naive_se,
        "naive {naive_mean} +- {naive_se}"
    );
    // ...which is more than 15 % too long (23.3 % in the limit; the replicate mean is within
    // 4 standard errors, about 1 %, of it).
    assert!(naive_mean > 1.15 * 0.010, "naive {naive_mean}");
    // Coverage of the 95 % likelihood-ratio interval: Binomial(20, 0.95) falls below 16 with
    // probability 1.6 %.
    assert!(
        experiment.covered >= 16,
        "covered {}/20",
        experiment.covered
    );
}

#[test]
fn exact_ml_is_unbiased_under_alternating_intervals_where_nominal_ar1_is_not() {
    // Two interleaved clocks: dt alternates 2 ms / 8 ms (mean 5 ms), Tc = 10 ms. The lag-1
    // coefficient tends to (exp(-0.2) + exp(-0.8))/2 = 0.634, so the nominal-dt route tends to
    // -5 ms / ln 0.634 = 10.97 ms (+9.7 %).
    let sampling = Sampling::Alternating {
        short_s: 0.002,
        long_s: 0.008,
    };
    let model = GaussMarkov::new(0.010, 2.0).unwrap();
    let experiment = run_bias_experiment(sampling, &model, 5000, 8);
    let (ml_mean, ml_se) = mean_and_standard_error(&experiment.ml_tc_s);
    let (naive_mean, naive_se) = mean_and_standard_error(&experiment.naive_tc_s);
    let naive_limit = sampling.naive_limit_s(0.010);
    assert!((naive_limit - 0.010_97).abs() < 1e-5);
    assert!(
        (ml_mean - 0.010).abs() < 4.0 * ml_se,
        "ML {ml_mean} +- {ml_se}"
    );
    assert!(
        (naive_mean - naive_limit).abs() < 4.0 * naive_se,
        "naive {naive_mean} +- {naive_se}"
    );
    assert!(naive_mean > 1.05 * 0.010, "naive {naive_mean}");
    // 8 replicates: Binomial(8, 0.95) is below 6 with probability 0.6 %.
    assert!(experiment.covered >= 6, "covered {}/8", experiment.covered);
}

#[test]
fn a_constant_offset_under_the_zero_mean_model_is_random_walk_like() {
    // x = 5 + 1e-6 sin(k) with the mean fixed at 0: the best Gauss-Markov explanation needs
    // phi -> 1 (the offset is carried from sample to sample). The profile grows like
    // (n/2) ln Tc until n eps^2 Tc / (2 dt) ~ 25, i.e. Tc ~ 1e9 s, beyond the 1e4 x span
    // = 2e4 s searched: the answer is "random-walk-like", not a number.
    let intervals = SampleIntervals::regular(200, 0.01).unwrap();
    let values: Vec<f64> = (0..200).map(|k| 5.0 + 1e-6 * (k as f64).sin()).collect();
    let outcome = fit_gauss_markov_exact_ml(&intervals, &values, MeanModel::Zero, LEVEL).unwrap();
    let ExactMlOutcome::RandomWalkLike { searched_up_to_s } = outcome else {
        panic!("random-walk-like expected, got {outcome:?}")
    };
    assert!(relative_error(searched_up_to_s, 1e4 * 1.99) < 1e-12);
}

#[test]
fn an_alternating_series_is_white_noise_like() {
    // AR(1) with c = -0.6: neighbours are negatively correlated, which no Gauss-Markov model
    // (phi = exp(-dt/Tc) > 0) can express; the likelihood is highest as Tc -> 0.
    let mut rng = ChaCha20Rng::seed_from_u64(7);
    let normal = rand_distr::StandardNormal;
    let mut x = 0.0;
    let values: Vec<f64> = (0..2000)
        .map(|_| {
            let draw: f64 = normal.sample(&mut rng);
            x = -0.6 * x + draw;
            x
        })
        .collect();
    let intervals = SampleIntervals::regular(2000, 0.01).unwrap();
    let outcome =
        fit_gauss_markov_exact_ml(&intervals, &values, MeanModel::Estimated, LEVEL).unwrap();
    let ExactMlOutcome::WhiteNoiseLike { searched_down_to_s } = outcome else {
        panic!("white-noise-like expected, got {outcome:?}")
    };
    // A tenth of the 10 ms interval, through exp(ln(.)): 1e-12.
    assert!(relative_error(searched_down_to_s, 0.001) < 1e-12);
}

#[test]
fn long_correlation_gives_an_unbounded_upper_end() {
    // Tc = 100 s observed for 20 s with an unknown mean: the data cannot exclude a random
    // walk. The restricted likelihood tends to the random walk's as Tc -> infinity, so its
    // LR interval has no upper end (or its peak is at the random-walk edge).
    let mut rng = ChaCha20Rng::seed_from_u64(11);
    let intervals = SampleIntervals::regular(2000, 0.01).unwrap();
    let model = GaussMarkov::new(100.0, 1.0).unwrap();
    let values = simulate_gauss_markov(&intervals, &model, &mut rng);
    let restricted =
        fit_gauss_markov_exact_ml(&intervals, &values, MeanModel::Restricted, LEVEL).unwrap();
    match restricted {
        ExactMlOutcome::Fitted(fit) => {
            assert_eq!(fit.correlation_time_interval.upper, UpperBound::Unbounded);
            assert!(fit.model.correlation_time_s().is_finite());
        }
        ExactMlOutcome::RandomWalkLike { .. } => {}
        other => panic!("a long correlation expected, got {other:?}"),
    }
    // The profiled (not restricted) likelihood falls like -(1/2) ln Tc beyond the record (the
    // start value's stationary density 1/sigma still counts while the mean absorbs it), so
    // its interval is finite: bounded by about exp(2 x 1.92) = 47 times the scale where that
    // decline starts, which is why MeanModel::Restricted is the one to use for Tc >~ span.
    let profiled = fitted(
        fit_gauss_markov_exact_ml(&intervals, &values, MeanModel::Estimated, LEVEL).unwrap(),
    );
    assert!(matches!(
        profiled.correlation_time_interval.upper,
        UpperBound::Finite(_)
    ));
}

#[test]
fn timestamps_units_and_scale_do_not_change_the_fit() {
    // Times on a whole-millisecond grid are exact both as f64 differences (to ~1e-16 s) and
    // as integer nanoseconds; values scaled by 1e-6 or 1e6 rescale sigma and the mean only.
    // The internal normalisation makes the searches identical up to rounding: 1e-9.
    let mut rng = ChaCha20Rng::seed_from_u64(3);
    let millis: Vec<i64> = (0..3000_i64).map(|k| k * 5 + (k * 7919 % 3)).collect();
    let seconds: Vec<f64> = millis.iter().map(|&m| m as f64 / 1000.0).collect();
    let stamps: Vec<Timestamp> = millis
        .iter()
        .map(|&m| Timestamp::from_nanos(m * 1_000_000))
        .collect();
    let intervals = SampleIntervals::from_times_s(&seconds).unwrap();
    let model = GaussMarkov::new(0.05, 1.0).unwrap();
    let values: Vec<f64> = simulate_gauss_markov(&intervals, &model, &mut rng)
        .iter()
        .map(|x| x + 0.3)
        .collect();
    let fit_of = |intervals: &SampleIntervals, values: &[f64]| {
        fitted(fit_gauss_markov_exact_ml(intervals, values, MeanModel::Estimated, LEVEL).unwrap())
    };
    let reference = fit_of(&intervals, &values);
    let from_stamps = fit_of(&SampleIntervals::from_timestamps(&stamps).unwrap(), &values);
    let tc = reference.model.correlation_time_s();
    let from_stamps_tc = from_stamps.model.correlation_time_s();
    assert!(
        relative_error(from_stamps_tc, tc) < 1e-9,
        "{from_stamps_tc} vs {tc}"
    );
    for scale in [1e-6, 1e6] {
        let scaled: Vec<f64> = values.iter().map(|x| x * scale).collect();
        let fit = fit_of(&intervals, &scaled);
        let scaled_tc = fit.model.correlation_time_s();
        assert!(
            relative_error(scaled_tc, tc) < 1e-9,
            "scale {scale}: {scaled_tc} vs {tc}"
        );
        assert!(relative_error(fit.model.sigma(), reference.model.sigma() * scale) < 1e-9);
        assert!(relative_error(fit.mean, reference.mean * scale) < 1e-9);
        // l(x scale) = l(x) - n ln(scale) (Jacobian of the change of units).
        let shifted = reference.log_likelihood - 3000.0 * scale.ln();
        assert!((fit.log_likelihood - shifted).abs() < 1e-9 * shifted.abs());
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let intervals = SampleIntervals::regular(5, 0.01).unwrap();
    let fit = |values: &[f64], mean_model| {
        fit_gauss_markov_exact_ml(&intervals, values, mean_model, LEVEL)
    };
    assert_eq!(
        fit(&[1.0, 2.0, 3.0], MeanModel::Zero),
        Err(GaussMarkovError::LengthMismatch {
            times: 5,
            values: 3
        })
    );
    assert!(matches!(
        fit(&[1.0, f64::NAN, 3.0, 1.0, 2.0], MeanModel::Zero),
        Err(GaussMarkovError::NonFinite { index: 1, .. })
    ));
    assert!(matches!(
        fit(&[2.0; 5], MeanModel::Estimated),
        Err(GaussMarkovError::ZeroVariance { .. })
    ));
    assert!(matches!(
        fit(&[0.0; 5], MeanModel::Zero),
        Err(GaussMarkovError::ZeroVariance { .. })
    ));
    let two = SampleIntervals::regular(2, 0.01).unwrap();
    assert_eq!(
        fit_gauss_markov_exact_ml(&two, &[1.0, 2.0], MeanModel::Zero, LEVEL),
        Err(GaussMarkovError::TooShort { needed: 3, got: 2 })
    );
    let model = GaussMarkov::new(1.0, 1.0).unwrap();
    assert!(matches!(
        gauss_markov_log_likelihood(&model, f64::INFINITY, &intervals, &[0.0; 5]),
        Err(GaussMarkovError::NonFinite { .. })
    ));
}

#[test]
fn likelihood_that_is_not_representable_is_an_error() {
    // Values 1e200 sigma away from the mean: the squared innovation overflows.
    let intervals = SampleIntervals::regular(3, 1.0).unwrap();
    let model = GaussMarkov::new(1.0, 1e-100).unwrap();
    assert!(matches!(
        gauss_markov_log_likelihood(&model, 0.0, &intervals, &[1e100, -1e100, 1e100]),
        Err(GaussMarkovError::OutOfRange { .. })
    ));
}
