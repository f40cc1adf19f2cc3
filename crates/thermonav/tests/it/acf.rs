//! Autocovariance / autocorrelation: FFT and blocked direct sums against a naive double loop,
//! and against MATLAB `autocorr` (data README §3.2).

use thermonav::stoch::acf::{
    AcfAlgorithm, AcfError, Demean, autocorrelation, autocovariance, autocovariance_with,
};

use crate::ar::data::{self, assert_close, simulate_ar};

/// Neumaier-compensated sum: the sample mean to full precision even for a large offset (a plain
/// running sum of 10^4 values near 1e6 is off by ~1e-8 in the mean, which shifts the lag-d
/// sums by ~1e-12 of gamma(0)).
fn compensated_sum(x: &[f64]) -> f64 {
    let (mut sum, mut compensation) = (0.0f64, 0.0f64);
    for &v in x {
        let t = sum + v;
        compensation += if sum.abs() >= v.abs() {
            (sum - t) + v
        } else {
            (v - t) + sum
        };
        sum = t;
    }
    sum + compensation
}

/// The defining double loop, `(1/N) sum_t (x_t - m)(x_{t+k} - m)`, two-pass, exact mean.
fn naive_autocovariance(x: &[f64], max_lag: usize, demean: Demean) -> Vec<f64> {
    let n = x.len();
    let mean = match demean {
        Demean::None => 0.0,
        Demean::SampleMean => compensated_sum(x) / n as f64,
    };
    (0..=max_lag)
        .map(|k| {
            (0..n - k)
                .map(|t| (x[t] - mean) * (x[t + k] - mean))
                .sum::<f64>()
                / n as f64
        })
        .collect()
}

/// An AR(2) series with an offset, so that demeaning matters.
fn test_series(n: usize, seed: u64) -> Vec<f64> {
    simulate_ar(&[0.5, -0.3], n, seed)
        .iter()
        .map(|v| v + 3.0)
        .collect()
}

#[test]
fn fft_and_direct_match_the_naive_double_loop() {
    // Both fast algorithms re-associate the sums; the error is a few ulps of gamma(0) times
    // log N (FFT) or sqrt(block) (direct): 1e-12 * gamma(0) is a wide margin that still catches
    // any wrong lag, wrap-around or normalisation.
    for (n, max_lag) in [(1000, 999), (4097, 300), (5000, 7), (2, 1), (1, 0)] {
        let x = test_series(n, n as u64);
        for demean in [Demean::None, Demean::SampleMean] {
            let expected = naive_autocovariance(&x, max_lag, demean);
            let tol = 1e-12 * expected[0];
            for algorithm in [AcfAlgorithm::Fft, AcfAlgorithm::Direct, AcfAlgorithm::Auto] {
                let got = autocovariance_with(&x, max_lag, demean, algorithm).unwrap();
                assert_close(
                    &got,
                    &expected,
                    tol,
                    0.0,
                    &format!("{algorithm:?} n={n} {demean:?}"),
                );
            }
        }
    }
}

#[test]
fn fft_handles_long_series_without_wrap_around() {
    // 2^18 samples, 2000 lags: the padded FFT length must be >= N + max_lag or lags near
    // max_lag would pick up products wrapped from the other end. Oracle: the direct sums,
    // themselves checked against the naive loop above.
    let x = test_series(1 << 18, 5);
    let fft = autocovariance_with(&x, 2000, Demean::SampleMean, AcfAlgorithm::Fft).unwrap();
    let direct = autocovariance_with(&x, 2000, Demean::SampleMean, AcfAlgorithm::Direct).unwrap();
    assert_close(&fft, &direct, 1e-12 * direct[0], 0.0, "fft vs direct");
}

#[test]
fn large_offsets_and_stride_aligned_spikes_keep_full_precision() {
    // The direct path centres on a provisional mean of every 64th sample and corrects the sums
    // afterwards. A mean 1e6 times the standard deviation, and spikes exactly on the subsampled
    // indices (provisional mean ~ 8 sigma off, the worst case), must still match the two-pass
    // naive loop to 1e-12 gamma(0).
    let base = test_series(10_000, 77);
    let offset: Vec<f64> = base.iter().map(|v| v + 1e6).collect();
    let spikes: Vec<f64> = (0..10_000)
        .map(|t| if t % 64 == 0 { 50.0 } else { base[t] })
        .collect();
    for x in [offset, spikes] {
        let expected = naive_autocovariance(&x, 40, Demean::SampleMean);
        let got = autocovariance_with(&x, 40, Demean::SampleMean, AcfAlgorithm::Direct).unwrap();
        assert_close(&got, &expected, 1e-12 * expected[0], 0.0, "direct");
    }
}

#[test]
fn autocorrelation_matches_matlab_autocorr_on_xar2() {
    // MATLAB autocorr values printed with 8 decimals: rounding <= 5e-9, so 1e-8 absolute.
    let reference = data::statsmodels_reference();
    let expected = &reference["matlab_acf_pacf_xar2"];
    for (x, key) in [
        (data::x100(), "acf100_lags0to20"),
        (data::x1000(), "acf1000_lags0to20"),
    ] {
        let rho = autocorrelation(&x, 20, Demean::SampleMean).unwrap();
        assert_close(&rho, &data::floats(&expected[key]), 1e-8, 0.0, key);
    }
}

#[test]
fn alternating_series_has_closed_form_autocovariance() {
    // x = (+1, -1, ...) of length N, no demeaning: gamma(k) = (-1)^k (N - k) / N exactly.
    let n = 64;
    let x: Vec<f64> = (0..n)
        .map(|t| if t % 2 == 0 { 1.0 } else { -1.0 })
        .collect();
    let expected: Vec<f64> = (0..n)
        .map(|k| if k % 2 == 0 { 1.0 } else { -1.0 } * (n - k) as f64 / n as f64)
        .collect();
    for algorithm in [AcfAlgorithm::Fft, AcfAlgorithm::Direct] {
        let got = autocovariance_with(&x, n - 1, Demean::None, algorithm).unwrap();
        assert_close(&got, &expected, 1e-14, 0.0, &format!("{algorithm:?}"));
    }
}

#[test]
fn bad_input_gives_errors_with_the_numbers() {
    assert_eq!(autocovariance(&[], 0, Demean::None), Err(AcfError::Empty));
    assert_eq!(
        autocovariance(&[1.0, 2.0], 2, Demean::None),
        Err(AcfError::MaxLagTooLarge {
            max_lag: 2,
            n_samples: 2
        })
    );
    match autocovariance(&[1.0, f64::NAN, 2.0], 1, Demean::SampleMean) {
        Err(AcfError::NonFinite { index: 1, value }) => assert!(value.is_nan()),
        other => panic!("expected NonFinite at 1, got {other:?}"),
    }
    assert_eq!(
        autocovariance(&[1.0, 2.0, f64::NEG_INFINITY], 1, Demean::None),
        Err(AcfError::NonFinite {
            index: 2,
            value: f64::NEG_INFINITY
        })
    );
    assert_eq!(
        autocorrelation(&[4.0; 10], 3, Demean::SampleMean),
        Err(AcfError::ZeroVariance { n_samples: 10 })
    );
    // Finite samples whose squares overflow f64.
    assert_eq!(
        autocovariance(&[1e200, -1e200, 3.0], 1, Demean::None),
        Err(AcfError::Overflow { max_abs: 1e200 })
    );
    // 100 000 copies of 0.35: the running means are off by rounding, so the centred samples are
    // ~1e-13, not 0; still a constant.
    assert_eq!(
        autocorrelation(&[0.35; 100_000], 3, Demean::SampleMean),
        Err(AcfError::ZeroVariance { n_samples: 100_000 })
    );
    // A constant has zero autocovariance, which is a valid answer (not NaN).
    assert_eq!(
        autocovariance(&[4.0; 10], 3, Demean::SampleMean).unwrap(),
        vec![0.0; 4]
    );
}
