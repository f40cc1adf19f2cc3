//! The IMU-GNSS time offset, estimated by an outer one-dimensional search: the IMU times are
//! shifted by a candidate offset, the whole run is made, and the offset that maximises the
//! innovations' log-likelihood L(δ) = Σ ln N(ν; 0, S) over the run is kept (the innovations
//! of a Kalman filter are the prediction-error decomposition of the data's likelihood).
//!
//! The offset has the sign of `convert --time-offset-s`: it is what is **added** to the IMU
//! times to put them on the GNSS time scale. An IMU whose clock reads 0.080 s late has an
//! offset of −0.080 s.
//!
//! # The interval: the likelihood's profile, not its curvature
//! The likelihood is profiled over the bracket on a grid ([`TimeOffsetSearch::grid_points`]
//! runs), its best grid cell refined by golden section, and the 95 % interval is the
//! hull of the likelihood-ratio set {δ : L(δ̂) − L(δ) ≤ c}, each end found by bisection
//! between the outermost point inside and the next one outside. With a correct filter model
//! and a smooth profile c = χ²₁,₀.₉₅ / 2 = 1.92 (Wilks). A curvature read at one point (the former sd) is blind to a profile that is
//! flat over hundreds of ms with small ripples from gating decisions: it gave a 17 ms sd on a
//! slow rover whose offset the data do not determine at all (issue 38, row 13).
//!
//! **Dispersion (a quasi-likelihood correction).** When the filter's innovations are larger
//! than its S says, φ = Σ NIS / Σ m (the mean NIS per degree of freedom over the run at δ̂)
//! exceeds 1 and L is too sharp by that factor; the drop threshold is then c = 1.92 · φ, as a
//! quasi-likelihood ratio test divides the deviance by the dispersion. φ < 1 is not used to
//! narrow the interval (under-dispersion on one run is mostly the gate trimming the largest
//! innovations, and a narrower interval than Wilks' would be the overconfidence this guards
//! against): c = 1.92 · max(1, φ). The innovations' serial correlation (a mis-modelled
//! coloured GNSS error) is not corrected for; the NIS level is the check available without a
//! second model. On the simulated slow rover φ is 1.00-1.01: there the correction changes
//! nothing, and what broke coverage was the next point.
//!
//! **Roughness.** A run's discrete decisions (alignment, which fix starts the filter, the
//! gate) make L(δ) ripple from one offset to the next by a nat or two on a slow vehicle, the
//! size of the threshold itself: the maximum sits on a ripple's crest and the set breaks into
//! pieces. The ripple's robust sd r is read from the grid's second differences near the
//! maximum ([`roughness`]; 0 for a smooth or sharply peaked profile) and the threshold is
//! c = 1.92 · max(1, φ) + 2 r: the drop from a crest to the true offset's trough is a
//! difference of two ripples, sd √2 r, and 2 r covers it about 92 % of the time one-sided.
//! On 20 seeds of the slow rover (`bench/slow_rover.py`, docs/user-guide.md) the plain 1.92
//! on the maximum's piece covered the offset in 15 of 20, the hull with 1.92 in 16 of 19, the
//! hull with c above in 17 of 19 (18 of 20 when rerun; measured from the same saved profiles).
//!
//! **Open ends and warnings.** Where the set reaches an end of the bracket, that end is open
//! ([`IntervalEnd::AtBracketEnd`]): the data allow offsets at least that far out. Where it
//! reaches both ends (the profile is flat over the bracket) or where a point between the ends
//! is outside the set (a multimodal profile), the offset is not observable from these data
//! and [`TimeOffsetEstimate::warning`] says so (an interval open on one side is warned of
//! too: the bracket is too small to bound it).
//!
//! **The same fixes for every candidate.** The runs see only the fixes that every shifted
//! record covers ([`common_fixes`]): otherwise the number of likelihood terms would change
//! with the offset and bias the profile toward the shift that drops the fixes near the ends.
//!
//! **Cost**, in filter runs: the grid (21 by default), then about 2 plus
//! log(2·step/tolerance)/log(1.618) for the golden section (10 for ±0.5 s to 2 ms), then
//! about log₂(step/tolerance) per closed end (5 each); some 35-40 runs in all, each run
//! evaluated once. The search is independent of the filter's internals (EKF, UKF or a
//! Gaussian sum alike).

use super::run::{NoiseModel, RunError, RunSettings, Start, prepare};
use super::solution::InnovationRecord;
use crate::gnss::GnssFix;
use crate::imu::ImuSeries;
use crate::optimise::golden_section::golden_section_maximum;
use crate::setting::{SettingError, positive};
use crate::time::Duration;
use serde::Serialize;

/// How the offset is searched for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeOffsetSearch {
    /// The search runs over −bracket..+bracket, s.
    pub bracket_s: f64,
    /// The golden-section refinement and the interval ends' bisection stop when their
    /// interval is this short, s.
    pub tolerance_s: f64,
    /// Points of the likelihood's profile over the bracket, ends included (at least 3).
    pub grid_points: usize,
}

impl Default for TimeOffsetSearch {
    fn default() -> Self {
        Self {
            bracket_s: 0.5,
            tolerance_s: 0.002,
            grid_points: 21,
        }
    }
}

/// The widest half-bracket of the search, s: a larger offset is a clock-scale error, not a
/// delay.
pub const MAX_BRACKET_S: f64 = 10.0;

impl TimeOffsetSearch {
    /// The search over ±`bracket_s` (positive, at most [`MAX_BRACKET_S`]), its other
    /// settings the defaults: what `integrate`, `evaluate` and the Python package search with.
    ///
    /// # Errors
    /// A bracket that is not positive or beyond [`MAX_BRACKET_S`], named
    /// `time_offset_bracket_s`.
    pub fn with_bracket(bracket_s: f64) -> Result<Self, SettingError> {
        const NAME: &str = "time_offset_bracket_s";
        match positive(NAME, bracket_s)? {
            b if b <= MAX_BRACKET_S => Ok(Self {
                bracket_s: b,
                ..Self::default()
            }),
            b => Err(SettingError {
                name: NAME,
                value: b.to_string(),
                expected: format!(
                    "beyond {MAX_BRACKET_S} s: a larger offset is a clock-scale error, not a delay"
                ),
            }),
        }
    }
}

/// χ²₁,₀.₉₅ / 2: the log-likelihood drop that bounds a 95 % likelihood-ratio interval of one
/// parameter (Wilks), natural log.
pub const LIKELIHOOD_DROP_95: f64 = 1.920_729_410_347_062;

/// One end of the offset's interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum IntervalEnd {
    /// The likelihood drops by the threshold here, s.
    Within {
        /// The end, s.
        offset_s: f64,
    },
    /// The likelihood stays within the threshold up to the bracket's end: the interval is
    /// open on this side and the data allow offsets at least this far out, s.
    AtBracketEnd {
        /// The bracket's end, s.
        offset_s: f64,
    },
}

impl IntervalEnd {
    /// The end's offset, s.
    pub fn offset_s(self) -> f64 {
        match self {
            Self::Within { offset_s } | Self::AtBracketEnd { offset_s } => offset_s,
        }
    }

    /// True when the interval is open on this side.
    pub fn is_open(self) -> bool {
        matches!(self, Self::AtBracketEnd { .. })
    }
}

/// Whether the data determine the offset.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Observability {
    /// The interval is closed on both sides, inside the bracket.
    Resolved,
    /// The interval reaches one end of the bracket: a wider bracket is needed to bound it.
    OpenOnOneSide,
    /// The profile stays within the threshold over the whole bracket.
    FlatOverTheBracket,
    /// Grid points apart from the maximum's region are inside the threshold too.
    Multimodal,
}

/// One evaluation of the profile: the run with the IMU times shifted by `offset_s`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ProfilePoint {
    /// The candidate offset, s.
    pub offset_s: f64,
    /// The innovations' log-likelihood (natural log).
    pub log_likelihood: f64,
    /// Σ NIS / Σ m over the run's innovations (1 for a consistent filter).
    pub nis_per_dof: f64,
}

/// The estimated offset.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TimeOffsetEstimate {
    /// Added to the IMU times to put them on the GNSS scale, s (the profile's maximum).
    pub time_offset_s: f64,
    /// The 95 % likelihood-ratio interval's lower end, s.
    pub lower: IntervalEnd,
    /// Its upper end, s.
    pub upper: IntervalEnd,
    /// The Gaussian sd with the same 95 % interval, (upper − lower) / (2 · 1.96), s; `None`
    /// when the interval is open on either side.
    pub time_offset_sd_s: Option<f64>,
    /// Whether the data determine the offset.
    pub observability: Observability,
    /// What the user should know when they do not (also printed by `integrate`).
    pub warning: Option<String>,
    /// Whether the run applies the estimate: only when the data determine the offset
    /// ([`Observability::Resolved`]). Otherwise the estimate and its interval are for
    /// information, and the run keeps the IMU times as given.
    pub applied: bool,
    /// The offset the run adds to the IMU times, s: the estimate when [`Self::applied`], else
    /// 0 (the times as given).
    pub applied_offset_s: f64,
    /// The innovations' dispersion φ = mean NIS per degree of freedom at the estimate.
    pub dispersion: f64,
    /// The profile's roughness r from run to run, natural log ([`roughness`]).
    pub roughness: f64,
    /// The log-likelihood drop that bounds the interval, 1.92 · max(1, φ) + 2 r.
    pub likelihood_drop: f64,
    /// The innovations' log-likelihood at the estimate (natural log).
    pub log_likelihood: f64,
    /// The bracket searched, s.
    pub bracket_s: [f64; 2],
    /// Filter runs made.
    pub runs: usize,
    /// Every evaluation, in increasing offset.
    pub profile: Vec<ProfilePoint>,
}

/// The sum of the innovations' log-densities ln N(ν; 0, S) over a run, accepted or not (a
/// rejected update's density still says how well the candidate offset explains the fix).
pub fn innovation_log_likelihood(records: &[InnovationRecord]) -> f64 {
    records.iter().map(|r| r.log_likelihood).sum()
}

/// Σ NIS / Σ m over the innovations, accepted or not (the same terms as the likelihood);
/// 1 without any.
pub fn nis_per_degree_of_freedom(records: &[InnovationRecord]) -> f64 {
    let dof: usize = records.iter().map(|r| r.kind.dimension()).sum();
    match dof {
        0 => 1.0,
        _ => records.iter().map(|r| r.nis).sum::<f64>() / dof as f64,
    }
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
    profile_point_at(series, gnss, noise, start, settings, offset_s).map(|p| p.log_likelihood)
}

/// The profile's point at `offset_s`: the run with the IMU times shifted by it.
///
/// # Errors
/// Any [`RunError`] of the run.
pub fn profile_point_at(
    series: &ImuSeries,
    gnss: &[GnssFix],
    noise: NoiseModel,
    start: Start,
    settings: &RunSettings,
    offset_s: f64,
) -> Result<ProfilePoint, RunError> {
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
    let records = &outcome.solution.innovations;
    Ok(ProfilePoint {
        offset_s,
        log_likelihood: innovation_log_likelihood(records),
        nis_per_dof: nis_per_degree_of_freedom(records),
    })
}

/// The offset that maximises the innovations' log-likelihood, with its likelihood-ratio
/// interval (see the module's documentation).
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
    let common = common_fixes(series, gnss, search.bracket_s.abs());
    let mut at =
        |offset_s: f64| profile_point_at(series, &common, noise, start, settings, offset_s);
    profile_time_offset(&mut at, search)
}

/// The fixes that every candidate run covers: those at least `bracket_s` inside both ends
/// of the IMU record (all of them when the record is shorter than twice the bracket).
///
/// Each fix adds a term ln N(ν; 0, S) to the likelihood, of a size set by S (about −3.5
/// for a 0.7 m fix, +8 for a 2 cm one): were the fixes near the ends counted only by the
/// candidates whose shifted record covers them, the likelihood would favour the shift that
/// keeps fewer (or more) of them, by some 3.5 per fix, 35 for 0.5 s of 20 Hz fixes: far
/// more than the offset's own signal on a slow vehicle.
pub fn common_fixes(series: &ImuSeries, gnss: &[GnssFix], bracket_s: f64) -> Vec<GnssFix> {
    let (Some(&first), Some(&last)) = (series.time.first(), series.time.last()) else {
        return gnss.to_vec();
    };
    let margin = Duration::from_seconds(bracket_s).unwrap_or(Duration::ZERO);
    let inside: Vec<GnssFix> = gnss
        .iter()
        .filter(|f| f.time >= first + margin && f.time + margin <= last)
        .copied()
        .collect();
    match inside.is_empty() {
        true => gnss.to_vec(),
        false => inside,
    }
}

/// The profile search over any evaluator of [`ProfilePoint`]s: the grid, the golden-section
/// refinement of the best cell, the threshold from the dispersion at the maximum and the
/// interval's ends.
///
/// # Errors
/// The first error of `at`.
pub fn profile_time_offset<E>(
    at: &mut dyn FnMut(f64) -> Result<ProfilePoint, E>,
    search: &TimeOffsetSearch,
) -> Result<TimeOffsetEstimate, E> {
    let bracket_s = [-search.bracket_s.abs(), search.bracket_s.abs()];
    let mut profile = Profile::default();
    for offset_s in grid_offsets_s(bracket_s, search.grid_points) {
        profile.evaluate(at, offset_s)?;
    }
    let grid = profile.points.clone();
    let best = refine_maximum(&mut profile, at, bracket_s, search.tolerance_s)?;
    let roughness = roughness(&grid, best.log_likelihood);
    let likelihood_drop = LIKELIHOOD_DROP_95 * best.nis_per_dof.max(1.0) + 2.0 * roughness;
    let floor = best.log_likelihood - likelihood_drop;
    let lower = interval_end(&mut profile, at, &best, floor, bracket_s[0], search)?;
    let upper = interval_end(&mut profile, at, &best, floor, bracket_s[1], search)?;
    let observability = observability_of(&profile.points, [lower, upper], floor);
    let applied = observability == Observability::Resolved;
    Ok(TimeOffsetEstimate {
        time_offset_s: best.offset_s,
        lower,
        upper,
        time_offset_sd_s: equivalent_sd_s(lower, upper),
        observability,
        warning: warning_of(observability, [lower, upper], best.offset_s),
        applied,
        applied_offset_s: if applied { best.offset_s } else { 0.0 },
        dispersion: best.nis_per_dof,
        roughness,
        likelihood_drop,
        log_likelihood: best.log_likelihood,
        bracket_s,
        runs: profile.points.len(),
        profile: profile.points,
    })
}

/// Every evaluation made, kept sorted by offset.
#[derive(Debug, Default)]
struct Profile {
    points: Vec<ProfilePoint>,
}

impl Profile {
    /// The point at `offset_s`, evaluated once.
    fn evaluate<E>(
        &mut self,
        at: &mut dyn FnMut(f64) -> Result<ProfilePoint, E>,
        offset_s: f64,
    ) -> Result<ProfilePoint, E> {
        let k = self.points.partition_point(|p| p.offset_s < offset_s);
        if let Some(p) = self.points.get(k).filter(|p| p.offset_s == offset_s) {
            return Ok(*p);
        }
        let point = at(offset_s)?;
        self.points.insert(k, point);
        Ok(point)
    }

    /// The point of the highest log-likelihood (`None` without any).
    fn best(&self) -> Option<ProfilePoint> {
        (self.points.iter().copied()).max_by(|a, b| a.log_likelihood.total_cmp(&b.log_likelihood))
    }
}

/// `n` offsets evenly over the bracket, its ends included (at least 3).
pub fn grid_offsets_s(bracket_s: [f64; 2], n: usize) -> Vec<f64> {
    let n = n.max(3);
    let step = (bracket_s[1] - bracket_s[0]) / (n - 1) as f64;
    (0..n).map(|k| bracket_s[0] + step * k as f64).collect()
}

/// The best grid point refined by golden section between its grid neighbours; the best of
/// all the points evaluated.
fn refine_maximum<E>(
    profile: &mut Profile,
    at: &mut dyn FnMut(f64) -> Result<ProfilePoint, E>,
    bracket_s: [f64; 2],
    tolerance_s: f64,
) -> Result<ProfilePoint, E> {
    let Some(grid_best) = profile.best() else {
        return at(0.0);
    };
    let k = profile
        .points
        .partition_point(|p| p.offset_s < grid_best.offset_s);
    let lo = profile
        .points
        .get(k.wrapping_sub(1))
        .map_or(bracket_s[0], |p| p.offset_s);
    let hi = profile
        .points
        .get(k + 1)
        .map_or(bracket_s[1], |p| p.offset_s);
    let mut f = |x: f64| profile.evaluate(at, x).map(|p| p.log_likelihood);
    golden_section_maximum(&mut f, lo, hi, tolerance_s)?;
    Ok(profile.best().unwrap_or(grid_best))
}

/// The most bisections of an interval end (2^-80 of a bracket is past f64's resolution).
const MAX_BISECTIONS: usize = 80;

/// The interval's end on the side of `bracket_end_s`: the outermost evaluated point on that
/// side still at or above `floor` (the maximum itself when none is), then bisection between it
/// and the next point beyond, which is below, to the tolerance, the end interpolated linearly
/// between the two; open at the bracket's end when no point beyond is below. Taking the
/// outermost point makes the interval the hull of the likelihood-ratio set: a set in pieces (a
/// multimodal or rough profile) is reported whole, not by the piece around the maximum.
fn interval_end<E>(
    profile: &mut Profile,
    at: &mut dyn FnMut(f64) -> Result<ProfilePoint, E>,
    best: &ProfilePoint,
    floor: f64,
    bracket_end_s: f64,
    search: &TimeOffsetSearch,
) -> Result<IntervalEnd, E> {
    let outward =
        |p: &&ProfilePoint| (p.offset_s - best.offset_s) * (bracket_end_s - best.offset_s) > 0.0;
    let mut side: Vec<ProfilePoint> = profile.points.iter().filter(outward).copied().collect();
    side.sort_by(|a, b| {
        (a.offset_s - best.offset_s)
            .abs()
            .total_cmp(&(b.offset_s - best.offset_s).abs())
    });
    let last_inside = side.iter().rposition(|p| p.log_likelihood >= floor);
    let mut inside = last_inside.map_or(*best, |k| side[k]);
    let Some(&(mut outside)) = side.get(last_inside.map_or(0, |k| k + 1)) else {
        return Ok(IntervalEnd::AtBracketEnd {
            offset_s: bracket_end_s,
        });
    };
    // Each step halves the gap; MAX_BISECTIONS of them pass f64's resolution, so a tolerance
    // of 0 still ends.
    for _ in 0..MAX_BISECTIONS {
        if (outside.offset_s - inside.offset_s).abs() <= search.tolerance_s {
            break;
        }
        let middle = profile.evaluate(at, 0.5 * (inside.offset_s + outside.offset_s))?;
        match middle.log_likelihood < floor {
            true => outside = middle,
            false => inside = middle,
        }
    }
    Ok(IntervalEnd::Within {
        offset_s: crossing_s(&inside, &outside, floor),
    })
}

/// Grid points within this many nats of the maximum are where the profile's roughness is
/// measured: the region where the threshold is decided (a drop of 1.92 to a few times that),
/// and where a sharply peaked profile has no three points in a row, so that its steep, smooth
/// but not quadratic flanks are not taken for roughness.
pub const ROUGHNESS_BAND: f64 = 10.0;

/// The profile's roughness r, natural log: the robust sd of its ripple from run to run (the
/// discrete decisions of a run, alignment, gating, which fixes start the filter, make L(δ)
/// jump by a nat or two between offsets 50 ms apart on a slow vehicle, as seen on the slow
/// rover of `bench/slow_rover.py`). From the second differences Δ²L of consecutive grid
/// points all within [`ROUGHNESS_BAND`] of `best`: a smooth (locally quadratic) profile has
/// them equal, white ripple of sd r gives them sd √6 r, so r = 1.4826 MAD(Δ²L) / √6; 0 with
/// fewer than three.
pub fn roughness(grid: &[ProfilePoint], best: f64) -> f64 {
    let near = |p: &ProfilePoint| best - p.log_likelihood <= ROUGHNESS_BAND;
    let second: Vec<f64> = grid
        .windows(3)
        .filter(|w| w.iter().all(near))
        .map(|w| w[0].log_likelihood - 2.0 * w[1].log_likelihood + w[2].log_likelihood)
        .collect();
    if second.len() < 3 {
        return 0.0;
    }
    let centre = median(&second);
    let spread: Vec<f64> = second.iter().map(|v| (v - centre).abs()).collect();
    1.4826 * median(&spread) / 6f64.sqrt()
}

/// The median of a non-empty slice (0 for an empty one).
fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => 0.0,
        n if n % 2 == 1 => v[n / 2],
        n => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

/// Where the line through two points crosses `floor` (the inside point's offset when they
/// are level).
fn crossing_s(inside: &ProfilePoint, outside: &ProfilePoint, floor: f64) -> f64 {
    let fall = inside.log_likelihood - outside.log_likelihood;
    match fall > 0.0 {
        true => {
            let w = ((inside.log_likelihood - floor) / fall).clamp(0.0, 1.0);
            inside.offset_s + w * (outside.offset_s - inside.offset_s)
        }
        false => inside.offset_s,
    }
}

/// Flat (open on both sides), multimodal (a point between the ends below `floor`: the set
/// is in pieces), open on one side, or resolved.
fn observability_of(points: &[ProfilePoint], ends: [IntervalEnd; 2], floor: f64) -> Observability {
    let [lo, hi] = ends.map(IntervalEnd::offset_s);
    let gap = points
        .iter()
        .any(|p| p.log_likelihood < floor && p.offset_s > lo && p.offset_s < hi);
    match (ends[0].is_open(), ends[1].is_open(), gap) {
        (true, true, _) => Observability::FlatOverTheBracket,
        (_, _, true) => Observability::Multimodal,
        (true, false, false) | (false, true, false) => Observability::OpenOnOneSide,
        (false, false, false) => Observability::Resolved,
    }
}

/// (upper − lower) / (2 · 1.96) for a closed interval.
fn equivalent_sd_s(lower: IntervalEnd, upper: IntervalEnd) -> Option<f64> {
    (!lower.is_open() && !upper.is_open())
        .then(|| (upper.offset_s() - lower.offset_s()) / (2.0 * 1.959_963_984_540_054))
}

/// The warning for an offset the data do not determine, saying that the run does not apply
/// the maximum at `best_s`.
fn warning_of(observability: Observability, ends: [IntervalEnd; 2], best_s: f64) -> Option<String> {
    let [lo, hi] = ends.map(|e| 1e3 * e.offset_s());
    let why = match observability {
        Observability::Resolved => None,
        Observability::OpenOnOneSide => Some(format!(
            "the IMU-GNSS time offset's 95 % interval reaches the bracket's end ({lo:+.0} to {hi:+.0} ms, open on one side): widen --time-offset-bracket-s or treat the offset as unbounded on that side"
        )),
        Observability::FlatOverTheBracket => Some(format!(
            "the IMU-GNSS time offset is not observable from these data: the likelihood is flat over the whole bracket ({lo:+.0} to {hi:+.0} ms); the vehicle's accelerations and turns are too small against the fixes' noise. Set the offset from the hardware instead"
        )),
        Observability::Multimodal => Some(format!(
            "the IMU-GNSS time offset is not observable from these data: the likelihood has more than one peak within the 95 % threshold over the bracket (the 95 % set spans {lo:+.0} to {hi:+.0} ms). Set the offset from the hardware instead"
        )),
    }?;
    Some(format!(
        "{why}. Not applied: the run keeps the IMU times as given (offset 0 ms), not the likelihood's maximum at {:+.0} ms",
        1e3 * best_s
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bracket_is_positive_and_at_most_ten_seconds() {
        let search = TimeOffsetSearch::with_bracket(0.2).unwrap();
        assert_eq!(search.bracket_s, 0.2);
        assert_eq!(search.grid_points, TimeOffsetSearch::default().grid_points);
        for bad in [0.0, -1.0, 10.5, f64::NAN] {
            let e = TimeOffsetSearch::with_bracket(bad).unwrap_err();
            assert_eq!(e.name, "time_offset_bracket_s", "{bad}");
        }
    }

    /// A Gaussian log-likelihood of mean `mean_s` and sd `sd_s`, with the dispersion `phi`.
    fn gaussian(mean_s: f64, sd_s: f64, phi: f64) -> impl FnMut(f64) -> Result<ProfilePoint, ()> {
        move |x: f64| {
            Ok(ProfilePoint {
                offset_s: x,
                log_likelihood: 50.0 - (x - mean_s).powi(2) / (2.0 * sd_s * sd_s),
                nis_per_dof: phi,
            })
        }
    }

    // Oracle: for L = −(x − μ)²/(2σ²) the set L(μ) − L ≤ 1.92 is μ ± σ √3.84 = μ ± 1.96 σ
    // exactly, and the equivalent sd is σ. Tolerance: the bisection stops at 2 ms and the
    // end is interpolated linearly on a parabola over that span, an error well below 1 ms.
    #[test]
    fn the_interval_of_a_gaussian_likelihood_is_its_1_96_sd_band() {
        let mut at = gaussian(0.083, 0.02, 1.0);
        let e = profile_time_offset(&mut at, &TimeOffsetSearch::default()).unwrap();
        assert!(
            (e.time_offset_s - 0.083).abs() < 0.002,
            "{}",
            e.time_offset_s
        );
        let half = 1.959_963_984_540_054 * 0.02;
        assert!(
            (e.lower.offset_s() - (0.083 - half)).abs() < 1e-3,
            "{:?}",
            e.lower
        );
        assert!(
            (e.upper.offset_s() - (0.083 + half)).abs() < 1e-3,
            "{:?}",
            e.upper
        );
        assert!((e.time_offset_sd_s.unwrap() - 0.02).abs() < 1e-3);
        assert_eq!(e.observability, Observability::Resolved);
        assert_eq!(e.warning, None);
        // Determined: the run applies the estimate.
        assert!(e.applied);
        assert_eq!(e.applied_offset_s, e.time_offset_s);
        // 21 grid runs, about 10 golden-section runs and about 5 per end.
        assert!((30..=50).contains(&e.runs), "{}", e.runs);
        assert_eq!(e.runs, e.profile.len());
    }

    // Oracle: the quasi-likelihood threshold 1.92 φ widens a Gaussian interval by √φ
    // exactly; φ < 1 does not narrow it.
    #[test]
    fn over_dispersion_widens_the_interval_by_its_square_root() {
        let width = |phi: f64| {
            let mut at = gaussian(-0.05, 0.01, phi);
            let e = profile_time_offset(&mut at, &TimeOffsetSearch::default()).unwrap();
            e.upper.offset_s() - e.lower.offset_s()
        };
        let plain = width(1.0);
        assert!(
            (width(4.0) / plain - 2.0).abs() < 0.05,
            "{}",
            width(4.0) / plain
        );
        assert!((width(0.5) - plain).abs() < 1e-12);
    }

    // A likelihood that falls by less than the threshold across the bracket (σ = 2 s against
    // a ±0.5 s bracket: a drop of at most 0.14) is flat: both ends open, a warning, no sd.
    #[test]
    fn a_flat_profile_is_open_on_both_sides_and_warned_of() {
        let mut at = gaussian(0.1, 2.0, 1.0);
        let e = profile_time_offset(&mut at, &TimeOffsetSearch::default()).unwrap();
        assert_eq!(e.lower, IntervalEnd::AtBracketEnd { offset_s: -0.5 });
        assert_eq!(e.upper, IntervalEnd::AtBracketEnd { offset_s: 0.5 });
        assert_eq!(e.observability, Observability::FlatOverTheBracket);
        assert_eq!(e.time_offset_sd_s, None);
        assert!(e.warning.as_ref().unwrap().contains("not observable"));
        // Not determined: the run keeps the times as given, and says so; the maximum (on the
        // Gaussian's side of 0.1 s, so not 0) stays in the estimate for information.
        assert!(!e.applied);
        assert_eq!(e.applied_offset_s, 0.0);
        assert!(e.time_offset_s > 0.05, "{}", e.time_offset_s);
        assert!(e.warning.unwrap().contains("Not applied"));
    }

    // A maximum near one end (μ = 0.45 s, σ = 0.05 s): the interval's upper side passes the
    // bracket's end at 0.5 s, so that side is open and the lower end is μ − 1.96 σ.
    #[test]
    fn an_interval_past_the_bracket_is_open_on_that_side() {
        let mut at = gaussian(0.45, 0.05, 1.0);
        let e = profile_time_offset(&mut at, &TimeOffsetSearch::default()).unwrap();
        assert_eq!(e.upper, IntervalEnd::AtBracketEnd { offset_s: 0.5 });
        assert!(
            (e.lower.offset_s() - (0.45 - 1.96 * 0.05)).abs() < 1e-3,
            "{:?}",
            e.lower
        );
        assert_eq!(e.observability, Observability::OpenOnOneSide);
        assert!(e.warning.unwrap().contains("Not applied"));
        assert!(!e.applied && e.applied_offset_s == 0.0);
    }

    // Two equal peaks 0.6 s apart, each narrow (σ = 20 ms): the second peak's grid points
    // lie within the threshold apart from the first's interval.
    #[test]
    fn two_peaks_are_multimodal() {
        let mut at = |x: f64| {
            let peak = |m: f64| (-(x - m).powi(2) / (2.0 * 0.02 * 0.02)).exp();
            Ok::<_, ()>(ProfilePoint {
                offset_s: x,
                log_likelihood: (peak(-0.3) + peak(0.3) + 1e-9).ln(),
                nis_per_dof: 1.0,
            })
        };
        let e = profile_time_offset(&mut at, &TimeOffsetSearch::default()).unwrap();
        assert_eq!(e.observability, Observability::Multimodal);
        assert!(e.warning.unwrap().contains("more than one peak"));
        assert!(!e.applied && e.applied_offset_s == 0.0);
    }

    // Oracle: a ripple of ±a alternating from grid point to grid point has second
    // differences ±4a, median 0 and median absolute deviation 4a, so r = 1.4826 · 4a / √6;
    // a parabola alone has equal second differences and r = 0 (to rounding); points beyond
    // the band are left out.
    #[test]
    fn roughness_is_the_robust_sd_of_the_ripple() {
        let a = 0.7;
        let point = |k: usize, l: f64| ProfilePoint {
            offset_s: k as f64,
            log_likelihood: l,
            nis_per_dof: 1.0,
        };
        // 20 points: 18 second differences, 9 of each sign, so the median is 0.
        let ripple: Vec<ProfilePoint> = (0..20)
            .map(|k| point(k, if k % 2 == 0 { a } else { -a }))
            .collect();
        let r = roughness(&ripple, a);
        assert!((r - 1.4826 * 4.0 * a / 6f64.sqrt()).abs() < 1e-12, "{r}");
        let parabola: Vec<ProfilePoint> = (0..21)
            .map(|k| point(k, -0.01 * (k as f64 - 10.0).powi(2)))
            .collect();
        assert!(roughness(&parabola, 0.0) < 1e-12);
        let steep: Vec<ProfilePoint> = (0..21)
            .map(|k| point(k, -100.0 * (k as f64 - 10.0).powi(2)))
            .collect();
        assert_eq!(roughness(&steep, 0.0), 0.0);
    }

    // Oracle: NIS 2 + 4 over 3 + 1 degrees of freedom.
    #[test]
    fn dispersion_is_the_nis_per_degree_of_freedom() {
        use crate::nav::measurement::MeasurementKind;
        let record = |kind, nis| InnovationRecord {
            time: crate::time::Timestamp::from_nanos(0),
            kind,
            innovation: [0.0; 3],
            sd: [1.0; 3],
            nis,
            log_likelihood: 0.0,
            gate_scale: 1.0,
            accepted: true,
            forced: false,
        };
        let records = [
            record(MeasurementKind::Position, 2.0),
            record(MeasurementKind::Heading, 4.0),
        ];
        assert!((nis_per_degree_of_freedom(&records) - 1.5).abs() < 1e-15);
        assert_eq!(nis_per_degree_of_freedom(&[]), 1.0);
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
