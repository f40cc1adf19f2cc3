//! PX4 EKF2's IMU noise parameters in a QGroundControl `.params` file.
//!
//! Sources: PX4 parameter reference (<https://docs.px4.io/main/en/advanced_config/parameter_reference.html>):
//! `EKF2_GYR_NOISE` "rate gyro noise for covariance prediction", rad/s; `EKF2_ACC_NOISE`
//! "accelerometer noise for covariance prediction", m/s²; `EKF2_GYR_B_NOISE` "process noise
//! for IMU rate gyro bias prediction", rad/s²; `EKF2_ACC_B_NOISE` "process noise for IMU
//! accelerometer bias prediction", m/s³; `EKF2_PREDICT_US` the prediction interval, default
//! 10000 µs. PX4-Autopilot `src/modules/ekf2/EKF/covariance.cpp` (`predictCovariance`): the
//! delta-angle variance is (dt · EKF2_GYR_NOISE)² and the bias variance grows by
//! (dt · EKF2_GYR_B_NOISE)² per prediction step of dt (likewise for the accelerometer), so both
//! are discrete per-step values: for a white-noise density N the delta angle over dt has
//! variance N² dt, hence EKF2_GYR_NOISE = N / √dt; for a bias random walk K the bias variance
//! grows by K² dt, hence EKF2_GYR_B_NOISE = K / √dt. File layout: QGroundControl,
//! `docs/en/qgc-dev-guide/file_formats/parameters.md` (`#` comments; vehicle id, component id,
//! name, value, `MAV_PARAM_TYPE` 9 = REAL32, tab-separated).
//!
//! Ours: N and K (or the Gauss-Markov stand-in), the largest of the three axes, with
//! dt = 10 ms (`EKF2_PREDICT_US` default).

use super::ekf_parameters::{EkfParameters, ekf_parameters_text};
use super::{ExportOptions, ImuNoise, NoiseExportError, NoiseFormat};
use crate::thermal_parameters::ParameterValue;

/// The prediction interval the values are computed for, s (`EKF2_PREDICT_US` = 10000).
pub const PX4_PREDICTION_INTERVAL_S: f64 = 0.010;

const PX4_EKF2: EkfParameters = EkfParameters {
    format: NoiseFormat::Px4Ekf2,
    step_s: PX4_PREDICTION_INTERVAL_S,
    names: [
        "EKF2_GYR_NOISE",
        "EKF2_ACC_NOISE",
        "EKF2_GYR_B_NOISE",
        "EKF2_ACC_B_NOISE",
    ],
    step_comments: [
        "discrete values for EKF2's prediction step dt = 0.01 s (EKF2_PREDICT_US = 10000, the default; for another interval multiply every value by sqrt(10000 / EKF2_PREDICT_US)):",
        "NOISE = N / sqrt(dt) from the continuous white-noise density N; B_NOISE = K / sqrt(dt) from the continuous bias random walk K",
    ],
    header: Some("Vehicle-Id Component-Id Name Value Type"),
    line: qgc_line,
};

/// The file's text.
///
/// # Errors
/// A missing white-noise density, neither K nor a Gauss-Markov model, or a non-finite value.
pub fn text(noise: &ImuNoise, options: &ExportOptions) -> Result<String, NoiseExportError> {
    ekf_parameters_text(noise, options, &PX4_EKF2)
}

/// `1<TAB>1<TAB>NAME<TAB>VALUE<TAB>TYPE`: vehicle and component 1, `MAV_PARAM_TYPE`.
fn qgc_line(name: &str, value: ParameterValue) -> String {
    format!(
        "1\t1\t{name}\t{}\t{}\n",
        value.text(),
        value.mav_param_type()
    )
}
