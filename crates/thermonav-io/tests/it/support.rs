//! Helpers shared by the test modules.

use thermonav::imu::ImuSeries;
use thermonav_io::{ReadError, Strictness, read_imu};

/// Name given to in-memory inputs; errors start with it.
pub const NAME: &str = "data/imu.csv";

/// Canonical rate header with temperature.
pub const RATE_HEADER: &str = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c";

/// Reads an IMU text under a policy.
pub fn read(text: &str, strictness: Strictness) -> Result<ImuSeries, ReadError> {
    read_imu(text.as_bytes(), NAME, strictness)
}

/// The message of the error that reading `text` strictly must give.
pub fn strict_error(text: &str) -> String {
    match read(text, Strictness::Strict) {
        Ok(series) => panic!("expected an error, read {} samples", series.len()),
        Err(error) => error.to_string(),
    }
}

/// `value` is within `ulps` units in the last place of `expected`.
pub fn within_ulps(value: f64, expected: f64, ulps: u64) -> bool {
    let distance = (value.to_bits() as i64 - expected.to_bits() as i64).unsigned_abs();
    value.signum() == expected.signum() && distance <= ulps
}

/// Path of a file under the project's `shared/data` folder, found in the nearest ancestor of
/// this crate that has one (the main checkout sits beside `shared/`, worktrees deeper).
pub fn shared_data(relative: &str) -> std::path::PathBuf {
    let manifest = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .ancestors()
        .map(|dir| dir.join("shared/data"))
        .find(|dir| dir.is_dir())
        .expect("a shared/data folder above the crate")
        .join(relative)
}
