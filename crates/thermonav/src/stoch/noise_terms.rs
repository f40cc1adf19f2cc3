//! IEEE Std 952-1997 Annex C noise terms read off an Allan deviation curve (El-Sheimy, Hou &
//! Niu 2008). Each term dominates where the log-log slope of σ(τ) takes its value:
//!
//! | term | slope | σ(τ) | read as |
//! |---|---|---|---|
//! | quantisation Q | −1 | √3 Q / τ | Q = σ τ / √3 |
//! | angle / velocity random walk N | −½ | N / √τ | N = σ √τ (the line's value at τ = 1 s) |
//! | bias instability B | 0 | 0.664 B at the flat minimum | B = σ_min / 0.664 |
//! | rate random walk K | +½ | K √(τ/3) | K = σ √(3/τ) (the line's value at τ = 3 s) |
//! | rate ramp R | +1 | R τ / √2 | R = σ √2 / τ |
//!
//! The local slope at a point is the central difference of ln σ over ln τ (one-sided at the
//! ends). Each term is read from **one contiguous region** of the curve, never from points
//! scattered over it, and is the geometric mean of the per-point readings over that region
//! (for N: the fixed-slope −½ line fitted to ln σ by least squares). Its confidence interval
//! is the geometric mean of the same readings of the points' own Allan confidence limits
//! (neighbouring τ of an overlapping curve share most of their data, so the limits are not
//! narrowed by averaging them).
//!
//! - **N**: the shortest-τ run of points on the falling branch (slope within
//!   ±[`BRANCH_TOLERANCE`] of −½, so that one point bumped by a periodic disturbance does not
//!   cut the line in two), ended at its last point whose slope is within ±[`SLOPE_TOLERANCE`] of
//!   −½ (the region ends on the line, not where the next term bends it). Only τ of at least
//!   [`MIN_WHITE_NOISE_FACTOR`] samples count: at shorter τ the curve sees the sensor's own
//!   anti-alias filter (real ADIS16405 curves flatten to slope −0.3 there). The search stops
//!   at the first point where the curve rises (slope > 0): a −½ stretch beyond it is the tail
//!   of a Gauss-Markov process at τ ≫ Tc (also slope −½), not white noise.
//! - **B**: the curve's minimum. At an interior minimum it is the usual reading. At the first
//!   or last point the flat floor was not reached; the reading is then an upper bound
//!   ([`Bound::AtMost`]). There is no lower-bound case: Allan variances of independent noises
//!   add, so the flicker floor 0.664 B lies under the curve at every τ.
//! - **K** (and R): the longest-τ run of points whose slope is within ±[`BRANCH_TOLERANCE`] of
//!   +½ (+1), started at its first point within ±[`SLOPE_TOLERANCE`], at least two points
//!   long, which must reach the curve's end: no later point may lie below the run's line by
//!   more than its own confidence limit (a rise that falls again is a Gauss-Markov peak, not a
//!   random walk; the last points of a curve, with few degrees of freedom, may scatter).
//! - **Q**: the run of points from the shortest τ whose slope is within ±[`SLOPE_TOLERANCE`]
//!   of −1, at least two points long.
//!
//! A term the curve does not support is `Err(Absent)` with the reason.

use super::allan::{AllanCurve, AllanIntervals};
use serde::Serialize;

/// Half-width of the slope window that a term's region must start or end in.
pub const SLOPE_TOLERANCE: f64 = 0.15;
/// Half-width of the slope window that the interior of a region may wander in.
pub const BRANCH_TOLERANCE: f64 = 0.35;
/// Smallest averaging factor m (τ = m τ₀) that the white-noise region may use.
pub const MIN_WHITE_NOISE_FACTOR: usize = 10;
/// σ_min = √(2 ln 2 / π) B ≈ 0.664 B for flicker (bias-instability) noise.
pub const BIAS_INSTABILITY_FACTOR: f64 = 0.664;

/// Whether a term is an estimate or only a bound on the coefficient.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Bound {
    /// Read where the term dominates.
    Estimate,
    /// The coefficient is at most `value` (bias instability at an end of the curve).
    AtMost,
}

/// A confidence interval of a term, in the term's unit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TermInterval {
    /// Confidence level of the Allan limits it was read from.
    pub level: f64,
    /// Lower limit.
    pub low: f64,
    /// Upper limit.
    pub high: f64,
}

/// One identified term: its value (SI of the curve's data), the τ range it was read over and
/// its confidence interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Term {
    /// The coefficient (or its bound, see `bound`).
    pub value: f64,
    /// Shortest τ used, s.
    pub tau_min_s: f64,
    /// Longest τ used, s.
    pub tau_max_s: f64,
    /// Points of the curve used.
    pub points: usize,
    /// Confidence interval; `None` when the limits do not belong to the curve or are not finite.
    pub ci: Option<TermInterval>,
    /// Estimate or bound.
    pub bound: Bound,
}

/// Why a term was not read.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Absent {
    /// What the curve lacks.
    pub reason: String,
}

/// A term, or why the curve does not support it.
pub type TermReading = Result<Term, Absent>;

/// The five terms.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NoiseTerms {
    /// Quantisation noise Q (rad or m/s for rate data in rad/s or m/s²).
    pub quantization: TermReading,
    /// Random walk N: ARW in rad/√s, VRW in m/s/√s.
    pub random_walk: TermReading,
    /// Bias instability B (rad/s or m/s²).
    pub bias_instability: TermReading,
    /// Rate random walk K (rad/s/√s or m/s²/√s).
    pub rate_random_walk: TermReading,
    /// Rate ramp R (rad/s² or m/s³).
    pub rate_ramp: TermReading,
}

impl NoiseTerms {
    /// Every term absent for the same reason.
    pub fn absent(reason: &str) -> Self {
        let absent = || Err(absent(reason));
        Self {
            quantization: absent(),
            random_walk: absent(),
            bias_instability: absent(),
            rate_random_walk: absent(),
            rate_ramp: absent(),
        }
    }
}

fn absent(reason: &str) -> Absent {
    Absent {
        reason: reason.to_string(),
    }
}

/// Local slopes d ln σ / d ln τ (one-sided at the ends; 0 for a one-point curve).
pub fn local_slopes(curve: &AllanCurve) -> Vec<f64> {
    let n = curve.adev.len().min(curve.tau_s.len());
    let ln = |v: &[f64], i: usize| v[i].max(f64::MIN_POSITIVE).ln();
    (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            if a == b {
                return 0.0;
            }
            (ln(&curve.adev, b) - ln(&curve.adev, a)) / (ln(&curve.tau_s, b) - ln(&curve.tau_s, a))
        })
        .collect()
}

/// Reads the five IEEE 952 terms off a curve, each over one region, with confidence intervals
/// from `limits` (the curve's own Allan limits; other limits give terms without intervals).
pub fn fit_noise_terms(curve: &AllanCurve, limits: &AllanIntervals) -> NoiseTerms {
    if curve.adev.len() < 2 || curve.tau_s.len() != curve.adev.len() {
        return NoiseTerms::absent("the curve has fewer than two points");
    }
    let slopes = local_slopes(curve);
    let read = |region: Result<Region, Absent>, reading: fn(f64, f64) -> f64| {
        region.and_then(|r| read_over(curve, limits, r, reading, Bound::Estimate))
    };
    NoiseTerms {
        quantization: read(quantization_region(curve, &slopes), quantization_reading),
        random_walk: read(white_noise_region(curve, &slopes), white_noise_reading),
        bias_instability: bias_instability(curve, limits),
        rate_random_walk: read(
            long_tau_region(curve, limits, &slopes, 0.5, rate_random_walk_reading),
            rate_random_walk_reading,
        ),
        rate_ramp: read(
            long_tau_region(curve, limits, &slopes, 1.0, rate_ramp_reading),
            rate_ramp_reading,
        ),
    }
}

/// Q = σ τ / √3.
fn quantization_reading(tau_s: f64, sigma: f64) -> f64 {
    sigma * tau_s / 3f64.sqrt()
}

/// N = σ √τ.
fn white_noise_reading(tau_s: f64, sigma: f64) -> f64 {
    sigma * tau_s.sqrt()
}

/// K = σ √(3/τ).
fn rate_random_walk_reading(tau_s: f64, sigma: f64) -> f64 {
    sigma * (3.0 / tau_s).sqrt()
}

/// R = σ √2 / τ.
fn rate_ramp_reading(tau_s: f64, sigma: f64) -> f64 {
    sigma * 2f64.sqrt() / tau_s
}

/// Points `first..=last` of a curve.
#[derive(Debug, Clone, Copy)]
struct Region {
    first: usize,
    last: usize,
}

/// Whether a local slope lies within `tolerance` of `slope`.
fn near(local_slope: f64, slope: f64, tolerance: f64) -> bool {
    (local_slope - slope).abs() <= tolerance
}

/// Geometric mean (NaN for no values, which callers refuse).
fn geometric_mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, count) = values.fold((0.0, 0usize), |(s, n), v| (s + v.ln(), n + 1));
    (sum / count as f64).exp()
}

/// The term read over `region`: the geometric mean of `reading(τ, σ)`, with its interval.
fn read_over(
    curve: &AllanCurve,
    limits: &AllanIntervals,
    region: Region,
    reading: impl Fn(f64, f64) -> f64,
    bound: Bound,
) -> TermReading {
    let points = region.first..=region.last;
    let value = geometric_mean(points.map(|i| reading(curve.tau_s[i], curve.adev[i])));
    if !(value.is_finite() && value > 0.0) {
        return Err(absent(
            "the curve is zero or not finite over the term's region",
        ));
    }
    Ok(Term {
        value,
        tau_min_s: curve.tau_s[region.first],
        tau_max_s: curve.tau_s[region.last],
        points: region.last - region.first + 1,
        ci: interval_over(curve, limits, region, reading),
        bound,
    })
}

/// The interval of a term: its reading of the lower and upper Allan limits over `region`.
fn interval_over(
    curve: &AllanCurve,
    limits: &AllanIntervals,
    region: Region,
    reading: impl Fn(f64, f64) -> f64,
) -> Option<TermInterval> {
    let n = curve.adev.len();
    if limits.low.len() != n || limits.high.len() != n {
        return None;
    }
    let at = |bound: &[f64]| {
        geometric_mean((region.first..=region.last).map(|i| reading(curve.tau_s[i], bound[i])))
    };
    let (low, high) = (at(&limits.low), at(&limits.high));
    (low.is_finite() && high.is_finite() && low >= 0.0 && low <= high).then_some(TermInterval {
        level: limits.level,
        low,
        high,
    })
}

/// The white-noise region (see the module documentation).
fn white_noise_region(curve: &AllanCurve, slopes: &[f64]) -> Result<Region, Absent> {
    let on_branch = |j: usize| near(slopes[j], -0.5, BRANCH_TOLERANCE) && curve.adev[j] > 0.0;
    let Some(mut i) = (curve.averaging_factor.iter()).position(|&m| m >= MIN_WHITE_NOISE_FACTOR)
    else {
        return Err(absent(&format!(
            "no τ of {MIN_WHITE_NOISE_FACTOR} samples or more, below which the sensor's own filter shapes the curve"
        )));
    };
    while i < slopes.len() && slopes[i] <= 0.0 {
        if !on_branch(i) {
            i += 1;
            continue;
        }
        let end = (i..slopes.len())
            .take_while(|&j| on_branch(j))
            .last()
            .unwrap_or(i);
        if let Some(last) = (i..=end)
            .rev()
            .find(|&j| near(slopes[j], -0.5, SLOPE_TOLERANCE))
        {
            return Ok(Region { first: i, last });
        }
        i = end + 1;
    }
    Err(absent(&white_noise_absence(curve, i)))
}

/// Why no white-noise region was found, the search having stopped at point `stop`.
fn white_noise_absence(curve: &AllanCurve, stop: usize) -> String {
    match curve.tau_s.get(stop) {
        Some(tau_s) => format!(
            "no region of slope -1/2 before the curve rises at τ = {tau_s} s (a -1/2 stretch beyond a rise is a Gauss-Markov tail, not white noise)"
        ),
        None => "no region of slope -1/2".to_string(),
    }
}

/// The run of slope −1 from the shortest τ.
fn quantization_region(curve: &AllanCurve, slopes: &[f64]) -> Result<Region, Absent> {
    let on_line = |j: usize| near(slopes[j], -1.0, SLOPE_TOLERANCE) && curve.adev[j] > 0.0;
    let run = (0..slopes.len()).take_while(|&j| on_line(j)).count();
    match run {
        0 => Err(absent("the curve does not start with slope -1")),
        1 => Err(absent(
            "only the shortest τ has slope -1: one point does not make a region",
        )),
        _ => Ok(Region {
            first: 0,
            last: run - 1,
        }),
    }
}

/// The last run of slope `slope` (+½ or +1), which must reach the longest τ: every later point's
/// upper confidence limit must reach the run's line (without limits: no later point).
fn long_tau_region(
    curve: &AllanCurve,
    limits: &AllanIntervals,
    slopes: &[f64],
    slope: f64,
    reading: fn(f64, f64) -> f64,
) -> Result<Region, Absent> {
    let on_branch = |j: usize| near(slopes[j], slope, BRANCH_TOLERANCE) && curve.adev[j] > 0.0;
    let last = (0..slopes.len()).rev().find(|&j| on_branch(j));
    let start = last.map(|e| {
        (0..=e)
            .rev()
            .take_while(|&j| on_branch(j))
            .last()
            .unwrap_or(e)
    });
    let first =
        start.and_then(|s| (s..slopes.len()).find(|&j| near(slopes[j], slope, SLOPE_TOLERANCE)));
    let (Some(first), Some(last)) = (first, last) else {
        return Err(absent(&format!("no region of slope {slope:+} at long τ")));
    };
    if first >= last {
        return Err(absent(&format!(
            "slope {slope:+} at τ = {} s only: one point does not make a region",
            curve.tau_s[last]
        )));
    }
    let region = Region { first, last };
    let line = read_over(curve, limits, region, reading, Bound::Estimate)?.value;
    match falls_below(curve, limits, last, line, reading) {
        Some(tau_s) => Err(absent(&format!(
            "slope {slope:+} at τ = {}..{} s does not reach the longest τ: the curve falls below that line at τ = {tau_s} s (a Gauss-Markov peak, not this term)",
            curve.tau_s[first], curve.tau_s[last]
        ))),
        None => Ok(region),
    }
}

/// The first τ after point `last` whose upper limit lies below the line of coefficient `line`
/// (every later τ when there are no limits for the curve).
fn falls_below(
    curve: &AllanCurve,
    limits: &AllanIntervals,
    last: usize,
    line: f64,
    reading: fn(f64, f64) -> f64,
) -> Option<f64> {
    let has_limits = limits.high.len() == curve.adev.len();
    (last + 1..curve.adev.len())
        .find(|&j| !has_limits || reading(curve.tau_s[j], limits.high[j]) < line)
        .map(|j| curve.tau_s[j])
}

/// B at the curve's minimum: an estimate inside the curve, an upper bound at its ends.
fn bias_instability(curve: &AllanCurve, limits: &AllanIntervals) -> TermReading {
    let minimum = (curve.adev.iter().enumerate())
        .filter(|(_, sigma)| **sigma > 0.0)
        .min_by(|a, b| a.1.total_cmp(b.1));
    let Some((i, _)) = minimum else {
        return Err(absent("the curve is zero everywhere"));
    };
    let at_an_end = i == 0 || i + 1 == curve.adev.len();
    let bound = if at_an_end {
        Bound::AtMost
    } else {
        Bound::Estimate
    };
    let region = Region { first: i, last: i };
    read_over(
        curve,
        limits,
        region,
        |_, sigma| sigma / BIAS_INSTABILITY_FACTOR,
        bound,
    )
}

/// Ratio of the Allan-deviation peak of a first-order Gauss-Markov process to its σ (≈ 0.62 at
/// τ ≈ 1.89 Tc); turns a data sheet's "in-run bias stability" into a Gauss-Markov σ.
pub const GAUSS_MARKOV_ADEV_PEAK_RATIO: f64 = 0.62;

/// Theoretical Allan variance of white rate noise of density N: N²/τ.
pub fn avar_white(density: f64, tau_s: f64) -> f64 {
    density * density / tau_s
}

/// Theoretical Allan variance of a rate random walk of density K: K² τ / 3.
pub fn avar_random_walk(density: f64, tau_s: f64) -> f64 {
    density * density * tau_s / 3.0
}

/// Theoretical Allan variance of a first-order Gauss-Markov rate of σ and Tc (q = 2σ²/Tc):
/// (q Tc²/τ) [1 − (Tc/2τ)(3 − 4 e^{−τ/Tc} + e^{−2τ/Tc})] (IEEE Std 952 Annex C; it tends to
/// q τ/3 for τ ≪ Tc and 2σ²Tc/τ for τ ≫ Tc).
pub fn avar_gauss_markov(sigma: f64, correlation_time_s: f64, tau_s: f64) -> f64 {
    let tc = correlation_time_s;
    let x = tau_s / tc;
    let q = 2.0 * sigma * sigma / tc;
    q * tc * tc / tau_s * (1.0 - (3.0 - 4.0 * (-x).exp() + (-2.0 * x).exp()) / (2.0 * x))
}
