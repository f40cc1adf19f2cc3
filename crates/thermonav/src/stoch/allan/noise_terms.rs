//! IEEE Std 952 noise terms read off an Allan deviation curve.

use std::f64::consts::{LN_2, PI};

use super::AllanError;
use super::deviation::AllanCurve;
use crate::units;

/// The five terms of IEEE Std 952-1997 Annex C, with the log-log slope of the Allan
/// deviation where each dominates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoiseTermKind {
    /// Quantisation noise Q: sigma^2 = 3 Q^2 / tau^2 (slope -1; sigma(√3) = Q).
    Quantization,
    /// Angle (gyro) or velocity (accelerometer) random walk N: sigma^2 = N^2 / tau
    /// (slope -1/2; sigma(1 s) = N).
    RandomWalk,
    /// Bias instability B: flat floor sigma_min = B sqrt(2 ln 2 / pi) ≈ 0.664 B (slope 0).
    BiasInstability,
    /// Rate random walk K: sigma^2 = K^2 tau / 3 (slope +1/2; sigma(3 s) = K).
    RateRandomWalk,
    /// Rate ramp R: sigma^2 = R^2 tau^2 / 2 (slope +1; sigma(√2 s) = R).
    RateRamp,
}

impl NoiseTermKind {
    /// Log-log slope of the Allan deviation where this term dominates.
    pub fn adev_slope(self) -> f64 {
        match self {
            Self::Quantization => -1.0,
            Self::RandomWalk => -0.5,
            Self::BiasInstability => 0.0,
            Self::RateRandomWalk => 0.5,
            Self::RateRamp => 1.0,
        }
    }

    /// Coefficient from the level C of the fixed-slope line sigma = C tau^slope (tau in s).
    fn coefficient_from_line(self, level: f64) -> f64 {
        match self {
            Self::Quantization => level / 3_f64.sqrt(),
            Self::RandomWalk | Self::BiasInstability => level,
            Self::RateRandomWalk => level * 3_f64.sqrt(),
            Self::RateRamp => level * 2_f64.sqrt(),
        }
    }
}

/// sigma_min / B for the bias-instability floor: sqrt(2 ln 2 / pi) = 0.6643.
pub fn bias_instability_floor_factor() -> f64 {
    (2.0 * LN_2 / PI).sqrt()
}

/// Settings of [`fit_noise_terms`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitSettings {
    /// A segment between neighbouring curve points belongs to a term's region when its
    /// log-log slope is within this of the term's slope; in (0, 0.25] so that regions of
    /// different terms cannot share a segment. Default 0.15.
    pub slope_tolerance: f64,
    /// Fewest curve points a slope region needs for its term to count as identified
    /// (at least 2). Default 3 (two consecutive segments agreeing).
    pub min_points: usize,
}

impl Default for FitSettings {
    fn default() -> Self {
        Self {
            slope_tolerance: 0.15,
            min_points: 3,
        }
    }
}

/// One fitted noise coefficient and the part of the curve it came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TermEstimate {
    /// Coefficient in SI units of the input (see [`NoiseTerms`]).
    pub value: f64,
    /// Smallest tau of the region used, s.
    pub tau_min_s: f64,
    /// Largest tau of the region used, s.
    pub tau_max_s: f64,
    /// Number of curve points in the region.
    pub n_points: usize,
}

/// IEEE Std 952 coefficients of one channel; `None` where the curve shows no region of that
/// slope. Units for an input in rad/s (gyro) or m/s² (accelerometer):
/// Q rad or m/s; N rad/√s or m/s/√s; B rad/s or m/s²; K rad/s/√s or m/s²/√s; R rad/s² or m/s³.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoiseTerms {
    /// Quantisation noise Q.
    pub quantization: Option<TermEstimate>,
    /// Angle or velocity random walk N.
    pub random_walk: Option<TermEstimate>,
    /// Bias instability B (the curve minimum divided by 0.664; region = the flat run around it).
    pub bias_instability: Option<TermEstimate>,
    /// Rate random walk K.
    pub rate_random_walk: Option<TermEstimate>,
    /// Rate ramp R.
    pub rate_ramp: Option<TermEstimate>,
}

/// A gyro's terms in customary units (input in rad/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GyroNoiseReport {
    /// Angle random walk, deg/√h.
    pub arw_deg_per_sqrt_h: Option<f64>,
    /// Bias instability, deg/h.
    pub bias_instability_deg_per_h: Option<f64>,
    /// Rate random walk, deg/h/√h.
    pub rrw_deg_per_h_per_sqrt_h: Option<f64>,
}

/// An accelerometer's terms in customary units (input in m/s²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AccelNoiseReport {
    /// Velocity random walk, m/s/√h.
    pub vrw_m_per_s_per_sqrt_h: Option<f64>,
    /// Bias instability, mg.
    pub bias_instability_mg: Option<f64>,
}

impl NoiseTerms {
    /// The terms of a gyro whose curve was computed from rates in rad/s.
    pub fn gyro_report(&self) -> GyroNoiseReport {
        let value = |t: Option<TermEstimate>, f: fn(f64) -> f64| t.map(|t| f(t.value));
        GyroNoiseReport {
            arw_deg_per_sqrt_h: value(
                self.random_walk,
                units::arw_rad_per_sqrt_s_to_deg_per_sqrt_h,
            ),
            bias_instability_deg_per_h: value(self.bias_instability, units::rad_per_s_to_deg_per_h),
            rrw_deg_per_h_per_sqrt_h: value(
                self.rate_random_walk,
                units::rrw_rad_per_s_per_sqrt_s_to_deg_per_h_per_sqrt_h,
            ),
        }
    }

    /// The terms of an accelerometer whose curve was computed from m/s².
    pub fn accel_report(&self) -> AccelNoiseReport {
        let value = |t: Option<TermEstimate>, f: fn(f64) -> f64| t.map(|t| f(t.value));
        AccelNoiseReport {
            vrw_m_per_s_per_sqrt_h: value(
                self.random_walk,
                units::vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h,
            ),
            bias_instability_mg: value(self.bias_instability, units::m_per_s2_to_mg),
        }
    }
}

/// Fits the IEEE Std 952 terms to an Allan deviation curve (IEEE Std 952-1997 Annex C;
/// El-Sheimy, Hou & Niu 2008).
///
/// 1. Slopes: for each pair of neighbouring points, s = Δ ln sigma / Δ ln tau.
/// 2. Regions: for Q, N, K and R, the longest run of consecutive segments whose slope is
///    within `slope_tolerance` of the term's slope (-1, -1/2, +1/2, +1); ties go to the
///    shorter taus (more averaging terms, less scatter). Fewer than `min_points` points:
///    the term is not identified (`None`).
/// 3. Level: the line of fixed slope through the region's points, least squares in log space
///    with equal weights: ln C = mean(ln sigma_i - slope ln tau_i); the coefficient is that
///    line read at the standard tau (Q at √3 s, N at 1 s, K at 3 s, R at √2 s), even if
///    outside the region. (Weights 1/tau, the inverse variance for a pure power law, were
///    tried: on real gyros they lean on the region's short-tau edge, where sensor filtering
///    flattens the curve, and read the ADIS16405 ARW 7 % low against allantools at 1.28 s.)
/// 4. Bias instability: the curve minimum / sqrt(2 ln 2 / pi), identified only if the minimum
///    is an interior point (the curve rises on both sides); its region is the run of
///    segments next to it with |slope| <= tolerance.
///
/// Assumes the curve comes from unfiltered data (a low-pass filter flattens the short-tau
/// end and biases Q and N). Points with zero deviation are skipped (no log).
///
/// # Errors
/// A malformed curve (lengths differ; tau not finite, positive and increasing; a deviation
/// negative or not finite) or settings out of range.
pub fn fit_noise_terms(
    curve: &AllanCurve,
    settings: &FitSettings,
) -> Result<NoiseTerms, AllanError> {
    validate_curve(curve)?;
    validate_settings(settings)?;
    let slopes = segment_slopes(&curve.tau_s, &curve.adev);
    let line_term = |kind| line_term(curve, &slopes, kind, settings);
    Ok(NoiseTerms {
        quantization: line_term(NoiseTermKind::Quantization),
        random_walk: line_term(NoiseTermKind::RandomWalk),
        bias_instability: bias_instability(curve, &slopes, settings),
        rate_random_walk: line_term(NoiseTermKind::RateRandomWalk),
        rate_ramp: line_term(NoiseTermKind::RateRamp),
    })
}

fn validate_curve(curve: &AllanCurve) -> Result<(), AllanError> {
    let (tau, adev) = (&curve.tau_s, &curve.adev);
    if tau.len() != adev.len() {
        return Err(AllanError::InvalidCurve("tau_s and adev differ in length"));
    }
    if !tau.iter().all(|t| t.is_finite() && *t > 0.0) {
        return Err(AllanError::InvalidCurve("every tau must be finite and > 0"));
    }
    if !tau.windows(2).all(|w| w[1] > w[0]) {
        return Err(AllanError::InvalidCurve("tau must increase strictly"));
    }
    if !adev.iter().all(|a| a.is_finite() && *a >= 0.0) {
        return Err(AllanError::InvalidCurve(
            "every deviation must be finite and >= 0",
        ));
    }
    Ok(())
}

fn validate_settings(settings: &FitSettings) -> Result<(), AllanError> {
    if !(settings.slope_tolerance > 0.0 && settings.slope_tolerance <= 0.25) {
        return Err(AllanError::InvalidFitSetting(
            "slope_tolerance must lie in (0, 0.25]",
        ));
    }
    if settings.min_points < 2 {
        return Err(AllanError::InvalidFitSetting(
            "min_points must be at least 2",
        ));
    }
    Ok(())
}

/// Log-log slope of each segment; `None` where a deviation is zero.
fn segment_slopes(tau: &[f64], adev: &[f64]) -> Vec<Option<f64>> {
    (1..tau.len())
        .map(|i| {
            let positive = adev[i - 1] > 0.0 && adev[i] > 0.0;
            positive.then(|| (adev[i] / adev[i - 1]).ln() / (tau[i] / tau[i - 1]).ln())
        })
        .collect()
}

/// Longest run of consecutive segments satisfying `matches`, as a point range [first, last].
fn longest_run(slopes: &[Option<f64>], matches: impl Fn(f64) -> bool) -> Option<(usize, usize)> {
    let mut best: Option<(usize, usize)> = None;
    let mut start = None;
    for (i, s) in slopes.iter().enumerate() {
        if s.is_some_and(&matches) {
            let first = *start.get_or_insert(i);
            let longer = best.is_none_or(|(b0, b1)| i + 1 - first > b1 - b0);
            if longer {
                best = Some((first, i + 1));
            }
        } else {
            start = None;
        }
    }
    best
}

fn line_term(
    curve: &AllanCurve,
    slopes: &[Option<f64>],
    kind: NoiseTermKind,
    settings: &FitSettings,
) -> Option<TermEstimate> {
    let slope = kind.adev_slope();
    let (first, last) = longest_run(slopes, |s| (s - slope).abs() <= settings.slope_tolerance)?;
    let n_points = last - first + 1;
    if n_points < settings.min_points {
        return None;
    }
    let log_level = mean_log_level(curve, first..=last, slope);
    Some(TermEstimate {
        value: kind.coefficient_from_line(log_level.exp()),
        tau_min_s: curve.tau_s[first],
        tau_max_s: curve.tau_s[last],
        n_points,
    })
}

/// ln C of the line ln sigma = ln C + slope ln tau through the points `range` (least squares
/// with the slope fixed: the mean of ln sigma_i - slope ln tau_i).
fn mean_log_level(curve: &AllanCurve, range: std::ops::RangeInclusive<usize>, slope: f64) -> f64 {
    let n = range.clone().count() as f64;
    range
        .map(|i| curve.adev[i].ln() - slope * curve.tau_s[i].ln())
        .sum::<f64>()
        / n
}

fn bias_instability(
    curve: &AllanCurve,
    slopes: &[Option<f64>],
    settings: &FitSettings,
) -> Option<TermEstimate> {
    let adev = &curve.adev;
    let i_min = (0..adev.len())
        .filter(|&i| adev[i] > 0.0)
        .min_by(|&a, &b| adev[a].total_cmp(&adev[b]))?;
    if i_min == 0 || i_min + 1 == adev.len() {
        return None;
    }
    let flat = |i: usize| slopes[i].is_some_and(|s| s.abs() <= settings.slope_tolerance);
    let first = (0..i_min)
        .rev()
        .take_while(|&i| flat(i))
        .last()
        .unwrap_or(i_min);
    let last = (i_min..slopes.len())
        .take_while(|&i| flat(i))
        .last()
        .map_or(i_min, |i| i + 1);
    Some(TermEstimate {
        value: adev[i_min] / bias_instability_floor_factor(),
        tau_min_s: curve.tau_s[first],
        tau_max_s: curve.tau_s[last],
        n_points: last - first + 1,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve(tau_s: Vec<f64>, adev: Vec<f64>) -> AllanCurve {
        let n = tau_s.len();
        AllanCurve {
            tau_s,
            adev,
            n_terms: vec![100; n],
            averaging_factor: (1..=n).collect(),
            sample_rate_hz: 1.0,
            n_samples: 1000,
            warnings: Vec::new(),
        }
    }

    // Closed form: a curve made of exact IEEE 952 power laws (Q, then N, then K) returns the
    // coefficients that built it; the junction segments have slopes -2.05 and +2.4, in no region.
    #[test]
    fn exact_power_law_pieces_are_recovered() {
        let tau: Vec<f64> = (0..30).map(|k| 2_f64.powi(k - 10)).collect();
        let (q, n, k) = (3e-3, 2e-2, 2e-3);
        // Quantisation region (tau < 2^-6), random walk (middle), rate random walk (tau > 64):
        // piecewise exact, joined so each piece is one power law.
        let sigma = |t: f64| {
            if t < 1.0 / 64.0 {
                3_f64.sqrt() * q / t
            } else if t <= 64.0 {
                n / t.sqrt()
            } else {
                k * (t / 3.0).sqrt()
            }
        };
        let c = curve(tau.clone(), tau.iter().map(|&t| sigma(t)).collect());
        let terms = fit_noise_terms(&c, &FitSettings::default()).unwrap();
        let rel = |a: f64, b: f64| ((a - b) / b).abs();
        assert!(rel(terms.quantization.unwrap().value, q) < 1e-12);
        assert!(rel(terms.random_walk.unwrap().value, n) < 1e-12);
        assert!(rel(terms.rate_random_walk.unwrap().value, k) < 1e-12);
        assert_eq!(terms.random_walk.unwrap().tau_min_s, 1.0 / 64.0);
        assert_eq!(terms.random_walk.unwrap().tau_max_s, 64.0);
        assert_eq!(terms.rate_ramp, None);
    }

    #[test]
    fn zero_curve_identifies_nothing_and_gives_no_nan() {
        let c = curve(vec![1.0, 2.0, 4.0, 8.0], vec![0.0; 4]);
        let terms = fit_noise_terms(&c, &FitSettings::default()).unwrap();
        assert_eq!(terms.random_walk, None);
        assert_eq!(terms.bias_instability, None);
    }

    #[test]
    fn malformed_curves_are_errors() {
        let c = curve(vec![1.0, 1.0], vec![1.0, 1.0]);
        assert!(fit_noise_terms(&c, &FitSettings::default()).is_err());
        let c = curve(vec![1.0, 2.0], vec![1.0, f64::NAN]);
        assert!(fit_noise_terms(&c, &FitSettings::default()).is_err());
    }

    #[test]
    fn floor_factor_is_0_664() {
        assert!((bias_instability_floor_factor() - 0.664_282_5).abs() < 1e-7);
    }
}
