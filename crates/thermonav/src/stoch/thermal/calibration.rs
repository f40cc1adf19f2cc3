//! A unit's thermal calibration: the repeatable bias curve of every channel (with the
//! power-on offsets kept apart where the data identify them), and its use, the compensation of
//! a record's samples at their own temperatures.
//!
//! # The band of a curve with power-on offsets
//! With J ≥ 2 power-ons the curve's constant is the mean of the J fitted offsets, so as an
//! estimate of the unit's repeatable bias (the long-run mean over power-ons) it carries the
//! further variance σ̂_b² / J (σ̂_b the spread between power-ons, [`PowerOnFit`]). That
//! variance is added to the constant's, and because it is estimated from only J − 1 degrees of
//! freedom, the band's multiple is the larger of the Scheffé factor and the two-sided 95 %
//! Student quantile t_{J−1}: with few power-ons the offsets' mean, not the shape, limits how
//! well the absolute curve is known.
//!
//! # Scale factor
//! A static, level unit reads Earth rate on its gyros (≤ 15 °/h) and ±g on one accelerometer
//! only, so a scale-factor change with temperature is either invisible (gyros, horizontal
//! accelerometers) or indistinguishable from a bias change (the vertical accelerometer reads
//! b(T) + g · s(T)). The calibration says so ([`ScaleFactorCalibration::NotIdentifiable`]);
//! the vertical accelerometer's curve holds both.

use super::selection::{HeldOutSelection, SweepBlock, SweepLeg, ThermalLag};
use super::{
    FitSettings, PowerOnFit, PowerOnOffset, PowerOnRecord, TemperaturePoint, ThermalCurve,
    ThermalError, fit_bias_curve, fit_bias_curve_with_power_ons,
};
use crate::imu::{Channel, ImuSeries, TemperatureColumnError};
use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, StudentsT};
use std::collections::BTreeMap;

/// Whether the calibration holds scale factor against temperature.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum ScaleFactorCalibration {
    /// The data cannot separate it (module docs, "Scale factor").
    NotIdentifiable {
        /// Why, in words.
        reason: String,
    },
}

impl ScaleFactorCalibration {
    /// The verdict for static sweeps in one orientation each.
    pub fn static_sweeps() -> Self {
        Self::NotIdentifiable {
            reason: "static sweeps: the gyros read only Earth rate and each accelerometer a \
                     fixed share of gravity, so a scale factor's change with temperature is \
                     read as a bias change"
                .into(),
        }
    }

    /// The verdict for static records of a level unit.
    pub fn static_level_unit() -> Self {
        Self::NotIdentifiable {
            reason: "static level records: the gyros read only Earth rate and the horizontal \
                     accelerometers nothing, so their scale factor is invisible; az reads \
                     b(T) + g s(T), so its curve holds both"
                .into(),
        }
    }
}

/// The calibration of one channel.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChannelCalibration {
    /// The repeatable bias curve (channel unit: rad/s or m/s²).
    pub bias: ThermalCurve,
    /// Each power-on's offset from the curve, when two or more power-ons were separated;
    /// empty when the curve was fitted to all observations as one.
    pub power_on_offsets: Vec<PowerOnOffset>,
    /// σ̂_b, the spread between power-ons, channel unit, when separated.
    pub between_power_on_sd: Option<f64>,
    /// From sweeps, when the chosen model holds a thermal lag: that model, which compensation
    /// uses; [`ChannelCalibration::bias`] is then the best curve in T alone (what the
    /// autopilots' cubic can hold).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lagged: Option<LaggedBias>,
    /// From sweeps: how the model was chosen on held-out legs, with the spread its band
    /// carries.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub selection: Option<HeldOutSelection>,
}

/// The thermal calibration of a unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ThermalCalibration {
    /// Per channel.
    pub channels: BTreeMap<Channel, ChannelCalibration>,
    /// Power-ons in the data.
    pub power_ons: usize,
    /// Scale factor against temperature.
    pub scale_factor: ScaleFactorCalibration,
    /// The true static signal taken off each channel's observations before the fit (a level
    /// unit's az reads −g), channel unit; channels not listed had none taken off.
    #[serde(default)]
    pub removed_signal: BTreeMap<Channel, f64>,
    /// The observations fitted, per channel (after the removed signal), for plots and refits.
    #[serde(default)]
    pub observations: BTreeMap<Channel, Vec<PowerOnRecord>>,
    /// The sensors it was fitted to, as the autopilot names them (from a ULog sweep).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub devices: Option<SensorDevices>,
    /// From sweeps alone: the legs found, numbered as the blocks name them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub legs: Vec<SweepLeg>,
    /// From sweeps alone: the block means fitted (before any offset), for checks and plots.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sweep_blocks: Vec<SweepBlock>,
}

/// The autopilot's identity of the sensors a calibration was fitted to: the topic instance
/// and the PX4 `device_id`s of a ULog's raw `sensor_gyro` and `sensor_accel`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct SensorDevices {
    /// The topics' instance (`multi_id`): 0 for the first IMU.
    pub instance: u8,
    /// The gyro's device id.
    pub gyro_device_id: Option<u32>,
    /// The accelerometer's device id.
    pub accel_device_id: Option<u32>,
}

/// The chosen model when it holds a lag term: the curve in the shifted temperature.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LaggedBias {
    /// The lag.
    pub lag: ThermalLag,
    /// The curve, its offsets and spread, with T + τ·dT/dt for T.
    pub fit: Box<ChannelCalibration>,
}

/// What a compensation did.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CompensationSummary {
    /// Samples compensated.
    pub samples: usize,
    /// Samples whose temperature lay outside a curve's fitted range (the curve's end value is
    /// used there, as PX4 clamps to TMIN/TMAX).
    pub clamped_samples: usize,
    /// Coldest and warmest sample temperature, °C.
    pub temperature_range_c: [f64; 2],
}

/// Why a record cannot be compensated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CompensationError {
    /// The record has no temperature column.
    #[error("the IMU record has no temp_c column, so its bias cannot be compensated")]
    NoTemperature,
    /// A sample's temperature is not finite.
    #[error("sample {index} has a non-finite temperature")]
    NonFiniteTemperature {
        /// Position of the sample.
        index: usize,
    },
}

/// Observations with a known static signal taken off each listed channel (a level unit's az
/// reads −g on top of its bias).
pub fn without_signal(
    mut observations: BTreeMap<Channel, Vec<PowerOnRecord>>,
    signal: &BTreeMap<Channel, f64>,
) -> BTreeMap<Channel, Vec<PowerOnRecord>> {
    for (channel, records) in &mut observations {
        let u = signal.get(channel).copied().unwrap_or(0.0);
        records.iter_mut().for_each(|r| r.value -= u);
    }
    observations
}

/// Fits the calibration of every channel from per-channel observations labelled by power-on.
/// With two or more power-ons, one of them at two or more temperatures, the offsets are
/// separated ([`fit_bias_curve_with_power_ons`]); otherwise one curve is fitted to all the
/// observations ([`fit_bias_curve`]), whose residual then holds any power-on scatter.
///
/// # Errors
/// The first channel's [`ThermalError`].
pub fn calibrate(
    observations: &BTreeMap<Channel, Vec<PowerOnRecord>>,
    settings: FitSettings,
) -> Result<ThermalCalibration, ThermalError> {
    let mut channels = BTreeMap::new();
    let mut power_ons = 0;
    for (&channel, records) in observations {
        let labels: std::collections::BTreeSet<u32> = records.iter().map(|r| r.power_on).collect();
        power_ons = power_ons.max(labels.len());
        channels.insert(channel, calibrate_channel(channel, records, settings)?);
    }
    Ok(ThermalCalibration {
        channels,
        power_ons,
        scale_factor: ScaleFactorCalibration::static_level_unit(),
        removed_signal: BTreeMap::new(),
        observations: observations.clone(),
        devices: None,
        legs: Vec::new(),
        sweep_blocks: Vec::new(),
    })
}

pub(super) fn calibrate_channel(
    channel: Channel,
    records: &[PowerOnRecord],
    settings: FitSettings,
) -> Result<ChannelCalibration, ThermalError> {
    match fit_bias_curve_with_power_ons(channel, records, settings) {
        Ok(fit) => Ok(with_offsets(fit)),
        Err(ThermalError::TooFewPowerOns { .. } | ThermalError::OffsetsUnidentifiable { .. }) => {
            let points: Vec<TemperaturePoint> = records
                .iter()
                .map(|r| TemperaturePoint {
                    temperature_c: r.temperature_c,
                    value: r.value,
                })
                .collect();
            Ok(ChannelCalibration {
                bias: fit_bias_curve(channel, &points, settings)?,
                power_on_offsets: Vec::new(),
                between_power_on_sd: None,
                lagged: None,
                selection: None,
            })
        }
        Err(e) => Err(e),
    }
}

/// The power-on fit's curve as an estimate of the repeatable curve (module docs, "The band").
fn with_offsets(fit: PowerOnFit) -> ChannelCalibration {
    let power_ons = fit.offsets.len() as f64;
    let mut bias = fit.curve;
    let sd = fit.between_power_on_sd;
    bias.coefficient_covariance[0][0] += sd * sd / power_ons;
    let t = StudentsT::new(0.0, 1.0, power_ons - 1.0)
        .expect("two or more power-ons")
        .inverse_cdf(0.5 + super::BAND_CONFIDENCE / 2.0);
    bias.scheffe_factor = bias.scheffe_factor.max(t);
    ChannelCalibration {
        bias,
        power_on_offsets: fit.offsets,
        between_power_on_sd: Some(sd),
        lagged: None,
        selection: None,
    }
}

impl ThermalCalibration {
    /// The repeatable bias of `channel` at `temperature_c`, clamped to the curve's fitted
    /// range; `None` for a channel not calibrated.
    pub fn bias_at(&self, channel: Channel, temperature_c: f64) -> Option<f64> {
        let curve = &self.channels.get(&channel)?.bias;
        let [low, high] = curve.temperature_range_c;
        Some(curve.value_at(temperature_c.clamp(low, high)))
    }

    /// True when some channel's model holds a thermal lag.
    pub fn has_lag(&self) -> bool {
        self.channels.values().any(|c| c.lagged.is_some())
    }

    /// Per channel with a lag, the lagged temperature of every sample of `series`
    /// ([`super::legs::lagged_temperatures`]); empty without a lag or a temperature column.
    pub fn effective_temperatures(&self, series: &ImuSeries) -> BTreeMap<Channel, Vec<f64>> {
        let Some(temperatures) = series.temperature_c.as_deref() else {
            return BTreeMap::new();
        };
        let time: Vec<f64> = series.time.iter().map(|t| t.as_seconds()).collect();
        (self.channels.iter())
            .filter(|(_, c)| c.lagged.is_some())
            .map(|(&ch, c)| {
                let lagged = super::legs::lagged_temperatures(&time, temperatures, c.lag_s());
                (ch, lagged)
            })
            .collect()
    }

    /// True when `temperature_c` lies outside some channel's fitted range.
    pub fn outside_range(&self, temperature_c: f64) -> bool {
        self.channels.values().any(|c| {
            let [low, high] = c.bias.temperature_range_c;
            temperature_c < low || temperature_c > high
        })
    }

    /// Subtracts the repeatable bias at each sample's own temperature from every calibrated
    /// channel (for increments, the bias times the sample's interval, the first sample taking
    /// the second's interval).
    ///
    /// # Errors
    /// A record without temperatures or with a non-finite one; the series is then unchanged.
    pub fn compensate(
        &self,
        series: &mut ImuSeries,
    ) -> Result<CompensationSummary, CompensationError> {
        let channels: Vec<Channel> = self.channels.keys().copied().collect();
        let effective = self.effective_temperatures(series);
        series
            .remove_thermal_error_at(&channels, |c, k, t| {
                let Some(calibration) = self.channels.get(&c) else {
                    return (0.0, 0.0);
                };
                let t = effective.get(&c).map_or(t, |e| e[k]);
                (calibration.bias_at_effective(t).0, 0.0)
            })
            .map_err(|e| match e {
                TemperatureColumnError::Missing => CompensationError::NoTemperature,
                TemperatureColumnError::NonFinite { index } => {
                    CompensationError::NonFiniteTemperature { index }
                }
            })?;
        let temperatures = series.temperature_c.as_deref().unwrap_or_default();
        let clamped = temperatures
            .iter()
            .filter(|&&t| self.outside_range(t))
            .count();
        let range = temperatures
            .iter()
            .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], &t| {
                [lo.min(t), hi.max(t)]
            });
        Ok(CompensationSummary {
            samples: temperatures.len(),
            clamped_samples: clamped,
            temperature_range_c: range,
        })
    }
}
