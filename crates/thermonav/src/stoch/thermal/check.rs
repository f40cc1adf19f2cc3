//! A calibration against a record it may not have seen, and a record with the calibration
//! taken off.
//!
//! # Check
//! The record is cut into blocks of `block_s` from its first sample (a last, shorter block is
//! dropped). A block's `observed` value is the raw mean of each channel (SI); its `predicted`
//! value is the full expected mean: the bias at the block's mean effective temperature (the
//! lagged temperature of the channel's model, [`super::legs::lagged_temperatures`];
//! [`ChannelCalibration::predict`]), plus the signal a still unit reads (gravity along the
//! record's mean specific force, for the accelerometers; [`gravity_signal`]), plus the offset
//! of the record's power-on: the bank's fitted offset of power-on K when it is named, that
//! power-on when the calibration has one, else the mean offset (a new power-on, whose band
//! carries the spread between power-ons). Per channel: `rms_before`, the RMS of observed minus
//! the bank's value at its reference temperature (plus the signal and the offset);
//! `rms_before_offset_removed`, of observed about its own mean (the record's shape with no
//! thermal model: what compensation must beat); `rms_after`, of observed minus predicted; `rms_after_offset_removed`, of that residual
//! about its own mean; `coverage`, the fraction of blocks whose residual lies within the band,
//! and `coverage_offset_removed`, of the residual about its mean within the band without its
//! offset part. The band adds the block mean's own noise, from the spread of its samples
//! (the bank's spread was measured on its own, usually longer, blocks).

use super::legs::{RATE_WINDOW_S, lagged_temperatures, temperature_rates};
use super::sweep_model::{PowerOnChoice, block_ranges};
use super::{ChannelCalibration, ThermalCalibration};
use crate::geo::gravity::normal_gravity_m_s2;
use crate::imu::{Channel, ImuSeries, SampleKind, Sensor};
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};

/// Default block of `bank check`, s.
pub const DEFAULT_CHECK_BLOCK_S: f64 = 30.0;

/// Why a record cannot be checked or compensated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CheckError {
    /// No temperature column.
    #[error("the record has no temp_c column")]
    NoTemperature,
    /// A non-finite temperature.
    #[error("sample {index} has a non-finite temperature")]
    NonFiniteTemperature {
        /// Position of the sample.
        index: usize,
    },
    /// Increments, not rates.
    #[error("the record holds increments; a thermal check reads rates (rad/s, m/s²)")]
    Increments,
    /// Too few whole blocks.
    #[error("{blocks} whole block(s) of {block_s} s in the record: at least 1 is needed")]
    NoBlock {
        /// Blocks found.
        blocks: usize,
        /// The block, s.
        block_s: f64,
    },
    /// The power-on named is not in the calibration.
    #[error("power-on {power_on} is not in the calibration (its power-ons: {known})")]
    UnknownPowerOn {
        /// The label asked for.
        power_on: u32,
        /// The labels it has.
        known: String,
    },
    /// No channel in common.
    #[error("the record and the calibration have no channel in common")]
    NoChannel,
}

/// One block of a check.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BlockCheck {
    /// Middle of the block, s.
    pub t_s: f64,
    /// Mean temperature, °C.
    pub temperature_c: f64,
    /// Mean temperature rate, °C/min.
    pub temperature_rate_c_per_min: f64,
    /// Raw mean, channel unit.
    pub observed: f64,
    /// Full expected mean, channel unit.
    pub predicted: f64,
    /// 95 % half-width, channel unit.
    pub band_half_width: f64,
    /// 95 % half-width without the offset's part, channel unit.
    pub band_half_width_offset_removed: f64,
    /// The (shifted) temperature lay outside the fitted range: the prediction is the range's
    /// end value and the band widened.
    pub clamped: bool,
}

/// One channel's check (module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelCheck {
    /// SI unit of every value.
    pub unit: &'static str,
    /// RMS of observed minus the bank's value at its reference temperature.
    pub rms_before: f64,
    /// RMS of observed about its own mean: the record's shape uncompensated, which
    /// `rms_after_offset_removed` must beat for the calibration to help on this record.
    pub rms_before_offset_removed: f64,
    /// RMS of observed minus predicted.
    pub rms_after: f64,
    /// RMS of that residual about its own mean.
    pub rms_after_offset_removed: f64,
    /// Fraction of blocks within the band.
    pub coverage: f64,
    /// Fraction of residuals about their mean within the band without its offset part.
    pub coverage_offset_removed: f64,
    /// The blocks.
    pub blocks: Vec<BlockCheck>,
}

impl ChannelCheck {
    /// True when the compensated shape is worse than the uncompensated one
    /// (`rms_after_offset_removed` > `rms_before_offset_removed`): on this record the
    /// calibration hurts. A channel left uncompensated (order 0) has the two equal but for
    /// rounding, which the relative margin of 1e-9 absorbs.
    pub fn makes_worse(&self) -> bool {
        self.rms_after_offset_removed > self.rms_before_offset_removed * (1.0 + 1e-9)
    }
}

/// The gravity a calibration took off (the norm of its removed signal), or the normal gravity
/// at 45° when it took none, m/s².
pub fn gravity_of(calibration: &ThermalCalibration) -> f64 {
    let g = calibration
        .removed_signal
        .iter()
        .filter(|(c, _)| c.sensor() == Sensor::Accelerometer)
        .map(|(_, v)| v * v)
        .sum::<f64>()
        .sqrt();
    if g > 0.0 {
        g
    } else {
        normal_gravity_m_s2(45f64.to_radians(), 0.0)
    }
}

/// Per accelerometer channel of `series`, g · f̄_c / |f̄|: the gravity a still unit reads along
/// its mean specific force (any orientation); empty without the three accelerometers.
pub fn gravity_signal(series: &[&ImuSeries], gravity_m_s2: f64) -> BTreeMap<Channel, f64> {
    let samples: usize = series.iter().map(|s| s.len()).sum();
    let mut mean = BTreeMap::new();
    for c in Channel::ALL
        .into_iter()
        .filter(|c| c.sensor() == Sensor::Accelerometer)
    {
        if samples == 0 || series.iter().any(|s| s.channel(c).len() != s.len()) {
            return BTreeMap::new();
        }
        let sum: f64 = series
            .iter()
            .map(|s| s.channel(c).iter().sum::<f64>())
            .sum();
        mean.insert(c, sum / samples as f64);
    }
    let norm = mean.values().map(|v| v * v).sum::<f64>().sqrt();
    if norm.is_nan() || norm <= 0.0 {
        return BTreeMap::new();
    }
    mean.into_iter()
        .map(|(c, f)| (c, gravity_m_s2 * f / norm))
        .collect()
}

/// The power-on labels of a calibration's observations.
fn power_on_labels(calibration: &ThermalCalibration) -> BTreeSet<u32> {
    calibration
        .observations
        .values()
        .flatten()
        .map(|r| r.power_on)
        .collect()
}

/// Whose offset a record carries (module docs).
///
/// # Errors
/// [`CheckError::UnknownPowerOn`] for a label the calibration does not have.
pub fn power_on_of(
    calibration: &ThermalCalibration,
    named: Option<u32>,
) -> Result<PowerOnChoice, CheckError> {
    let labels = power_on_labels(calibration);
    match named {
        Some(k) if labels.contains(&k) || (labels.is_empty() && k == 1) => {
            Ok(PowerOnChoice::Known(k))
        }
        Some(k) => Err(CheckError::UnknownPowerOn {
            power_on: k,
            known: labels
                .iter()
                .map(u32::to_string)
                .collect::<Vec<_>>()
                .join(", "),
        }),
        None if labels.len() <= 1 => Ok(PowerOnChoice::Known(labels.first().copied().unwrap_or(1))),
        None => Ok(PowerOnChoice::New),
    }
}

/// Temperatures of a rate record, checked.
fn temperatures_of(series: &ImuSeries) -> Result<&[f64], CheckError> {
    if series.kind == Some(SampleKind::Increments) {
        return Err(CheckError::Increments);
    }
    let t = series
        .temperature_c
        .as_deref()
        .ok_or(CheckError::NoTemperature)?;
    match t.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(CheckError::NonFiniteTemperature { index }),
        None => Ok(t),
    }
}

/// Checks `calibration` against `series` (module docs).
///
/// # Errors
/// [`CheckError`].
pub fn check_record(
    calibration: &ThermalCalibration,
    series: &ImuSeries,
    block_s: f64,
    power_on: Option<u32>,
) -> Result<BTreeMap<Channel, ChannelCheck>, CheckError> {
    let temperatures = temperatures_of(series)?;
    let choice = power_on_of(calibration, power_on)?;
    let time: Vec<f64> = series.time.iter().map(|t| t.as_seconds()).collect();
    let rates = temperature_rates(&time, temperatures, RATE_WINDOW_S);
    let ranges = block_ranges(&time, block_s);
    if ranges.is_empty() {
        return Err(CheckError::NoBlock { blocks: 0, block_s });
    }
    let signal = gravity_signal(&[series], gravity_of(calibration));
    let present = series.present_channels();
    let mean = |xs: &[f64]| xs.iter().sum::<f64>() / xs.len() as f64;
    let mut out = BTreeMap::new();
    for (&channel, cal) in calibration
        .channels
        .iter()
        .filter(|(c, _)| present.contains(c))
    {
        let s = signal.get(&channel).copied().unwrap_or(0.0);
        let effective = lagged_temperatures(&time, temperatures, cal.lag_s());
        let blocks: Vec<BlockCheck> = ranges
            .iter()
            .map(|&(a, b)| {
                let (t, rate) = (mean(&temperatures[a..b]), mean(&rates[a..b]));
                let samples = &series.channel(channel)[a..b];
                let observed = mean(samples);
                let t_eff = mean(&effective[a..b]);
                let p = cal.predict(t_eff, choice, mean_noise_variance(samples, observed));
                BlockCheck {
                    t_s: (time[a] + time[b - 1]) / 2.0,
                    temperature_c: t,
                    temperature_rate_c_per_min: rate * 60.0,
                    observed,
                    predicted: p.value + s,
                    band_half_width: p.band_half_width,
                    band_half_width_offset_removed: p.band_half_width_offset_removed,
                    clamped: p.clamped,
                }
            })
            .collect();
        let reference = reference_value(cal, choice) + s;
        out.insert(channel, channel_check(channel, blocks, reference));
    }
    if out.is_empty() {
        return Err(CheckError::NoChannel);
    }
    Ok(out)
}

/// The variance of a block mean from its samples' spread: s² / n (0 for one sample).
fn mean_noise_variance(samples: &[f64], mean: f64) -> f64 {
    let n = samples.len();
    if n < 2 {
        return 0.0;
    }
    let ss: f64 = samples.iter().map(|x| (x - mean).powi(2)).sum();
    ss / (n - 1) as f64 / n as f64
}

/// The bank's value at its reference temperature with the power-on's offset.
fn reference_value(cal: &ChannelCalibration, choice: PowerOnChoice) -> f64 {
    let (model, _) = cal.compensation_model();
    let offset = match choice {
        PowerOnChoice::Known(k) => model.offset_of(k),
        PowerOnChoice::New => 0.0,
    };
    model.bias.value_at(model.bias.reference_temperature_c) + offset
}

fn rms(xs: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = xs.fold((0.0, 0usize), |(s, n), x| (s + x * x, n + 1));
    (sum / n.max(1) as f64).sqrt()
}

fn channel_check(channel: Channel, blocks: Vec<BlockCheck>, reference: f64) -> ChannelCheck {
    let residuals: Vec<f64> = blocks.iter().map(|b| b.observed - b.predicted).collect();
    let n = residuals.len() as f64;
    let mean = residuals.iter().sum::<f64>() / n;
    let observed_mean = blocks.iter().map(|b| b.observed).sum::<f64>() / n;
    let within = |pairs: &mut dyn Iterator<Item = (f64, f64)>| {
        pairs.filter(|(r, w)| r.abs() <= *w).count() as f64 / n
    };
    ChannelCheck {
        unit: channel.si_unit(SampleKind::Rates),
        rms_before: rms(blocks.iter().map(|b| b.observed - reference)),
        rms_before_offset_removed: rms(blocks.iter().map(|b| b.observed - observed_mean)),
        rms_after: rms(residuals.iter().copied()),
        rms_after_offset_removed: rms(residuals.iter().map(|r| r - mean)),
        coverage: within(
            &mut residuals
                .iter()
                .zip(&blocks)
                .map(|(r, b)| (*r, b.band_half_width)),
        ),
        coverage_offset_removed: within(
            &mut residuals
                .iter()
                .zip(&blocks)
                .map(|(r, b)| (r - mean, b.band_half_width_offset_removed)),
        ),
        blocks,
    }
}

/// What [`compensate_record`] took off one channel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelRemoval {
    /// SI unit of the values.
    pub unit: &'static str,
    /// Polynomial order of the model used.
    pub order: usize,
    /// Its thermal lag, s (`None`: the curve in T alone).
    pub thermal_lag_s: Option<f64>,
    /// The power-on offset taken off (beyond the curve's constant).
    pub power_on_offset: f64,
    /// Smallest, mean and largest value taken off a sample.
    pub removed_min: f64,
    /// Mean value taken off.
    pub removed_mean: f64,
    /// Largest value taken off.
    pub removed_max: f64,
}

/// What a compensation did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecordCompensation {
    /// Per channel.
    pub channels: BTreeMap<Channel, ChannelRemoval>,
    /// Samples whose (shifted) temperature lay outside some channel's fitted range.
    pub clamped_samples: usize,
    /// The power-on whose offset was taken off; `None` for the mean offset (a new power-on).
    pub power_on: Option<u32>,
}

/// Takes the bias (at each sample's lagged temperature, [`ChannelCalibration::bias_at_effective`])
/// and the power-on's offset off every sample of every calibrated channel of `series` (rates),
/// keeping gravity (what [`check_record`]'s prediction adds as the signal is not taken off); a
/// gyro curve's constant holds the Earth rate's projection of the sweeps it was fitted to, and
/// goes with it.
///
/// # Errors
/// [`CheckError`] for a record without valid temperatures, of increments, or an unknown
/// power-on.
pub fn compensate_record(
    calibration: &ThermalCalibration,
    series: &mut ImuSeries,
    power_on: Option<u32>,
) -> Result<RecordCompensation, CheckError> {
    let temperatures = temperatures_of(series)?.to_vec();
    let choice = power_on_of(calibration, power_on)?;
    let time: Vec<f64> = series.time.iter().map(|t| t.as_seconds()).collect();
    let present = series.present_channels();
    let mut channels = BTreeMap::new();
    let mut clamped = vec![false; temperatures.len()];
    for (&channel, cal) in calibration
        .channels
        .iter()
        .filter(|(c, _)| present.contains(c))
    {
        let (model, tau) = cal.compensation_model();
        let effective = lagged_temperatures(&time, &temperatures, tau);
        let offset = match choice {
            PowerOnChoice::Known(k) => model.offset_of(k),
            PowerOnChoice::New => 0.0,
        };
        let column = &mut series.channels[channel.index()];
        let (mut lo, mut hi, mut sum) = (f64::INFINITY, f64::NEG_INFINITY, 0.0);
        for (k, value) in column.iter_mut().enumerate() {
            let (bias, out) = cal.bias_at_effective(effective[k]);
            clamped[k] |= out;
            let removed = bias + offset;
            *value -= removed;
            (lo, hi, sum) = (lo.min(removed), hi.max(removed), sum + removed);
        }
        channels.insert(
            channel,
            ChannelRemoval {
                unit: channel.si_unit(SampleKind::Rates),
                order: model.bias.order,
                thermal_lag_s: cal.lagged.as_ref().map(|_| tau),
                power_on_offset: offset,
                removed_min: lo,
                removed_mean: sum / column.len().max(1) as f64,
                removed_max: hi,
            },
        );
    }
    if channels.is_empty() {
        return Err(CheckError::NoChannel);
    }
    Ok(RecordCompensation {
        channels,
        clamped_samples: clamped.iter().filter(|&&c| c).count(),
        power_on: match choice {
            PowerOnChoice::Known(k) => Some(k),
            PowerOnChoice::New => None,
        },
    })
}
