//! Every candidate model through the same filter on the same data (in parallel), the
//! outage metrics of each, the ranking, and its Monte Carlo significance.

use super::candidates::{Candidate, CandidateKind, Record};
use super::metrics::{EpochError, Metric, RunMetrics, evaluate_solution};
use super::scenario::Scenario;
use super::significance::{MeanInterval, PairedTest, mean_interval, paired_t_test};
use crate::ins::state::Increment;
use crate::nav::engine::{EngineSettings, FilterKind};
use crate::nav::navigate::run_scheduled;
use crate::nav::schedule::ModelSchedule;
use crate::nav::solution::InnovationStatistics;
use rayon::prelude::*;
use serde::Serialize;

/// What a run of one candidate gave.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Evaluated {
    /// The outage figures.
    pub metrics: RunMetrics,
    /// Per-epoch errors inside each outage.
    #[serde(skip)]
    pub errors: Vec<Vec<EpochError>>,
    /// Innovation statistics of the run.
    pub innovations: Vec<InnovationStatistics>,
}

/// One candidate through one filter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelResult {
    /// Candidate label.
    pub label: String,
    /// Candidate kind.
    pub candidate: CandidateKind,
    /// The filter.
    pub filter: FilterKind,
    /// The figures, or why the run failed (divergence).
    pub outcome: Result<Evaluated, String>,
}

impl ModelResult {
    /// The value of `metric`, when the run succeeded.
    pub fn value(&self, metric: Metric) -> Option<f64> {
        self.outcome
            .as_ref()
            .ok()
            .and_then(|e| metric.of(&e.metrics))
    }
}

/// Runs every candidate through every filter on `scenario`, in parallel; the results are in
/// candidate-major order. `on_done` is called after each run (for progress).
pub fn run_tournament(
    scenario: &Scenario,
    candidates: &[Candidate],
    filters: &[FilterKind],
    on_done: &(dyn Fn() + Sync),
) -> Vec<ModelResult> {
    let all: Vec<usize> = (0..candidates.len() * filters.len()).collect();
    run_selected(scenario, (candidates, filters), &all, on_done)
}

/// The runs `selected` (positions in the candidate-major order of [`run_tournament`]) on
/// `scenario`, in parallel, in the order given.
pub(super) fn run_selected(
    scenario: &Scenario,
    (candidates, filters): (&[Candidate], &[FilterKind]),
    selected: &[usize],
    on_done: &(dyn Fn() + Sync),
) -> Vec<ModelResult> {
    let pairs: Vec<(&Candidate, FilterKind)> = candidates
        .iter()
        .flat_map(|c| filters.iter().map(move |f| (c, *f)))
        .collect();
    selected
        .par_iter()
        .map(|&k| {
            let (candidate, filter) = pairs[k];
            let result = run_one(scenario, candidate, filter);
            on_done();
            result
        })
        .collect()
}

fn run_one(scenario: &Scenario, candidate: &Candidate, filter: FilterKind) -> ModelResult {
    let settings = EngineSettings {
        filter,
        ..scenario.settings.clone()
    };
    let outcome = candidate_inputs(scenario, candidate).and_then(|(increments, schedule)| {
        let solution = run_scheduled(
            increments,
            &scenario.gnss,
            scenario.initial,
            scenario.initial_covariance(candidate.initial),
            schedule,
            &settings,
            &mut |_| {},
        )
        .map_err(|e| e.to_string())?;
        let (metrics, errors) = evaluate_solution(
            scenario.reference(),
            &solution.epochs,
            settings.outages.windows(),
        )
        .map_err(|e| e.to_string())?;
        Ok(Evaluated {
            metrics,
            errors,
            innovations: solution.innovation_statistics(),
        })
    });
    ModelResult {
        label: candidate.label.clone(),
        candidate: candidate.kind,
        filter,
        outcome,
    }
}

/// The increments a candidate runs on and its model schedule, or why the scenario lacks
/// them.
fn candidate_inputs<'a>(
    scenario: &'a Scenario,
    candidate: &'a Candidate,
) -> Result<(&'a [Increment], ModelSchedule<'a>), String> {
    let increments = match candidate.record {
        Record::Raw => Some(&scenario.increments),
        Record::Compensated => scenario.compensated_increments.as_ref(),
        Record::OracleCompensated => scenario.oracle_increments.as_ref(),
    }
    .ok_or("the scenario has no compensated IMU record")?;
    let schedule = match (&candidate.schedule, &scenario.temperature) {
        (None, _) => ModelSchedule::Fixed(&candidate.model),
        (Some(grid), Some(track)) => ModelSchedule::ByTemperature { track, grid },
        (Some(_), None) => return Err("the scenario's IMU record has no temperature".into()),
    };
    Ok((increments, schedule))
}

/// One model's metrics over the Monte Carlo replicates.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelSummary {
    /// Candidate label.
    pub label: String,
    /// The filter.
    pub filter: FilterKind,
    /// Per metric key, the mean and its 95 % interval.
    pub ci95: Vec<(Metric, MeanInterval)>,
    /// Replicates in which the run failed.
    pub failures: usize,
}

/// Whether the winner of one metric beats the runner-up beyond the replicate noise.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Significance {
    /// The filter.
    pub filter: FilterKind,
    /// The metric.
    pub metric: Metric,
    /// Lowest mean over the replicates.
    pub winner: String,
    /// Second lowest.
    pub runner_up: String,
    /// Paired t-test of winner − runner-up over the replicates.
    pub test: Option<PairedTest>,
    /// p < 0.05.
    pub significant: bool,
}

/// Per-model summaries and winner-against-runner-up tests over replicates, each replicate
/// holding the same candidates and filters in the same order. A model with a failed run in
/// any replicate, and the oracle (which no user can configure), are left out of the tests.
pub fn summarize_replicates(
    replicates: &[Vec<ModelResult>],
) -> (Vec<ModelSummary>, Vec<Significance>) {
    let Some(first) = replicates.first() else {
        return (Vec::new(), Vec::new());
    };
    let values = |index: usize, metric: Metric| -> Vec<Option<f64>> {
        replicates
            .iter()
            .map(|r| r.get(index).and_then(|m| m.value(metric)))
            .collect()
    };
    let summaries: Vec<ModelSummary> = first
        .iter()
        .enumerate()
        .map(|(i, m)| ModelSummary {
            label: m.label.clone(),
            filter: m.filter,
            ci95: Metric::ALL
                .iter()
                .filter_map(|&metric| {
                    let v: Vec<f64> = values(i, metric).into_iter().flatten().collect();
                    mean_interval(&v).map(|ci| (metric, ci))
                })
                .collect(),
            failures: values(i, Metric::RmsHorizontal)
                .iter()
                .filter(|v| v.is_none())
                .count(),
        })
        .collect();
    let mut tests = Vec::new();
    let mut filters: Vec<FilterKind> = Vec::new();
    for m in first {
        if !filters.contains(&m.filter) {
            filters.push(m.filter);
        }
    }
    for filter in filters {
        for metric in Metric::ALL {
            let complete: Vec<(usize, Vec<f64>)> = first
                .iter()
                .enumerate()
                .filter(|(_, m)| m.filter == filter && !m.candidate.is_oracle())
                .filter_map(|(i, _)| {
                    values(i, metric)
                        .into_iter()
                        .collect::<Option<Vec<f64>>>()
                        .map(|v| (i, v))
                })
                .collect();
            let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
            let mut order: Vec<&(usize, Vec<f64>)> = complete.iter().collect();
            order.sort_by(|a, b| mean(&a.1).total_cmp(&mean(&b.1)));
            if let [winner, runner_up, ..] = order[..] {
                let test = paired_t_test(&winner.1, &runner_up.1);
                tests.push(Significance {
                    filter,
                    metric,
                    winner: first[winner.0].label.clone(),
                    runner_up: first[runner_up.0].label.clone(),
                    significant: test.is_some_and(|t| t.p_value < 0.05),
                    test,
                });
            }
        }
    }
    (summaries, tests)
}

/// One model against another on the mean of per-outage RMS horizontal error, over the
/// replicates (paired: the same data in each replicate).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Contrast {
    /// The filter.
    pub filter: FilterKind,
    /// The model with the lower mean.
    pub better: String,
    /// The other.
    pub worse: String,
    /// Mean of worse − better over the replicates, m.
    pub mean_difference_m: f64,
    /// Paired t-test of worse − better (`None` with fewer than two replicates or no spread).
    pub test: Option<PairedTest>,
}

/// Every pair of models of one filter whose runs all succeeded, on the horizontal error.
pub fn horizontal_contrasts(replicates: &[Vec<ModelResult>]) -> Vec<Contrast> {
    let Some(first) = replicates.first() else {
        return Vec::new();
    };
    let series: Vec<Option<Vec<f64>>> = (0..first.len())
        .map(|i| {
            replicates
                .iter()
                .map(|r| r.get(i).and_then(|m| m.value(Metric::RmsHorizontal)))
                .collect()
        })
        .collect();
    let mut contrasts = Vec::new();
    for (i, a) in first.iter().enumerate() {
        for (j, b) in first.iter().enumerate().skip(i + 1) {
            if a.filter != b.filter {
                continue;
            }
            if let (Some(x), Some(y)) = (&series[i], &series[j]) {
                contrasts.push(contrast(a, x, b, y));
            }
        }
    }
    contrasts
}

fn contrast(a: &ModelResult, x: &[f64], b: &ModelResult, y: &[f64]) -> Contrast {
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let ((better, bv), (worse, wv)) = if mean(x) <= mean(y) {
        ((a, x), (b, y))
    } else {
        ((b, y), (a, x))
    };
    Contrast {
        filter: a.filter,
        better: better.label.clone(),
        worse: worse.label.clone(),
        mean_difference_m: mean(wv) - mean(bv),
        test: paired_t_test(wv, bv),
    }
}
