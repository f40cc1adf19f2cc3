//! ROS `sensor_msgs/Imu` covariances, as YAML parameters for a driver that fills them.
//!
//! Source: ROS message definition `sensor_msgs/msg/Imu.msg`
//! (<https://docs.ros.org/en/api/sensor_msgs/html/msg/Imu.html>): `orientation_covariance`,
//! `angular_velocity_covariance` (rad/s)² and `linear_acceleration_covariance` (m/s²)², each
//! a `float64[9]` 3x3 matrix in row-major order about x, y, z; "if you have no estimate for
//! one of the data elements, set element 0 of the associated covariance matrix to -1". Axes:
//! REP 103 (x forward, y left, z up): the rotation from our FRD is diag(1, −1, −1), which
//! leaves a diagonal covariance unchanged.
//!
//! Ours: each message carries one sample, so its covariance is the discrete per-sample
//! variance of the white noise, σ² = N² · rate (the record's rate), on the diagonal; the bias
//! (Gauss-Markov, random walk) is not part of a single sample's noise and is left out.
//! `orientation_covariance` is [-1, 0, ...]: an IMU without an orientation estimate.

use super::{
    ExportOptions, ImuNoise, NoiseExportError, NoiseFormat, Term, commented, finite, finite_axes,
    provenance, vector_text,
};
use thermonav::imu::Sensor;

/// The file's text.
///
/// # Errors
/// A missing white-noise density, or a non-finite value.
pub fn text(noise: &ImuNoise, options: &ExportOptions) -> Result<String, NoiseExportError> {
    let rate_hz = finite("rate", noise.sample_rate_hz)?;
    let variance = |sensor, key| -> Result<[f64; 9], NoiseExportError> {
        let density = noise.axes(sensor, Term::WhiteNoiseDensity)?;
        let [x, y, z] = finite_axes(key, density.map(|n| n * n * rate_hz))?;
        Ok([x, 0.0, 0.0, 0.0, y, 0.0, 0.0, 0.0, z])
    };
    let gyro = variance(Sensor::Gyro, "angular_velocity_covariance")?;
    let accel = variance(Sensor::Accelerometer, "linear_acceleration_covariance")?;
    let mut comments = provenance(NoiseFormat::RosImuCovariance, noise, options);
    comments.extend([
        format!("discrete per-sample variances: density^2 * rate, rate = {rate_hz} Hz (continuous density N in rad/s/sqrt(Hz), m/s^2/sqrt(Hz)); bias not included"),
        "3x3 row-major about x, y, z; the same diagonal in ROS's FLU axes as in our FRD".to_string(),
    ]);
    let mut orientation = [0.0; 9];
    orientation[0] = -1.0;
    let body = format!(
        "orientation_covariance: {}  # no orientation estimate\nangular_velocity_covariance: {}  # [(rad/s)^2]\nlinear_acceleration_covariance: {}  # [(m/s^2)^2]\n",
        vector_text(&orientation),
        vector_text(&gyro),
        vector_text(&accel)
    );
    Ok(commented("#", &comments) + &body)
}
