//! The overlapping Allan deviation against allantools, Stable32, NIST SP 1065 and a slow
//! implementation of the definition.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use thermonav::stoch::allan::{AllanError, AllanWarning, TauGrid, overlapping_adev};

use super::data;

fn relative_error(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Slow, obviously correct: average the raw series over adjacent windows of m samples and
/// take half the mean squared difference of every overlapping pair (NIST SP 1065 eq. 10 with
/// overlapping windows), O(N m) per m.
fn slow_oadev(y: &[f64], m: usize) -> f64 {
    let n_terms = y.len() + 1 - 2 * m;
    let window_mean = |start: usize| y[start..start + m].iter().sum::<f64>() / m as f64;
    let sum_sq: f64 = (0..n_terms)
        .map(|i| window_mean(i + m) - window_mean(i))
        .map(|d| d * d)
        .sum();
    (sum_sq / (2.0 * n_terms as f64)).sqrt()
}

// Oracle: allantools 2024.6 oadev(y, rate=100, data_type='freq') on the real ADIS16405 run,
// all six channels, printed with 10 significant digits (%.10g: rounding <= 5e-10 relative).
// 1e-9 relative covers that rounding plus both programs' floating-point error (each sums
// ~1e6 products; relative error ~1e-13).
#[test]
fn oadev_matches_allantools_on_the_adis16405_run_all_channels() {
    let (names, columns) = data::adis16405_run1();
    let oracle = data::lines("peer-results-on-real-data/adis_16405_imu1_oadev_allantools.csv");
    for (name, y) in names.iter().zip(&columns) {
        let curve = overlapping_adev(y, 100.0, &TauGrid::Octave).unwrap();
        let rows: Vec<Vec<&str>> = oracle
            .iter()
            .skip(1)
            .map(|l| l.split(',').collect::<Vec<_>>())
            .filter(|f| f[0] == name)
            .collect();
        assert_eq!(rows.len(), curve.adev.len(), "{name}: number of taus");
        for (i, f) in rows.iter().enumerate() {
            assert_eq!(curve.averaging_factor[i], f[1].parse::<usize>().unwrap());
            assert_eq!(curve.n_terms[i], f[3].parse::<usize>().unwrap());
            assert!(relative_error(curve.tau_s[i], f[2].parse().unwrap()) < 1e-12);
            let expected: f64 = f[4].parse().unwrap();
            let err = relative_error(curve.adev[i], expected);
            assert!(
                err < 1e-9,
                "{name} m={}: {} vs {expected} ({err:e})",
                f[1],
                curve.adev[i]
            );
        }
    }
}

// Oracle: the definition, evaluated the slow way, on seeded data with an offset (so the mean
// removal inside the fast path is exercised). Both are double-precision evaluations of the
// same sum; 1e-12 relative leaves room for their different rounding (cumulative-sum
// cancellation ~ eps sqrt(N/m) ~ 1e-14).
#[test]
fn oadev_matches_the_slow_definition_on_every_grid() {
    let mut rng = ChaCha8Rng::seed_from_u64(20_240_601);
    let y: Vec<f64> = (0..3001)
        .map(|_| {
            let w: f64 = StandardNormal.sample(&mut rng);
            0.75 + w * 0.2
        })
        .collect();
    let grids = [
        TauGrid::Octave,
        TauGrid::Decade,
        TauGrid::Dense {
            points_per_decade: 12,
        },
        TauGrid::Explicit(vec![1, 3, 7, 999, 1500]),
    ];
    for grid in &grids {
        let curve = overlapping_adev(&y, 4.0, grid).unwrap();
        assert!(!curve.adev.is_empty());
        for (i, &m) in curve.averaging_factor.iter().enumerate() {
            let slow = slow_oadev(&y, m);
            let err = relative_error(curve.adev[i], slow);
            assert!(err < 1e-12, "{grid:?} m={m}: {err:e}");
            assert_eq!(curve.n_terms[i], y.len() - 2 * m + 1);
            assert_eq!(curve.tau_s[i], m as f64 / 4.0);
        }
    }
}

// Oracle: allantools 2024.6 oadev(taus='decade') on the NBS14 1000-point series (values in
// tests/data/allan.json, full double precision): same m list (its tau_generator rule), same
// term counts, values to 1e-12 relative (different summation order only).
#[test]
fn decade_grid_matches_allantools() {
    let y = data::column("allantools/nbs14/nbs14_1000_frequency.txt");
    let oracle = &data::oracle_json()["oadev_decade_nbs14"];
    let curve = overlapping_adev(&y, 1.0, &TauGrid::Decade).unwrap();
    let as_usize = |v: &serde_json::Value| -> Vec<usize> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_u64().unwrap() as usize)
            .collect()
    };
    assert_eq!(curve.averaging_factor, as_usize(&oracle["m"]));
    assert_eq!(curve.n_terms, as_usize(&oracle["n_terms"]));
    for (ours, expected) in curve.adev.iter().zip(oracle["oadev"].as_array().unwrap()) {
        assert!(relative_error(*ours, expected.as_f64().unwrap()) < 1e-12);
    }
}

// Oracle: published NBS14 values (NIST SP 1065 pp. 107-108, via allantools' tests), printed
// with 7 significant digits: the tolerance is half a unit in the 7th digit.
#[test]
fn oadev_matches_the_published_nbs14_values() {
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(data::shared("allantools/nbs14/nbs14_reference.json")).unwrap(),
    )
    .unwrap();
    let f64s = |v: &serde_json::Value| -> Vec<f64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let half_unit_7th = |v: f64| 0.5 * 10_f64.powf(v.abs().log10().floor() - 6.0);
    let ten = &json["ten_point"];
    let thousand = &json["thousand_point"];
    let cases = [
        (
            f64s(&ten["frequency_data"]),
            f64s(&ten["expected"]["tau_s"]),
            f64s(&ten["expected"]["oadev"]),
        ),
        (
            data::column("allantools/nbs14/nbs14_1000_frequency.txt"),
            f64s(&thousand["expected"]["tau_s"]),
            f64s(&thousand["expected"]["oadev"]),
        ),
    ];
    for (y, taus, expected) in &cases {
        let ms: Vec<usize> = taus.iter().map(|&t| t as usize).collect();
        let curve = overlapping_adev(y, 1.0, &TauGrid::Explicit(ms)).unwrap();
        for (ours, published) in curve.adev.iter().zip(expected) {
            assert!(
                (ours - published).abs() <= half_unit_7th(*published),
                "{ours} vs {published}"
            );
        }
    }
}

// Oracle: Stable32 1.60 "Overlapping Allan" at every tau (ocxo, pink noise with tau0 = 42 s,
// PHASE.DAT, Cs 5071A; phase data converted to frequency by first differences, which leaves
// the estimator unchanged). `#` must match exactly; Sigma is printed with 5 significant
// digits, so the deviation must agree to 1e-4 relative (allantools' own tolerance there).
#[test]
fn oadev_matches_stable32_at_every_tau() {
    for set in data::stable32_value_sets() {
        let rows = data::stable32_rows(set.result_file);
        let ms: Vec<usize> = rows.iter().map(|r| r.m).collect();
        let curve = overlapping_adev(&set.y, 1.0 / set.tau0_s, &TauGrid::Explicit(ms)).unwrap();
        for (i, row) in rows.iter().enumerate() {
            assert_eq!(curve.n_terms[i], row.n_terms, "{} m={}", set.name, row.m);
            assert!(relative_error(curve.tau_s[i], row.tau_s) < 1e-4);
            let err = relative_error(curve.adev[i], row.sigma);
            assert!(
                err < 1e-4,
                "{} m={}: {} vs {} ({err:e})",
                set.name,
                row.m,
                curve.adev[i],
                row.sigma
            );
        }
    }
}

#[test]
fn invalid_input_is_rejected_with_the_numbers() {
    assert_eq!(
        overlapping_adev(&[1.0, 2.0], 1.0, &TauGrid::Octave),
        Err(AllanError::TooFewSamples { got: 2, min: 3 })
    );
    let err = overlapping_adev(&[1.0, f64::NAN, 2.0], 1.0, &TauGrid::Octave).unwrap_err();
    assert!(matches!(err, AllanError::NonFiniteSample { index: 1, .. }));
    for rate in [0.0, -1.0, f64::INFINITY, f64::NAN] {
        let err = overlapping_adev(&[1.0, 2.0, 3.0], rate, &TauGrid::Octave).unwrap_err();
        assert!(matches!(err, AllanError::InvalidSampleRate(_)));
    }
    let err = overlapping_adev(
        &[1.0; 10],
        1.0,
        &TauGrid::Dense {
            points_per_decade: 0,
        },
    );
    assert_eq!(err, Err(AllanError::ZeroPointsPerDecade));
}

// Closed form: a constant series has zero Allan deviation, reported as such (no NaN).
#[test]
fn constant_series_gives_zero_and_a_warning() {
    let curve = overlapping_adev(&[0.125; 64], 10.0, &TauGrid::Octave).unwrap();
    assert_eq!(curve.warnings, [AllanWarning::ConstantInput]);
    assert!(curve.adev.iter().all(|&a| a == 0.0));
    let varying = overlapping_adev(&[0.0, 1.0, 0.0, 1.0], 1.0, &TauGrid::Octave).unwrap();
    assert!(varying.warnings.is_empty());
}
