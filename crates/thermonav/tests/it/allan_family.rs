//! The Allan family (mdev, hdev, ohdev, tdev, totdev) against allantools 2024.6 on real data
//! (ADIS16405 run 1, NBS14, pink frequency noise) and on generated series, with the values
//! written once by `tools/oracles/allan_family.py` into `tests/data/allan_family.json`; and the
//! fast modified Allan variance against its slow definition.

use crate::allan::adis_16405_columns;
use crate::{oracle_json, shared_column};
use serde_json::Value;
use thermonav::stoch::allan::{DeviationKind, TauGrid, deviation, overlapping_adev};

/// The kinds allantools computed, by their names in the fixture.
const KINDS: [DeviationKind; 5] = [
    DeviationKind::Mdev,
    DeviationKind::Hdev,
    DeviationKind::Ohdev,
    DeviationKind::Tdev,
    DeviationKind::Totdev,
];

/// The JSON array `v` as numbers.
pub(crate) fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

/// The JSON array `v` as counts.
fn counts(v: &Value) -> Vec<usize> {
    numbers(v).iter().map(|&x| x as usize).collect()
}

/// Largest relative difference |ours/theirs − 1| over the curve of every kind of `grid_entry`
/// (the fixture's "octave" or "explicit" object) on `y` at `rate_hz`, after checking that the
/// factors and term counts are allantools' exactly.
fn worst_relative_error(y: &[f64], rate_hz: f64, grid_entry: &Value, explicit: bool) -> f64 {
    let mut worst = 0.0_f64;
    for kind in KINDS {
        let expected = &grid_entry[kind.name()];
        let m = counts(&expected["m"]);
        let grid = if explicit {
            TauGrid::Explicit(m.clone())
        } else {
            TauGrid::Octave
        };
        let curve = deviation(kind, y, rate_hz, &grid).unwrap();
        assert_eq!(curve.averaging_factor, m, "{kind} factors");
        assert_eq!(curve.n_terms, counts(&expected["n_terms"]), "{kind} terms");
        for (got, want) in curve.deviation.iter().zip(numbers(&expected["deviation"])) {
            worst = worst.max((got / want - 1.0).abs());
        }
    }
    worst
}

// Tolerance 1e-9 relative: allantools and we compute the same sums from the same phase in a
// different order (numpy's cumsum and vectorised sums against our chained running sums and
// sliding windows); the rounding of either is below 1e-12 on these lengths, so 1e-9 leaves
// three decades of margin while a wrong term count or divisor (at least 1/N ≈ 1e-6) fails.
const TOLERANCE: f64 = 1e-9;

#[test]
fn family_matches_allantools_on_the_real_adis16405_gyro() {
    let fixture = oracle_json("allan_family.json");
    let y = &adis_16405_columns()[0];
    let entry = &fixture["adis_16405_imu1_gyro_x"]["octave"];
    let worst = worst_relative_error(y, 100.0, entry, false);
    assert!(worst < TOLERANCE, "worst relative difference {worst:e}");
}

#[test]
fn family_matches_allantools_on_nbs14_and_pink_frequency_noise() {
    let fixture = oracle_json("allan_family.json");
    let nbs14 = shared_column("allantools/nbs14/nbs14_1000_frequency.txt");
    let entry = &fixture["nbs14_1000"];
    let worst = worst_relative_error(&nbs14, 1.0, &entry["octave"], false)
        .max(worst_relative_error(&nbs14, 1.0, &entry["explicit"], true));
    assert!(
        worst < TOLERANCE,
        "NBS14: worst relative difference {worst:e}"
    );
    let pink = shared_column("allantools/pink_frequency/pink_frequency.txt");
    let entry = &fixture["pink_frequency"]["octave"];
    let worst = worst_relative_error(&pink, 1.0 / 42.0, entry, false);
    assert!(
        worst < TOLERANCE,
        "pink: worst relative difference {worst:e}"
    );
}

#[test]
fn family_matches_allantools_on_generated_white_random_walk_and_flicker_fm() {
    let fixture = oracle_json("allan_family.json");
    for name in ["white_fm", "random_walk_fm", "flicker_fm"] {
        let entry = &fixture["generated"][name];
        let y = numbers(&entry["y"]);
        let rate_hz = entry["rate_hz"].as_f64().unwrap();
        let worst = worst_relative_error(&y, rate_hz, &entry["octave"], false)
            .max(worst_relative_error(&y, rate_hz, &entry["explicit"], true));
        assert!(
            worst < TOLERANCE,
            "{name}: worst relative difference {worst:e}"
        );
    }
}

/// The slow definition of the modified Allan deviation, term by term: each of the n terms sums
/// the m second differences of the phase x = Σ y (units of τ₀) afresh, O(N m) per factor.
fn slow_mdev(y: &[f64], m: usize) -> f64 {
    let mut x = vec![0.0];
    for v in y {
        x.push(x.last().unwrap() + v);
    }
    let n = x.len() + 1 - 3 * m;
    let total: f64 = (0..n)
        .map(|j| {
            (j..j + m)
                .map(|i| x[i + 2 * m] - 2.0 * x[i + m] + x[i])
                .sum::<f64>()
                .powi(2)
        })
        .sum();
    (total / (2.0 * (m as f64).powi(4) * n as f64)).sqrt()
}

#[test]
fn sliding_mdev_equals_the_slow_definition() {
    // Same quantity, summed two ways; 1e-11 relative is rounding (the slow sum runs on the
    // uncentred phase, which grows to 1e3 here).
    let y = &adis_16405_columns()[3][..3000];
    let factors = vec![1, 2, 5, 64, 333, 1000];
    let curve = deviation(DeviationKind::Mdev, y, 100.0, &TauGrid::Explicit(factors)).unwrap();
    for (&m, got) in curve.averaging_factor.iter().zip(&curve.deviation) {
        let slow = slow_mdev(y, m);
        assert!((got / slow - 1.0).abs() < 1e-11, "m {m}: {got} vs {slow}");
    }
}

#[test]
fn adev_kind_is_the_overlapping_allan_deviation_unchanged() {
    // The dispatcher's adev is overlapping_adev itself: the same bits.
    let y = shared_column("allantools/nbs14/nbs14_1000_frequency.txt");
    let curve = deviation(DeviationKind::Adev, &y, 1.0, &TauGrid::Octave).unwrap();
    let adev = overlapping_adev(&y, 1.0, &TauGrid::Octave).unwrap();
    assert_eq!(curve.deviation, adev.adev);
    assert_eq!(curve.n_terms, adev.n_terms);
}
