//! The oracle: the error model a simulator knows to be true, as a tournament candidate.
//!
//! A simulated survey states, on a fine temperature grid, each channel's true Gauss-Markov
//! bias (Tc, σ), white-noise density and repeatable bias (the unit's fixed bias plus its
//! thermal curve). The oracle candidates use it as no real user can:
//!
//! - **truth scheduled**: the true model at the IMU's temperature at every covariance step, on
//!   the record as read;
//! - **truth scheduled compensated**: the same on the record with the true repeatable bias
//!   subtracted and the true thermal scale-factor error divided out at each sample's
//!   temperature (u = (y − b(T)) / (1 + s(T)·1e-6)), which is what a perfect thermal
//!   calibration would remove. The survey's power-on offset stays in the record, as it would for any
//!   calibration: the filter estimates it like every other candidate;
//! - **truth scheduled on calibrated**: the true model scheduled on the record compensated
//!   with the bank's own thermal calibration, as the compensated candidates run (only with a
//!   calibrated bank): what the true noise models add when the compensation is ours.
//!
//! The gap between a candidate and the oracle is what a better model could still gain.

use crate::imu::{Channel, ImuSeries};
use crate::nav::schedule::{ModelGrid, ScheduleError, TemperatureRule};
use crate::nav::sensor_model::{
    AxisModel, GaussMarkovParameters, ImuStochasticModel, ScaleFactorPrior, SensorModelError,
};
use crate::stoch::thermal::legs::lagged_temperatures;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The true error model of one channel at one temperature (SI: rad/s or m/s²).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrueChannelModel {
    /// Gauss-Markov correlation time, s.
    pub correlation_time_s: f64,
    /// Gauss-Markov σ, channel unit.
    pub sigma: f64,
    /// White-noise density, channel unit·√s.
    pub white_noise_density: f64,
    /// Repeatable bias (the unit's fixed bias plus its thermal curve), channel unit.
    pub repeatable_bias: f64,
    /// Thermal scale-factor error, ppm (the sensor's scale-factor temperature coefficient
    /// times T − T_ref; 0 when absent).
    #[serde(default)]
    pub thermal_scale_factor_ppm: f64,
    /// Scale-factor Gauss-Markov correlation time, s, when the sensor states one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale_factor_correlation_time_s: Option<f64>,
    /// Scale-factor Gauss-Markov σ (dimensionless, 1e-6 = 1 ppm), when stated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale_factor_sigma: Option<f64>,
}

/// The true model of every channel at one temperature.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrueModelAt {
    /// Temperature, °C.
    pub temperature_c: f64,
    /// Per channel (all six).
    pub channels: BTreeMap<Channel, TrueChannelModel>,
}

/// Why a truth table cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OracleError {
    /// No temperature at all.
    #[error("the truth has no model (its \"models\" list is empty)")]
    Empty,
    /// Temperatures not strictly increasing, or not finite.
    #[error(
        "the truth's temperatures must be finite and strictly increasing; model {index} is at {temperature_c} °C"
    )]
    Temperatures {
        /// Position in the table.
        index: usize,
        /// Its temperature.
        temperature_c: f64,
    },
    /// A channel missing at one temperature.
    #[error("the truth at {temperature_c} °C has no channel {channel}")]
    MissingChannel {
        /// The temperature, °C.
        temperature_c: f64,
        /// The channel's name.
        channel: &'static str,
    },
    /// A value that is not a usable model parameter.
    #[error("the truth at {temperature_c} °C: {source}")]
    Model {
        /// The temperature, °C.
        temperature_c: f64,
        /// What is wrong.
        source: SensorModelError,
    },
    /// A repeatable bias that is not finite, or a scale-factor error of −1e6 ppm or less.
    #[error(
        "the truth at {temperature_c} °C: repeatable_bias of {channel} must be finite and thermal_scale_factor_ppm finite and above -1e6"
    )]
    Bias {
        /// The temperature, °C.
        temperature_c: f64,
        /// The channel's name.
        channel: &'static str,
    },
    /// The record has no temperatures, or a non-finite one.
    #[error("the oracle needs the IMU's temp_c at every sample")]
    NoTemperature,
    /// A structure lag that is negative or not finite.
    #[error("thermal_lag_s of {channel} is {lag_s}: expected a finite lag of 0 s or more")]
    ThermalLag {
        /// The channel's name.
        channel: &'static str,
        /// The lag given, s.
        lag_s: f64,
    },
}

/// A validated truth table, increasing in temperature.
#[derive(Debug, Clone, PartialEq)]
pub struct TrueModel {
    table: Vec<TrueModelAt>,
    models: Vec<ImuStochasticModel>,
    /// Per channel, the time constant by which the structure lags the temperature sensor, s
    /// (none or 0: no lag).
    thermal_lag_s: BTreeMap<Channel, f64>,
}

impl TrueModel {
    /// Validates `table` (temperatures strictly increasing, all six channels, parameters
    /// usable) and builds each temperature's model with `scale` where the truth states no
    /// scale-factor model.
    ///
    /// # Errors
    /// [`OracleError`] naming the first bad entry.
    pub fn new(table: Vec<TrueModelAt>, scale: &ScaleFactorPrior) -> Result<Self, OracleError> {
        if table.is_empty() {
            return Err(OracleError::Empty);
        }
        check_temperatures(&table)?;
        let models = table
            .iter()
            .map(|at| model_of(at, scale))
            .collect::<Result<_, _>>()?;
        Ok(Self {
            table,
            models,
            thermal_lag_s: BTreeMap::new(),
        })
    }

    /// The model with each channel's structure lagging its temperature sensor by a
    /// first-order lag of `lags_s` (s; the simulator's `thermal_lag_s`): its repeatable error
    /// is then read at the structure's temperature ([`TrueModel::compensate`]).
    ///
    /// # Errors
    /// [`OracleError::ThermalLag`] for a lag that is negative or not finite.
    pub fn with_thermal_lags(
        mut self,
        lags_s: BTreeMap<Channel, f64>,
    ) -> Result<Self, OracleError> {
        if let Some((c, lag)) = lags_s.iter().find(|(_, l)| !(l.is_finite() && **l >= 0.0)) {
            return Err(OracleError::ThermalLag {
                channel: c.name(),
                lag_s: *lag,
            });
        }
        self.thermal_lag_s = lags_s;
        Ok(self)
    }

    /// Coldest and warmest temperature of the table, °C.
    pub fn range_c(&self) -> [f64; 2] {
        let last = self.table.len() - 1;
        [self.table[0].temperature_c, self.table[last].temperature_c]
    }

    /// The model of the table temperature nearest `temperature_c`.
    pub fn model_at(&self, temperature_c: f64) -> &ImuStochasticModel {
        &self.models[self.nearest_index(temperature_c)]
    }

    /// The repeatable bias of `channel` at `temperature_c`, interpolated linearly between
    /// table temperatures and held at the table's ends, channel unit.
    pub fn repeatable_bias_at(&self, channel: Channel, temperature_c: f64) -> f64 {
        self.interpolated(temperature_c, |at| at.channels[&channel].repeatable_bias)
    }

    /// The thermal scale-factor error of `channel` at `temperature_c`, ppm, interpolated as
    /// [`TrueModel::repeatable_bias_at`].
    pub fn thermal_scale_factor_ppm_at(&self, channel: Channel, temperature_c: f64) -> f64 {
        self.interpolated(temperature_c, |at| {
            at.channels[&channel].thermal_scale_factor_ppm
        })
    }

    /// `value` of the table, linear in temperature between entries, held beyond the ends.
    fn interpolated(&self, temperature_c: f64, value: impl Fn(&TrueModelAt) -> f64) -> f64 {
        let after = self
            .table
            .partition_point(|at| at.temperature_c <= temperature_c);
        match after {
            0 => value(&self.table[0]),
            n if n == self.table.len() => value(&self.table[n - 1]),
            n => {
                let (below, above) = (&self.table[n - 1], &self.table[n]);
                let w = (temperature_c - below.temperature_c)
                    / (above.temperature_c - below.temperature_c);
                value(below) + w * (value(above) - value(below))
            }
        }
    }

    /// The models by temperature over `range_c` (coldest, warmest, °C) for the scheduled
    /// oracle, each grid point taking the table temperature nearest it.
    ///
    /// # Errors
    /// None in practice (every table model is valid); the type is [`ModelGrid::over`]'s.
    pub fn grid(&self, range_c: [f64; 2]) -> Result<ModelGrid, ScheduleError> {
        ModelGrid::over(range_c, TemperatureRule::Truth, |t| Ok(*self.model_at(t)))
    }

    /// Removes the true repeatable bias and thermal scale-factor error at each sample's
    /// structure temperature from every channel: u = (y − b(T)) / (1 + s(T)·1e-6) (for
    /// increments the bias times the sample's interval, the first sample taking the second's).
    /// T is the sample's temperature, or for a channel with a thermal lag that temperature
    /// through the lag ([`crate::stoch::thermal::legs::lagged_temperatures`], which the
    /// simulator's structure follows exactly for a temperature linear between samples).
    ///
    /// # Errors
    /// [`OracleError::NoTemperature`] for a record without temperatures or with a non-finite
    /// one; the series is then unchanged.
    pub fn compensate(&self, series: &mut ImuSeries) -> Result<(), OracleError> {
        let structure = self.structure_temperatures(series);
        let error = |c: Channel, k: usize, t: f64| {
            let t = structure.get(&c).map_or(t, |lagged| lagged[k]);
            let ppm = self.thermal_scale_factor_ppm_at(c, t);
            (self.repeatable_bias_at(c, t), ppm * 1e-6)
        };
        series
            .remove_thermal_error_at(&Channel::ALL, error)
            .map_err(|_| OracleError::NoTemperature)
    }

    /// Per lagging channel, the structure's temperature at each sample of `series` (empty
    /// without lags or temperatures).
    fn structure_temperatures(&self, series: &ImuSeries) -> BTreeMap<Channel, Vec<f64>> {
        let Some(temperature_c) = series.temperature_c.as_deref() else {
            return BTreeMap::new();
        };
        let time_s: Vec<f64> = series.time.iter().map(|t| t.as_seconds()).collect();
        (self.thermal_lag_s.iter())
            .filter(|(_, lag)| **lag > 0.0)
            .map(|(c, lag)| (*c, lagged_temperatures(&time_s, temperature_c, -lag)))
            .collect()
    }

    fn nearest_index(&self, temperature_c: f64) -> usize {
        let after = self
            .table
            .partition_point(|at| at.temperature_c <= temperature_c);
        match after {
            0 => 0,
            n if n == self.table.len() => n - 1,
            n => {
                let below = temperature_c - self.table[n - 1].temperature_c;
                let above = self.table[n].temperature_c - temperature_c;
                if above < below { n } else { n - 1 }
            }
        }
    }
}

fn check_temperatures(table: &[TrueModelAt]) -> Result<(), OracleError> {
    let mut previous = f64::NEG_INFINITY;
    for (index, at) in table.iter().enumerate() {
        let t = at.temperature_c;
        if !t.is_finite() || t <= previous {
            return Err(OracleError::Temperatures {
                index,
                temperature_c: t,
            });
        }
        previous = t;
    }
    Ok(())
}

/// The stochastic model of one table temperature.
fn model_of(at: &TrueModelAt, scale: &ScaleFactorPrior) -> Result<ImuStochasticModel, OracleError> {
    let temperature_c = at.temperature_c;
    for channel in Channel::ALL {
        let truth = at
            .channels
            .get(&channel)
            .ok_or(OracleError::MissingChannel {
                temperature_c,
                channel: channel.name(),
            })?;
        let scale = 1.0 + truth.thermal_scale_factor_ppm * 1e-6;
        if !(truth.repeatable_bias.is_finite() && scale.is_finite() && scale > 0.0) {
            return Err(OracleError::Bias {
                temperature_c,
                channel: channel.name(),
            });
        }
    }
    let axis = |channel: Channel, prior: GaussMarkovParameters| {
        let truth = &at.channels[&channel];
        let scale_factor = match (
            truth.scale_factor_correlation_time_s,
            truth.scale_factor_sigma,
        ) {
            (Some(correlation_time_s), Some(sigma)) => GaussMarkovParameters {
                correlation_time_s,
                sigma,
            },
            _ => prior,
        };
        Ok(AxisModel {
            white_noise_density: truth.white_noise_density,
            bias: GaussMarkovParameters {
                correlation_time_s: truth.correlation_time_s,
                sigma: truth.sigma,
            },
            scale_factor,
        })
    };
    ImuStochasticModel::from_axes(axis, scale).map_err(|source| OracleError::Model {
        temperature_c,
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::imu::SampleKind;
    use crate::time::Timestamp;

    /// A table at `temperatures_c` whose gx repeatable bias takes `gx_bias`, every other
    /// channel 0, Tc = 100 s + the temperature, σ 1e-4, density 1e-5.
    fn table(temperatures_c: &[f64], gx_bias: &[f64]) -> Vec<TrueModelAt> {
        temperatures_c
            .iter()
            .zip(gx_bias)
            .map(|(&temperature_c, &bias)| TrueModelAt {
                temperature_c,
                channels: Channel::ALL
                    .iter()
                    .map(|&c| {
                        let truth = TrueChannelModel {
                            correlation_time_s: 100.0 + temperature_c,
                            sigma: 1e-4,
                            white_noise_density: 1e-5,
                            repeatable_bias: if c == Channel::Gx { bias } else { 0.0 },
                            thermal_scale_factor_ppm: if c == Channel::Ax {
                                1e3 * bias
                            } else {
                                0.0
                            },
                            scale_factor_correlation_time_s: None,
                            scale_factor_sigma: None,
                        };
                        (c, truth)
                    })
                    .collect(),
            })
            .collect()
    }

    fn truth() -> TrueModel {
        let t = table(&[0.0, 10.0, 20.0], &[1.0, 3.0, 2.0]);
        TrueModel::new(t, &ScaleFactorPrior::default()).unwrap()
    }

    // Closed form: linear between (0, 1), (10, 3), (20, 2); held beyond the ends.
    #[test]
    fn repeatable_bias_is_linear_between_table_temperatures_and_held_beyond() {
        let t = truth();
        let at = |c| t.repeatable_bias_at(Channel::Gx, c);
        assert_eq!(at(0.0), 1.0);
        assert!((at(5.0) - 2.0).abs() < 1e-15);
        assert!((at(15.0) - 2.5).abs() < 1e-15);
        assert_eq!(at(-5.0), 1.0);
        assert_eq!(at(25.0), 2.0);
        assert_eq!(t.repeatable_bias_at(Channel::Az, 7.0), 0.0);
        assert_eq!(t.range_c(), [0.0, 20.0]);
    }

    #[test]
    fn the_model_is_the_nearest_table_temperatures() {
        let t = truth();
        let tc = |c| t.model_at(c).gyro[0].bias.correlation_time_s;
        assert_eq!(tc(4.9), 100.0);
        assert_eq!(tc(5.1), 110.0);
        assert_eq!(tc(-30.0), 100.0);
        assert_eq!(tc(99.0), 120.0);
        let grid = t.grid([0.0, 20.0]).unwrap();
        assert_eq!(grid.rule(), TemperatureRule::Truth);
        assert_eq!(grid.model_at(14.0).gyro[0].bias.correlation_time_s, 110.0);
    }

    // Closed form: an increment loses bias(T)·dt (the first sample takes the second's
    // interval), a rate loses bias(T); channels without bias are untouched.
    #[test]
    fn compensation_subtracts_the_bias_at_each_samples_temperature() {
        let t = truth();
        let times = [0.0, 0.01, 0.03].map(|s| Timestamp::from_seconds(s).unwrap());
        let mut series = ImuSeries::new(SampleKind::Increments);
        series.time = times.to_vec();
        series.channels = std::array::from_fn(|_| vec![0.5; 3]);
        series.temperature_c = Some(vec![0.0, 5.0, 10.0]);
        let mut rates = series.clone();
        rates.kind = Some(SampleKind::Rates);
        t.compensate(&mut series).unwrap();
        t.compensate(&mut rates).unwrap();
        let expected = [0.5 - 1.0 * 0.01, 0.5 - 2.0 * 0.01, 0.5 - 3.0 * 0.02];
        for (got, want) in series.channel(Channel::Gx).iter().zip(expected) {
            assert!((got - want).abs() < 1e-15, "{got} against {want}");
        }
        assert_eq!(rates.channel(Channel::Gx), &[-0.5, -1.5, -2.5]);
        assert_eq!(series.channel(Channel::Ay), &[0.5; 3]);
        // ax: no bias, scale-factor error 1000, 2000 and 3000 ppm divided out.
        let ax = series.channel(Channel::Ax);
        for (got, ppm) in ax.iter().zip([1e3, 2e3, 3e3]) {
            assert!((got - 0.5 / (1.0 + ppm * 1e-6)).abs() < 1e-15, "{got}");
        }
        series.temperature_c = None;
        assert_eq!(t.compensate(&mut series), Err(OracleError::NoTemperature));
    }

    // Closed form: the sensor's temperature ramps at m = 0.05 °C/s from 0 °C, so a structure
    // lagging by τ = 60 s (settled at the start) reads T_s(t) = m·t − τ·m·(1 − exp(−t/τ)); gx's
    // bias is linear there (0.2 per °C between 0 and 10 °C), so the compensated rate is
    // 0.5 − (1 + 0.2·T_s). A channel without a lag is read at the sensor's temperature.
    #[test]
    fn compensation_with_a_lag_reads_the_structures_temperature() {
        let lags = BTreeMap::from([(Channel::Gx, 60.0)]);
        let t = truth().with_thermal_lags(lags).unwrap();
        for bad in [-1.0, f64::NAN, f64::INFINITY] {
            let refused = truth().with_thermal_lags(BTreeMap::from([(Channel::Gy, bad)]));
            assert!(
                matches!(refused, Err(OracleError::ThermalLag { channel: "gy", .. })),
                "{bad}"
            );
        }
        let (m, tau) = (0.05, 60.0);
        let time_s: Vec<f64> = (0..=100).map(|k| k as f64 * 1.5).collect();
        let mut series = ImuSeries::new(SampleKind::Rates);
        series.time = (time_s.iter())
            .map(|&s| Timestamp::from_seconds(s).unwrap())
            .collect();
        series.channels = std::array::from_fn(|_| vec![0.5; time_s.len()]);
        series.temperature_c = Some(time_s.iter().map(|s| m * s).collect());
        t.compensate(&mut series).unwrap();
        for (k, &s) in time_s.iter().enumerate() {
            let structure = m * s - tau * m * (1.0 - (-s / tau).exp());
            let want = 0.5 - (1.0 + 0.2 * structure);
            let got = series.channel(Channel::Gx)[k];
            assert!((got - want).abs() < 1e-12, "t {s}: {got} against {want}");
            // ax has no lag: its scale factor is read at the sensor's temperature.
            let ppm = 1e3 * (1.0 + 0.2 * (m * s));
            let ax = series.channel(Channel::Ax)[k];
            assert!((ax - 0.5 / (1.0 + ppm * 1e-6)).abs() < 1e-12, "t {s}: {ax}");
        }
    }

    #[test]
    fn unusable_tables_are_refused_naming_what_is_wrong() {
        let scale = ScaleFactorPrior::default();
        let refuse = |t: Vec<TrueModelAt>| TrueModel::new(t, &scale).unwrap_err().to_string();
        assert!(refuse(Vec::new()).contains("empty"));
        assert!(refuse(table(&[10.0, 10.0], &[0.0, 0.0])).contains("model 1 is at 10 °C"));
        let mut missing = table(&[0.0], &[0.0]);
        missing[0].channels.remove(&Channel::Ay);
        assert!(refuse(missing).contains("no channel ay"));
        let mut bad = table(&[0.0], &[f64::NAN]);
        assert!(refuse(bad.clone()).contains("repeatable_bias of gx"));
        bad[0]
            .channels
            .get_mut(&Channel::Gx)
            .unwrap()
            .repeatable_bias = 0.0;
        bad[0]
            .channels
            .get_mut(&Channel::Az)
            .unwrap()
            .correlation_time_s = -1.0;
        assert!(refuse(bad).contains("-1"));
    }
}
