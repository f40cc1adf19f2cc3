//! The temperature model bank: one entry per temperature point, per channel, saved as JSON.
//!
//! An entry records how the static record was pre-processed (filter, decimation), the Allan
//! curve and its noise terms (from the unfiltered data), the chosen AR model, and the three
//! Gauss-Markov models: AR-based (the paper's), exact maximum likelihood on the irregular
//! timestamps, and the classical fit to the autocorrelation. The bank is a file-format contract:
//! its types are plain summaries, independent of the estimators' internal types, and carry a
//! `version`.
//!
//! Selecting a model for an operating temperature: [`Selection::Nearest`] takes the entry whose
//! temperature is closest (ties go to the colder point); [`Selection::Linear`] interpolates
//! the correlation time and sigma linearly in temperature between the two bracketing entries and
//! holds the end value outside the covered range (reported as [`Placement::Clamped`]).

use crate::imu::Channel;
use crate::stoch::gmwm::Fold;
use crate::stoch::thermal::{RecordMean, ThermalCalibration};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Version of the bank's JSON layout written by this build. Version 2 added the optional
/// `thermal` calibration; version 1 banks (without it) are read as they are.
pub const BANK_VERSION: u32 = 2;

/// Oldest layout version this build reads.
pub const OLDEST_READABLE_BANK_VERSION: u32 = 1;

/// A whole bank: entries sorted by temperature, no two at the same temperature.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelBank {
    /// Layout version ([`BANK_VERSION`]).
    pub version: u32,
    /// Entries, strictly increasing in temperature.
    pub entries: Vec<TemperatureEntry>,
    /// The unit's thermal bias calibration, when the campaign was calibrated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thermal: Option<ThermalCalibration>,
}

/// The models of one temperature point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TemperatureEntry {
    /// Temperature of the static record, °C.
    pub temperature_c: f64,
    /// Where the record came from (file name), for the report.
    pub source: String,
    /// How the record was conditioned before AR / Gauss-Markov modelling.
    pub preprocessing: Preprocessing,
    /// Models per channel.
    pub channels: BTreeMap<Channel, ChannelModel>,
    /// The record's means (the thermal calibration's observation of this record).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub record_mean: Option<RecordMean>,
    /// The IMU mounting the record was turned by into body axes as it was read (its text,
    /// `-y,x,z` or `rpy:0,0,90`, see [`crate::mounting::Mounting`]); absent when the record's
    /// axes were taken as the body's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub imu_rotation: Option<String>,
}

/// Conditioning applied before AR and Gauss-Markov modelling (Allan uses the raw data).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Preprocessing {
    /// Nominal rate of the raw record, Hz.
    pub input_rate_hz: f64,
    /// Low-pass filter, when the Kaiser filter was the de-noiser.
    pub filter: Option<FilterSummary>,
    /// Wavelet de-noising, when it was the de-noiser (absent in banks from before it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wavelet: Option<WaveletSummary>,
    /// Keep-every-n-th factor after filtering (1 = none).
    pub decimation_factor: usize,
    /// Nominal rate of the modelled series, Hz.
    pub modelling_rate_hz: f64,
}

/// A Kaiser low-pass filter as applied.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FilterSummary {
    /// Pass-band edge, Hz.
    pub cutoff_hz: f64,
    /// Transition width, Hz.
    pub transition_hz: f64,
    /// Ripple / attenuation, dB.
    pub ripple_db: f64,
    /// Number of taps.
    pub num_taps: usize,
    /// Kaiser window beta.
    pub beta: f64,
    /// Zero-phase mode (`zero-phase` or `filtfilt`).
    pub mode: String,
}

/// Wavelet de-noising as applied ([`crate::signal::wavelet::denoise`]), then every
/// `decimation_factor`-th sample kept.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WaveletSummary {
    /// The wavelet (`db1`..`db10`).
    pub wavelet: String,
    /// Decomposition level used.
    pub level: usize,
    /// Extension mode (PyWavelets' name: `symmetric` or `periodization`).
    pub mode: String,
    /// Threshold rule (`universal`, `sure` or `sure-hybrid`).
    pub threshold: String,
    /// Thresholding (`soft` or `hard`).
    pub thresholding: String,
}

/// Every model of one channel at one temperature. Values are SI: rad/s for gyros, m/s² for
/// accelerometers (the `unit` field says which).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChannelModel {
    /// Unit of `sigma` and of the Allan deviations (`rad/s` or `m/s^2`).
    pub unit: String,
    /// Allan deviation curve of the raw data and its noise terms.
    pub allan: AllanSummary,
    /// The chosen AR model of the conditioned series.
    pub ar: ArSummary,
    /// The three Gauss-Markov models.
    pub gauss_markov: GaussMarkovModels,
    /// The composite model fitted to the whole wavelet variance (GMWM), when fitted.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gmwm: Option<GmwmSummary>,
}

/// A composite noise model fitted to the raw record's Haar wavelet variance by GMWM
/// ([`crate::stoch::gmwm`]), and what the filter takes from it
/// ([`crate::stoch::gmwm::map_to_filter_states`]); its bias state is
/// [`GaussMarkovModels::gmwm`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GmwmSummary {
    /// The composite (`wn+rw+2gm`, ...).
    pub model: String,
    /// Its physical parameters by name; `unit` in a name is the channel's unit
    /// (`white_noise_density_unit_sqrt_s`, `gm1_correlation_time_s`, ...).
    pub parameters: BTreeMap<String, f64>,
    /// The minimised GMWM objective, dimensionless (about the number of scales for a model
    /// that describes the data).
    pub objective: f64,
    /// Wavelet scales fitted.
    pub scales: usize,
    /// The first scale fitted, s: later than the record's first when the shortest scales
    /// follow a sensor's internal filter ([`crate::stoch::gmwm::fit_from_first_adequate_scale`]).
    pub first_scale_s: f64,
    /// The averaging times the mapping onto the filter's states is made for, s.
    pub band_tau_s: [f64; 2],
    /// The filter's white-noise density from the composite (channel unit·√s): the white
    /// noise plus the Gauss-Markov processes shorter than the bias state.
    pub white_noise_density: f64,
    /// What became of each process, in the order of `model`.
    pub folds: Vec<Fold>,
}

/// An Allan deviation curve and the IEEE Std 952 noise terms fitted to it (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AllanSummary {
    /// Averaging times, s.
    pub tau_s: Vec<f64>,
    /// Overlapping Allan deviation at each tau, channel unit.
    pub adev: Vec<f64>,
    /// White-noise density N (ARW rad/√s or VRW m/s/√s), when identified.
    pub white_noise_density: Option<f64>,
    /// Bias instability B (rad/s or m/s²), when identified.
    pub bias_instability: Option<f64>,
    /// Rate random walk K (rad/s/√s or m/s²/√s), when identified.
    pub rate_random_walk: Option<f64>,
    /// Upper bound on B when the curve's minimum is its first or last point (the floor was not
    /// reached; `bias_instability` is then `None`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bias_instability_at_most: Option<f64>,
    /// τ range of the white-noise region, s: `[shortest, longest]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub white_noise_tau_range_s: Option<[f64; 2]>,
    /// Why a term is missing: its key (`white_noise_density`, ...) → the reason.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub absent_terms: BTreeMap<String, String>,
}

/// An AR model of the conditioned series (paper sign: x_k = Σ c_i x_{k−i} + w_k).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ArSummary {
    /// Estimator (`yule-walker`, `burg`, `covariance`, `modified-covariance`).
    pub method: String,
    /// Coefficients c_1..c_p.
    pub coefficients: Vec<f64>,
    /// Innovation variance, channel unit squared.
    pub noise_variance: f64,
    /// Sampling interval the model was fitted at, s.
    pub dt_s: f64,
}

/// The Gauss-Markov models of one channel.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GaussMarkovModels {
    /// AR(1)-based (the paper's equations 8-10).
    pub ar_based: GaussMarkovEstimate,
    /// Exact maximum likelihood with each step's own dt.
    pub irregular_ml: GaussMarkovEstimate,
    /// Classical fit of σ² exp(−τ/Tc) to the autocorrelation.
    pub acf_fit: GaussMarkovEstimate,
    /// The bias state mapped from the GMWM composite ([`ChannelModel::gmwm`]), when fitted.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gmwm: Option<GaussMarkovEstimate>,
}

/// What [`GaussMarkovModels::get`] gives for a bank without a GMWM fit.
static NO_GMWM: std::sync::LazyLock<GaussMarkovEstimate> =
    std::sync::LazyLock::new(|| GaussMarkovEstimate::NoEquivalent {
        reason: "the bank has no GMWM model (characterized with --gmwm off, or before GMWM \
                 entered the bank)"
            .into(),
    });

/// Which of the Gauss-Markov models to use (the default: the exact likelihood on the
/// irregular timestamps, see DESIGN.md).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GaussMarkovSource {
    /// AR(1)-based (the paper's).
    ArBased,
    /// Exact maximum likelihood on the irregular timestamps.
    #[default]
    IrregularMl,
    /// Fit to the autocorrelation.
    AcfFit,
    /// The bias state of the GMWM composite (and its white noise, see
    /// [`crate::stoch::gmwm::map_to_filter_states`]).
    Gmwm,
}

impl GaussMarkovSource {
    /// The snake_case name of the family, as in the bank (and Python's `family`, `model`).
    pub fn name(self) -> &'static str {
        match self {
            GaussMarkovSource::IrregularMl => "irregular_ml",
            GaussMarkovSource::ArBased => "ar_based",
            GaussMarkovSource::AcfFit => "acf_fit",
            GaussMarkovSource::Gmwm => "gmwm",
        }
    }
}

/// A Gauss-Markov estimate, or the reason there is none.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum GaussMarkovEstimate {
    /// A first-order Gauss-Markov model.
    Model {
        /// Correlation time Tc, s.
        correlation_time_s: f64,
        /// Standard deviation σ, channel unit.
        sigma: f64,
        /// 95 % interval of Tc, s; `None` for an unbounded side.
        ci95_correlation_time_s: [Option<f64>; 2],
    },
    /// No Gauss-Markov equivalent (e.g. AR c₁ ≥ 1: random walk or drift).
    NoEquivalent {
        /// Why, in words.
        reason: String,
    },
}

/// How to pick a model for an operating temperature (the default: the nearest entry).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Selection {
    /// The entry at the nearest temperature.
    #[default]
    Nearest,
    /// Linear interpolation of Tc and σ between the bracketing entries.
    Linear,
}

/// Where the operating temperature fell relative to the bank.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "placement", rename_all = "snake_case")]
pub enum Placement {
    /// One entry was used as it is.
    Entry {
        /// Its temperature, °C.
        temperature_c: f64,
    },
    /// Interpolated between two entries with weight `weight` on the upper one.
    Between {
        /// Lower entry's temperature, °C.
        lower_c: f64,
        /// Upper entry's temperature, °C.
        upper_c: f64,
        /// Weight of the upper entry, in [0, 1].
        weight: f64,
    },
    /// Outside the covered range: the end entry's model is held.
    Clamped {
        /// The end entry's temperature, °C.
        temperature_c: f64,
    },
}

/// A Gauss-Markov model selected for an operating temperature.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SelectedModel {
    /// Correlation time Tc, s.
    pub correlation_time_s: f64,
    /// Standard deviation σ, channel unit.
    pub sigma: f64,
    /// Which entries it came from.
    pub placement: Placement,
}

/// Why a bank cannot be used or a model cannot be selected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BankError {
    /// The bank has no entry.
    #[error(
        "the model bank has no temperature entry (a bank calibrated from sweeps alone holds only a thermal calibration: characterize static records for a noise model)"
    )]
    Empty,
    /// Written by a newer thermonav.
    #[error(
        "model bank version {found} is not supported (this build reads versions {OLDEST_READABLE_BANK_VERSION} to {BANK_VERSION})"
    )]
    Version {
        /// Version in the file.
        found: u32,
    },
    /// Entries not strictly increasing in temperature.
    #[error(
        "model bank entries must be strictly increasing in temperature: {previous_c} °C is followed by {next_c} °C"
    )]
    Order {
        /// Earlier entry's temperature.
        previous_c: f64,
        /// Later entry's temperature.
        next_c: f64,
    },
    /// A temperature that is not a finite number.
    #[error("temperature {temperature_c} °C is not a finite number")]
    Temperature {
        /// The value.
        temperature_c: f64,
    },
    /// A value that is not what it must be (see [`super::bank_values`]).
    #[error(
        "the entry at {temperature_c} °C, channel {channel}: {field} = {value} (expected {expected})"
    )]
    Value {
        /// Entry temperature, °C.
        temperature_c: f64,
        /// Channel name (`-` for the entry's own values).
        channel: &'static str,
        /// The field, as its JSON path inside the channel or entry.
        field: String,
        /// The value.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// An entry lacks a channel.
    #[error("the entry at {temperature_c} °C has no model for channel {channel}")]
    MissingChannel {
        /// Entry temperature.
        temperature_c: f64,
        /// Channel name.
        channel: &'static str,
    },
    /// The requested Gauss-Markov model does not exist for an entry.
    #[error(
        "the entry at {temperature_c} °C has no Gauss-Markov model for channel {channel}: {reason}"
    )]
    NoModel {
        /// Entry temperature.
        temperature_c: f64,
        /// Channel name.
        channel: &'static str,
        /// The recorded reason.
        reason: String,
    },
}

/// Checks an operating temperature, °C, before any bank is read: a finite number (a bank's
/// range is checked against the bank).
///
/// # Errors
/// [`BankError::Temperature`] for a NaN or an infinity.
pub fn check_operating_temperature(temperature_c: f64) -> Result<(), BankError> {
    if temperature_c.is_finite() {
        Ok(())
    } else {
        Err(BankError::Temperature { temperature_c })
    }
}

impl ModelBank {
    /// A bank from entries in any order.
    ///
    /// # Errors
    /// [`BankError`] when there is no entry, a temperature is not finite, or two entries share
    /// a temperature.
    pub fn new(mut entries: Vec<TemperatureEntry>) -> Result<Self, BankError> {
        entries.sort_by(|a, b| a.temperature_c.total_cmp(&b.temperature_c));
        let bank = Self {
            version: BANK_VERSION,
            entries,
            thermal: None,
        };
        bank.validate()?;
        Ok(bank)
    }

    /// Checks a bank read from a file: its layout ([`ModelBank::check_layout`]) and every
    /// entry's values ([`TemperatureEntry::check_values`]).
    ///
    /// # Errors
    /// The first [`BankError`] found.
    pub fn validate(&self) -> Result<(), BankError> {
        if self.entries.is_empty() && self.thermal.is_some() {
            return self.check_version();
        }
        self.check_layout()?;
        self.entries
            .iter()
            .try_for_each(TemperatureEntry::check_values)
    }

    /// What selecting a model relies on: a readable version, at least one entry, finite and
    /// strictly increasing temperatures. (The values a selection takes are checked again by
    /// the model built from them; the whole bank's values are checked once, on reading.)
    ///
    /// # Errors
    /// The first [`BankError`] found.
    pub fn check_layout(&self) -> Result<(), BankError> {
        self.check_version()?;
        if self.entries.is_empty() {
            return Err(BankError::Empty);
        }
        if let Some(bad) = self.entries.iter().find(|e| !e.temperature_c.is_finite()) {
            return Err(BankError::Temperature {
                temperature_c: bad.temperature_c,
            });
        }
        if let Some(w) = self
            .entries
            .windows(2)
            .find(|w| w[0].temperature_c >= w[1].temperature_c)
        {
            return Err(BankError::Order {
                previous_c: w[0].temperature_c,
                next_c: w[1].temperature_c,
            });
        }
        Ok(())
    }

    /// A readable version.
    fn check_version(&self) -> Result<(), BankError> {
        if !(OLDEST_READABLE_BANK_VERSION..=BANK_VERSION).contains(&self.version) {
            return Err(BankError::Version {
                found: self.version,
            });
        }
        Ok(())
    }

    /// A bank that holds only a thermal calibration (from temperature sweeps alone): no
    /// temperature entry, so no noise model to select.
    pub fn thermal_only(calibration: ThermalCalibration) -> Self {
        Self {
            version: BANK_VERSION,
            entries: Vec::new(),
            thermal: Some(calibration),
        }
    }

    /// The bank with `thermal` for its thermal calibration (another bank's: `--thermal-from`),
    /// when it covers the channels of the bank's entries in their units.
    ///
    /// # Errors
    /// [`ThermalJoinError`](crate::stoch::thermal::join::ThermalJoinError) naming the channels or the unit that differ.
    pub fn with_thermal_from(
        mut self,
        thermal: ThermalCalibration,
    ) -> Result<Self, crate::stoch::thermal::join::ThermalJoinError> {
        let units = self
            .entries
            .first()
            .map(|e| {
                e.channels
                    .iter()
                    .map(|(&c, m)| (c, m.unit.clone()))
                    .collect()
            })
            .unwrap_or_default();
        crate::stoch::thermal::join::check_join(&units, &thermal)?;
        self.thermal = Some(thermal);
        Ok(self)
    }

    /// Temperatures of the entries, °C, increasing.
    pub fn temperatures_c(&self) -> Vec<f64> {
        self.entries.iter().map(|e| e.temperature_c).collect()
    }

    /// Index of the entry nearest to `temperature_c` (ties to the colder entry).
    pub fn nearest_index(&self, temperature_c: f64) -> usize {
        let distance = |e: &TemperatureEntry| (e.temperature_c - temperature_c).abs();
        (0..self.entries.len())
            .min_by(|&a, &b| distance(&self.entries[a]).total_cmp(&distance(&self.entries[b])))
            .unwrap_or(0)
    }

    /// The Gauss-Markov model of `channel` for an operating temperature.
    ///
    /// # Errors
    /// [`BankError`] when the temperature is not finite, an entry involved lacks the channel,
    /// or its model of that `source` has no Gauss-Markov equivalent.
    pub fn select(
        &self,
        temperature_c: f64,
        channel: Channel,
        source: GaussMarkovSource,
        selection: Selection,
    ) -> Result<SelectedModel, BankError> {
        check_operating_temperature(temperature_c)?;
        self.check_layout()?;
        let placement = self.placement(temperature_c, selection);
        match placement {
            Placement::Entry { temperature_c: t } | Placement::Clamped { temperature_c: t } => {
                let (tc, sigma) = self.model_at(self.index_of(t), channel, source)?;
                Ok(SelectedModel {
                    correlation_time_s: tc,
                    sigma,
                    placement,
                })
            }
            Placement::Between {
                lower_c,
                upper_c,
                weight,
            } => {
                let (tc_lo, s_lo) = self.model_at(self.index_of(lower_c), channel, source)?;
                let (tc_hi, s_hi) = self.model_at(self.index_of(upper_c), channel, source)?;
                Ok(SelectedModel {
                    correlation_time_s: lerp(tc_lo, tc_hi, weight),
                    sigma: lerp(s_lo, s_hi, weight),
                    placement,
                })
            }
        }
    }

    /// Where `temperature_c` falls, for the chosen selection.
    pub fn placement(&self, temperature_c: f64, selection: Selection) -> Placement {
        let temps = self.temperatures_c();
        let (first, last) = (temps[0], temps[temps.len() - 1]);
        match selection {
            Selection::Nearest => Placement::Entry {
                temperature_c: temps[self.nearest_index(temperature_c)],
            },
            Selection::Linear if temperature_c <= first => Placement::Clamped {
                temperature_c: first,
            },
            Selection::Linear if temperature_c >= last => Placement::Clamped {
                temperature_c: last,
            },
            Selection::Linear => bracket(&temps, temperature_c),
        }
    }

    fn index_of(&self, temperature_c: f64) -> usize {
        self.entries
            .iter()
            .position(|e| e.temperature_c == temperature_c)
            .unwrap_or(0)
    }

    fn model_at(
        &self,
        index: usize,
        channel: Channel,
        source: GaussMarkovSource,
    ) -> Result<(f64, f64), BankError> {
        let entry = &self.entries[index];
        let model = entry
            .channels
            .get(&channel)
            .ok_or(BankError::MissingChannel {
                temperature_c: entry.temperature_c,
                channel: channel.name(),
            })?;
        match model.gauss_markov.get(source) {
            GaussMarkovEstimate::Model {
                correlation_time_s,
                sigma,
                ..
            } => Ok((*correlation_time_s, *sigma)),
            GaussMarkovEstimate::NoEquivalent { reason } => Err(BankError::NoModel {
                temperature_c: entry.temperature_c,
                channel: channel.name(),
                reason: reason.clone(),
            }),
        }
    }
}

impl GaussMarkovModels {
    /// The estimate of one source.
    pub fn get(&self, source: GaussMarkovSource) -> &GaussMarkovEstimate {
        match source {
            GaussMarkovSource::ArBased => &self.ar_based,
            GaussMarkovSource::IrregularMl => &self.irregular_ml,
            GaussMarkovSource::AcfFit => &self.acf_fit,
            GaussMarkovSource::Gmwm => self.gmwm.as_ref().unwrap_or(&NO_GMWM),
        }
    }
}

/// The two temperatures around `t` (strictly inside the range) and the upper weight.
fn bracket(temps: &[f64], t: f64) -> Placement {
    let upper = temps.partition_point(|&x| x <= t).min(temps.len() - 1);
    let (lower_c, upper_c) = (temps[upper - 1], temps[upper]);
    if t == lower_c {
        return Placement::Entry {
            temperature_c: lower_c,
        };
    }
    Placement::Between {
        lower_c,
        upper_c,
        weight: (t - lower_c) / (upper_c - lower_c),
    }
}

fn lerp(a: f64, b: f64, weight: f64) -> f64 {
    a + (b - a) * weight
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_familys_name_is_its_name_in_the_bank() {
        use GaussMarkovSource::*;
        for family in [ArBased, IrregularMl, AcfFit, Gmwm] {
            assert_eq!(serde_json::to_value(family).unwrap(), family.name());
        }
    }

    #[test]
    fn an_operating_temperature_must_be_finite() {
        for ok in [-40.0, 0.0, 85.0, f64::MAX] {
            assert_eq!(check_operating_temperature(ok), Ok(()));
        }
        for bad in [f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(
                check_operating_temperature(bad),
                Err(BankError::Temperature { temperature_c: bad })
            );
        }
        assert!(matches!(
            check_operating_temperature(f64::NAN),
            Err(BankError::Temperature { temperature_c }) if temperature_c.is_nan()
        ));
    }

    fn gm(tc: f64, sigma: f64) -> GaussMarkovEstimate {
        GaussMarkovEstimate::Model {
            correlation_time_s: tc,
            sigma,
            ci95_correlation_time_s: [Some(tc * 0.9), None],
        }
    }

    fn entry(temperature_c: f64, tc: f64, sigma: f64) -> TemperatureEntry {
        let model = ChannelModel {
            unit: "rad/s".into(),
            allan: AllanSummary {
                tau_s: vec![1.0],
                adev: vec![1e-3],
                white_noise_density: Some(1e-3),
                bias_instability: None,
                rate_random_walk: None,
                bias_instability_at_most: None,
                white_noise_tau_range_s: None,
                absent_terms: BTreeMap::new(),
            },
            ar: ArSummary {
                method: "burg".into(),
                coefficients: vec![0.9],
                noise_variance: 1e-6,
                dt_s: 0.1,
            },
            gauss_markov: GaussMarkovModels {
                ar_based: gm(tc, sigma),
                irregular_ml: gm(tc * 2.0, sigma),
                acf_fit: GaussMarkovEstimate::NoEquivalent {
                    reason: "c1 >= 1".into(),
                },
                gmwm: None,
            },
            gmwm: None,
        };
        TemperatureEntry {
            temperature_c,
            source: format!("{temperature_c}.csv"),
            preprocessing: Preprocessing {
                input_rate_hz: 200.0,
                filter: None,
                wavelet: None,
                decimation_factor: 1,
                modelling_rate_hz: 200.0,
            },
            channels: BTreeMap::from([(Channel::Gx, model)]),
            record_mean: None,
            imu_rotation: None,
        }
    }

    fn bank() -> ModelBank {
        ModelBank::new(vec![
            entry(20.0, 200.0, 2.0),
            entry(-20.0, 100.0, 1.0),
            entry(60.0, 50.0, 4.0),
        ])
        .unwrap()
    }

    fn pick(t: f64, selection: Selection) -> Result<SelectedModel, BankError> {
        bank().select(t, Channel::Gx, GaussMarkovSource::ArBased, selection)
    }

    #[test]
    fn entries_are_sorted_and_duplicates_refused() {
        assert_eq!(bank().temperatures_c(), vec![-20.0, 20.0, 60.0]);
        let twice = ModelBank::new(vec![entry(20.0, 1.0, 1.0), entry(20.0, 2.0, 1.0)]);
        assert!(matches!(twice, Err(BankError::Order { .. })));
        assert_eq!(ModelBank::new(vec![]), Err(BankError::Empty));
    }

    #[test]
    fn nearest_picks_the_closest_entry_and_ties_go_colder() {
        assert_eq!(
            pick(17.0, Selection::Nearest).unwrap().correlation_time_s,
            200.0
        );
        assert_eq!(
            pick(0.0, Selection::Nearest).unwrap().correlation_time_s,
            100.0
        );
        assert_eq!(
            pick(100.0, Selection::Nearest).unwrap().correlation_time_s,
            50.0
        );
    }

    #[test]
    fn linear_interpolates_tc_and_sigma_between_neighbours() {
        // 30 °C is a quarter of the way from 20 to 60: Tc = 200 + 0.25 (50 − 200) = 162.5,
        // sigma = 2 + 0.25 (4 − 2) = 2.5.
        let m = pick(30.0, Selection::Linear).unwrap();
        assert!((m.correlation_time_s - 162.5).abs() < 1e-12);
        assert!((m.sigma - 2.5).abs() < 1e-12);
        assert_eq!(
            m.placement,
            Placement::Between {
                lower_c: 20.0,
                upper_c: 60.0,
                weight: 0.25
            }
        );
        assert_eq!(
            pick(20.0, Selection::Linear).unwrap().placement,
            Placement::Entry {
                temperature_c: 20.0
            }
        );
    }

    #[test]
    fn linear_holds_the_end_value_outside_the_range() {
        let m = pick(-40.0, Selection::Linear).unwrap();
        assert_eq!(
            (m.correlation_time_s, m.placement),
            (
                100.0,
                Placement::Clamped {
                    temperature_c: -20.0
                }
            )
        );
        assert_eq!(
            pick(80.0, Selection::Linear).unwrap().correlation_time_s,
            50.0
        );
    }

    #[test]
    fn missing_models_and_bad_temperatures_are_errors() {
        let b = bank();
        let acf = b.select(
            20.0,
            Channel::Gx,
            GaussMarkovSource::AcfFit,
            Selection::Nearest,
        );
        assert!(matches!(acf, Err(BankError::NoModel { .. })));
        let gy = b.select(
            20.0,
            Channel::Gy,
            GaussMarkovSource::ArBased,
            Selection::Nearest,
        );
        assert!(matches!(gy, Err(BankError::MissingChannel { .. })));
        assert!(matches!(
            pick(f64::NAN, Selection::Linear),
            Err(BankError::Temperature { .. })
        ));
    }

    #[test]
    fn json_round_trip_keeps_everything_and_names_the_status() {
        let b = bank();
        let text = serde_json::to_string(&b).unwrap();
        assert!(text.contains("\"version\":2") && text.contains("\"status\":\"no_equivalent\""));
        assert!(text.contains("\"gx\""));
        let back: ModelBank = serde_json::from_str(&text).unwrap();
        assert_eq!(back, b);
        let newer = text.replace("\"version\":2", "\"version\":9");
        let newer: ModelBank = serde_json::from_str(&newer).unwrap();
        assert_eq!(newer.validate(), Err(BankError::Version { found: 9 }));
        // A version-1 bank (no thermal calibration) is still read.
        let older: ModelBank =
            serde_json::from_str(&text.replace("\"version\":2", "\"version\":1")).unwrap();
        assert_eq!(older.validate(), Ok(()));
        assert_eq!(older.thermal, None);
    }
}
