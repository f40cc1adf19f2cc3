//! Outside solutions: trajectories computed by another tool (KF-GINS, RTKLIB, or any solver
//! whose output is written as a trajectory) scored against the reference with the tournament's
//! outage metrics, as rows of its report beside our candidates.
//!
//! A trajectory does not say where its solver had GNSS: the scoring assumes that the outside
//! solver withheld GNSS in the same outages as the ones scored. The figures are those of
//! [`super::metrics::evaluate_trajectory`], the same arithmetic as our filters' figures, so an
//! outside solution and one of ours written as a trajectory score alike.

use super::experiment::Replicates;
use super::metrics::{MetricsError, Reference, evaluate_trajectory};
use super::report::{ModelReport, SignificanceReport, TournamentReport, outage_spans};
use super::tournament::Evaluated;
use crate::nav::outage::Outage;
use crate::trajectory::{ReferenceContent, TrajectoryPoint};
use std::collections::BTreeMap;

/// An outside solution scored.
#[derive(Debug, Clone, PartialEq)]
pub struct OutsideResult {
    /// Label in tables and JSON.
    pub label: String,
    /// Its figures and per-epoch errors (no innovations: the trajectory has none).
    pub evaluated: Evaluated,
}

/// Why an outside solution cannot be scored.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OutsideError {
    /// The trajectory has no point.
    #[error("the solution has no point")]
    Empty,
    /// No epoch of the solution inside an outage (most often another time scale).
    #[error(
        "{source}; the solution spans {first_s:.3}-{last_s:.3} s: are both on the same time scale?"
    )]
    NoEpochs {
        /// The metrics' error.
        source: MetricsError,
        /// First solution time, s.
        first_s: f64,
        /// Last solution time, s.
        last_s: f64,
    },
    /// The reference does not cover an outage, or no outage was given.
    #[error(transparent)]
    Metrics(MetricsError),
}

/// Scores `points` (labelled `label`) against `reference` inside `outages`.
///
/// # Errors
/// [`OutsideError`]: an empty solution, an outage without a solution epoch, a reference that
/// does not cover an outage, no outage.
pub fn score_outside(
    label: &str,
    points: &[TrajectoryPoint],
    reference: Reference,
    outages: &[Outage],
) -> Result<OutsideResult, OutsideError> {
    let (Some(first), Some(last)) = (points.first(), points.last()) else {
        return Err(OutsideError::Empty);
    };
    let (metrics, errors) =
        evaluate_trajectory(reference, points, outages).map_err(|e| match e {
            MetricsError::NoEpochs { .. } => OutsideError::NoEpochs {
                source: e,
                first_s: first.time.as_seconds(),
                last_s: last.time.as_seconds(),
            },
            _ => OutsideError::Metrics(e),
        })?;
    let evaluated = Evaluated {
        metrics,
        errors,
        innovations: Vec::new(),
    };
    Ok(OutsideResult {
        label: label.to_owned(),
        evaluated,
    })
}

/// The report row of an outside solution: kind `outside`, no filter, no temperature, no
/// replicate interval (its outages cannot be shifted: the solver ran with its own).
pub fn outside_model_report(result: &OutsideResult) -> ModelReport {
    let m = &result.evaluated.metrics;
    ModelReport {
        label: result.label.clone(),
        candidate: super::candidates::CandidateKind::Outside,
        temperature_c: None,
        filter: None,
        failure: None,
        rms_north_m: Some(m.rms_north_m),
        rms_east_m: Some(m.rms_east_m),
        rms_horizontal_m: Some(m.rms_horizontal_m),
        rms_heading_deg: m.rms_heading_deg,
        max_drift_horizontal_m: Some(m.max_drift_horizontal_m),
        rms_of_max_north_m: Some(m.rms_of_max_north_m),
        rms_of_max_east_m: Some(m.rms_of_max_east_m),
        rms_of_max_heading_deg: m.rms_of_max_heading_deg,
        per_outage: m.per_outage.clone(),
        ci95: Default::default(),
        innovations: Vec::new(),
        errors_csv: None,
    }
}

impl TournamentReport {
    /// The report of outside solutions alone (no filter ran): their rows, the outages, no
    /// ranking, no replicate.
    pub fn outside_only(
        outages: &[Outage],
        outside: &[OutsideResult],
        content: ReferenceContent,
    ) -> Self {
        Self {
            operating_temperature_c: None,
            gauss_markov_source: None,
            filters: Vec::new(),
            outages: outage_spans(outages),
            reference: super::report::ReferenceScoring::of(content),
            models: outside.iter().map(outside_model_report).collect(),
            excluded: Vec::new(),
            best: BTreeMap::new(),
            best_by_filter: BTreeMap::new(),
            significance: SignificanceReport {
                replicates: 1,
                replicates_differ_by: Replicates::None.differ_by().into(),
                tests: Vec::new(),
                horizontal_contrasts: Vec::new(),
            },
            oracle_gaps: Vec::new(),
        }
    }

    /// Adds the rows of outside solutions after the candidates' (they are not ranked: no
    /// model of ours stands behind them).
    pub fn add_outside(&mut self, outside: &[OutsideResult]) {
        self.models.extend(outside.iter().map(outside_model_report));
    }
}
