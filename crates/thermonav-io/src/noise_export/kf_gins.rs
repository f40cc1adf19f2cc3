//! KF-GINS's IMU noise block, `imunoise:` of its YAML configuration.
//!
//! Source: i2Nav-WHU/KF-GINS, `config/kf-gins.yaml` (keys and units) and `src/kf_gins.cpp`
//! (`loadConfig`: each of `arw`, `vrw`, `gbstd`, `abstd`, `gsstd`, `asstd` read as a 3-vector,
//! all six required, `corrtime` a scalar). Units: `arw` deg/√h, `vrw` m/s/√h, `gbstd` deg/h,
//! `abstd` mGal (1 mGal = 1e-5 m/s²), `gsstd`/`asstd` ppm, `corrtime` hours; axes forward,
//! right, down (ours). KF-GINS models biases and scale factors as first-order Gauss-Markov
//! processes with the one `corrtime` and the given standard deviations (its process noise is
//! 2σ²/T), and `arw`/`vrw` as continuous white-noise densities.
//!
//! Ours: N → `arw`/`vrw`; the Gauss-Markov σ → `gbstd`/`abstd`; the geometric mean of the six
//! Tc → `corrtime`; `gsstd`/`asstd` from the user ([`ExportOptions::scale_factor_std_ppm`]):
//! a static record does not observe scale factors.

use super::{
    ExportOptions, ImuNoise, NoiseExportError, NoiseFormat, Term, bias_stand_in_comments,
    commented, common_correlation_time_s, correlation_times_comment, finite, finite_axes,
    float_text, provenance, vector_text,
};
use thermonav::imu::Sensor;
use thermonav::units::{
    SECONDS_PER_HOUR, arw_rad_per_sqrt_s_to_deg_per_sqrt_h, rad_per_s_to_deg_per_h,
    vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h,
};

/// m/s² in one milligal.
pub const M_PER_S2_PER_MGAL: f64 = 1.0e-5;

/// The block's text.
///
/// # Errors
/// A missing white-noise density or Gauss-Markov model, no scale-factor std given, or a
/// non-finite value.
pub fn text(noise: &ImuNoise, options: &ExportOptions) -> Result<String, NoiseExportError> {
    let ppm = options
        .scale_factor_std_ppm
        .ok_or(NoiseExportError::ScaleFactorNeeded(
            NoiseFormat::KfGins.name(),
        ))?;
    let ppm = finite("gsstd/asstd", ppm)?;
    let arw = noise.axes(Sensor::Gyro, Term::WhiteNoiseDensity)?;
    let vrw = noise.axes(Sensor::Accelerometer, Term::WhiteNoiseDensity)?;
    let gbstd = noise.bias_model_axes(Sensor::Gyro)?.map(|m| m.sigma);
    let abstd = noise
        .bias_model_axes(Sensor::Accelerometer)?
        .map(|m| m.sigma);
    let corrtime_h = common_correlation_time_s(noise)? / SECONDS_PER_HOUR;
    let lines = [
        (
            "arw",
            finite_axes("arw", arw.map(arw_rad_per_sqrt_s_to_deg_per_sqrt_h))?,
            "[deg/sqrt(hr)] angle random walk, continuous",
        ),
        (
            "vrw",
            finite_axes("vrw", vrw.map(vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h))?,
            "[m/s/sqrt(hr)] velocity random walk, continuous",
        ),
        (
            "gbstd",
            finite_axes("gbstd", gbstd.map(rad_per_s_to_deg_per_h))?,
            "[deg/hr] gyro bias Gauss-Markov std (stationary)",
        ),
        (
            "abstd",
            finite_axes("abstd", abstd.map(|s| s / M_PER_S2_PER_MGAL))?,
            "[mGal] accelerometer bias Gauss-Markov std (stationary)",
        ),
        (
            "gsstd",
            [ppm; 3],
            "[ppm] gyro scale-factor std: given by the user, not from the bank",
        ),
        (
            "asstd",
            [ppm; 3],
            "[ppm] accelerometer scale-factor std: given by the user, not from the bank",
        ),
    ];
    let mut comments = provenance(NoiseFormat::KfGins, noise, options);
    comments.extend([
        "the imunoise block of a KF-GINS configuration: paste it into kf-gins.yaml".to_string(),
        "arw, vrw: continuous white-noise densities; gbstd, abstd: stationary std of first-order Gauss-Markov biases; KF-GINS discretises with each IMU interval".to_string(),
        correlation_times_comment(noise)?,
    ]);
    comments.extend(bias_stand_in_comments(noise)?);
    let mut body = String::from("imunoise:\n");
    for (key, values, note) in lines {
        body.push_str(&format!("  {key}: {}  # {note}\n", vector_text(&values)));
    }
    let corrtime_h = finite("corrtime", corrtime_h)?;
    body.push_str(&format!(
        "  corrtime: {}  # [hr] Gauss-Markov correlation time\n",
        float_text(corrtime_h)
    ));
    Ok(commented("#", &comments) + &body)
}
