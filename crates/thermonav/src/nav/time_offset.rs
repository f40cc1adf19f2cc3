//! The IMU-GNSS time offset, estimated by an outer one-dimensional search: the IMU times are
//! shifted by a candidate offset, the whole run is made, and the offset that maximises the
//! innovations' log-likelihood Σ ln N(ν; 0, S) over the run is kept (golden-section search over
//! a bracket). Its sd is read from the curvature of that log-likelihood at the maximum
//! (the innovations of a Kalman filter are the prediction-error decomposition of the data's
//! likelihood, so −d²L/dδ² is the Fisher information of the offset).
//!
//! The offset has the sign of `convert --time-offset-s`: it is what is **added** to the IMU
//! times to put them on the GNSS time scale. An IMU whose clock reads 0.080 s late has an
//! offset of −0.080 s.
//!
//! The search is independent of the filter's internals (EKF, UKF or a Gaussian sum alike); its
//! cost is one run per evaluation (about 16 for a ±0.5 s bracket to 2 ms, and 2 more for the
//! curvature).

use super::run::{NoiseModel, RunError, RunSettings, Start, prepare};
use super::solution::InnovationRecord;
use crate::gnss::GnssFix;
use crate::imu::ImuSeries;
use crate::optimise::golden_section::golden_section_maximum;
use crate::time::Duration;
use serde::Serialize;

/// How the offset is searched for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeOffsetSearch {
    /// The search runs over −bracket..+bracket, s.
    pub bracket_s: f64,
    /// The golden-section search stops when its interval is this short, s.
    pub tolerance_s: f64,
    /// The step of the central second difference the sd is read from, s: long enough for the
    /// log-likelihood's change to stand above its roughness from gating decisions, short
    /// enough for the curve to be quadratic over it.
    pub curvature_step_s: f64,
}

impl Default for TimeOffsetSearch {
    fn default() -> Self {
        Self {
            bracket_s: 0.5,
            tolerance_s: 0.002,
            curvature_step_s: 0.01,
        }
    }
}

/// The estimated offset.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TimeOffsetEstimate {
    /// Added to the IMU times to put them on the GNSS scale, s.
    pub time_offset_s: f64,
    /// Its sd from the curvature of the log-likelihood, s; `None` when the curve is not
    /// concave at the maximum (the offset is then not observable from these data).
    pub time_offset_sd_s: Option<f64>,
    /// The innovations' log-likelihood at the estimate (natural log).
    pub log_likelihood: f64,
    /// The bracket searched, s.
    pub bracket_s: [f64; 2],
    /// Filter runs made.
    pub runs: usize,
}

/// The sum of the innovations' log-densities ln N(ν; 0, S) over a run, accepted or not (a
/// rejected update's density still says how well the candidate offset explains the fix).
pub fn innovation_log_likelihood(records: &[InnovationRecord]) -> f64 {
    records.iter().map(|r| r.log_likelihood).sum()
}

/// The sd of a maximum-likelihood estimate from the log-likelihood at x − h, x and x + h:
/// 1/√(−L'') with L'' the central second difference; `None` when L'' ≥ 0.
pub fn sd_from_curvature(below: f64, at: f64, above: f64, step: f64) -> Option<f64> {
    let second = (below - 2.0 * at + above) / (step * step);
    (second < 0.0).then(|| 1.0 / (-second).sqrt())
}

/// The series with `offset_s` added to every time (an offset beyond the timestamp range,
/// ±9e9 s, leaves the times as they are; the search's bracket is far inside it).
pub fn shifted(series: &ImuSeries, offset_s: f64) -> ImuSeries {
    let span = Duration::from_seconds(offset_s).unwrap_or(Duration::ZERO);
    let mut out = series.clone();
    for t in &mut out.time {
        *t = t.checked_add(span).unwrap_or(*t);
    }
    out
}

/// The innovations' log-likelihood of the run with the IMU times shifted by `offset_s`.
///
/// # Errors
/// Any [`RunError`] of the run.
pub fn log_likelihood_at(
    series: &ImuSeries,
    gnss: &[GnssFix],
    noise: NoiseModel,
    start: Start,
    settings: &RunSettings,
    offset_s: f64,
) -> Result<f64, RunError> {
    let mut quiet = settings.clone();
    quiet.engine.smooth = false;
    let prepared = prepare(
        shifted(series, offset_s),
        gnss.to_vec(),
        noise,
        start,
        &quiet,
    )?;
    let outcome = prepared.run(&mut |_| {})?;
    Ok(innovation_log_likelihood(&outcome.solution.innovations))
}

/// The offset that maximises the innovations' log-likelihood, and its sd.
///
/// # Errors
/// Any [`RunError`] of a run.
pub fn estimate_time_offset(
    series: &ImuSeries,
    gnss: &[GnssFix],
    noise: NoiseModel,
    start: Start,
    settings: &RunSettings,
    search: &TimeOffsetSearch,
) -> Result<TimeOffsetEstimate, RunError> {
    let mut at = |offset_s: f64| log_likelihood_at(series, gnss, noise, start, settings, offset_s);
    let bracket_s = [-search.bracket_s, search.bracket_s];
    let (best_s, best, runs) =
        golden_section_maximum(&mut at, bracket_s[0], bracket_s[1], search.tolerance_s)?;
    let h = search.curvature_step_s;
    let (below, above) = (at(best_s - h)?, at(best_s + h)?);
    Ok(TimeOffsetEstimate {
        time_offset_s: best_s,
        time_offset_sd_s: sd_from_curvature(below, best, above, h),
        log_likelihood: best,
        bracket_s,
        runs: runs + 2,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    // Oracle: the Gaussian log-likelihood −(x − μ)²/(2σ²) has −L'' = 1/σ² exactly, and the
    // central second difference of a quadratic is exact (to rounding).
    #[test]
    fn sd_from_curvature_of_a_gaussian_log_likelihood() {
        let sigma = 0.0031;
        let ll = |x: f64| 17.0 - (x - 0.08) * (x - 0.08) / (2.0 * sigma * sigma);
        let (x, h) = (0.081, 0.01);
        let sd = sd_from_curvature(ll(x - h), ll(x), ll(x + h), h).unwrap();
        assert!((sd - sigma).abs() < 1e-9 * sigma * 1e3, "{sd}");
        assert_eq!(sd_from_curvature(1.0, 0.0, 1.0, h), None);
    }

    #[test]
    fn shifted_adds_the_offset_to_every_time() {
        let series = ImuSeries {
            time: vec![
                crate::time::Timestamp::from_nanos(1_000_000_000),
                crate::time::Timestamp::from_nanos(1_005_000_000),
            ],
            ..ImuSeries::default()
        };
        let out = shifted(&series, -0.125);
        assert_eq!(out.time[0].as_nanos(), 875_000_000);
        assert_eq!(out.time[1].as_nanos(), 880_000_000);
    }
}
