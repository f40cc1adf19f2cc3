//! The Allan family behind one entry point: the factors a kind can use, the phase they all
//! start from, and the dispatch from a [`DeviationKind`] to its estimator.

use rayon::prelude::*;

use crate::imu::{Channel, ImuSeries};

use super::deviation::{centred_cumulative_sum, checked_factors_for};
use super::{
    AllanError, DeviationCurve, DeviationKind, TauGrid, hadamard_deviation, modified_adev,
    overlapping_adev, overlapping_hadamard_deviation, time_deviation, total_deviation,
};

/// The deviation `kind` of rate samples `y` at `sample_rate_hz` on `grid`.
///
/// [`DeviationKind::Adev`] is [`overlapping_adev`] itself (same numbers, same speed); the others
/// are [`modified_adev`], [`hadamard_deviation`], [`overlapping_hadamard_deviation`],
/// [`time_deviation`] and [`total_deviation`]. Each kind keeps only the factors of `grid` it can
/// be evaluated at ([`DeviationKind::fits`]).
///
/// # Errors
/// [`AllanError`] for fewer than 3 samples, non-finite values, a bad rate, or a grid with no
/// factor that fits the kind.
///
/// # Example
/// ```
/// use thermonav::stoch::allan::{deviation, DeviationKind, TauGrid};
/// let y = [1.0, -1.0, 1.0, -1.0, 1.0, -1.0];
/// let curve = deviation(DeviationKind::Mdev, &y, 1.0, &TauGrid::Octave).unwrap();
/// assert_eq!(curve.averaging_factor, vec![1, 2]);
/// assert!((curve.deviation[0] - 2.0_f64.sqrt()).abs() < 1e-12);
/// ```
pub fn deviation(
    kind: DeviationKind,
    y: &[f64],
    sample_rate_hz: f64,
    grid: &TauGrid,
) -> Result<DeviationCurve, AllanError> {
    let estimator = match kind {
        DeviationKind::Adev => return overlapping_adev(y, sample_rate_hz, grid).map(Into::into),
        DeviationKind::Mdev => modified_adev,
        DeviationKind::Hdev => hadamard_deviation,
        DeviationKind::Ohdev => overlapping_hadamard_deviation,
        DeviationKind::Tdev => time_deviation,
        DeviationKind::Totdev => total_deviation,
    };
    estimator(y, sample_rate_hz, grid)
}

/// The deviation `kind` ([`deviation`]) of every channel of `series` (rates sampled at
/// `sample_rate_hz`), in [`Channel::ALL`] order; only those present for a record of a subset
/// ([`ImuSeries::present_channels`]).
///
/// # Errors
/// The first channel whose curve cannot be computed, with its [`AllanError`].
pub fn channel_deviations(
    kind: DeviationKind,
    series: &ImuSeries,
    sample_rate_hz: f64,
    grid: &TauGrid,
) -> Result<Vec<(Channel, DeviationCurve)>, (Channel, AllanError)> {
    series
        .present_channels()
        .into_iter()
        .map(|c| {
            deviation(kind, series.channel(c), sample_rate_hz, grid)
                .map(|curve| (c, curve))
                .map_err(|e| (c, e))
        })
        .collect()
}

/// The curve of `kind` whose variance at factor m is `variance(phase, m)`, with the phase
/// S_i = Σ_{j<i} (y_j − ȳ) (N + 1 points, in units of τ₀) and the variance in the unit of
/// `y` squared. The factors are evaluated in parallel; each one alone, so the result does not
/// depend on the number of threads.
///
/// # Errors
/// As [`deviation`].
pub(super) fn curve_from_variance(
    kind: DeviationKind,
    y: &[f64],
    sample_rate_hz: f64,
    grid: &TauGrid,
    variance: impl Fn(&[f64], usize) -> f64 + Sync,
) -> Result<DeviationCurve, AllanError> {
    let factors = checked_factors_for(kind, y.len(), sample_rate_hz, grid)?;
    if let Some(index) = y.iter().position(|v| !v.is_finite()) {
        return Err(AllanError::NonFinite { index });
    }
    let phase = centred_cumulative_sum(y);
    let sigma = factors
        .par_iter()
        .map(|&m| variance(&phase, m).sqrt())
        .collect();
    Ok(DeviationCurve::new(
        kind,
        factors,
        sigma,
        y.len(),
        sample_rate_hz,
    ))
}
