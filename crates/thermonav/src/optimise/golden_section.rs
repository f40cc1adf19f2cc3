//! Golden-section search for the extremum of a unimodal function of one variable on a bracket
//! (Kiefer 1953): each step keeps the part of the bracket holding the better of two interior
//! points and reuses that point, so one evaluation shrinks the bracket by (√5 − 1)/2 ≈ 0.618.

use std::convert::Infallible;

/// The maximum of `f` on [lo, hi] by golden-section search, to an interval of `tolerance`:
/// (x, f(x), evaluations). `f` is taken to be unimodal on the bracket.
///
/// # Errors
/// The first error of `f`.
pub fn golden_section_maximum<E>(
    f: &mut dyn FnMut(f64) -> Result<f64, E>,
    lo: f64,
    hi: f64,
    tolerance: f64,
) -> Result<(f64, f64, usize), E> {
    search(f, lo, hi, Stop::Width(tolerance))
}

/// The minimum of `f` on [lo, hi] after `steps` golden-section steps (the bracket then
/// 0.618^steps of its width: 40 steps leave 4e-9 of it), the better of the last two interior
/// points. `f` is taken to be unimodal on the bracket.
pub fn golden_section_minimum(f: impl Fn(f64) -> f64, lo: f64, hi: f64, steps: usize) -> f64 {
    let Ok((x, _, _)) = search(
        &mut |x| Ok::<_, Infallible>(-f(x)),
        lo,
        hi,
        Stop::Steps(steps),
    );
    x
}

/// The most steps a search to a width takes (0.618^150 ≈ 3e-32).
const MAX_WIDTH_STEPS: usize = 150;

/// When a search stops.
#[derive(Debug, Clone, Copy)]
enum Stop {
    /// When the bracket is no wider than this.
    Width(f64),
    /// After this many steps (evaluations after the first two).
    Steps(usize),
}

impl Stop {
    /// Whether a search whose bracket is `width` wide after `steps` steps takes another.
    fn goes_on(self, width: f64, steps: usize) -> bool {
        match self {
            // Each step keeps 0.618 of the bracket: after MAX_WIDTH_STEPS it is below 1e-31 of
            // its width, past f64's resolution, so a tolerance of 0 (or NaN) still ends.
            Stop::Width(tolerance) => width > tolerance && steps < MAX_WIDTH_STEPS,
            Stop::Steps(last) => steps < last,
        }
    }
}

/// The maximum of `f` on [lo, hi] by golden sections until `stop`: (x, f(x), evaluations), x the
/// better of the last two interior points (the lower one on a tie).
fn search<E>(
    f: &mut dyn FnMut(f64) -> Result<f64, E>,
    lo: f64,
    hi: f64,
    stop: Stop,
) -> Result<(f64, f64, usize), E> {
    let ratio = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (lo, hi);
    let mut c = b - ratio * (b - a);
    let mut d = a + ratio * (b - a);
    let (mut fc, mut fd) = (f(c)?, f(d)?);
    let mut evaluations = 2;
    while stop.goes_on(b - a, evaluations - 2) {
        if fc >= fd {
            (b, d, fd) = (d, c, fc);
            c = b - ratio * (b - a);
            fc = f(c)?;
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + ratio * (b - a);
            fd = f(d)?;
        }
        evaluations += 1;
    }
    Ok(match fc >= fd {
        true => (c, fc, evaluations),
        false => (d, fd, evaluations),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    // A tolerance of 0 still ends: after MAX_WIDTH_STEPS steps the bracket is below f64's
    // resolution, and the point found is the parabola's maximum (0.123) to that resolution.
    #[test]
    fn a_zero_tolerance_search_ends_at_the_step_limit() {
        let mut f = |x: f64| Ok::<_, ()>(4.0 - (x - 0.123) * (x - 0.123));
        let (x, _, n) = golden_section_maximum(&mut f, -0.5, 0.5, 0.0).unwrap();
        assert_eq!(n, MAX_WIDTH_STEPS + 2);
        assert!((x - 0.123).abs() < 1e-7, "{x}");
    }

    // Oracle: a closed form. The maximum of −(x − 0.123)² + 4 on [−0.5, 0.5] is at 0.123; the
    // search's interval shrinks below its tolerance, so the error is below the tolerance.
    #[test]
    fn golden_section_finds_the_maximum_of_a_parabola() {
        let mut f = |x: f64| Ok::<_, ()>(4.0 - (x - 0.123) * (x - 0.123));
        let (x, fx, n) = golden_section_maximum(&mut f, -0.5, 0.5, 1e-6).unwrap();
        assert!((x - 0.123).abs() < 1e-6, "{x}");
        assert!((fx - 4.0).abs() < 1e-11, "{fx}");
        // ln(1e6)/ln(1.618) ≈ 28.7 shrinkings after the first two evaluations.
        assert!((29..=32).contains(&n), "{n}");
    }

    // A maximum at the bracket's end is found there (a bracket that is too small shows up as
    // an estimate on its edge).
    #[test]
    fn golden_section_on_a_monotone_function_ends_at_the_edge() {
        let mut f = |x: f64| Ok::<_, ()>(x);
        let (x, _, _) = golden_section_maximum(&mut f, -0.5, 0.5, 1e-4).unwrap();
        assert!((x - 0.5).abs() < 1e-4, "{x}");
    }

    // Closed form: the minimum of (x − 0.37)² + 1 on [0, 2] is at 0.37. After n steps the
    // bracket is 2 · 0.618^n wide and holds the minimum and the point returned: 2.5e-4 after
    // 20 steps, 4e-9 after 40 (the value's rounding, about 1e-8 in x for a value near 1, is
    // then what is left).
    #[test]
    fn golden_section_finds_the_minimum_of_a_parabola_in_steps() {
        let count = std::cell::Cell::new(0);
        let f = |x: f64| {
            count.set(count.get() + 1);
            (x - 0.37) * (x - 0.37) + 1.0
        };
        let ratio: f64 = (5f64.sqrt() - 1.0) / 2.0;
        let x = golden_section_minimum(f, 0.0, 2.0, 20);
        assert!((x - 0.37).abs() < 2.0 * ratio.powi(20), "{x}");
        assert_eq!(count.get(), 22);
        let x = golden_section_minimum(f, 0.0, 2.0, 40);
        assert!((x - 0.37).abs() < 2e-8, "{x}");
    }

    // The minimum in steps is the maximum of −f: the same points, so the same answer bit for
    // bit as the maximum search stopped at the width those steps reach.
    #[test]
    fn the_minimum_is_the_maximum_of_the_negated_function() {
        let f = |x: f64| (x - 0.3).powi(4) + 0.1 * x;
        let mut negated = |x: f64| Ok::<_, ()>(-f(x));
        let (at_width, _, n) = golden_section_maximum(&mut negated, -1.0, 1.0, 1e-6).unwrap();
        assert_eq!(golden_section_minimum(f, -1.0, 1.0, n - 2), at_width);
    }
}
