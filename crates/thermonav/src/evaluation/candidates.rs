//! The models that compete in a tournament.
//!
//! - one per bank entry (the model "of temperature T");
//! - the bank interpolated linearly at the operating temperature;
//! - **pooled**: a temperature-blind model, per axis the geometric mean of the entries'
//!   correlation times and the RMS of their σ and white-noise densities (what one gets by
//!   ignoring temperature and averaging the campaign);
//! - **data sheet**: the manufacturer's angle/velocity random walk and in-run bias stability,
//!   with σ = stability / 0.62 (the peak of a Gauss-Markov process's Allan deviation is
//!   ≈ 0.62 σ) and a stated correlation time (1 h unless given), as a user without a chamber
//!   campaign would configure a filter;
//! - **thermal** ([`thermal_candidates`]), when the IMU record has temperatures: the entry
//!   nearest the operating temperature on the record compensated with the bank's thermal
//!   calibration, the bank scheduled by temperature (linear interpolation at every covariance
//!   step), and the scheduled bank on the compensated record (the compensated ones only when
//!   the bank holds a calibration);
//! - **oracle** ([`oracle_candidates`]), when the caller has the simulator's truth: the true
//!   model scheduled, on the raw record, on the record without the true bias(T), and on the
//!   record compensated with the bank's own calibration (what the true noise models add when
//!   the compensation is ours: the bound of a claim about scheduling on that record);
//! - **profile** ([`profile_candidates`]), for a sensor without a chamber campaign: a sensor
//!   profile's model at each of its table temperatures and at the operating temperature, and
//!   the profile scheduled by temperature.

pub use crate::sensor::DatasheetValues;

use super::oracle::TrueModel;
use crate::nav::alignment::InitialUncertainty;
use crate::nav::run::{NoiseModel, initial_uncertainty_of};
use crate::nav::schedule::{Compensation, ModelGrid, Scheduling, TemperatureRule};
use crate::nav::sensor_model::{
    AxisModel, BankChoice, GaussMarkovParameters, ImuStochasticModel, ScaleFactorPrior,
    SensorModelError,
};
use crate::sensor::SensorProfile;
use crate::stoch::bank::{GaussMarkovSource, ModelBank, Selection};
use serde::Serialize;
use std::sync::Arc;

/// What a candidate is.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum CandidateKind {
    /// A bank entry's model.
    Entry {
        /// Entry temperature, °C.
        temperature_c: f64,
    },
    /// The bank interpolated at the operating temperature.
    Interpolated {
        /// Operating temperature, °C.
        temperature_c: f64,
    },
    /// The temperature-blind mean of the bank.
    Pooled,
    /// Data-sheet values.
    Datasheet,
    /// A bank entry's model on the thermally compensated record.
    CompensatedEntry {
        /// Entry temperature, °C.
        temperature_c: f64,
    },
    /// Models scheduled by the IMU's temperature.
    Scheduled {
        /// How the models are made from a temperature.
        rule: TemperatureRule,
    },
    /// Models scheduled by the IMU's temperature, on the thermally compensated record.
    ScheduledCompensated {
        /// How the models are made from a temperature.
        rule: TemperatureRule,
    },
    /// A sensor profile's model at one temperature.
    Profile {
        /// The temperature, °C.
        temperature_c: f64,
    },
    /// The simulator's true model scheduled by temperature (see [`super::oracle`]).
    Oracle,
    /// The true model scheduled, on the record with the true repeatable bias subtracted.
    OracleCompensated,
    /// The true model scheduled, on the record compensated with the bank's thermal
    /// calibration (as the compensated candidates run).
    OracleOnCalibrated,
    /// A trajectory computed by another tool, scored beside the candidates (see
    /// [`super::outside`]); not a model of ours, so it is not ranked.
    Outside,
}

/// Which IMU record a candidate runs on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Record {
    /// The record as read.
    Raw,
    /// The record with the thermal calibration's bias(T) subtracted.
    Compensated,
    /// The record with the true repeatable bias(T) subtracted (the oracle's).
    OracleCompensated,
}

/// One competing model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Candidate {
    /// Label in tables and JSON.
    pub label: String,
    /// What it is.
    pub kind: CandidateKind,
    /// The model (of a scheduled candidate: the model at the operating temperature, for
    /// reference only).
    pub model: ImuStochasticModel,
    /// Models by temperature, for a scheduled candidate.
    #[serde(skip)]
    pub schedule: Option<Arc<ModelGrid>>,
    /// The record it runs on.
    pub record: Record,
    /// Its initial uncertainty before a still start tightens it: what `integrate` starts
    /// from with this model on this record ([`crate::nav::run::initial_uncertainty_of`]; set
    /// for a tournament's plan by [`with_initial_uncertainty`], the default until then).
    #[serde(skip)]
    pub initial: InitialUncertainty,
}

impl Candidate {
    /// A fixed model on the raw record.
    pub fn fixed(label: impl Into<String>, kind: CandidateKind, model: ImuStochasticModel) -> Self {
        Self {
            label: label.into(),
            kind,
            model,
            schedule: None,
            record: Record::Raw,
            initial: InitialUncertainty::default(),
        }
    }

    /// The temperature a candidate stands for, if any.
    pub fn temperature_c(&self) -> Option<f64> {
        self.kind.temperature_c()
    }
}

impl CandidateKind {
    /// The temperature a candidate of this kind stands for, if any.
    pub fn temperature_c(self) -> Option<f64> {
        match self {
            CandidateKind::Entry { temperature_c }
            | CandidateKind::Interpolated { temperature_c }
            | CandidateKind::CompensatedEntry { temperature_c }
            | CandidateKind::Profile { temperature_c } => Some(temperature_c),
            CandidateKind::Pooled
            | CandidateKind::Datasheet
            | CandidateKind::Scheduled { .. }
            | CandidateKind::ScheduledCompensated { .. }
            | CandidateKind::Oracle
            | CandidateKind::OracleCompensated
            | CandidateKind::OracleOnCalibrated
            | CandidateKind::Outside => None,
        }
    }

    /// True for the oracle, which no user can configure: it is ranked apart.
    pub fn is_oracle(self) -> bool {
        matches!(
            self,
            CandidateKind::Oracle
                | CandidateKind::OracleCompensated
                | CandidateKind::OracleOnCalibrated
        )
    }

    /// True for the baselines that answer no temperature question (pooled, data sheet).
    pub fn is_baseline(self) -> bool {
        matches!(self, CandidateKind::Pooled | CandidateKind::Datasheet)
    }
}

/// `candidates` with each one's [`Candidate::initial`]: what `integrate` starts from with its
/// model, under `noise`, on its record (compensated with the noise model's thermal calibration
/// for a compensated candidate and the oracle's, whose record holds the unit's own bias curve
/// too).
pub fn with_initial_uncertainty(candidates: &mut [Candidate], noise: NoiseModel) {
    for candidate in candidates {
        let compensated = candidate.record != Record::Raw;
        candidate.initial = initial_uncertainty_of(noise, compensated, &candidate.model).0;
    }
}

/// A candidate that could not be built, and why.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct Excluded {
    /// Label it would have had.
    pub label: String,
    /// Why it is not in the tournament.
    pub reason: String,
}

/// Label of a bank entry's candidate, to 0.1 °C (an entry measured at −0.04 °C is
/// "bank 0.0 °C", not "bank -0.0 °C").
pub fn entry_label(temperature_c: f64) -> String {
    let rounded = (temperature_c * 10.0).round() / 10.0 + 0.0;
    format!("bank {rounded:.1} °C")
}

/// The candidates of a bank at an operating temperature with one Gauss-Markov family, plus
/// the data-sheet model when given (from [`DatasheetValues::model`], or a profile's model at
/// its reference temperature); entries without a usable model are listed as excluded.
pub fn tournament_candidates(
    bank: &ModelBank,
    operating_temperature_c: f64,
    source: GaussMarkovSource,
    scale: &ScaleFactorPrior,
    datasheet: Option<&ImuStochasticModel>,
) -> (Vec<Candidate>, Vec<Excluded>) {
    let mut candidates = Vec::new();
    let mut excluded = Vec::new();
    let choice = |temperature_c, selection| BankChoice {
        temperature_c,
        selection,
        source,
    };
    let mut entry_models = Vec::new();
    for t in bank.temperatures_c() {
        let label = entry_label(t);
        match ImuStochasticModel::from_bank(bank, &choice(t, Selection::Nearest), scale) {
            Ok(model) => {
                entry_models.push(model);
                let kind = CandidateKind::Entry { temperature_c: t };
                candidates.push(Candidate::fixed(label, kind, model));
            }
            Err(e) => excluded.push(Excluded {
                label,
                reason: e.to_string(),
            }),
        }
    }
    let label = format!("interpolated {operating_temperature_c:.1} °C");
    match ImuStochasticModel::from_bank(
        bank,
        &choice(operating_temperature_c, Selection::Linear),
        scale,
    ) {
        Ok(model) => candidates.push(Candidate::fixed(
            label,
            CandidateKind::Interpolated {
                temperature_c: operating_temperature_c,
            },
            model,
        )),
        Err(e) => excluded.push(Excluded {
            label,
            reason: e.to_string(),
        }),
    }
    match pooled(&entry_models) {
        Some(model) => candidates.push(Candidate::fixed("pooled", CandidateKind::Pooled, model)),
        None => excluded.push(Excluded {
            label: "pooled".into(),
            reason: "no bank entry has a usable model".into(),
        }),
    }
    if let Some(model) = datasheet {
        candidates.push(Candidate::fixed(
            "data sheet",
            CandidateKind::Datasheet,
            *model,
        ));
    }
    (candidates, excluded)
}

/// The data-sheet candidate's model: a profile's model at its reference temperature, or the
/// ADIS16364 data sheet.
///
/// # Errors
/// A profile whose model cannot be built at its reference temperature.
pub fn datasheet_model(
    profile: Option<&SensorProfile>,
    scale: &ScaleFactorPrior,
) -> Result<ImuStochasticModel, SensorModelError> {
    match profile {
        Some(p) => p.stochastic_model(p.reference_temperature_c, scale),
        None => Ok(DatasheetValues::adis16364().model(scale)),
    }
}

/// What the thermal and profile candidates need to know of the record, and the switches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermalOptions {
    /// Coldest and warmest IMU temperature, °C; `None` when the record has no temp_c (no
    /// scheduled or compensated candidate then).
    pub imu_temperature_range_c: Option<[f64; 2]>,
    /// Whether scheduled candidates compete.
    pub scheduling: Scheduling,
    /// Whether compensated candidates compete (when the bank holds a calibration).
    pub compensation: Compensation,
}

impl ThermalOptions {
    /// The options for a scenario: its record's temperature range, and the switches.
    pub fn of_scenario(
        scenario: &super::scenario::Scenario,
        scheduling: Scheduling,
        compensation: Compensation,
    ) -> Self {
        Self {
            imu_temperature_range_c: scenario.temperature.as_ref().map(|t| t.range_c()),
            scheduling,
            compensation,
        }
    }

    /// The record's range when `scheduling` lets the scheduled candidates in.
    fn scheduled_range_c(&self) -> Option<[f64; 2]> {
        self.imu_temperature_range_c
            .filter(|_| self.scheduling == Scheduling::ByTemperature)
    }

    /// True when a bank with a calibration `calibrated` gives compensated candidates.
    fn compensates(&self, calibrated: bool) -> bool {
        calibrated
            && self.imu_temperature_range_c.is_some()
            && self.compensation == Compensation::WhenCalibrated
    }
}

/// Candidates and the ones that could not be built.
#[derive(Debug, Default)]
struct Field {
    candidates: Vec<Candidate>,
    excluded: Vec<Excluded>,
}

impl Field {
    fn push(&mut self, label: String, built: Result<Candidate, String>) {
        match built {
            Ok(candidate) => self.candidates.push(candidate),
            Err(reason) => self.excluded.push(Excluded { label, reason }),
        }
    }

    fn into_parts(self) -> (Vec<Candidate>, Vec<Excluded>) {
        (self.candidates, self.excluded)
    }
}

/// A scheduled candidate on `record` from a grid, labelled, with the grid's model at the
/// operating temperature for reference.
fn scheduled(
    label: &str,
    grid: &Arc<ModelGrid>,
    record: Record,
    operating_temperature_c: f64,
) -> Candidate {
    let rule = grid.rule();
    let kind = match record {
        Record::Raw => CandidateKind::Scheduled { rule },
        Record::Compensated => CandidateKind::ScheduledCompensated { rule },
        Record::OracleCompensated => CandidateKind::OracleCompensated,
    };
    Candidate {
        label: label.into(),
        kind,
        model: *grid.model_at(operating_temperature_c),
        schedule: Some(Arc::clone(grid)),
        record,
        initial: InitialUncertainty::default(),
    }
}

/// The bank's thermal candidates (module docs): the entry nearest the operating temperature
/// on the compensated record, the bank scheduled with linear interpolation, and scheduled on
/// the compensated record, as `options` and the bank allow.
pub fn thermal_candidates(
    bank: &ModelBank,
    operating_temperature_c: f64,
    source: GaussMarkovSource,
    scale: &ScaleFactorPrior,
    options: &ThermalOptions,
) -> (Vec<Candidate>, Vec<Excluded>) {
    let mut field = Field::default();
    let compensates = options.compensates(bank.thermal.is_some());
    if let (true, Some(t)) = (compensates, nearest_entry_c(bank, operating_temperature_c)) {
        let label = format!("{} compensated", entry_label(t));
        field.push(label, compensated_entry(bank, t, source, scale));
    }
    if let Some(range_c) = options.scheduled_range_c() {
        let grid = ModelGrid::from_bank(bank, Selection::Linear, source, scale, range_c)
            .map(Arc::new)
            .map_err(|e| e.to_string());
        let (raw, compensated) = ("scheduled linear", "scheduled linear compensated");
        let make = |label, record| {
            grid.as_ref()
                .map(|g| scheduled(label, g, record, operating_temperature_c))
                .map_err(Clone::clone)
        };
        field.push(raw.into(), make(raw, Record::Raw));
        if compensates {
            field.push(compensated.into(), make(compensated, Record::Compensated));
        }
    }
    field.into_parts()
}

/// The oracle's candidates over the record's temperature range `range_c`: the true model
/// scheduled on the raw record, on the record with the true repeatable bias subtracted, and
/// on the record compensated with the bank's calibration (the caller keeps the last two only
/// where those records are made).
pub fn oracle_candidates(
    truth: &TrueModel,
    range_c: [f64; 2],
    operating_temperature_c: f64,
) -> (Vec<Candidate>, Vec<Excluded>) {
    let mut field = Field::default();
    let grid = truth.grid(range_c).map(Arc::new).map_err(|e| e.to_string());
    let runs = [
        ("truth scheduled", CandidateKind::Oracle, Record::Raw),
        (
            "truth scheduled compensated",
            CandidateKind::OracleCompensated,
            Record::OracleCompensated,
        ),
        (
            "truth scheduled on calibrated",
            CandidateKind::OracleOnCalibrated,
            Record::Compensated,
        ),
    ];
    for (label, kind, record) in runs {
        let built = grid.as_ref().map_err(Clone::clone).map(|g| Candidate {
            label: label.into(),
            kind,
            model: *g.model_at(operating_temperature_c),
            schedule: Some(Arc::clone(g)),
            record,
            initial: InitialUncertainty::default(),
        });
        field.push(label.into(), built);
    }
    field.into_parts()
}

/// The bank temperature nearest `temperature_c`, °C.
fn nearest_entry_c(bank: &ModelBank, temperature_c: f64) -> Option<f64> {
    let distance = |t: &f64| (t - temperature_c).abs();
    bank.temperatures_c()
        .into_iter()
        .min_by(|a, b| distance(a).total_cmp(&distance(b)))
}

/// The entry at `temperature_c` on the compensated record.
fn compensated_entry(
    bank: &ModelBank,
    temperature_c: f64,
    source: GaussMarkovSource,
    scale: &ScaleFactorPrior,
) -> Result<Candidate, String> {
    let choice = BankChoice {
        temperature_c,
        selection: Selection::Nearest,
        source,
    };
    let model = ImuStochasticModel::from_bank(bank, &choice, scale).map_err(|e| e.to_string())?;
    Ok(Candidate {
        record: Record::Compensated,
        ..Candidate::fixed(
            format!("{} compensated", entry_label(temperature_c)),
            CandidateKind::CompensatedEntry { temperature_c },
            model,
        )
    })
}

/// A sensor profile's candidates (module docs): its model at each table temperature and at
/// the operating temperature, and scheduled by temperature as `options` allow; the data-sheet
/// model when given.
pub fn profile_candidates(
    profile: &SensorProfile,
    operating_temperature_c: f64,
    scale: &ScaleFactorPrior,
    options: &ThermalOptions,
    datasheet: Option<&ImuStochasticModel>,
) -> (Vec<Candidate>, Vec<Excluded>) {
    let mut field = Field::default();
    for t in profile_temperatures_c(profile, operating_temperature_c) {
        let label = format!("profile {t:.1} °C");
        let built = profile
            .stochastic_model(t, scale)
            .map(|m| Candidate::fixed(&label, CandidateKind::Profile { temperature_c: t }, m))
            .map_err(|e| e.to_string());
        field.push(label, built);
    }
    if let Some(range_c) = options.scheduled_range_c() {
        let label = "profile scheduled";
        let built = ModelGrid::from_profile(profile, scale, range_c)
            .map(|g| scheduled(label, &Arc::new(g), Record::Raw, operating_temperature_c))
            .map_err(|e| e.to_string());
        field.push(label.into(), built);
    }
    if let Some(model) = datasheet {
        let kind = CandidateKind::Datasheet;
        field.push(
            "data sheet".into(),
            Ok(Candidate::fixed("data sheet", kind, *model)),
        );
    }
    field.into_parts()
}

/// The temperatures of a profile's Gauss-Markov tables and the operating temperature, °C,
/// increasing, each once.
fn profile_temperatures_c(profile: &SensorProfile, operating_temperature_c: f64) -> Vec<f64> {
    let mut temperatures: Vec<f64> = profile
        .channels
        .values()
        .flat_map(|c| c.bias_gauss_markov.iter().map(|p| p.temperature_c))
        .chain([operating_temperature_c])
        .collect();
    temperatures.sort_by(f64::total_cmp);
    temperatures.dedup();
    temperatures
}

/// The temperature-blind model: per axis, geometric mean of Tc, RMS of σ and of the white
/// density over `models`; `None` for an empty list.
pub fn pooled(models: &[ImuStochasticModel]) -> Option<ImuStochasticModel> {
    if models.is_empty() {
        return None;
    }
    let n = models.len() as f64;
    let axis = |pick: &dyn Fn(&ImuStochasticModel) -> AxisModel| {
        let axes: Vec<AxisModel> = models.iter().map(pick).collect();
        let rms = |f: &dyn Fn(&AxisModel) -> f64| {
            (axes.iter().map(|a| f(a).powi(2)).sum::<f64>() / n).sqrt()
        };
        let ln_mean_tc = axes
            .iter()
            .map(|a| a.bias.correlation_time_s.ln())
            .sum::<f64>()
            / n;
        AxisModel {
            white_noise_density: rms(&|a| a.white_noise_density),
            bias: GaussMarkovParameters {
                correlation_time_s: ln_mean_tc.exp(),
                sigma: rms(&|a| a.bias.sigma),
            },
            scale_factor: axes[0].scale_factor,
        }
    };
    Some(ImuStochasticModel {
        gyro: std::array::from_fn(|k| axis(&|m| m.gyro[k])),
        accel: std::array::from_fn(|k| axis(&|m| m.accel[k])),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entry_labels_have_no_negative_zero() {
        assert_eq!(entry_label(-0.042), "bank 0.0 °C");
        assert_eq!(entry_label(-39.966), "bank -40.0 °C");
        assert_eq!(entry_label(20.0029), "bank 20.0 °C");
    }

    // Closed forms: pooling two models with Tc 100 s and 400 s gives 200 s (geometric mean);
    // σ 3 and 4 give √12.5 (RMS). The data-sheet σ is the stability over 0.62.
    #[test]
    fn pooling_and_datasheet_follow_their_formulas() {
        let ds = DatasheetValues::adis16364();
        let scale = ScaleFactorPrior::default();
        let mut a = ds.model(&scale);
        let mut b = a;
        for axis in a.gyro.iter_mut().chain(a.accel.iter_mut()) {
            axis.bias = GaussMarkovParameters {
                correlation_time_s: 100.0,
                sigma: 3.0,
            };
        }
        for axis in b.gyro.iter_mut().chain(b.accel.iter_mut()) {
            axis.bias = GaussMarkovParameters {
                correlation_time_s: 400.0,
                sigma: 4.0,
            };
        }
        let p = pooled(&[a, b]).unwrap();
        assert!((p.gyro[1].bias.correlation_time_s - 200.0).abs() < 1e-9);
        assert!((p.accel[2].bias.sigma - 12.5f64.sqrt()).abs() < 1e-12);
        let gyro = ds.model(&scale).gyro[0];
        assert!((gyro.bias.sigma - 0.007f64.to_radians() / 0.62).abs() < 1e-15);
        assert!((gyro.white_noise_density - 2f64.to_radians() / 60.0).abs() < 1e-15);
        assert!(pooled(&[]).is_none());
    }
}
