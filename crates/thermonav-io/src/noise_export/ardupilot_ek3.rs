//! ArduPilot EKF3's IMU noise parameters in a `.parm` file.
//!
//! Sources: ArduPilot parameter reference (<https://ardupilot.org/copter/docs/parameters.html>,
//! EK3_ group): `EK3_GYRO_P_NSE` "rate gyro noise", rad/s; `EK3_ACC_P_NSE` "accelerometer
//! noise", m/s²; `EK3_GBIAS_P_NSE` "rate gyro bias stability", rad/s²; `EK3_ABIAS_P_NSE`
//! "accelerometer bias stability", m/s³. ArduPilot `libraries/AP_NavEKF3/AP_NavEKF3_core.cpp`
//! (`CovariancePrediction`): delta-angle variance (dt · EK3_GYRO_P_NSE)², delta-angle bias
//! process noise dt² · EK3_GBIAS_P_NSE as a standard deviation, i.e. the gyro bias variance
//! grows by (dt · EK3_GBIAS_P_NSE)² per step; dt is the EKF step, at least `EKF_TARGET_DT` =
//! 12 ms (`AP_NavEKF3_core.h`). So, as for PX4: value = N / √dt and K / √dt. File layout:
//! `NAME VALUE` lines with `#` comments, as MAVProxy's `param load` (pymavlink `mavparm.py`)
//! and Mission Planner read them.
//!
//! Ours: N and K (or the Gauss-Markov stand-in), the largest of the three axes, dt = 12 ms.

use super::{
    ExportOptions, ImuNoise, NoiseExportError, NoiseFormat, commented, filter_step_noise,
    provenance,
};
use crate::thermal_parameters::ParameterValue;

/// The EKF step the values are computed for, s (`EKF_TARGET_DT`).
pub const EK3_STEP_S: f64 = 0.012;

/// The file's text.
///
/// # Errors
/// A missing white-noise density, neither K nor a Gauss-Markov model, or a non-finite value.
pub fn text(noise: &ImuNoise, options: &ExportOptions) -> Result<String, NoiseExportError> {
    let step = filter_step_noise(noise, EK3_STEP_S)?;
    let parameters = [
        ("EK3_GYRO_P_NSE", step.gyro_rad_s, "rad/s"),
        ("EK3_ACC_P_NSE", step.accel_m_s2, "m/s^2"),
        ("EK3_GBIAS_P_NSE", step.gyro_bias_rad_s2, "rad/s^2"),
        ("EK3_ABIAS_P_NSE", step.accel_bias_m_s3, "m/s^3"),
    ];
    let mut comments = provenance(NoiseFormat::ArdupilotEk3, noise, options);
    comments.extend([
        "discrete values for EKF3's step dt = 0.012 s (EKF_TARGET_DT; a vehicle whose loop is slower than 83 Hz steps at its loop interval: multiply every value by sqrt(0.012 / that)):".to_string(),
        "P_NSE = N / sqrt(dt) from the continuous white-noise density N; BIAS_P_NSE = K / sqrt(dt) from the continuous bias random walk K".to_string(),
        "one value per sensor: the largest of the three axes x, y, z".to_string(),
    ]);
    comments.extend(step.comments);
    let mut body = String::new();
    for (name, value, unit) in parameters {
        body.push_str(&format!("# {name} [{unit}]\n"));
        body.push_str(&format!(
            "{name} {}\n",
            ParameterValue::Real(value as f32).text()
        ));
    }
    Ok(commented("#", &comments) + &body)
}
