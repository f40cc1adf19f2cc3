//! The Hadamard deviations: third differences of the phase, blind to a linear frequency drift.

use super::deviation::curve_from_variance;
use super::{AllanError, DeviationCurve, DeviationKind, TauGrid};

/// The overlapping Hadamard deviation (NIST SP 1065 eq. 20; allantools `ohdev(y, rate,
/// data_type='freq')`) of rate samples `y` at `sample_rate_hz` on `grid`, in the unit of `y`:
///
/// σ²_H(τ) = Σ_{i=0}^{n−1} (x_{i+3m} − 3 x_{i+2m} + 3 x_{i+m} − x_i)² / (6 τ² n),
///
/// with the phase x = τ₀ Σ (y − ȳ) (N + 1 points), τ = m τ₀ and n = N + 1 − 3m terms (every
/// start). The third difference cancels a constant rate and a linear drift of it, so the
/// deviation converges for random-walk FM and drift where the Allan deviation is biased by
/// them. Factors need 3m + 1 ≤ N (two terms at least).
///
/// # Errors
/// [`AllanError`] for fewer than 3 samples, non-finite values, a bad rate, or a grid with no
/// factor that fits.
pub fn overlapping_hadamard_deviation(
    y: &[f64],
    sample_rate_hz: f64,
    grid: &TauGrid,
) -> Result<DeviationCurve, AllanError> {
    curve_from_variance(DeviationKind::Ohdev, y, sample_rate_hz, grid, |s, m| {
        hadamard_var(s, m, 1)
    })
}

/// The (non-overlapping) Hadamard deviation (NIST SP 1065 eqs. 17-18; allantools `hdev(y,
/// rate, data_type='freq')`): the sum of [`overlapping_hadamard_deviation`] taken only at the
/// starts i = 0, m, 2m, …, so n = ⌈(N + 1 − 3m)/m⌉ terms; in the unit of `y`. Factors need
/// 4m ≤ N (two terms at least).
///
/// # Errors
/// As [`overlapping_hadamard_deviation`].
pub fn hadamard_deviation(
    y: &[f64],
    sample_rate_hz: f64,
    grid: &TauGrid,
) -> Result<DeviationCurve, AllanError> {
    curve_from_variance(DeviationKind::Hdev, y, sample_rate_hz, grid, |s, m| {
        hadamard_var(s, m, m)
    })
}

/// The Hadamard variance at factor m from the phase `s` in units of τ₀ (x = τ₀ s), taking
/// every `stride`-th start: Σ_i (s_{i+3m} − 3 s_{i+2m} + 3 s_{i+m} − s_i)² / (6 m² n), n the
/// number of starts i with i + 3m < s.len().
fn hadamard_var(s: &[f64], m: usize, stride: usize) -> f64 {
    let (total, n) = (0..s.len() - 3 * m)
        .step_by(stride)
        .map(|i| s[i + 3 * m] - 3.0 * (s[i + 2 * m] - s[i + m]) - s[i])
        .fold((0.0, 0usize), |(total, n), h| (h.mul_add(h, total), n + 1));
    total / (6.0 * (m as f64).powi(2) * n as f64)
}
