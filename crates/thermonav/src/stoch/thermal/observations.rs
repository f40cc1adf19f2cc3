//! What a thermal calibration is fitted to: the mean of each static record, or block means of
//! a temperature sweep, labelled by the power-on they belong to.

use super::{PowerOnRecord, ThermalError};
use crate::imu::{Channel, ImuSeries};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The means of a static record: one observation of every channel's bias at one temperature.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RecordMean {
    /// Mean sensor temperature (the temp_c column's, or the temperature given), °C.
    pub temperature_c: f64,
    /// Mean of each channel, in its rate unit (rad/s or m/s²).
    pub values: BTreeMap<Channel, f64>,
    /// Samples averaged.
    pub samples: usize,
}

/// Running sums for a [`RecordMean`] of a record read in pieces.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RecordSums {
    sums: [f64; 6],
    samples: usize,
}

impl RecordSums {
    /// Adds the samples of `piece`.
    pub fn add(&mut self, piece: &ImuSeries) {
        for channel in Channel::ALL {
            self.sums[channel.index()] += piece.channel(channel).iter().sum::<f64>();
        }
        self.samples += piece.len();
    }

    /// The means at `temperature_c`; `None` before any sample.
    pub fn mean(&self, temperature_c: f64) -> Option<RecordMean> {
        (self.samples > 0).then(|| RecordMean {
            temperature_c,
            values: Channel::ALL
                .iter()
                .map(|&c| (c, self.sums[c.index()] / self.samples as f64))
                .collect(),
            samples: self.samples,
        })
    }
}

/// The means of a whole record at `temperature_c`; `None` for an empty record.
pub fn record_mean(series: &ImuSeries, temperature_c: f64) -> Option<RecordMean> {
    let mut sums = RecordSums::default();
    sums.add(series);
    let present = series.present_channels();
    sums.mean(temperature_c).map(|mut mean| {
        mean.values.retain(|c, _| present.contains(c));
        mean
    })
}

/// The observations of records that belong to power-on `power_on`, per channel.
pub fn power_on_records(
    power_on: u32,
    means: &[RecordMean],
) -> BTreeMap<Channel, Vec<PowerOnRecord>> {
    let mut out: BTreeMap<Channel, Vec<PowerOnRecord>> = BTreeMap::new();
    for mean in means {
        for (&channel, &value) in &mean.values {
            out.entry(channel).or_default().push(PowerOnRecord {
                power_on,
                temperature_c: mean.temperature_c,
                value,
            });
        }
    }
    out
}

/// Block means of a temperature sweep in one power-on: consecutive blocks of `block_s`
/// seconds (a last, shorter block is dropped), temperature and every channel averaged alike.
///
/// # Errors
/// [`ThermalError::NoTemperature`] for a record without temp_c, [`ThermalError::EmptyBlock`]
/// for a block length that is not positive and finite, and
/// [`ThermalError::TooFewObservations`] when fewer than two whole blocks fit.
pub fn sweep_records(
    power_on: u32,
    series: &ImuSeries,
    block_s: f64,
) -> Result<BTreeMap<Channel, Vec<PowerOnRecord>>, ThermalError> {
    let temperatures = series
        .temperature_c
        .as_ref()
        .ok_or(ThermalError::NoTemperature)?;
    if !(block_s.is_finite() && block_s > 0.0) {
        return Err(ThermalError::EmptyBlock);
    }
    let bounds = block_bounds(series, block_s);
    if bounds.len() < 2 {
        return Err(ThermalError::TooFewObservations {
            observations: bounds.len(),
            needed: 2,
        });
    }
    let mean = |xs: &[f64]| xs.iter().sum::<f64>() / xs.len() as f64;
    let means: Vec<RecordMean> = bounds
        .iter()
        .map(|&(a, b)| RecordMean {
            temperature_c: mean(&temperatures[a..b]),
            values: Channel::ALL
                .iter()
                .map(|&c| (c, mean(&series.channel(c)[a..b])))
                .collect(),
            samples: b - a,
        })
        .collect();
    Ok(power_on_records(power_on, &means))
}

/// Sample ranges [a, b) of the whole blocks of `block_s` seconds.
fn block_bounds(series: &ImuSeries, block_s: f64) -> Vec<(usize, usize)> {
    let Some(&start) = series.time.first() else {
        return Vec::new();
    };
    let mut bounds = Vec::new();
    let mut first = 0;
    let mut block = 1.0;
    for (k, t) in series.time.iter().enumerate() {
        if t.since(start).as_seconds() >= block * block_s {
            if k > first {
                bounds.push((first, k));
            }
            first = k;
            block = (t.since(start).as_seconds() / block_s).floor() + 1.0;
        }
    }
    bounds
}

/// Merges the observations of several power-ons.
pub fn merge_records(
    parts: impl IntoIterator<Item = BTreeMap<Channel, Vec<PowerOnRecord>>>,
) -> BTreeMap<Channel, Vec<PowerOnRecord>> {
    let mut out: BTreeMap<Channel, Vec<PowerOnRecord>> = BTreeMap::new();
    for part in parts {
        for (channel, records) in part {
            out.entry(channel).or_default().extend(records);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::imu::SampleKind;
    use crate::time::Timestamp;

    fn series(n: usize, rate_hz: f64) -> ImuSeries {
        let mut s = ImuSeries::new(SampleKind::Rates);
        s.time = (0..n)
            .map(|k| Timestamp::from_nanos((k as f64 / rate_hz * 1e9) as i64))
            .collect();
        for c in Channel::ALL {
            s.channels[c.index()] = (0..n).map(|k| k as f64 + c.index() as f64).collect();
        }
        s.temperature_c = Some((0..n).map(|k| k as f64 * 0.5).collect());
        s
    }

    #[test]
    fn record_mean_is_the_arithmetic_mean() {
        // Closed form: the mean of 0..n−1 is (n − 1)/2.
        let m = record_mean(&series(11, 10.0), 20.0).unwrap();
        assert_eq!(m.values[&Channel::Gx], 5.0);
        assert_eq!(m.values[&Channel::Az], 10.0);
        assert_eq!(m.samples, 11);
        assert!(record_mean(&ImuSeries::new(SampleKind::Rates), 0.0).is_none());
    }

    #[test]
    fn sweep_blocks_are_whole_blocks_of_time() {
        // 25 samples at 10 Hz (0..2.4 s), blocks of 1 s: samples 0-9 and 10-19; 20-24 dropped.
        let records = sweep_records(3, &series(25, 10.0), 1.0).unwrap();
        let gx = &records[&Channel::Gx];
        assert_eq!(gx.len(), 2);
        assert_eq!(gx[0].value, 4.5);
        assert_eq!(gx[1].value, 14.5);
        assert_eq!(gx[1].temperature_c, 7.25);
        assert_eq!(gx[0].power_on, 3);
        let mut no_temperature = series(25, 10.0);
        no_temperature.temperature_c = None;
        assert_eq!(
            sweep_records(3, &no_temperature, 1.0),
            Err(ThermalError::NoTemperature)
        );
        assert!(matches!(
            sweep_records(3, &series(25, 10.0), 2.0),
            Err(ThermalError::TooFewObservations { .. })
        ));
    }
}
