//! Burg's method (Burg 1968; Kay 1988, §7.4): at each order the reflection coefficient
//! minimises the sum of forward and backward prediction-error powers,
//! k_m = 2 Σ f_{m−1}(t) b_{m−1}(t−1) / Σ (f_{m−1}(t)² + b_{m−1}(t−1)²), t = m..N−1
//! (paper sign), then f_m(t) = f_{m−1}(t) − k_m b_{m−1}(t−1), b_m(t) = b_{m−1}(t−1) − k_m f_{m−1}(t),
//! and the coefficients follow the Levinson update. O(N p) time, O(N) memory.

use super::{ArError, ArMethod, ArModel};

pub(super) fn burg(centred: &[f64], order: usize) -> Result<ArModel, ArError> {
    let n = centred.len();
    let mut forward = centred.to_vec();
    let mut backward = centred.to_vec();
    let mut c: Vec<f64> = Vec::with_capacity(order);
    let mut reflection = Vec::with_capacity(order);
    let mut levinson = centred.iter().map(|v| v * v).sum::<f64>() / n as f64;
    let mut last_power = 0.0;
    for m in 1..=order {
        let (mut num, mut den) = (0.0, 0.0);
        for t in m..n {
            num += forward[t] * backward[t - 1];
            den += forward[t] * forward[t] + backward[t - 1] * backward[t - 1];
        }
        if den <= 0.0 {
            return Err(ArError::Constant);
        }
        let k = 2.0 * num / den;
        // Update in place, walking down so that backward[t − 1] is still the old value.
        let mut power = 0.0;
        for t in (m..n).rev() {
            let (f, b) = (forward[t], backward[t - 1]);
            forward[t] = f - k * b;
            backward[t] = b - k * f;
            power += forward[t] * forward[t] + backward[t] * backward[t];
        }
        let previous = c.clone();
        for i in 0..c.len() {
            c[i] = previous[i] - k * previous[m - 2 - i];
        }
        c.push(k);
        reflection.push(k);
        levinson *= 1.0 - k * k;
        last_power = power;
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
