//! First-order Gauss-Markov (GM) models: the process, the paper's AR-based estimate
//! (method.md equations 8-10) and the classical fit to the autocorrelation.
//!
//! dx/dt = −x/Tc + w, R(τ) = σ² exp(−|τ|/Tc); discretely x_k = φ_k x_{k−1} + w_k with
//! φ_k = exp(−dt_k/Tc) and var(w_k) = σ²(1 − φ_k²) (exact; equation 4).

use serde::Serialize;
use statrs::distribution::{ContinuousCDF, Normal};

/// A first-order Gauss-Markov process.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GaussMarkov {
    /// Correlation time Tc, s.
    pub correlation_time_s: f64,
    /// Standard deviation σ, unit of the data.
    pub sigma: f64,
}

impl GaussMarkov {
    /// φ = exp(−dt/Tc).
    pub fn phi(&self, dt_s: f64) -> f64 {
        (-dt_s / self.correlation_time_s).exp()
    }

    /// var(w) = σ² (1 − exp(−2 dt/Tc)), the exact driving-noise variance over dt.
    pub fn driving_noise_variance(&self, dt_s: f64) -> f64 {
        self.sigma * self.sigma * (1.0 - (-2.0 * dt_s / self.correlation_time_s).exp())
    }

    /// R(τ) = σ² exp(−|τ|/Tc).
    pub fn autocovariance(&self, tau_s: f64) -> f64 {
        self.sigma * self.sigma * (-tau_s.abs() / self.correlation_time_s).exp()
    }

    /// One exact step (equations 3-4): x_k = φ x_{k−1} + √(σ²(1 − φ²)) z with φ = exp(−dt/Tc)
    /// and z a standard normal draw; 1 − φ² is eq. 4's 1 − exp(−2 dt/Tc) with one exp.
    pub fn step(&self, previous: f64, dt_s: f64, z: f64) -> f64 {
        let phi = self.phi(dt_s);
        phi * previous + self.sigma * (1.0 - phi * phi).max(0.0).sqrt() * z
    }

    /// Spectral density of the continuous driving noise, q = 2σ²/Tc.
    pub fn spectral_density(&self) -> f64 {
        2.0 * self.sigma * self.sigma / self.correlation_time_s
    }
}

/// A GM estimate with a 95 % interval on Tc, or the reason there is none.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum GaussMarkovOutcome {
    /// A model.
    Model {
        /// The process.
        model: GaussMarkov,
        /// 95 % interval of Tc, s; `None` on a side the data do not bound.
        ci95_correlation_time_s: [Option<f64>; 2],
    },
    /// No GM equivalent.
    NoEquivalent {
        /// Why, in words.
        reason: String,
    },
}

/// The inputs of the AR-based estimate: an AR(1) fit at interval dt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ar1Estimate {
    /// AR(1) coefficient c₁.
    pub c1: f64,
    /// Its standard error.
    pub c1_std_error: f64,
    /// Innovation variance var(w).
    pub innovation_variance: f64,
    /// Sampling interval of the fitted series, s.
    pub dt_s: f64,
}

/// z of a two-sided 95 % normal interval.
fn z95() -> f64 {
    Normal::standard().inverse_cdf(0.975)
}

/// Tc = −dt / ln c₁ for 0 < c₁ < 1.
fn tc_of(c1: f64, dt_s: f64) -> f64 {
    -dt_s / c1.ln()
}

/// The paper's AR-based GM (equations 8-10): Tc = −dt / ln c₁, σ² = var(w)/(1 − c₁²). The 95 %
/// interval maps c₁ ± 1.96 se(c₁), clipped to (0, 1), through the increasing function Tc(c₁);
/// when the upper end of c₁ reaches 1 the upper side is unbounded (`None`).
pub fn ar_based(estimate: &Ar1Estimate) -> GaussMarkovOutcome {
    let Ar1Estimate {
        c1,
        c1_std_error,
        innovation_variance,
        dt_s,
    } = *estimate;
    let valid = [c1, c1_std_error, innovation_variance, dt_s]
        .iter()
        .all(|v| v.is_finite())
        && dt_s > 0.0;
    if !valid {
        return GaussMarkovOutcome::NoEquivalent {
            reason: "the AR(1) fit has non-finite values or a non-positive interval".into(),
        };
    }
    if c1 >= 1.0 {
        return GaussMarkovOutcome::NoEquivalent {
            reason: format!(
                "c1 = {c1:.6} >= 1: the series behaves as a random walk or drift, which has no stationary Gauss-Markov equivalent"
            ),
        };
    }
    if c1 <= 0.0 {
        return GaussMarkovOutcome::NoEquivalent {
            reason: format!(
                "c1 = {c1:.6} <= 0: no positive correlation between successive samples, so no correlation time"
            ),
        };
    }
    let half = z95() * c1_std_error.max(0.0);
    let low = c1 - half;
    let high = c1 + half;
    let sigma = (innovation_variance / (1.0 - c1 * c1)).max(0.0).sqrt();
    GaussMarkovOutcome::Model {
        model: GaussMarkov {
            correlation_time_s: tc_of(c1, dt_s),
            sigma,
        },
        ci95_correlation_time_s: [
            (low > 0.0).then(|| tc_of(low, dt_s)),
            (high < 1.0).then(|| tc_of(high, dt_s)),
        ],
    }
}

/// Which lags of the autocorrelation the classical fit uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LagWindow {
    /// Lags 1.. up to (not including) the first non-positive autocovariance.
    FirstZeroCrossing,
    /// Lags 1..=n.
    Fixed(usize),
}

/// The classical GM fit (the method the paper improves on): nonlinear least squares of
/// σ² exp(−k dt / Tc) to the autocovariance γ(k) over the lag window, lag 0 excluded (it holds
/// the white-noise spike). Started from the log-linear fit ln γ(k) = ln σ² − k dt/Tc, refined
/// by Gauss-Newton with step halving on the residual sum of squares. No interval is given: the
/// ACF values are correlated, so least-squares errors would mislead.
pub fn fit_autocovariance(gamma: &[f64], lag_dt_s: f64, window: LagWindow) -> GaussMarkovOutcome {
    let last = match window {
        LagWindow::FirstZeroCrossing => gamma
            .iter()
            .skip(1)
            .position(|&g| g <= 0.0)
            .unwrap_or(gamma.len() - 1),
        LagWindow::Fixed(n) => n.min(gamma.len().saturating_sub(1)),
    };
    if last < 2
        || !(lag_dt_s.is_finite() && lag_dt_s > 0.0)
        || gamma.iter().take(last + 1).any(|g| !g.is_finite())
    {
        return GaussMarkovOutcome::NoEquivalent {
            reason: format!(
                "the autocovariance stays positive for only {last} lags after lag 0; at least 2 are needed for an exponential fit"
            ),
        };
    }
    let points: Vec<(f64, f64)> = (1..=last)
        .map(|k| (k as f64 * lag_dt_s, gamma[k]))
        .collect();
    let Some((mut a, mut b)) = log_linear_start(&points) else {
        return GaussMarkovOutcome::NoEquivalent {
            reason: "the autocovariance does not decay: no exponential fits it".into(),
        };
    };
    for _ in 0..100 {
        match gauss_newton_step(&points, a, b) {
            Some((na, nb))
                if (na - a).abs() <= 1e-14 * a.abs() && (nb - b).abs() <= 1e-14 * b.abs() =>
            {
                (a, b) = (na, nb);
                break;
            }
            Some(next) => (a, b) = next,
            None => break,
        }
    }
    if !(a > 0.0 && b > 0.0 && a.is_finite() && b.is_finite()) {
        return GaussMarkovOutcome::NoEquivalent {
            reason: "the fitted exponential does not decay".into(),
        };
    }
    GaussMarkovOutcome::Model {
        model: GaussMarkov {
            correlation_time_s: 1.0 / b,
            sigma: a.sqrt(),
        },
        ci95_correlation_time_s: [None, None],
    }
}

/// Model a e^{−b τ}: the start from the least-squares line through ln γ over the leading
/// positive values (noise makes the tail of a sample autocovariance change sign).
fn log_linear_start(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let leading = points
        .iter()
        .position(|&(_, g)| g <= 0.0)
        .unwrap_or(points.len());
    let points = &points[..leading];
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let (st, sy, stt, sty) =
        points
            .iter()
            .fold((0.0, 0.0, 0.0, 0.0), |(st, sy, stt, sty), &(t, g)| {
                let y = g.ln();
                (st + t, sy + y, stt + t * t, sty + t * y)
            });
    let slope = (n * sty - st * sy) / (n * stt - st * st);
    let intercept = (sy - slope * st) / n;
    (slope < 0.0 && slope.is_finite()).then(|| (intercept.exp(), -slope))
}

fn rss(points: &[(f64, f64)], a: f64, b: f64) -> f64 {
    points
        .iter()
        .map(|&(t, g)| (g - a * (-b * t).exp()).powi(2))
        .sum()
}

/// One Gauss-Newton step for (a, b), halved until the residual sum of squares decreases.
fn gauss_newton_step(points: &[(f64, f64)], a: f64, b: f64) -> Option<(f64, f64)> {
    let (mut jtj, mut jtr) = ([[0.0; 2]; 2], [0.0; 2]);
    for &(t, g) in points {
        let e = (-b * t).exp();
        let j = [e, -a * t * e];
        let r = g - a * e;
        for i in 0..2 {
            jtr[i] += j[i] * r;
            for k in 0..2 {
                jtj[i][k] += j[i] * j[k];
            }
        }
    }
    let det = jtj[0][0] * jtj[1][1] - jtj[0][1] * jtj[1][0];
    if det.abs() <= f64::MIN_POSITIVE {
        return None;
    }
    let da = (jtj[1][1] * jtr[0] - jtj[0][1] * jtr[1]) / det;
    let db = (jtj[0][0] * jtr[1] - jtj[1][0] * jtr[0]) / det;
    let current = rss(points, a, b);
    let mut step = 1.0;
    for _ in 0..40 {
        let (na, nb) = (a + step * da, b + step * db);
        if nb > 0.0 && rss(points, na, nb) <= current {
            return Some((na, nb));
        }
        step *= 0.5;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ar_based_inverts_phi_exactly() {
        // c1 = exp(−dt/Tc) with Tc = 100 s, dt = 1 s; var(w) = σ²(1 − c1²) with σ = 2.
        let c1 = (-0.01_f64).exp();
        let out = ar_based(&Ar1Estimate {
            c1,
            c1_std_error: 0.001,
            innovation_variance: 4.0 * (1.0 - c1 * c1),
            dt_s: 1.0,
        });
        let GaussMarkovOutcome::Model {
            model,
            ci95_correlation_time_s: [lo, hi],
        } = out
        else {
            panic!("{out:?}")
        };
        assert!((model.correlation_time_s - 100.0).abs() < 1e-9);
        assert!((model.sigma - 2.0).abs() < 1e-12);
        // c1 ± 1.96e-3 → Tc = −1/ln(c1 ∓ 0.00196): closed form.
        assert!((lo.unwrap() - (-1.0 / (c1 - 0.001 * z95()).ln())).abs() < 1e-9);
        assert!((hi.unwrap() - (-1.0 / (c1 + 0.001 * z95()).ln())).abs() < 1e-6);
    }

    #[test]
    fn upper_interval_is_unbounded_near_one_and_no_equivalent_outside() {
        let out = ar_based(&Ar1Estimate {
            c1: 0.999,
            c1_std_error: 0.01,
            innovation_variance: 1.0,
            dt_s: 1.0,
        });
        assert!(matches!(
            out,
            GaussMarkovOutcome::Model {
                ci95_correlation_time_s: [Some(_), None],
                ..
            }
        ));
        for c1 in [1.0, 1.02, 0.0, -0.3] {
            let out = ar_based(&Ar1Estimate {
                c1,
                c1_std_error: 0.01,
                innovation_variance: 1.0,
                dt_s: 1.0,
            });
            let GaussMarkovOutcome::NoEquivalent { reason } = out else {
                panic!("c1 {c1}")
            };
            assert!(reason.contains("c1"), "{reason}");
        }
    }

    #[test]
    fn exact_exponential_autocovariance_is_recovered() {
        // γ(k) = σ² exp(−k dt/Tc) with a white spike at lag 0: closed form, recovered to 1e-9.
        let truth = GaussMarkov {
            correlation_time_s: 12.5,
            sigma: 0.3,
        };
        let mut gamma: Vec<f64> = (0..200)
            .map(|k| truth.autocovariance(k as f64 * 0.5))
            .collect();
        gamma[0] += 5.0;
        let GaussMarkovOutcome::Model { model, .. } =
            fit_autocovariance(&gamma, 0.5, LagWindow::Fixed(100))
        else {
            panic!()
        };
        assert!((model.correlation_time_s / 12.5 - 1.0).abs() < 1e-9);
        assert!((model.sigma / 0.3 - 1.0).abs() < 1e-9);
    }

    #[test]
    fn driving_noise_keeps_the_variance_stationary_at_any_step() {
        // σ² = φ² σ² + var(w) for every dt: the exact discretisation's defining identity.
        let gm = GaussMarkov {
            correlation_time_s: 3.0,
            sigma: 1.7,
        };
        for dt in [1e-4, 0.005, 1.0, 30.0] {
            let phi = gm.phi(dt);
            assert!(
                (phi * phi * 1.7 * 1.7 + gm.driving_noise_variance(dt) - 1.7 * 1.7).abs() < 1e-12
            );
        }
        assert!((gm.spectral_density() - 2.0 * 1.7 * 1.7 / 3.0).abs() < 1e-15);
    }
}
