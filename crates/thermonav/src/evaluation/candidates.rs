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
//!   campaign would configure a filter.

pub use crate::sensor::DatasheetValues;

use crate::nav::sensor_model::{
    AxisModel, BankChoice, GaussMarkovParameters, ImuStochasticModel, ScaleFactorPrior,
};
use crate::stoch::bank::{GaussMarkovSource, ModelBank, Selection};
use serde::Serialize;

/// What a candidate is.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
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
}

/// One competing model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Candidate {
    /// Label in tables and JSON.
    pub label: String,
    /// What it is.
    pub kind: CandidateKind,
    /// The model.
    pub model: ImuStochasticModel,
}

impl Candidate {
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
            | CandidateKind::Interpolated { temperature_c } => Some(temperature_c),
            CandidateKind::Pooled | CandidateKind::Datasheet => None,
        }
    }
}

/// A candidate that could not be built, and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Excluded {
    /// Label it would have had.
    pub label: String,
    /// Why it is not in the tournament.
    pub reason: String,
}

/// Label of a bank entry's candidate.
pub fn entry_label(temperature_c: f64) -> String {
    format!("bank {temperature_c:.1} °C")
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
                candidates.push(Candidate {
                    label,
                    kind: CandidateKind::Entry { temperature_c: t },
                    model,
                });
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
        Ok(model) => candidates.push(Candidate {
            label,
            kind: CandidateKind::Interpolated {
                temperature_c: operating_temperature_c,
            },
            model,
        }),
        Err(e) => excluded.push(Excluded {
            label,
            reason: e.to_string(),
        }),
    }
    match pooled(&entry_models) {
        Some(model) => candidates.push(Candidate {
            label: "pooled".into(),
            kind: CandidateKind::Pooled,
            model,
        }),
        None => excluded.push(Excluded {
            label: "pooled".into(),
            reason: "no bank entry has a usable model".into(),
        }),
    }
    if let Some(model) = datasheet {
        candidates.push(Candidate {
            label: "data sheet".into(),
            kind: CandidateKind::Datasheet,
            model: *model,
        });
    }
    (candidates, excluded)
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
