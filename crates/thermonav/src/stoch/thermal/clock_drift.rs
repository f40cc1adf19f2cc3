//! Whether a channel of a sweep calibration follows the clock rather than the temperature.
//!
//! Within one leg the temperature runs one way, so a drift with time reads as a slope against
//! temperature. Across two legs of one power-on that run opposite ways, a drift keeps its sign
//! in time and so flips the sign of its slope against temperature, which no curve in T (with or
//! without a lag, whose loop keeps the slope's sign) can draw. A leg's trend is the
//! least-squares line of its blocks against their mean temperature; its slope's 95 % interval
//! takes the blocks' residual scatter, with the count of blocks shrunk by their lag-1
//! autocorrelation ρ to n(1 − ρ)/(1 + ρ), as the calibration's other intervals do.

use super::legs::LegDirection;
use super::selection::{BAND_Z, SweepBlock, SweepLeg};
use super::sweep_model::{lag_one_autocorrelation, shrunk_by_autocorrelation};
use crate::imu::Channel;
use serde::Serialize;

/// Fewest blocks a leg needs for its trend.
pub const MIN_BLOCKS_PER_LEG: usize = 5;

/// One leg's straight-line trend of a channel against temperature.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LegTrend {
    /// The leg, as [`SweepBlock::leg`] numbers it.
    pub leg: u32,
    /// Which way it runs.
    pub direction: LegDirection,
    /// The slope against the blocks' mean temperature, channel unit per °C.
    pub slope_per_c: f64,
    /// The slope's 95 % half-width, channel unit per °C.
    pub slope_half_width_per_c: f64,
    /// The line's change over the leg, slope × (last block's temperature − first's), channel
    /// unit.
    pub change: f64,
}

/// Two legs of one power-on, running opposite ways, whose slopes against temperature have
/// opposite signs, each outside its 95 % interval: the channel drifts with time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ClockDrift {
    /// The two legs, in time order.
    pub legs: [LegTrend; 2],
}

/// The trend of `channel` over the blocks of one leg (in time order); `None` with fewer than
/// [`MIN_BLOCKS_PER_LEG`] blocks or no spread of temperature.
fn leg_trend(blocks: &[&SweepBlock], channel: Channel, leg: &SweepLeg) -> Option<LegTrend> {
    let points: Vec<(f64, f64)> = blocks
        .iter()
        .filter_map(|b| Some((b.temperature_c, *b.values.get(&channel)?)))
        .collect();
    let n = points.len();
    if n < MIN_BLOCKS_PER_LEG {
        return None;
    }
    let mean = |f: fn(&(f64, f64)) -> f64| points.iter().map(f).sum::<f64>() / n as f64;
    let (t_mean, y_mean) = (mean(|p| p.0), mean(|p| p.1));
    let sxx: f64 = points.iter().map(|p| (p.0 - t_mean).powi(2)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let sxy: f64 = points.iter().map(|p| (p.0 - t_mean) * (p.1 - y_mean)).sum();
    let slope = sxy / sxx;
    let residuals: Vec<f64> = (points.iter())
        .map(|p| p.1 - y_mean - slope * (p.0 - t_mean))
        .collect();
    let ss: f64 = residuals.iter().map(|r| r * r).sum();
    let rho = lag_one_autocorrelation(&residuals);
    let effective = shrunk_by_autocorrelation(n as f64, rho);
    let variance = ss / (n - 2) as f64 / sxx * (n as f64 / effective.max(1.0));
    Some(LegTrend {
        leg: leg.leg,
        direction: leg.direction,
        slope_per_c: slope,
        slope_half_width_per_c: BAND_Z * variance.sqrt(),
        change: slope * (points[n - 1].0 - points[0].0),
    })
}

/// The first pair of legs (in time order) of one power-on that shows `channel` drifting with
/// time (module docs), if any.
pub fn clock_drift(
    blocks: &[SweepBlock],
    legs: &[SweepLeg],
    channel: Channel,
) -> Option<ClockDrift> {
    let trends: Vec<(u32, LegTrend)> = legs
        .iter()
        .filter_map(|leg| {
            let mut of_leg: Vec<&SweepBlock> = (blocks.iter())
                .filter(|b| b.leg == leg.leg && b.power_on == leg.power_on)
                .collect();
            of_leg.sort_by(|a, b| a.t_s.total_cmp(&b.t_s));
            Some((leg.power_on, leg_trend(&of_leg, channel, leg)?))
        })
        .collect();
    let clear = |t: &LegTrend| t.slope_per_c.abs() > t.slope_half_width_per_c;
    trends.iter().enumerate().find_map(|(k, (power_on, a))| {
        trends[k + 1..]
            .iter()
            .find(|(p, b)| {
                p == power_on
                    && a.direction != b.direction
                    && clear(a)
                    && clear(b)
                    && a.slope_per_c.signum() != b.slope_per_c.signum()
            })
            .map(|(_, b)| ClockDrift { legs: [*a, *b] })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    /// A cooling leg 20 → 10 °C then a heating leg 10 → 20 °C, 20 blocks each 300 s apart, of
    /// one power-on, whose gx reads `value(t_s, temperature_c)` plus a ±1e-7 alternating ripple.
    fn two_legs(value: impl Fn(f64, f64) -> f64) -> (Vec<SweepBlock>, Vec<SweepLeg>) {
        let mut blocks = Vec::new();
        for k in 0..40 {
            let t_s = 300.0 * k as f64;
            let (leg, temperature_c) = match k < 20 {
                true => (1, 20.0 - 0.5 * k as f64),
                false => (2, 10.0 + 0.5 * (k - 20) as f64),
            };
            let ripple = if k % 2 == 0 { 1e-7 } else { -1e-7 };
            blocks.push(SweepBlock {
                power_on: 1,
                leg,
                t_s,
                temperature_c,
                sample_range_c: [temperature_c; 2],
                lagged_temperature_c: Vec::new(),
                rate_c_per_s: 0.0,
                samples: 300,
                values: BTreeMap::from([(Channel::Gx, value(t_s, temperature_c) + ripple)]),
            });
        }
        let leg = |leg, direction, t_s, temperature_c| SweepLeg {
            leg,
            power_on: 1,
            source: "sweep.csv".into(),
            t_s,
            temperature_c,
            span_c: 10.0,
            direction,
        };
        let legs = vec![
            leg(1, LegDirection::Cooling, [0.0, 5700.0], [20.0, 10.5]),
            leg(2, LegDirection::Warming, [6000.0, 11700.0], [10.0, 19.5]),
        ];
        (blocks, legs)
    }

    // Closed forms: a bias falling 1e-8 rad/s per second reads, against temperature, +6e-6
    // rad/s per °C on the cooling leg (0.5 °C per 300 s) and −6e-6 on the heating leg, each
    // far outside its interval: a drift with time, whose change over each leg is the same,
    // −5.7e-5 rad/s (9.5 °C of line). The alternating ripple tilts each fitted slope by
    // 2 · 1e-7 · 10 / 665 = 3.0e-9 per °C (its covariance with the block index over the
    // index's sum of squares, two blocks per °C), so the slopes are held to 1e-8 and the
    // changes to 1e-7. A bias of 2e-5 rad/s per °C has that slope on both legs: no drift.
    #[test]
    fn a_drift_with_time_flips_the_slope_against_temperature_and_a_curve_does_not() {
        let (blocks, legs) = two_legs(|t_s, _| -1e-8 * t_s);
        let drift = clock_drift(&blocks, &legs, Channel::Gx).expect("a drift with time");
        let [cooling, heating] = drift.legs;
        assert!((cooling.slope_per_c - 6e-6).abs() < 1e-8, "{cooling:?}");
        assert!((heating.slope_per_c + 6e-6).abs() < 1e-8, "{heating:?}");
        for leg in drift.legs {
            assert!((leg.change + 5.7e-5).abs() < 1e-7, "{leg:?}");
        }
        let (blocks, legs) = two_legs(|_, temperature_c| 2e-5 * temperature_c);
        assert_eq!(clock_drift(&blocks, &legs, Channel::Gx), None);
    }
}
