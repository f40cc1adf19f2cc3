//! Is a ranking real or noise? Monte Carlo summaries of each metric and a paired t-test of
//! the winner against the runner-up over the same replicates (Student 1908; the replicates
//! share data within a pair, so the paired test removes the common variation).

use serde::Serialize;
use statrs::distribution::{ContinuousCDF, StudentsT};

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
    if sd <= 0.0 {
        return None;
    }
    let n = d.len() as f64;
    let t = mean / (sd / n.sqrt());
    let dist = StudentsT::new(0.0, 1.0, n - 1.0).ok()?;
    Some(PairedTest {
        n: d.len(),
        mean_difference: mean,
        ci95_difference: [interval.low, interval.high],
        t,
        p_value: 2.0 * (1.0 - dist.cdf(t.abs())),
    })
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
        assert!(paired_t_test(&g1, &g1).is_none() && paired_t_test(&g1[..1], &g2[..1]).is_none());
    }
}
