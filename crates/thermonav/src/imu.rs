//! IMU samples and series.
//!
//! A series is stored by column: one `Vec<f64>` per channel, all of the same length as the time
//! axis. Per-channel processing (Allan variance, AR fitting, filtering) then works on contiguous
//! slices. Values are SI: rad/s and m/s² for rates, rad and m/s for increments.

use crate::time::Timestamp;
use serde::{Deserialize, Serialize};

/// One of the six inertial channels, in the body frame (FRD, see CONVENTIONS.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Channel {
    /// Gyro about body x (forward).
    Gx,
    /// Gyro about body y (right).
    Gy,
    /// Gyro about body z (down).
    Gz,
    /// Accelerometer along body x.
    Ax,
    /// Accelerometer along body y.
    Ay,
    /// Accelerometer along body z.
    Az,
}

/// Why a temperature-dependent error cannot be removed from a series.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum TemperatureColumnError {
    /// The series has no temperature column.
    #[error("the IMU record has no temp_c column")]
    Missing,
    /// A sample's temperature is not finite.
    #[error("sample {index} has a non-finite temperature")]
    NonFinite {
        /// Position of the sample.
        index: usize,
    },
}

/// Which sensor a channel belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sensor {
    /// Angular rate (or angle increment).
    Gyro,
    /// Specific force (or velocity increment).
    Accelerometer,
}

impl Channel {
    /// The six channels in file order: gx, gy, gz, ax, ay, az.
    pub const ALL: [Channel; 6] = [
        Channel::Gx,
        Channel::Gy,
        Channel::Gz,
        Channel::Ax,
        Channel::Ay,
        Channel::Az,
    ];

    /// Short name used in JSON keys and tables (`gx`, …, `az`).
    pub fn name(self) -> &'static str {
        match self {
            Channel::Gx => "gx",
            Channel::Gy => "gy",
            Channel::Gz => "gz",
            Channel::Ax => "ax",
            Channel::Ay => "ay",
            Channel::Az => "az",
        }
    }

    /// The channel of a short name ([`Channel::name`]); `None` for any other text.
    pub fn from_name(name: &str) -> Option<Channel> {
        Channel::ALL.into_iter().find(|c| c.name() == name)
    }

    /// Position in [`Channel::ALL`] (0..6).
    pub fn index(self) -> usize {
        self as usize
    }

    /// The sensor that measures this channel.
    pub fn sensor(self) -> Sensor {
        match self {
            Channel::Gx | Channel::Gy | Channel::Gz => Sensor::Gyro,
            Channel::Ax | Channel::Ay | Channel::Az => Sensor::Accelerometer,
        }
    }

    /// SI unit of the channel's values for a given sample kind.
    pub fn si_unit(self, kind: SampleKind) -> &'static str {
        match (self.sensor(), kind) {
            (Sensor::Gyro, SampleKind::Rates) => "rad/s",
            (Sensor::Gyro, SampleKind::Increments) => "rad",
            (Sensor::Accelerometer, SampleKind::Rates) => "m/s^2",
            (Sensor::Accelerometer, SampleKind::Increments) => "m/s",
        }
    }
}

/// Whether the samples are instantaneous rates or increments integrated over the sample interval.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SampleKind {
    /// Angular rate in rad/s and specific force in m/s².
    Rates,
    /// Angle increment in rad and velocity increment in m/s over the interval ending at the
    /// sample's timestamp.
    Increments,
}

/// One IMU sample, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImuSample {
    /// Time of the sample (end of the interval for increments).
    pub time: Timestamp,
    /// Gyro x, y, z: rad/s (rates) or rad (increments).
    pub gyro: [f64; 3],
    /// Accelerometer x, y, z: m/s² (rates) or m/s (increments).
    pub accel: [f64; 3],
    /// Sensor temperature in °C, when logged.
    pub temperature_c: Option<f64>,
}

/// A whole IMU record, stored by column.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ImuSeries {
    /// Time axis.
    pub time: Vec<Timestamp>,
    /// One column per channel, in [`Channel::ALL`] order.
    pub channels: [Vec<f64>; 6],
    /// Temperature column in °C, when every sample carries one.
    pub temperature_c: Option<Vec<f64>>,
    /// Kind of the values in `channels`.
    pub kind: Option<SampleKind>,
}

impl ImuSeries {
    /// An empty series of the given kind.
    pub fn new(kind: SampleKind) -> Self {
        Self {
            kind: Some(kind),
            ..Self::default()
        }
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// True when the series holds no sample.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    /// Mean of the temperature column, °C; `None` without one (or with no sample).
    pub fn mean_temperature_c(&self) -> Option<f64> {
        self.temperature_c
            .as_ref()
            .filter(|c| !c.is_empty())
            .map(|c| c.iter().sum::<f64>() / c.len() as f64)
    }

    /// Each sample's interval, s, for a series of increments (the first sample taking the
    /// second's interval); `None` for rates, whose values need no interval.
    pub fn increment_intervals_s(&self) -> Option<Vec<f64>> {
        if self.kind != Some(SampleKind::Increments) {
            return None;
        }
        let mut dt: Vec<f64> = self
            .time
            .windows(2)
            .map(|w| w[1].since(w[0]).as_seconds())
            .collect();
        dt.insert(0, dt.first().copied().unwrap_or(0.0));
        Some(dt)
    }

    /// Removes a temperature-dependent bias and scale-factor error from `channels`: each
    /// sample y becomes (y − b·dt) / (1 + s), with (b, s) = `error(channel, T)` at the sample's
    /// own temperature T (b in the channel's rate unit, s dimensionless; dt the sample's
    /// interval for increments, 1 for rates).
    ///
    /// # Errors
    /// [`TemperatureColumnError`] for a series without temperatures or with a non-finite one;
    /// the series is then unchanged.
    pub fn remove_thermal_error(
        &mut self,
        channels: &[Channel],
        error: impl Fn(Channel, f64) -> (f64, f64),
    ) -> Result<(), TemperatureColumnError> {
        self.remove_thermal_error_at(channels, |c, _, t| error(c, t))
    }

    /// [`ImuSeries::remove_thermal_error`] with the sample's index given to `error` as well
    /// (for an error that depends on more than the temperature, such as its rate).
    ///
    /// # Errors
    /// As [`ImuSeries::remove_thermal_error`].
    pub fn remove_thermal_error_at(
        &mut self,
        channels: &[Channel],
        error: impl Fn(Channel, usize, f64) -> (f64, f64),
    ) -> Result<(), TemperatureColumnError> {
        let intervals = self.increment_intervals_s();
        let temperatures = self
            .temperature_c
            .as_deref()
            .ok_or(TemperatureColumnError::Missing)?;
        if let Some(index) = temperatures.iter().position(|t| !t.is_finite()) {
            return Err(TemperatureColumnError::NonFinite { index });
        }
        for &channel in channels {
            let column = &mut self.channels[channel.index()];
            for (k, value) in column.iter_mut().enumerate() {
                let (bias, scale) = error(channel, k, temperatures[k]);
                let dt = intervals.as_ref().map_or(1.0, |dt| dt[k]);
                *value = (*value - bias * dt) / (1.0 + scale);
            }
        }
        Ok(())
    }

    /// The channels the series holds, in [`Channel::ALL`] order: all six, except for a record
    /// of a subset of them (a single-gyro file, read for the static analyses), whose absent
    /// channels have empty columns while the series has samples.
    pub fn present_channels(&self) -> Vec<Channel> {
        Channel::ALL
            .into_iter()
            .filter(|&c| self.is_empty() || !self.channel(c).is_empty())
            .collect()
    }

    /// Empties the columns of the channels not in `present` (see
    /// [`ImuSeries::present_channels`]).
    pub fn keep_channels(&mut self, present: &[Channel]) {
        for channel in Channel::ALL {
            if !present.contains(&channel) {
                self.channels[channel.index()] = Vec::new();
            }
        }
    }

    /// The column of one channel.
    pub fn channel(&self, channel: Channel) -> &[f64] {
        &self.channels[channel.index()]
    }

    /// This series with every column emptied and its room kept, ready for a series of `kind`:
    /// reading the next record into it writes over memory already mapped, where a new series
    /// would fault in (and have the kernel zero) every page of its columns again.
    pub fn emptied(mut self, kind: SampleKind) -> Self {
        self.time.clear();
        for column in self.channels.iter_mut().chain(&mut self.temperature_c) {
            column.clear();
        }
        self.kind = Some(kind);
        self
    }

    /// Appends one sample. A temperature column is kept only while every sample has one.
    pub fn push(&mut self, sample: &ImuSample) {
        let first = self.time.is_empty();
        self.time.push(sample.time);
        for (column, value) in self
            .channels
            .iter_mut()
            .zip(sample.gyro.iter().chain(&sample.accel))
        {
            column.push(*value);
        }
        match (sample.temperature_c, first) {
            (Some(t), true) => {
                // An emptied series' temperature column is reused.
                let mut column = self.temperature_c.take().unwrap_or_default();
                column.clear();
                column.push(t);
                self.temperature_c = Some(column);
            }
            (Some(t), false) => {
                if let Some(column) = self.temperature_c.as_mut() {
                    column.push(t);
                }
            }
            (None, _) => self.temperature_c = None,
        }
    }

    /// Sample times in seconds from the first sample (f64, for arithmetic).
    pub fn seconds_from_start(&self) -> Vec<f64> {
        let Some(&start) = self.time.first() else {
            return Vec::new();
        };
        self.time
            .iter()
            .map(|t| t.since(start).as_seconds())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Every channel's name reads back as that channel; no other text names one.
    #[test]
    fn channel_names_read_back() {
        for c in Channel::ALL {
            assert_eq!(Channel::from_name(c.name()), Some(c));
        }
        assert_eq!(Channel::from_name("GX"), None);
        assert_eq!(Channel::from_name("temp_c"), None);
    }

    fn sample(nanos: i64, temperature_c: Option<f64>) -> ImuSample {
        ImuSample {
            time: Timestamp::from_nanos(nanos),
            gyro: [1.0, 2.0, 3.0],
            accel: [4.0, 5.0, 6.0],
            temperature_c,
        }
    }

    #[test]
    fn push_fills_columns_in_channel_order() {
        let mut series = ImuSeries::new(SampleKind::Rates);
        series.push(&sample(0, Some(20.0)));
        series.push(&sample(5_000_000, Some(20.5)));
        assert_eq!(series.len(), 2);
        assert_eq!(series.channel(Channel::Gz), &[3.0, 3.0]);
        assert_eq!(series.channel(Channel::Ax), &[4.0, 4.0]);
        assert_eq!(series.temperature_c.as_deref(), Some(&[20.0, 20.5][..]));
        assert_eq!(series.seconds_from_start(), vec![0.0, 0.005]);
    }

    #[test]
    fn temperature_column_dropped_when_a_sample_lacks_it() {
        let mut series = ImuSeries::new(SampleKind::Rates);
        series.push(&sample(0, Some(20.0)));
        series.push(&sample(1, None));
        assert!(series.temperature_c.is_none());
    }
}
