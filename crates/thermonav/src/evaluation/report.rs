//! The tournament's report: these types are the `evaluation.json` contract (snake_case keys,
//! units in the names), built from the runs by [`super::experiment::Tournament::run`] and from
//! a tournament's [`ShardFrame`] (all the report needs beside the runs, which every shard
//! stores) by the merge of [`super::shard`].

use super::candidates::{CandidateKind, Excluded};
use super::metrics::{Metric, OutageMetrics, RunMetrics};
use super::significance::MeanInterval;
use super::tournament::{Contrast, ModelResult, ModelSummary, Significance};
use crate::nav::engine::FilterKind;
use crate::nav::outage::Outage;
use crate::nav::solution::InnovationStatistics;
use crate::stoch::bank::GaussMarkovSource;
use crate::trajectory::ReferenceContent;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// One outage window, s on the data's time scale.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OutageSpan {
    /// First instant without GNSS, s.
    pub start_s: f64,
    /// First instant with GNSS again, s.
    pub end_s: f64,
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

/// One model of the tournament (a candidate through a filter), in report order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FrameModel {
    /// Candidate label.
    pub label: String,
    /// Candidate kind.
    pub candidate: CandidateKind,
    /// The filter.
    pub filter: FilterKind,
}

/// What every shard of a tournament shares: all the report needs beside the runs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ShardFrame {
    /// Operating temperature, °C.
    pub operating_temperature_c: f64,
    /// Gauss-Markov family of the bank candidates.
    pub gauss_markov_source: GaussMarkovSource,
    /// Filters, in report order.
    pub filters: Vec<FilterKind>,
    /// Outages of the main run.
    pub outages: Vec<OutageSpan>,
    /// The models of one replicate, in report order.
    pub models: Vec<FrameModel>,
    /// Candidates that could not be built.
    pub excluded: Vec<Excluded>,
    /// Replicates, the main run included.
    pub replicates: usize,
    /// How they differ, in words.
    pub replicates_differ_by: String,
    /// What the reference held (older shard files: a full reference).
    #[serde(default)]
    pub reference_content: ReferenceContent,
}

impl ShardFrame {
    /// Runs in all (replicates × models).
    pub fn runs(&self) -> usize {
        self.replicates * self.models.len()
    }
}

/// One model through one filter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelReport {
    /// Candidate label.
    pub label: String,
    /// What the candidate is (`kind`, and the temperature of bank candidates).
    #[serde(flatten)]
    pub candidate: CandidateKind,
    /// The temperature the candidate stands for, °C (null for pooled and data sheet).
    pub temperature_c: Option<f64>,
    /// The filter (none for an outside solution, see [`super::outside`]).
    pub filter: Option<FilterKind>,
    /// Why the main run failed, if it did.
    pub failure: Option<String>,
    /// Mean of per-outage RMS north error, m.
    pub rms_north_m: Option<f64>,
    /// Mean of per-outage RMS east error, m.
    pub rms_east_m: Option<f64>,
    /// Mean of per-outage RMS horizontal error, m.
    pub rms_horizontal_m: Option<f64>,
    /// Mean of per-outage RMS heading error, deg (absent against a position-only reference,
    /// and for a failed run).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rms_heading_deg: Option<f64>,
    /// RMS of per-outage maximum horizontal error, m.
    pub max_drift_horizontal_m: Option<f64>,
    /// RMS of per-outage maximum |north error|, m.
    pub rms_of_max_north_m: Option<f64>,
    /// RMS of per-outage maximum |east error|, m.
    pub rms_of_max_east_m: Option<f64>,
    /// RMS of per-outage maximum |heading error|, deg (absent as the RMS heading error).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rms_of_max_heading_deg: Option<f64>,
    /// Per outage of the main run.
    pub per_outage: Vec<OutageMetrics>,
    /// Per metric key, the mean over the replicates and its 95 % interval.
    pub ci95: BTreeMap<&'static str, MeanInterval>,
    /// Innovation statistics of the main run.
    pub innovations: Vec<InnovationStatistics>,
    /// Where the caller wrote the main run's per-epoch errors (none is written here).
    pub errors_csv: Option<PathBuf>,
}

impl ModelReport {
    /// The main run's value of `metric`, when the run succeeded.
    pub fn value(&self, metric: Metric) -> Option<f64> {
        match metric {
            Metric::RmsNorth => self.rms_north_m,
            Metric::RmsEast => self.rms_east_m,
            Metric::RmsHorizontal => self.rms_horizontal_m,
            Metric::RmsHeading => self.rms_heading_deg,
            Metric::MaxDriftHorizontal => self.max_drift_horizontal_m,
        }
    }
}

/// The significance section.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SignificanceReport {
    /// Replicates, the main run included.
    pub replicates: usize,
    /// How they differ, in words.
    pub replicates_differ_by: String,
    /// Winner against runner-up, per filter and metric.
    pub tests: Vec<Significance>,
    /// Every pair of models of a filter on the horizontal error, the better one first.
    pub horizontal_contrasts: Vec<Contrast>,
}

/// What the reference held and so what was scored: position always; heading only against
/// a reference with attitude.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct ReferenceScoring {
    /// What the reference held.
    pub content: ReferenceContent,
    /// What was not scored, in words (absent when everything was).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub not_scored: Option<&'static str>,
}

/// Why heading is not scored against a position-only reference.
pub const HEADING_NOT_SCORED: &str = "heading and attitude: the reference holds positions only (GNSS or RTK fixes), so only position errors are scored";

impl ReferenceScoring {
    /// The scoring against a reference holding `content`.
    pub fn of(content: ReferenceContent) -> Self {
        Self {
            content,
            not_scored: (!content.scores_heading()).then_some(HEADING_NOT_SCORED),
        }
    }
}

/// The whole report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TournamentReport {
    /// Operating temperature, °C (none when only outside solutions are scored).
    pub operating_temperature_c: Option<f64>,
    /// Gauss-Markov family of the bank candidates (none when only outside solutions are
    /// scored).
    pub gauss_markov_source: Option<GaussMarkovSource>,
    /// Filters, in report order.
    pub filters: Vec<FilterKind>,
    /// Outages of the main run.
    pub outages: Vec<OutageSpan>,
    /// What the reference held, and what was therefore not scored.
    pub reference: ReferenceScoring,
    /// Every model through every filter, candidate-major.
    pub models: Vec<ModelReport>,
    /// Candidates that could not be built.
    pub excluded: Vec<Excluded>,
    /// Per metric key, the best label of the first filter (the oracle is not ranked: no
    /// user can configure it).
    pub best: BTreeMap<&'static str, String>,
    /// Per filter and metric key, the best label.
    pub best_by_filter: BTreeMap<&'static str, BTreeMap<&'static str, String>>,
    /// Whether the rankings are beyond the replicate noise.
    pub significance: SignificanceReport,
    /// With an oracle: every other model's horizontal error against the best oracle run of
    /// its filter (empty without one).
    pub oracle_gaps: Vec<OracleGap>,
}

/// How far one model is from the best possible one (the oracle) on the horizontal error.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OracleGap {
    /// The model's label.
    pub label: String,
    /// The filter.
    pub filter: FilterKind,
    /// The oracle it is measured against.
    pub oracle: String,
    /// The model's mean of per-outage RMS horizontal error, m (the Monte Carlo mean with
    /// replicates).
    pub rms_horizontal_m: f64,
    /// The oracle's, m.
    pub oracle_rms_horizontal_m: f64,
    /// The model's minus the oracle's, m (what a better model could still gain).
    pub excess_m: f64,
    /// The model's over the oracle's.
    pub ratio: f64,
}

/// A model's label, filter and the values it is ranked by (in [`Metric::ALL`] order).
type Ranked = (String, FilterKind, [Option<f64>; 5]);

/// Position of the horizontal error in [`Metric::ALL`].
fn horizontal_index() -> usize {
    Metric::ALL
        .iter()
        .position(|m| *m == Metric::RmsHorizontal)
        .unwrap_or(0)
}

pub(super) fn report_of(
    frame: &ShardFrame,
    results: &[ModelResult],
    summaries: &[ModelSummary],
    (tests, horizontal_contrasts): (Vec<Significance>, Vec<Contrast>),
) -> TournamentReport {
    let models: Vec<ModelReport> = results
        .iter()
        .zip(summaries)
        .map(|(r, s)| model_report(r, &s.ci95))
        .collect();
    let replicated = frame.replicates > 1;
    let (oracles, users): (Vec<&ModelReport>, Vec<&ModelReport>) =
        models.iter().partition(|m| m.candidate.is_oracle());
    let ranking = ranking_values(&users, replicated);
    let oracle_gaps = oracle_gaps(&ranking, &ranking_values(&oracles, replicated));
    let filters = frame.filters.clone();
    TournamentReport {
        operating_temperature_c: Some(frame.operating_temperature_c),
        gauss_markov_source: Some(frame.gauss_markov_source),
        outages: frame.outages.clone(),
        reference: ReferenceScoring::of(frame.reference_content),
        excluded: frame.excluded.clone(),
        best: (filters.first())
            .map(|f| best_labels(&ranking, *f))
            .unwrap_or_default(),
        best_by_filter: filters
            .iter()
            .map(|f| (f.name(), best_labels(&ranking, *f)))
            .collect(),
        significance: SignificanceReport {
            replicates: frame.replicates,
            replicates_differ_by: frame.replicates_differ_by.clone(),
            tests,
            horizontal_contrasts,
        },
        oracle_gaps,
        models,
        filters,
    }
}

/// Each ranked model against the best oracle of its filter on the horizontal error.
fn oracle_gaps(ranking: &[Ranked], oracles: &[Ranked]) -> Vec<OracleGap> {
    let k = horizontal_index();
    let best_oracle = |filter: FilterKind| {
        oracles
            .iter()
            .filter(|(_, f, _)| *f == filter)
            .filter_map(|(label, _, v)| v[k].map(|x| (label, x)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    };
    ranking
        .iter()
        .filter_map(|(label, filter, v)| {
            let (oracle, reference) = best_oracle(*filter)?;
            let value = v[k]?;
            if reference <= 0.0 {
                return None;
            }
            Some(OracleGap {
                label: label.clone(),
                filter: *filter,
                oracle: oracle.clone(),
                rms_horizontal_m: value,
                oracle_rms_horizontal_m: reference,
                excess_m: value - reference,
                ratio: value / reference,
            })
        })
        .collect()
}

/// The values each model is ranked by: the Monte Carlo means when there are replicates,
/// the main run's values otherwise.
fn ranking_values(models: &[&ModelReport], replicated: bool) -> Vec<Ranked> {
    models
        .iter()
        .filter_map(|m| {
            let pick = |metric: Metric| match replicated {
                true => m.ci95.get(metric.key()).map(|c| c.mean),
                false => m.value(metric),
            };
            Some((m.label.clone(), m.filter?, Metric::ALL.map(pick)))
        })
        .collect()
}

/// The label with the lowest value of each metric among `filter`'s models.
fn best_labels(values: &[Ranked], filter: FilterKind) -> BTreeMap<&'static str, String> {
    Metric::ALL
        .iter()
        .enumerate()
        .filter_map(|(k, metric)| {
            values
                .iter()
                .filter(|(_, f, _)| *f == filter)
                .filter_map(|(label, _, v)| v[k].map(|x| (label, x)))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(label, _)| (metric.key(), label.clone()))
        })
        .collect()
}

fn model_report(result: &ModelResult, ci95: &[(Metric, MeanInterval)]) -> ModelReport {
    let ok = result.outcome.as_ref().ok();
    let metrics = ok.map(|e| &e.metrics);
    let pick = |f: fn(&RunMetrics) -> f64| metrics.map(f);
    ModelReport {
        label: result.label.clone(),
        candidate: result.candidate,
        temperature_c: result.candidate.temperature_c(),
        filter: Some(result.filter),
        failure: result.outcome.as_ref().err().cloned(),
        rms_north_m: pick(|m| m.rms_north_m),
        rms_east_m: pick(|m| m.rms_east_m),
        rms_horizontal_m: pick(|m| m.rms_horizontal_m),
        rms_heading_deg: metrics.and_then(|m| m.rms_heading_deg),
        max_drift_horizontal_m: pick(|m| m.max_drift_horizontal_m),
        rms_of_max_north_m: pick(|m| m.rms_of_max_north_m),
        rms_of_max_east_m: pick(|m| m.rms_of_max_east_m),
        rms_of_max_heading_deg: metrics.and_then(|m| m.rms_of_max_heading_deg),
        per_outage: metrics.map(|m| m.per_outage.clone()).unwrap_or_default(),
        ci95: ci95.iter().map(|(m, ci)| (m.key(), *ci)).collect(),
        innovations: ok.map(|e| e.innovations.clone()).unwrap_or_default(),
        errors_csv: None,
    }
}
