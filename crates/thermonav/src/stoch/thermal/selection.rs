//! What a sweep calibration keeps: its blocks and legs, the candidates of a channel's model,
//! how each did on held-out data, and the spread the chosen model's band carries (the types of
//! `sweep_model`, apart from the fits).

use super::legs::LegDirection;
use crate::imu::Channel;
use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, StudentsT};
use std::collections::BTreeMap;

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
    /// Coldest and warmest sample of the block, °C.
    #[serde(default)]
    pub sample_range_c: [f64; 2],
    /// Mean of the lagged temperature ([`super::legs::lagged_temperatures`]) at each τ of
    /// [`super::legs::LAG_GRID_S`], °C; kept while fitting, not in the bank.
    #[serde(skip)]
    pub lagged_temperature_c: Vec<f64>,
    /// Mean rate of the temperature, °C/s.
    pub rate_c_per_s: f64,
    /// Samples averaged.
    pub samples: usize,
    /// Mean of each channel (after the removed signal), rate unit.
    pub values: BTreeMap<Channel, f64>,
}

impl SweepBlock {
    /// The block's mean lagged temperature at τ (s), °C: interpolated between the grid's
    /// values while fitting; from a bank (no grid kept), T + τ·dT/dt, its first-order form.
    pub fn effective_temperature_c(&self, tau_s: f64) -> f64 {
        let grid = super::legs::LAG_GRID_S;
        if self.lagged_temperature_c.len() != grid.len() || tau_s == 0.0 {
            return self.temperature_c + tau_s * self.rate_c_per_s;
        }
        let tau = tau_s.clamp(grid[0], grid[grid.len() - 1]);
        let k = grid.partition_point(|&g| g < tau).clamp(1, grid.len() - 1);
        let (g0, g1) = (grid[k - 1], grid[k]);
        let w = (tau - g0) / (g1 - g0);
        let (y0, y1) = (
            self.lagged_temperature_c[k - 1],
            self.lagged_temperature_c[k],
        );
        y0 + w * (y1 - y0)
    }
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
    pub direction: LegDirection,
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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ChoiceRule {
    /// Leave one leg out.
    LeaveOneLegOut,
    /// One leg: T alone, leaving out one of [`super::sweep_model::SEGMENTS_OF_ONE_LEG`] contiguous stretches of
    /// the leg at a time.
    LeaveOneSegmentOut,
}

/// The lag term of a chosen model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ThermalLag {
    /// τ, s: the bias is b(T_τ), T_τ the sensor's temperature through a first-order lag of
    /// |τ| ([`super::legs::lagged_temperatures`]; τ < 0: the structure lags), with the curve
    /// of [`super::LaggedBias::fit`]; to first order T_τ = T + τ·dT/dt.
    pub tau_s: f64,
    /// The 95 % profile interval of τ, s; `None` for an end at the search limit.
    pub tau_interval_s: [Option<f64>; 2],
    /// Window of the least-squares rate dT/dt that checks report beside the blocks, s.
    pub rate_window_s: f64,
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
    /// Degrees of freedom of the spread's estimate, the held-out residuals' count shrunk by
    /// their autocorrelation (`None` in banks written before 2026-12-06: the normal quantile).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub effective_dof: Option<f64>,
}

/// Two-sided 95 % quantile of the normal distribution: the band's multiple without a count of
/// degrees of freedom (and for curves not chosen on held-out legs).
pub(super) const BAND_Z: f64 = 1.959_963_984_540_054;

impl PredictionSpread {
    /// The 95 % band's multiple: Student's t at 0.975 with [`PredictionSpread::effective_dof`]
    /// degrees of freedom (the spread is estimated from few effectively independent
    /// residuals), or the normal quantile without them.
    pub fn band_quantile(&self) -> f64 {
        self.effective_dof
            .and_then(|dof| StudentsT::new(0.0, 1.0, dof).ok())
            .map_or(BAND_Z, |t| t.inverse_cdf(0.975))
    }
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
    /// Every candidate's score (by the rule's folds).
    pub scores: Vec<CandidateScore>,
    /// The spread of its predictions.
    pub spread: PredictionSpread,
}
