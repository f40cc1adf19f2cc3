//! Thermal calibration from temperature sweeps alone, with a thermal-lag term, chosen by what
//! it predicts on legs it was not fitted to.
//!
//! # Blocks
//! Each sweep piece is cut into consecutive blocks of `block_s` seconds from its first sample
//! (a last, shorter block is dropped); a block's observation is the mean of every channel, of
//! the temperature and of the temperature's rate ([`super::legs`], "Rate") over its samples,
//! and its leg is the leg ([`super::legs::find_legs`], found within the piece) that holds its middle
//! sample. The default block ([`default_block_s`]) is the shorter of 300 s and the time the
//! temperature takes to move 1 °C at the piece's ramp rate (the 90th percentile of |dT/dt|,
//! since a chamber program dwells at its turns), and at least 10 samples.
//!
//! # Candidates
//! Per channel: order 0 (no thermal term: the channel is left uncompensated but for its
//! constant), b(T) of order 1..3, and b(T_τ) of order 1..3: the bias read at the temperature
//! of a structure that follows the sensor's through a first-order lag of time constant |τ|
//! ([`super::legs::lagged_temperatures`]; τ < 0 when the structure lags the sensor, τ > 0 for
//! the mirror, a structure that leads). To first order T_τ = T + τ·dT/dt, so the model is
//! b(T) + τ·b′(T)·dT/dt away from the turns, the loop a lagging structure draws; at the turns
//! the first-order lag is exact where the rate form is not. For a given τ the fit is linear
//! (the polynomial fit of [`super::calibrate`] on the blocks' mean lagged temperatures, with
//! one offset per power-on); τ is found by profiling the residual sum of squares over the
//! grid [`LAG_GRID_S`] (each block's lagged temperature computed from its samples there,
//! interpolated between), then golden-section search about the best.
//!
//! # Choice
//! Folds: with two or more legs, the legs; with one (or legs that share no temperature, so
//! that none can predict another), [`SEGMENTS_OF_ONE_LEG`] contiguous stretches of the
//! blocks in time (the lag cannot then be told from the curve: T alone). Each fold
//! is left out in turn: each candidate is fitted (τ profiled again) on the other folds and
//! predicts the left-out blocks that lie within their temperature range (outside it every
//! method clamps to the range's end, and the score would measure the range, not the model).
//! A fold's score is the mean square of those residuals about their own mean (the shape,
//! since a leg's level also holds the power-on's offset); for a stretch of one leg, whose
//! power-on kept the other stretches, about that power-on's fitted offset instead (within a
//! leg the stretch's level is the leg's shape, and the other stretches fix the offset). A
//! candidate's score is the mean over folds. The choice follows the one-standard-error rule, paired across folds: the simplest
//! candidate (fewest terms: order, plus one for the lag; T alone first on a tie) whose mean
//! excess over the best candidate's fold scores is within the standard error of that excess,
//! or within [`MIN_RELATIVE_GAIN`] of the best score. The excess of a fold is the log of the
//! ratio of the two fold scores, not their difference: folds differ in scale by orders of
//! magnitude (a fold that no candidate predicts, such as two cooling legs predicting a
//! heating one, where no lag can be fitted), and differences would let that one fold's
//! spread hide a clear gain on every other fold. So a term that does not predict
//! unseen legs is not used, and a channel where nothing clearly beats order 0 is left
//! uncompensated. A lag whose fit to every block runs to the search limit is not identified,
//! and the choice is made again without it. The best candidate in T alone, by the same rule,
//! is kept beside it for the autopilots' parameter files, which hold a cubic in T only.
//!
//! Leave-one-block-out PRESS, which the static fits use, is not used here: neighbouring
//! blocks of a sweep share its slow drift, so leaving one out hides little, and on the CATS
//! record it chose curves that made unseen legs worse than no compensation.
//!
//! # Band
//! A prediction's 95 % band is ±t·sqrt(s_shape² + s_level² + se(T)² + s_offset² + s_n²), t
//! Student's quantile at 0.975 with the spread's effective degrees of freedom (the held-out
//! residuals less one per fold, shrunk by their lag-1 autocorrelation ρ within folds to
//! ν(1 − ρ)/(1 + ρ): a spread measured on few, slowly varying legs is itself uncertain): s_shape
//! the held-out residuals' sd about their folds' means (for stretches of one leg, about their
//! power-on's fitted offset, as they are scored: within one leg a stretch's level is the leg's
//! shape, so the band without the offset keeps it, and there is no s_level), s_level the sd of
//! the held-out legs' mean residuals from their
//! power-on's fitted offset (where that power-on kept other legs), se(T) the fitted curve's
//! standard error, s_offset the uncertainty of the power-on's offset (its own sd, or the spread
//! between power-ons for a new one), s_n the noise of the observed mean itself (its samples'
//! variance over their count, from the record checked). The band with the offset removed drops s_level and
//! s_offset. Outside the fitted range the prediction is the range's end value and the band is
//! widened by |b′(end)|·distance, what a straight continuation would have added.
//!
//! # τ's interval
//! The profile interval {τ : RSS(τ) ≤ RSS(τ̂)·(1 + F_{1,ν;0.95}/ν)}, ν the residual degrees
//! of freedom shrunk by the residuals' lag-1 autocorrelation ρ to ν(1 − ρ)/(1 + ρ) (neighbouring
//! blocks of a sweep are not independent); an end that reaches the search limit is open.

use super::calibration::calibrate_channel;
use super::legs::{Leg, RATE_WINDOW_S, find_legs, lagged_temperatures, temperature_rates};
use super::selection::BAND_Z;
pub use super::selection::{
    Candidate, CandidateScore, ChoiceRule, HeldOutSelection, PredictionSpread, SweepBlock,
    SweepLeg, ThermalLag,
};
use super::{
    ChannelCalibration, FitSettings, LaggedBias, OrderChoice, PowerOnRecord, ThermalError,
};
use crate::imu::Channel;
use crate::optimise::golden_section::golden_section_minimum;
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, FisherSnedecor};
use std::collections::{BTreeMap, BTreeSet};

pub use super::legs::{LAG_GRID_S, LAG_SEARCH_S};

/// Longest default block of a sweep, s.
pub const MAX_DEFAULT_BLOCK_S: f64 = 300.0;

/// Fewest samples in a default block.
pub const MIN_BLOCK_SAMPLES: usize = 10;

/// Fewest blocks a sweep must give.
pub const MIN_SWEEP_BLOCKS: usize = 3;

/// Smallest temperature range a sweep must cover, °C.
pub const MIN_SWEEP_RANGE_C: f64 = 2.0;

/// One piece of a sweep, as plain columns: time (s), temperature (°C) and the channels.
#[derive(Debug, Clone, Copy)]
pub struct SweepPiece<'a> {
    /// Sample times, s, increasing.
    pub time_s: &'a [f64],
    /// Temperatures, °C.
    pub temperature_c: &'a [f64],
    /// The channels' columns (rate units), with the signal to take off each.
    pub channels: &'a [(Channel, &'a [f64], f64)],
}

/// Why a sweep cannot be calibrated from.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SweepError {
    /// A non-finite temperature.
    #[error("sample {index} has a non-finite temperature")]
    NonFiniteTemperature {
        /// Position of the sample.
        index: usize,
    },
    /// The temperature covers too small a range.
    #[error(
        "the temperature spans {span_c:.2} °C ({low_c:.2} to {high_c:.2} °C): a sweep must cover at least {MIN_SWEEP_RANGE_C} °C"
    )]
    TooNarrow {
        /// Coldest, °C.
        low_c: f64,
        /// Warmest, °C.
        high_c: f64,
        /// Warmest minus coldest.
        span_c: f64,
    },
    /// A gap between samples longer than a block.
    #[error(
        "a gap of {gap_s:.1} s after t = {at_s:.3} s is longer than a block ({block_s:.1} s): split the sweep there (pieces of one power-on are given comma-separated)"
    )]
    Gap {
        /// Time of the sample before the gap, s.
        at_s: f64,
        /// The gap, s.
        gap_s: f64,
        /// The block, s.
        block_s: f64,
    },
    /// Too few blocks.
    #[error(
        "{blocks} block(s) of {block_s:.1} s: a sweep needs at least {MIN_SWEEP_BLOCKS} (a longer record or a shorter --sweep-block-s)"
    )]
    TooFewBlocks {
        /// Blocks found.
        blocks: usize,
        /// The block, s.
        block_s: f64,
    },
    /// Columns of different lengths.
    #[error("the time, temperature and channel columns differ in length")]
    Ragged,
    /// The block length is not positive and finite.
    #[error("the block length {0} s is not a positive number")]
    BadBlock(f64),
}

/// The default block of a piece (module docs, "Blocks"), s.
pub fn default_block_s(time_s: &[f64], temperature_c: &[f64]) -> f64 {
    if time_s.len() != temperature_c.len() || time_s.is_empty() {
        return MAX_DEFAULT_BLOCK_S;
    }
    let rates = temperature_rates(time_s, temperature_c, RATE_WINDOW_S);
    let mut speeds: Vec<f64> = rates.iter().map(|r| r.abs()).collect();
    speeds.sort_by(f64::total_cmp);
    // The ramps' rate: a chamber program dwells at its turns, where the rate is zero.
    let ramp = speeds.get(speeds.len() * 9 / 10).copied().unwrap_or(0.0);
    let one_degree = if ramp > 0.0 {
        1.0 / ramp
    } else {
        f64::INFINITY
    };
    let mut dts: Vec<f64> = time_s.windows(2).map(|w| w[1] - w[0]).collect();
    dts.sort_by(f64::total_cmp);
    let dt = dts.get(dts.len() / 2).copied().unwrap_or(0.0);
    MAX_DEFAULT_BLOCK_S
        .min(one_degree)
        .max(MIN_BLOCK_SAMPLES as f64 * dt)
}

/// The blocks of one sweep piece of power-on `power_on`; its legs are numbered from
/// `first_leg`. Returns the blocks and the legs found.
///
/// # Errors
/// A non-finite temperature, a range under [`MIN_SWEEP_RANGE_C`], a gap longer than a block,
/// fewer than [`MIN_SWEEP_BLOCKS`] blocks, or a bad block length.
pub fn sweep_blocks(
    piece: SweepPiece<'_>,
    power_on: u32,
    first_leg: u32,
    block_s: f64,
) -> Result<(Vec<SweepBlock>, Vec<Leg>), SweepError> {
    if !(block_s.is_finite() && block_s > 0.0) {
        return Err(SweepError::BadBlock(block_s));
    }
    let n = piece.time_s.len();
    if piece.temperature_c.len() != n || piece.channels.iter().any(|c| c.1.len() != n) {
        return Err(SweepError::Ragged);
    }
    check_temperatures(piece.temperature_c)?;
    if let Some(k) =
        (1..piece.time_s.len()).find(|&k| piece.time_s[k] - piece.time_s[k - 1] > block_s)
    {
        return Err(SweepError::Gap {
            at_s: piece.time_s[k - 1],
            gap_s: piece.time_s[k] - piece.time_s[k - 1],
            block_s,
        });
    }
    let legs = find_legs(piece.time_s, piece.temperature_c);
    let rates = temperature_rates(piece.time_s, piece.temperature_c, RATE_WINDOW_S);
    let lagged: Vec<Vec<f64>> = LAG_GRID_S
        .iter()
        .map(|&tau| lagged_temperatures(piece.time_s, piece.temperature_c, tau))
        .collect();
    let mean = |xs: &[f64]| xs.iter().sum::<f64>() / xs.len() as f64;
    let blocks: Vec<SweepBlock> = block_ranges(piece.time_s, block_s)
        .into_iter()
        .map(|(a, b)| {
            let middle = (a + b - 1) / 2;
            let leg = legs.iter().position(|l| middle < l.end).unwrap_or(0);
            SweepBlock {
                power_on,
                leg: first_leg + leg as u32,
                t_s: (piece.time_s[a] + piece.time_s[b - 1]) / 2.0,
                temperature_c: mean(&piece.temperature_c[a..b]),
                sample_range_c: {
                    let (lo, hi) = super::solve::range(piece.temperature_c[a..b].iter().copied());
                    [lo, hi]
                },
                rate_c_per_s: mean(&rates[a..b]),
                lagged_temperature_c: lagged.iter().map(|l| mean(&l[a..b])).collect(),
                samples: b - a,
                values: piece
                    .channels
                    .iter()
                    .map(|&(c, column, signal)| (c, mean(&column[a..b]) - signal))
                    .collect(),
            }
        })
        .collect();
    if blocks.len() < MIN_SWEEP_BLOCKS {
        return Err(SweepError::TooFewBlocks {
            blocks: blocks.len(),
            block_s,
        });
    }
    Ok((blocks, legs))
}

/// Refuses non-finite temperatures and a range under [`MIN_SWEEP_RANGE_C`].
fn check_temperatures(temperature_c: &[f64]) -> Result<(), SweepError> {
    if let Some(index) = temperature_c.iter().position(|t| !t.is_finite()) {
        return Err(SweepError::NonFiniteTemperature { index });
    }
    let (low_c, high_c) = super::solve::range(temperature_c.iter().copied());
    let span_c = high_c - low_c;
    if span_c.is_nan() || span_c < MIN_SWEEP_RANGE_C {
        return Err(SweepError::TooNarrow {
            low_c,
            high_c,
            span_c: span_c.max(0.0),
        });
    }
    Ok(())
}

/// Sample ranges [a, b) of the whole blocks of `block_s` from the first sample.
pub fn block_ranges(time_s: &[f64], block_s: f64) -> Vec<(usize, usize)> {
    let Some(&start) = time_s.first() else {
        return Vec::new();
    };
    let end = *time_s.last().expect("non-empty");
    let mut ranges = Vec::new();
    let mut a = 0;
    let mut block = 1.0;
    for (k, &t) in time_s.iter().enumerate() {
        if t - start >= block * block_s {
            if k > a {
                ranges.push((a, k));
            }
            a = k;
            block = ((t - start) / block_s).floor() + 1.0;
        }
    }
    // The last block is whole when the record reaches its end.
    if end - start >= block * block_s - 1e-9 * block_s && time_s.len() > a {
        ranges.push((a, time_s.len()));
    }
    ranges
}

/// A block's record for the fits: its lagged temperature at τ.
fn records_at(blocks: &[&SweepBlock], channel: Channel, tau_s: f64) -> Vec<PowerOnRecord> {
    blocks
        .iter()
        .filter_map(|b| {
            b.values.get(&channel).map(|&value| PowerOnRecord {
                power_on: b.power_on,
                temperature_c: b.effective_temperature_c(tau_s),
                value,
            })
        })
        .collect()
}

/// Fixed-order settings of a candidate.
fn fixed(order: usize) -> FitSettings {
    FitSettings {
        reference_temperature_c: None,
        order: OrderChoice::Fixed(order),
    }
}

/// A fit of one candidate with τ (0 without lag).
struct Fitted {
    calibration: ChannelCalibration,
    tau_s: f64,
    rss: f64,
}

/// The residual sum of squares of a calibration's curve.
fn rss_of(c: &ChannelCalibration) -> f64 {
    c.bias.residual_sd.powi(2) * c.bias.residual_degrees_of_freedom as f64
}

fn fit_with_tau(
    blocks: &[&SweepBlock],
    channel: Channel,
    order: usize,
    tau_s: f64,
) -> Option<Fitted> {
    let records = records_at(blocks, channel, tau_s);
    let calibration = calibrate_channel(channel, &records, fixed(order)).ok()?;
    let rss = rss_of(&calibration);
    rss.is_finite().then_some(Fitted {
        calibration,
        tau_s,
        rss,
    })
}

/// Fewest blocks of each direction (warming and cooling) for a lag to be fitted.
pub const MIN_BLOCKS_PER_DIRECTION: usize = 2;

/// True when `blocks` hold both warming and cooling blocks (by the sign of their rate): with
/// the temperature moving one way at one rate, a lag shifts every temperature alike and a
/// polynomial absorbs the shift, so τ is not identified. A dwell's blocks, whose rates are
/// noise about zero, count on either side; with the first-order lag they carry the
/// structure's relaxation after a ramp, which does tell τ.
fn lag_identifiable(blocks: &[&SweepBlock]) -> bool {
    let warming = blocks.iter().filter(|b| b.rate_c_per_s > 0.0).count();
    let cooling = blocks.iter().filter(|b| b.rate_c_per_s < 0.0).count();
    warming >= MIN_BLOCKS_PER_DIRECTION && cooling >= MIN_BLOCKS_PER_DIRECTION
}

/// The candidate fitted to `blocks` (τ profiled for a lag candidate; τ = 0 where the blocks
/// cannot identify it, [`lag_identifiable`]).
fn fit_candidate(blocks: &[&SweepBlock], channel: Channel, c: Candidate) -> Option<Fitted> {
    if !c.lag || !lag_identifiable(blocks) {
        return fit_with_tau(blocks, channel, c.order, 0.0);
    }
    let rss =
        |tau: f64| fit_with_tau(blocks, channel, c.order, tau).map_or(f64::INFINITY, |f| f.rss);
    let grid: Vec<(f64, f64)> = LAG_GRID_S.iter().map(|&tau| (tau, rss(tau))).collect();
    let best = grid
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.1.total_cmp(&b.1.1))?
        .0;
    let lo = grid[best.saturating_sub(1)].0;
    let hi = grid[(best + 1).min(grid.len() - 1)].0;
    let tau = golden_section_minimum(rss, lo, hi, 40);
    let at = fit_with_tau(blocks, channel, c.order, tau)?;
    Some(if at.rss <= grid[best].1 {
        at
    } else {
        fit_with_tau(blocks, channel, c.order, grid[best].0)?
    })
}

/// Sets a final curve's fitted range to its blocks' samples (shifted by τ times the block's
/// rate), not the block means': a record's samples reach the sweep's ends, and the autopilots'
/// TMIN/TMAX are the extreme samples too.
fn widen_to_samples(calibration: &mut ChannelCalibration, blocks: &[&SweepBlock], tau_s: f64) {
    let (lo, hi) = blocks
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), b| {
            let shift = b.effective_temperature_c(tau_s) - b.temperature_c;
            (
                lo.min(b.sample_range_c[0] + shift),
                hi.max(b.sample_range_c[1] + shift),
            )
        });
    let range = &mut calibration.bias.temperature_range_c;
    *range = [range[0].min(lo), range[1].max(hi)];
}

/// A held-out block's prediction by a fold's fit, without the power-on's offset (shapes need
/// none). Not clamped: the block lies within the fold's temperature range, and only the lag's
/// shift τ·dT/dt can carry it a little past the shifted range of the fit.
fn predict(fit: &Fitted, block: &SweepBlock) -> f64 {
    fit.calibration
        .bias
        .value_at(block.effective_temperature_c(fit.tau_s))
}

/// The held-out residuals of a candidate, fold by fold.
struct HeldOut {
    /// Per fold that scored: the mean square of its in-range residuals about their mean.
    fold_mean_squares: Vec<f64>,
    /// Σ (r − r̄_fold)² and the count of residuals, over the folds.
    shape_ss: f64,
    /// Σ (r − centre)² over the folds, the centre as the fold's score takes it.
    scored_ss: f64,
    residuals: usize,
    /// Σ d_k·d_{k+1} of neighbouring residuals' deviations d (about the centre the score
    /// takes) within each fold: with `scored_ss`, their lag-1 autocorrelation.
    scored_cross: f64,
    /// r̄_fold − offset of its power-on in the fold's fit, where that power-on kept other
    /// folds.
    levels: Vec<f64>,
}

/// Stretches a single leg is cut into, as folds.
pub const SEGMENTS_OF_ONE_LEG: usize = 5;

/// The fold of each of `n` blocks in time order: its fifth of the record.
fn segments(n: usize) -> Vec<u32> {
    (0..n)
        .map(|k| (k * SEGMENTS_OF_ONE_LEG / n.max(1)) as u32)
        .collect()
}

/// Each fold left out in turn: the candidate fitted on the others predicts the held-out
/// blocks that lie within the others' temperature range (outside it every method clamps, and
/// the score would measure the range, not the model). A fold scores its residuals about their
/// own mean, except under [`ChoiceRule::LeaveOneSegmentOut`] when its power-on kept other
/// stretches: there the fold's level is that power-on's fitted offset, so the score sees
/// whether the curve carries the level across the left-out stretch.
fn held_out(
    blocks: &[&SweepBlock],
    fold: &[u32],
    channel: Channel,
    c: Candidate,
    rule: ChoiceRule,
) -> Option<HeldOut> {
    let labels: BTreeSet<u32> = fold.iter().copied().collect();
    let mut out = HeldOut {
        fold_mean_squares: Vec::new(),
        shape_ss: 0.0,
        scored_ss: 0.0,
        residuals: 0,
        scored_cross: 0.0,
        levels: Vec::new(),
    };
    for &label in &labels {
        let mut test = Vec::new();
        let mut train = Vec::new();
        for (b, &f) in blocks.iter().zip(fold) {
            if f == label {
                test.push(*b)
            } else {
                train.push(*b)
            }
        }
        let (low, high) = super::solve::range(train.iter().map(|b| b.temperature_c));
        test.retain(|b| (low..=high).contains(&b.temperature_c));
        if test.len() < 2 {
            continue;
        }
        let fit = fit_candidate(&train, channel, c)?;
        let r: Vec<f64> = test
            .iter()
            .map(|b| b.values[&channel] - predict(&fit, b))
            .collect();
        let mean = r.iter().sum::<f64>() / r.len() as f64;
        let ss: f64 = r.iter().map(|x| (x - mean).powi(2)).sum();
        // A stretch of the segment rule may span two power-ons (legs of several sweeps that
        // share no temperature): its level is then no single offset, and it is scored about
        // its own mean, as a leg is.
        let power_on = test[0].power_on;
        let one_power_on = test.iter().all(|b| b.power_on == power_on);
        let offset_known = one_power_on && train.iter().any(|b| b.power_on == power_on);
        let centre = match (rule, offset_known) {
            (ChoiceRule::LeaveOneSegmentOut, true) => fit.calibration.offset_of(power_on),
            _ => mean,
        };
        let scored: f64 = r.iter().map(|x| (x - centre).powi(2)).sum();
        out.scored_cross += r
            .windows(2)
            .map(|w| (w[0] - centre) * (w[1] - centre))
            .sum::<f64>();
        out.fold_mean_squares.push(scored / r.len() as f64);
        out.shape_ss += ss;
        out.scored_ss += scored;
        out.residuals += r.len();
        if offset_known {
            out.levels.push(mean - fit.calibration.offset_of(power_on));
        }
    }
    (!out.fold_mean_squares.is_empty()).then_some(out)
}

impl HeldOut {
    /// The mean over folds of their mean squares.
    fn score(&self) -> f64 {
        self.fold_mean_squares.iter().sum::<f64>() / self.fold_mean_squares.len() as f64
    }

    /// The spread of its predictions. Within one leg a stretch's level is part of the leg's
    /// shape, so under [`ChoiceRule::LeaveOneSegmentOut`] the shape spread is the scored one
    /// (about the power-on's offset) and there is no separate level spread.
    fn spread(&self, rule: ChoiceRule, legs: usize) -> PredictionSpread {
        let effective_dof = Some(self.effective_dof());
        if rule == ChoiceRule::LeaveOneSegmentOut {
            return PredictionSpread {
                shape_sd: (self.scored_ss / self.residuals.max(1) as f64).sqrt(),
                level_sd: None,
                rule,
                legs,
                effective_dof,
            };
        }
        let dof = self
            .residuals
            .saturating_sub(self.fold_mean_squares.len())
            .max(1);
        let level_sd = (!self.levels.is_empty()).then(|| {
            (self.levels.iter().map(|l| l * l).sum::<f64>() / self.levels.len() as f64).sqrt()
        });
        PredictionSpread {
            shape_sd: (self.shape_ss / dof as f64).sqrt(),
            level_sd,
            rule,
            legs,
            effective_dof,
        }
    }

    /// The degrees of freedom of the spread's estimate: the held-out residuals less one per
    /// fold, shrunk by their lag-1 autocorrelation ρ (within folds, clamped to 0..0.99) to
    /// ν(1 − ρ)/(1 + ρ), as τ's interval does (module docs, "Band"); at least 1.
    fn effective_dof(&self) -> f64 {
        let rho = match self.scored_ss > 0.0 {
            true => (self.scored_cross / self.scored_ss).clamp(0.0, 0.99),
            false => 0.0,
        };
        let dof = self.residuals.saturating_sub(self.fold_mean_squares.len()) as f64;
        shrunk_by_autocorrelation(dof, rho).max(1.0)
    }
}

/// Every candidate the rule allows, with its held-out residuals (`None` where no fold
/// scored).
fn scored_candidates(
    all: &[&SweepBlock],
    channel: Channel,
    rule: ChoiceRule,
) -> Vec<(Candidate, Option<HeldOut>)> {
    let fold = match rule {
        ChoiceRule::LeaveOneLegOut => all.iter().map(|b| b.leg).collect(),
        ChoiceRule::LeaveOneSegmentOut => segments(all.len()),
    };
    Candidate::all()
        .into_iter()
        .filter(|c| rule == ChoiceRule::LeaveOneLegOut || !c.lag)
        .map(|c| (c, held_out(all, &fold, channel, c, rule)))
        .collect()
}

/// Fitted parameters of a candidate beyond the offsets: its order, plus one for the lag.
fn complexity(c: Candidate) -> (usize, bool) {
    (c.order + usize::from(c.lag), c.lag)
}

/// The one-standard-error rule (Breiman et al. 1984, "Classification and Regression Trees"),
/// paired across folds: among the candidates `eligible` admits, the simplest whose fold scores
/// exceed the best candidate's by no more than the standard error of that mean excess (the
/// folds' differences, so that a fold every candidate predicts equally badly does not hide a
/// clear difference elsewhere).
fn one_standard_error_choice(
    scored: &[(Candidate, Option<HeldOut>)],
    eligible: impl Fn(Candidate) -> bool,
) -> Option<usize> {
    let valid: Vec<(usize, Candidate, &HeldOut)> = scored
        .iter()
        .enumerate()
        .filter_map(|(k, (c, h))| Some((k, *c, h.as_ref()?)))
        .filter(|(_, c, _)| eligible(*c))
        .collect();
    let &(_, _, best) = valid
        .iter()
        .min_by(|a, b| a.2.score().total_cmp(&b.2.score()))?;
    valid
        .iter()
        .filter(|(_, _, h)| within_one_standard_error(h, best))
        .min_by_key(|(_, c, _)| complexity(*c))
        .map(|(k, _, _)| *k)
}

/// True when `h`'s mean excess over `best` across the folds (the log ratio of their fold
/// scores) is at most its standard error, or at most ln(1 + [`MIN_RELATIVE_GAIN`]).
fn within_one_standard_error(h: &HeldOut, best: &HeldOut) -> bool {
    let d: Vec<f64> = (h.fold_mean_squares.iter())
        .zip(&best.fold_mean_squares)
        .map(|(a, b)| log_ratio(*a, *b))
        .collect();
    let f = d.len() as f64;
    let mean = d.iter().sum::<f64>() / f;
    let floor = MIN_RELATIVE_GAIN.ln_1p();
    if d.len() < 2 {
        return mean <= floor;
    }
    let var = d.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (f - 1.0);
    mean <= (var / f).sqrt().max(floor)
}

/// ln(a/b) of two fold mean squares, each lifted by a trillionth of the larger so that an
/// exact fit (0) compares as a large finite ratio.
fn log_ratio(a: f64, b: f64) -> f64 {
    let lift = 1e-12 * a.max(b).max(f64::MIN_POSITIVE);
    ((a + lift) / (b + lift)).ln()
}

/// A more complex candidate must lower the held-out mean square by more than this fraction
/// of the best score (about 5 % in RMS) as well as by more than the standard error.
pub const MIN_RELATIVE_GAIN: f64 = 0.1;

/// The sweep calibration of one channel: the chosen model (and the best in T alone), module
/// docs.
///
/// # Errors
/// The fit of the chosen candidate to all blocks, or every candidate failing.
pub fn calibrate_channel_from_sweeps(
    blocks: &[SweepBlock],
    channel: Channel,
) -> Result<ChannelCalibration, ThermalError> {
    let mut all: Vec<&SweepBlock> = blocks
        .iter()
        .filter(|b| b.values.contains_key(&channel))
        .collect();
    all.sort_by(|a, b| {
        (a.power_on, a.t_s)
            .partial_cmp(&(b.power_on, b.t_s))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let legs = all.iter().map(|b| b.leg).collect::<BTreeSet<u32>>().len();
    let mut rule = if legs >= 2 {
        ChoiceRule::LeaveOneLegOut
    } else {
        ChoiceRule::LeaveOneSegmentOut
    };
    let mut scored = scored_candidates(&all, channel, rule);
    if scored.iter().all(|(_, h)| h.is_none()) && rule == ChoiceRule::LeaveOneLegOut {
        // Legs that share no temperature cannot predict each other: fall back to stretches.
        rule = ChoiceRule::LeaveOneSegmentOut;
        scored = scored_candidates(&all, channel, rule);
    }
    let no_valid = || ThermalError::NoValidOrder {
        observations: all.len(),
        distinct_temperatures: super::solve::distinct(all.iter().map(|b| b.temperature_c)),
    };
    let t_only = one_standard_error_choice(&scored, |c| !c.lag).ok_or_else(no_valid)?;
    let t_only_c = scored[t_only].0;
    let mut calibration = fit_candidate(&all, channel, t_only_c)
        .ok_or_else(no_valid)?
        .calibration;
    widen_to_samples(&mut calibration, &all, 0.0);
    // A lag whose fit on every block runs to the search limit is not identified: the choice is
    // made again without that candidate.
    let mut excluded: Vec<Candidate> = match lag_identifiable(&all) {
        true => Vec::new(),
        false => Candidate::all().into_iter().filter(|c| c.lag).collect(),
    };
    let (chosen, lagged) = loop {
        let k =
            one_standard_error_choice(&scored, |c| !excluded.contains(&c)).ok_or_else(no_valid)?;
        let c = scored[k].0;
        if !c.lag {
            break (k, None);
        }
        let fit = fit_candidate(&all, channel, c).ok_or_else(no_valid)?;
        if fit.tau_s.abs() >= LAG_SEARCH_S * (1.0 - 1e-6) {
            excluded.push(c);
            continue;
        }
        let interval = tau_interval(&all, channel, c.order, &fit);
        let mut fit = fit;
        widen_to_samples(&mut fit.calibration, &all, fit.tau_s);
        let lag = ThermalLag {
            tau_s: fit.tau_s,
            tau_interval_s: interval,
            rate_window_s: RATE_WINDOW_S,
        };
        break (
            k,
            Some(LaggedBias {
                lag,
                fit: Box::new(fit.calibration),
            }),
        );
    };
    let spread = scored[chosen]
        .1
        .as_ref()
        .expect("a chosen candidate is scored")
        .spread(rule, legs);
    calibration.lagged = lagged;
    calibration.selection = Some(HeldOutSelection {
        rule,
        chosen: scored[chosen].0,
        best_in_temperature_alone: t_only_c,
        scores: scored
            .iter()
            .map(|(c, h)| CandidateScore {
                candidate: *c,
                held_out_rms: h.as_ref().map(|h| h.score().sqrt()),
            })
            .collect(),
        spread,
    });
    Ok(calibration)
}

/// `count` values shrunk to the independent values they are worth, given their lag-1
/// autocorrelation `rho`: count·(1 − ρ)/(1 + ρ) (the effective sample size of an AR(1) series).
pub(super) fn shrunk_by_autocorrelation(count: f64, rho: f64) -> f64 {
    count * (1.0 - rho) / (1.0 + rho)
}

/// Lag-1 autocorrelation of a series (0 for fewer than 3 values or none negative clamps).
pub(super) fn lag_one_autocorrelation(x: &[f64]) -> f64 {
    if x.len() < 3 {
        return 0.0;
    }
    let mean = x.iter().sum::<f64>() / x.len() as f64;
    let var: f64 = x.iter().map(|v| (v - mean).powi(2)).sum();
    let cov: f64 = x.windows(2).map(|w| (w[0] - mean) * (w[1] - mean)).sum();
    if var > 0.0 {
        (cov / var).clamp(0.0, 0.99)
    } else {
        0.0
    }
}

/// τ's 95 % profile interval (module docs).
fn tau_interval(
    blocks: &[&SweepBlock],
    channel: Channel,
    order: usize,
    fit: &Fitted,
) -> [Option<f64>; 2] {
    let residuals: Vec<f64> = {
        let mut sorted: Vec<&&SweepBlock> = blocks.iter().collect();
        sorted.sort_by(|a, b| {
            (a.power_on, a.t_s)
                .partial_cmp(&(b.power_on, b.t_s))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        sorted
            .iter()
            .map(|b| b.values[&channel] - predict(fit, b) - fit.calibration.offset_of(b.power_on))
            .collect()
    };
    let rho = lag_one_autocorrelation(&residuals);
    let dof =
        shrunk_by_autocorrelation(fit.calibration.bias.residual_degrees_of_freedom as f64, rho);
    let dof = dof.max(1.0);
    let f = FisherSnedecor::new(1.0, dof)
        .map(|d| d.inverse_cdf(0.95))
        .unwrap_or(f64::INFINITY);
    let limit = fit.rss * (1.0 + f / dof);
    let rss = |tau: f64| fit_with_tau(blocks, channel, order, tau).map_or(f64::INFINITY, |f| f.rss);
    let end = |direction: f64| {
        // Step out until the profile passes the limit, then bisect.
        let mut inside = fit.tau_s;
        let mut step = 1.0_f64.max(fit.tau_s.abs() * 0.05);
        loop {
            let out = (inside + direction * step).clamp(-LAG_SEARCH_S, LAG_SEARCH_S);
            if rss(out) > limit {
                let (mut a, mut b) = (inside, out);
                for _ in 0..40 {
                    let m = (a + b) / 2.0;
                    if rss(m) > limit { b = m } else { a = m }
                }
                return Some((a + b) / 2.0);
            }
            if out.abs() >= LAG_SEARCH_S {
                return None;
            }
            inside = out;
            step *= 2.0;
        }
    };
    [end(-1.0), end(1.0)]
}

/// A prediction of a block mean.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Prediction {
    /// The bias with the power-on's offset, channel unit.
    pub value: f64,
    /// 95 % half-width with the offset's uncertainty and the level spread between legs.
    pub band_half_width: f64,
    /// 95 % half-width of the shape alone (the record's own mean residual taken off).
    pub band_half_width_offset_removed: f64,
    /// True when the (shifted) temperature lay outside the fitted range.
    pub clamped: bool,
}

/// Whose offset a prediction carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PowerOnChoice {
    /// The fitted offset of this power-on.
    Known(u32),
    /// A power-on the calibration has not seen: the mean offset, with the spread between
    /// power-ons in the band.
    New,
}

impl ChannelCalibration {
    /// The model used for compensation: the lag model when chosen, else the curve in T.
    pub fn compensation_model(&self) -> (&ChannelCalibration, f64) {
        match &self.lagged {
            Some(l) => (&l.fit, l.lag.tau_s),
            None => (self, 0.0),
        }
    }

    /// The thermal lag of the compensation model, s (0 without one).
    pub fn lag_s(&self) -> f64 {
        self.compensation_model().1
    }

    /// The bias at an effective temperature (°C: the lagged temperature of
    /// [`super::legs::lagged_temperatures`] at [`ChannelCalibration::lag_s`]), clamped to the
    /// fitted range, without the power-on's offset, and whether it was clamped.
    pub fn bias_at_effective(&self, t: f64) -> (f64, bool) {
        let (model, _) = self.compensation_model();
        let curve = &model.bias;
        let [low, high] = curve.temperature_range_c;
        (
            curve.value_at(t.clamp(low, high)),
            !(low..=high).contains(&t),
        )
    }

    /// The prediction of a block mean at its mean effective temperature `t` (°C, see
    /// [`ChannelCalibration::bias_at_effective`]) for a power-on (module docs, "Band");
    /// `noise_var` is the variance of the observed mean's own noise (its samples' variance
    /// over their count, channel unit squared), which the band adds.
    pub fn predict(&self, t: f64, power_on: PowerOnChoice, noise_var: f64) -> Prediction {
        let (model, _) = self.compensation_model();
        let curve = &model.bias;
        let [low, high] = curve.temperature_range_c;
        let inside = t.clamp(low, high);
        let clamped = inside != t;
        let (offset, offset_var) = match power_on {
            PowerOnChoice::Known(label) => {
                let o = model.power_on_offsets.iter().find(|o| o.power_on == label);
                (
                    o.map_or(0.0, |o| o.offset),
                    o.map_or(0.0, |o| o.offset_sd.powi(2)),
                )
            }
            PowerOnChoice::New => (0.0, model.between_power_on_sd.map_or(0.0, |s| s * s)),
        };
        let se2 = curve.standard_error_at(inside).powi(2) + noise_var.max(0.0);
        let (shape, level) = match &self.selection {
            Some(s) => (s.spread.shape_sd, s.spread.level_sd.unwrap_or(0.0)),
            None => (curve.residual_sd, 0.0),
        };
        let widening = if clamped {
            derivative(curve, inside).abs() * (t - inside).abs()
        } else {
            0.0
        };
        let z = self
            .selection
            .as_ref()
            .map_or(BAND_Z, |s| s.spread.band_quantile());
        Prediction {
            value: curve.value_at(inside) + offset,
            band_half_width: z * (shape * shape + level * level + se2 + offset_var).sqrt()
                + widening,
            band_half_width_offset_removed: z * (shape * shape + se2).sqrt() + widening,
            clamped,
        }
    }
}

/// b′(T) of a curve.
fn derivative(curve: &super::ThermalCurve, temperature_c: f64) -> f64 {
    let d = temperature_c - curve.reference_temperature_c;
    curve
        .coefficients
        .iter()
        .enumerate()
        .skip(1)
        .map(|(k, b)| k as f64 * b * d.powi(k as i32 - 1))
        .sum()
}

/// The calibration of every channel of `blocks`.
///
/// # Errors
/// The first channel's [`ThermalError`].
pub fn calibrate_from_sweeps(
    blocks: &[SweepBlock],
) -> Result<BTreeMap<Channel, ChannelCalibration>, ThermalError> {
    let channels: BTreeSet<Channel> = blocks
        .iter()
        .flat_map(|b| b.values.keys().copied())
        .collect();
    channels
        .into_iter()
        .map(|c| calibrate_channel_from_sweeps(blocks, c).map(|cal| (c, cal)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const ORDER_2_LAG: Candidate = Candidate {
        order: 2,
        lag: true,
    };

    /// Blocks of a noiseless cool-heat-cool program at ±`rate` °C/s (30 s blocks) whose gx
    /// reads b(T + τ Ṫ) = 2e-4 (T' − 20) + 4e-6 (T' − 20)², T' = T + τ Ṫ.
    fn program_blocks(tau_s: f64, rate: f64) -> Vec<SweepBlock> {
        let knots = [(25.0, 5.0), (5.0, 45.0), (45.0, 25.0)];
        let mut blocks = Vec::new();
        let mut t0 = 0.0;
        for (leg, (from, to)) in knots.into_iter().enumerate() {
            let duration = (to - from) / rate;
            let duration: f64 = duration.abs();
            let slope = if to > from { rate } else { -rate };
            let n = (duration / 30.0) as usize;
            for k in 0..n {
                let t = from + slope * (k as f64 + 0.5) * 30.0;
                let shifted = t + tau_s * slope - 20.0;
                let value = 2e-4 * shifted + 4e-6 * shifted * shifted;
                // A tiny alternating error keeps the residual variance positive.
                let wiggle = if k % 2 == 0 { 1e-9 } else { -1e-9 };
                blocks.push(SweepBlock {
                    power_on: 1,
                    leg: leg as u32 + 1,
                    t_s: t0 + (k as f64 + 0.5) * 30.0,
                    temperature_c: t,
                    sample_range_c: [t - 0.5, t + 0.5],
                    rate_c_per_s: slope,
                    lagged_temperature_c: Vec::new(),
                    samples: 60,
                    values: BTreeMap::from([(Channel::Gx, value + wiggle)]),
                });
            }
            t0 += duration;
        }
        blocks
    }

    fn held_out_of(fold_mean_squares: &[f64]) -> HeldOut {
        HeldOut {
            fold_mean_squares: fold_mean_squares.to_vec(),
            shape_ss: 0.0,
            scored_ss: 0.0,
            residuals: 0,
            scored_cross: 0.0,
            levels: Vec::new(),
        }
    }

    // The folds of a simulated lagging unit (thermal_lag_units, ±2 °C/min, seed 5, ax): the
    // lag model predicts two folds to the noise (mean squares 6.4e-8 and 9.0e-8) where order 0
    // is 250 and 30,000 times worse, while the third fold (two cooling legs, where no lag can
    // be fitted) is predicted badly by both, order 0 a little less badly. Closed form: the
    // folds' excesses in mean square are 1.62e-5, −3.1e-4 and 2.66e-3, mean 7.9e-4 under its
    // standard error 9.4e-4, so order 0 would pass as "as good"; their log ratios are 5.54,
    // −0.44 and 10.30, mean 5.13 over its standard error 3.11, so it does not.
    #[test]
    fn a_fold_every_candidate_predicts_badly_does_not_make_order_0_as_good() {
        let lag = held_out_of(&[6.4e-8, 8.7e-4, 9.0e-8]);
        let order_0 = held_out_of(&[1.63e-5, 5.6e-4, 2.665e-3]);
        assert!(!within_one_standard_error(&order_0, &lag));
        assert!(within_one_standard_error(&lag, &lag));
        // ln(a/b) for ordinary values; an exact fit compares as a large finite ratio.
        assert!((log_ratio(2.0, 1.0) - std::f64::consts::LN_2).abs() < 1e-11);
        let exact = log_ratio(1e-6, 0.0);
        assert!(exact.is_finite() && (exact - 12.0 * std::f64::consts::LN_10).abs() < 1e-6);
    }

    #[test]
    fn the_lag_of_an_exact_lagging_curve_is_recovered() {
        // Closed form: the data are exactly the order-2 lag model with τ = −120 s, so its
        // profile's minimum is at −120 s and its held-out legs are predicted exactly.
        let blocks = program_blocks(-120.0, 2.0 / 60.0);
        let all: Vec<&SweepBlock> = blocks.iter().collect();
        let fit = fit_candidate(&all, Channel::Gx, ORDER_2_LAG).unwrap();
        assert!((fit.tau_s + 120.0).abs() < 0.5, "{}", fit.tau_s);
        let cal = calibrate_channel_from_sweeps(&blocks, Channel::Gx).unwrap();
        let selection = cal.selection.as_ref().unwrap();
        assert_eq!(selection.chosen, ORDER_2_LAG, "{selection:?}");
        assert!((cal.lagged.as_ref().unwrap().lag.tau_s + 120.0).abs() < 0.5);
    }

    // One leg: each left-out stretch is scored about its power-on's offset, which the other
    // stretches fix, so a curve that misplaces the stretch's level is penalised. Oracle: the
    // closed form. The blocks read 4e-5 rad/s/°C · (T − 10) plus a bounded deterministic
    // ripple of 1e-4 rad/s (sin 2.3k). Within a stretch (4 °C) the slope moves the reading by
    // 4.6e-5 rad/s rms, under the ripple, but order 0 misplaces stretches 2 and 4 (means near
    // 6 and 14 °C, the others' near 11 and 9 °C) by about 2e-4 rad/s, twice the ripple; a
    // straight line does not.
    #[test]
    fn one_leg_stretches_are_scored_about_their_power_on_offset() {
        let blocks: Vec<SweepBlock> = (0..50)
            .map(|k| {
                let t = 20.0 * (k as f64 + 0.5) / 50.0;
                let value = 4e-5 * (t - 10.0) + 1e-4 * (2.3 * k as f64).sin();
                SweepBlock {
                    power_on: 1,
                    leg: 1,
                    t_s: 30.0 * (k as f64 + 0.5),
                    temperature_c: t,
                    sample_range_c: [t - 0.2, t + 0.2],
                    rate_c_per_s: 20.0 / 1500.0,
                    lagged_temperature_c: Vec::new(),
                    samples: 60,
                    values: BTreeMap::from([(Channel::Gx, value)]),
                }
            })
            .collect();
        let cal = calibrate_channel_from_sweeps(&blocks, Channel::Gx).unwrap();
        let selection = cal.selection.as_ref().unwrap();
        assert_eq!(selection.rule, ChoiceRule::LeaveOneSegmentOut);
        let rms = |order: usize| {
            (selection.scores.iter())
                .find(|s| s.candidate.order == order && !s.candidate.lag)
                .and_then(|s| s.held_out_rms)
                .unwrap()
        };
        assert!(rms(0) > 1.5 * rms(1), "{} {}", rms(0), rms(1));
        assert!(selection.chosen.order >= 1, "{selection:?}");
        // Within one leg the level is the shape: no separate level spread, and the shape
        // spread holds the level errors (at least the ripple's rms, 7e-5 rad/s).
        assert_eq!(selection.spread.level_sd, None);
        assert!(selection.spread.shape_sd > 5e-5, "{:?}", selection.spread);
    }

    #[test]
    fn without_a_lag_the_curve_in_temperature_alone_is_chosen() {
        let blocks = program_blocks(0.0, 2.0 / 60.0);
        let cal = calibrate_channel_from_sweeps(&blocks, Channel::Gx).unwrap();
        let selection = cal.selection.as_ref().unwrap();
        assert!(!selection.chosen.lag, "{selection:?}");
        assert_eq!(selection.chosen.order, 2);
    }

    #[test]
    fn a_lag_is_not_fitted_to_legs_that_all_run_one_way() {
        // Two cooling legs: a lag only shifts every temperature alike.
        let blocks: Vec<SweepBlock> = program_blocks(-120.0, 2.0 / 60.0)
            .into_iter()
            .filter(|b| b.rate_c_per_s < 0.0)
            .collect();
        let all: Vec<&SweepBlock> = blocks.iter().collect();
        assert!(!lag_identifiable(&all));
        let fit = fit_candidate(&all, Channel::Gx, ORDER_2_LAG).unwrap();
        assert_eq!(fit.tau_s, 0.0);
    }

    #[test]
    fn the_band_widens_by_students_t_on_autocorrelated_residuals() {
        // 32 held-out residuals in 2 folds, Σd² = 10: with Σ d_k·d_{k+1} = 5 (ρ = 0.5) the
        // 30 degrees of freedom shrink to 30·0.5/1.5 = 10; a negative sum counts as ρ = 0.
        let held_out = |cross: f64| HeldOut {
            fold_mean_squares: vec![0.3, 0.35],
            shape_ss: 10.0,
            scored_ss: 10.0,
            residuals: 32,
            scored_cross: cross,
            levels: Vec::new(),
        };
        assert!((held_out(5.0).effective_dof() - 10.0).abs() < 1e-12);
        assert_eq!(held_out(-3.0).effective_dof(), 30.0);
        let spread = |dof: Option<f64>| PredictionSpread {
            shape_sd: 1.0,
            level_sd: None,
            rule: ChoiceRule::LeaveOneLegOut,
            legs: 2,
            effective_dof: dof,
        };
        // Closed forms of t at 0.975: tan(0.475π) with 1 degree of freedom, 0.95/√(2·0.975·0.025)
        // with 2; the normal quantile without a count (banks written before it was kept).
        let t1 = (0.475 * std::f64::consts::PI).tan();
        let t2 = 0.95 / (2.0 * 0.975 * 0.025_f64).sqrt();
        assert!((spread(Some(1.0)).band_quantile() - t1).abs() < 1e-6 * t1);
        assert!((spread(Some(2.0)).band_quantile() - t2).abs() < 1e-6 * t2);
        assert!((spread(None).band_quantile() - BAND_Z).abs() < 1e-15);
    }

    #[test]
    fn blocks_are_whole_blocks_from_the_first_sample() {
        // 10 samples at 1 s: blocks of 3 s are samples 0-2, 3-5, 6-8; sample 9 starts a
        // block that does not end.
        let time: Vec<f64> = (0..10).map(f64::from).collect();
        assert_eq!(block_ranges(&time, 3.0), vec![(0, 3), (3, 6), (6, 9)]);
        let time: Vec<f64> = (0..9).map(f64::from).collect();
        assert_eq!(block_ranges(&time, 3.0), vec![(0, 3), (3, 6)]);
    }
}
