//! Nelder-Mead minimisation in two dimensions (Nelder & Mead 1965, standard coefficients), each
//! iteration's candidates evaluated in one batch.

/// A function of two variables that can be evaluated at several points at once (for the noisy
/// Gauss-Markov likelihood, one multi-lane Kalman pass costs about what one point does).
pub trait Objective {
    /// The values at `points`, each what evaluating it alone gives.
    fn values<const N: usize>(&self, points: [[f64; 2]; N]) -> [f64; N];
}

/// A plain function as an [`Objective`], evaluated point by point.
pub struct PointByPoint<F>(pub F);

impl<F: Fn([f64; 2]) -> f64> Objective for PointByPoint<F> {
    fn values<const N: usize>(&self, points: [[f64; 2]; N]) -> [f64; N] {
        points.map(&self.0)
    }
}

/// Nelder-Mead minimisation in two dimensions (standard coefficients 1, 2, ½, ½), stopping when
/// the simplex's values agree to 1e-10 relative or after `max_iter` iterations.
///
/// Each iteration evaluates its four candidates (reflection, expansion, outside and inside
/// contraction) at once and then takes the standard decisions on them: the same decisions on
/// the same values as the standard method, so the same path and minimum, with one batch per
/// iteration (four evaluations that cost about one pass) instead of one to three evaluations
/// in a row.
pub fn nelder_mead(
    f: &impl Objective,
    start: [f64; 2],
    step: [f64; 2],
    max_iter: usize,
) -> [f64; 2] {
    let mut simplex = [
        start,
        [start[0] + step[0], start[1]],
        [start[0], start[1] + step[1]],
    ];
    let mut values = f.values(simplex);
    for _ in 0..max_iter {
        order(&mut simplex, &mut values);
        if settled(&values) {
            break;
        }
        let along = |t: f64| along_worst(&simplex, t);
        let candidates = [along(-1.0), along(-2.0), along(-0.5), along(0.5)];
        let [fr, fe, f_outside, f_inside] = f.values(candidates);
        let [reflected, expanded, outside, inside] = candidates;
        if fr < values[0] {
            (simplex[2], values[2]) = if fe < fr {
                (expanded, fe)
            } else {
                (reflected, fr)
            };
        } else if fr < values[1] {
            (simplex[2], values[2]) = (reflected, fr);
        } else {
            let (contracted, fc) = if fr < values[2] {
                (outside, f_outside)
            } else {
                (inside, f_inside)
            };
            if fc < values[2].min(fr) {
                (simplex[2], values[2]) = (contracted, fc);
            } else {
                shrink(&mut simplex, &mut values, f);
            }
        }
    }
    order(&mut simplex, &mut values);
    simplex[0]
}

fn order(simplex: &mut [[f64; 2]; 3], values: &mut [f64; 3]) {
    let mut idx = [0, 1, 2];
    idx.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    *simplex = idx.map(|i| simplex[i]);
    *values = idx.map(|i| values[i]);
}

fn shrink(simplex: &mut [[f64; 2]; 3], values: &mut [f64; 3], f: &impl Objective) {
    let shrunk = shrunk(simplex);
    [values[1], values[2]] = f.values(shrunk);
    [simplex[1], simplex[2]] = shrunk;
}

/// Whether an ordered simplex's values agree to 1e-10 relative (Nelder-Mead's stop).
fn settled(values: &[f64; 3]) -> bool {
    (values[2] - values[0]).abs() <= 1e-10 * values[0].abs().max(1.0)
}

/// The point at `t` along the line from the centroid of an ordered simplex's two best points
/// through its worst (t = −1 the reflection, −2 the expansion, ∓½ the contractions).
fn along_worst(simplex: &[[f64; 2]; 3], t: f64) -> [f64; 2] {
    let centroid = [
        (simplex[0][0] + simplex[1][0]) / 2.0,
        (simplex[0][1] + simplex[1][1]) / 2.0,
    ];
    [
        centroid[0] + t * (simplex[2][0] - centroid[0]),
        centroid[1] + t * (simplex[2][1] - centroid[1]),
    ]
}

/// The two other points of an ordered simplex moved halfway to the best.
fn shrunk(simplex: &[[f64; 2]; 3]) -> [[f64; 2]; 2] {
    let towards_best = |k: usize| {
        [
            (simplex[0][0] + simplex[k][0]) / 2.0,
            (simplex[0][1] + simplex[k][1]) / 2.0,
        ]
    };
    [towards_best(1), towards_best(2)]
}

/// Nelder-Mead as first written: one evaluation at a time, only those the method's
/// decisions ask for. The reference for [`nelder_mead`].
/// Also counts the steps taken: expansions, reflections, outside and inside contractions,
/// shrinks.
#[cfg(test)]
pub(crate) fn nelder_mead_reference(
    f: impl Fn([f64; 2]) -> f64,
    start: [f64; 2],
    step: [f64; 2],
    steps: &mut [usize; 5],
) -> [f64; 2] {
    let mut simplex = [
        start,
        [start[0] + step[0], start[1]],
        [start[0], start[1] + step[1]],
    ];
    let mut values = simplex.map(&f);
    for _ in 0..400 {
        order(&mut simplex, &mut values);
        if settled(&values) {
            break;
        }
        let along = |t: f64| along_worst(&simplex, t);
        let reflected = along(-1.0);
        let fr = f(reflected);
        if fr < values[0] {
            let expanded = along(-2.0);
            let fe = f(expanded);
            steps[usize::from(fe >= fr)] += 1;
            (simplex[2], values[2]) = if fe < fr {
                (expanded, fe)
            } else {
                (reflected, fr)
            };
        } else if fr < values[1] {
            steps[1] += 1;
            (simplex[2], values[2]) = (reflected, fr);
        } else {
            let contracted = if fr < values[2] {
                along(-0.5)
            } else {
                along(0.5)
            };
            let fc = f(contracted);
            if fc < values[2].min(fr) {
                steps[if fr < values[2] { 2 } else { 3 }] += 1;
                (simplex[2], values[2]) = (contracted, fc);
            } else {
                steps[4] += 1;
                [simplex[1], simplex[2]] = shrunk(&simplex);
                values[1] = f(simplex[1]);
                values[2] = f(simplex[2]);
            }
        }
    }
    order(&mut simplex, &mut values);
    simplex[0]
}

#[cfg(test)]
mod tests {
    use super::*;

    // The batched method takes the reference's path: the same minimum, bit for bit, on
    // Rosenbrock's valley and on |x| + 2|y| (whose kinks force shrinks) from three starts each;
    // every kind of step is taken along the way. (`stoch::noisy_gauss_markov` checks the same on
    // its likelihood, through multi-lane passes.)
    #[test]
    fn nelder_mead_in_batches_is_the_standard_method() {
        let rosenbrock = |p: [f64; 2]| (1.0 - p[0]).powi(2) + 100.0 * (p[1] - p[0] * p[0]).powi(2);
        let kinked = |p: [f64; 2]| p[0].abs() + 2.0 * p[1].abs();
        let mut steps = [0; 5];
        for start in [[-1.2, 1.0], [2.0, -1.5], [0.0, 0.0]] {
            let batched = nelder_mead(&PointByPoint(rosenbrock), start, [0.5, 0.5], 400);
            let reference = nelder_mead_reference(rosenbrock, start, [0.5, 0.5], &mut steps);
            assert_eq!(batched, reference, "{start:?}");
            let batched = nelder_mead(&PointByPoint(kinked), start, [0.5, 0.5], 400);
            let reference = nelder_mead_reference(kinked, start, [0.5, 0.5], &mut steps);
            assert_eq!(batched, reference, "{start:?}");
        }
        assert!(steps.iter().all(|&n| n > 0), "steps taken {steps:?}");
    }

    // Closed forms: Rosenbrock's valley (1 − x)² + 100 (y − x²)² has its minimum 0 at (1, 1),
    // and 2 + (x − 1.5)² + 3 (y + 0.25)² its minimum 2 at (1.5, −0.25). The stop (values within
    // 1e-10) leaves a point whose value is within about 1e-10 of the minimum: within
    // √(1e-10 / 0.2) ≈ 2e-5 of it along Rosenbrock's flattest direction (curvature about 0.4
    // at (1, 1)), within √(1e-10) = 1e-5 for the quadratic; 1e-4 asked of both.
    #[test]
    fn nelder_mead_finds_closed_form_minima() {
        let rosenbrock = |p: [f64; 2]| (1.0 - p[0]).powi(2) + 100.0 * (p[1] - p[0] * p[0]).powi(2);
        let quadratic = |p: [f64; 2]| 2.0 + (p[0] - 1.5).powi(2) + 3.0 * (p[1] + 0.25).powi(2);
        for start in [[-1.2, 1.0], [2.0, -1.5], [0.0, 0.0]] {
            let [x, y] = nelder_mead(&PointByPoint(rosenbrock), start, [0.5, 0.5], 400);
            assert!(
                (x - 1.0).abs() < 1e-4 && (y - 1.0).abs() < 1e-4,
                "{start:?}: {x} {y}"
            );
            let [x, y] = nelder_mead(&PointByPoint(quadratic), start, [0.5, 0.5], 400);
            assert!(
                (x - 1.5).abs() < 1e-4 && (y + 0.25).abs() < 1e-4,
                "{start:?}: {x} {y}"
            );
        }
    }
}
