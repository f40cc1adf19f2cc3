//! The layout PX4 EKF2 and ArduPilot EKF3 share: four discrete per-step noise parameters
//! (gyro, accelerometer, gyro bias, accelerometer bias), each under a comment naming its unit.

use super::{
    ExportOptions, ImuNoise, NoiseExportError, NoiseFormat, commented, filter_step_noise,
    provenance,
};
use crate::thermal_parameters::ParameterValue;

/// What the values are and are not.
const FLOOR_NOT_TUNING: &str = "these are the sensor's own noise in a static record: the autopilot's defaults are larger on purpose (vibration, unmodelled errors in flight), so treat them as a floor, not as a tuning";

/// How one autopilot names and lays out its EKF's noise parameters.
pub struct EkfParameters {
    /// The format.
    pub format: NoiseFormat,
    /// The EKF step the values are computed for, s.
    pub step_s: f64,
    /// Names of the gyro, accelerometer, gyro-bias and accelerometer-bias parameters.
    pub names: [&'static str; 4],
    /// What the step is and how to rescale for another, as comment lines.
    pub step_comments: [&'static str; 2],
    /// A last comment line before the parameters (the column names), if any.
    pub header: Option<&'static str>,
    /// One parameter's line.
    pub line: fn(&str, ParameterValue) -> String,
}

/// The file's text for `target`.
///
/// # Errors
/// A missing white-noise density, neither K nor a Gauss-Markov model, or a non-finite value.
pub fn ekf_parameters_text(
    noise: &ImuNoise,
    options: &ExportOptions,
    target: &EkfParameters,
) -> Result<String, NoiseExportError> {
    let step = filter_step_noise(noise, target.step_s)?;
    let values = [
        step.gyro_rad_s,
        step.accel_m_s2,
        step.gyro_bias_rad_s2,
        step.accel_bias_m_s3,
    ];
    let units = ["rad/s", "m/s^2", "rad/s^2", "m/s^3"];
    let mut comments = provenance(target.format, noise, options);
    comments.extend(target.step_comments.map(String::from));
    comments.push("one value per sensor: the largest of the three axes x, y, z".to_string());
    comments.push(FLOOR_NOT_TUNING.to_string());
    comments.extend(step.comments);
    comments.extend(target.header.map(String::from));
    let mut body = String::new();
    for ((name, value), unit) in target.names.iter().zip(values).zip(units) {
        body.push_str(&format!("# {name} [{unit}]\n"));
        let stored =
            ParameterValue::real(value).ok_or_else(|| NoiseExportError::NotRepresentable {
                key: name.to_string(),
                value,
            })?;
        body.push_str(&(target.line)(name, stored));
    }
    Ok(commented("#", &comments) + &body)
}
