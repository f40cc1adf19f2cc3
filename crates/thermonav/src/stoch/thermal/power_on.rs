//! The fixed-effects fit: one free offset per power-on plus a shared thermal shape.

use super::solve::{Scaling, distinct, least_squares};
use super::{
    CurveParts, DataShape, FitSettings, ThermalCurve, ThermalError, check_points, curve_from,
    fit_orders, reference_temperature,
};
use crate::imu::Channel;
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One observation of a channel during one power-on of the unit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PowerOnRecord {
    /// Which power-on (any label; records with the same label share one offset).
    pub power_on: u32,
    /// Sensor temperature, °C.
    pub temperature_c: f64,
    /// The channel's value in its rate unit (rad/s or m/s²).
    pub value: f64,
}

/// One power-on's offset from the repeatable curve.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PowerOnOffset {
    /// The power-on's label.
    pub power_on: u32,
    /// α̂_j − ᾱ, channel unit: the power-on's bias is the repeatable curve plus this.
    pub offset: f64,
    /// Standard deviation of the estimate α̂_j − ᾱ, channel unit.
    pub offset_sd: f64,
    /// Records of this power-on.
    pub records: usize,
    /// Distinct temperatures among them.
    pub distinct_temperatures: usize,
}

/// A bias curve with per-power-on offsets kept apart.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PowerOnFit {
    /// The repeatable curve, with the mean offset ᾱ as its constant. Its covariance and band
    /// are those of this curve; as an estimate of the unit's long-run mean over power-ons its
    /// constant carries a further variance σ_b² / J.
    pub curve: ThermalCurve,
    /// Each power-on's offset, in increasing label order (they sum to zero).
    pub offsets: Vec<PowerOnOffset>,
    /// Sample standard deviation of the estimated offsets (J − 1 degrees of freedom), channel
    /// unit.
    pub offset_spread_sd: f64,
    /// σ̂_b, the standard deviation between power-ons with the offsets' estimation noise
    /// removed (method of moments, zero when the noise explains all the spread), channel unit.
    pub between_power_on_sd: f64,
}

/// Fits the bias curve of `channel` with one free offset per power-on (module docs, "Power-on
/// offsets"). The order rule is that of [`super::fit_bias_curve`], with PRESS summed over the
/// records of power-ons that have two or more records (a power-on's only record always has
/// leverage 1) and orders limited to what the within-power-on temperatures identify.
///
/// # Errors
/// Fewer than 3 records, a non-finite temperature, value or reference, fewer than 2 power-ons,
/// every power-on at a single temperature ([`ThermalError::OffsetsUnidentifiable`]), a fixed
/// order above 3 or beyond the data, or no valid order.
pub fn fit_bias_curve_with_power_ons(
    channel: Channel,
    records: &[PowerOnRecord],
    settings: FitSettings,
) -> Result<PowerOnFit, ThermalError> {
    check_points(records.iter().map(|r| (r.temperature_c, r.value)), 3)?;
    let groups = group(records);
    if groups.len() < 2 {
        return Err(ThermalError::TooFewPowerOns {
            power_ons: groups.len(),
        });
    }
    if groups.values().all(|g| g.distinct_temperatures < 2) {
        return Err(ThermalError::OffsetsUnidentifiable {
            power_ons: groups.len(),
        });
    }
    let temperatures = || records.iter().map(|r| r.temperature_c);
    let reference_c = reference_temperature(settings, temperatures())?;
    let scaling = Scaling::of(temperatures());
    let column: BTreeMap<u32, usize> = groups.keys().enumerate().map(|(j, &id)| (id, j)).collect();
    let power_ons = groups.len();
    let y = DVector::from_iterator(records.len(), records.iter().map(|r| r.value));
    let design = |order: usize| {
        DMatrix::from_fn(records.len(), power_ons + order, |i, c| {
            let r = &records[i];
            match c.checked_sub(power_ons) {
                None => f64::from(u8::from(column[&r.power_on] == c)),
                Some(k) => scaling.z(r.temperature_c).powi(k as i32 + 1),
            }
        })
    };
    let in_press = |i: usize| groups[&records[i].power_on].records >= 2;
    let data = DataShape::of(records.len(), temperatures());
    // The shape is learnt from changes within power-ons: Σ_j (d_j − 1) of them at most.
    let within: usize = groups.values().map(|g| g.distinct_temperatures - 1).sum();
    let identifiable = within.min(data.distinct_temperatures - 1);
    let (fits, (selection, order)) = fit_orders(
        settings.order,
        data,
        identifiable,
        |k| power_ons + k,
        |k| {
            least_squares(&design(k), &y).map(|ls| {
                let press = ls.press(in_press);
                (ls, press)
            })
        },
    )?;
    let fit = &fits[order];
    let dof = records.len() - power_ons - order;
    let variance = fit.rss() / dof as f64;
    let covariance = &fit.inverse_gram * variance;
    // (ᾱ, a_1..a_K) = L θ, L = [1/J … 1/J 0; 0 I_K].
    let l = DMatrix::from_fn(order + 1, power_ons + order, |row, c| match (row, c) {
        (0, c) if c < power_ons => 1.0 / power_ons as f64,
        (row, c) if row > 0 && c == power_ons + row - 1 => 1.0,
        _ => 0.0,
    });
    let offsets = offsets(&groups, &fit.coefficients, &covariance);
    let curve = curve_from(
        CurveParts {
            channel,
            reference_c,
            scaling,
            coefficients: &l * &fit.coefficients,
            covariance: &l * &covariance * l.transpose(),
            residual_sd: variance.sqrt(),
            residual_degrees_of_freedom: dof,
            data,
        },
        selection,
    );
    let (offset_spread_sd, between_power_on_sd) = spread(&offsets);
    Ok(PowerOnFit {
        curve,
        offsets,
        offset_spread_sd,
        between_power_on_sd,
    })
}

/// Records and distinct temperatures of one power-on.
struct Group {
    records: usize,
    distinct_temperatures: usize,
}

/// The power-ons by label.
fn group(records: &[PowerOnRecord]) -> BTreeMap<u32, Group> {
    let mut temperatures: BTreeMap<u32, Vec<f64>> = BTreeMap::new();
    for r in records {
        temperatures
            .entry(r.power_on)
            .or_default()
            .push(r.temperature_c);
    }
    temperatures
        .into_iter()
        .map(|(id, ts)| {
            let group = Group {
                records: ts.len(),
                distinct_temperatures: distinct(ts.into_iter()),
            };
            (id, group)
        })
        .collect()
}

/// α̂_j − ᾱ with Var = cᵀ Cov(θ̂) c, c = e_j − 1/J on the offset columns.
fn offsets(
    groups: &BTreeMap<u32, Group>,
    theta: &DVector<f64>,
    covariance: &DMatrix<f64>,
) -> Vec<PowerOnOffset> {
    let power_ons = groups.len();
    let mean = theta.rows(0, power_ons).mean();
    groups
        .iter()
        .enumerate()
        .map(|(j, (&power_on, g))| {
            let c = DVector::from_fn(theta.len(), |i, _| match i {
                i if i >= power_ons => 0.0,
                i if i == j => 1.0 - 1.0 / power_ons as f64,
                _ => -1.0 / power_ons as f64,
            });
            PowerOnOffset {
                power_on,
                offset: theta[j] - mean,
                offset_sd: (c.transpose() * covariance * &c)[(0, 0)].max(0.0).sqrt(),
                records: g.records,
                distinct_temperatures: g.distinct_temperatures,
            }
        })
        .collect()
}

/// (sample sd of the offsets, method-of-moments sd between power-ons).
fn spread(offsets: &[PowerOnOffset]) -> (f64, f64) {
    let dof = (offsets.len() - 1) as f64;
    let squares: f64 = offsets.iter().map(|o| o.offset * o.offset).sum();
    let noise: f64 = offsets.iter().map(|o| o.offset_sd * o.offset_sd).sum();
    (
        (squares / dof).sqrt(),
        ((squares - noise).max(0.0) / dof).sqrt(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(power_on: u32, temperature_c: f64, value: f64) -> PowerOnRecord {
        PowerOnRecord {
            power_on,
            temperature_c,
            value,
        }
    }

    #[test]
    fn one_temperature_per_power_on_is_unidentifiable() {
        let records = [
            record(1, 0.0, 1.0),
            record(2, 20.0, 2.0),
            record(3, 40.0, 2.5),
        ];
        let err = fit_bias_curve_with_power_ons(Channel::Gy, &records, FitSettings::default())
            .unwrap_err();
        assert_eq!(err, ThermalError::OffsetsUnidentifiable { power_ons: 3 });
        assert!(
            err.to_string()
                .contains("at least 2 power-ons at 2 or more temperatures")
        );
    }

    #[test]
    fn a_single_power_on_is_refused() {
        let records = [
            record(1, 0.0, 1.0),
            record(1, 20.0, 2.0),
            record(1, 40.0, 2.5),
        ];
        assert_eq!(
            fit_bias_curve_with_power_ons(Channel::Gy, &records, FitSettings::default()),
            Err(ThermalError::TooFewPowerOns { power_ons: 1 })
        );
    }

    #[test]
    fn exact_offsets_and_slope_are_recovered() {
        // bias = 0.01 (T − 20) + offset, offsets +0.3 and −0.3 (mean 0), tiny alternating noise.
        let mut records = Vec::new();
        for (id, offset) in [(7, 0.3), (9, -0.3)] {
            for (i, t) in [0.0, 20.0, 40.0, 60.0].into_iter().enumerate() {
                let noise = if (i + id as usize) % 2 == 0 {
                    1e-9
                } else {
                    -1e-9
                };
                records.push(record(id, t, 0.01 * (t - 20.0) + offset + noise));
            }
        }
        let settings = FitSettings {
            reference_temperature_c: Some(20.0),
            order: super::super::OrderChoice::Fixed(1),
        };
        let fit = fit_bias_curve_with_power_ons(Channel::Az, &records, settings).unwrap();
        assert!((fit.curve.coefficients[0]).abs() < 1e-8);
        assert!((fit.curve.coefficients[1] - 0.01).abs() < 1e-10);
        assert!((fit.offsets[0].offset - 0.3).abs() < 1e-8);
        assert_eq!(fit.offsets[1].power_on, 9);
        assert!((fit.offset_spread_sd - 0.3 * 2f64.sqrt()).abs() < 1e-7);
    }
}
