//! A channel's calibration in a few numbers (for tables and summaries), and its observations
//! lined up with the repeatable curve (for figures).

use super::{ChannelCalibration, PowerOnRecord, ThermalCalibration, ThermalCurve};
use crate::imu::Channel;
use serde::Serialize;
use std::collections::BTreeSet;

/// Evenly spaced temperatures, ends included, at which the band's largest half-width over the
/// fitted range is sought.
pub const BAND_SEARCH_POINTS: usize = 201;

impl ThermalCurve {
    /// `points` evenly spaced temperatures across the fitted range, ends included, °C (one
    /// point, the range's start, when `points` < 2 or the range is a single temperature).
    pub fn range_grid_c(&self, points: usize) -> Vec<f64> {
        let [low, high] = self.temperature_range_c;
        if points < 2 || high <= low {
            return vec![low];
        }
        let step = (high - low) / (points - 1) as f64;
        (0..points).map(|k| low + k as f64 * step).collect()
    }

    /// The largest half-width of the simultaneous band over the fitted range, channel unit,
    /// sought at [`BAND_SEARCH_POINTS`] temperatures.
    pub fn max_band_half_width(&self) -> f64 {
        self.range_grid_c(BAND_SEARCH_POINTS)
            .into_iter()
            .map(|t| self.band_at(t).1)
            .fold(0.0, f64::max)
    }
}

/// A channel's calibration in a few numbers; rates in the channel's unit (rad/s or m/s²).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CalibrationSummary {
    /// Polynomial order K.
    pub order: usize,
    /// T_ref, °C.
    pub reference_temperature_c: f64,
    /// Coldest and warmest temperature fitted, °C.
    pub temperature_range_c: [f64; 2],
    /// b̂ at the coldest temperature fitted.
    pub bias_at_range_start: f64,
    /// b̂ at T_ref.
    pub bias_at_reference: f64,
    /// b̂ at the warmest temperature fitted.
    pub bias_at_range_end: f64,
    /// The largest half-width of the simultaneous 95 % band over the fitted range.
    pub max_band_half_width: f64,
    /// s_e, the residual standard deviation.
    pub residual_sd: f64,
    /// Power-ons among the channel's observations.
    pub power_ons: usize,
    /// σ̂_b, the spread between power-ons, when separated.
    pub between_power_on_sd: Option<f64>,
}

impl CalibrationSummary {
    /// The rate-valued numbers in table order: b̂ at the range's start, at T_ref and at the
    /// range's end, the largest band half-width and the residual sd (channel unit).
    pub fn rate_values(&self) -> [f64; 5] {
        [
            self.bias_at_range_start,
            self.bias_at_reference,
            self.bias_at_range_end,
            self.max_band_half_width,
            self.residual_sd,
        ]
    }
}

impl ChannelCalibration {
    /// The channel's numbers, with `power_ons` the power-ons among its observations.
    pub fn summary(&self, power_ons: usize) -> CalibrationSummary {
        let curve = &self.bias;
        let [low, high] = curve.temperature_range_c;
        CalibrationSummary {
            order: curve.order,
            reference_temperature_c: curve.reference_temperature_c,
            temperature_range_c: curve.temperature_range_c,
            bias_at_range_start: curve.value_at(low),
            bias_at_reference: curve.value_at(curve.reference_temperature_c),
            bias_at_range_end: curve.value_at(high),
            max_band_half_width: curve.max_band_half_width(),
            residual_sd: curve.residual_sd,
            power_ons,
            between_power_on_sd: self.between_power_on_sd,
        }
    }

    /// The offset of power-on `label` from the repeatable curve, channel unit (zero when the
    /// offsets were not separated or the label is unknown).
    pub fn offset_of(&self, label: u32) -> f64 {
        self.power_on_offsets
            .iter()
            .find(|o| o.power_on == label)
            .map_or(0.0, |o| o.offset)
    }
}

impl ThermalCalibration {
    /// The numbers of `channel`; `None` for a channel not calibrated.
    pub fn summary(&self, channel: Channel) -> Option<CalibrationSummary> {
        let calibration = self.channels.get(&channel)?;
        Some(calibration.summary(self.power_ons_of(channel)))
    }

    /// Distinct power-ons among the observations of `channel` (the calibration's power-ons
    /// when it kept no observations).
    pub fn power_ons_of(&self, channel: Channel) -> usize {
        match self.observations.get(&channel) {
            Some(records) if !records.is_empty() => records
                .iter()
                .map(|r| r.power_on)
                .collect::<BTreeSet<_>>()
                .len(),
            _ => self.power_ons,
        }
    }

    /// The observations of `channel` with each power-on's offset taken off, so that they
    /// scatter about the repeatable curve (channel unit; empty for a channel not calibrated).
    pub fn aligned_observations(&self, channel: Channel) -> Vec<PowerOnRecord> {
        let (Some(calibration), Some(records)) =
            (self.channels.get(&channel), self.observations.get(&channel))
        else {
            return Vec::new();
        };
        records
            .iter()
            .map(|r| PowerOnRecord {
                value: r.value - calibration.offset_of(r.power_on),
                ..*r
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::super::{FitSettings, calibrate};
    use super::*;
    use std::collections::BTreeMap;

    /// Three power-ons at six temperatures of a line 1e-3 + 2e-5 (T − 25) rad/s, each shifted
    /// by its own offset, with a small deterministic scatter.
    fn calibration() -> ThermalCalibration {
        let offsets = [1e-4, -2e-4, 1e-4];
        let records: Vec<PowerOnRecord> = (0..3u32)
            .flat_map(|j| {
                (0..6).map(move |k| {
                    let t = -40.0 + 20.0 * k as f64;
                    let scatter = 1e-6 * ((j * 6 + k) as f64).sin();
                    PowerOnRecord {
                        power_on: j + 1,
                        temperature_c: t,
                        value: 1e-3 + 2e-5 * (t - 25.0) + offsets[j as usize] + scatter,
                    }
                })
            })
            .collect();
        calibrate(
            &BTreeMap::from([(Channel::Gx, records)]),
            FitSettings::default(),
        )
        .expect("identifiable")
    }

    #[test]
    fn the_summary_reads_the_curve_at_its_range_ends_and_reference() {
        let c = calibration();
        let s = c.summary(Channel::Gx).expect("gx calibrated");
        let curve = &c.channels[&Channel::Gx].bias;
        assert_eq!(s.temperature_range_c, [-40.0, 60.0]);
        assert!((s.bias_at_range_start - curve.value_at(-40.0)).abs() < 1e-15);
        assert!((s.bias_at_range_end - curve.value_at(60.0)).abs() < 1e-15);
        assert!((s.bias_at_range_start - (1e-3 + 2e-5 * -65.0)).abs() < 1e-5);
        assert_eq!(s.power_ons, 3);
        let widest = [-40.0, 0.0, 60.0].map(|t| curve.band_at(t).1);
        assert!(widest.iter().all(|&w| w <= s.max_band_half_width + 1e-18));
        assert!(c.summary(Channel::Az).is_none());
    }

    #[test]
    fn aligned_observations_lie_on_the_curve_once_their_offsets_are_taken_off() {
        let c = calibration();
        let curve = &c.channels[&Channel::Gx].bias;
        let aligned = c.aligned_observations(Channel::Gx);
        assert_eq!(aligned.len(), 18);
        for r in &aligned {
            assert!(
                (r.value - curve.value_at(r.temperature_c)).abs() < 5e-6,
                "{r:?}"
            );
        }
        let raw = &c.observations[&Channel::Gx];
        assert!(
            raw.iter()
                .any(|r| (r.value - curve.value_at(r.temperature_c)).abs() > 5e-5)
        );
    }

    #[test]
    fn the_range_grid_includes_both_ends() {
        let c = calibration();
        let grid = c.channels[&Channel::Gx].bias.range_grid_c(5);
        assert_eq!(grid, [-40.0, -15.0, 10.0, 35.0, 60.0]);
    }
}
