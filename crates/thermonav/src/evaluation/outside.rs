//! Outside solutions: trajectories computed by another tool (KF-GINS, RTKLIB, or any solver
//! whose output is written as a trajectory) scored against the reference with the tournament's
//! outage metrics, as rows of its report beside our candidates.
//!
//! A trajectory does not say where its solver had GNSS: the scoring assumes that the outside
//! solver withheld GNSS in the same outages as the ones scored. The figures are those of
//! [`super::metrics::evaluate_trajectory`], the same arithmetic as our filters' figures, so an
//! outside solution and one of ours written as a trajectory score alike.

use super::metrics::{MetricsError, evaluate_trajectory};
use super::report::{ModelReport, OutageSpan};
use super::tournament::Evaluated;
use crate::nav::outage::Outage;
use crate::trajectory::TrajectoryPoint;

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
    reference: &[TrajectoryPoint],
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
        rms_heading_deg: Some(m.rms_heading_deg),
        max_drift_horizontal_m: Some(m.max_drift_horizontal_m),
        rms_of_max_north_m: Some(m.rms_of_max_north_m),
        rms_of_max_east_m: Some(m.rms_of_max_east_m),
        rms_of_max_heading_deg: Some(m.rms_of_max_heading_deg),
        per_outage: m.per_outage.clone(),
        ci95: Default::default(),
        innovations: Vec::new(),
        errors_csv: None,
    }
}

/// The spans of `outages`, as the report lists them.
pub fn outage_spans(outages: &[Outage]) -> Vec<OutageSpan> {
    outages
        .iter()
        .map(|w| OutageSpan {
            start_s: w.start.as_seconds(),
            end_s: w.end.as_seconds(),
        })
        .collect()
}
