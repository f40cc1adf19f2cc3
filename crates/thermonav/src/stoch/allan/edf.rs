//! Equivalent degrees of freedom of the overlapping Allan variance (Greenhall & Riley 2004).
//!
//! Notation of the paper, specialised to the overlapping Allan variance: difference order
//! d = 2, filter factor F = m (unmodified variance), stride factor S = m (fully overlapped).
//! For N phase points: L = m/F + m d = 2m + 1, M = 1 + floor(S (N - L) / m) = N - 2m (the
//! number of terms), J = min(M, (d + 1) S), r = M / S.

/// Order of the difference of the Allan variance.
const D: i32 = 2;
/// Largest sum length evaluated term by term before switching to the paper's approximations.
const J_MAX: f64 = 100.0;

/// Filter factor F of the paper: finite (1/F is the averaging step) or the F -> ∞ limit.
#[derive(Debug, Clone, Copy)]
enum Filter {
    Finite(f64),
    Infinite,
}

/// Equivalent degrees of freedom of the overlapping Allan variance for `n_phase` phase points
/// (N rate samples give N + 1), averaging factor `m` and power-law exponent `alpha` (2 white
/// PM … −2 random-walk FM; others are clamped to that range): Greenhall & Riley (2004) algorithm, cases 2 (alpha <= 0), 3 (alpha = 1) and
/// 4 (alpha = 2) for unmodified variances, including their Table 2 and Table 3 coefficients.
///
/// 1/edf = BasicSum(J, M, S, F, alpha) / (sz(0, F, alpha)^2 M) when J <= 100, otherwise the
/// paper's asymptotic forms. For white PM with ceil(r) <= d, where the paper gives no closed
/// form, the basic sum is evaluated in full (exact there: sz has compact support).
///
/// This is allantools `edf_greenhall(alpha, d=2, m, N, overlapping=True, modified=False)`
/// (which raises for that white-PM corner) and what Stable32 1.60 uses for OADEV.
///
/// Requires 1 <= m and 2m + 2 <= n_phase (at least two terms); outside that the result is
/// not meaningful (callers pass curve points, which satisfy it).
pub fn edf_overlapping_adev(n_phase: usize, m: usize, alpha: i32) -> f64 {
    let geometry = Geometry::new(m, n_phase);
    let alpha = alpha.clamp(-2, 2);
    1.0 / match alpha {
        2 => inverse_edf_white_pm(&geometry),
        1 => inverse_edf_flicker_pm(&geometry),
        _ => inverse_edf_frequency_noise(&geometry, alpha),
    }
}

/// M, S, J and r of the paper for the overlapping Allan variance.
struct Geometry {
    m: f64,
    big_m: f64,
    s: f64,
    j: f64,
    r: f64,
}

impl Geometry {
    fn new(m: usize, n_phase: usize) -> Self {
        let big_m = n_phase.saturating_sub(2 * m) as f64;
        let (m, s) = (m as f64, m as f64);
        Self {
            m,
            big_m,
            s,
            j: big_m.min(f64::from(D + 1) * s),
            r: big_m / s,
        }
    }
}

/// Case 2: unmodified variance, alpha <= 0.
fn inverse_edf_frequency_noise(g: &Geometry, alpha: i32) -> f64 {
    if g.j <= J_MAX {
        let filter = if g.m * f64::from(D + 1) <= J_MAX {
            Filter::Finite(g.m)
        } else {
            Filter::Infinite
        };
        normalised_sum(g.j, g.big_m, g.s, filter, alpha) / g.big_m
    } else if g.r > f64::from(D + 1) {
        let (a0, a1) = table2(alpha);
        (a0 - a1 / g.r) / g.r
    } else {
        let m_prime = J_MAX / g.r;
        normalised_sum(J_MAX, J_MAX, m_prime, Filter::Infinite, alpha) / J_MAX
    }
}

/// Case 3: unmodified variance, alpha = 1 (flicker PM).
fn inverse_edf_flicker_pm(g: &Geometry) -> f64 {
    // Table 3, d = 2: sz(0, m, 1, 2) ≈ b0 + b1 ln m.
    const B0: f64 = 15.23;
    const B1: f64 = 12.0;
    let scale = (B0 + B1 * g.m.ln()).powi(2);
    if g.j <= J_MAX {
        normalised_sum(g.j, g.big_m, g.s, Filter::Finite(g.m), 1) / g.big_m
    } else if g.r > f64::from(D + 1) {
        let (a0, a1) = table2(1);
        (a0 - a1 / g.r) / (scale * g.r)
    } else {
        let m_prime = J_MAX / g.r;
        basic_sum(J_MAX, J_MAX, m_prime, Filter::Finite(m_prime), 1) / (scale * J_MAX)
    }
}

/// Case 4: unmodified variance, alpha = 2 (white PM).
fn inverse_edf_white_pm(g: &Geometry) -> f64 {
    if g.r.ceil() <= f64::from(D) {
        normalised_sum(g.j, g.big_m, g.s, Filter::Finite(g.m), 2) / g.big_m
    } else {
        // a0 = C(4d, 2d) / C(2d, d)^2 = 70/36, a1 = d/2.
        let (a0, a1) = (35.0 / 18.0, f64::from(D) / 2.0);
        (a0 - a1 / g.r) / g.big_m
    }
}

/// Table 2 of Greenhall & Riley (2004), column d = 2: (a0, a1) for unmodified variances.
fn table2(alpha: i32) -> (f64, f64) {
    match alpha {
        2 => (35.0 / 18.0, 1.0),
        1 => (790.0, 410.0),
        0 => (2.0 / 3.0, 1.0 / 3.0),
        -1 => (0.852, 0.375),
        _ => (1.079, 0.368),
    }
}

/// BasicSum / sz(0)^2.
fn normalised_sum(j: f64, big_m: f64, s: f64, filter: Filter, alpha: i32) -> f64 {
    basic_sum(j, big_m, s, filter, alpha) / sz(0.0, filter, alpha).powi(2)
}

/// Eq. (10): sz(0)^2 + (1 - J/M) sz(J/S)^2 + 2 sum_{j=1}^{J-1} (1 - j/M) sz(j/S)^2.
fn basic_sum(j_total: f64, big_m: f64, s: f64, filter: Filter, alpha: i32) -> f64 {
    let first = sz(0.0, filter, alpha).powi(2);
    let last = (1.0 - j_total / big_m) * sz(j_total / s, filter, alpha).powi(2);
    let middle: f64 = (1..j_total as u64)
        .map(|j| j as f64)
        .map(|j| 2.0 * (1.0 - j / big_m) * sz(j / s, filter, alpha).powi(2))
        .sum();
    first + last + middle
}

/// Eq. (9) for d = 2: the binomial second difference 6 sx(t) - 4 sx(t±1) + sx(t±2).
fn sz(t: f64, filter: Filter, alpha: i32) -> f64 {
    6.0 * sx(t, filter, alpha) - 4.0 * (sx(t - 1.0, filter, alpha) + sx(t + 1.0, filter, alpha))
        + sx(t - 2.0, filter, alpha)
        + sx(t + 2.0, filter, alpha)
}

/// Eq. (8): F^2 [2 sw(t) - sw(t - 1/F) - sw(t + 1/F)], and sw(t, alpha + 2) for F = ∞.
fn sx(t: f64, filter: Filter, alpha: i32) -> f64 {
    match filter {
        Filter::Infinite => sw(t, alpha + 2),
        Filter::Finite(f) => {
            f * f * (2.0 * sw(t, alpha) - sw(t - 1.0 / f, alpha) - sw(t + 1.0 / f, alpha))
        }
    }
}

/// Eq. (7): the generalised autocovariance of the phase noise, up to a constant factor.
fn sw(t: f64, alpha: i32) -> f64 {
    let a = t.abs();
    let t_ln_t = |power: i32| {
        if a == 0.0 {
            0.0
        } else {
            a.powi(power) * a.ln()
        }
    };
    match alpha {
        2 => -a,
        1 => t_ln_t(2),
        0 => a.powi(3),
        -1 => t_ln_t(4),
        -2 => a.powi(5),
        -3 => t_ln_t(6),
        _ => a.powi(7),
    }
}
