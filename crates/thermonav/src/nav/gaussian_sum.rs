//! A Gaussian sum of filters over the z-gyro bias, for runs whose heading nothing observes
//! directly (position-only GNSS, no heading aiding).
//!
//! With position fixes only, the heading is seen only through horizontal accelerations. A
//! MEMS z gyro's turn-on bias (about 1 °/s on the data sheet) turns the heading by tens of
//! degrees before the first speed change shows it, and a single filter linearised about a
//! heading that far off then "converges" to a wrong bias with a small sd. Here the prior of
//! the z-gyro bias, N(b̂, σ²), is split into members on a grid, N(b̂ + σ zₖ, (σ s)²) with weights
//! wₖ ∝ exp(−zₖ²/(2(1 − s²))) and s² chosen so that the mixture's variance is σ² exactly; each
//! member is an ordinary filter (EKF or UKF) whose bias error stays small enough for its
//! linearisation to hold. All members run in lockstep on the same increments and fixes; every
//! update multiplies a member's weight by the density of its innovation, N(ν; 0, S) (offered
//! updates, accepted or not: a member that rejects a fix others accept has explained it
//! worse). A member whose normalised weight falls below [`BiasHypotheses::prune_below`] is
//! dropped, so the cost falls to about one filter's once the heading has been seen. A member
//! that diverges is dropped too.
//!
//! The solution is the mixture's: at each epoch the members' estimates as errors ⊖ from the
//! heaviest one, their weighted mean applied to it, and the sd of each state from the
//! weighted variances plus the spread of the members. Its innovations are those of the
//! heaviest member at each update.

use super::engine::{
    BiasHypotheses, Filtering, MAX_BIAS_HYPOTHESES, NavError, Run, StreamError, StreamTail,
    check_fix_latitudes, check_imu_gaps, check_settings,
};
use super::error_state::ErrorVector;
use super::solution::{InnovationRecord, SolutionEpoch, SolutionSink};
use crate::gnss::GnssFix;
use crate::ins::error_model::{STATES, block};
use crate::ins::state::Increment;
use std::cell::RefCell;
use std::rc::Rc;

/// Index of the z-gyro bias in the error state.
const GYRO_Z_BIAS: usize = block::GYRO_BIAS + 2;

/// One member's place in the prior: offset and sd in units of the prior sd, and weight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Member {
    /// Offset of its mean from the prior's, in prior sds.
    pub offset_sd: f64,
    /// Its sd, in prior sds.
    pub sd: f64,
    /// Its prior weight (the weights add up to 1).
    pub weight: f64,
}

impl BiasHypotheses {
    /// The members' places in the prior ([`split_prior`]), checked first against
    /// [`MAX_BIAS_HYPOTHESES`] so that nothing is allocated for an absurd count.
    ///
    /// # Errors
    /// [`NavError::BiasHypotheses`] for more than [`MAX_BIAS_HYPOTHESES`] members, or a count or
    /// span that [`split_prior`] cannot split.
    pub fn split(&self) -> Result<Vec<Member>, NavError> {
        let refused = NavError::BiasHypotheses(self.members);
        if self.members > MAX_BIAS_HYPOTHESES {
            return Err(refused);
        }
        split_prior(self.members, self.span_sd).ok_or(refused)
    }
}

/// The members of the split: offsets on an even grid over ±`span_sd`, weights from a normal of
/// variance 1 − s² with s the grid spacing, and the members' common sd s' then set so that the
/// mixture's variance is 1 exactly (s'² = 1 − Σ wₖ zₖ²). `None` for an even or zero count, a
/// non-positive span, or a grid too coarse for s'² > 0.
pub fn split_prior(members: usize, span_sd: f64) -> Option<Vec<Member>> {
    if members % 2 == 0 || !(span_sd > 0.0 && span_sd.is_finite()) {
        return None;
    }
    if members == 1 {
        return Some(vec![Member {
            offset_sd: 0.0,
            sd: 1.0,
            weight: 1.0,
        }]);
    }
    let spacing = 2.0 * span_sd / (members - 1) as f64;
    let spread = 1.0 - spacing * spacing;
    if spread <= 0.0 {
        return None;
    }
    let offsets: Vec<f64> = (0..members)
        .map(|k| -span_sd + spacing * k as f64)
        .collect();
    let raw: Vec<f64> = offsets
        .iter()
        .map(|z| (-z * z / (2.0 * spread)).exp())
        .collect();
    let total: f64 = raw.iter().sum();
    let grid_variance: f64 = offsets
        .iter()
        .zip(&raw)
        .map(|(z, w)| w / total * z * z)
        .sum();
    let within = 1.0 - grid_variance;
    if within <= 0.0 {
        return None;
    }
    Some(
        offsets
            .iter()
            .zip(&raw)
            .map(|(z, w)| Member {
                offset_sd: *z,
                sd: within.sqrt(),
                weight: w / total,
            })
            .collect(),
    )
}

/// What a member's run handed its sink since the last look, in order.
#[derive(Debug, Default)]
struct Records {
    items: Vec<Record>,
}

/// One record a member handed over. (Kept by value: a few per increment, reused buffers; boxing
/// the epochs would allocate for each.)
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy)]
enum Record {
    Epoch(SolutionEpoch),
    Innovation(InnovationRecord),
}

impl Record {
    fn innovation(&self) -> Option<&InnovationRecord> {
        match self {
            Record::Innovation(r) => Some(r),
            Record::Epoch(_) => None,
        }
    }

    fn epoch(&self) -> Option<&SolutionEpoch> {
        match self {
            Record::Epoch(e) => Some(e),
            Record::Innovation(_) => None,
        }
    }
}

/// A member's sink: its records wait in a shared buffer until the sum combines them.
struct Buffered(Rc<RefCell<Records>>);

impl SolutionSink for Buffered {
    fn epoch(&mut self, epoch: &SolutionEpoch) {
        self.0.borrow_mut().items.push(Record::Epoch(*epoch));
    }

    fn innovation(&mut self, record: &InnovationRecord) {
        self.0.borrow_mut().items.push(Record::Innovation(*record));
    }
}

/// The fixes after the start, as a member reads them.
type Fixes<'f> = std::iter::Peekable<std::iter::Copied<std::slice::Iter<'f, &'f GnssFix>>>;

/// A member still in the sum.
struct Live<'a, 's, 'f> {
    run: Option<Run<'a, 's>>,
    records: Rc<RefCell<Records>>,
    fixes: Fixes<'f>,
    log_weight: f64,
}

/// [`super::navigate::run_streaming`] with the z-gyro bias prior split into a Gaussian sum
/// (see the module's documentation); the mixture's epochs and the heaviest member's
/// innovations go to `sink`. Smoothing is refused (a sum has no single forward history).
///
/// # Errors
/// As [`super::navigate::run_streaming`]; [`NavError::Setting`] for a split [`split_prior`]
/// refuses or `smooth`; the last member's divergence when every member diverged.
pub fn run_gaussian_sum<E>(
    filtering: Filtering,
    hypotheses: &BiasHypotheses,
    increments: impl IntoIterator<Item = Result<Increment, E>>,
    gnss: &[GnssFix],
    sink: &mut dyn SolutionSink,
    progress: &mut dyn FnMut(usize),
) -> Result<StreamTail, StreamError<E>> {
    let settings = filtering.settings;
    check_settings(settings)?;
    check_fix_latitudes(gnss)?;
    if settings.smooth {
        return Err(NavError::Setting {
            what: "smooth (not available with a Gaussian sum)",
            value: 1.0,
        }
        .into());
    }
    let members = hypotheses.split()?;
    let start = filtering.initial.nav.time;
    let starts: Vec<_> = members
        .iter()
        .map(|m| member_start(&filtering, m))
        .collect();
    let carried: Vec<_> = starts
        .iter()
        .map(|(_, p0)| filtering.schedule.keeping_turn_on_bias(p0, start))
        .collect();
    let after_start: Vec<&GnssFix> = gnss.iter().filter(|f| f.time > start).collect();
    let mut sinks: Vec<Buffered> = members.iter().map(|_| Buffered(Rc::default())).collect();
    let mut live = Vec::with_capacity(members.len());
    for (k, member_sink) in sinks.iter_mut().enumerate() {
        let records = Rc::clone(&member_sink.0);
        let member_filtering = Filtering {
            initial: starts[k].0,
            p0: starts[k].1,
            schedule: carried[k].schedule(),
            settings,
        };
        live.push(Live {
            run: Some(Run::new(member_filtering, member_sink)?),
            records,
            fixes: after_start.iter().copied().peekable(),
            log_weight: members[k].weight.ln(),
        });
    }
    let mut sum = Sum { live };
    sum.combine(sink);
    let mut n = 0;
    for inc in increments {
        let inc = inc.map_err(StreamError::Input)?;
        if inc.time <= start {
            continue;
        }
        check_imu_gaps(std::slice::from_ref(&inc), settings.max_imu_gap_s)?;
        sum.feed(inc, start)?;
        sum.combine(sink);
        sum.prune(hypotheses.prune_below);
        if n % 4096 == 0 {
            progress(n);
        }
        n += 1;
    }
    if n == 0 {
        return Err(NavError::NoImu(start.as_seconds()).into());
    }
    sum.finish()?;
    sum.combine(sink);
    progress(n);
    Ok(StreamTail {
        imu_samples: n,
        smoothed: Vec::new(),
    })
}

/// A member's start: the z-gyro bias estimate moved by its offset, that bias's row and column
/// of P0 scaled by its sd (its variance by the sd squared, its correlations kept).
fn member_start(
    filtering: &Filtering,
    member: &Member,
) -> (
    super::error_state::Estimate,
    crate::ins::error_model::SystemMatrix,
) {
    let prior_sd = filtering.p0[(GYRO_Z_BIAS, GYRO_Z_BIAS)].max(0.0).sqrt();
    let mut initial = filtering.initial;
    initial.sensors.gyro_bias_rad_s[2] += prior_sd * member.offset_sd;
    let mut p0 = filtering.p0;
    for j in 0..STATES {
        p0[(GYRO_Z_BIAS, j)] *= member.sd;
        p0[(j, GYRO_Z_BIAS)] *= member.sd;
    }
    (initial, p0)
}

/// The members in the sum.
struct Sum<'a, 's, 'f> {
    live: Vec<Live<'a, 's, 'f>>,
}

impl Sum<'_, '_, '_> {
    /// Feeds one increment to every member; a member that diverges is dropped (with what it
    /// had recorded since the last combination). When the last one diverges, its error.
    fn feed(&mut self, inc: Increment, start: crate::time::Timestamp) -> Result<(), NavError> {
        let mut failure = None;
        self.live.retain_mut(|member| {
            let Some(run) = member.run.as_mut() else {
                return true;
            };
            match run.feed(inc, start, &mut member.fixes) {
                Ok(()) => true,
                Err(e) => {
                    failure = Some(e);
                    false
                }
            }
        });
        match failure {
            Some(e) if self.live.is_empty() || !matches!(e, NavError::Diverged { .. }) => Err(e),
            _ => Ok(()),
        }
    }

    /// Ends every member's run (the last propagation and epoch).
    fn finish(&mut self) -> Result<(), NavError> {
        let mut failure = None;
        self.live
            .retain_mut(|member| match member.run.take().map(Run::finish) {
                Some(Err(e)) => {
                    failure = Some(e);
                    false
                }
                _ => true,
            });
        match failure {
            Some(e) if self.live.is_empty() => Err(e),
            _ => Ok(()),
        }
    }

    /// Hands the mixture of what the members recorded since the last call to `sink`. The
    /// members run in lockstep, so their records line up one for one.
    fn combine(&mut self, sink: &mut dyn SolutionSink) {
        let taken: Vec<Vec<Record>> = self
            .live
            .iter()
            .map(|m| std::mem::take(&mut m.records.borrow_mut().items))
            .collect();
        let count = taken.iter().map(Vec::len).min().unwrap_or(0);
        debug_assert!(taken.iter().all(|t| t.len() == count));
        for j in 0..count {
            match taken[0][j] {
                Record::Innovation(_) => {
                    let records: Vec<&InnovationRecord> =
                        taken.iter().filter_map(|t| t[j].innovation()).collect();
                    self.weigh(&records);
                    sink.innovation(records[self.heaviest()]);
                }
                Record::Epoch(_) => {
                    let epochs: Vec<&SolutionEpoch> =
                        taken.iter().filter_map(|t| t[j].epoch()).collect();
                    sink.epoch(&self.mixture(&epochs));
                }
            }
        }
    }

    /// Multiplies each member's weight by its innovation's density (kept as logs, the largest
    /// at 0). When no member's density is positive the weights are left as they were.
    fn weigh(&mut self, records: &[&InnovationRecord]) {
        let updated: Vec<f64> = self
            .live
            .iter()
            .zip(records)
            .map(|(m, r)| m.log_weight + r.log_likelihood)
            .collect();
        let top = updated.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !top.is_finite() {
            return;
        }
        for (m, w) in self.live.iter_mut().zip(updated) {
            m.log_weight = w - top;
        }
    }

    fn heaviest(&self) -> usize {
        let mut best = 0;
        for (k, m) in self.live.iter().enumerate() {
            if m.log_weight > self.live[best].log_weight {
                best = k;
            }
        }
        best
    }

    /// The members' weights, adding up to 1.
    fn weights(&self) -> Vec<f64> {
        let top = self.live[self.heaviest()].log_weight;
        let raw: Vec<f64> = self
            .live
            .iter()
            .map(|m| (m.log_weight - top).exp())
            .collect();
        let total: f64 = raw.iter().sum();
        raw.iter().map(|w| w / total).collect()
    }

    /// The mixture of one epoch of every member (a single member's epoch as it is).
    fn mixture(&self, epochs: &[&SolutionEpoch]) -> SolutionEpoch {
        if epochs.len() == 1 {
            return *epochs[0];
        }
        mixture_of(epochs, &self.weights(), self.heaviest())
    }

    /// Drops the members whose weight fell below `threshold` (never the heaviest).
    fn prune(&mut self, threshold: f64) {
        if self.live.len() < 2 {
            return;
        }
        let weights = self.weights();
        let mut k = 0;
        self.live.retain(|_| {
            let keep = weights[k] >= threshold;
            k += 1;
            keep
        });
    }
}

/// The mixture of `epochs` with `weights` (adding up to 1): every estimate as its error ⊖ from
/// the `reference` one, the weighted mean of those errors applied to the reference, and each
/// state's sd from the weighted second moments about that mean (Σ wₖ (σₖ² + (δxₖ − δx̄)²)).
pub fn mixture_of(epochs: &[&SolutionEpoch], weights: &[f64], reference: usize) -> SolutionEpoch {
    let reference = *epochs[reference];
    let errors: Vec<ErrorVector> = epochs
        .iter()
        .map(|e| e.estimate.error_from(&reference.estimate))
        .collect();
    let mean: ErrorVector = errors
        .iter()
        .zip(weights)
        .fold(ErrorVector::zeros(), |acc, (dx, w)| acc + dx * *w);
    let sd = std::array::from_fn(|i| {
        epochs
            .iter()
            .zip(&errors)
            .zip(weights)
            .map(|((e, dx), w)| w * (e.sd[i] * e.sd[i] + (dx[i] - mean[i]).powi(2)))
            .sum::<f64>()
            .sqrt()
    });
    SolutionEpoch {
        estimate: reference.estimate.corrected_by(&mean),
        sd,
        in_outage: reference.in_outage,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nav::error_state::sample_estimate;

    fn normal_pdf(x: f64, mean: f64, sd: f64) -> f64 {
        (-(x - mean).powi(2) / (2.0 * sd * sd)).exp() / (sd * (2.0 * std::f64::consts::PI).sqrt())
    }

    // Closed forms of the split: the weights add up to 1, the mixture's mean is 0 and its
    // variance Σ wₖ (zₖ² + s²) is 1 to rounding, the grid is symmetric; and its density is the
    // standard normal's within 0.005 everywhere on ±6 (of a peak of 0.399: the truncation at
    // ±3 sd moves 0.3 % of the mass inward; 0.0030 measured for 41 members).
    #[test]
    fn the_split_keeps_the_prior_mean_and_variance_and_its_shape() {
        for members in [1, 9, 21, 41, 61] {
            let split = split_prior(members, 3.0).unwrap();
            assert_eq!(split.len(), members);
            let total: f64 = split.iter().map(|m| m.weight).sum();
            let mean: f64 = split.iter().map(|m| m.weight * m.offset_sd).sum();
            let variance: f64 = split
                .iter()
                .map(|m| m.weight * (m.offset_sd.powi(2) + m.sd.powi(2)))
                .sum();
            assert!((total - 1.0).abs() < 1e-12, "{members}: {total}");
            assert!(mean.abs() < 1e-12, "{members}: {mean}");
            assert!((variance - 1.0).abs() < 1e-12, "{members}: {variance}");
            for (a, b) in split.iter().zip(split.iter().rev()) {
                assert!((a.offset_sd + b.offset_sd).abs() < 1e-12);
                assert!((a.weight - b.weight).abs() < 1e-15);
            }
        }
        let split = split_prior(41, 3.0).unwrap();
        for i in 0..=1200 {
            let x = -6.0 + 0.01 * f64::from(i);
            let mixture: f64 = split
                .iter()
                .map(|m| m.weight * normal_pdf(x, m.offset_sd, m.sd))
                .sum();
            assert!((mixture - normal_pdf(x, 0.0, 1.0)).abs() < 0.005, "x {x}");
        }
    }

    #[test]
    fn splits_that_cannot_be_made_are_refused() {
        assert!(split_prior(0, 3.0).is_none());
        assert!(split_prior(4, 3.0).is_none());
        assert!(split_prior(5, 0.0).is_none());
        assert!(split_prior(5, f64::NAN).is_none());
        // 3 members over ±3 sd are 3 sd apart: no room left for the members' own spread.
        assert!(split_prior(3, 3.0).is_none());
    }

    // Closed form: two members 10 m apart north and 0.01 rad/s apart in the z-gyro bias, with
    // weights 1/4 and 3/4, mix to the point 3/4 of the way (as an error from the first) with
    // variance Σ w (σ² + (δ − δ̄)²) per state; 1e-9: the ⊕/⊖ round trip through geodetic
    // position.
    #[test]
    fn the_mixture_is_the_weighted_mean_with_the_spread_added() {
        let first = sample_estimate();
        let mut dx = ErrorVector::zeros();
        dx[block::POSITION] = 10.0;
        dx[GYRO_Z_BIAS] = 0.01;
        let second = first.corrected_by(&dx);
        let epoch = |estimate, sd: f64| SolutionEpoch {
            estimate,
            sd: [sd; STATES],
            in_outage: false,
        };
        let (a, b) = (epoch(first, 1.0), epoch(second, 2.0));
        let mixed = mixture_of(&[&a, &b], &[0.25, 0.75], 0);
        let moved = mixed.estimate.error_from(&first);
        for i in 0..STATES {
            assert!(
                (moved[i] - 0.75 * dx[i]).abs() < 1e-9,
                "state {i}: {}",
                moved[i]
            );
            let spread =
                0.25 * (1.0 + (0.75 * dx[i]).powi(2)) + 0.75 * (4.0 + (0.25 * dx[i]).powi(2));
            assert!((mixed.sd[i] - spread.sqrt()).abs() < 1e-9, "state {i}");
        }
        // The same mixture taken from the other member.
        let other = mixture_of(&[&a, &b], &[0.25, 0.75], 1);
        let gap = other.estimate.error_from(&mixed.estimate);
        assert!(gap.iter().all(|v| v.abs() < 1e-9), "{gap:?}");
    }
}
