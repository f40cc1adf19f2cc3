//! Is a ranking real or noise? Monte Carlo summaries of each metric and a paired t-test of
//! the winner against the runner-up over the same replicates (Student 1908; the replicates
//! share data within a pair, so the paired test removes the common variation).

use serde::Serialize;
use statrs::distribution::{ContinuousCDF, Normal, StudentsT};
use statrs::function::gamma::ln_gamma;

/// Mean of a metric over replicates with the two-sided 95 % t-interval of the mean.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MeanInterval {
    /// Mean.
    pub mean: f64,
    /// Lower bound of the 95 % interval of the mean.
    pub low: f64,
    /// Upper bound.
    pub high: f64,
    /// Replicates.
    pub n: usize,
}

fn mean_and_sd(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (mean, var.sqrt())
}

/// The 97.5 % quantile of Student's t with `dof` degrees of freedom.
fn t_quantile_975(dof: f64) -> f64 {
    StudentsT::new(0.0, 1.0, dof).map_or(f64::NAN, |t| t.inverse_cdf(0.975))
}

/// Mean and 95 % t-interval of `values`; `None` for fewer than two values.
pub fn mean_interval(values: &[f64]) -> Option<MeanInterval> {
    if values.len() < 2 || values.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let (mean, sd) = mean_and_sd(values);
    let half = t_quantile_975(values.len() as f64 - 1.0) * sd / (values.len() as f64).sqrt();
    Some(MeanInterval {
        mean,
        low: mean - half,
        high: mean + half,
        n: values.len(),
    })
}

/// A paired two-sided t-test of the differences a − b.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PairedTest {
    /// Pairs.
    pub n: usize,
    /// Mean of a − b.
    pub mean_difference: f64,
    /// 95 % interval of the mean difference.
    pub ci95_difference: [f64; 2],
    /// t statistic.
    pub t: f64,
    /// Two-sided p-value.
    pub p_value: f64,
}

/// The paired t-test of `a` against `b`; `None` with fewer than two pairs, unequal lengths,
/// non-finite values, or identical pairs (zero spread).
pub fn paired_t_test(a: &[f64], b: &[f64]) -> Option<PairedTest> {
    if a.len() != b.len() || a.len() < 2 {
        return None;
    }
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    let interval = mean_interval(&d)?;
    let (mean, sd) = mean_and_sd(&d);
    let n = d.len() as f64;
    let t = mean / (sd / n.sqrt());
    // A zero or non-finite spread, or a non-finite t (sums that overflowed), has no p-value
    // (statrs' Student t panics on a NaN argument).
    if !(sd > 0.0 && t.is_finite()) {
        return None;
    }
    let dist = StudentsT::new(0.0, 1.0, n - 1.0).ok()?;
    Some(PairedTest {
        n: d.len(),
        mean_difference: mean,
        ci95_difference: [interval.low, interval.high],
        t,
        p_value: 2.0 * (1.0 - dist.cdf(t.abs())),
    })
}

impl PairedTest {
    /// The standardised mean difference (Cohen's d_z: the mean difference over the sd of the
    /// differences), t/√n.
    pub fn effect_size(&self) -> f64 {
        self.t / (self.n as f64).sqrt()
    }
}

/// Intervals of the Simpson rule over the scaled chi variable in [`paired_t_power`].
const POWER_INTERVALS: usize = 2000;

/// Power of the two-sided paired t-test at level `alpha` with `n` pairs when the true mean
/// difference is `effect_size` sds of the differences: P(|T| > t(1 − α/2, n − 1)) for T a
/// noncentral t with n − 1 degrees of freedom and noncentrality d·√n. With T = (Z + λ)/S,
/// S = sqrt(V/ν), V chi-square with ν degrees of freedom, the power is
/// E_S[Φ(λ − c·S) + Φ(−λ − c·S)], integrated over S's density by Simpson's rule.
/// `None` for fewer than two pairs, a non-finite effect or `alpha` outside (0, 1).
pub fn paired_t_power(effect_size: f64, n: usize, alpha: f64) -> Option<f64> {
    if n < 2 || !effect_size.is_finite() || !(alpha > 0.0 && alpha < 1.0) {
        return None;
    }
    let dof = (n - 1) as f64;
    let critical = StudentsT::new(0.0, 1.0, dof)
        .ok()?
        .inverse_cdf(1.0 - alpha / 2.0);
    let normal = Normal::standard();
    let lambda = effect_size * (n as f64).sqrt();
    let s_max = ((dof + 12.0 * (2.0 * dof).sqrt() + 40.0) / dof).sqrt();
    let h = s_max / POWER_INTERVALS as f64;
    let integrand = |s: f64| {
        let tails = normal.cdf(lambda - critical * s) + normal.cdf(-lambda - critical * s);
        tails * scaled_chi_density(s, dof)
    };
    let inner: f64 = (1..POWER_INTERVALS)
        .map(|k| integrand(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    let total = (integrand(0.0) + inner + integrand(s_max)) * h / 3.0;
    Some(total.clamp(0.0, 1.0))
}

/// Density of S = sqrt(V/ν), V chi-square with ν degrees of freedom, at s ≥ 0:
/// 2νs · f_V(νs²).
fn scaled_chi_density(s: f64, dof: f64) -> f64 {
    if s <= 0.0 {
        return if dof == 1.0 {
            (2.0 / std::f64::consts::PI).sqrt()
        } else {
            0.0
        };
    }
    let v = dof * s * s;
    let ln_v_density =
        (dof / 2.0 - 1.0) * v.ln() - v / 2.0 - (dof / 2.0) * 2f64.ln() - ln_gamma(dof / 2.0);
    2.0 * dof * s * ln_v_density.exp()
}

/// The fewest pairs (at most `max_pairs`) whose two-sided paired t-test at `alpha` reaches
/// `power` for an effect of `effect_size` sds of the differences; `None` when even
/// `max_pairs` do not, or for an effect of zero.
pub fn pairs_for_power(
    effect_size: f64,
    alpha: f64,
    power: f64,
    max_pairs: usize,
) -> Option<usize> {
    if effect_size == 0.0 {
        return None;
    }
    let enough = |n: usize| paired_t_power(effect_size, n, alpha).is_some_and(|p| p >= power);
    if !enough(max_pairs) {
        return None;
    }
    // The power grows with the pairs: bisect on n.
    let (mut low, mut high) = (1, max_pairs);
    while high - low > 1 {
        let mid = (low + high) / 2;
        if enough(mid) { high = mid } else { low = mid }
    }
    Some(high)
}

#[cfg(test)]
mod tests {
    use super::*;

    // Student's sleep data (Cushny & Peebles 1905), R's `t.test(extra ~ group, data = sleep,
    // paired = TRUE)`: t = -4.0621, df = 9, p-value = 0.002833, mean difference -1.58, 95 %
    // interval (-2.4598858, -0.7001142). R prints 4-5 significant digits; tolerances follow.
    #[test]
    fn paired_test_matches_r_on_the_sleep_data() {
        let g1 = [0.7, -1.6, -0.2, -1.2, -0.1, 3.4, 3.7, 0.8, 0.0, 2.0];
        let g2 = [1.9, 0.8, 1.1, 0.1, -0.1, 4.4, 5.5, 1.6, 4.6, 3.4];
        let test = paired_t_test(&g1, &g2).unwrap();
        assert!((test.t + 4.0621).abs() < 1e-4);
        assert!((test.p_value - 0.002833).abs() < 1e-6);
        assert!((test.mean_difference + 1.58).abs() < 1e-12);
        assert!((test.ci95_difference[0] + 2.4598858).abs() < 1e-6);
        assert!((test.ci95_difference[1] + 0.7001142).abs() < 1e-6);
        // R's sd(g1 - g2) = 1.229995 (7 digits): d_z = -1.58 / 1.229995.
        assert!((test.effect_size() + 1.58 / 1.229995).abs() < 1e-5);
        assert!(paired_t_test(&g1, &g1).is_none() && paired_t_test(&g1[..1], &g2[..1]).is_none());
    }

    // tools/oracles/paired_t_power.py: statsmodels 0.15.0 TTestPower (scipy's noncentral t).
    // Simpson's rule on 2000 intervals of a smooth density is good to about 1e-8 here; the
    // tolerance 1e-6 leaves room for the quantile's own accuracy.
    #[test]
    fn power_matches_statsmodels() {
        let oracle = [
            (0.5, 10, 0.05, 0.2931756065),
            (1.0, 8, 0.01, 0.3478113581),
            (1.5, 5, 0.01, 0.3125361499),
            (0.3, 60, 0.01, 0.3755547925),
            (2.5, 3, 0.01, 0.1784913696),
        ];
        for (d, n, alpha, expected) in oracle {
            let power = paired_t_power(d, n, alpha).unwrap();
            assert!((power - expected).abs() < 1e-6, "{d} {n} {alpha}: {power}");
            // The sign of the effect does not matter to a two-sided test.
            assert!((paired_t_power(-d, n, alpha).unwrap() - power).abs() < 1e-12);
        }
        // No effect: the power is the level.
        assert!((paired_t_power(0.0, 12, 0.05).unwrap() - 0.05).abs() < 1e-6);
    }

    // statsmodels' real-valued solutions of power(d, n, 0.01) = 0.8 (the same script): the
    // fewest whole pairs is the next integer above each.
    #[test]
    fn pairs_for_power_are_the_next_integer_above_statsmodels_solution() {
        let oracle = [
            (0.5, 50.064694),
            (0.8, 21.631044),
            (1.0, 15.080702),
            (1.5, 8.607852),
            (2.0, 6.306029),
            (3.0, 4.555636),
        ];
        for (d, n) in oracle {
            let expected = f64::ceil(n) as usize;
            assert_eq!(pairs_for_power(d, 0.01, 0.8, 1000), Some(expected), "{d}");
        }
        assert_eq!(pairs_for_power(0.05, 0.01, 0.8, 1000), None);
        assert_eq!(pairs_for_power(0.0, 0.01, 0.8, 1000), None);
    }
}
