//! The Haar wavelet variance against allantools (half the overlapping Allan variance at
//! m = τ_j/2, on a generated series and the real ADIS16405 run 2), against the MODWT filter
//! written out tap by tap, and the coverage of its chi-square intervals.

use crate::allan::adis_16405_run;
use crate::oracle_json;
use rand_distr::{Distribution, StandardNormal};
use serde_json::Value;
use statrs::distribution::{Binomial, DiscreteCDF};
use thermonav::rng::named_rng;
use thermonav::stoch::wavelet_variance::{WaveletVariance, haar_wavelet_variance, max_level};

/// (m, n_terms, ν² = oadev²/2) rows of allantools 2024.6 (tools/oracles/wavelet_variance.py).
fn oracle_rows(rows: &Value) -> Vec<(usize, usize, f64)> {
    rows.as_array()
        .expect("rows")
        .iter()
        .map(|r| {
            (
                r["m"].as_u64().unwrap() as usize,
                r["n_terms"].as_u64().unwrap() as usize,
                r["haar_wv"].as_f64().unwrap(),
            )
        })
        .collect()
}

/// Scale 2^j pairs with allantools' m = 2^(j−1), the same number of coefficients, and ν² to
/// 1e-9 relative. allantools works on the uncentred cumulative sum, so its second differences
/// of a series with mean μ lose about ε N μ / (m σ) relative digits (≤ 2e-10 on these series);
/// 1e-9 is the tolerance and above that rounding.
fn assert_matches(wv: &WaveletVariance, rows: &[(usize, usize, f64)]) {
    assert!(wv.variance.len() >= rows.len() - 1, "levels");
    for (j, &(m, n_terms, expected)) in rows.iter().take(wv.variance.len()).enumerate() {
        assert_eq!(wv.scale_samples[j], 2 * m);
        assert_eq!(wv.n_coefficients[j], n_terms);
        let got = wv.variance[j];
        assert!(
            (got / expected - 1.0).abs() < 1e-9,
            "m {m}: {got} vs {expected}"
        );
    }
}

#[test]
fn equals_half_the_allantools_allan_variance_on_a_generated_series() {
    let oracle = oracle_json("wavelet_variance.json");
    let generated = &oracle["generated"];
    let y: Vec<f64> = generated["y"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let rate = generated["rate_hz"].as_f64().unwrap();
    let wv = haar_wavelet_variance(&y, rate, None, 0.95).unwrap();
    assert_eq!(wv.variance.len(), max_level(y.len()));
    assert_matches(&wv, &oracle_rows(&generated["rows"]));
    assert!((wv.scale_s[0] - 2.0 / rate).abs() < 1e-15, "τ₁ = 2 dt in s");
}

#[test]
fn equals_half_the_allantools_allan_variance_on_the_real_adis16405_run_2() {
    let oracle = oracle_json("wavelet_variance.json");
    let names = [
        "Gyro_X", "Gyro_Y", "Gyro_Z", "Accel_X", "Accel_Y", "Accel_Z",
    ];
    for (y, name) in adis_16405_run(2).iter().zip(names) {
        let wv = haar_wavelet_variance(y, 100.0, None, 0.95).unwrap();
        assert_matches(&wv, &oracle_rows(&oracle["adis_16405_imu2"][name]));
    }
}

/// ν²_j from the MODWT coefficients W_{j,t} = Σ_l h_{j,l} y_{t−l}, h = +1/τ on the recent half
/// and −1/τ on the older half, t = τ − 1 .. N − 1: O(N τ) per level.
fn slow_modwt_variance(y: &[f64], tau: usize) -> f64 {
    let coefficients: Vec<f64> = (tau - 1..y.len())
        .map(|t| {
            (0..tau)
                .map(|l| if l < tau / 2 { 1.0 } else { -1.0 } * y[t - l] / tau as f64)
                .sum()
        })
        .collect();
    coefficients.iter().map(|w| w * w).sum::<f64>() / coefficients.len() as f64
}

#[test]
fn equals_the_modwt_filter_written_out() {
    // Same quantity, two computations (the slow one sums τ terms per coefficient): 1e-11
    // relative covers the rounding of the slow sums on a series with mean 5.
    let mut rng = named_rng(11, "wavelet-variance/slow");
    let y: Vec<f64> = (0..3000)
        .map(|_| 5.0 + <StandardNormal as Distribution<f64>>::sample(&StandardNormal, &mut rng))
        .collect();
    let wv = haar_wavelet_variance(&y, 10.0, None, 0.95).unwrap();
    for (j, &tau) in wv.scale_samples.iter().enumerate() {
        let slow = slow_modwt_variance(&y, tau);
        assert!((wv.variance[j] / slow - 1.0).abs() < 1e-11, "tau {tau}");
    }
}

#[test]
fn intervals_cover_white_noise_at_least_at_their_level() {
    // White noise of variance 1: ν²_j = 1/τ_j. 200 seeded records of 512 samples; at the
    // scales 2, 8 and 32 samples the 95 % intervals must cover 1/τ in a count that a one-sided
    // binomial test against 0.95 does not find too low at the 1 % level. One-sided because
    // η₃ = M_j/2^j is a lower bound of the degrees of freedom: for white noise the large-sample
    // value M_j ν⁴/A_j (A_j = Σ_h s²_{j,h}, s the coefficients' autocovariance) is 1.33, 2.78
    // and 2.99 times η₃ at τ = 2, 8 and 32, so the intervals are conservative (200 of 200 at
    // 32 samples).
    let records = 200;
    let scales = [0usize, 2, 4];
    let mut covered = [0u64; 3];
    for seed in 0..records {
        let mut rng = named_rng(seed, "wavelet-variance/coverage");
        let y: Vec<f64> = (0..512)
            .map(|_| <StandardNormal as Distribution<f64>>::sample(&StandardNormal, &mut rng))
            .collect();
        let wv = haar_wavelet_variance(&y, 1.0, None, 0.95).unwrap();
        for (count, &j) in covered.iter_mut().zip(&scales) {
            let truth = 1.0 / wv.scale_samples[j] as f64;
            *count += u64::from(wv.ci_low[j] <= truth && truth <= wv.ci_high[j]);
        }
    }
    let binomial = Binomial::new(0.95, records).unwrap();
    for (count, j) in covered.iter().zip(scales) {
        let p_low = binomial.cdf(*count);
        assert!(p_low > 0.01, "level {}: {count} of {records}", j + 1);
    }
}

#[test]
fn refuses_bad_input() {
    assert!(haar_wavelet_variance(&[1.0, 2.0, 3.0], 1.0, None, 0.95).is_err());
    assert!(haar_wavelet_variance(&[1.0; 16], 1.0, None, 1.0).is_err());
    assert!(haar_wavelet_variance(&[1.0, f64::NAN, 0.0, 1.0], 1.0, None, 0.95).is_err());
    assert!(haar_wavelet_variance(&[1.0; 16], 0.0, None, 0.95).is_err());
}
