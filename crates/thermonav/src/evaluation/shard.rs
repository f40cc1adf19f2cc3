//! A tournament cut into shards, as one batch job per shard runs it (a Slurm array), and the
//! merge that gives the report of one whole run.
//!
//! The units of work are the runs (replicate × candidate × filter), numbered replicate-major
//! then in the report's model order: run `k` of `R × M` is replicate `k / M`, model `k % M`.
//! Shard `I` of `N` (1-based, as `sbatch --array=1-N` numbers its tasks) holds the runs with
//! `k mod N = I − 1`, so that every shard gets a share of the main run and of each replicate.
//! A replicate is the same whichever shard runs it: its outage shift is drawn from the one
//! seeded stream by its index, never by the shard's position in it.
//!
//! Each shard stores its runs' figures as they came out of the filter (serde_json writes the
//! shortest text that reads back to the same `f64`), the frame every shard shares (models,
//! outages, excluded candidates, replicates) and the fingerprint the caller gives (hashes of
//! the inputs and settings). [`merge_shards`] checks that the shards are one complete set of
//! one tournament and does the aggregation; the unsharded run is one shard merged alone, so
//! the two give the same report by construction.

use super::metrics::{EpochError, RunMetrics};
use super::report::{FrameModel, ShardFrame, TournamentReport, report_of};
use super::tournament::{Evaluated, ModelResult, horizontal_contrasts, summarize_replicates};
use crate::nav::solution::InnovationStatistics;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One slice of a tournament's runs: shard `index` of `count`, 1-based.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// Which shard, 1..=count.
    pub index: usize,
    /// Shards in all.
    pub count: usize,
}

/// A shard that cannot be.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("shard {index}/{count}: the index must be 1..={count} (1-based) and the count at least 1")]
pub struct ShardRangeError {
    /// The index given.
    pub index: usize,
    /// The count given.
    pub count: usize,
}

impl Shard {
    /// All the runs in one shard (the unsharded run).
    pub const WHOLE: Shard = Shard { index: 1, count: 1 };

    /// Shard `index` of `count`.
    ///
    /// # Errors
    /// [`ShardRangeError`] unless 1 ≤ index ≤ count.
    pub fn new(index: usize, count: usize) -> Result<Self, ShardRangeError> {
        match (1..=count).contains(&index) {
            true => Ok(Self { index, count }),
            false => Err(ShardRangeError { index, count }),
        }
    }

    /// Whether run `run` (0-based over all runs) is this shard's.
    pub fn holds(&self, run: usize) -> bool {
        run % self.count == self.index - 1
    }
}

/// What one run gave, as stored (per-epoch errors only for the main run).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StoredEvaluation {
    /// The outage figures.
    pub metrics: RunMetrics,
    /// Per-epoch errors inside each outage (empty for a replicate).
    pub errors: Vec<Vec<EpochError>>,
    /// Innovation statistics of the run.
    pub innovations: Vec<InnovationStatistics>,
}

/// One run of a shard.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ShardRun {
    /// Its number over all runs (replicate-major, see the module's docs).
    pub run: usize,
    /// The figures, or why the run failed.
    pub outcome: Result<StoredEvaluation, String>,
}

/// The runs of one shard with what the merge needs to check and aggregate them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TournamentShard {
    /// Which shard.
    pub shard: Shard,
    /// Hashes of the inputs and settings, by name (set by the caller; the merge refuses
    /// shards whose fingerprints differ, naming the entry).
    pub fingerprint: BTreeMap<String, String>,
    /// What every shard shares.
    pub frame: ShardFrame,
    /// This shard's runs, in run order.
    pub runs: Vec<ShardRun>,
}

/// Why shards cannot be merged; shards are named as the caller named them.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum MergeError {
    /// No shard given.
    #[error("no shard to merge")]
    Empty,
    /// Shards of differently cut tournaments.
    #[error(
        "{a} is shard {a_index}/{a_count} but {b} is shard {b_index}/{b_count}: shards of one tournament share their count"
    )]
    Count {
        /// One shard.
        a: String,
        /// Its index.
        a_index: usize,
        /// Its count.
        a_count: usize,
        /// The other.
        b: String,
        /// Its index.
        b_index: usize,
        /// Its count.
        b_count: usize,
    },
    /// The same shard twice.
    #[error("shard {index}/{count} is given twice: {a} and {b}")]
    Duplicate {
        /// The shard's index.
        index: usize,
        /// Shards in all.
        count: usize,
        /// One file.
        a: String,
        /// The other.
        b: String,
    },
    /// A shard missing.
    #[error("shard {index}/{count} is missing (given: {given})")]
    Missing {
        /// The missing index.
        index: usize,
        /// Shards in all.
        count: usize,
        /// The shards given, by name.
        given: String,
    },
    /// Shards of different inputs or settings.
    #[error("{a} and {b} come from different {what}: they are not shards of one tournament")]
    Differs {
        /// One shard.
        a: String,
        /// The other.
        b: String,
        /// The fingerprint entry (or "tournament models, outages or replicates").
        what: String,
    },
    /// Shards whose runs cannot be those of their frame (an edited or foreign file).
    #[error(
        "the shards hold {held} runs in all, but their frame stands for {expected} (replicates x models): not one tournament's complete shards"
    )]
    RunCount {
        /// What the frame stands for, in words (it may overflow).
        expected: String,
        /// Runs held by all shards.
        held: usize,
    },
    /// A stored figure no run can give (negative, or not finite).
    #[error(
        "{name}: run {run}: {what} is {value}, not a figure a run gives (expected a finite number >= 0)"
    )]
    Value {
        /// The shard.
        name: String,
        /// The run.
        run: usize,
        /// The figure's name.
        what: &'static str,
        /// Its value, as text.
        value: String,
    },
    /// A shard without the runs its index stands for.
    #[error("{name}: its runs are not those of shard {index}/{count} (run {run})")]
    Runs {
        /// The shard.
        name: String,
        /// Its index.
        index: usize,
        /// Shards in all.
        count: usize,
        /// The first run out of place.
        run: usize,
    },
}

/// The merged tournament: the report and the main run (with per-epoch errors).
#[derive(Debug, Clone)]
pub struct MergedTournament {
    /// The report (the `evaluation.json` contract).
    pub report: TournamentReport,
    /// The main run, in the report's model order.
    pub main: Vec<ModelResult>,
}

/// Checks that `shards` (each with its name for the messages) are the complete set of one
/// tournament's shards and aggregates their runs as one run does: the main run's figures,
/// the Monte Carlo summaries, the significance tests, the contrasts and the ranking.
///
/// # Errors
/// Every [`MergeError`].
pub fn merge_shards(shards: &[(String, TournamentShard)]) -> Result<MergedTournament, MergeError> {
    let (first_name, first) = shards.first().ok_or(MergeError::Empty)?;
    for (name, shard) in &shards[1..] {
        check_same_tournament((first_name, first), (name, shard))?;
    }
    for (name, shard) in shards {
        check_stored_figures(name, shard)?;
    }
    check_count_against_shards(shards)?;
    let ordered = complete_set(shards)?;
    check_runs_against_frame(shards)?;
    let frame = &first.frame;
    let replicates = replicate_results(frame, &ordered)?;
    let (summaries, tests) = summarize_replicates(&replicates);
    let contrasts = horizontal_contrasts(&replicates);
    let main = replicates.into_iter().next().unwrap_or_default();
    let report = report_of(frame, &main, &summaries, (tests, contrasts));
    Ok(MergedTournament { report, main })
}

/// Refuses two shards of different counts, fingerprints or frames.
fn check_same_tournament(
    (a_name, a): (&str, &TournamentShard),
    (b_name, b): (&str, &TournamentShard),
) -> Result<(), MergeError> {
    let differs = |what: &str| MergeError::Differs {
        a: a_name.into(),
        b: b_name.into(),
        what: what.into(),
    };
    if a.shard.count != b.shard.count {
        return Err(MergeError::Count {
            a: a_name.into(),
            a_index: a.shard.index,
            a_count: a.shard.count,
            b: b_name.into(),
            b_index: b.shard.index,
            b_count: b.shard.count,
        });
    }
    let keys = a.fingerprint.keys().chain(b.fingerprint.keys());
    if let Some(key) = keys
        .into_iter()
        .find(|k| a.fingerprint.get(*k) != b.fingerprint.get(*k))
    {
        return Err(differs(key));
    }
    if a.frame != b.frame {
        return Err(differs("tournament models, outages or replicates"));
    }
    Ok(())
}

/// Refuses a stored figure that no run gives: a negative or non-finite RMS, maximum or
/// outage time.
fn check_stored_figures(name: &str, shard: &TournamentShard) -> Result<(), MergeError> {
    for run in &shard.runs {
        let Ok(stored) = &run.outcome else { continue };
        let m = &stored.metrics;
        // A heading figure is absent against a position-only reference: nothing to check.
        let whole = [
            ("rms_north_m", m.rms_north_m),
            ("rms_east_m", m.rms_east_m),
            ("rms_horizontal_m", m.rms_horizontal_m),
            ("rms_heading_deg", m.rms_heading_deg.unwrap_or(0.0)),
            ("max_drift_horizontal_m", m.max_drift_horizontal_m),
            ("rms_of_max_north_m", m.rms_of_max_north_m),
            ("rms_of_max_east_m", m.rms_of_max_east_m),
            (
                "rms_of_max_heading_deg",
                m.rms_of_max_heading_deg.unwrap_or(0.0),
            ),
        ];
        let outages = m.per_outage.iter().flat_map(|o| {
            [
                ("per_outage.start_s", o.start_s),
                ("per_outage.end_s", o.end_s),
                ("per_outage.rms_north_m", o.rms_north_m),
                ("per_outage.rms_east_m", o.rms_east_m),
                ("per_outage.rms_horizontal_m", o.rms_horizontal_m),
                (
                    "per_outage.rms_heading_deg",
                    o.rms_heading_deg.unwrap_or(0.0),
                ),
                ("per_outage.max_north_m", o.max_north_m),
                ("per_outage.max_east_m", o.max_east_m),
                ("per_outage.max_horizontal_m", o.max_horizontal_m),
                (
                    "per_outage.max_heading_deg",
                    o.max_heading_deg.unwrap_or(0.0),
                ),
            ]
        });
        // Outage times may be negative (before the record's first sample); the magnitudes not.
        let bad = whole.into_iter().chain(outages).find(|&(what, v)| {
            !v.is_finite() || (v < 0.0 && !what.ends_with("start_s") && !what.ends_with("end_s"))
        });
        if let Some((what, value)) = bad {
            return Err(MergeError::Value {
                name: name.to_string(),
                run: run.run,
                what,
                value: value.to_string(),
            });
        }
    }
    Ok(())
}

/// Refuses, before anything is allocated for them, a shard count beyond the shards given (the
/// first index missing is named).
fn check_count_against_shards(shards: &[(String, TournamentShard)]) -> Result<(), MergeError> {
    let count = shards[0].1.shard.count;
    if count > shards.len() {
        let given: std::collections::BTreeSet<usize> =
            shards.iter().map(|(_, s)| s.shard.index).collect();
        let index = (1..=shards.len() + 1)
            .find(|i| !given.contains(i))
            .unwrap_or(1);
        let names: Vec<&str> = shards.iter().map(|(n, _)| n.as_str()).collect();
        return Err(MergeError::Missing {
            index,
            count,
            given: names.join(", "),
        });
    }
    Ok(())
}

/// Refuses a frame whose runs are not the runs the shards hold, before anything is allocated
/// for the frame's runs.
fn check_runs_against_frame(shards: &[(String, TournamentShard)]) -> Result<(), MergeError> {
    let frame = &shards[0].1.frame;
    let held: usize = shards.iter().map(|(_, s)| s.runs.len()).sum();
    match frame.replicates.checked_mul(frame.models.len()) {
        Some(expected) if expected == held => Ok(()),
        expected => Err(MergeError::RunCount {
            expected: expected.map_or_else(
                || {
                    format!(
                        "{} x {} (beyond any count)",
                        frame.replicates,
                        frame.models.len()
                    )
                },
                |e| e.to_string(),
            ),
            held,
        }),
    }
}

/// The shards in index order, each once, none missing.
fn complete_set(shards: &[(String, TournamentShard)]) -> Result<Vec<&TournamentShard>, MergeError> {
    let count = shards[0].1.shard.count;
    let mut slots: Vec<Option<&(String, TournamentShard)>> = vec![None; count];
    for entry in shards {
        let index = entry.1.shard.index;
        let slot = slots
            .get_mut(index.wrapping_sub(1))
            .ok_or(MergeError::Runs {
                name: entry.0.clone(),
                index,
                count,
                run: 0,
            })?;
        if let Some(earlier) = slot.replace(entry) {
            return Err(MergeError::Duplicate {
                index,
                count,
                a: earlier.0.clone(),
                b: entry.0.clone(),
            });
        }
    }
    let given = || {
        let names: Vec<&str> = shards.iter().map(|(n, _)| n.as_str()).collect();
        names.join(", ")
    };
    slots
        .iter()
        .enumerate()
        .map(|(i, s)| {
            s.map(|(_, shard)| shard)
                .ok_or_else(|| MergeError::Missing {
                    index: i + 1,
                    count,
                    given: given(),
                })
        })
        .collect()
}

/// Every replicate's results in report order, from the shards' runs.
fn replicate_results(
    frame: &ShardFrame,
    shards: &[&TournamentShard],
) -> Result<Vec<Vec<ModelResult>>, MergeError> {
    let mut runs: Vec<Option<&ShardRun>> = vec![None; frame.runs()];
    for shard in shards {
        let expected = (0..frame.runs()).filter(|k| shard.shard.holds(*k));
        let held: Vec<usize> = shard.runs.iter().map(|r| r.run).collect();
        if let Some(run) = first_difference(expected, &held) {
            let Shard { index, count } = shard.shard;
            let name = format!("shard {index}/{count}");
            return Err(MergeError::Runs {
                name,
                index,
                count,
                run,
            });
        }
        for run in &shard.runs {
            runs[run.run] = Some(run);
        }
    }
    let models = frame.models.len().max(1);
    Ok(runs
        .chunks(models)
        .map(|replicate| {
            (replicate.iter().zip(&frame.models))
                .map(|(run, model)| model_result(model, run.map(|r| &r.outcome)))
                .collect()
        })
        .collect())
}

/// The first run where `held` is not `expected`, if any.
fn first_difference(expected: impl Iterator<Item = usize>, held: &[usize]) -> Option<usize> {
    let expected: Vec<usize> = expected.collect();
    if expected == held {
        return None;
    }
    let at = expected.iter().zip(held).position(|(a, b)| a != b);
    let at = at.unwrap_or(expected.len().min(held.len()));
    expected.get(at).or(held.get(at)).copied()
}

fn model_result(
    model: &FrameModel,
    outcome: Option<&Result<StoredEvaluation, String>>,
) -> ModelResult {
    let outcome = match outcome {
        Some(Ok(e)) => Ok(Evaluated {
            metrics: e.metrics.clone(),
            errors: e.errors.clone(),
            innovations: e.innovations.clone(),
        }),
        Some(Err(reason)) => Err(reason.clone()),
        None => Err("no shard holds this run".into()),
    };
    ModelResult {
        label: model.label.clone(),
        candidate: model.candidate,
        filter: model.filter,
        outcome,
    }
}

/// A run's result as a shard stores it.
pub(super) fn stored_run(run: usize, result: &ModelResult) -> ShardRun {
    let outcome = result.outcome.as_ref().map(|e| StoredEvaluation {
        metrics: e.metrics.clone(),
        errors: e.errors.clone(),
        innovations: e.innovations.clone(),
    });
    ShardRun {
        run,
        outcome: outcome.map_err(Clone::clone),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Oracle: the definition, k mod N = I − 1, enumerated by hand for 3 shards of 7 runs.
    #[test]
    fn shards_split_the_runs_round_robin_and_cover_each_once() {
        let held = |i| {
            let shard = Shard::new(i, 3).unwrap();
            (0..7).filter(|k| shard.holds(*k)).collect::<Vec<_>>()
        };
        assert_eq!(held(1), [0, 3, 6]);
        assert_eq!(held(2), [1, 4]);
        assert_eq!(held(3), [2, 5]);
        assert!(Shard::new(0, 3).is_err() && Shard::new(4, 3).is_err());
        assert!(Shard::new(1, 0).is_err());
    }

    #[test]
    fn first_difference_names_the_run_out_of_place() {
        assert_eq!(first_difference([0, 3, 6].into_iter(), &[0, 3, 6]), None);
        assert_eq!(first_difference([0, 3, 6].into_iter(), &[0, 3]), Some(6));
        assert_eq!(first_difference([0, 3].into_iter(), &[0, 4]), Some(3));
    }
}
