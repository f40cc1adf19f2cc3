//! Integration tests of the thermonav library against independent oracles.

mod allan;
mod allan_confidence;
mod allan_family;
mod ar;
mod error_model;
mod evaluation;
mod gauss_markov;
mod geo;
mod gmwm;
mod ideal_imu;
mod ins;
mod navigation;
mod position_only;
mod round_trip;
mod schedule;
mod signal;
mod streamed_navigation;
mod streaming;
mod thermal;
mod thermal_recovery;
mod time_offset;
mod ukf;
mod vessel;
mod wavelet_denoise;
mod wavelet_variance;

use std::path::PathBuf;

/// Path of a file under `../shared/data` (the repository sits beside `shared/`), or under
/// `$THERMONAV_SHARED_DATA` when set (a checkout elsewhere, e.g. a git worktree).
pub fn shared_data(relative: &str) -> PathBuf {
    std::env::var_os("THERMONAV_SHARED_DATA")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data"))
        .join(relative)
}

/// Path of a committed oracle file under `tests/data`.
pub fn oracle_data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// Parses a committed oracle JSON file.
pub fn oracle_json(name: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(oracle_data(name)).expect("oracle file exists");
    serde_json::from_str(&text).expect("oracle file is JSON")
}

/// A one-column text file under `../shared/data` ('#' comment lines skipped).
pub fn shared_column(relative: &str) -> Vec<f64> {
    std::fs::read_to_string(shared_data(relative))
        .expect("shared data present")
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.trim().parse().expect("number"))
        .collect()
}
