//! A bank's noise model at one temperature as the noise block other tools read, each with its
//! own names, shapes and units ([`NoiseFormat`]; one module per tool, each citing the source
//! of its keys and units).
//!
//! The quantities come from [`ImuNoise`] (SI, per channel): the Allan terms N, B, K of the raw
//! record and the Gauss-Markov bias model (σ, Tc) of the chosen family. Every file states, in
//! comments, the temperature and entries it comes from, whether each value is a continuous-time
//! density or a discrete per-sample value, the unit of every number, and every stand-in:
//! - **bias random walk** for tools that need one (Kalibr, PX4 EKF2, ArduPilot EKF3) when the
//!   Allan curve shows no rate random walk K: the density of the white noise that drives the
//!   Gauss-Markov model, q = σ √(2 / Tc) (from dx/dt = −x/Tc + w with stationary variance
//!   σ² = q² Tc / 2): the random walk the bias follows over times short against Tc; and
//!   without a Gauss-Markov model either (a record of white noise alone), the largest K the
//!   Allan curve allows, K = σ(τ) √(3/τ) at its longest τ (IEEE Std 952: σ_K(τ) = K √(τ/3)
//!   would otherwise lift the curve above its last point); [`bias_random_walk`];
//! - **Gauss-Markov bias** for tools that need σ and Tc (KF-GINS, OB_GINS, gnss-ins-sim) when
//!   the bank has none (its part was not significant): the first-order Gauss-Markov that
//!   reproduces the Allan minimum, σ = B (the minimum / 0.664) and Tc = the τ of the minimum;
//!   with no minimum inside the curve, the bound on B at its longest τ as σ and that τ as Tc
//!   ([`AllanStandIn`]);
//! - **one value for three axes** (Kalibr, OB_GINS, PX4, ArduPilot): the largest of the three,
//!   so that no axis is given less noise than it has; **one correlation time** for all six
//!   channels (KF-GINS, OB_GINS): the geometric mean of their Tc (correlation times spread over
//!   decades; the log scale is the natural average), each channel's Tc listed beside it.
//!
//! The PX4 and ArduPilot files also say that their values are the sensor's own noise, a floor
//! under the autopilots' larger defaults (which cover vibration in flight), not a tuning.
//!
//! A quantity the format needs and the bank lacks, with no documented stand-in, is refused
//! with an error naming the channel, the quantity and the bank's reason; so is any value that
//! would not be a finite number. Files are written through a temporary file renamed into place
//! ([`write_noise_config`]).
//!
//! Axes: our channels are the body axes x forward, y right, z down (FRD). KF-GINS, OB_GINS,
//! gnss-ins-sim, PX4 and ArduPilot use the same axes, so x, y, z map one to one. ROS
//! (REP 103) uses x forward, y left, z up: a diagonal covariance is the same in both, so the
//! ROS file holds the same diagonal; Kalibr takes one value per sensor. MATLAB's `imuSensor`
//! takes the axes as given.

pub mod ardupilot_ek3;
mod ekf_parameters;
mod error;
pub mod gnss_ins_sim;
pub mod kalibr;
pub mod kf_gins;
pub mod matlab;
pub mod ob_gins;
pub mod px4_ekf2;
pub mod ros_imu;
mod selection;

pub use error::NoiseExportError;
pub use selection::{AllanStandIn, ChannelNoise, ImuNoise, Term, sensor_channels};

use crate::atomic::write_atomically;
use crate::error::WriteError;
use serde::Serialize;
use std::io::Write as _;
use std::path::Path;
use thermonav::imu::{Channel, Sensor};
use thermonav::stoch::bank::{GaussMarkovSource, Placement};

/// The tools whose noise configuration `bank export` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum NoiseFormat {
    /// Kalibr `imu.yaml` ([`kalibr`]).
    Kalibr,
    /// KF-GINS `imunoise:` block ([`kf_gins`]).
    KfGins,
    /// OB_GINS `imumodel:` block ([`ob_gins`]).
    ObGins,
    /// gnss-ins-sim `imu_err` dictionary, Python ([`gnss_ins_sim`]).
    GnssInsSim,
    /// PX4 EKF2 noise parameters, QGroundControl `.params` ([`px4_ekf2`]).
    Px4Ekf2,
    /// ArduPilot EKF3 noise parameters, `.parm` ([`ardupilot_ek3`]).
    ArdupilotEk3,
    /// MATLAB `gyroparams`/`accelparams`/`imuSensor` script ([`matlab`]).
    Matlab,
    /// ROS `sensor_msgs/Imu` covariances, YAML ([`ros_imu`]).
    RosImuCovariance,
}

impl NoiseFormat {
    /// Every format, in the order the command line lists them.
    pub const ALL: [NoiseFormat; 8] = [
        NoiseFormat::Kalibr,
        NoiseFormat::KfGins,
        NoiseFormat::ObGins,
        NoiseFormat::GnssInsSim,
        NoiseFormat::Px4Ekf2,
        NoiseFormat::ArdupilotEk3,
        NoiseFormat::Matlab,
        NoiseFormat::RosImuCovariance,
    ];

    /// What it writes, in a line (the command line's help).
    pub fn help(self) -> &'static str {
        match self {
            NoiseFormat::Kalibr => "Kalibr imu.yaml (noise densities and random walks, continuous)",
            NoiseFormat::KfGins => {
                "KF-GINS imunoise: block (arw, vrw, gbstd, abstd, gsstd, asstd, corrtime)"
            }
            NoiseFormat::ObGins => "OB_GINS imumodel: block (arw, vrw, gbstd, abstd, corrtime)",
            NoiseFormat::GnssInsSim => "gnss-ins-sim imu_err dictionary (Python)",
            NoiseFormat::Px4Ekf2 => {
                "PX4 EKF2_GYR/ACC(_B)_NOISE parameters, a QGroundControl .params file"
            }
            NoiseFormat::ArdupilotEk3 => "ArduPilot EK3_*_P_NSE parameters, a .parm file",
            NoiseFormat::Matlab => "MATLAB gyroparams/accelparams/imuSensor script",
            NoiseFormat::RosImuCovariance => "ROS sensor_msgs/Imu covariances (YAML)",
        }
    }

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            NoiseFormat::Kalibr => "kalibr",
            NoiseFormat::KfGins => "kf-gins",
            NoiseFormat::ObGins => "ob-gins",
            NoiseFormat::GnssInsSim => "gnss-ins-sim",
            NoiseFormat::Px4Ekf2 => "px4-ekf2",
            NoiseFormat::ArdupilotEk3 => "ardupilot-ek3",
            NoiseFormat::Matlab => "matlab",
            NoiseFormat::RosImuCovariance => "ros-imu-covariance",
        }
    }
}

impl NoiseFormat {
    /// Checks that `options` hold what the format needs from the user (before any file is
    /// read): KF-GINS's scale-factor standard deviation, a finite number ≥ 0 when given.
    ///
    /// # Errors
    /// [`NoiseExportError::ScaleFactorNeeded`], [`NoiseExportError::ScaleFactorInvalid`].
    pub fn check_options(self, options: &ExportOptions) -> Result<(), NoiseExportError> {
        match options.scale_factor_std_ppm {
            Some(ppm) if !(ppm.is_finite() && ppm >= 0.0) => {
                Err(NoiseExportError::ScaleFactorInvalid(ppm))
            }
            None if self == NoiseFormat::KfGins => {
                Err(NoiseExportError::ScaleFactorNeeded(self.name()))
            }
            _ => Ok(()),
        }
    }
}

/// What the formats need beyond the bank.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportOptions {
    /// The bank's name, for the files' provenance comment.
    pub bank_name: String,
    /// Kalibr's `rostopic`.
    pub rostopic: String,
    /// KF-GINS `gsstd`/`asstd`: scale-factor standard deviation, ppm (a static bank does not
    /// measure it).
    pub scale_factor_std_ppm: Option<f64>,
}

/// What an export wrote, for `--json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NoiseExportSummary {
    /// The format.
    pub format: NoiseFormat,
    /// The operating temperature, °C.
    pub temperature_c: f64,
    /// Where it fell in the bank.
    pub placement: Placement,
    /// The Gauss-Markov family used.
    pub model: GaussMarkovSource,
    /// Nominal rate of the record, Hz.
    pub sample_rate_hz: f64,
}

impl NoiseExportSummary {
    /// The summary of writing `noise` as `format`.
    pub fn new(format: NoiseFormat, noise: &ImuNoise) -> Self {
        Self {
            format,
            temperature_c: noise.temperature_c,
            placement: noise.placement,
            model: noise.source,
            sample_rate_hz: noise.sample_rate_hz,
        }
    }
}

/// The text of `noise` in `format`.
///
/// # Errors
/// [`NoiseExportError`] naming the quantity that is missing or not finite.
pub fn noise_config_text(
    format: NoiseFormat,
    noise: &ImuNoise,
    options: &ExportOptions,
) -> Result<String, NoiseExportError> {
    let text = match format {
        NoiseFormat::Kalibr => kalibr::text(noise, options),
        NoiseFormat::KfGins => kf_gins::text(noise, options),
        NoiseFormat::ObGins => ob_gins::text(noise, options),
        NoiseFormat::GnssInsSim => gnss_ins_sim::text(noise, options),
        NoiseFormat::Px4Ekf2 => px4_ekf2::text(noise, options),
        NoiseFormat::ArdupilotEk3 => ardupilot_ek3::text(noise, options),
        NoiseFormat::Matlab => matlab::text(noise, options),
        NoiseFormat::RosImuCovariance => ros_imu::text(noise, options),
    };
    text.map_err(|e| named_format(e, format))
}

/// Writes `text` to `path` through a temporary file renamed into place.
///
/// # Errors
/// As [`write_atomically`].
pub fn write_noise_config(path: &Path, text: &str) -> Result<(), WriteError> {
    write_atomically(path, |out| Ok(out.write_all(text.as_bytes())?))
}

fn named_format(error: NoiseExportError, format: NoiseFormat) -> NoiseExportError {
    match error {
        NoiseExportError::MissingTerm {
            channel,
            term,
            temperature_c,
            reason,
            ..
        } => NoiseExportError::MissingTerm {
            format: format.name(),
            channel,
            term,
            temperature_c,
            reason,
        },
        other => other,
    }
}

/// Where a bias random walk comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WalkOrigin {
    /// The Allan curve's K.
    Measured,
    /// The Gauss-Markov stand-in σ √(2 / Tc).
    GaussMarkov,
    /// The largest K the Allan curve allows ([`Term::RateRandomWalkAtMost`]).
    CurveBound,
}

/// A bias random walk of a channel: the Allan curve's K, or a stand-in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BiasRandomWalk {
    /// rad/s/√s (= rad/s²/√Hz) or m/s²/√s (= m/s³/√Hz).
    pub value: f64,
    /// Where it comes from.
    pub origin: WalkOrigin,
}

/// K of `channel`; else the stand-in σ √(2 / Tc) of its Gauss-Markov model; else the largest
/// K its Allan curve allows (module docs).
///
/// # Errors
/// [`NoiseExportError::MissingTerm`] when none exists.
pub fn bias_random_walk(
    noise: &ImuNoise,
    channel: Channel,
) -> Result<BiasRandomWalk, NoiseExportError> {
    let channel_noise = &noise.channels[&channel];
    let walk = |value, origin| Ok(BiasRandomWalk { value, origin });
    if let Some(value) = channel_noise.rate_random_walk {
        return walk(value, WalkOrigin::Measured);
    }
    if let Some(gm) = channel_noise.gauss_markov {
        let value = gm.sigma * (2.0 / gm.correlation_time_s).sqrt();
        return walk(value, WalkOrigin::GaussMarkov);
    }
    match channel_noise.rate_random_walk_at_most {
        Some(value) => walk(value, WalkOrigin::CurveBound),
        None => Err(noise.missing(channel, Term::RateRandomWalkAtMost)),
    }
}

/// The bias random walks of the three axes of `sensor`.
///
/// # Errors
/// As [`bias_random_walk`].
pub fn bias_random_walk_axes(
    noise: &ImuNoise,
    sensor: Sensor,
) -> Result<[BiasRandomWalk; 3], NoiseExportError> {
    let [x, y, z] = sensor_channels(sensor);
    Ok([
        bias_random_walk(noise, x)?,
        bias_random_walk(noise, y)?,
        bias_random_walk(noise, z)?,
    ])
}

/// The comment lines saying which bias random walks are stand-ins.
fn stand_in_comments(sensor: Sensor, walks: &[BiasRandomWalk; 3]) -> Vec<String> {
    let rule = |origin| match origin {
        WalkOrigin::Measured => None,
        WalkOrigin::GaussMarkov => Some("sigma*sqrt(2/Tc) of its Gauss-Markov model"),
        WalkOrigin::CurveBound => Some(
            "no Gauss-Markov model either: the largest K the Allan curve allows, K = adev(tau)*sqrt(3/tau) at its longest tau",
        ),
    };
    let line = |(c, w): (&Channel, &BiasRandomWalk)| {
        let rule = rule(w.origin)?;
        Some(format!(
            "{}: no rate random walk K on the Allan curve; stand-in {rule} = {} (continuous)",
            c.name(),
            float_text(w.value)
        ))
    };
    sensor_channels(sensor)
        .iter()
        .zip(walks)
        .filter_map(line)
        .collect()
}

/// The comment lines saying which Gauss-Markov biases are stand-ins reproducing the Allan
/// minimum ([`AllanStandIn`]), with the bank's reason for having none.
///
/// # Errors
/// As [`ImuNoise::bias_model`].
pub fn bias_stand_in_comments(noise: &ImuNoise) -> Result<Vec<String>, NoiseExportError> {
    let mut lines = Vec::new();
    for channel in Channel::ALL {
        let Some(stand_in) = noise.bias_model(channel)?.1 else {
            continue;
        };
        let unit = channel.si_unit(thermonav::imu::SampleKind::Rates);
        let reason = noise.channels[&channel].absent.get(&Term::GaussMarkov);
        let rule = if stand_in.at_minimum {
            "sigma = B = the minimum Allan deviation / 0.664, Tc = the tau of that minimum"
        } else {
            "the curve has no minimum inside it: sigma = the bound on B at its longest tau (adev / 0.664), Tc = that tau"
        };
        lines.push(format!(
            "{}: no Gauss-Markov model in the bank ({}); stand-in: a first-order Gauss-Markov reproducing the Allan minimum, {rule}: sigma {} {unit}, Tc {} s",
            channel.name(),
            reason.map_or("not in the bank", String::as_str),
            float_text(stand_in.model.sigma),
            float_text(stand_in.model.correlation_time_s)
        ));
    }
    Ok(lines)
}

/// The discrete per-step noise of an EKF that predicts every `dt_s` (PX4 EKF2, ArduPilot
/// EKF3): N / √dt and K / √dt, the largest of the three axes.
#[derive(Debug, Clone, PartialEq)]
pub struct FilterStepNoise {
    /// Gyro white noise per step, rad/s.
    pub gyro_rad_s: f64,
    /// Accelerometer white noise per step, m/s².
    pub accel_m_s2: f64,
    /// Gyro bias process noise per step, rad/s².
    pub gyro_bias_rad_s2: f64,
    /// Accelerometer bias process noise per step, m/s³.
    pub accel_bias_m_s3: f64,
    /// The stand-ins used, as comment lines.
    pub comments: Vec<String>,
}

/// [`FilterStepNoise`] of `noise` for a step of `dt_s`.
///
/// # Errors
/// A missing white-noise density, neither K nor a Gauss-Markov model, or a non-finite value.
pub fn filter_step_noise(noise: &ImuNoise, dt_s: f64) -> Result<FilterStepNoise, NoiseExportError> {
    let per_step = |key: &str, density: f64| finite(key, density / dt_s.sqrt());
    let white = |sensor| -> Result<f64, NoiseExportError> {
        Ok(largest(noise.axes(sensor, Term::WhiteNoiseDensity)?))
    };
    let gyro_walks = bias_random_walk_axes(noise, Sensor::Gyro)?;
    let accel_walks = bias_random_walk_axes(noise, Sensor::Accelerometer)?;
    let mut comments = stand_in_comments(Sensor::Gyro, &gyro_walks);
    comments.extend(stand_in_comments(Sensor::Accelerometer, &accel_walks));
    Ok(FilterStepNoise {
        gyro_rad_s: per_step("gyro noise", white(Sensor::Gyro)?)?,
        accel_m_s2: per_step("accelerometer noise", white(Sensor::Accelerometer)?)?,
        gyro_bias_rad_s2: per_step("gyro bias noise", largest(gyro_walks.map(|w| w.value)))?,
        accel_bias_m_s3: per_step(
            "accelerometer bias noise",
            largest(accel_walks.map(|w| w.value)),
        )?,
        comments,
    })
}

/// The largest of three values (the rule for one value per sensor, module docs).
pub fn largest(values: [f64; 3]) -> f64 {
    values.into_iter().fold(f64::NEG_INFINITY, f64::max)
}

/// The geometric mean of the six channels' Tc, s (the rule for one correlation time).
///
/// # Errors
/// [`NoiseExportError::MissingTerm`] when a channel has no Gauss-Markov model.
pub fn common_correlation_time_s(noise: &ImuNoise) -> Result<f64, NoiseExportError> {
    let mut log_sum = 0.0;
    for channel in Channel::ALL {
        log_sum += noise.bias_model(channel)?.0.correlation_time_s.ln();
    }
    Ok((log_sum / Channel::ALL.len() as f64).exp())
}

/// `value`, or [`NoiseExportError::NotFinite`] naming `key`.
///
/// # Errors
/// When `value` is NaN or infinite.
pub fn finite(key: &str, value: f64) -> Result<f64, NoiseExportError> {
    match value.is_finite() {
        true => Ok(value),
        false => Err(NoiseExportError::NotFinite {
            key: key.to_string(),
            value,
        }),
    }
}

/// Three values, each checked by [`finite`].
///
/// # Errors
/// As [`finite`].
pub fn finite_axes(key: &str, values: [f64; 3]) -> Result<[f64; 3], NoiseExportError> {
    for (axis, v) in ["x", "y", "z"].iter().zip(values) {
        finite(&format!("{key} ({axis})"), v)?;
    }
    Ok(values)
}

/// A number as text that reads back to the same `f64` in YAML 1.1 (PyYAML, Kalibr), YAML 1.2,
/// Python, MATLAB and C `strtod`: shortest round-trip digits, a decimal point in the mantissa
/// and a signed exponent (`1.0e-4`, `2.5e+2`; PyYAML reads `1e-4` as a string).
pub fn float_text(value: f64) -> String {
    let text = format!("{value:e}");
    let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
    let point = if mantissa.contains('.') { "" } else { ".0" };
    let sign = if exponent.starts_with('-') { "" } else { "+" };
    format!("{mantissa}{point}e{sign}{exponent}")
}

/// `[x, y, z]` in [`float_text`].
pub fn vector_text(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|&v| float_text(v)).collect();
    format!("[{}]", items.join(", "))
}

/// `lines` as comment lines with `prefix` (`#`, `%`).
pub fn commented(prefix: &str, lines: &[String]) -> String {
    lines
        .iter()
        .map(|line| match line.is_empty() {
            true => format!("{prefix}\n"),
            false => format!("{prefix} {line}\n"),
        })
        .collect()
}

/// Where the values come from: bank, temperature, entries, model family, rate.
pub fn provenance(format: NoiseFormat, noise: &ImuNoise, options: &ExportOptions) -> Vec<String> {
    vec![
        format!(
            "{} noise configuration written by thermonav bank export from {}",
            format.name(),
            options.bank_name
        ),
        format!(
            "at {} degC: {}; Gauss-Markov model {}; record rate {} Hz",
            noise.temperature_c,
            placement_words(noise.placement),
            noise.source.cli_name(),
            noise.sample_rate_hz
        ),
    ]
}

/// Where the values come from, in words.
pub fn placement_words(placement: Placement) -> String {
    match placement {
        Placement::Entry { temperature_c } | Placement::Clamped { temperature_c } => {
            format!("the bank's entry at {temperature_c} degC (nearest)")
        }
        Placement::Between {
            lower_c,
            upper_c,
            weight,
        } => format!(
            "interpolated linearly between the entries at {lower_c} and {upper_c} degC (weight {weight} on {upper_c})"
        ),
    }
}

/// Each channel's Tc, for the comment beside a common correlation time.
fn correlation_times_comment(noise: &ImuNoise) -> Result<String, NoiseExportError> {
    let mut items = Vec::new();
    for channel in Channel::ALL {
        let tc = noise.bias_model(channel)?.0.correlation_time_s;
        items.push(format!("{} {} s", channel.name(), float_text(tc)));
    }
    Ok(format!(
        "Tc per channel: {}; one correlation time for all: their geometric mean",
        items.join(", ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    // The command line's names are the formats' serialised (kebab-case) names, each listed
    // once: serde derives those names from the variants independently of `name()`.
    #[test]
    fn every_format_is_listed_once_under_its_serialised_name() {
        let names: Vec<&str> = NoiseFormat::ALL.iter().map(|f| f.name()).collect();
        for (format, name) in NoiseFormat::ALL.iter().zip(&names) {
            let serialised = serde_json::to_string(format).unwrap();
            assert_eq!(serialised, format!("\"{name}\""));
            assert!(!format.help().is_empty());
        }
        let distinct: std::collections::BTreeSet<_> = names.iter().collect();
        assert_eq!(distinct.len(), names.len(), "{names:?}");
    }

    #[test]
    fn float_text_reads_back_and_has_a_point_and_a_signed_exponent() {
        for v in [1e-4, 2.5e2, 0.1, -3.0, 1.0 / 3.0, 6.02e23, 5e-324] {
            let text = float_text(v);
            assert_eq!(text.parse::<f64>().unwrap(), v, "{text}");
            let (m, e) = text.split_once('e').unwrap();
            assert!(
                m.contains('.') && (e.starts_with('-') || e.starts_with('+')),
                "{text}"
            );
        }
        assert_eq!(float_text(1e-4), "1.0e-4");
        assert_eq!(float_text(250.0), "2.5e+2");
    }

    #[test]
    fn largest_and_finite() {
        assert_eq!(largest([1.0, 3.0, 2.0]), 3.0);
        assert!(finite("k", f64::NAN).is_err());
        assert!(finite_axes("k", [1.0, f64::INFINITY, 0.0]).is_err());
    }
}
