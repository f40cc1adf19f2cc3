//! `stoch::gauss_markov`: the model, the AR-based, maximum-likelihood and autocovariance fits,
//! and the exact simulator, against closed forms, SciPy/statsmodels values and seeded
//! simulations.

mod acf_fit;
mod ar_based;
mod exact_ml;
mod model;
mod simulate;

use std::path::PathBuf;

/// A JSON file written by `tools/oracles/*.py` into `crates/thermonav/tests/data`.
fn oracle_json(name: &str) -> serde_json::Value {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    serde_json::from_str(&text).unwrap()
}

/// The numbers of a JSON array.
fn numbers(value: &serde_json::Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

/// `|actual / expected - 1|`.
fn relative_error(actual: f64, expected: f64) -> f64 {
    (actual / expected - 1.0).abs()
}
