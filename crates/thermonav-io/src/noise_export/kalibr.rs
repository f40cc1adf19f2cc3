//! Kalibr's IMU configuration, `imu.yaml`.
//!
//! Source: ethz-asl/kalibr wiki, "IMU Noise Model" and "Supported IMU models / YAML formats"
//! (<https://github.com/ethz-asl/kalibr/wiki/IMU-Noise-Model>,
//! <https://github.com/ethz-asl/kalibr/wiki/yaml-formats>): top-level keys `rostopic`,
//! `update_rate` (Hz), `accelerometer_noise_density` (m/s²/√Hz), `accelerometer_random_walk`
//! (m/s³/√Hz), `gyroscope_noise_density` (rad/s/√Hz), `gyroscope_random_walk` (rad/s²/√Hz),
//! one scalar per sensor, all continuous-time; Kalibr discretises them itself with
//! `update_rate`: σ_d = σ·√rate for the white noise, σ_bd = σ_b/√rate for the bias random
//! walk. Kalibr reads the file with PyYAML, hence [`super::float_text`].
//!
//! Ours: N → `*_noise_density` (rad/√s is rad/s/√Hz), K → `*_random_walk` (rad/s/√s is
//! rad/s²/√Hz), else the Gauss-Markov stand-in ([`super::bias_random_walk`]); the largest of
//! the three axes; `update_rate` the record's rate.

use super::{
    ExportOptions, ImuNoise, NoiseExportError, NoiseFormat, Term, bias_random_walk_axes, commented,
    finite, float_text, largest, provenance, stand_in_comments,
};
use thermonav::imu::Sensor;

/// The file's text.
///
/// # Errors
/// A missing white-noise density, or neither K nor a Gauss-Markov model, or a non-finite value.
pub fn text(noise: &ImuNoise, options: &ExportOptions) -> Result<String, NoiseExportError> {
    let mut comments = provenance(NoiseFormat::Kalibr, noise, options);
    comments.extend([
        "continuous-time values (Kalibr discretises them with update_rate: sigma_d = sigma*sqrt(rate) for the white noise, sigma_bd = sigma_b/sqrt(rate) for the bias random walk)".to_string(),
        "one value per sensor: the largest of the three axes x, y, z".to_string(),
    ]);
    let mut body = String::new();
    for (sensor, name, [density_unit, walk_unit]) in [
        (
            Sensor::Accelerometer,
            "accelerometer",
            ["m/s^2/sqrt(Hz)", "m/s^3/sqrt(Hz)"],
        ),
        (
            Sensor::Gyro,
            "gyroscope",
            ["rad/s/sqrt(Hz)", "rad/s^2/sqrt(Hz)"],
        ),
    ] {
        let density = finite(name, largest(noise.axes(sensor, Term::WhiteNoiseDensity)?))?;
        let walks = bias_random_walk_axes(noise, sensor)?;
        comments.extend(stand_in_comments(sensor, &walks));
        let walk = finite(name, largest(walks.map(|w| w.value)))?;
        body.push_str(&format!(
            "{name}_noise_density: {}  # [{density_unit}] white noise, continuous\n",
            float_text(density)
        ));
        body.push_str(&format!(
            "{name}_random_walk: {}  # [{walk_unit}] bias random walk, continuous\n",
            float_text(walk)
        ));
    }
    let rate = finite("update_rate", noise.sample_rate_hz)?;
    body.push_str(&format!(
        "rostopic: {}  # the IMU topic\n",
        yaml_string(&options.rostopic)
    ));
    body.push_str(&format!(
        "update_rate: {}  # [Hz] the record's rate\n",
        float_text(rate)
    ));
    Ok(commented("#", &comments) + &body)
}

/// A YAML double-quoted string.
fn yaml_string(text: &str) -> String {
    format!("\"{}\"", text.replace('\\', "\\\\").replace('"', "\\\""))
}
