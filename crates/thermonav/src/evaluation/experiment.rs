//! The tournament as an experiment: the candidates of a bank or a sensor profile, one main run of every candidate
//! through every filter, replicates that differ from it in a stated way, and the report
//! ([`super::report::TournamentReport`]) with the ranking and its significance.
//!
//! The main run keeps its per-epoch errors (for the caller to write or plot); a replicate keeps
//! only its figures, and replicates are made one at a time, so memory stays that of the main
//! run whatever the number of replicates.

use super::candidates::{
    Candidate, CandidateKind, Excluded, ThermalOptions, oracle_candidates, profile_candidates,
    thermal_candidates, tournament_candidates, with_initial_uncertainty,
};
use super::oracle::TrueModel;
use super::report::{FrameModel, ShardFrame, TournamentReport, outage_spans};
use super::scenario::Scenario;
use super::shard::{Shard, ShardRun, TournamentShard, merge_shards, stored_run};
use super::tournament::{ModelResult, run_selected};
use crate::nav::engine::FilterKind;
use crate::nav::outage::{OutageError, OutageSpec};
use crate::nav::run::NoiseModel;
use crate::nav::schedule::Compensation;
use crate::nav::sensor_model::{ImuStochasticModel, ScaleFactorPrior};
use crate::rng::named_rng;
use crate::sensor::SensorProfile;
use crate::stoch::bank::{GaussMarkovSource, ModelBank};
use rayon::prelude::*;
use std::collections::BTreeMap;

/// The replicates of a tournament unless asked for more: one run of every candidate through
/// every filter, no Monte Carlo (`evaluate --monte-carlo`, Python's `monte_carlo`).
pub const DEFAULT_MONTE_CARLO: usize = 1;

/// The most replicates a tournament runs (each is a run of every candidate through every
/// filter: 1000 replicates of the demo's 28 runs take hours already).
pub const MAX_REPLICATES: usize = 1000;

/// The outages of a tournament when none are given: eight windows of 100 s spread over the
/// data (a wrong model's drift grows with the cube of time, so outages of minutes tell the
/// models apart).
pub const DEFAULT_OUTAGES: OutageSpec = OutageSpec::Spread {
    count: 8,
    duration_s: 100.0,
};

/// Where a tournament's candidates come from.
#[derive(Debug, Clone, Copy)]
pub enum CandidateSource<'a> {
    /// A bank: its entries, interpolated, pooled and the thermal candidates.
    Bank(&'a ModelBank),
    /// A sensor profile (no chamber campaign): the profile at fixed temperatures and
    /// scheduled.
    Profile(&'a SensorProfile),
}

/// What a tournament compares.
#[derive(Debug, Clone)]
pub struct TournamentPlan<'a> {
    /// Where the candidates come from.
    pub noise: CandidateSource<'a>,
    /// The record's temperatures and the scheduling and compensation switches.
    pub thermal: ThermalOptions,
    /// The sensor's operating temperature, °C (where the interpolated candidate stands).
    pub operating_temperature_c: f64,
    /// The Gauss-Markov family of the bank used by every bank candidate.
    pub source: GaussMarkovSource,
    /// The filters, reported in this order.
    pub filters: Vec<FilterKind>,
    /// The data-sheet candidate's model, when there is one (see
    /// [`super::candidates::DatasheetValues::model`]).
    pub datasheet: Option<ImuStochasticModel>,
    /// Scale-factor prior of every candidate.
    pub scale: ScaleFactorPrior,
    /// The simulator's truth, for the oracle candidates (ranked apart, see
    /// [`super::report::TournamentReport::oracle_gaps`]).
    pub oracle: Option<&'a TrueModel>,
}

/// How the replicates differ from the main run.
pub enum Replicates<'a> {
    /// No replicate: the ranking of the main run alone.
    None,
    /// `extra` replicates, each with every outage moved by one seeded shift, uniform within
    /// ± half the smallest margin (between outages and to the data's ends), so that windows
    /// never overlap or leave the data.
    ShiftedOutages {
        /// Replicates beside the main run.
        extra: usize,
        /// Seed of the shifts (stream "evaluate/outage-shift").
        seed: u64,
    },
    /// `extra` replicates made by the caller (for instance surveys simulated anew).
    Made {
        /// Replicates beside the main run.
        extra: usize,
        /// How they differ, in words (for the report).
        differ_by: &'static str,
        /// Replicate `k` (1-based: the main run is 0).
        make: &'a (dyn Fn(usize) -> Result<Scenario, String> + Sync),
    },
}

impl Replicates<'_> {
    /// Replicates beside the main run.
    pub fn extra(&self) -> usize {
        match self {
            Self::None => 0,
            Self::ShiftedOutages { extra, .. } | Self::Made { extra, .. } => *extra,
        }
    }

    /// How the replicates differ, in words.
    pub fn differ_by(&self) -> &'static str {
        match self {
            Self::None => "no replicates",
            Self::ShiftedOutages { .. } => {
                "shifted outage start times (one common random shift per replicate)"
            }
            Self::Made { differ_by, .. } => differ_by,
        }
    }
}

/// Why a tournament cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TournamentError {
    /// No bank entry (or profile temperature) gave a usable model.
    #[error("no model of the bank or profile can be used:\n  {}", reasons.join("\n  "))]
    NoUsableModel {
        /// Each excluded candidate with its reason.
        reasons: Vec<String>,
    },
    /// More replicates than [`MAX_REPLICATES`].
    #[error("{asked} replicates asked for; at most {MAX_REPLICATES} are run")]
    TooManyReplicates {
        /// Replicates asked for, the main run included.
        asked: usize,
    },
    /// More shards than runs: a shard would hold none.
    #[error(
        "shard count {count}: the tournament has {runs} runs (replicates x models x filters), so at most {runs} shards"
    )]
    ShardCount {
        /// Shards asked for.
        count: usize,
        /// Runs of the tournament.
        runs: usize,
    },
    /// A shifted outage list is unusable.
    #[error("shifted outages: {0}")]
    Outage(#[from] OutageError),
    /// The caller could not make a replicate.
    #[error("replicate {index}: {reason}")]
    Replicate {
        /// Its index (1-based).
        index: usize,
        /// Why.
        reason: String,
    },
}

/// A tournament ready to run: its candidates and the ones left out.
#[derive(Debug, Clone)]
pub struct Tournament {
    candidates: Vec<Candidate>,
    excluded: Vec<Excluded>,
    operating_temperature_c: f64,
    source: GaussMarkovSource,
    filters: Vec<FilterKind>,
}

/// What a tournament gave: the report and the main run's results (with per-epoch errors).
#[derive(Debug, Clone)]
pub struct TournamentOutcome {
    /// The report (the `evaluation.json` contract).
    pub report: TournamentReport,
    /// The main run, candidate-major, in the report's model order.
    pub main: Vec<ModelResult>,
}

impl Tournament {
    /// The candidates of `plan`.
    ///
    /// # Errors
    /// [`TournamentError::NoUsableModel`] when only the pooled and data-sheet baselines can
    /// be used: they alone answer no question.
    pub fn new(plan: &TournamentPlan) -> Result<Self, TournamentError> {
        let (candidates, excluded) = plan_candidates(plan);
        if candidates
            .iter()
            .all(|c| c.kind.is_baseline() || c.kind.is_oracle())
        {
            let reasons = excluded
                .iter()
                .map(|e| format!("{}: {}", e.label, e.reason))
                .collect();
            return Err(TournamentError::NoUsableModel { reasons });
        }
        Ok(Self {
            candidates,
            excluded,
            operating_temperature_c: plan.operating_temperature_c,
            source: plan.source,
            filters: plan.filters.clone(),
        })
    }

    /// The tournament with every candidate's white-noise densities multiplied by `factor`
    /// (as `process_noise_scale` does to one run's model), the oracle's excepted: it is the
    /// simulator's truth, which no tuning changes.
    pub fn with_process_noise_scale(mut self, factor: f64) -> Self {
        if factor == 1.0 {
            return self;
        }
        for candidate in (self.candidates.iter_mut()).filter(|c| !c.kind.is_oracle()) {
            candidate.model.scale_white_noise(factor);
            if let Some(grid) = &mut candidate.schedule {
                std::sync::Arc::make_mut(grid).scale_white_noise(factor);
            }
        }
        self
    }

    /// The competing candidates.
    pub fn candidates(&self) -> &[Candidate] {
        &self.candidates
    }

    /// Filter runs in all, the replicates included (for progress).
    pub fn runs(&self, replicates: &Replicates) -> usize {
        self.candidates.len() * self.filters.len() * (1 + replicates.extra())
    }

    /// Runs the main scenario and the replicates; `on_done` is called after every run. The
    /// same as running [`Shard::WHOLE`] with [`Tournament::run_shard`] and merging it alone
    /// (which it does), so that a sharded run merged gives the same report.
    ///
    /// # Errors
    /// [`TournamentError`] for too many replicates or a replicate that cannot be made. A
    /// diverging filter is not an error: it is that model's outcome.
    pub fn run(
        &self,
        main: &Scenario,
        replicates: &Replicates,
        on_done: &(dyn Fn() + Sync),
    ) -> Result<TournamentOutcome, TournamentError> {
        let whole = self.run_shard(main, replicates, Shard::WHOLE, on_done)?;
        let merged = merge_shards(&[(String::from("the whole run"), whole)])
            .expect("one whole shard always merges");
        Ok(TournamentOutcome {
            report: merged.report,
            main: merged.main,
        })
    }

    /// Runs the share of the main scenario and the replicates that `shard` holds (see
    /// [`super::shard`]), with an empty fingerprint for the caller to fill; replicates with
    /// no run in the shard are not made. `on_done` is called after every run.
    ///
    /// # Errors
    /// As [`Tournament::run`].
    pub fn run_shard(
        &self,
        main: &Scenario,
        replicates: &Replicates,
        shard: Shard,
        on_done: &(dyn Fn() + Sync),
    ) -> Result<TournamentShard, TournamentError> {
        let asked = 1 + replicates.extra();
        if asked > MAX_REPLICATES {
            return Err(TournamentError::TooManyReplicates { asked });
        }
        let shifts_s = match replicates {
            Replicates::ShiftedOutages { extra, seed } => outage_shifts_s(main, *seed, *extra),
            _ => Vec::new(),
        };
        let per_replicate = self.candidates.len() * self.filters.len();
        if shard.count > asked * per_replicate {
            return Err(TournamentError::ShardCount {
                count: shard.count,
                runs: asked * per_replicate,
            });
        }
        // Replicates are made and run a few at a time (as many as the pool has threads, so
        // that no more scenarios than that are held at once), each one's runs in parallel too:
        // a simulated replicate is made on one core while another runs candidates. The runs
        // keep their order, so the output does not depend on the schedule.
        let pairs = (self.candidates.as_slice(), self.filters.as_slice());
        let replicate_runs = |index: usize| -> Result<Vec<ShardRun>, TournamentError> {
            let first = index * per_replicate;
            let held: Vec<usize> = (0..per_replicate)
                .filter(|p| shard.holds(first + p))
                .collect();
            if held.is_empty() {
                return Ok(Vec::new());
            }
            let made;
            let scenario = match index {
                0 => main,
                _ => {
                    made = replicate(main, replicates, &shifts_s, index)?;
                    &made
                }
            };
            let mut results = run_selected(scenario, pairs, &held, on_done);
            if index > 0 {
                drop_epoch_errors(&mut results);
            }
            let numbered = held.iter().zip(&results);
            Ok(numbered.map(|(p, r)| stored_run(first + p, r)).collect())
        };
        let indices: Vec<usize> = (0..asked).collect();
        let mut runs = Vec::new();
        for group in indices.chunks(rayon::current_num_threads().max(1)) {
            let made: Vec<_> = group.par_iter().map(|&k| replicate_runs(k)).collect();
            for replicate in made {
                runs.extend(replicate?);
            }
        }
        Ok(TournamentShard {
            shard,
            fingerprint: BTreeMap::new(),
            frame: self.frame(main, replicates),
            runs,
        })
    }

    /// What every shard of this tournament on `main` with `replicates` shares.
    fn frame(&self, main: &Scenario, replicates: &Replicates) -> ShardFrame {
        let models = self.candidates.iter().flat_map(|c| {
            self.filters.iter().map(|f| FrameModel {
                label: c.label.clone(),
                candidate: c.kind,
                filter: *f,
            })
        });
        ShardFrame {
            operating_temperature_c: self.operating_temperature_c,
            gauss_markov_source: self.source,
            filters: self.filters.clone(),
            outages: outage_spans(main.settings.outages.windows()),
            models: models.collect(),
            excluded: self.excluded.clone(),
            replicates: 1 + replicates.extra(),
            replicates_differ_by: replicates.differ_by().into(),
            reference_content: main.reference_content,
        }
    }
}

/// The candidates of a plan and the ones left out, the oracle's last.
fn plan_candidates(plan: &TournamentPlan) -> (Vec<Candidate>, Vec<Excluded>) {
    let (mut candidates, mut excluded) = model_candidates(plan);
    if let Some(truth) = plan.oracle {
        let (more, left_out) = match plan.thermal.imu_temperature_range_c {
            Some(range_c) => oracle_candidates(truth, range_c, plan.operating_temperature_c),
            None => (
                Vec::new(),
                vec![Excluded {
                    label: "truth scheduled".into(),
                    reason: "the IMU record has no temp_c to schedule the truth by".into(),
                }],
            ),
        };
        // With compensation off no candidate runs on a compensated record, the oracle's
        // neither; on the record compensated with the bank's calibration only where the bank
        // holds one.
        let compensates = plan.thermal.compensation != Compensation::Off;
        let calibrated = matches!(plan.noise, CandidateSource::Bank(b) if b.thermal.is_some());
        candidates.extend(more.into_iter().filter(|c| match c.kind {
            CandidateKind::OracleCompensated => compensates,
            CandidateKind::OracleOnCalibrated => compensates && calibrated,
            _ => true,
        }));
        excluded.extend(left_out);
    }
    let noise = match plan.noise {
        CandidateSource::Bank(bank) => NoiseModel::Bank(bank),
        CandidateSource::Profile(profile) => NoiseModel::Profile(profile),
    };
    with_initial_uncertainty(&mut candidates, noise);
    (candidates, excluded)
}

/// The candidates of the plan's bank or profile and the ones left out.
fn model_candidates(plan: &TournamentPlan) -> (Vec<Candidate>, Vec<Excluded>) {
    let (t, scale) = (plan.operating_temperature_c, &plan.scale);
    let bank = match plan.noise {
        CandidateSource::Profile(profile) => {
            let datasheet = plan.datasheet.as_ref();
            return profile_candidates(profile, t, scale, &plan.thermal, datasheet);
        }
        CandidateSource::Bank(bank) => bank,
    };
    let datasheet = plan.datasheet.as_ref();
    let (mut candidates, mut excluded) =
        tournament_candidates(bank, t, plan.source, scale, datasheet);
    let (more, left_out) = thermal_candidates(bank, t, plan.source, scale, &plan.thermal);
    candidates.extend(more);
    excluded.extend(left_out);
    (candidates, excluded)
}

fn drop_epoch_errors(run: &mut [ModelResult]) {
    for m in run {
        if let Ok(e) = &mut m.outcome {
            e.errors.clear();
        }
    }
}

/// Replicate `index` (1-based) of `main`; `shifts_s` are the outage shifts of shifted
/// replicates.
fn replicate(
    main: &Scenario,
    replicates: &Replicates,
    shifts_s: &[f64],
    index: usize,
) -> Result<Scenario, TournamentError> {
    match replicates {
        Replicates::None => Ok(main.clone()),
        Replicates::ShiftedOutages { .. } => {
            let mut scenario = main.clone();
            scenario.settings.outages = main.settings.outages.shifted(shifts_s[index - 1])?;
            Ok(scenario)
        }
        Replicates::Made { make, .. } => {
            make(index).map_err(|reason| TournamentError::Replicate { index, reason })
        }
    }
}

/// The first `count` outage shifts of the seeded stream, s.
fn outage_shifts_s(main: &Scenario, seed: u64, count: usize) -> Vec<f64> {
    use rand::RngExt;
    let half = shift_bound_s(main);
    let mut rng = named_rng(seed, "evaluate/outage-shift");
    (0..count)
        .map(|_| {
            if half.is_finite() && half > 0.0 {
                rng.random_range(-half..half)
            } else {
                0.0
            }
        })
        .collect()
}

/// Half the smallest margin between outages and between them and the data's ends, s (the
/// ends count twice, as a window may move towards them only by half the margin either way).
fn shift_bound_s(main: &Scenario) -> f64 {
    let windows = main.settings.outages.windows();
    let (Some(first), Some(last)) = (main.increments.first(), main.increments.last()) else {
        return 0.0;
    };
    let mut margins: Vec<f64> = windows
        .windows(2)
        .map(|p| p[1].start.since(p[0].end).as_seconds())
        .collect();
    if let (Some(a), Some(b)) = (windows.first(), windows.last()) {
        margins.push(2.0 * a.start.since(first.time).as_seconds());
        margins.push(2.0 * last.time.since(b.end).as_seconds());
    }
    margins.iter().copied().fold(f64::INFINITY, f64::min) / 2.0
}
