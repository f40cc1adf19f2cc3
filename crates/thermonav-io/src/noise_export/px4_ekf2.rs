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

use super::{
    ExportOptions, ImuNoise, NoiseExportError, NoiseFormat, commented, filter_step_noise,
    provenance,
};
use crate::thermal_parameters::ParameterValue;

/// The prediction interval the values are computed for, s (`EKF2_PREDICT_US` = 10000).
pub const PX4_PREDICTION_INTERVAL_S: f64 = 0.010;

/// The file's text.
///
/// # Errors
/// A missing white-noise density, neither K nor a Gauss-Markov model, or a non-finite value.
pub fn text(noise: &ImuNoise, options: &ExportOptions) -> Result<String, NoiseExportError> {
    let step = filter_step_noise(noise, PX4_PREDICTION_INTERVAL_S)?;
    let parameters = [
        ("EKF2_GYR_NOISE", step.gyro_rad_s, "rad/s"),
        ("EKF2_ACC_NOISE", step.accel_m_s2, "m/s^2"),
        ("EKF2_GYR_B_NOISE", step.gyro_bias_rad_s2, "rad/s^2"),
        ("EKF2_ACC_B_NOISE", step.accel_bias_m_s3, "m/s^3"),
    ];
    let mut comments = provenance(NoiseFormat::Px4Ekf2, noise, options);
    comments.extend([
        "discrete values for EKF2's prediction step dt = 0.01 s (EKF2_PREDICT_US = 10000, the default; for another interval multiply every value by sqrt(10000 / EKF2_PREDICT_US)):".to_string(),
        "NOISE = N / sqrt(dt) from the continuous white-noise density N; B_NOISE = K / sqrt(dt) from the continuous bias random walk K".to_string(),
        "one value per sensor: the largest of the three axes x, y, z".to_string(),
    ]);
    comments.extend(step.comments);
    comments.push("Vehicle-Id Component-Id Name Value Type".to_string());
    let mut body = String::new();
    for (name, value, unit) in parameters {
        let value = ParameterValue::Real(value as f32);
        body.push_str(&format!("# {name} [{unit}]\n"));
        body.push_str(&format!(
            "1\t1\t{name}\t{}\t{}\n",
            value.text(),
            value.mav_param_type()
        ));
    }
    Ok(commented("#", &comments) + &body)
}
