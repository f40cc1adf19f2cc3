//! The legs of a temperature sweep and its rate of change.
//!
//! # Legs
//! A leg is a stretch between turning points of the temperature smoothed over
//! [`LEG_SMOOTHING_S`] (a centred moving average of every sample within ±30 s). A turning point
//! is an extreme that the smoothed temperature has since left by at least [`LEG_REVERSAL_C`]:
//! a running maximum (while warming) or minimum (while cooling) is confirmed as a turning point
//! once the temperature has come back from it by 1 °C; before the first one, the first extreme
//! to be left by 1 °C is the first turning point. The record's first and last samples end the
//! first and last legs. A leg whose smoothed temperature spans less than [`LEG_MIN_SPAN_C`] is
//! merged into a neighbour: the leg of the smallest span first, into the neighbour of the
//! smaller span (the earlier one on a tie), until every leg spans 3 °C or only one is left;
//! then neighbours that run the same way (warming or cooling, by the sign of end minus start)
//! are joined.
//!
//! # Rate
//! The rate of change at a sample is the least-squares slope of the raw temperature against
//! time over the samples within ±[`RATE_WINDOW_S`]/2 of it (fewer at the record's ends), °C/s:
//! a stated smoothing that takes the sensor's quantisation steps out.

use serde::{Deserialize, Serialize};

/// The thermal lag is searched within ±this, s.
pub const LAG_SEARCH_S: f64 = 3600.0;

/// The lags at which each block's lagged temperature is computed from its samples (s,
/// increasing, within ±[`LAG_SEARCH_S`]): the profile's grid; between them the block's value is
/// interpolated.
pub const LAG_GRID_S: [f64; 2 * LAG_MAGNITUDES.len() + 1] = {
    let n = LAG_MAGNITUDES.len();
    let mut grid = [0.0; 2 * LAG_MAGNITUDES.len() + 1];
    let mut k = 0;
    while k < n {
        grid[n - 1 - k] = -LAG_MAGNITUDES[k];
        grid[n + 1 + k] = LAG_MAGNITUDES[k];
        k += 1;
    }
    grid
};

/// |τ| of the grid, s: 10 s apart to 300 s, 25 s to 600 s, 100 s to 1200 s, then coarser.
const LAG_MAGNITUDES: [f64; 53] = {
    let mut m = [0.0; 53];
    let mut k = 0;
    while k < 30 {
        m[k] = 10.0 * (k + 1) as f64;
        k += 1;
    }
    while k < 42 {
        m[k] = 300.0 + 25.0 * (k - 29) as f64;
        k += 1;
    }
    while k < 48 {
        m[k] = 600.0 + 100.0 * (k - 41) as f64;
        k += 1;
    }
    let tail = [1500.0, 1800.0, 2400.0, 3000.0, 3600.0];
    while k < 53 {
        m[k] = tail[k - 48];
        k += 1;
    }
    m
};

/// Width of the centred moving average the legs are found on, s.
pub const LEG_SMOOTHING_S: f64 = 60.0;

/// How far the smoothed temperature must come back from an extreme for it to be a turning
/// point, °C.
pub const LEG_REVERSAL_C: f64 = 1.0;

/// A leg spanning less than this is merged into a neighbour, °C.
pub const LEG_MIN_SPAN_C: f64 = 3.0;

/// Width of the window of the least-squares rate, s.
pub const RATE_WINDOW_S: f64 = 120.0;

/// Which way a leg runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LegDirection {
    /// The temperature rises over the leg.
    Warming,
    /// It falls.
    Cooling,
}

/// One leg of a sweep: samples `start..end` (end exclusive).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Leg {
    /// First sample.
    pub start: usize,
    /// One past the last sample.
    pub end: usize,
    /// Smoothed temperature at the first and last sample, °C.
    pub temperature_c: [f64; 2],
    /// Span of the smoothed temperature over the leg (largest minus smallest), °C.
    pub span_c: f64,
    /// Which way it runs.
    pub direction: LegDirection,
}

/// For every sample, the range [lo, hi) of samples within ±`half_s` of its time (`time_s`
/// non-decreasing).
fn centred_windows(time_s: &[f64], half_s: f64) -> Vec<(usize, usize)> {
    let (mut lo, mut hi) = (0, 0);
    (0..time_s.len())
        .map(|k| {
            while time_s[lo] < time_s[k] - half_s {
                lo += 1;
            }
            while hi < time_s.len() && time_s[hi] <= time_s[k] + half_s {
                hi += 1;
            }
            (lo, hi)
        })
        .collect()
}

/// The centred moving average of `values` over samples within ±`width_s`/2 of each sample's
/// time (`time_s` non-decreasing).
pub fn centred_mean(time_s: &[f64], values: &[f64], width_s: f64) -> Vec<f64> {
    let n = time_s.len().min(values.len());
    let prefix = prefix_sums(values[..n].iter().copied());
    centred_windows(&time_s[..n], width_s / 2.0)
        .into_iter()
        .map(|(lo, hi)| (prefix[hi] - prefix[lo]) / (hi - lo) as f64)
        .collect()
}

/// Running sums 0, x_0, x_0 + x_1, ….
fn prefix_sums(values: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut sums = vec![0.0];
    let mut sum = 0.0;
    for v in values {
        sum += v;
        sums.push(sum);
    }
    sums
}

/// The least-squares rate of the temperature at every sample (module docs, "Rate"), °C/s; zero
/// where the window holds one distinct time.
pub fn temperature_rates(time_s: &[f64], temperature_c: &[f64], window_s: f64) -> Vec<f64> {
    let n = time_s.len().min(temperature_c.len());
    let (time_s, temperature_c) = (&time_s[..n], &temperature_c[..n]);
    let Some(&t0) = time_s.first() else {
        return Vec::new();
    };
    // Times from the first sample keep the sums' cancellation small.
    let t: Vec<f64> = time_s.iter().map(|x| x - t0).collect();
    let st = prefix_sums(t.iter().copied());
    let stt = prefix_sums(t.iter().map(|x| x * x));
    let sy = prefix_sums(temperature_c.iter().copied());
    let sty = prefix_sums(t.iter().zip(temperature_c).map(|(x, y)| x * y));
    centred_windows(&t, window_s / 2.0)
        .into_iter()
        .map(|(lo, hi)| {
            let n = (hi - lo) as f64;
            // Centred sums: Sxx = Σt² − (Σt)²/n, Sxy = Σty − Σt Σy / n.
            let (sum_t, sum_y) = (st[hi] - st[lo], sy[hi] - sy[lo]);
            let sxx = stt[hi] - stt[lo] - sum_t * sum_t / n;
            let sxy = sty[hi] - sty[lo] - sum_t * sum_y / n;
            if hi - lo >= 2 && sxx > 0.0 {
                sxy / sxx
            } else {
                0.0
            }
        })
        .collect()
}

/// The temperature of a structure that follows the sensor's through a first-order lag,
/// dT_s/dt = (T − T_s)/|τ|, for τ < 0 (the structure lags); for τ > 0 its mirror 2T − T_s (the
/// structure leads); T itself for τ = 0. T is taken as linear between samples, for which the
/// step is exact: with m the slope over the interval and a = exp(−dt/|τ|),
/// T_s,k = T_k − |τ|m + (T_s,k−1 − T_k−1 + |τ|m)·a. The structure starts at the first sample's
/// temperature (a unit that sat still before the record).
pub fn lagged_temperatures(time_s: &[f64], temperature_c: &[f64], tau_s: f64) -> Vec<f64> {
    let n = time_s.len().min(temperature_c.len());
    if tau_s == 0.0 || n == 0 {
        return temperature_c[..n].to_vec();
    }
    let lag = tau_s.abs();
    let mut out = Vec::with_capacity(n);
    let mut s = temperature_c[0];
    out.push(s);
    // The decay of the last interval, kept while the interval repeats (a steady rate).
    let (mut last_dt, mut a) = (f64::NAN, 0.0);
    for k in 1..n {
        let dt = time_s[k] - time_s[k - 1];
        let (t0, t1) = (temperature_c[k - 1], temperature_c[k]);
        if dt > 0.0 {
            if dt != last_dt {
                (last_dt, a) = (dt, (-dt / lag).exp());
            }
            let m = (t1 - t0) / dt;
            s = t1 - lag * m + (s - t0 + lag * m) * a;
        }
        out.push(s);
    }
    if tau_s > 0.0 {
        for (s, t) in out.iter_mut().zip(temperature_c) {
            *s = 2.0 * t - *s;
        }
    }
    out
}

/// The legs of a sweep (module docs, "Legs"); one leg for a record without a turning point,
/// none for an empty one.
pub fn find_legs(time_s: &[f64], temperature_c: &[f64]) -> Vec<Leg> {
    let n = time_s.len().min(temperature_c.len());
    let (time_s, temperature_c) = (&time_s[..n], &temperature_c[..n]);
    if n == 0 {
        return Vec::new();
    }
    let smooth = centred_mean(time_s, temperature_c, LEG_SMOOTHING_S);
    let mut bounds = turning_points(&smooth);
    merge_short_legs(&smooth, &mut bounds);
    join_same_direction(&smooth, &mut bounds);
    legs_of(&smooth, &bounds)
}

/// Sample indices of the turning points, with 0 first and the last sample last.
fn turning_points(smooth: &[f64]) -> Vec<usize> {
    let last = smooth.len() - 1;
    let mut bounds = vec![0];
    // Before the first turning point: the running extremes of both kinds.
    let (mut lo, mut hi) = (0, 0);
    let mut rising: Option<bool> = None;
    let mut extreme = 0;
    for (k, &s) in smooth.iter().enumerate() {
        match rising {
            None => {
                if s < smooth[lo] {
                    lo = k;
                }
                if s > smooth[hi] {
                    hi = k;
                }
                if s - smooth[lo] >= LEG_REVERSAL_C {
                    rising = Some(true);
                    if lo > 0 {
                        bounds.push(lo);
                    }
                    extreme = if hi > lo { hi } else { k };
                } else if smooth[hi] - s >= LEG_REVERSAL_C {
                    rising = Some(false);
                    if hi > 0 {
                        bounds.push(hi);
                    }
                    extreme = if lo > hi { lo } else { k };
                }
            }
            Some(up) => {
                let further = if up {
                    s > smooth[extreme]
                } else {
                    s < smooth[extreme]
                };
                if further {
                    extreme = k;
                } else if (smooth[extreme] - s).abs() >= LEG_REVERSAL_C {
                    bounds.push(extreme);
                    rising = Some(!up);
                    extreme = k;
                }
            }
        }
    }
    if *bounds.last().unwrap_or(&0) != last || bounds.len() == 1 {
        bounds.push(last);
    }
    bounds
}

/// Span of the smoothed temperature over samples `a..=b`.
fn span(smooth: &[f64], a: usize, b: usize) -> f64 {
    let (lo, hi) = smooth[a..=b]
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &s| {
            (lo.min(s), hi.max(s))
        });
    hi - lo
}

/// Merges legs under [`LEG_MIN_SPAN_C`] (module docs); `bounds` lists leg ends.
fn merge_short_legs(smooth: &[f64], bounds: &mut Vec<usize>) {
    loop {
        let legs = bounds.len() - 1;
        if legs < 2 {
            return;
        }
        let spans: Vec<f64> = (0..legs)
            .map(|j| span(smooth, bounds[j], bounds[j + 1]))
            .collect();
        let (shortest, &s) = spans
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))
            .expect("two or more legs");
        if s >= LEG_MIN_SPAN_C {
            return;
        }
        let into_previous = match (shortest.checked_sub(1), spans.get(shortest + 1)) {
            (Some(p), Some(&next)) => spans[p] <= next,
            (Some(_), None) => true,
            _ => false,
        };
        // Joining leg j with leg j−1 drops bound j; with leg j+1, bound j+1.
        bounds.remove(if into_previous {
            shortest
        } else {
            shortest + 1
        });
    }
}

/// True when samples a..b warm (end above start).
fn warms(smooth: &[f64], a: usize, b: usize) -> bool {
    smooth[b] >= smooth[a]
}

/// Joins neighbouring legs that run the same way.
fn join_same_direction(smooth: &[f64], bounds: &mut Vec<usize>) {
    let mut j = 1;
    while j + 1 < bounds.len() {
        let before = warms(smooth, bounds[j - 1], bounds[j]);
        let after = warms(smooth, bounds[j], bounds[j + 1]);
        if before == after {
            bounds.remove(j);
        } else {
            j += 1;
        }
    }
}

fn legs_of(smooth: &[f64], bounds: &[usize]) -> Vec<Leg> {
    let last = smooth.len() - 1;
    bounds
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            Leg {
                start: a,
                end: if b == last { b + 1 } else { b },
                temperature_c: [smooth[a], smooth[b]],
                span_c: span(smooth, a, b),
                direction: if warms(smooth, a, b) {
                    LegDirection::Warming
                } else {
                    LegDirection::Cooling
                },
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A piecewise-linear temperature through `knots` (time s, °C), sampled at 1 Hz.
    fn piecewise(knots: &[(f64, f64)]) -> (Vec<f64>, Vec<f64>) {
        let end = knots.last().unwrap().0;
        let time: Vec<f64> = (0..=end as usize).map(|k| k as f64).collect();
        let temp = time
            .iter()
            .map(|&t| {
                let j = knots.windows(2).position(|w| t <= w[1].0).unwrap();
                let ((t0, y0), (t1, y1)) = (knots[j], knots[j + 1]);
                y0 + (y1 - y0) * (t - t0) / (t1 - t0)
            })
            .collect();
        (time, temp)
    }

    #[test]
    fn a_cool_heat_cool_cycle_has_three_legs_at_its_knots() {
        // Knots far apart compared with the 60 s smoothing: turning points at the knots.
        let (time, temp) =
            piecewise(&[(0.0, 20.0), (3000.0, 5.0), (9000.0, 35.0), (12000.0, 25.0)]);
        let legs = find_legs(&time, &temp);
        assert_eq!(legs.len(), 3);
        assert_eq!(legs[0].direction, LegDirection::Cooling);
        assert_eq!(legs[1].direction, LegDirection::Warming);
        assert_eq!(legs[2].direction, LegDirection::Cooling);
        // Closed form: the ±30 s average of a V with slopes a (in) and b (out) peaks where the
        // window's ends are level, 30 (a − b)/(a + b) s past the knot: 0 s at 3000 s (5 and 5
        // mK/s), 6 s at 9000 s (5 and 3.33 mK/s).
        let shift = |a: f64, b: f64| 30.0 * (a - b) / (a + b);
        assert!((legs[0].end as f64 - 3000.0 - shift(5.0, 5.0)).abs() <= 1.0);
        let second = 9000.0 + shift(5.0, 10.0 / 3.0);
        assert!(
            (legs[1].end as f64 - second).abs() <= 1.0,
            "{}",
            legs[1].end
        );
        assert_eq!(legs[2].end, time.len());
        // The smoothed extremes are shallower than the knots: at the symmetric V by
        // a·30/2 = 0.075 °C; at the other, level-ended window over −24..36 s, by
        // (a·24²/2 + b·36²/2)/60 = 0.06 °C. So the span is 30 − 0.135 °C.
        assert!(
            (legs[1].span_c - (30.0 - 0.135)).abs() < 0.005,
            "{}",
            legs[1].span_c
        );
    }

    #[test]
    fn a_small_reversal_is_no_turning_point_and_a_short_leg_is_merged() {
        // A 0.8 °C dip is no reversal; a 2 °C dip is one, but its 2 °C leg is merged, and the
        // warming legs either side are joined: one warming leg.
        let (time, temp) = piecewise(&[
            (0.0, 0.0),
            (2000.0, 10.0),
            (2400.0, 9.2),
            (4000.0, 15.0),
            (4600.0, 13.0),
            (8000.0, 25.0),
        ]);
        let legs = find_legs(&time, &temp);
        assert_eq!(legs.len(), 1, "{legs:?}");
        assert_eq!(legs[0].direction, LegDirection::Warming);
        assert_eq!((legs[0].start, legs[0].end), (0, time.len()));
    }

    #[test]
    fn rates_of_a_line_are_its_slope() {
        // Closed form: the least-squares slope of an exact line is the line's slope, also at
        // the ends and on irregular times.
        let time: Vec<f64> = (0..500)
            .map(|k| k as f64 * 0.5 + (k % 3) as f64 * 1e-3)
            .collect();
        let temp: Vec<f64> = time.iter().map(|t| 3.0 - 0.05 * t).collect();
        for r in temperature_rates(&time, &temp, RATE_WINDOW_S) {
            assert!((r + 0.05).abs() < 1e-9, "{r}");
        }
    }

    #[test]
    fn the_centred_mean_of_a_line_is_the_line_inside() {
        let time: Vec<f64> = (0..300).map(|k| k as f64).collect();
        let m = centred_mean(&time, &time, 60.0);
        assert_eq!(m[100], 100.0);
        assert_eq!(m[0], 15.0); // samples 0..=30
    }
}
