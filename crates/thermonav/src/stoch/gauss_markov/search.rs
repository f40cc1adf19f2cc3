//! One-dimensional searches used by the likelihood fit: golden-section maximisation inside a
//! bracket and a bracketed (Illinois regula falsi) search for a level crossing. Both evaluate only function values, tolerate
//! `-inf` (treated as "very low"), and always return a point inside the given interval.

/// The golden ratio conjugate `(sqrt 5 - 1) / 2`.
const INVERSE_GOLDEN_RATIO: f64 = 0.618_033_988_749_894_9;

/// Bound on iterations of both searches (golden section shrinks the interval by 0.618 per
/// step; the crossing search converges superlinearly and falls back on halving).
const MAX_ITERATIONS: usize = 200;

/// A point and the function value there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Peak {
    pub x: f64,
    pub value: f64,
}

/// Maximum of `f` on `[a, b]` by golden-section search, to an interval width below
/// `tolerance`. `f` should be unimodal on `[a, b]`; otherwise a local maximum is returned.
pub(crate) fn golden_section_max(
    mut f: impl FnMut(f64) -> f64,
    mut a: f64,
    mut b: f64,
    tolerance: f64,
) -> Peak {
    let mut c = b - INVERSE_GOLDEN_RATIO * (b - a);
    let mut d = a + INVERSE_GOLDEN_RATIO * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..MAX_ITERATIONS {
        if (b - a).abs() <= tolerance {
            break;
        }
        if fc >= fd {
            (b, d, fd) = (d, c, fc);
            c = b - INVERSE_GOLDEN_RATIO * (b - a);
            fc = f(c);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + INVERSE_GOLDEN_RATIO * (b - a);
            fd = f(d);
        }
    }
    if fc >= fd {
        Peak { x: c, value: fc }
    } else {
        Peak { x: d, value: fd }
    }
}

/// The point between `inside` (where `f >= level`) and `outside` (where `f < level`) at which
/// `f` crosses `level`, to a bracket width or step below `tolerance`. The two points may be
/// given in either order on the axis. Regula falsi with the Illinois modification (the
/// retained end's value is halved when the same end is kept twice), which converges
/// superlinearly for smooth `f`; a bisection step is taken whenever the secant point is not
/// strictly inside the bracket (for example when `f` is `-inf` at an end).
pub(crate) fn find_crossing(
    mut f: impl FnMut(f64) -> f64,
    mut inside: f64,
    mut outside: f64,
    level: f64,
    tolerance: f64,
) -> f64 {
    let mut g_inside = f(inside) - level;
    let mut g_outside = f(outside) - level;
    let mut kept = Kept::Neither;
    let mut previous = inside;
    for _ in 0..MAX_ITERATIONS {
        let point = secant_or_midpoint(inside, outside, g_inside, g_outside);
        if (outside - inside).abs() <= tolerance || (point - previous).abs() <= 0.5 * tolerance {
            return point;
        }
        previous = point;
        let g = f(point) - level;
        if g >= 0.0 {
            inside = point;
            g_inside = g;
            if kept == Kept::Outside {
                g_outside *= 0.5;
            }
            kept = Kept::Outside;
        } else {
            outside = point;
            g_outside = g;
            if kept == Kept::Inside {
                g_inside *= 0.5;
            }
            kept = Kept::Inside;
        }
    }
    0.5 * (inside + outside)
}

/// Which end of the bracket the last step kept.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kept {
    Neither,
    Inside,
    Outside,
}

/// The zero of the secant through the bracket ends, or the midpoint when that zero is not
/// strictly inside the bracket or not finite.
fn secant_or_midpoint(a: f64, b: f64, ga: f64, gb: f64) -> f64 {
    let secant = (a * gb - b * ga) / (gb - ga);
    let (low, high) = (a.min(b), a.max(b));
    if secant > low && secant < high {
        secant
    } else {
        0.5 * (a + b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn golden_section_finds_the_vertex_of_a_parabola() {
        // Closed form: -(x - 0.3)^2 peaks at 0.3; tolerance 1e-12 on the bracket width, and a
        // parabola's peak is located to ~sqrt(eps) by function values, hence 1e-7.
        let peak = golden_section_max(|x| -(x - 0.3) * (x - 0.3), -2.0, 5.0, 1e-12);
        assert!((peak.x - 0.3).abs() < 1e-7, "{peak:?}");
        assert!(peak.value <= 0.0 && peak.value > -1e-14);
    }

    #[test]
    fn golden_section_handles_minus_infinity_on_one_side() {
        // ln(x) - x peaks at x = 1 (closed form); -inf for x <= 0 must only push the search right.
        let f = |x: f64| {
            if x > 0.0 {
                x.ln() - x
            } else {
                f64::NEG_INFINITY
            }
        };
        let peak = golden_section_max(f, -1.0, 4.0, 1e-12);
        assert!((peak.x - 1.0).abs() < 1e-7, "{peak:?}");
    }

    #[test]
    fn the_level_crossing_is_found_from_either_side() {
        // exp(-x) = 0.25 at x = ln 4 (closed form); the search is exact to its tolerance.
        let f = |x: f64| (-x).exp();
        let x = find_crossing(f, 0.0, 3.0, 0.25, 1e-13);
        assert!((x - 4f64.ln()).abs() < 1e-12);
        // exp(x) = 0.25 at x = -ln 4, with the inside point on the right.
        let x = find_crossing(|x: f64| x.exp(), 0.0, -3.0, 0.25, 1e-13);
        assert!((x + 4f64.ln()).abs() < 1e-12);
    }
}

#[cfg(test)]
mod crossing_tests {
    use super::*;

    #[test]
    fn crossing_search_survives_minus_infinity_and_converges_fast() {
        // ln(x) = -1 at x = 1/e (closed form), with f = -inf at the outside end x = 0.
        let mut calls = 0;
        let f = |x: f64| {
            calls += 1;
            if x > 0.0 { x.ln() } else { f64::NEG_INFINITY }
        };
        let x = find_crossing(f, 2.0, 0.0, -1.0, 1e-13);
        assert!((x - (-1.0_f64).exp()).abs() < 1e-12, "{x}");
        // Bisection alone would need ~45 evaluations for 1e-13 from a width of 2.
        assert!(calls < 30, "{calls} evaluations");
    }
}
