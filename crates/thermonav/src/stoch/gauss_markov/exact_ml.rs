//! Exact maximum-likelihood Gauss-Markov fit on irregular sampling times.

use std::f64::consts::{LN_10, TAU};

use serde::{Deserialize, Serialize};

use super::GaussMarkovError;
use super::intervals::{SampleIntervals, require_finite, require_samples};
use super::model::{ConfidenceLevel, CorrelationTimeInterval, GaussMarkov, UpperBound};
use super::search::{Peak, find_crossing, golden_section_max};

/// Fewest samples [`fit_gauss_markov_exact_ml`] accepts (two parameters plus the mean).
pub const MIN_ML_SAMPLES: usize = 3;

/// The search for `Tc` starts this factor below the shortest sampling interval (where every
/// `exp(-dt_k/Tc) <= exp(-10)`: white noise for all practical purposes)...
const SEARCH_BELOW_MIN_DT: f64 = 10.0;
/// ...and ends this factor above the span of the series (where the process is a random walk
/// over the record: `1 - exp(-span/Tc) ~ 1e-4`).
const SEARCH_ABOVE_SPAN: f64 = 1e4;
/// `Tc` is never searched above this multiple of the shortest interval, so that
/// `dt_k/Tc` cannot underflow.
const MAX_TC_OVER_MIN_DT: f64 = 1e250;
/// Coarse grid density over `ln Tc`, points per decade.
const GRID_POINTS_PER_DECADE: f64 = 8.0;
/// Final width of the bracket of `ln Tc` (absolute); the argmax itself is limited to about
/// `sqrt(eps |l| / I)` by the flatness of the likelihood at its peak.
const LN_TC_TOLERANCE: f64 = 1e-12;

/// How the mean of the series is treated by the likelihood.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum MeanModel {
    /// The series is zero-mean (a known bias was removed by the caller); no mean is fitted.
    Zero,
    /// A constant mean `mu` is a third parameter, estimated jointly by maximum likelihood: for
    /// each `Tc` its generalised-least-squares value is profiled out in closed form (more
    /// accurate than subtracting the sample mean first, which biases `Tc` low when `Tc` is not
    /// small against the span). Beyond the span of the record the profile falls like
    /// `-(1/2) ln Tc` (the mean absorbs the start value, whose stationary density `1/sigma`
    /// still counts), so even random-walk data get a finite likelihood-ratio upper bound,
    /// some 50 times the scale where that decline starts: use [`MeanModel::Restricted`] when
    /// `Tc` may exceed the record.
    Estimated,
    /// The mean is integrated out (restricted maximum likelihood, REML; Patterson & Thompson
    /// 1971, Harville 1977): the likelihood of the contrasts free of `mu`,
    /// `l_R = -(n-1)/2 ln(2 pi sigma^2) - (1/2) ln|R| - (1/2) ln(1' R^-1 1) - Q/(2 sigma^2)`,
    /// with `R` the correlation matrix, `Q` the generalised residual sum of squares at the GLS
    /// mean and `1' R^-1 1 = 1 + sum (1 - phi_k)/(1 + phi_k)`; `sigma^2 = Q/(n-1)`. It counts
    /// the degree of freedom spent on the mean, so its profile tends to a constant (the random
    /// walk) as `Tc -> infinity`: long correlation times get an unbounded interval or the
    /// [`ExactMlOutcome::RandomWalkLike`] answer, and `Tc` is less biased low for short
    /// records. The reported mean is the GLS mean at the estimate, the reported
    /// log-likelihood the restricted one (not comparable with the other two models').
    Restricted,
}

/// A maximum-likelihood Gauss-Markov model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ExactMlFit {
    /// The fitted model (`sigma^2` with divisor `n`, or `n - 1` under
    /// [`MeanModel::Restricted`]).
    pub model: GaussMarkov,
    /// The fitted mean (0 under [`MeanModel::Zero`]).
    pub mean: f64,
    /// Likelihood-ratio interval of `Tc`.
    pub correlation_time_interval: CorrelationTimeInterval,
    /// The maximised log-likelihood, in the units of the values (natural log).
    pub log_likelihood: f64,
}

/// The answer of [`fit_gauss_markov_exact_ml`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum ExactMlOutcome {
    /// An interior maximum: a Gauss-Markov model.
    Fitted(ExactMlFit),
    /// The likelihood still increases at the longest correlation time searched
    /// (`1e4 x span`): the data look like a random walk or a drift, not a stationary process.
    RandomWalkLike {
        /// The longest correlation time searched, s.
        searched_up_to_s: f64,
    },
    /// The likelihood is highest at the shortest correlation time searched (a tenth of the
    /// shortest interval): no positive correlation between neighbours, white noise.
    WhiteNoiseLike {
        /// The shortest correlation time searched, s.
        searched_down_to_s: f64,
    },
}

/// The exact Gaussian log-likelihood of `values` at the sampling `intervals` under `model`
/// shifted by `mean`:
/// `x_0 - mu ~ N(0, sigma^2)` (stationary start) and
/// `x_k - mu | x_{k-1} ~ N(phi_k (x_{k-1} - mu), sigma^2 (1 - phi_k^2))` with
/// `phi_k = exp(-dt_k/Tc)` for each step's own `dt_k` (eqs. 3-4). This Markov factorisation
/// equals the multivariate normal density with covariance `sigma^2 exp(-|t_i - t_j|/Tc)`.
///
/// # Errors
/// [`GaussMarkovError::LengthMismatch`], [`GaussMarkovError::NonFinite`] for a bad value or
/// mean, [`GaussMarkovError::OutOfRange`] when the log-likelihood is not representable (values
/// enormous against `sigma`, or `Tc` so long against an interval that `1 - phi^2` underflows).
pub fn gauss_markov_log_likelihood(
    model: &GaussMarkov,
    mean: f64,
    intervals: &SampleIntervals,
    values: &[f64],
) -> Result<f64, GaussMarkovError> {
    require_matching_values(intervals, values, 1)?;
    require_finite("mean", &[mean])?;
    let standardised: Vec<f64> = values.iter().map(|x| (x - mean) / model.sigma()).collect();
    let mut transitions = Transitions::default();
    transitions.fill(intervals.dt_s(), model.correlation_time_s());
    let n = values.len() as f64;
    let log_likelihood = innovation_sums(&standardised, 0.0, &transitions)
        .map(|sums| -0.5 * (n * TAU.ln() + sums.weighted_squares + sums.ln_variances))
        .map(|standard| standard - n * model.sigma().ln())
        .filter(|value| value.is_finite());
    log_likelihood.ok_or(GaussMarkovError::OutOfRange {
        quantity: "log-likelihood",
        value: f64::NEG_INFINITY,
    })
}

/// Exact maximum-likelihood fit of a first-order Gauss-Markov model to a series sampled at
/// arbitrary (irregular) times.
///
/// Likelihood: as [`gauss_markov_log_likelihood`], each step with its own `dt_k`, so jitter,
/// gaps and rate changes are modelled rather than averaged into a nominal `dt` (the bias of an
/// AR(1) fit with a nominal interval). For a fixed `Tc` the mean (unless [`MeanModel::Zero`])
/// and `sigma^2` have closed forms and are profiled out:
/// `mu = [x_0 + sum (x_k - phi_k x_{k-1})/(1 + phi_k)] / [1 + sum (1 - phi_k)/(1 + phi_k)]`,
/// `sigma^2 = [(x_0 - mu)^2 + sum e_k^2 / (1 - phi_k^2)] / n` (`n - 1` under
/// [`MeanModel::Restricted`]), `e_k = (x_k - mu) - phi_k (x_{k-1} - mu)`.
///
/// Search: the profile log-likelihood of `ln Tc` is evaluated on a grid of 8 points per decade
/// from a tenth of the shortest interval to `1e4 x span`; its best grid point is refined
/// between its neighbours by a bracketed root search on the analytic derivative (to 1e-12 in
/// `ln Tc`; golden section on the values if the derivative does not change sign). A maximum on
/// either end of the grid is reported as [`ExactMlOutcome::WhiteNoiseLike`] or
/// [`ExactMlOutcome::RandomWalkLike`].
///
/// Interval: likelihood ratio, `{Tc : l_p(Tc) >= l_p(Tc_hat) - chi2_1(level)/2}` (a drop of
/// 1.92 at 95 %), each end found by a bracketed root search. It is preferred over a Wald
/// interval from the observed information of `ln Tc` because the profile is skewed in `Tc`
/// (long correlation times are always less well determined than short ones) and because it
/// extends naturally to the unbounded case: when the profile does not drop by the threshold
/// before `1e4 x span`, the upper end is [`UpperBound::Unbounded`]; when it does not drop
/// before the grid's lower end, the lower end is 0.
///
/// Reference and peers: the exact likelihood of a continuous-time AR(1) (Ornstein-Uhlenbeck)
/// process observed at irregular times (Jones 1981, "Fitting a continuous time autoregression
/// to discrete data"); it is the Gaussian-process likelihood with the exponential kernel
/// `sigma^2 exp(-|t_i - t_j|/Tc)` that `celerite`, `george` or scikit-learn's
/// `GaussianProcessRegressor(Matern(nu=0.5))` maximise with dense or semiseparable solvers;
/// the Markov factorisation here is O(n) per evaluation.
///
/// Numerics: the values are shifted by their sample mean (for an estimated mean) and scaled
/// to unit RMS before the search, so results do not depend on units; the reported quantities
/// are mapped back.
///
/// # Errors
/// [`GaussMarkovError::LengthMismatch`], [`GaussMarkovError::TooShort`] (fewer than
/// [`MIN_ML_SAMPLES`]), [`GaussMarkovError::NonFinite`], [`GaussMarkovError::ZeroVariance`],
/// and [`GaussMarkovError::OutOfRange`] when the fitted `sigma^2` is not representable.
pub fn fit_gauss_markov_exact_ml(
    intervals: &SampleIntervals,
    values: &[f64],
    mean_model: MeanModel,
    level: ConfidenceLevel,
) -> Result<ExactMlOutcome, GaussMarkovError> {
    require_matching_values(intervals, values, MIN_ML_SAMPLES)?;
    let normalised = NormalisedSeries::new(values, mean_model)?;
    let mut profile = ProfileLikelihood::new(intervals.dt_s(), &normalised.values, mean_model);
    let grid = LnTcGrid::new(intervals);
    let grid_values: Vec<f64> = grid.points.iter().map(|&t| profile.at(t)).collect();
    let best = argmax(&grid_values);
    if best == 0 {
        return Ok(ExactMlOutcome::WhiteNoiseLike {
            searched_down_to_s: grid.points[0].exp(),
        });
    }
    if best + 1 == grid.points.len() {
        return Ok(ExactMlOutcome::RandomWalkLike {
            searched_up_to_s: grid.points[best].exp(),
        });
    }
    let peak = refine_peak(&mut profile, grid.points[best - 1], grid.points[best + 1]);
    let interval = likelihood_ratio_interval(&mut profile, &grid, &grid_values, best, peak, level);
    normalised
        .fit_at(&mut profile, peak, interval)
        .map(ExactMlOutcome::Fitted)
}

fn require_matching_values(
    intervals: &SampleIntervals,
    values: &[f64],
    needed: usize,
) -> Result<(), GaussMarkovError> {
    if values.len() != intervals.sample_count() {
        return Err(GaussMarkovError::LengthMismatch {
            times: intervals.sample_count(),
            values: values.len(),
        });
    }
    require_samples(values.len(), needed)?;
    require_finite("values", values)
}

/// Index of the largest element (the first one on ties); `-inf` entries never win over finite.
fn argmax(values: &[f64]) -> usize {
    let mut best = 0;
    for (k, &value) in values.iter().enumerate() {
        if value > values[best] {
            best = k;
        }
    }
    best
}

/// The peak of the profile between the grid neighbours `left` and `right` of the best grid
/// point: the zero of its analytic slope, by a bracketed root search. Function values alone
/// locate a flat peak only to about `sqrt(eps |l| / I)` (~1e-7 in `ln Tc`); the slope's zero
/// is located to `LN_TC_TOLERANCE`. Golden section on the values is the fallback when the slope does not
/// change sign across the bracket.
fn refine_peak(profile: &mut ProfileLikelihood, left: f64, right: f64) -> Peak {
    if profile.slope(left) > 0.0 && profile.slope(right) < 0.0 {
        let x = find_crossing(|t| profile.slope(t), left, right, 0.0, LN_TC_TOLERANCE);
        Peak {
            x,
            value: profile.at(x),
        }
    } else {
        golden_section_max(|t| profile.at(t), left, right, LN_TC_TOLERANCE)
    }
}

/// The likelihood-ratio interval around the peak, in seconds.
fn likelihood_ratio_interval(
    profile: &mut ProfileLikelihood,
    grid: &LnTcGrid,
    grid_values: &[f64],
    best: usize,
    peak: Peak,
    level: ConfidenceLevel,
) -> CorrelationTimeInterval {
    let threshold = peak.value - 0.5 * level.chi_square_1dof_quantile();
    let mut crossing = |inside: f64, outside: f64| {
        find_crossing(
            |t| profile.at(t),
            inside,
            outside,
            threshold,
            LN_TC_TOLERANCE,
        )
        .exp()
    };
    let above = (best + 1..grid.points.len()).find(|&j| grid_values[j] < threshold);
    let upper = match above {
        Some(j) => UpperBound::Finite(crossing(grid.points[j - 1].max(peak.x), grid.points[j])),
        None => UpperBound::Unbounded,
    };
    let below = (0..best).rev().find(|&j| grid_values[j] < threshold);
    let lower_s = match below {
        Some(j) => crossing(grid.points[j + 1].min(peak.x), grid.points[j]),
        None => 0.0,
    };
    CorrelationTimeInterval {
        lower_s,
        upper,
        level,
    }
}

/// The coarse search grid over `ln Tc`.
struct LnTcGrid {
    points: Vec<f64>,
}

impl LnTcGrid {
    fn new(intervals: &SampleIntervals) -> Self {
        // Both exist: the fit needs at least MIN_ML_SAMPLES samples.
        let min_dt_s = intervals.min_dt_s().unwrap_or(1.0);
        let lowest = (min_dt_s / SEARCH_BELOW_MIN_DT).ln();
        let highest = (intervals.span_s() * SEARCH_ABOVE_SPAN)
            .min(min_dt_s * MAX_TC_OVER_MIN_DT)
            .ln();
        let steps = ((highest - lowest) / LN_10 * GRID_POINTS_PER_DECADE).ceil() as usize;
        let step = (highest - lowest) / steps as f64;
        let points = (0..=steps).map(|i| lowest + i as f64 * step).collect();
        Self { points }
    }
}

/// The values shifted and scaled to unit RMS, and the map back to the caller's units.
struct NormalisedSeries {
    values: Vec<f64>,
    offset: f64,
    scale: f64,
}

impl NormalisedSeries {
    /// Divides by the largest magnitude first so that no sum can overflow.
    fn new(values: &[f64], mean_model: MeanModel) -> Result<Self, GaussMarkovError> {
        let about = match mean_model {
            MeanModel::Zero => "zero",
            MeanModel::Estimated | MeanModel::Restricted => "their mean",
        };
        let magnitude = values.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        if magnitude == 0.0 {
            return Err(GaussMarkovError::ZeroVariance { about });
        }
        let unit: Vec<f64> = values.iter().map(|x| x / magnitude).collect();
        let unit_offset = match mean_model {
            MeanModel::Zero => 0.0,
            MeanModel::Estimated | MeanModel::Restricted => {
                unit.iter().sum::<f64>() / unit.len() as f64
            }
        };
        let mean_square =
            unit.iter().map(|u| (u - unit_offset).powi(2)).sum::<f64>() / unit.len() as f64;
        if mean_square <= 0.0 {
            return Err(GaussMarkovError::ZeroVariance { about });
        }
        let unit_scale = mean_square.sqrt();
        Ok(Self {
            values: unit
                .iter()
                .map(|u| (u - unit_offset) / unit_scale)
                .collect(),
            offset: unit_offset * magnitude,
            scale: unit_scale * magnitude,
        })
    }

    /// The fit at the peak, mapped back to the caller's units.
    fn fit_at(
        &self,
        profile: &mut ProfileLikelihood,
        peak: Peak,
        interval: CorrelationTimeInterval,
    ) -> Result<ExactMlFit, GaussMarkovError> {
        let at_peak = profile.parameters(peak.x);
        let sigma = at_peak.variance.sqrt() * self.scale;
        // Rescaling the data by s shifts the log-likelihood by -(degrees of freedom) ln s.
        let degrees = profile.degrees_of_freedom();
        Ok(ExactMlFit {
            model: GaussMarkov::new(peak.x.exp(), sigma)?,
            mean: self.offset + at_peak.mean * self.scale,
            correlation_time_interval: interval,
            log_likelihood: peak.value - degrees * self.scale.ln(),
        })
    }
}

/// Per-step transition terms `phi_k` and `1 - phi_k` at one correlation time.
#[derive(Default)]
struct Transitions {
    phi: Vec<f64>,
    one_minus_phi: Vec<f64>,
}

impl Transitions {
    fn fill(&mut self, dt_s: &[f64], correlation_time_s: f64) {
        self.phi.clear();
        self.one_minus_phi.clear();
        for &dt in dt_s {
            // One transcendental per step: 1 - phi from expm1 where phi is near 1 (no
            // cancellation), phi from exp where it is small (no loss of its relative accuracy).
            let x = dt / correlation_time_s;
            let (phi, one_minus_phi) = if x < 1.0 {
                let one_minus_phi = -(-x).exp_m1();
                (1.0 - one_minus_phi, one_minus_phi)
            } else {
                let phi = (-x).exp();
                (phi, 1.0 - phi)
            };
            self.phi.push(phi);
            self.one_minus_phi.push(one_minus_phi);
        }
    }
}

/// `sum e_k^2 / v_k` (with the start term `(x_0 - mu)^2 / 1`) and `sum ln v_k`, in units of
/// `sigma^2`, where `v_k = 1 - phi_k^2`.
struct InnovationSums {
    weighted_squares: f64,
    ln_variances: f64,
}

/// The sums for `values` about `mean`; `None` when some `1 - phi_k^2` underflows to 0 or a sum
/// is not finite.
fn innovation_sums(values: &[f64], mean: f64, transitions: &Transitions) -> Option<InnovationSums> {
    let start = values[0] - mean;
    let mut sums = InnovationSums {
        weighted_squares: start * start,
        ln_variances: 0.0,
    };
    for (k, pair) in values.windows(2).enumerate() {
        let phi = transitions.phi[k];
        let variance = transitions.one_minus_phi[k] * (1.0 + phi);
        if variance <= 0.0 {
            return None;
        }
        let innovation = (pair[1] - mean) - phi * (pair[0] - mean);
        sums.weighted_squares += innovation * innovation / variance;
        sums.ln_variances += variance.ln();
    }
    let finite = sums.weighted_squares.is_finite() && sums.ln_variances.is_finite();
    finite.then_some(sums)
}

/// The generalised-least-squares mean for the current transitions (see
/// [`fit_gauss_markov_exact_ml`]) and its information `1' R^-1 1`.
struct GlsMean {
    mean: f64,
    information: f64,
}

fn gls_mean(values: &[f64], transitions: &Transitions) -> GlsMean {
    let mut numerator = values[0];
    let mut denominator = 1.0;
    for (k, pair) in values.windows(2).enumerate() {
        let one_plus_phi = 1.0 + transitions.phi[k];
        numerator += (pair[1] - transitions.phi[k] * pair[0]) / one_plus_phi;
        denominator += transitions.one_minus_phi[k] / one_plus_phi;
    }
    GlsMean {
        mean: numerator / denominator,
        information: denominator,
    }
}

/// The profiled parameters at one `Tc`, in normalised units.
struct ProfiledParameters {
    mean: f64,
    /// `1' R^-1 1` (1 when the mean is not estimated).
    mean_information: f64,
    variance: f64,
    log_likelihood: f64,
}

/// The profile log-likelihood of `ln Tc` of a normalised series.
struct ProfileLikelihood<'a> {
    dt_s: &'a [f64],
    values: &'a [f64],
    mean_model: MeanModel,
    transitions: Transitions,
}

impl<'a> ProfileLikelihood<'a> {
    fn new(dt_s: &'a [f64], values: &'a [f64], mean_model: MeanModel) -> Self {
        Self {
            dt_s,
            values,
            mean_model,
            transitions: Transitions::default(),
        }
    }

    /// Observations left for `sigma^2`: `n`, or `n - 1` when the mean is integrated out.
    fn degrees_of_freedom(&self) -> f64 {
        match self.mean_model {
            MeanModel::Restricted => (self.values.len() - 1) as f64,
            MeanModel::Zero | MeanModel::Estimated => self.values.len() as f64,
        }
    }

    /// The profile log-likelihood at `ln_tc`; `-inf` where it is not representable.
    fn at(&mut self, ln_tc: f64) -> f64 {
        self.parameters(ln_tc).log_likelihood
    }

    /// The derivative of the profile log-likelihood with respect to `ln Tc`. By the envelope
    /// theorem it is the partial derivative at the profiled mean and variance:
    /// `sum phi_k phi'_k / v_k + (1/sigma^2) sum [e_k y_{k-1} phi'_k / v_k -
    /// e_k^2 phi_k phi'_k / v_k^2]` with `y = x - mu`, `v_k = 1 - phi_k^2` and
    /// `phi'_k = d phi_k / d ln Tc = phi_k dt_k / Tc`; the restricted likelihood adds
    /// `-(1/2) d ln(1' R^-1 1) / d ln Tc = sum phi'_k / (1 + phi_k)^2 / (1' R^-1 1)`. NaN where
    /// the profile is not representable (callers only compare it with 0).
    fn slope(&mut self, ln_tc: f64) -> f64 {
        let profiled = self.parameters(ln_tc);
        let correlation_time_s = ln_tc.exp();
        let (mut determinant_part, mut residual_part, mut mean_part) = (0.0, 0.0, 0.0);
        for (k, pair) in self.values.windows(2).enumerate() {
            let phi = self.transitions.phi[k];
            let variance = self.transitions.one_minus_phi[k] * (1.0 + phi);
            let phi_slope = phi * self.dt_s[k] / correlation_time_s;
            let previous = pair[0] - profiled.mean;
            let innovation = (pair[1] - profiled.mean) - phi * previous;
            determinant_part += phi * phi_slope / variance;
            mean_part += phi_slope / ((1.0 + phi) * (1.0 + phi));
            residual_part +=
                innovation * phi_slope / variance * (previous - innovation * phi / variance);
        }
        let mean_part = match self.mean_model {
            MeanModel::Restricted => mean_part / profiled.mean_information,
            MeanModel::Zero | MeanModel::Estimated => 0.0,
        };
        determinant_part + residual_part / profiled.variance + mean_part
    }

    fn parameters(&mut self, ln_tc: f64) -> ProfiledParameters {
        self.transitions.fill(self.dt_s, ln_tc.exp());
        let gls = match self.mean_model {
            MeanModel::Zero => GlsMean {
                mean: 0.0,
                information: 1.0,
            },
            MeanModel::Estimated | MeanModel::Restricted => {
                gls_mean(self.values, &self.transitions)
            }
        };
        let mean_term = match self.mean_model {
            MeanModel::Restricted => gls.information.ln(),
            MeanModel::Zero | MeanModel::Estimated => 0.0,
        };
        let degrees = self.degrees_of_freedom();
        let sums = innovation_sums(self.values, gls.mean, &self.transitions);
        let variance = sums.as_ref().map_or(0.0, |s| s.weighted_squares / degrees);
        let log_likelihood = match sums {
            Some(s) if variance > 0.0 => {
                -0.5 * (degrees * (TAU.ln() + 1.0 + variance.ln()) + s.ln_variances + mean_term)
            }
            _ => f64::NEG_INFINITY,
        };
        ProfiledParameters {
            mean: gls.mean,
            mean_information: gls.information,
            variance,
            log_likelihood,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A short irregular series (deterministic, no RNG needed for a derivative check).
    fn series() -> (Vec<f64>, Vec<f64>) {
        let dt_s = (0..59)
            .map(|k| 0.004 + 0.003 * ((k * 7 % 5) as f64))
            .collect();
        let values = (0..60)
            .map(|k| (k as f64 * 0.37).sin() + 0.5 * (k as f64 * 1.3).cos() + 0.2)
            .collect();
        (dt_s, values)
    }

    #[test]
    fn analytic_slope_matches_a_central_difference_of_the_profile() {
        // Central difference with h = 1e-4: truncation ~h^2 |third derivative| ~ 1e-8,
        // rounding ~eps |l| / h ~ 1e-10; 1e-6 relative (absolute near a zero slope).
        let (dt_s, values) = series();
        for mean_model in [MeanModel::Zero, MeanModel::Estimated, MeanModel::Restricted] {
            let mut profile = ProfileLikelihood::new(&dt_s, &values, mean_model);
            for ln_tc in [-6.0, -4.5, -3.0, -1.0, 2.0] {
                let h = 1e-4;
                let numeric = (profile.at(ln_tc + h) - profile.at(ln_tc - h)) / (2.0 * h);
                let analytic = profile.slope(ln_tc);
                let scale = numeric.abs().max(1.0);
                assert!(
                    (analytic - numeric).abs() < 1e-6 * scale,
                    "{mean_model:?} ln Tc {ln_tc}: {analytic} vs {numeric}"
                );
            }
        }
    }
}
