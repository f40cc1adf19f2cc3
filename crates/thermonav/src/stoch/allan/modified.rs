//! The modified Allan deviation and the time deviation derived from it.

use super::deviation::curve_from_variance;
use super::{AllanError, DeviationCurve, DeviationKind, TauGrid};

/// The modified Allan deviation (NIST SP 1065 eq. 14; allantools `mdev(y, rate,
/// data_type='freq')`) of rate samples `y` at `sample_rate_hz` on `grid`, in the unit of `y`.
///
/// With the phase x = τ₀ S, S_i = Σ_{j<i} (y_j − ȳ) (N + 1 points), each term is the sum over
/// m consecutive starts of the second difference of the phase, and
///
/// mod σ²(τ) = Σ_{j=0}^{n−1} \[Σ_{i=j}^{j+m−1} (x_{i+2m} − 2 x_{i+m} + x_i)\]² / (2 m² τ² n),
///
/// τ = m τ₀, n = N − 3m + 2 terms. Averaging the phase over m points before differencing is
/// what separates white from flicker phase noise. Factors need 3m ≤ N (two terms at least, as
/// allantools keeps). O(N) per factor: the inner sum slides along by one addition and one
/// subtraction.
///
/// # Errors
/// [`AllanError`] for fewer than 3 samples, non-finite values, a bad rate, or a grid with no
/// factor that fits.
pub fn modified_adev(
    y: &[f64],
    sample_rate_hz: f64,
    grid: &TauGrid,
) -> Result<DeviationCurve, AllanError> {
    curve_from_variance(DeviationKind::Mdev, y, sample_rate_hz, grid, modified_avar)
}

/// The time deviation (NIST SP 1065 eq. 15; allantools `tdev(y, rate, data_type='freq')`):
/// σ_x(τ) = τ mod σ_y(τ) / √3, τ = m τ₀ in seconds, so in the unit of `y` times seconds (for
/// fractional frequency: seconds of time error; for a gyro in rad/s: rad). Same factors and
/// term counts as [`modified_adev`].
///
/// # Errors
/// As [`modified_adev`].
pub fn time_deviation(
    y: &[f64],
    sample_rate_hz: f64,
    grid: &TauGrid,
) -> Result<DeviationCurve, AllanError> {
    let mut curve = modified_adev(y, sample_rate_hz, grid)?;
    curve.kind = DeviationKind::Tdev;
    for (sigma, tau_s) in curve.deviation.iter_mut().zip(&curve.tau_s) {
        *sigma *= tau_s / 3.0_f64.sqrt();
    }
    Ok(curve)
}

/// The modified Allan variance at factor m from the phase `s` in units of τ₀ (x = τ₀ s):
/// Σ_j w_j² / (2 m⁴ n), w_j = Σ_{i=j}^{j+m−1} (s_{i+2m} − 2 s_{i+m} + s_i), n = s.len() − 3m + 1.
///
/// w_{j+1} = w_j + d_{j+m} − d_j with d the second difference: the rounding of the running
/// window grows like √n times that of one d, far below the 1e-9 the oracle tests ask.
pub(crate) fn modified_avar(s: &[f64], m: usize) -> f64 {
    let d = |i: usize| s[i + 2 * m] - 2.0 * s[i + m] + s[i];
    let n = s.len() + 1 - 3 * m;
    let mut window: f64 = (0..m).map(d).sum();
    let mut total = window * window;
    for j in 1..n {
        window += d(j + m - 1) - d(j - 1);
        total += window * window;
    }
    total / (2.0 * (m as f64).powi(4) * n as f64)
}
