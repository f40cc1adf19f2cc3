//! Newton's method for the maximum of a smooth function of one variable, its slope and curvature
//! from central differences of three values taken together.

/// The maximum of a smooth concave-near-its-top `f` by Newton steps from central differences,
/// `f` taken at three points a call (x − h, x, x + h: for the noisy Gauss-Markov likelihood one
/// multi-lane pass, which costs what one point does). Stops when the parabola through the three
/// predicts a rise of at most `tolerance` above the best value seen, and returns that point and
/// value (a value `f` took, so never above the maximum). Where the three are not concave it
/// steps the longest step uphill. `None` (the caller then searches otherwise) when a point
/// would leave `bracket`, a value is not finite, or 12 steps do not settle.
///
/// The spacing h starts at 0.05 and follows the last step's length, kept in [1e-3, 0.05]: the
/// differences' truncation error (h² f‴/6 in the slope) then shrinks with the step, while the
/// three values stay far enough apart for their rounding (about 1e-9 on a log-likelihood of
/// 1e5) to matter little.
pub fn newton_maximum(
    f: impl Fn([f64; 3]) -> [f64; 3],
    bracket: [f64; 2],
    start: f64,
    tolerance: f64,
) -> Option<(f64, f64)> {
    const MAX_STEP: f64 = 1.0;
    let (mut centre, mut h) = (start, 0.05_f64);
    let mut best = (start, f64::NEG_INFINITY);
    for _ in 0..12 {
        let points = [centre - h, centre, centre + h];
        if points[0] < bracket[0] || points[2] > bracket[1] {
            return None;
        }
        let values = f(points);
        if !values.iter().all(|v| v.is_finite()) {
            return None;
        }
        for (x, value) in points.into_iter().zip(values) {
            if value > best.1 {
                best = (x, value);
            }
        }
        let [below, at, above] = values;
        let curvature = (above - 2.0 * at + below) / (h * h);
        let slope = (above - below) / (2.0 * h);
        let step = if curvature < 0.0 {
            let peak = at - 0.5 * slope * slope / curvature;
            if peak - best.1 <= tolerance {
                return Some(best);
            }
            (-slope / curvature).clamp(-MAX_STEP, MAX_STEP)
        } else {
            // Not concave here (the maximum is further off): the longest step uphill.
            MAX_STEP.copysign(slope)
        };
        centre += step;
        h = step.abs().clamp(1e-3, 0.05);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    // Closed forms, as for Brent: the quartic's maximum 0 at 1.234 and x e^{−x}'s 1/e at 1, each
    // returned within the 1e-9 asked of the maximum and 1e-4 of its place, in a few calls (the
    // skewed one from a start where it is convex); a convex function and a maximum outside the
    // bracket, whose uphill steps leave it, are refused.
    #[test]
    fn newton_finds_the_maximum_in_few_calls() {
        let calls = std::cell::Cell::new(0);
        let three = |f: fn(f64) -> f64| {
            let calls = &calls;
            move |x: [f64; 3]| {
                calls.set(calls.get() + 1);
                x.map(f)
            }
        };
        let quartic: fn(f64) -> f64 = |x| -(x - 1.234).powi(2) - (x - 1.234).powi(4);
        let (x, value) = newton_maximum(three(quartic), [-3.0, 5.0], 0.5, 1e-9).unwrap();
        assert!(value > -1e-9 && (x - 1.234).abs() < 1e-4, "{x} {value}");
        assert!(calls.get() <= 8, "{} calls", calls.get());
        calls.set(0);
        let skewed: fn(f64) -> f64 = |x| x * (-x).exp();
        let (x, value) = newton_maximum(three(skewed), [0.0, 7.0], 3.5, 1e-9).unwrap();
        let top = (-1.0f64).exp();
        assert!(value > top - 1e-9 && (x - 1.0).abs() < 1e-4, "{x} {value}");
        // Two uphill steps out of the convex part (x > 2), then Newton's.
        assert!(calls.get() <= 10, "{} calls", calls.get());
        let convex: fn(f64) -> f64 = |x| x * x;
        assert_eq!(newton_maximum(three(convex), [-3.0, 3.0], 0.5, 1e-9), None);
        let rising: fn(f64) -> f64 = |x| x - 0.01 * x * x;
        assert_eq!(newton_maximum(three(rising), [-3.0, 3.0], 0.0, 1e-9), None);
    }
}
