//! The theoretical Haar wavelet variance of each process, per sample (τ in samples, variances in
//! the unit of the data squared per sample).
//!
//! With W = (S_recent − S_older)/τ, S two adjacent sums of m = τ/2 samples:
//! - white noise, var σ²: ν² = σ²/τ;
//! - quantisation noise y_t = x_t − x_{t−1}, x white with var Q²: the window difference is
//!   x_t − 2 x_{t−m} + x_{t−2m}, so ν² = 6 Q²/τ²;
//! - random walk with increments of var γ²: ν² = γ² (τ² + 2)/(12 τ);
//! - drift y_t = ω t: ν² = ω² τ²/16;
//! - first-order Gauss-Markov (AR(1) with φ = e^{−a}, a = 1/Tc in samples⁻¹, stationary var s²):
//!   var(S_m) − cov(S_older, S_recent) = s² φ \[F(m a) + 2m (sinh a − a)\] / (1 − φ)², with
//!   F(x) = 2x − 3 + 4e^{−x} − e^{−2x}, hence ν² = 2 s² φ \[F(m a) + 2m (sinh a − a)\] / (τ (1 − φ))².
//!
//! The last form is the textbook one, (τ/2 − 3φ − τφ²/2 + 4φ^{τ/2+1} − φ^{τ+1}) · 2σ²_w /
//! (τ² (1 − φ)² (1 − φ²)) with σ²_w = s² (1 − φ²), rewritten so that it keeps its digits when
//! Tc ≫ τ: the textbook numerator is (1 − φ)³ for τ = 2, a difference of terms of order 1 that
//! loses every digit at φ = 1 − 10⁻⁵, while F and sinh a − a are summed from their Taylor series
//! below 1 and both parts are positive. Every form is checked in the tests against the slow
//! definition Σ_l Σ_k h_l h_k γ(l − k) over the filter taps.

/// ν² of white noise of variance `variance` at scale `tau` samples.
pub fn white(variance: f64, tau: f64) -> f64 {
    variance / tau
}

/// ν² of quantisation noise x_t − x_{t−1}, var(x) = `variance`, at scale `tau` samples.
pub fn quantisation(variance: f64, tau: f64) -> f64 {
    6.0 * variance / (tau * tau)
}

/// ν² of a random walk with increments of variance `variance` at scale `tau` samples.
pub fn random_walk(variance: f64, tau: f64) -> f64 {
    variance * (tau * tau + 2.0) / (12.0 * tau)
}

/// ν² of a drift of `slope` (unit of the data per sample) at scale `tau` samples.
pub fn drift(slope: f64, tau: f64) -> f64 {
    slope * slope * tau * tau / 16.0
}

/// ν² of a Gauss-Markov process with correlation time `correlation_samples` (samples) and
/// stationary variance `variance` at scale `tau` samples.
pub fn gauss_markov(correlation_samples: f64, variance: f64, tau: f64) -> f64 {
    GaussMarkovCurve::new(correlation_samples).at(variance, tau)
}

/// [`gauss_markov`] at many scales for one correlation time: the factors that depend on Tc
/// alone (two exponentials and sinh a − a) computed once, the same arithmetic at each scale.
#[derive(Debug, Clone, Copy)]
pub struct GaussMarkovCurve {
    /// a = 1/Tc, 1/samples.
    a: f64,
    phi: f64,
    one_minus_phi: f64,
    /// sinh a − a, for a < 1 (unused otherwise).
    sinh_minus_a: f64,
}

impl GaussMarkovCurve {
    /// The curve of a Gauss-Markov process with correlation time `correlation_samples`.
    pub fn new(correlation_samples: f64) -> Self {
        let a = 1.0 / correlation_samples;
        Self {
            a,
            phi: (-a).exp(),
            one_minus_phi: -(-a).exp_m1(),
            sinh_minus_a: if a < 1.0 { sinh_minus_identity(a) } else { 0.0 },
        }
    }

    /// ν² at scale `tau` samples for stationary variance `variance`.
    pub fn at(&self, variance: f64, tau: f64) -> f64 {
        self.factors(tau).at(variance)
    }

    /// The curve's factors at scale `tau` samples, which ν² takes for any variance.
    pub fn factors(&self, tau: f64) -> ScaleFactors {
        let (a, phi) = (self.a, self.phi);
        let m = tau / 2.0;
        // φ·2m(sinh a − a) = m(1 − φ²) − 2maφ, the form that cannot overflow at large a.
        let phi_bracket = if a < 1.0 {
            phi * (f_of(m * a) + 2.0 * m * self.sinh_minus_a)
        } else {
            phi * f_of(m * a) + m * (1.0 - phi * phi) - 2.0 * m * a * phi
        };
        ScaleFactors {
            phi_bracket,
            denominator: (tau * self.one_minus_phi).powi(2),
        }
    }
}

/// A Gauss-Markov curve at one scale: ν² = 2 s² φ[F(m a) + 2m (sinh a − a)] / (τ (1 − φ))², the
/// bracket (times φ) and the denominator kept, so that every variance s² costs two products and
/// a division (the same arithmetic as [`GaussMarkovCurve::at`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScaleFactors {
    phi_bracket: f64,
    denominator: f64,
}

impl ScaleFactors {
    /// ν² for stationary variance `variance`.
    pub fn at(self, variance: f64) -> f64 {
        2.0 * variance * self.phi_bracket / self.denominator
    }
}

/// F(x) = 2x − 3 + 4e^{−x} − e^{−2x} = Σ_{k≥3} (−1)^k (4 − 2^k) x^k / k!.
fn f_of(x: f64) -> f64 {
    if x >= 1.0 {
        return 2.0 * x - 3.0 + 4.0 * (-x).exp() - (-2.0 * x).exp();
    }
    let mut power_over_factorial = x * x / 2.0; // x^k/k! at k = 2
    let mut two_to_k = 4.0; // 2^k at k = 2, doubled exactly
    let mut sum = 0.0;
    for k in 3..40 {
        power_over_factorial *= x / f64::from(k);
        two_to_k *= 2.0;
        let term = (4.0 - two_to_k) * power_over_factorial;
        sum += if k % 2 == 0 { term } else { -term };
        if term.abs() < 1e-17 * sum.abs() {
            break;
        }
    }
    sum
}

/// sinh a − a = Σ_{k≥1} a^{2k+1}/(2k+1)! for 0 ≤ a < 1.
fn sinh_minus_identity(a: f64) -> f64 {
    let mut term = a * a * a / 6.0;
    let mut sum = term;
    let mut k = 3.0;
    while term > 1e-17 * sum {
        term *= a * a / ((k + 1.0) * (k + 2.0));
        sum += term;
        k += 2.0;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    // τ·ν²(τ) is non-decreasing in τ for white noise (constant), a random walk, a drift and a
    // Gauss-Markov process of any Tc (a positively correlated process's block means
    // decorrelate more slowly than white noise's), while quantisation noise's falls as 1/τ.
    // This is what makes a rise-then-fall of τ·ν² faster than 1/τ impossible for any composite
    // (`tests/it/gmwm.rs`, on the ADIS16405 accelerometers).
    #[test]
    fn tau_times_wavelet_variance_never_falls_except_for_quantisation() {
        let scales: Vec<f64> = (1..40).map(|j| 2f64.powi(j)).collect();
        for tc in [0.3, 1.0, 3.0, 100.0, 1e5, 1e12] {
            let f: Vec<f64> = scales
                .iter()
                .map(|&t| t * gauss_markov(tc, 1.0, t))
                .collect();
            for k in 1..f.len() {
                assert!(
                    f[k] >= f[k - 1] * (1.0 - 1e-12),
                    "Tc {tc}: at scale {}",
                    scales[k]
                );
            }
        }
        for t in &scales[1..] {
            assert!(t * random_walk(1.0, *t) >= (t / 2.0) * random_walk(1.0, t / 2.0));
            assert!(t * drift(1.0, *t) >= (t / 2.0) * drift(1.0, t / 2.0));
            let q = t * quantisation(1.0, *t) / ((t / 2.0) * quantisation(1.0, t / 2.0));
            assert!((q - 0.5).abs() < 1e-15);
        }
    }

    /// The Haar MODWT filter of width `tau`: −1/τ on the older half, +1/τ on the recent half
    /// (index l = 0 is the most recent sample).
    fn haar(tau: usize) -> Vec<f64> {
        (0..tau)
            .map(|l| if l < tau / 2 { 1.0 } else { -1.0 } / tau as f64)
            .collect()
    }

    /// Σ_l Σ_k h_l h_k γ(l − k): the wavelet variance of a stationary process from its
    /// autocovariance, term by term.
    fn slow_stationary(tau: usize, acvs: impl Fn(usize) -> f64) -> f64 {
        let h = haar(tau);
        let mut total = 0.0;
        for (l, hl) in h.iter().enumerate() {
            for (k, hk) in h.iter().enumerate() {
                total += hl * hk * acvs(l.abs_diff(k));
            }
        }
        total
    }

    /// A random walk y_t = Σ_{i≤t} e_i seen through the filter: W = Σ_k g_k e_{t−k} with
    /// g_k = Σ_{l≥k} h_l (the taps sum to zero, so older increments cancel); ν² = γ² Σ g_k².
    fn slow_random_walk(tau: usize, variance: f64) -> f64 {
        let h = haar(tau);
        (0..tau)
            .map(|k| h[k..].iter().sum::<f64>().powi(2))
            .sum::<f64>()
            * variance
    }

    fn close(got: f64, expected: f64, tolerance: f64) -> bool {
        (got / expected - 1.0).abs() < tolerance
    }

    // Every comparison below is the same number computed two ways in f64; the slow sums add
    // up to τ² terms of mixed sign, so 1e-11 relative leaves room for their rounding.
    const SCALES: [usize; 7] = [2, 4, 8, 16, 64, 256, 1024];

    #[test]
    fn white_and_quantisation_equal_the_filter_sums() {
        for tau in SCALES {
            let wn = slow_stationary(tau, |h| if h == 0 { 2.5 } else { 0.0 });
            assert!(close(white(2.5, tau as f64), wn, 1e-11), "tau {tau}");
            // x_t − x_{t−1}: γ(0) = 2Q², γ(1) = −Q².
            let acvs = |h| match h {
                0 => 2.0 * 0.7,
                1 => -0.7,
                _ => 0.0,
            };
            let qn = slow_stationary(tau, acvs);
            assert!(close(quantisation(0.7, tau as f64), qn, 1e-11), "tau {tau}");
        }
    }

    #[test]
    fn random_walk_and_drift_equal_the_filter_sums() {
        for tau in SCALES {
            let rw = slow_random_walk(tau, 0.3);
            assert!(close(random_walk(0.3, tau as f64), rw, 1e-11), "tau {tau}");
            // y_t = ω (t − l): Σ_l h_l ω (t − l) = −ω Σ_l l h_l.
            let h = haar(tau);
            let w: f64 = -1.5 * h.iter().enumerate().map(|(l, v)| l as f64 * v).sum::<f64>();
            assert!(close(drift(1.5, tau as f64), w * w, 1e-11), "tau {tau}");
        }
    }

    #[test]
    fn gauss_markov_equals_the_filter_sum_from_short_to_long_correlation_times() {
        for tc in [0.3_f64, 1.0, 7.5, 100.0, 1e4, 1e6] {
            let phi: f64 = (-1.0 / tc).exp();
            for tau in SCALES {
                let slow = slow_stationary(tau, |h| 2.0 * phi.powi(h as i32));
                let got = gauss_markov(tc, 2.0, tau as f64);
                // At Tc = 10⁶ samples the slow sum itself cancels to ~1e-6 of its terms: its
                // rounding, ~τ² ε / (τ/Tc), sets the tolerance there.
                let tolerance = if tc > 1e3 { 1e-7 } else { 1e-11 };
                assert!(
                    close(got, slow, tolerance),
                    "tc {tc} tau {tau}: {got} vs {slow}"
                );
            }
        }
    }

    #[test]
    fn gauss_markov_matches_the_textbook_form_where_that_form_is_accurate() {
        // The brief's closed form, (τ/2 − 3φ − τφ²/2 + 4φ^{τ/2+1} − φ^{τ+1}) 2σ²_w /
        // (τ²(1 − φ)²(1 − φ²)), is well conditioned for φ far from 1.
        let (tc, s2): (f64, f64) = (3.0, 1.7);
        let phi: f64 = (-1.0 / tc).exp();
        let innovation = s2 * (1.0 - phi * phi);
        for tau in SCALES {
            let t = tau as f64;
            let numerator = t / 2.0 - 3.0 * phi - t * phi * phi / 2.0
                + 4.0 * phi.powf(t / 2.0 + 1.0)
                - phi.powf(t + 1.0);
            let textbook =
                numerator * 2.0 * innovation / (t * t * (1.0 - phi).powi(2) * (1.0 - phi * phi));
            assert!(close(gauss_markov(tc, s2, t), textbook, 1e-12), "tau {tau}");
        }
    }

    #[test]
    fn gauss_markov_tends_to_white_and_random_walk_at_its_limits() {
        // Tc ≪ 1 sample: white noise of variance s²; Tc ≫ τ: a random walk with increments of
        // variance s²(1 − φ²) ≈ 2 s²/Tc (relative error of order τ/Tc).
        assert!(close(gauss_markov(1e-3, 2.0, 8.0), white(2.0, 8.0), 1e-12));
        let tc = 1e7;
        let rw = random_walk(2.0 * 2.0 / tc, 64.0);
        assert!(close(gauss_markov(tc, 2.0, 64.0), rw, 1e-5));
    }
}
