//! Noise models scheduled by the sensor's temperature: at every covariance step the filter
//! takes the Gauss-Markov bias (Tc, σ) and the white-noise densities of the model at the IMU's
//! temperature at that time.
//!
//! - [`TemperatureTrack`]: the IMU's temperature over time, held from each sample to the next
//!   (before the first sample, the first sample's), stored as the instants where it changes.
//! - [`ModelGrid`]: the models precomputed on a [`ModelGrid::STEP_C`] grid over a temperature
//!   range, so a step costs a binary search and an index, not a bank selection. A temperature
//!   is rounded to the nearest grid point (at most half a step away) and held at the range's
//!   ends; a record at one constant temperature has a grid of that one temperature, so its
//!   scheduled run is the fixed run.
//! - [`ModelSchedule`]: what the engine takes, one fixed model or a track with a grid.
//!
//! The model of a covariance step over (s, e] is the model at the temperature at s, as the
//! system matrix is taken at the interval's start.

use super::sensor_model::{BankChoice, ImuStochasticModel, ScaleFactorPrior, SensorModelError};
use crate::imu::ImuSeries;
use crate::ins::error_model::SystemMatrix;
use crate::sensor::SensorProfile;
use crate::stoch::bank::{GaussMarkovSource, ModelBank, Selection};
use crate::stoch::thermal::ThermalCalibration;
use crate::time::Timestamp;
use serde::Serialize;

/// Whether the filter follows the sensor's temperature.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Scheduling {
    /// The model at the temperature at every covariance step, when the record has one.
    #[default]
    ByTemperature,
    /// One model for the whole run.
    Fixed,
}

/// Whether the bank's thermal bias calibration is subtracted from the record.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Compensation {
    /// Subtract bias(T) at every sample when the bank holds a calibration and the record
    /// has temperatures.
    #[default]
    WhenCalibrated,
    /// Never.
    Off,
}

impl Scheduling {
    /// The default, scheduling by temperature, when `enabled`; else one model for the run
    /// (the CLI's `--no-schedule`, Python's `schedule=False`).
    pub fn when(enabled: bool) -> Self {
        match enabled {
            true => Self::default(),
            false => Self::Fixed,
        }
    }
}

impl Compensation {
    /// The default, compensating when the bank holds a calibration, when `enabled`; else off
    /// (the CLI's `--no-compensation`, Python's `compensation=False`).
    pub fn when(enabled: bool) -> Self {
        match enabled {
            true => Self::default(),
            false => Self::Off,
        }
    }
}

/// Why a schedule cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ScheduleError {
    /// A temperature that is not finite.
    #[error("sample {index} has a non-finite temperature")]
    NonFiniteTemperature {
        /// Position of the sample.
        index: usize,
    },
    /// Times and temperatures of different lengths, or none at all.
    #[error("a temperature track needs one temperature per time and at least one sample")]
    Shape,
    /// A grid model cannot be built.
    #[error("model at {temperature_c:.2} °C: {source}")]
    Model {
        /// The grid temperature, °C.
        temperature_c: f64,
        /// Why.
        source: SensorModelError,
    },
}

/// The IMU's temperature over time: piecewise constant, changing at `starts`.
#[derive(Debug, Clone, PartialEq)]
pub struct TemperatureTrack {
    starts: Vec<Timestamp>,
    temperature_c: Vec<f64>,
    range_c: [f64; 2],
}

impl TemperatureTrack {
    /// The track of sample times and temperatures, °C (times non-decreasing).
    ///
    /// # Errors
    /// [`ScheduleError`] for a non-finite temperature or mismatched lengths.
    pub fn new(time: &[Timestamp], temperature_c: &[f64]) -> Result<Self, ScheduleError> {
        if time.len() != temperature_c.len() || time.is_empty() {
            return Err(ScheduleError::Shape);
        }
        if let Some(index) = temperature_c.iter().position(|t| !t.is_finite()) {
            return Err(ScheduleError::NonFiniteTemperature { index });
        }
        let mut track = Self {
            starts: Vec::new(),
            temperature_c: Vec::new(),
            range_c: [f64::INFINITY, f64::NEG_INFINITY],
        };
        for (&t, &c) in time.iter().zip(temperature_c) {
            track.push(t, c);
        }
        Ok(track)
    }

    /// The track of a series' temp_c column; `None` when it has none (or no sample).
    ///
    /// # Errors
    /// [`ScheduleError::NonFiniteTemperature`].
    pub fn of_series(series: &ImuSeries) -> Result<Option<Self>, ScheduleError> {
        match series.temperature_c.as_deref() {
            Some(column) if !column.is_empty() => Self::new(&series.time, column).map(Some),
            _ => Ok(None),
        }
    }

    fn push(&mut self, time: Timestamp, temperature_c: f64) {
        self.range_c = [
            self.range_c[0].min(temperature_c),
            self.range_c[1].max(temperature_c),
        ];
        if self.temperature_c.last() != Some(&temperature_c) {
            self.starts.push(time);
            self.temperature_c.push(temperature_c);
        }
    }

    /// The temperature at `time`, °C: the latest sample's at or before it (the first sample's
    /// before the track starts).
    pub fn at(&self, time: Timestamp) -> f64 {
        let after = self.starts.partition_point(|&s| s <= time);
        self.temperature_c[after.saturating_sub(1)]
    }

    /// Coldest and warmest temperature, °C.
    pub fn range_c(&self) -> [f64; 2] {
        self.range_c
    }

    /// The first sample's temperature, °C.
    pub fn first_c(&self) -> f64 {
        self.temperature_c[0]
    }

    /// Number of changes of temperature plus one.
    pub fn segments(&self) -> usize {
        self.starts.len()
    }
}

/// How a grid's models are made from a temperature.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TemperatureRule {
    /// The bank entry nearest the temperature.
    BankNearest,
    /// The bank interpolated linearly at the temperature.
    BankLinear,
    /// A sensor profile's Gauss-Markov table at the temperature.
    ProfileTable,
    /// A simulator's true model at the temperature (the oracle).
    Truth,
}

impl TemperatureRule {
    /// The rule of a bank selection.
    pub fn of_selection(selection: Selection) -> Self {
        match selection {
            Selection::Nearest => Self::BankNearest,
            Selection::Linear => Self::BankLinear,
        }
    }
}

/// Models precomputed at `lowest_c + k · step_c`, k = 0, 1, …
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelGrid {
    lowest_c: f64,
    step_c: f64,
    rule: TemperatureRule,
    #[serde(skip)]
    models: Vec<ImuStochasticModel>,
}

impl ModelGrid {
    /// Grid spacing, °C (wider only when a range would need more than
    /// [`ModelGrid::MAX_POINTS`] points).
    pub const STEP_C: f64 = 0.1;
    /// Most grid points.
    pub const MAX_POINTS: usize = 4096;

    /// The grid over `range_c` (coldest, warmest, °C) of the models `model_at` gives.
    ///
    /// # Errors
    /// [`ScheduleError::Model`] at the first grid temperature without a usable model.
    pub fn over(
        range_c: [f64; 2],
        rule: TemperatureRule,
        model_at: impl Fn(f64) -> Result<ImuStochasticModel, SensorModelError>,
    ) -> Result<Self, ScheduleError> {
        let [lowest_c, highest_c] = range_c;
        let span_c = (highest_c - lowest_c).max(0.0);
        let step_c = Self::STEP_C.max(span_c / (Self::MAX_POINTS - 1) as f64);
        let points = (span_c / step_c).ceil() as usize + 1;
        let models = (0..points)
            .map(|k| {
                let temperature_c = lowest_c + k as f64 * step_c;
                model_at(temperature_c).map_err(|source| ScheduleError::Model {
                    temperature_c,
                    source,
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(Self {
            lowest_c,
            step_c,
            rule,
            models,
        })
    }

    /// The grid of a bank's models under one selection rule and Gauss-Markov family.
    ///
    /// # Errors
    /// As [`ModelGrid::over`].
    pub fn from_bank(
        bank: &ModelBank,
        selection: Selection,
        source: GaussMarkovSource,
        scale: &ScaleFactorPrior,
        range_c: [f64; 2],
    ) -> Result<Self, ScheduleError> {
        let rule = TemperatureRule::of_selection(selection);
        Self::over(range_c, rule, |temperature_c| {
            let choice = BankChoice {
                temperature_c,
                selection,
                source,
            };
            ImuStochasticModel::from_bank(bank, &choice, scale)
        })
    }

    /// The grid of a sensor profile's models.
    ///
    /// # Errors
    /// As [`ModelGrid::over`].
    pub fn from_profile(
        profile: &SensorProfile,
        scale: &ScaleFactorPrior,
        range_c: [f64; 2],
    ) -> Result<Self, ScheduleError> {
        Self::over(range_c, TemperatureRule::ProfileTable, |temperature_c| {
            profile.stochastic_model(temperature_c, scale)
        })
    }

    /// The model at the grid point nearest `temperature_c` (the end point outside the range).
    pub fn model_at(&self, temperature_c: f64) -> &ImuStochasticModel {
        let last = self.models.len() - 1;
        let index = ((temperature_c - self.lowest_c) / self.step_c).round();
        &self.models[(index.max(0.0) as usize).min(last)]
    }

    /// Multiplies every model's white-noise densities by `factor`.
    pub fn scale_white_noise(&mut self, factor: f64) {
        for model in &mut self.models {
            model.scale_white_noise(factor);
        }
    }

    /// Grid spacing, °C.
    pub fn step_c(&self) -> f64 {
        self.step_c
    }

    /// How the models were made.
    pub fn rule(&self) -> TemperatureRule {
        self.rule
    }

    /// Number of grid points.
    pub fn points(&self) -> usize {
        self.models.len()
    }
}

/// The model the engine uses at each covariance step.
#[derive(Debug, Clone, Copy)]
pub enum ModelSchedule<'a> {
    /// One model throughout.
    Fixed(&'a ImuStochasticModel),
    /// The grid's model at the track's temperature.
    ByTemperature {
        /// The IMU's temperature over time.
        track: &'a TemperatureTrack,
        /// The models by temperature.
        grid: &'a ModelGrid,
    },
}

impl<'a> ModelSchedule<'a> {
    /// The model at `time`.
    pub fn model_at(&self, time: Timestamp) -> &'a ImuStochasticModel {
        match *self {
            Self::Fixed(model) => model,
            Self::ByTemperature { track, grid } => grid.model_at(track.at(time)),
        }
    }
}

/// The models a run's filter carries: a schedule's models with the turn-on biases its
/// initial covariance states kept in their bias states ([`ModelSchedule::keeping_turn_on_bias`]).
#[derive(Debug, Clone)]
pub enum CarriedModels<'a> {
    /// One model throughout.
    Fixed(ImuStochasticModel),
    /// The models by temperature along a track.
    ByTemperature {
        /// The IMU's temperature over time.
        track: &'a TemperatureTrack,
        /// The carried models by temperature.
        grid: ModelGrid,
    },
}

impl CarriedModels<'_> {
    /// The schedule of these models.
    pub fn schedule(&self) -> ModelSchedule<'_> {
        match self {
            Self::Fixed(model) => ModelSchedule::Fixed(model),
            Self::ByTemperature { track, grid } => ModelSchedule::ByTemperature { track, grid },
        }
    }
}

impl<'a> ModelSchedule<'a> {
    /// The models with the turn-on biases that `p0` implies at `start` (the part of each
    /// initial bias variance above the Gauss-Markov σ² of the model at `start`:
    /// [`ImuStochasticModel::turn_on_bias_in`]) added to every model's bias states, so that
    /// the filter does not forget a bias it has not observed yet.
    pub fn keeping_turn_on_bias(&self, p0: &SystemMatrix, start: Timestamp) -> CarriedModels<'a> {
        let turn_on = self.model_at(start).turn_on_bias_in(p0);
        match *self {
            Self::Fixed(model) => CarriedModels::Fixed(model.keeping_turn_on_bias(&turn_on)),
            Self::ByTemperature { track, grid } => {
                let mut grid = grid.clone();
                for model in &mut grid.models {
                    *model = model.keeping_turn_on_bias(&turn_on);
                }
                CarriedModels::ByTemperature { track, grid }
            }
        }
    }
}

/// What a run used, for its summary.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ScheduleSummary {
    /// One model.
    Fixed {
        /// Its temperature, °C.
        temperature_c: f64,
    },
    /// Scheduled by temperature.
    Scheduled {
        /// Coldest and warmest sample temperature, °C.
        temperature_range_c: [f64; 2],
        /// How the models were made.
        rule: TemperatureRule,
        /// Grid spacing, °C.
        grid_step_c: f64,
    },
}

impl ScheduleSummary {
    /// The summary of a track with a grid.
    pub fn scheduled(track: &TemperatureTrack, grid: &ModelGrid) -> Self {
        Self::Scheduled {
            temperature_range_c: track.range_c(),
            rule: grid.rule(),
            grid_step_c: grid.step_c(),
        }
    }
}

/// What the thermal compensation of a record did.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum CompensationOutcome {
    /// bias(T) subtracted at every sample.
    Applied {
        /// Samples compensated.
        samples: usize,
        /// Samples outside a curve's fitted range (compensated with the curve's end value).
        clamped_samples: usize,
    },
    /// Turned off.
    Off,
    /// Asked for but impossible.
    NotAvailable {
        /// Why, in words.
        reason: String,
    },
}

impl CompensationOutcome {
    /// True when the record was compensated.
    pub fn applied(&self) -> bool {
        matches!(self, Self::Applied { .. })
    }
}

/// Subtracts `thermal`'s bias(T) from `series` at every sample under `compensation`; the
/// series is unchanged unless the outcome is [`CompensationOutcome::Applied`].
pub fn compensate_record(
    series: &mut ImuSeries,
    thermal: Option<&ThermalCalibration>,
    compensation: Compensation,
) -> CompensationOutcome {
    let Some(thermal) = thermal.filter(|_| compensation == Compensation::WhenCalibrated) else {
        return match compensation {
            Compensation::Off => CompensationOutcome::Off,
            Compensation::WhenCalibrated => CompensationOutcome::NotAvailable {
                reason: "the noise model has no thermal calibration".into(),
            },
        };
    };
    match thermal.compensate(series) {
        Ok(done) => CompensationOutcome::Applied {
            samples: done.samples,
            clamped_samples: done.clamped_samples,
        },
        Err(e) => CompensationOutcome::NotAvailable {
            reason: e.to_string(),
        },
    }
}
