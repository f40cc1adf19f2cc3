//! Sensor profiles as TOML, with the unit in every key name.
//!
//! ```toml
//! name = "ADIS16364-like"
//! reference_temperature_c = 25.0
//!
//! [channels.gx]
//! white_noise_deg_per_sqrt_h = 2.0
//! bias_random_walk_deg_per_h_per_sqrt_h = 0.0
//! turn_on_bias_sd_deg_s = 1.0        # the unit's fixed bias, unit to unit
//! power_on_offset_sd_deg_s = 0.1     # optional: added at each power-on
//! bias_tempco_deg_s_per_c = 0.01
//! bias_tempco2_deg_s_per_c2 = -5e-5  # optional: curvature of bias(T)
//! scale_factor_tempco_ppm_per_c = 40.0
//! quantization_deg_s = 0.05
//! thermal_lag_s = 120.0              # optional: the structure lags the temperature sensor
//! bias_gauss_markov = [
//!   { temperature_c = -40.0, correlation_time_s = 40.0, sigma_deg_h = 61.0 },
//!   { temperature_c = 20.0, correlation_time_s = 150.0, sigma_deg_h = 40.6 },
//! ]
//! # optional: scale_factor_gauss_markov = { correlation_time_s = 3600.0, sigma_ppm = 100.0 }
//!
//! [channels.ax]
//! white_noise_m_s_per_sqrt_h = 0.12
//! bias_random_walk_m_s2_per_sqrt_h = 0.0
//! turn_on_bias_sd_mg = 2.67
//! power_on_offset_sd_mg = 0.27
//! bias_tempco_mg_per_c = 0.05
//! bias_tempco2_mg_per_c2 = -2.5e-4
//! scale_factor_tempco_ppm_per_c = 25.0
//! quantization_mg = 1.0
//! bias_gauss_markov = [{ temperature_c = 20.0, correlation_time_s = 400.0, sigma_mg = 0.145 }]
//! ```
//! Gyro channels (gx, gy, gz) use the gyro keys, accelerometer channels (ax, ay, az) the
//! accelerometer keys; all six are required. Values convert once to SI.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;
use thermonav::imu::{Channel, Sensor};
use thermonav::sensor::{ChannelProfile, GaussMarkovPoint, ScaleFactorGaussMarkov, SensorProfile};
use thermonav::units::{
    arw_deg_per_sqrt_h_to_rad_per_sqrt_s, arw_rad_per_sqrt_s_to_deg_per_sqrt_h,
    deg_per_h_to_rad_per_s, deg_to_rad, m_per_s2_to_mg, mg_to_m_per_s2, rad_per_s_to_deg_per_h,
    rad_to_deg, vrw_m_per_s_per_sqrt_h_to_m_per_s_per_sqrt_s,
    vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h,
};

/// Why a profile file cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum ProfileFileError {
    /// The file cannot be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// File.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// Not valid TOML for the schema.
    #[error("{path}: {message}")]
    Parse {
        /// File.
        path: String,
        /// The parser's message, with line and column.
        message: String,
    },
    /// A channel given with the other sensor's keys, or missing.
    #[error("{path}: {message}")]
    Schema {
        /// File.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// Values out of range.
    #[error("{path}: {source}")]
    Invalid {
        /// File.
        path: String,
        /// The validation error.
        source: thermonav::sensor::ProfileError,
    },
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ProfileFile {
    name: String,
    reference_temperature_c: f64,
    channels: BTreeMap<String, toml::Value>,
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct GyroChannel {
    white_noise_deg_per_sqrt_h: f64,
    #[serde(default)]
    bias_random_walk_deg_per_h_per_sqrt_h: f64,
    #[serde(default)]
    turn_on_bias_sd_deg_s: f64,
    #[serde(default)]
    power_on_offset_sd_deg_s: f64,
    #[serde(default)]
    bias_tempco_deg_s_per_c: f64,
    #[serde(default)]
    bias_tempco2_deg_s_per_c2: f64,
    #[serde(default)]
    scale_factor_tempco_ppm_per_c: f64,
    #[serde(default)]
    quantization_deg_s: f64,
    /// Thermal lag of the structure behind the temperature sensor, s.
    #[serde(default, skip_serializing_if = "is_zero")]
    thermal_lag_s: f64,
    bias_gauss_markov: Vec<GyroPoint>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    scale_factor_gauss_markov: Option<ScaleFactorGaussMarkov>,
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct GyroPoint {
    temperature_c: f64,
    correlation_time_s: f64,
    sigma_deg_h: f64,
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct AccelChannel {
    white_noise_m_s_per_sqrt_h: f64,
    #[serde(default)]
    bias_random_walk_m_s2_per_sqrt_h: f64,
    #[serde(default)]
    turn_on_bias_sd_mg: f64,
    #[serde(default)]
    power_on_offset_sd_mg: f64,
    #[serde(default)]
    bias_tempco_mg_per_c: f64,
    #[serde(default)]
    bias_tempco2_mg_per_c2: f64,
    #[serde(default)]
    scale_factor_tempco_ppm_per_c: f64,
    #[serde(default)]
    quantization_mg: f64,
    /// Thermal lag of the structure behind the temperature sensor, s.
    #[serde(default, skip_serializing_if = "is_zero")]
    thermal_lag_s: f64,
    bias_gauss_markov: Vec<AccelPoint>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    scale_factor_gauss_markov: Option<ScaleFactorGaussMarkov>,
}

#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct AccelPoint {
    temperature_c: f64,
    correlation_time_s: f64,
    sigma_mg: f64,
}

const SQRT_H_IN_S: f64 = 60.0;

/// True for a value left out of a written profile (its default).
fn is_zero(value: &f64) -> bool {
    *value == 0.0
}

impl GyroChannel {
    fn to_si(&self) -> ChannelProfile {
        ChannelProfile {
            white_noise_density: arw_deg_per_sqrt_h_to_rad_per_sqrt_s(
                self.white_noise_deg_per_sqrt_h,
            ),
            bias_gauss_markov: self
                .bias_gauss_markov
                .iter()
                .map(|p| GaussMarkovPoint {
                    temperature_c: p.temperature_c,
                    correlation_time_s: p.correlation_time_s,
                    sigma: deg_per_h_to_rad_per_s(p.sigma_deg_h),
                })
                .collect(),
            bias_random_walk_density: deg_per_h_to_rad_per_s(
                self.bias_random_walk_deg_per_h_per_sqrt_h,
            ) / SQRT_H_IN_S,
            turn_on_bias_sigma: deg_to_rad(self.turn_on_bias_sd_deg_s),
            power_on_offset_sigma: deg_to_rad(self.power_on_offset_sd_deg_s),
            bias_temperature_coefficient_per_c: deg_to_rad(self.bias_tempco_deg_s_per_c),
            bias_temperature_quadratic_per_c2: deg_to_rad(self.bias_tempco2_deg_s_per_c2),
            scale_factor_temperature_coefficient_ppm_per_c: self.scale_factor_tempco_ppm_per_c,
            scale_factor_gauss_markov: self.scale_factor_gauss_markov,
            quantization_step: deg_to_rad(self.quantization_deg_s),
            thermal_lag_s: self.thermal_lag_s,
        }
    }

    fn from_si(p: &ChannelProfile) -> Self {
        Self {
            white_noise_deg_per_sqrt_h: arw_rad_per_sqrt_s_to_deg_per_sqrt_h(p.white_noise_density),
            bias_random_walk_deg_per_h_per_sqrt_h: rad_per_s_to_deg_per_h(
                p.bias_random_walk_density,
            ) * SQRT_H_IN_S,
            turn_on_bias_sd_deg_s: rad_to_deg(p.turn_on_bias_sigma),
            power_on_offset_sd_deg_s: rad_to_deg(p.power_on_offset_sigma),
            bias_tempco_deg_s_per_c: rad_to_deg(p.bias_temperature_coefficient_per_c),
            bias_tempco2_deg_s_per_c2: rad_to_deg(p.bias_temperature_quadratic_per_c2),
            scale_factor_tempco_ppm_per_c: p.scale_factor_temperature_coefficient_ppm_per_c,
            quantization_deg_s: rad_to_deg(p.quantization_step),
            thermal_lag_s: p.thermal_lag_s,
            bias_gauss_markov: p
                .bias_gauss_markov
                .iter()
                .map(|g| GyroPoint {
                    temperature_c: g.temperature_c,
                    correlation_time_s: g.correlation_time_s,
                    sigma_deg_h: rad_per_s_to_deg_per_h(g.sigma),
                })
                .collect(),
            scale_factor_gauss_markov: p.scale_factor_gauss_markov,
        }
    }
}

impl AccelChannel {
    fn to_si(&self) -> ChannelProfile {
        ChannelProfile {
            white_noise_density: vrw_m_per_s_per_sqrt_h_to_m_per_s_per_sqrt_s(
                self.white_noise_m_s_per_sqrt_h,
            ),
            bias_gauss_markov: self
                .bias_gauss_markov
                .iter()
                .map(|p| GaussMarkovPoint {
                    temperature_c: p.temperature_c,
                    correlation_time_s: p.correlation_time_s,
                    sigma: mg_to_m_per_s2(p.sigma_mg),
                })
                .collect(),
            bias_random_walk_density: self.bias_random_walk_m_s2_per_sqrt_h / SQRT_H_IN_S,
            turn_on_bias_sigma: mg_to_m_per_s2(self.turn_on_bias_sd_mg),
            power_on_offset_sigma: mg_to_m_per_s2(self.power_on_offset_sd_mg),
            bias_temperature_coefficient_per_c: mg_to_m_per_s2(self.bias_tempco_mg_per_c),
            bias_temperature_quadratic_per_c2: mg_to_m_per_s2(self.bias_tempco2_mg_per_c2),
            scale_factor_temperature_coefficient_ppm_per_c: self.scale_factor_tempco_ppm_per_c,
            scale_factor_gauss_markov: self.scale_factor_gauss_markov,
            quantization_step: mg_to_m_per_s2(self.quantization_mg),
            thermal_lag_s: self.thermal_lag_s,
        }
    }

    fn from_si(p: &ChannelProfile) -> Self {
        Self {
            white_noise_m_s_per_sqrt_h: vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h(
                p.white_noise_density,
            ),
            bias_random_walk_m_s2_per_sqrt_h: p.bias_random_walk_density * SQRT_H_IN_S,
            turn_on_bias_sd_mg: m_per_s2_to_mg(p.turn_on_bias_sigma),
            power_on_offset_sd_mg: m_per_s2_to_mg(p.power_on_offset_sigma),
            bias_tempco_mg_per_c: m_per_s2_to_mg(p.bias_temperature_coefficient_per_c),
            bias_tempco2_mg_per_c2: m_per_s2_to_mg(p.bias_temperature_quadratic_per_c2),
            scale_factor_tempco_ppm_per_c: p.scale_factor_temperature_coefficient_ppm_per_c,
            quantization_mg: m_per_s2_to_mg(p.quantization_step),
            thermal_lag_s: p.thermal_lag_s,
            bias_gauss_markov: p
                .bias_gauss_markov
                .iter()
                .map(|g| AccelPoint {
                    temperature_c: g.temperature_c,
                    correlation_time_s: g.correlation_time_s,
                    sigma_mg: m_per_s2_to_mg(g.sigma),
                })
                .collect(),
            scale_factor_gauss_markov: p.scale_factor_gauss_markov,
        }
    }
}

/// Parses a profile from TOML text; `path` names the source in errors.
///
/// # Errors
/// [`ProfileFileError`] for invalid TOML, unknown or missing keys, a missing channel, or values
/// out of range.
pub fn parse_profile(text: &str, path: &str) -> Result<SensorProfile, ProfileFileError> {
    let parse = |message: String| ProfileFileError::Parse {
        path: path.to_string(),
        message,
    };
    let file: ProfileFile = toml::from_str(text).map_err(|e| parse(e.to_string()))?;
    let mut channels = BTreeMap::new();
    for channel in Channel::ALL {
        let value = file
            .channels
            .get(channel.name())
            .ok_or_else(|| ProfileFileError::Schema {
                path: path.to_string(),
                message: format!("missing table [channels.{}]", channel.name()),
            })?;
        let schema = |e: toml::de::Error| ProfileFileError::Schema {
            path: path.to_string(),
            message: format!("[channels.{}]: {e}", channel.name()),
        };
        let profile = match channel.sensor() {
            Sensor::Gyro => value
                .clone()
                .try_into::<GyroChannel>()
                .map_err(schema)?
                .to_si(),
            Sensor::Accelerometer => value
                .clone()
                .try_into::<AccelChannel>()
                .map_err(schema)?
                .to_si(),
        };
        channels.insert(channel, profile);
    }
    if let Some(extra) = file
        .channels
        .keys()
        .find(|k| !Channel::ALL.iter().any(|c| c.name() == k.as_str()))
    {
        return Err(ProfileFileError::Schema {
            path: path.to_string(),
            message: format!("unknown channel [channels.{extra}] (expected gx gy gz ax ay az)"),
        });
    }
    let profile = SensorProfile {
        name: file.name,
        reference_temperature_c: file.reference_temperature_c,
        channels,
    };
    profile
        .validate()
        .map_err(|source| ProfileFileError::Invalid {
            path: path.to_string(),
            source,
        })?;
    Ok(profile)
}

/// Parses a profile from the bytes of a file named `path`, which must be UTF-8 text.
///
/// # Errors
/// As [`parse_profile`], plus [`ProfileFileError::Parse`] with the line of the first byte that
/// is not UTF-8.
pub fn parse_profile_bytes(bytes: &[u8], path: &str) -> Result<SensorProfile, ProfileFileError> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        ProfileFileError::Parse {
            path: path.to_string(),
            message: format!("line {line}: not UTF-8 text (expected a TOML sensor profile)"),
        }
    })?;
    parse_profile(text, path)
}

/// Reads a profile file.
///
/// # Errors
/// As [`parse_profile_bytes`], plus an unreadable file.
pub fn read_profile(path: &Path) -> Result<SensorProfile, ProfileFileError> {
    let name = path.display().to_string();
    let bytes = crate::read_document(path).map_err(|source| ProfileFileError::Read {
        path: name.clone(),
        source,
    })?;
    parse_profile_bytes(&bytes, &name)
}

/// A profile as TOML text in the file schema (edge units).
///
/// # Errors
/// The TOML serialiser's error (not expected for these plain tables).
pub fn profile_to_toml(profile: &SensorProfile) -> Result<String, toml::ser::Error> {
    let channels = profile
        .channels
        .iter()
        .map(|(channel, p)| {
            let value = match channel.sensor() {
                Sensor::Gyro => toml::Value::try_from(GyroChannel::from_si(p)),
                Sensor::Accelerometer => toml::Value::try_from(AccelChannel::from_si(p)),
            };
            value.map(|v| (channel.name().to_string(), v))
        })
        .collect::<Result<_, _>>()?;
    let file = ProfileFile {
        name: profile.name.clone(),
        reference_temperature_c: profile.reference_temperature_c,
        channels,
    };
    toml::to_string(&file)
}

#[cfg(test)]
mod tests {
    use super::*;
    use thermonav::sensor::adis16364_like;

    #[test]
    fn built_in_profile_round_trips_through_toml() {
        // Unit conversions out and back are each a multiplication and its inverse: 1e-12
        // relative covers the rounding.
        let profile = adis16364_like();
        let text = profile_to_toml(&profile).unwrap();
        assert!(text.contains("white_noise_deg_per_sqrt_h") && text.contains("sigma_mg"));
        let back = parse_profile(&text, "built-in.toml").unwrap();
        for (channel, p) in &profile.channels {
            let q = &back.channels[channel];
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300);
            assert!(
                close(p.white_noise_density, q.white_noise_density),
                "{channel:?}"
            );
            for (a, b) in p.bias_gauss_markov.iter().zip(&q.bias_gauss_markov) {
                assert!(close(a.sigma, b.sigma) && a.correlation_time_s == b.correlation_time_s);
            }
            assert!(close(p.quantization_step, q.quantization_step));
        }
    }

    #[test]
    fn mistakes_name_the_file_and_the_key() {
        let text = profile_to_toml(&adis16364_like()).unwrap();
        let wrong_unit = text.replacen("white_noise_deg_per_sqrt_h", "white_noise_rad", 1);
        let e = parse_profile(&wrong_unit, "p.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("p.toml") && e.contains("white_noise_rad"),
            "{e}"
        );
        let missing = text.replace("[channels.az]", "[channels.az_old]");
        let e = parse_profile(&missing, "p.toml").unwrap_err().to_string();
        assert!(e.contains("channels.az"), "{e}");
        let e = parse_profile("name = 3", "p.toml").unwrap_err().to_string();
        assert!(e.starts_with("p.toml"), "{e}");
        let negative = text.replacen("correlation_time_s = 40.0", "correlation_time_s = -40.0", 1);
        assert!(parse_profile(&negative, "p.toml").is_err());
    }
}
