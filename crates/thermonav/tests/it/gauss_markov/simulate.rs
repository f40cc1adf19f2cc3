//! The exact simulator: stationary variance and per-step correlation, checked statistically
//! with bounds from the estimators' standard errors.

use rand::SeedableRng;
use rand_chacha::ChaCha20Rng;
use thermonav::stoch::gauss_markov::{
    GaussMarkov, GaussMarkovError, SampleIntervals, simulate_gauss_markov,
};
use thermonav::time::Timestamp;

/// Mean square about the known mean 0.
fn mean_square(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64
}

/// Asymptotic standard error of the mean square of `n` samples of an AR(1) process with
/// coefficient `phi` and variance `variance` (Bartlett): `var(s^2) = (2 sigma^4 / n) sum_k
/// rho_k^2 = (2 sigma^4 / n) (1 + phi^2) / (1 - phi^2)`.
fn variance_standard_error(variance: f64, phi: f64, n: usize) -> f64 {
    variance * (2.0 / n as f64 * (1.0 + phi * phi) / (1.0 - phi * phi)).sqrt()
}

/// Least-squares lag-1 coefficient through the origin over the pairs `(x[k-1], x[k])` with
/// `k` in `ends`.
fn lag_one_coefficient(x: &[f64], ends: impl Iterator<Item = usize>) -> (f64, usize) {
    let (mut cross, mut square, mut pairs) = (0.0, 0.0, 0);
    for k in ends {
        cross += x[k - 1] * x[k];
        square += x[k - 1] * x[k - 1];
        pairs += 1;
    }
    (cross / square, pairs)
}

// Every statistical bound below is 4 asymptotic standard errors: a correct simulator fails
// one with probability 6e-5 for a fresh seed, while a wrong variance or transition (e.g. the
// first-order driving noise q dt) lies tens of standard errors away.

#[test]
fn regular_path_has_the_model_variance_and_lag_correlation() {
    let model = GaussMarkov::new(0.05, 2.0).unwrap();
    let n = 50_000;
    let intervals = SampleIntervals::regular(n, 0.005).unwrap();
    let path = simulate_gauss_markov(&intervals, &model, &mut ChaCha20Rng::seed_from_u64(42));
    assert_eq!(path.len(), n);
    let phi = model.phi(0.005);
    let variance_se = variance_standard_error(4.0, phi, n);
    assert!(
        (mean_square(&path) - 4.0).abs() < 4.0 * variance_se,
        "{}",
        mean_square(&path)
    );
    // Standard error of the lag-1 least-squares coefficient of an AR(1): sqrt((1 - phi^2)/n).
    let (r1, pairs) = lag_one_coefficient(&path, 1..n);
    let r1_se = ((1.0 - phi * phi) / pairs as f64).sqrt();
    assert!((r1 - phi).abs() < 4.0 * r1_se, "r1 {r1} vs {phi}");
}

#[test]
fn variance_does_not_depend_on_the_sampling_rate() {
    // The same process (Tc = 50 ms, sigma = 2) over 200 s at 10 Hz and at 1000 Hz. At 10 Hz
    // dt/Tc = 2: a simulator using the first-order driving noise q dt would give a stationary
    // variance of q dt / (1 - phi^2) = 4 sigma^2 / (1 - e^-4) = 16.3 instead of 4.
    let model = GaussMarkov::new(0.05, 2.0).unwrap();
    let mut rng = ChaCha20Rng::seed_from_u64(2009);
    for (rate_hz, n) in [(10.0, 2_000), (1000.0, 200_000)] {
        let dt_s = 1.0 / rate_hz;
        let intervals = SampleIntervals::regular(n, dt_s).unwrap();
        let path = simulate_gauss_markov(&intervals, &model, &mut rng);
        let se = variance_standard_error(4.0, model.phi(dt_s), n);
        let observed = mean_square(&path);
        assert!(
            (observed - 4.0).abs() < 4.0 * se,
            "{rate_hz} Hz: {observed} +- {se}"
        );
        let euler_variance = model.spectral_density_q() * dt_s / (1.0 - model.phi(dt_s).powi(2));
        if rate_hz == 10.0 {
            assert!(
                (euler_variance - 4.0).abs() > 40.0 * se,
                "the check discriminates"
            );
        }
    }
}

#[test]
fn each_step_uses_its_own_interval() {
    // dt alternates 2 ms / 8 ms with Tc = 10 ms: pairs across a 2-ms step correlate by
    // exp(-0.2) = 0.819, across an 8-ms step by exp(-0.8) = 0.449. A simulator that used the
    // mean interval would give exp(-0.5) = 0.607 for both.
    let model = GaussMarkov::new(0.010, 1.0).unwrap();
    let n = 40_000;
    let times: Vec<Timestamp> = (0..n as i64)
        .map(|k| Timestamp::from_nanos(k / 2 * 10_000_000 + (k % 2) * 2_000_000))
        .collect();
    let intervals = SampleIntervals::from_timestamps(&times).unwrap();
    assert_eq!(&intervals.dt_s()[..3], &[0.002, 0.008, 0.002]);
    let path = simulate_gauss_markov(&intervals, &model, &mut ChaCha20Rng::seed_from_u64(5));
    for (first_end, dt_s) in [(1, 0.002), (2, 0.008)] {
        let phi = model.phi(dt_s);
        let (r, pairs) = lag_one_coefficient(&path, (first_end..n).step_by(2));
        let se = ((1.0 - phi * phi) / pairs as f64).sqrt();
        assert!((r - phi).abs() < 4.0 * se, "dt {dt_s}: {r} vs {phi}");
    }
}

#[test]
fn the_seed_fixes_the_path_and_one_sample_is_allowed() {
    let model = GaussMarkov::new(1.0, 0.5).unwrap();
    let intervals = SampleIntervals::regular(100, 0.1).unwrap();
    let a = simulate_gauss_markov(&intervals, &model, &mut ChaCha20Rng::seed_from_u64(9));
    let b = simulate_gauss_markov(&intervals, &model, &mut ChaCha20Rng::seed_from_u64(9));
    assert_eq!(a, b);
    let single = SampleIntervals::regular(1, 0.1).unwrap();
    let one = simulate_gauss_markov(&single, &model, &mut ChaCha20Rng::seed_from_u64(9));
    assert_eq!(one.len(), 1);
    assert!(one[0].is_finite());
}

#[test]
fn sampling_times_are_validated() {
    assert_eq!(
        SampleIntervals::from_times_s(&[]),
        Err(GaussMarkovError::TooShort { needed: 1, got: 0 })
    );
    assert!(matches!(
        SampleIntervals::from_times_s(&[0.0, f64::NAN]),
        Err(GaussMarkovError::NonFinite { index: 1, .. })
    ));
    assert!(matches!(
        SampleIntervals::from_times_s(&[0.0, 0.1, 0.1]),
        Err(GaussMarkovError::NonIncreasingTime { index: 2, .. })
    ));
    assert!(matches!(
        SampleIntervals::from_times_s(&[-1e308, 1e308]),
        Err(GaussMarkovError::OutOfRange { .. })
    ));
    let stamps = [Timestamp::from_nanos(5), Timestamp::from_nanos(3)];
    assert!(matches!(
        SampleIntervals::from_timestamps(&stamps),
        Err(GaussMarkovError::NonIncreasingTime { index: 1, .. })
    ));
    assert!(matches!(
        SampleIntervals::regular(4, 0.0),
        Err(GaussMarkovError::NotPositive { .. })
    ));
    let intervals = SampleIntervals::from_times_s(&[0.0, 0.5, 2.0]).unwrap();
    assert_eq!(intervals.sample_count(), 3);
    assert_eq!(intervals.span_s(), 2.0);
    assert_eq!(intervals.min_dt_s(), Some(0.5));
    assert_eq!(intervals.mean_dt_s(), Some(1.0));
}
