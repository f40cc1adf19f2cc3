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
//! A point belongs to a term's region when the local slope (central difference of ln σ over
//! ln τ) lies within ±0.15 of the nominal slope; the term is the geometric mean of the
//! per-point readings over its region, and is absent (`None`) when no point qualifies. Bias
//! instability is read at the curve's minimum when the slope changes sign there.

use super::allan::AllanCurve;
use serde::Serialize;

/// Half-width of the slope window that assigns a point to a term.
pub const SLOPE_TOLERANCE: f64 = 0.15;
/// σ_min = √(2 ln 2 / π) B ≈ 0.664 B for flicker (bias-instability) noise.
pub const BIAS_INSTABILITY_FACTOR: f64 = 0.664;

/// One identified term: its value (SI of the curve's data) and the τ range it was read over.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Term {
    /// The coefficient.
    pub value: f64,
    /// Shortest τ used, s.
    pub tau_min_s: f64,
    /// Longest τ used, s.
    pub tau_max_s: f64,
}

/// The five terms; each `None` where the curve shows no region of its slope.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct NoiseTerms {
    /// Quantisation noise Q (rad or m/s for rate data in rad/s or m/s²).
    pub quantization: Option<Term>,
    /// Random walk N: ARW in rad/√s, VRW in m/s/√s.
    pub random_walk: Option<Term>,
    /// Bias instability B (rad/s or m/s²).
    pub bias_instability: Option<Term>,
    /// Rate random walk K (rad/s/√s or m/s²/√s).
    pub rate_random_walk: Option<Term>,
    /// Rate ramp R (rad/s² or m/s³).
    pub rate_ramp: Option<Term>,
}

/// Local slopes d ln σ / d ln τ (one-sided at the ends).
pub fn local_slopes(curve: &AllanCurve) -> Vec<f64> {
    let n = curve.adev.len();
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

/// Geometric mean of `read(τ, σ)` over the points whose slope is near `slope`.
fn term(
    curve: &AllanCurve,
    slopes: &[f64],
    slope: f64,
    read: impl Fn(f64, f64) -> f64,
) -> Option<Term> {
    let chosen: Vec<usize> = (0..slopes.len())
        .filter(|&i| (slopes[i] - slope).abs() <= SLOPE_TOLERANCE && curve.adev[i] > 0.0)
        .collect();
    let (&first, &last) = (chosen.first()?, chosen.last()?);
    let ln_mean = chosen
        .iter()
        .map(|&i| read(curve.tau_s[i], curve.adev[i]).ln())
        .sum::<f64>()
        / chosen.len() as f64;
    Some(Term {
        value: ln_mean.exp(),
        tau_min_s: curve.tau_s[first],
        tau_max_s: curve.tau_s[last],
    })
}

/// Bias instability at an interior minimum of the curve.
fn bias_instability(curve: &AllanCurve) -> Option<Term> {
    let (i, &sigma) = curve
        .adev
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))?;
    let interior = i > 0 && i + 1 < curve.adev.len();
    (interior && sigma > 0.0).then(|| Term {
        value: sigma / BIAS_INSTABILITY_FACTOR,
        tau_min_s: curve.tau_s[i],
        tau_max_s: curve.tau_s[i],
    })
}

/// Reads the five IEEE 952 terms off a curve.
pub fn fit_noise_terms(curve: &AllanCurve) -> NoiseTerms {
    if curve.adev.len() < 2 {
        return NoiseTerms::default();
    }
    let slopes = local_slopes(curve);
    NoiseTerms {
        quantization: term(curve, &slopes, -1.0, |tau, s| s * tau / 3f64.sqrt()),
        random_walk: term(curve, &slopes, -0.5, |tau, s| s * tau.sqrt()),
        bias_instability: bias_instability(curve),
        rate_random_walk: term(curve, &slopes, 0.5, |tau, s| s * (3.0 / tau).sqrt()),
        rate_ramp: term(curve, &slopes, 1.0, |tau, s| s * 2f64.sqrt() / tau),
    }
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
