//! The total deviation: the Allan deviation of the phase extended by reflection at both ends.

use super::deviation::curve_from_variance;
use super::{AllanError, DeviationCurve, DeviationKind, TauGrid};

/// The total deviation (NIST SP 1065 eq. 25; allantools `totdev(y, rate, data_type='freq')`)
/// of rate samples `y` at `sample_rate_hz` on `grid`, in the unit of `y`.
///
/// The phase x = τ₀ Σ (y − ȳ) (M = N + 1 points x_0 … x_{M−1}) is extended by M − 2 points at
/// each end, reflected through the end points (inverted, so the reflection continues the
/// slope): x*_{−j} = 2 x_0 − x_j and x*_{M−1+j} = 2 x_{M−1} − x_{M−1−j}, j = 1 … M − 2. Then
///
/// σ²_tot(τ) = Σ_{i=1}^{M−2} (x*_{i−m} − 2 x_i + x*_{i+m})² / (2 τ² (M − 2)),
///
/// τ = m τ₀, with n = M − 2 = N − 1 terms at every factor. Every factor up to m = N is
/// evaluated, as allantools does (Stable32 stops at N/2): the reflected phase gives each one
/// the full N − 1 terms, which is the point of the estimator (better confidence at long τ).
/// allantools' bias correction for totdev is not applied (it has none either).
///
/// # Errors
/// [`AllanError`] for fewer than 3 samples, non-finite values, a bad rate, or a grid with no
/// factor that fits.
pub fn total_deviation(
    y: &[f64],
    sample_rate_hz: f64,
    grid: &TauGrid,
) -> Result<DeviationCurve, AllanError> {
    let reflected = std::sync::OnceLock::new();
    curve_from_variance(DeviationKind::Totdev, y, sample_rate_hz, grid, |s, m| {
        total_var(reflected.get_or_init(|| reflected_phase(s)), s.len(), m)
    })
}

/// The phase `s` (M points) with M − 2 points reflected through each end point before and after
/// it: 3M − 4 points, s_0 at index M − 2.
fn reflected_phase(s: &[f64]) -> Vec<f64> {
    let (first, last) = (s[0], s[s.len() - 1]);
    let inner = &s[1..s.len() - 1];
    let before = inner.iter().rev().map(|x| 2.0 * first - x);
    let after = inner.iter().rev().map(|x| 2.0 * last - x);
    before.chain(s.iter().copied()).chain(after).collect()
}

/// The total variance at factor m ≤ M − 1 from the reflected phase `x` of [`reflected_phase`]
/// for M = `phase_len` original points, in units of τ₀:
/// Σ_{i=1}^{M−2} (x*_{i−m} − 2 x_i + x*_{i+m})² / (2 m² (M − 2)).
fn total_var(x: &[f64], phase_len: usize, m: usize) -> f64 {
    let offset = phase_len - 2;
    let n = phase_len - 2;
    let total = (offset + 1..offset + 1 + n)
        .map(|k| x[k - m] - 2.0 * x[k] + x[k + m])
        .fold(0.0, |total, d: f64| d.mul_add(d, total));
    total / (2.0 * (m as f64).powi(2) * n as f64)
}
