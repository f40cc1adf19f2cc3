//! OB_GINS's IMU noise block, `imumodel:` of its YAML configuration.
//!
//! Source: i2Nav-WHU/OB_GINS, `config/ob_gins.yaml` and `src/ob_gins.cc` (the `imumodel`
//! keys read as scalars: `arw` deg/√h, `vrw` m/s/√h, `gbstd` deg/h, `abstd` mGal, `corrtime`
//! hours; no scale-factor keys). Like KF-GINS, a first-order Gauss-Markov bias with one
//! correlation time, continuous white-noise densities.
//!
//! Ours: as [`super::kf_gins`], with one value per sensor (the largest of the three axes).

use super::kf_gins::M_PER_S2_PER_MGAL;
use super::{
    ExportOptions, ImuNoise, NoiseExportError, NoiseFormat, Term, bias_stand_in_comments,
    commented, common_correlation_time_s, correlation_times_comment, finite, float_text, largest,
    provenance,
};
use thermonav::imu::Sensor;
use thermonav::units::{
    SECONDS_PER_HOUR, arw_rad_per_sqrt_s_to_deg_per_sqrt_h, rad_per_s_to_deg_per_h,
    vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h,
};

/// The block's text.
///
/// # Errors
/// A missing white-noise density or Gauss-Markov model, or a non-finite value.
pub fn text(noise: &ImuNoise, options: &ExportOptions) -> Result<String, NoiseExportError> {
    let gyro =
        |term| -> Result<f64, NoiseExportError> { Ok(largest(noise.axes(Sensor::Gyro, term)?)) };
    let accel = |term| -> Result<f64, NoiseExportError> {
        Ok(largest(noise.axes(Sensor::Accelerometer, term)?))
    };
    let bias_sigma = |sensor| -> Result<f64, NoiseExportError> {
        Ok(largest(noise.bias_model_axes(sensor)?.map(|m| m.sigma)))
    };
    let lines = [
        (
            "arw",
            arw_rad_per_sqrt_s_to_deg_per_sqrt_h(gyro(Term::WhiteNoiseDensity)?),
            "[deg/sqrt(hr)] angle random walk, continuous",
        ),
        (
            "vrw",
            vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h(accel(Term::WhiteNoiseDensity)?),
            "[m/s/sqrt(hr)] velocity random walk, continuous",
        ),
        (
            "gbstd",
            rad_per_s_to_deg_per_h(bias_sigma(Sensor::Gyro)?),
            "[deg/hr] gyro bias Gauss-Markov std (stationary)",
        ),
        (
            "abstd",
            bias_sigma(Sensor::Accelerometer)? / M_PER_S2_PER_MGAL,
            "[mGal] accelerometer bias Gauss-Markov std (stationary)",
        ),
        (
            "corrtime",
            common_correlation_time_s(noise)? / SECONDS_PER_HOUR,
            "[hr] Gauss-Markov correlation time",
        ),
    ];
    let mut comments = provenance(NoiseFormat::ObGins, noise, options);
    comments.extend([
        "the imumodel block of an OB_GINS configuration: paste it into ob_gins.yaml".to_string(),
        "one value per sensor: the largest of the three axes x, y, z".to_string(),
        "arw, vrw: continuous white-noise densities; gbstd, abstd: stationary std of first-order Gauss-Markov biases".to_string(),
        correlation_times_comment(noise)?,
    ]);
    comments.extend(bias_stand_in_comments(noise)?);
    let mut body = String::from("imumodel:\n");
    for (key, value, note) in lines {
        body.push_str(&format!(
            "    {key}: {}  # {note}\n",
            float_text(finite(key, value)?)
        ));
    }
    Ok(commented("#", &comments) + &body)
}
