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
    /// Log of the Gaussian density of the innovation, ln N(ν; 0, S) =
    /// −(NIS + ln det S + m ln 2π)/2 with m the dimension: what a Gaussian sum of filters
    /// weighs its members by ([`super::gaussian_sum`]). Not written to files.
    #[serde(skip)]
    pub log_likelihood: f64,
    /// The factor the gate's chi-square quantile was widened by for this update, from the
    /// recent NIS level (1 = the plain gate; see [`crate::filter::gating::ScaledGate`]).
    pub gate_scale: f64,
    /// False when the chi-square gate rejected it.
    pub accepted: bool,
    /// True when it failed the gate but was applied after too many rejections in a row.
    pub forced: bool,
}

/// Statistics of one measurement kind over a run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
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
#[derive(Debug, Clone, Default, PartialEq)]
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

/// Where a run's records go as the filter makes them (an observer of the run, not code inside
/// its loop): the in-memory [`Solution`], a [`SolutionSummary`], or a writer that streams them
/// to files. Epochs arrive in time order, each once and final (the engine holds the last one
/// back until the updates at its time are done).
pub trait SolutionSink {
    /// One solution epoch.
    fn epoch(&mut self, epoch: &SolutionEpoch);
    /// One measurement update (accepted or rejected).
    fn innovation(&mut self, record: &InnovationRecord);
}

impl SolutionSink for Solution {
    fn epoch(&mut self, epoch: &SolutionEpoch) {
        self.epochs.push(*epoch);
    }

    fn innovation(&mut self, record: &InnovationRecord) {
        self.innovations.push(*record);
    }
}

/// Runs `body` with a sink that hands every record, in order, to `inner` on a thread of its
/// own, in batches of [`HANDOVER_BATCH`] with at most [`HANDOVER_BATCHES`] batches in flight
/// (so memory stays bounded): writing a solution at the IMU rate costs about as much as
/// computing it, and the two then share the two cores. Returns what `body` returns once
/// `inner` has seen every record. A panic on the writer's thread is resumed here.
pub fn with_sink_on_own_thread<S, R>(
    inner: &mut S,
    body: impl FnOnce(&mut dyn SolutionSink) -> R,
) -> R
where
    S: SolutionSink + Send,
{
    let (sender, receiver) = std::sync::mpsc::sync_channel::<Vec<Handover>>(HANDOVER_BATCHES);
    std::thread::scope(|scope| {
        let writer = scope.spawn(move || {
            for batch in receiver {
                for record in batch {
                    match record {
                        Handover::Epoch(epoch) => inner.epoch(&epoch),
                        Handover::Innovation(record) => inner.innovation(&record),
                    }
                }
            }
        });
        let mut batching = Batching {
            sender,
            batch: Vec::with_capacity(HANDOVER_BATCH),
        };
        let result = body(&mut batching);
        batching.send();
        drop(batching);
        if let Err(panic) = writer.join() {
            std::panic::resume_unwind(panic);
        }
        result
    })
}

/// Records per handover batch of [`with_sink_on_own_thread`].
pub const HANDOVER_BATCH: usize = 1024;
/// Batches in flight at most in [`with_sink_on_own_thread`] (about 3 MB of epochs).
pub const HANDOVER_BATCHES: usize = 8;

// Boxing the epoch would allocate once per record; the batches are what bound the memory.
#[allow(clippy::large_enum_variant)]
enum Handover {
    Epoch(SolutionEpoch),
    Innovation(InnovationRecord),
}

struct Batching {
    sender: std::sync::mpsc::SyncSender<Vec<Handover>>,
    batch: Vec<Handover>,
}

impl Batching {
    fn push(&mut self, record: Handover) {
        self.batch.push(record);
        if self.batch.len() == HANDOVER_BATCH {
            self.send();
        }
    }

    /// Sends the batch; a writer that stopped has panicked, which the join resumes.
    fn send(&mut self) {
        if !self.batch.is_empty() {
            let batch = std::mem::replace(&mut self.batch, Vec::with_capacity(HANDOVER_BATCH));
            let _ = self.sender.send(batch);
        }
    }
}

impl SolutionSink for Batching {
    fn epoch(&mut self, epoch: &SolutionEpoch) {
        self.push(Handover::Epoch(*epoch));
    }

    fn innovation(&mut self, record: &InnovationRecord) {
        self.push(Handover::Innovation(*record));
    }
}

impl<S: SolutionSink + ?Sized> SolutionSink for &mut S {
    fn epoch(&mut self, epoch: &SolutionEpoch) {
        (**self).epoch(epoch);
    }

    fn innovation(&mut self, record: &InnovationRecord) {
        (**self).innovation(record);
    }
}

/// Both sinks see every record.
impl<A: SolutionSink, B: SolutionSink> SolutionSink for (A, B) {
    fn epoch(&mut self, epoch: &SolutionEpoch) {
        self.0.epoch(epoch);
        self.1.epoch(epoch);
    }

    fn innovation(&mut self, record: &InnovationRecord) {
        self.0.innovation(record);
        self.1.innovation(record);
    }
}

/// What a run's report needs of its records, accumulated record by record in bounded memory:
/// the first epoch's time, the last epoch, and the innovation statistics (the same sums in the
/// same order as [`Solution::innovation_statistics`], so the same numbers to the bit).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SolutionSummary {
    /// Time of the first epoch.
    pub first_time: Option<Timestamp>,
    /// The last epoch.
    pub last: Option<SolutionEpoch>,
    /// Epochs seen.
    pub epochs: usize,
    tallies: [Tally; 3],
}

/// Running sums of one measurement kind's updates.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Tally {
    offered: usize,
    accepted: usize,
    forced: usize,
    nis_sum: f64,
    nis_in_95: usize,
    innovation_squares: [f64; 3],
    gate_scale_sum: f64,
    /// The 95 % NIS band, computed at the first accepted update.
    band: Option<(f64, f64)>,
}

impl SolutionSummary {
    /// The summary of a whole solution's records.
    pub fn of(solution: &Solution) -> Self {
        let mut summary = Self::default();
        solution.epochs.iter().for_each(|e| summary.epoch(e));
        (solution.innovations.iter()).for_each(|r| summary.innovation(r));
        summary
    }

    /// Span from the first epoch to the last, s (0 without two epochs).
    pub fn span_s(&self) -> f64 {
        match (self.first_time, &self.last) {
            (Some(a), Some(b)) => b.estimate.nav.time.since(a).as_seconds(),
            _ => 0.0,
        }
    }

    /// Statistics per measurement kind present in the run.
    pub fn innovation_statistics(&self) -> Vec<InnovationStatistics> {
        MeasurementKind::ALL
            .into_iter()
            .filter_map(|kind| self.tallies[kind as usize].statistics(kind))
            .collect()
    }
}

impl SolutionSink for SolutionSummary {
    fn epoch(&mut self, epoch: &SolutionEpoch) {
        self.first_time = self.first_time.or(Some(epoch.estimate.nav.time));
        self.last = Some(*epoch);
        self.epochs += 1;
    }

    fn innovation(&mut self, record: &InnovationRecord) {
        let tally = &mut self.tallies[record.kind as usize];
        tally.offered += 1;
        tally.forced += usize::from(record.forced);
        tally.gate_scale_sum += record.gate_scale;
        if !record.accepted {
            return;
        }
        let band = tally.band.or_else(|| nis_band_95(record.kind));
        tally.band = band;
        let (lo, hi) = band.unwrap_or((f64::NAN, f64::NAN));
        tally.accepted += 1;
        tally.nis_sum += record.nis;
        tally.nis_in_95 += usize::from(record.nis >= lo && record.nis <= hi);
        for (sum, v) in tally.innovation_squares.iter_mut().zip(record.innovation) {
            *sum += v.powi(2);
        }
    }
}

impl Tally {
    fn statistics(&self, kind: MeasurementKind) -> Option<InnovationStatistics> {
        if self.offered == 0 {
            return None;
        }
        nis_band_95(kind)?;
        let n = self.accepted.max(1) as f64;
        Some(InnovationStatistics {
            kind,
            dimension: kind.dimension(),
            offered: self.offered,
            rejected: self.offered - self.accepted,
            forced: self.forced,
            mean_nis: self.nis_sum / n,
            fraction_nis_in_95: self.nis_in_95 as f64 / n,
            rms_innovation: self.innovation_squares.map(|s| (s / n).sqrt()),
            mean_gate_scale: self.gate_scale_sum / self.offered as f64,
        })
    }
}

/// The two-sided 95 % interval of a chi-square with the kind's dimension.
fn nis_band_95(kind: MeasurementKind) -> Option<(f64, f64)> {
    let chi = ChiSquared::new(kind.dimension() as f64).ok()?;
    Some((chi.inverse_cdf(0.025), chi.inverse_cdf(0.975)))
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
