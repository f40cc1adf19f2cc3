//! Chi-square confidence intervals of the overlapping Allan deviation.

use statrs::distribution::{ChiSquared, ContinuousCDF};

use super::edf::edf_overlapping_adev;
use super::noise_id::identify_noise_at_factors;
use super::{AllanCurve, AllanError, AllanIntervals};

/// erf(1/√2) = 0.682689...: the probability within ±1 sigma of a normal distribution.
///
/// Stable32 labels this "Confidence Factor = 0.683"; its limits agree with this value, not
/// with 0.683 itself (the tail probabilities implied by its printed limits are 0.1586).
pub const ONE_SIGMA_CONFIDENCE: f64 = 0.682_689_492_137_085_9;

/// The confidence level used unless told otherwise: 0.683, as Stable32 prints its "1-sigma"
/// confidence factor (so that a user comparing with it types the same number).
pub const DEFAULT_CONFIDENCE: f64 = 0.683;

/// How the chi-square quantiles are computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ChiSquareQuantile {
    /// The exact inverse of the chi-square distribution function (statrs), as scipy's
    /// `chi2.ppf` and allantools use.
    #[default]
    Exact,
    /// Stable32 1.60's computation, to reproduce its limits digit for digit: exact for
    /// edf <= 100; above, Abramowitz & Stegun 26.4.17 (Wilson-Hilferty)
    /// chi2_p = edf (1 - 2/(9 edf) + x_p sqrt(2/(9 edf)))^3 with x_p from A&S 26.2.22 with
    /// Stable32's coefficient 0.27601 where A&S print 0.27061 (the intervals come out about
    /// 0.5 % narrower at edf ≈ 100, less above).
    Stable32,
}

/// Settings of [`confidence_intervals_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CiSettings {
    /// Two-sided confidence level in (0, 1); default [`ONE_SIGMA_CONFIDENCE`] ("1-sigma").
    pub level: f64,
    /// Chi-square quantile computation; default exact.
    pub quantile: ChiSquareQuantile,
}

impl CiSettings {
    /// Checks the settings: the level must lie strictly between 0 and 1.
    ///
    /// # Errors
    /// [`AllanError::InvalidConfidenceLevel`] for a level outside (0, 1) or NaN.
    pub fn validate(&self) -> Result<(), AllanError> {
        validate_level(self.level)
    }
}

impl Default for CiSettings {
    fn default() -> Self {
        Self {
            level: ONE_SIGMA_CONFIDENCE,
            quantile: ChiSquareQuantile::Exact,
        }
    }
}

/// Confidence limits at `level` (0 < level < 1; anything else means
/// [`ONE_SIGMA_CONFIDENCE`]) for the curve of `y`, with exact chi-square quantiles: see
/// [`confidence_intervals_with`].
pub fn confidence_intervals(y: &[f64], curve: &AllanCurve, level: f64) -> AllanIntervals {
    let settings = CiSettings {
        level: valid_level_or_one_sigma(level),
        quantile: ChiSquareQuantile::Exact,
    };
    confidence_intervals_with(y, curve, &settings)
}

fn valid_level_or_one_sigma(level: f64) -> f64 {
    if level > 0.0 && level < 1.0 {
        level
    } else {
        ONE_SIGMA_CONFIDENCE
    }
}

/// Confidence limits for every point of `curve`, computed from the series `y` it came from.
///
/// At each averaging factor m: identify the dominant noise ([`super::identify_noise`], Stable32's
/// rule), compute Greenhall's EDF for N + 1 phase points ([`edf_overlapping_adev`]), and bound
/// the variance by the chi-square distribution (NIST SP 1065 eq. 45):
/// edf σ²/χ²(1 − q, edf) ≤ σ²_true ≤ edf σ²/χ²(q, edf), q = (1 − level)/2.
///
/// With `CiSettings { level: ONE_SIGMA_CONFIDENCE, quantile: ChiSquareQuantile::Stable32 }`
/// this reproduces Stable32 1.60's OADEV MinSigma/MaxSigma (see the integration tests for
/// the agreement). Where no noise type exists (the m-averages are constant, so the
/// deviation is zero) white FM (α = 0) is assumed. A level outside (0, 1) means
/// [`ONE_SIGMA_CONFIDENCE`]; a length of `y` other than the curve's gives limits equal to the
/// deviation (no interval can be computed from another series).
pub fn confidence_intervals_with(
    y: &[f64],
    curve: &AllanCurve,
    settings: &CiSettings,
) -> AllanIntervals {
    let settings = CiSettings {
        level: valid_level_or_one_sigma(settings.level),
        quantile: settings.quantile,
    };
    let matches = y.len() == curve.n_samples;
    let alpha: Vec<i32> = match matches {
        true => identify_noise_at_factors(y, &curve.averaging_factor)
            .iter()
            .map(|id| id.map_or(0, |id| id.noise.alpha()))
            .collect(),
        false => vec![0; curve.averaging_factor.len()],
    };
    if matches {
        return intervals_for_noise(curve, alpha, &settings);
    }
    let edf = edf_of(curve, &alpha);
    AllanIntervals {
        level: settings.level,
        alpha,
        edf,
        low: curve.adev.clone(),
        high: curve.adev.clone(),
    }
}

/// Greenhall's EDF at every point of `curve` for the noise exponents `alpha`.
fn edf_of(curve: &AllanCurve, alpha: &[i32]) -> Vec<f64> {
    curve
        .averaging_factor
        .iter()
        .zip(alpha)
        .map(|(&m, &a)| edf_overlapping_adev(curve.n_samples + 1, m, a))
        .collect()
}

/// Confidence limits for every point of `curve` given the noise exponent α at each point
/// (already identified, e.g. by a streaming pass): EDF and chi-square bounds as in
/// [`confidence_intervals_with`]. A level outside (0, 1) means [`ONE_SIGMA_CONFIDENCE`].
pub fn intervals_for_noise(
    curve: &AllanCurve,
    alpha: Vec<i32>,
    settings: &CiSettings,
) -> AllanIntervals {
    let settings = CiSettings {
        level: valid_level_or_one_sigma(settings.level),
        quantile: settings.quantile,
    };
    let edf = edf_of(curve, &alpha);
    let (low, high) = curve
        .adev
        .iter()
        .zip(&edf)
        .map(|(&sigma, &e)| interval_from_edf(sigma, e, &settings).unwrap_or((sigma, sigma)))
        .unzip();
    AllanIntervals {
        level: settings.level,
        alpha,
        edf,
        low,
        high,
    }
}

fn validate_level(level: f64) -> Result<(), AllanError> {
    if level > 0.0 && level < 1.0 {
        Ok(())
    } else {
        Err(AllanError::InvalidConfidenceLevel(level))
    }
}

/// Chi-square bounds (lower, upper) of a deviation `adev` with `edf` degrees of freedom:
/// adev √(edf/χ²(1 − q, edf)) and adev √(edf/χ²(q, edf)), q = (1 − level)/2.
///
/// # Errors
/// A level outside (0, 1) or an edf that is not finite and positive.
pub fn interval_from_edf(
    adev: f64,
    edf: f64,
    settings: &CiSettings,
) -> Result<(f64, f64), AllanError> {
    validate_level(settings.level)?;
    if !(edf.is_finite() && edf > 0.0) {
        return Err(AllanError::InvalidEdf(edf));
    }
    let tail = (1.0 - settings.level) / 2.0;
    let chi2_high = chi_square_quantile(1.0 - tail, edf, settings.quantile)?;
    let chi2_low = chi_square_quantile(tail, edf, settings.quantile)?;
    Ok((
        adev * (edf / chi2_high).sqrt(),
        adev * (edf / chi2_low).sqrt(),
    ))
}

/// Quantile chi2(p, edf) for lower-tail probability p by the chosen method.
///
/// # Errors
/// p outside (0, 1) (reported as [`AllanError::InvalidConfidenceLevel`]) or an edf that is
/// not finite and positive.
pub fn chi_square_quantile(p: f64, edf: f64, method: ChiSquareQuantile) -> Result<f64, AllanError> {
    validate_level(p)?;
    let distribution = ChiSquared::new(edf).map_err(|_| AllanError::InvalidEdf(edf))?;
    if !edf.is_finite() {
        return Err(AllanError::InvalidEdf(edf));
    }
    Ok(match method {
        ChiSquareQuantile::Stable32 if edf > 100.0 => wilson_hilferty_stable32(p, edf),
        _ => distribution.inverse_cdf(p),
    })
}

/// A&S 26.4.17 with the normal quantile of A&S 26.2.22 as coded in Stable32.
fn wilson_hilferty_stable32(p: f64, edf: f64) -> f64 {
    let z = if p < 0.5 {
        -upper_normal_quantile_stable32(p)
    } else {
        upper_normal_quantile_stable32(1.0 - p)
    };
    let k = 2.0 / (9.0 * edf);
    edf * (1.0 - k + z * k.sqrt()).powi(3)
}

/// A&S 26.2.22: x with upper-tail probability q in (0, 0.5], |error| < 3e-3, with Stable32's
/// a1 = 0.27601 (A&S: 0.27061).
fn upper_normal_quantile_stable32(q: f64) -> f64 {
    let t = (-2.0 * q.ln()).sqrt();
    t - (2.30753 + 0.27601 * t) / (1.0 + 0.99229 * t + 0.04481 * t * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    // Closed form: with the true A&S coefficient 0.27061, 26.2.22 is within 3e-3 of the exact
    // normal quantile (A&S's stated bound); Stable32's 0.27601 shifts it by 0.0054 t/(denominator).
    #[test]
    fn stable32_normal_quantile_is_the_misprinted_as_26_2_22() {
        let q: f64 = 0.158_655_253_931_457; // 1 - Phi(1)
        let t = (-2.0 * q.ln()).sqrt();
        let denominator = 1.0 + 0.99229 * t + 0.04481 * t * t;
        let as_printed = t - (2.30753 + 0.27061 * t) / denominator;
        assert!((as_printed - 1.0).abs() < 3e-3);
        let shift = (0.27601 - 0.27061) * t / denominator;
        assert!((upper_normal_quantile_stable32(q) - (as_printed - shift)).abs() < 1e-15);
    }

    // The open interval (0, 1) by its ends and a NaN: the rule stated in the docs.
    #[test]
    fn validate_accepts_only_levels_strictly_between_0_and_1() {
        let with = |level| CiSettings {
            level,
            ..CiSettings::default()
        };
        for ok in [
            f64::MIN_POSITIVE,
            DEFAULT_CONFIDENCE,
            0.95,
            1.0 - f64::EPSILON,
        ] {
            assert_eq!(with(ok).validate(), Ok(()), "{ok}");
        }
        for bad in [0.0, 1.0, -0.5, 1.5, f64::INFINITY] {
            assert_eq!(
                with(bad).validate(),
                Err(AllanError::InvalidConfidenceLevel(bad)),
                "{bad}"
            );
        }
        assert!(matches!(
            with(f64::NAN).validate(),
            Err(AllanError::InvalidConfidenceLevel(l)) if l.is_nan()
        ));
    }

    #[test]
    fn invalid_level_and_edf_are_errors() {
        let bad = CiSettings {
            level: 1.0,
            ..CiSettings::default()
        };
        assert_eq!(
            interval_from_edf(1.0, 10.0, &bad),
            Err(AllanError::InvalidConfidenceLevel(1.0))
        );
        assert!(matches!(
            interval_from_edf(1.0, f64::NAN, &CiSettings::default()),
            Err(AllanError::InvalidEdf(_))
        ));
    }
}
