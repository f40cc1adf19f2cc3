//! The Allan family behind one entry point: the dispatch from a [`DeviationKind`] to its
//! estimator (the factors a kind can use and the phase they all start from are in
//! [`super::deviation`]'s helpers).

use crate::imu::{Channel, ImuSeries};

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
