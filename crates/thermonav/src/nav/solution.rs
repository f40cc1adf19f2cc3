//! What a navigation run returns: solution epochs with standard deviations and sensor
//! estimates, every innovation, and their statistics.

use super::error_state::Estimate;
use super::measurement::MeasurementKind;
use crate::ins::error_model::STATES;
use crate::time::Timestamp;
use serde::Serialize;
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// One output epoch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolutionEpoch {
    /// The estimate.
    pub estimate: Estimate,
    /// Standard deviations of the 21 error states (SI units of each state).
    pub sd: [f64; STATES],
    /// True when GNSS was withheld at this epoch (inside an outage).
    pub in_outage: bool,
}

/// One measurement update (accepted or rejected).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct InnovationRecord {
    /// Epoch.
    #[serde(skip)]
    pub time: Timestamp,
    /// Measurement kind.
    pub kind: MeasurementKind,
    /// Innovation z − ẑ (measured minus predicted): m, m/s or rad; unused entries 0.
    pub innovation: [f64; 3],
    /// Square roots of the diagonal of the innovation covariance S, same units.
    pub sd: [f64; 3],
    /// Normalised innovation squared νᵀ S⁻¹ ν.
    pub nis: f64,
    /// The factor the gate's chi-square quantile was widened by for this update, from the
    /// recent NIS level (1 = the plain gate; see [`crate::filter::gating::ScaledGate`]).
    pub gate_scale: f64,
    /// False when the chi-square gate rejected it.
    pub accepted: bool,
    /// True when it failed the gate but was applied after too many rejections in a row.
    pub forced: bool,
}

/// Statistics of one measurement kind over a run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct InnovationStatistics {
    /// Measurement kind.
    pub kind: MeasurementKind,
    /// Degrees of freedom of each NIS.
    pub dimension: usize,
    /// Updates offered (outside outages).
    pub offered: usize,
    /// Updates the gate rejected.
    pub rejected: usize,
    /// Updates that failed the gate but were applied to recover from a run of rejections.
    pub forced: usize,
    /// Mean NIS over accepted updates (its expectation is `dimension` for a consistent filter).
    pub mean_nis: f64,
    /// Fraction of accepted NIS inside the two-sided 95 % chi-square interval.
    pub fraction_nis_in_95: f64,
    /// RMS of each innovation component over accepted updates, m, m/s or rad.
    pub rms_innovation: [f64; 3],
    /// Mean factor the gate's quantile was widened by, over offered updates (1 = never).
    pub mean_gate_scale: f64,
}

/// Everything a run produces.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Output epochs.
    pub epochs: Vec<SolutionEpoch>,
    /// Every update attempted.
    pub innovations: Vec<InnovationRecord>,
    /// IMU samples processed.
    pub imu_samples: usize,
    /// The RTS-smoothed solution at every covariance step ([`super::smoother`]); empty
    /// unless [`super::engine::EngineSettings::smooth`] was set.
    pub smoothed: Vec<SolutionEpoch>,
}

impl Solution {
    /// Statistics per measurement kind present in the run.
    pub fn innovation_statistics(&self) -> Vec<InnovationStatistics> {
        MeasurementKind::ALL
            .into_iter()
            .filter_map(|kind| statistics_of(kind, &self.innovations))
            .collect()
    }
}

fn statistics_of(
    kind: MeasurementKind,
    records: &[InnovationRecord],
) -> Option<InnovationStatistics> {
    let of_kind: Vec<_> = records.iter().filter(|r| r.kind == kind).collect();
    if of_kind.is_empty() {
        return None;
    }
    let accepted: Vec<_> = of_kind.iter().filter(|r| r.accepted).collect();
    let dimension = kind.dimension();
    let chi = ChiSquared::new(dimension as f64).ok()?;
    let (lo, hi) = (chi.inverse_cdf(0.025), chi.inverse_cdf(0.975));
    let n = accepted.len().max(1) as f64;
    let mean_nis = accepted.iter().map(|r| r.nis).sum::<f64>() / n;
    let inside = accepted
        .iter()
        .filter(|r| r.nis >= lo && r.nis <= hi)
        .count() as f64
        / n;
    let rms = std::array::from_fn(|k| {
        (accepted
            .iter()
            .map(|r| r.innovation[k].powi(2))
            .sum::<f64>()
            / n)
            .sqrt()
    });
    Some(InnovationStatistics {
        kind,
        dimension,
        offered: of_kind.len(),
        rejected: of_kind.len() - accepted.len(),
        forced: of_kind.iter().filter(|r| r.forced).count(),
        mean_nis,
        fraction_nis_in_95: inside,
        rms_innovation: rms,
        mean_gate_scale: of_kind.iter().map(|r| r.gate_scale).sum::<f64>() / of_kind.len() as f64,
    })
}
