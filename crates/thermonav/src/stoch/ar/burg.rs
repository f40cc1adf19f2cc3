//! Burg's method (Burg 1968; Kay 1988, §7.4). Two implementations of the same estimator:
//!
//! - [`burg`] (used): the forward and backward error powers of every order are quadratic forms
//!   of the windowed covariance matrix R_ij = Σ_{t=m+1}^{N−1} x_{t−i} x_{t−j}, which is the
//!   Toeplitz autocorrelation r(|i−j|) minus a few products at the two ends (Vos 2013, "A fast
//!   implementation of Burg's method"). One pass over the data computes r(0..p); the recursion
//!   then costs O(p⁴), independent of N.
//! - the lattice recursion below (the textbook form, kept as the reference the fast one is
//!   tested against): at each order the reflection coefficient minimises the sum of forward and
//!   backward prediction-error powers,
//!   k_m = 2 Σ f_{m−1}(t) b_{m−1}(t−1) / Σ (f_{m−1}(t)² + b_{m−1}(t−1)²), t = m..N−1
//!   (paper sign), then f_m(t) = f_{m−1}(t) − k_m b_{m−1}(t−1),
//!   b_m(t) = b_{m−1}(t−1) − k_m f_{m−1}(t), and the coefficients follow the Levinson update.
//!   O(N p) time, O(N) memory.

use super::{ArError, ArMethod, ArModel};
#[cfg(test)]
use crate::stoch::acf::lagged_products;

#[cfg(test)]
pub(super) fn burg_lattice(centred: &[f64], order: usize) -> Result<ArModel, ArError> {
    let n = centred.len();
    let mut forward = centred.to_vec();
    let mut backward = centred.to_vec();
    let mut c: Vec<f64> = Vec::with_capacity(order);
    let mut reflection = Vec::with_capacity(order);
    let mut levinson = centred.iter().map(|v| v * v).sum::<f64>() / n as f64;
    // Sums for order 1, over t = 1..N−1 of f(t) b(t−1), f(t)² + b(t−1)².
    let (mut num, mut den) = next_sums(&forward, &backward, 1);
    let mut last_power = 0.0;
    for m in 1..=order {
        if den <= 0.0 {
            return Err(ArError::Constant);
        }
        let k = 2.0 * num / den;
        // One fused pass: update f and b in place (walking down, so that backward[t − 1] is still
        // the previous order's value) and accumulate both the final error power and the next
        // order's sums over t = m+1..N−1, which use f_m(t) and b_m(t − 1).
        let (mut power, mut next_num, mut next_den) = (0.0, 0.0, 0.0);
        for t in (m..n).rev() {
            let (f, b) = (forward[t], backward[t - 1]);
            let f_new = f - k * b;
            let b_new = b - k * f;
            forward[t] = f_new;
            backward[t] = b_new;
            power += f_new * f_new + b_new * b_new;
            if t + 1 < n {
                // b_m(t) pairs with f_m(t + 1), already updated in the previous iteration.
                next_num += forward[t + 1] * b_new;
                next_den += forward[t + 1] * forward[t + 1] + b_new * b_new;
            }
        }
        let previous = c.clone();
        for i in 0..c.len() {
            c[i] = previous[i] - k * previous[m - 2 - i];
        }
        c.push(k);
        reflection.push(k);
        levinson *= 1.0 - k * k;
        last_power = power;
        (num, den) = (next_num, next_den);
    }
    Ok(ArModel {
        method: ArMethod::Burg,
        coefficients: c,
        noise_variance: last_power / (2.0 * (n - order) as f64),
        levinson_variance: Some(levinson),
        reflection: Some(reflection),
        std_errors: Vec::new(),
        n_samples: n,
        mean: 0.0,
    })
}

/// Σ f(t) b(t−1) and Σ f(t)² + b(t−1)² over t = m..N−1.
#[cfg(test)]
fn next_sums(forward: &[f64], backward: &[f64], m: usize) -> (f64, f64) {
    (m..forward.len()).fold((0.0, 0.0), |(num, den), t| {
        let (f, b) = (forward[t], backward[t - 1]);
        (num + f * b, den + f * f + b * b)
    })
}

/// Σ_{t=start}^{N−1} y_{t−i} y_{t−j} for i, j < size, from the full-range products r(k) with
/// the end terms removed; y = x − mean.
fn window_covariance(x: &[f64], mean: f64, r: &[f64], start: usize, size: usize) -> Vec<Vec<f64>> {
    let n = x.len();
    let y = |s: usize| x[s] - mean;
    let entry = |i: usize, j: usize| {
        let (i, j) = (i.min(j), i.max(j));
        let k = j - i;
        // t − j runs over [start − j, N − 1 − j]; the full range of lag k is [0, N − 1 − k].
        let head: f64 = (0..start - j).map(|s| y(s) * y(s + k)).sum();
        let tail: f64 = (n - j..n - k).map(|s| y(s) * y(s + k)).sum();
        r[k] - head - tail
    };
    (0..size)
        .map(|i| (0..size).map(|j| entry(i, j)).collect())
        .collect()
}

fn quadratic(m: &[Vec<f64>], u: &[f64], v: &[f64]) -> f64 {
    u.iter()
        .enumerate()
        .map(|(i, ui)| {
            ui * v
                .iter()
                .enumerate()
                .map(|(j, vj)| m[i][j] * vj)
                .sum::<f64>()
        })
        .sum()
}

/// Burg's estimate from the lagged products r(0..=p) of `x` − `mean` (one pass over the data,
/// done by the caller) and the first and last p samples.
pub(super) fn burg(x: &[f64], mean: f64, r: &[f64], order: usize) -> Result<ArModel, ArError> {
    let n = x.len();
    let mut a = vec![1.0]; // A-polynomial, a_0 = 1
    let mut reflection = Vec::with_capacity(order);
    let mut levinson = r[0] / n as f64;
    for m in 0..order {
        let cov = window_covariance(x, mean, r, m + 1, m + 2);
        let u: Vec<f64> = a.iter().copied().chain([0.0]).collect();
        let v: Vec<f64> = [0.0].into_iter().chain(a.iter().rev().copied()).collect();
        let den = quadratic(&cov, &u, &u) + quadratic(&cov, &v, &v);
        if den.is_nan() || den <= 0.0 {
            return Err(ArError::Constant);
        }
        let k = -2.0 * quadratic(&cov, &u, &v) / den;
        a = u.iter().zip(&v).map(|(ui, vi)| ui + k * vi).collect();
        reflection.push(-k);
        levinson *= 1.0 - k * k;
    }
    let cov = window_covariance(x, mean, r, order, order + 1);
    let reversed: Vec<f64> = a.iter().rev().copied().collect();
    let power = quadratic(&cov, &a, &a) + quadratic(&cov, &reversed, &reversed);
    Ok(ArModel {
        method: ArMethod::Burg,
        coefficients: a[1..].iter().map(|v| -v).collect(),
        noise_variance: power / (2.0 * (n - order) as f64),
        levinson_variance: Some(levinson),
        reflection: Some(reflection),
        std_errors: Vec::new(),
        n_samples: n,
        mean,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::named_rng;
    use rand_distr::{Distribution, StandardNormal};

    // The one-pass form against the lattice recursion (same estimator, two algorithms) on an
    // AR(3) series and on a strongly correlated one (c1 ≈ 0.999, where the quadratic forms
    // cancel most): 1e-9 on coefficients and relative variances.
    #[test]
    fn fast_burg_equals_the_lattice_recursion() {
        for (phi, name) in [([0.6, -0.3, 0.1], "ar3"), ([0.999, 0.0, 0.0], "near-unit")] {
            let mut rng = named_rng(21, name);
            let mut x = vec![0.0; 20_000];
            for t in 3..x.len() {
                let z: f64 = StandardNormal.sample(&mut rng);
                x[t] = phi[0] * x[t - 1]
                    + phi[1] * x[t - 2]
                    + phi[2] * x[t - 3]
                    + z
                    + 5.0 * (1.0 - phi.iter().sum::<f64>());
            }
            let mean = x.iter().sum::<f64>() / x.len() as f64;
            let centred: Vec<f64> = x.iter().map(|v| v - mean).collect();
            for order in [1, 3, 8] {
                let fast = burg(&x, mean, &lagged_products(&x, mean, order), order).unwrap();
                let slow = burg_lattice(&centred, order).unwrap();
                for (a, b) in fast.coefficients.iter().zip(&slow.coefficients) {
                    assert!((a - b).abs() < 1e-9, "{name} order {order}: {a} vs {b}");
                }
                assert!(
                    (fast.noise_variance / slow.noise_variance - 1.0).abs() < 1e-9,
                    "{name} variance"
                );
                assert!(
                    (fast.levinson_variance.unwrap() / slow.levinson_variance.unwrap() - 1.0).abs()
                        < 1e-9
                );
            }
        }
    }
}
