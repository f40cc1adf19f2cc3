//! Thermal calibration from temperature sweeps alone, with a thermal-lag term, chosen by what
//! it predicts on legs it was not fitted to.
//!
//! # Blocks
//! Each sweep piece is cut into consecutive blocks of `block_s` seconds from its first sample
//! (a last, shorter block is dropped); a block's observation is the mean of every channel, of
//! the temperature and of the temperature's rate ([`super::legs`], "Rate") over its samples,
//! and its leg is the leg ([`super::find_legs`], found within the piece) that holds its middle
//! sample. The default block ([`default_block_s`]) is the shorter of 300 s and the time the
//! temperature takes to move 1 °C at the piece's median rate, and at least 10 samples.
//!
//! # Candidates
//! Per channel: order 0 (no thermal term: the channel is left uncompensated but for its
//! constant), b(T) of order 1..3, and b(T + τ·dT/dt) of order 1..3, the bias read at a
//! temperature shifted by the rate times a thermal lag τ (s): to first order
//! b(T) + τ·b′(T)·dT/dt, the loop that a structure lagging its temperature sensor draws. τ < 0
//! when the structure lags the sensor. For a given τ the fit is linear (the polynomial fit of
//! [`super::calibrate`] on the shifted temperatures, with one offset per power-on); τ is found
//! by profiling the residual sum of squares over ±[`LAG_SEARCH_S`] (a grid of
//! [`LAG_GRID_POINTS`] values, then golden-section search about the best).
//!
//! # Choice
//! With two or more legs: leave one leg out. Each candidate is fitted (τ profiled again) on
//! every leg but one and predicts the blocks of the leg left out; its score is the pooled
//! mean square of those residuals about each held-out leg's own mean (the shape of the leg,
//! since a leg's level also holds the power-on's offset). The candidate of the smallest score
//! is chosen, the simpler one on a tie (order 0 first, then increasing order, T alone before the
//! lag). So a term that does not predict unseen legs is not used, and a channel where nothing
//! beats order 0 is left uncompensated. The best candidate in T alone is kept beside it for
//! the autopilots' parameter files, which hold a cubic in T only. With one leg the lag cannot
//! be told from the curve: T alone, the order by leave-one-block-out PRESS.
//!
//! # Band
//! A prediction's 95 % band is ±1.96·sqrt(s_shape² + s_level² + se(T)² + s_offset²): s_shape
//! the held-out residuals' sd about their legs' means (with one leg, PRESS's deletion residuals,
//! which do not know other legs), s_level the sd of the held-out legs' mean residuals from their
//! power-on's fitted offset (where that power-on kept other legs), se(T) the fitted curve's
//! standard error, s_offset the uncertainty of the power-on's offset (its own sd, or the spread
//! between power-ons for a new one). The band with the offset removed drops s_level and
//! s_offset. Outside the fitted range the prediction is the range's end value and the band is
//! widened by |b′(end)|·distance, what a straight continuation would have added.
//!
//! # τ's interval
//! The profile interval {τ : RSS(τ) ≤ RSS(τ̂)·(1 + F_{1,ν;0.95}/ν)}, ν the residual degrees
//! of freedom shrunk by the residuals' lag-1 autocorrelation ρ to ν(1 − ρ)/(1 + ρ) (neighbouring
//! blocks of a sweep are not independent); an end that reaches the search limit is open.

use super::calibration::calibrate_channel;
use super::legs::{Leg, RATE_WINDOW_S, find_legs, temperature_rates};
use super::{ChannelCalibration, FitSettings, OrderChoice, PowerOnRecord, ThermalError};
use crate::imu::Channel;
use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, FisherSnedecor};
use std::collections::{BTreeMap, BTreeSet};

/// The thermal lag is searched within ±this, s.
pub const LAG_SEARCH_S: f64 = 3600.0;

/// Points of the lag's profile grid over ±[`LAG_SEARCH_S`].
pub const LAG_GRID_POINTS: usize = 73;

/// Longest default block of a sweep, s.
pub const MAX_DEFAULT_BLOCK_S: f64 = 300.0;

/// Fewest samples in a default block.
pub const MIN_BLOCK_SAMPLES: usize = 10;

/// Fewest blocks a sweep must give.
pub const MIN_SWEEP_BLOCKS: usize = 3;

/// Smallest temperature range a sweep must cover, °C.
pub const MIN_SWEEP_RANGE_C: f64 = 2.0;

/// Two-sided 95 % quantile of the normal distribution: the band's multiple.
const BAND_Z: f64 = 1.959_963_984_540_054;

/// One block of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepBlock {
    /// The power-on (sweep) it belongs to.
    pub power_on: u32,
    /// The leg it belongs to, numbered across the calibration from 1.
    pub leg: u32,
    /// Time of its middle, s (the record's time axis).
    pub t_s: f64,
    /// Mean temperature, °C.
    pub temperature_c: f64,
    /// Mean rate of the temperature, °C/s.
    pub rate_c_per_s: f64,
    /// Samples averaged.
    pub samples: usize,
    /// Mean of each channel (after the removed signal), rate unit.
    pub values: BTreeMap<Channel, f64>,
}

/// A leg of a sweep as the calibration keeps it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepLeg {
    /// Its number, as [`SweepBlock::leg`] names it.
    pub leg: u32,
    /// The power-on (sweep).
    pub power_on: u32,
    /// The file it was found in.
    pub source: String,
    /// Time of its first and last sample, s.
    pub t_s: [f64; 2],
    /// Smoothed temperature at its ends, °C.
    pub temperature_c: [f64; 2],
    /// Span of the smoothed temperature, °C.
    pub span_c: f64,
    /// Which way it runs.
    pub direction: super::legs::LegDirection,
}

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
    /// The block length is not positive and finite.
    #[error("the block length {0} s is not a positive number")]
    BadBlock(f64),
}

/// The default block of a piece (module docs, "Blocks"), s.
pub fn default_block_s(time_s: &[f64], temperature_c: &[f64]) -> f64 {
    let rates = temperature_rates(time_s, temperature_c, RATE_WINDOW_S);
    let mut speeds: Vec<f64> = rates.iter().map(|r| r.abs()).collect();
    speeds.sort_by(f64::total_cmp);
    let median = speeds.get(speeds.len() / 2).copied().unwrap_or(0.0);
    let one_degree = if median > 0.0 {
        1.0 / median
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
    check_temperatures(piece.temperature_c)?;
    if let Some(k) = (1..piece.time_s.len()).find(|&k| piece.time_s[k] - piece.time_s[k - 1] > block_s)
    {
        return Err(SweepError::Gap {
            at_s: piece.time_s[k - 1],
            gap_s: piece.time_s[k] - piece.time_s[k - 1],
            block_s,
        });
    }
    let legs = find_legs(piece.time_s, piece.temperature_c);
    let rates = temperature_rates(piece.time_s, piece.temperature_c, RATE_WINDOW_S);
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
                rate_c_per_s: mean(&rates[a..b]),
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
    if !(span_c >= MIN_SWEEP_RANGE_C) {
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

/// A candidate model of one channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Candidate {
    /// Polynomial order, 0..=3.
    pub order: usize,
    /// True for b(T + τ·dT/dt).
    pub lag: bool,
}

impl Candidate {
    /// Every candidate, simplest first.
    pub fn all() -> Vec<Candidate> {
        let mut all = vec![Candidate {
            order: 0,
            lag: false,
        }];
        for order in 1..=super::MAX_ORDER {
            all.push(Candidate { order, lag: false });
        }
        for order in 1..=super::MAX_ORDER {
            all.push(Candidate { order, lag: true });
        }
        all
    }
}

/// How a candidate did on the legs it was not fitted to.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CandidateScore {
    /// The candidate.
    pub candidate: Candidate,
    /// RMS of the held-out residuals about their legs' means, channel unit; `None` when it
    /// could not be fitted on some fold.
    pub held_out_rms: Option<f64>,
}

/// How a channel's model was chosen.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ChoiceRule {
    /// Leave one leg out.
    LeaveOneLegOut,
    /// One leg: T alone, order by leave-one-block-out PRESS.
    LeaveOneBlockOut,
}

/// The lag term of a chosen model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ThermalLag {
    /// τ, s: the bias is b(T + τ·dT/dt) with the curve of [`LaggedBias::bias`].
    pub tau_s: f64,
    /// The 95 % profile interval of τ, s; `None` for an end at the search limit.
    pub tau_interval_s: [Option<f64>; 2],
    /// Window of the least-squares rate dT/dt, s.
    pub rate_window_s: f64,
}

/// The chosen model when it holds a lag term: the curve in the shifted temperature.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LaggedBias {
    /// The lag.
    pub lag: ThermalLag,
    /// The curve, its offsets and spread, with T + τ·dT/dt for T.
    pub fit: Box<ChannelCalibration>,
}

/// What a channel's predictions are uncertain by beyond the fitted curve (module docs,
/// "Band"), channel unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PredictionSpread {
    /// s_shape.
    pub shape_sd: f64,
    /// s_level; `None` when no held-out leg had its power-on's offset fitted without it.
    pub level_sd: Option<f64>,
    /// How they were measured.
    pub rule: ChoiceRule,
    /// Legs the choice saw.
    pub legs: usize,
}

/// The model selection of a channel calibrated from sweeps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HeldOutSelection {
    /// The rule.
    pub rule: ChoiceRule,
    /// The chosen candidate.
    pub chosen: Candidate,
    /// The best candidate in T alone (what the autopilots' cubic can hold).
    pub best_in_temperature_alone: Candidate,
    /// Every candidate's score (empty with one leg).
    pub scores: Vec<CandidateScore>,
    /// The spread of its predictions.
    pub spread: PredictionSpread,
}

/// A block's record for the fits: its temperature shifted by τ times its rate.
fn records_at(blocks: &[&SweepBlock], channel: Channel, tau_s: f64) -> Vec<PowerOnRecord> {
    blocks
        .iter()
        .filter_map(|b| {
            b.values.get(&channel).map(|&value| PowerOnRecord {
                power_on: b.power_on,
                temperature_c: b.temperature_c + tau_s * b.rate_c_per_s,
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

/// The candidate fitted to `blocks` (τ profiled for a lag candidate).
fn fit_candidate(blocks: &[&SweepBlock], channel: Channel, c: Candidate) -> Option<Fitted> {
    if !c.lag {
        return fit_with_tau(blocks, channel, c.order, 0.0);
    }
    let rss = |tau: f64| fit_with_tau(blocks, channel, c.order, tau).map_or(f64::INFINITY, |f| f.rss);
    let step = 2.0 * LAG_SEARCH_S / (LAG_GRID_POINTS - 1) as f64;
    let grid: Vec<(f64, f64)> = (0..LAG_GRID_POINTS)
        .map(|k| -LAG_SEARCH_S + k as f64 * step)
        .map(|tau| (tau, rss(tau)))
        .collect();
    let best = grid
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.1.total_cmp(&b.1.1))?
        .0;
    let lo = grid[best.saturating_sub(1)].0;
    let hi = grid[(best + 1).min(grid.len() - 1)].0;
    let tau = golden_minimum(&rss, lo, hi, 40);
    let at = fit_with_tau(blocks, channel, c.order, tau)?;
    Some(if at.rss <= grid[best].1 {
        at
    } else {
        fit_with_tau(blocks, channel, c.order, grid[best].0)?
    })
}

/// Golden-section search for a minimum of `f` on [lo, hi].
fn golden_minimum(f: &impl Fn(f64) -> f64, mut lo: f64, mut hi: f64, steps: usize) -> f64 {
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut fa, mut fb) = (f(a), f(b));
    for _ in 0..steps {
        if fa <= fb {
            hi = b;
            (b, fb) = (a, fa);
            a = hi - g * (hi - lo);
            fa = f(a);
        } else {
            lo = a;
            (a, fa) = (b, fb);
            b = lo + g * (hi - lo);
            fb = f(b);
        }
    }
    if fa <= fb { a } else { b }
}

/// A block's prediction by a fit, without the power-on's offset (shapes need none).
fn predict(fit: &Fitted, block: &SweepBlock) -> f64 {
    let curve = &fit.calibration.bias;
    let [low, high] = curve.temperature_range_c;
    let t = block.temperature_c + fit.tau_s * block.rate_c_per_s;
    curve.value_at(t.clamp(low, high))
}

/// The held-out residuals of a candidate: per leg, the residuals and the leg's level against
/// its power-on's offset when that power-on kept other legs.
struct HeldOut {
    /// Σ (r − r̄_leg)² and the count of residuals.
    shape_ss: f64,
    residuals: usize,
    legs: usize,
    /// r̄_leg − offset of the power-on in the fold's fit.
    levels: Vec<f64>,
}

fn held_out(blocks: &[SweepBlock], channel: Channel, c: Candidate) -> Option<HeldOut> {
    let legs: BTreeSet<u32> = blocks.iter().map(|b| b.leg).collect();
    let mut out = HeldOut {
        shape_ss: 0.0,
        residuals: 0,
        legs: legs.len(),
        levels: Vec::new(),
    };
    for &leg in &legs {
        let (test, train): (Vec<&SweepBlock>, Vec<&SweepBlock>) =
            blocks.iter().partition(|b| b.leg == leg);
        let test: Vec<&SweepBlock> = test.into_iter().filter(|b| b.values.contains_key(&channel)).collect();
        let fit = fit_candidate(&train, channel, c)?;
        let r: Vec<f64> = test.iter().map(|b| b.values[&channel] - predict(&fit, b)).collect();
        if r.is_empty() {
            continue;
        }
        let mean = r.iter().sum::<f64>() / r.len() as f64;
        out.shape_ss += r.iter().map(|x| (x - mean).powi(2)).sum::<f64>();
        out.residuals += r.len();
        let power_on = test[0].power_on;
        if train.iter().any(|b| b.power_on == power_on) {
            out.levels.push(mean - level_of(&fit, power_on, &train));
        }
    }
    Some(out)
}

/// The fitted constant of `power_on` in a fold: the curve's constant is the mean offset, the
/// power-on's own offset from it is kept apart when several were fitted.
fn level_of(fit: &Fitted, power_on: u32, _train: &[&SweepBlock]) -> f64 {
    fit.calibration.offset_of(power_on)
}

impl HeldOut {
    fn mean_square(&self) -> f64 {
        self.shape_ss / self.residuals.max(1) as f64
    }

    fn spread(&self, rule: ChoiceRule) -> PredictionSpread {
        let dof = self.residuals.saturating_sub(self.legs).max(1);
        let level_sd = (!self.levels.is_empty()).then(|| {
            (self.levels.iter().map(|l| l * l).sum::<f64>() / self.levels.len() as f64).sqrt()
        });
        PredictionSpread {
            shape_sd: (self.shape_ss / dof as f64).sqrt(),
            level_sd,
            rule,
            legs: self.legs,
        }
    }
}

/// The sweep calibration of one channel: the chosen model (and the best in T alone), module
/// docs.
///
/// # Errors
/// The fit of the chosen candidate to all blocks, or every candidate failing.
pub fn calibrate_channel_from_sweeps(
    blocks: &[SweepBlock],
    channel: Channel,
) -> Result<ChannelCalibration, ThermalError> {
    let legs: BTreeSet<u32> = blocks.iter().map(|b| b.leg).collect();
    let all: Vec<&SweepBlock> = blocks.iter().filter(|b| b.values.contains_key(&channel)).collect();
    if legs.len() < 2 {
        return one_leg(&all, channel);
    }
    let mut scores = Vec::new();
    let mut spreads = Vec::new();
    for c in Candidate::all() {
        let h = held_out(blocks, channel, c);
        scores.push(CandidateScore {
            candidate: c,
            held_out_rms: h.as_ref().map(|h| h.mean_square().sqrt()),
        });
        spreads.push(h);
    }
    let best = |lag_allowed: bool| {
        scores
            .iter()
            .enumerate()
            .filter(|(_, s)| lag_allowed || !s.candidate.lag)
            .filter_map(|(k, s)| s.held_out_rms.map(|r| (k, r)))
            .fold(None, |acc: Option<(usize, f64)>, (k, r)| match acc {
                Some((_, q)) if q <= r => acc,
                _ => Some((k, r)),
            })
            .map(|(k, _)| k)
    };
    let no_valid = ThermalError::NoValidOrder {
        observations: all.len(),
        distinct_temperatures: super::solve::distinct(all.iter().map(|b| b.temperature_c)),
    };
    let chosen = best(true).ok_or(no_valid.clone())?;
    let t_only = best(false).ok_or(no_valid)?;
    let (chosen_c, t_only_c) = (scores[chosen].candidate, scores[t_only].candidate);
    let spread = spreads[chosen]
        .as_ref()
        .expect("a scored candidate")
        .spread(ChoiceRule::LeaveOneLegOut);
    let t_fit = fit_candidate(&all, channel, t_only_c).ok_or(ThermalError::NoValidOrder {
        observations: all.len(),
        distinct_temperatures: 0,
    })?;
    let mut calibration = t_fit.calibration;
    if chosen_c.lag {
        let lag_fit = fit_candidate(&all, channel, chosen_c).ok_or(ThermalError::NoValidOrder {
            observations: all.len(),
            distinct_temperatures: 0,
        })?;
        let interval = tau_interval(&all, channel, chosen_c.order, &lag_fit);
        calibration.lagged = Some(LaggedBias {
            lag: ThermalLag {
                tau_s: lag_fit.tau_s,
                tau_interval_s: interval,
                rate_window_s: RATE_WINDOW_S,
            },
            fit: Box::new(lag_fit.calibration),
        });
    }
    calibration.selection = Some(HeldOutSelection {
        rule: ChoiceRule::LeaveOneLegOut,
        chosen: chosen_c,
        best_in_temperature_alone: t_only_c,
        scores,
        spread,
    });
    Ok(calibration)
}

/// One leg: T alone, order by PRESS, the spread from the deletion residuals.
fn one_leg(all: &[&SweepBlock], channel: Channel) -> Result<ChannelCalibration, ThermalError> {
    let records = records_at(all, channel, 0.0);
    let mut calibration = calibrate_channel(channel, &records, FitSettings::default())?;
    let order = calibration.bias.order;
    let press = calibration.bias.order_selection.press[order].unwrap_or(f64::NAN);
    let shape_sd = if press.is_finite() {
        (press / records.len().max(1) as f64).sqrt()
    } else {
        calibration.bias.residual_sd
    };
    let chosen = Candidate { order, lag: false };
    calibration.selection = Some(HeldOutSelection {
        rule: ChoiceRule::LeaveOneBlockOut,
        chosen,
        best_in_temperature_alone: chosen,
        scores: Vec::new(),
        spread: PredictionSpread {
            shape_sd,
            level_sd: None,
            rule: ChoiceRule::LeaveOneBlockOut,
            legs: 1,
        },
    });
    Ok(calibration)
}

/// Lag-1 autocorrelation of a series (0 for fewer than 3 values or none negative clamps).
fn lag_one_autocorrelation(x: &[f64]) -> f64 {
    if x.len() < 3 {
        return 0.0;
    }
    let mean = x.iter().sum::<f64>() / x.len() as f64;
    let var: f64 = x.iter().map(|v| (v - mean).powi(2)).sum();
    let cov: f64 = x.windows(2).map(|w| (w[0] - mean) * (w[1] - mean)).sum();
    if var > 0.0 { (cov / var).clamp(0.0, 0.99) } else { 0.0 }
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
        sorted.sort_by(|a, b| (a.power_on, a.t_s).partial_cmp(&(b.power_on, b.t_s)).unwrap_or(std::cmp::Ordering::Equal));
        sorted
            .iter()
            .map(|b| b.values[&channel] - predict(fit, b) - fit.calibration.offset_of(b.power_on))
            .collect()
    };
    let rho = lag_one_autocorrelation(&residuals);
    let dof = fit.calibration.bias.residual_degrees_of_freedom as f64 * (1.0 - rho) / (1.0 + rho);
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

    /// The bias at a temperature and rate (°C, °C/s), clamped to the fitted range, without the
    /// power-on's offset, and whether it was clamped.
    pub fn bias_at_rate(&self, temperature_c: f64, rate_c_per_s: f64) -> (f64, bool) {
        let (model, tau) = self.compensation_model();
        let curve = &model.bias;
        let [low, high] = curve.temperature_range_c;
        let t = temperature_c + tau * rate_c_per_s;
        (curve.value_at(t.clamp(low, high)), !(low..=high).contains(&t))
    }

    /// The prediction of a block mean at a temperature and rate (°C, °C/s) for a power-on
    /// (module docs, "Band").
    pub fn predict(&self, temperature_c: f64, rate_c_per_s: f64, power_on: PowerOnChoice) -> Prediction {
        let (model, tau) = self.compensation_model();
        let curve = &model.bias;
        let [low, high] = curve.temperature_range_c;
        let t = temperature_c + tau * rate_c_per_s;
        let inside = t.clamp(low, high);
        let clamped = inside != t;
        let (offset, offset_var) = match power_on {
            PowerOnChoice::Known(label) => {
                let o = model.power_on_offsets.iter().find(|o| o.power_on == label);
                (o.map_or(0.0, |o| o.offset), o.map_or(0.0, |o| o.offset_sd.powi(2)))
            }
            PowerOnChoice::New => (0.0, model.between_power_on_sd.map_or(0.0, |s| s * s)),
        };
        let se2 = curve.standard_error_at(inside).powi(2);
        let (shape, level) = match &self.selection {
            Some(s) => (s.spread.shape_sd, s.spread.level_sd.unwrap_or(0.0)),
            None => (curve.residual_sd, 0.0),
        };
        let widening = if clamped {
            derivative(curve, inside).abs() * (t - inside).abs()
        } else {
            0.0
        };
        Prediction {
            value: curve.value_at(inside) + offset,
            band_half_width: BAND_Z * (shape * shape + level * level + se2 + offset_var).sqrt() + widening,
            band_half_width_offset_removed: BAND_Z * (shape * shape + se2).sqrt() + widening,
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
    let channels: BTreeSet<Channel> = blocks.iter().flat_map(|b| b.values.keys().copied()).collect();
    channels
        .into_iter()
        .map(|c| calibrate_channel_from_sweeps(blocks, c).map(|cal| (c, cal)))
        .collect()
}
