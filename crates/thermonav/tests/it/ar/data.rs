//! Oracle files, small helpers and a seeded AR simulator shared by the AR and ACF tests.

use std::path::PathBuf;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use serde_json::Value;

/// Path of a file under the read-only shared data folder.
pub fn shared(relative: &str) -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/data/"
    ))
    .join(relative)
}

/// Parses a JSON file.
pub fn read_json(path: PathBuf) -> Value {
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).expect("valid JSON")
}

/// `statsmodels/ar_reference.json` (R, MATLAB, Stata values).
pub fn statsmodels_reference() -> Value {
    read_json(shared("statsmodels/ar_reference.json"))
}

/// `spectrum/ar_reference.json`.
pub fn spectrum_reference() -> Value {
    read_json(shared("spectrum/ar_reference.json"))
}

/// `tests/data/ar_least_squares.json`, written by `tools/oracles/ar_least_squares.py`.
pub fn least_squares_oracle() -> Value {
    read_json(PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/ar_least_squares.json"
    )))
}

/// A JSON array of numbers.
pub fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

/// A JSON number.
pub fn float(v: &Value) -> f64 {
    v.as_f64().expect("number")
}

/// Numbers of a text file, skipping `#` comment lines.
fn text_column(relative: &str) -> Vec<f64> {
    std::fs::read_to_string(shared(relative))
        .expect("readable")
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.trim().parse().expect("number"))
        .collect()
}

/// statsmodels' x1000 = xar2 / 1000 (data README §3.2).
pub fn x1000() -> Vec<f64> {
    text_column("statsmodels/xar2.txt")
        .iter()
        .map(|v| v / 1000.0)
        .collect()
}

/// statsmodels' x100 = the last 100 values of x1000.
pub fn x100() -> Vec<f64> {
    let x = x1000();
    x[x.len() - 100..].to_vec()
}

/// The MA(1) series of R's `ar.burg` oracle.
pub fn burg_ma1() -> Vec<f64> {
    text_column("statsmodels/burg_ma1_series.txt")
}

/// Yearly sunspot numbers 1700-2008.
pub fn sunspots() -> Vec<f64> {
    std::fs::read_to_string(shared("statsmodels/sunspots.csv"))
        .expect("readable")
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .nth(1)
                .expect("two columns")
                .parse()
                .expect("number")
        })
        .collect()
}

/// `n` samples of `y_t = sum c_i y_{t-i} + w_t`, `w ~ N(0, 1)`, after a burn-in of 1000,
/// from ChaCha8 seeded with `seed`.
pub fn simulate_ar(coefficients: &[f64], n: usize, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let burn_in = 1000;
    let mut y = vec![0.0; n + burn_in];
    for t in 0..y.len() {
        let w: f64 = StandardNormal.sample(&mut rng);
        let past: f64 = coefficients
            .iter()
            .enumerate()
            .filter(|(i, _)| t > *i)
            .map(|(i, c)| c * y[t - 1 - i])
            .sum();
        y[t] = past + w;
    }
    y.split_off(burn_in)
}

/// Asserts `|a - e| <= abs_tol + rel_tol |e|` element by element.
pub fn assert_close(actual: &[f64], expected: &[f64], abs_tol: f64, rel_tol: f64, label: &str) {
    assert_eq!(actual.len(), expected.len(), "{label}: lengths");
    for (i, (a, e)) in actual.iter().zip(expected).enumerate() {
        let tol = abs_tol + rel_tol * e.abs();
        assert!(
            (a - e).abs() <= tol,
            "{label}[{i}]: got {a:e}, expected {e:e} (|diff| {:e} > {tol:e})",
            (a - e).abs()
        );
    }
}

/// Asserts one scalar like [`assert_close`].
pub fn assert_scalar(actual: f64, expected: f64, abs_tol: f64, rel_tol: f64, label: &str) {
    assert_close(&[actual], &[expected], abs_tol, rel_tol, label);
}
