//! A thermal calibration checked against a record (`thermonav bank check`): per channel, the
//! record's block means and the calibration's prediction with its 95 % band against time, and
//! the same block means and predictions against temperature, where a lagging unit draws its
//! loop.

use super::{DisplayUnits, channel_color};
use crate::chart::{Chart, Figure, Layer, Marker, Shape, Stroke};
use crate::palette;
use crate::scale::Axis;
use thermonav::imu::Channel;
use thermonav::stoch::thermal::check::ChannelCheck;

/// Legend name of the record's block means.
pub const OBSERVED_NAME: &str = "observed block mean";
/// Legend name of the prediction.
pub const PREDICTED_NAME: &str = "predicted";
/// Legend name of the band.
pub const BAND_NAME: &str = "95 % band";
/// Legend name of the blocks predicted outside the fitted range.
pub const CLAMPED_NAME: &str = "clamped (outside the fitted range)";

/// The figure: a row per channel (gyros, then accelerometers), time on the left and
/// temperature on the right.
pub fn thermal_check_figure(
    title: &str,
    checks: &[(Channel, &ChannelCheck)],
    units: DisplayUnits,
) -> String {
    let mut panels = Vec::new();
    for &(channel, check) in checks {
        panels.push(against_time(channel, check, units));
        panels.push(against_temperature(channel, check, units));
    }
    Figure {
        title: title.to_owned(),
        columns: 2,
        panels,
    }
    .to_svg()
}

/// Hours since the first block.
fn hours(check: &ChannelCheck) -> Vec<f64> {
    let start = check.blocks.first().map_or(0.0, |b| b.t_s);
    check
        .blocks
        .iter()
        .map(|b| (b.t_s - start) / 3600.0)
        .collect()
}

fn y_label(channel: Channel, units: DisplayUnits) -> String {
    format!("{} ({})", channel.name(), units.rate_unit(channel.sensor()))
}

fn against_time(channel: Channel, check: &ChannelCheck, units: DisplayUnits) -> Chart {
    let shown = |si: f64| units.rate(channel.sensor(), si);
    let x = hours(check);
    let edge = |sign: f64| -> Vec<f64> {
        (check.blocks.iter())
            .map(|b| shown(b.predicted + sign * b.band_half_width))
            .collect()
    };
    let mut layers = vec![
        Layer::Band {
            name: BAND_NAME.into(),
            x: x.clone(),
            low: edge(-1.0),
            high: edge(1.0),
            fill: channel_color(channel),
        },
        Layer::Line {
            name: PREDICTED_NAME.into(),
            points: x
                .iter()
                .zip(&check.blocks)
                .map(|(&t, b)| (t, shown(b.predicted)))
                .collect(),
            stroke: Stroke::solid(channel_color(channel)),
        },
        observed(
            x.iter()
                .copied()
                .zip(check.blocks.iter().map(|b| shown(b.observed))),
        ),
    ];
    layers.extend(clamped(check, |k| x[k], &shown));
    Chart {
        title: format!(
            "{} against time: rms {:.3} before, {:.3} after {}",
            channel.name(),
            shown(check.rms_before),
            shown(check.rms_after),
            units.rate_unit(channel.sensor())
        ),
        x: Axis::linear("time since the first block (h)"),
        y: Axis::linear(y_label(channel, units)),
        layers,
    }
}

fn against_temperature(channel: Channel, check: &ChannelCheck, units: DisplayUnits) -> Chart {
    let shown = |si: f64| units.rate(channel.sensor(), si);
    let at = |value: fn(&thermonav::stoch::thermal::check::BlockCheck) -> f64| -> Vec<(f64, f64)> {
        (check.blocks.iter())
            .map(|b| (b.temperature_c, shown(value(b))))
            .collect()
    };
    let mut predicted = Marker::filled(Shape::Diamond, channel_color(channel));
    predicted.radius = 2.0;
    let mut layers = vec![
        observed(at(|b| b.observed).into_iter()),
        Layer::Markers {
            name: PREDICTED_NAME.into(),
            points: at(|b| b.predicted),
            marker: predicted,
        },
    ];
    layers.extend(clamped(check, |k| check.blocks[k].temperature_c, &shown));
    Chart {
        title: format!(
            "{} against temperature: band covers {:.0} % of blocks",
            channel.name(),
            100.0 * check.coverage
        ),
        x: Axis::linear("temperature (°C)"),
        y: Axis::linear(y_label(channel, units)),
        layers,
    }
}

fn observed(points: impl Iterator<Item = (f64, f64)>) -> Layer {
    let mut marker = Marker::filled(Shape::Circle, palette::series_color(3));
    marker.radius = 2.0;
    Layer::Markers {
        name: OBSERVED_NAME.into(),
        points: points.collect(),
        marker,
    }
}

/// The observed means of the clamped blocks, ringed; none when no block was clamped.
fn clamped(
    check: &ChannelCheck,
    x_of: impl Fn(usize) -> f64,
    shown: &impl Fn(f64) -> f64,
) -> Option<Layer> {
    let points: Vec<(f64, f64)> = (check.blocks.iter().enumerate())
        .filter(|(_, b)| b.clamped)
        .map(|(k, b)| (x_of(k), shown(b.observed)))
        .collect();
    (!points.is_empty()).then(|| {
        let mut marker = Marker::filled(Shape::Square, palette::series_color(5));
        marker.radius = 3.0;
        Layer::Markers {
            name: CLAMPED_NAME.into(),
            points,
            marker,
        }
    })
}
