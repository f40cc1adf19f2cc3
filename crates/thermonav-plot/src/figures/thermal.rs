//! Bias against temperature from a unit's thermal calibration: a panel per channel, gyros in
//! the left column and accelerometers in the right, with the fitted repeatable curve, its
//! simultaneous 95 % band over the fitted range, and the observations marked by power-on with
//! each power-on's offset taken off (so that they scatter about the curve).

use super::{DisplayUnits, channel_color};
use crate::chart::{Chart, Figure, Layer, Marker, Shape, Stroke};
use crate::palette;
use crate::scale::Axis;
use thermonav::imu::Channel;
use thermonav::stoch::thermal::{PowerOnRecord, ThermalCalibration};

/// Temperatures at which the curve and band are drawn across the fitted range.
pub const CURVE_POINTS: usize = 101;

/// Legend name of the fitted curve.
pub const CURVE_NAME: &str = "repeatable b(T)";
/// Legend name of the band.
pub const BAND_NAME: &str = "simultaneous 95 % band";

/// One channel's curve and observations, SI (rad/s or m/s²).
#[derive(Debug, Clone, PartialEq)]
pub struct ThermalBiasPanel {
    /// The channel.
    pub channel: Channel,
    /// Polynomial order of the curve.
    pub order: usize,
    /// Temperatures drawn, °C.
    pub temperatures_c: Vec<f64>,
    /// b̂(T) at each temperature.
    pub bias: Vec<f64>,
    /// Half-width of the simultaneous band at each temperature.
    pub band_half_width: Vec<f64>,
    /// Observations with their power-on's offset taken off.
    pub observations: Vec<PowerOnRecord>,
}

/// The panels of a calibration, for `channels` (all calibrated ones when empty).
pub fn thermal_bias_panels(
    calibration: &ThermalCalibration,
    channels: &[Channel],
) -> Vec<ThermalBiasPanel> {
    calibration
        .channels
        .iter()
        .filter(|(c, _)| channels.is_empty() || channels.contains(c))
        .map(|(&channel, c)| {
            let temperatures_c = c.bias.range_grid_c(CURVE_POINTS);
            let (bias, band_half_width) = temperatures_c.iter().map(|&t| c.bias.band_at(t)).unzip();
            ThermalBiasPanel {
                channel,
                order: c.bias.order,
                temperatures_c,
                bias,
                band_half_width,
                observations: calibration.aligned_observations(channel),
            }
        })
        .collect()
}

/// The figure: a panel per channel present, in rows (gx ax), (gy ay), (gz az); one column
/// when a single channel is drawn.
pub fn thermal_bias_figure(
    title: &str,
    panels: &[ThermalBiasPanel],
    units: DisplayUnits,
) -> String {
    let order = [
        Channel::Gx,
        Channel::Ax,
        Channel::Gy,
        Channel::Ay,
        Channel::Gz,
        Channel::Az,
    ];
    let charts = order
        .iter()
        .filter_map(|&channel| panels.iter().find(|p| p.channel == channel))
        .map(|p| thermal_bias_chart(p, units))
        .collect();
    Figure {
        title: title.to_owned(),
        columns: if panels.len() > 1 { 2 } else { 1 },
        panels: charts,
    }
    .to_svg()
}

/// The y-axis label of a channel: az reads b(T) + g s(T) on a level unit.
fn bias_label(channel: Channel, units: DisplayUnits) -> String {
    let unit = units.rate_unit(channel.sensor());
    match channel {
        Channel::Az => format!("bias + g·s(T) ({unit})"),
        _ => format!("bias ({unit})"),
    }
}

fn thermal_bias_chart(panel: &ThermalBiasPanel, units: DisplayUnits) -> Chart {
    let sensor = panel.channel.sensor();
    let shown = |si: f64| units.rate(sensor, si);
    let mut layers = vec![band_layer(panel, &shown), curve_layer(panel, &shown)];
    layers.extend(observation_layers(&panel.observations, &shown));
    Chart {
        title: format!(
            "{} (order {}, power-on offsets removed)",
            panel.channel.name(),
            panel.order
        ),
        x: Axis::linear("temperature (°C)"),
        y: Axis::linear(bias_label(panel.channel, units)),
        layers,
    }
}

fn band_layer(panel: &ThermalBiasPanel, shown: &impl Fn(f64) -> f64) -> Layer {
    let edge = |sign: f64| -> Vec<f64> {
        panel
            .bias
            .iter()
            .zip(&panel.band_half_width)
            .map(|(b, h)| shown(b + sign * h))
            .collect()
    };
    Layer::Band {
        name: BAND_NAME.into(),
        x: panel.temperatures_c.clone(),
        low: edge(-1.0),
        high: edge(1.0),
        fill: channel_color(panel.channel),
    }
}

fn curve_layer(panel: &ThermalBiasPanel, shown: &impl Fn(f64) -> f64) -> Layer {
    Layer::Line {
        name: CURVE_NAME.into(),
        points: panel
            .temperatures_c
            .iter()
            .zip(&panel.bias)
            .map(|(&t, &b)| (t, shown(b)))
            .collect(),
        stroke: Stroke::solid(channel_color(panel.channel)),
    }
}

/// One marker layer per power-on, in increasing label order, each its own shape and colour.
fn observation_layers(records: &[PowerOnRecord], shown: &impl Fn(f64) -> f64) -> Vec<Layer> {
    let labels: std::collections::BTreeSet<u32> = records.iter().map(|r| r.power_on).collect();
    labels
        .into_iter()
        .enumerate()
        .map(|(index, label)| Layer::Markers {
            name: format!("power-on {label}"),
            points: records
                .iter()
                .filter(|r| r.power_on == label)
                .map(|r| (r.temperature_c, shown(r.value)))
                .collect(),
            marker: power_on_marker(index),
        })
        .collect()
}

/// The marker of the `index`-th power-on: shapes cycle, colours skip the curve's three.
fn power_on_marker(index: usize) -> Marker {
    let shapes = [
        Shape::Circle,
        Shape::Square,
        Shape::Triangle,
        Shape::Diamond,
    ];
    let mut marker = Marker::filled(shapes[index % 4], palette::series_color(3 + index));
    marker.radius = 3.0;
    marker
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parsed_svg::{
        ParsedSvg, assert_complete_figure, grid_mapping, layers_named, number, polyline_points,
    };
    use std::collections::BTreeMap;
    use thermonav::stoch::thermal::{FitSettings, calibrate};
    use thermonav::units::{m_per_s2_to_mg, rad_per_s_to_deg_per_h};

    /// Three power-ons at six temperatures of gx (a line in T, rad/s) and az (m/s²), each
    /// power-on shifted by its own offset, with a small deterministic scatter.
    fn calibration() -> ThermalCalibration {
        let offsets = [1e-4, -2e-4, 1e-4];
        let records = |scale: f64| -> Vec<PowerOnRecord> {
            (0..3u32)
                .flat_map(|j| {
                    (0..6).map(move |k| {
                        let t = -40.0 + 20.0 * k as f64;
                        let scatter = 1e-6 * ((j * 6 + k) as f64).sin();
                        let value = 1e-3 + 2e-5 * (t - 25.0) + offsets[j as usize] + scatter;
                        PowerOnRecord {
                            power_on: j + 1,
                            temperature_c: t,
                            value: value * scale,
                        }
                    })
                })
                .collect()
        };
        let observations =
            BTreeMap::from([(Channel::Gx, records(1.0)), (Channel::Az, records(10.0))]);
        calibrate(&observations, FitSettings::default()).expect("identifiable")
    }

    fn figure(channels: &[Channel]) -> String {
        let panels = thermal_bias_panels(&calibration(), channels);
        thermal_bias_figure("Thermal bias", &panels, DisplayUnits::Navigation)
    }

    #[test]
    fn each_channel_gets_a_panel_with_the_curve_band_and_power_ons_in_its_legend() {
        let text = figure(&[]);
        let svg = ParsedSvg::parse(&text);
        assert_complete_figure(&svg);
        let c = calibration();
        let title = |ch: Channel| {
            let order = c.channels[&ch].bias.order;
            format!("{} (order {order}, power-on offsets removed)", ch.name())
        };
        assert_eq!(
            svg.texts("panel-title"),
            [title(Channel::Gx), title(Channel::Az)]
        );
        assert_eq!(
            svg.texts("axis-label y"),
            ["bias (deg/h)", "bias + g·s(T) (mg)"]
        );
        assert_eq!(
            svg.texts("legend-entry")[..5],
            [
                BAND_NAME,
                CURVE_NAME,
                "power-on 1",
                "power-on 2",
                "power-on 3"
            ]
        );
    }

    #[test]
    fn observations_land_on_their_values_less_their_power_on_offset_in_display_units() {
        let text = figure(&[Channel::Gx]);
        let svg = ParsedSvg::parse(&text);
        assert_eq!(svg.with_class("panel").len(), 1);
        let c = calibration();
        let gx = &c.channels[&Channel::Gx];
        let (x_of, y_of) = (
            grid_mapping(&svg, 0, "x", false),
            grid_mapping(&svg, 0, "y", false),
        );
        let first = layers_named(&svg, "power-on 1")[0];
        let markers: Vec<_> = first
            .descendants()
            .filter(|n| n.attribute("class") == Some("marker"))
            .collect();
        let records: Vec<_> = c.observations[&Channel::Gx]
            .iter()
            .filter(|r| r.power_on == 1)
            .collect();
        assert_eq!(markers.len(), records.len());
        for (m, r) in markers.iter().zip(records) {
            let shown = rad_per_s_to_deg_per_h(r.value - gx.offset_of(1));
            assert!((number(m, "cx") - x_of(r.temperature_c)).abs() < 0.05);
            assert!((number(m, "cy") - y_of(shown)).abs() < 0.05, "{r:?}");
        }
        assert!(
            gx.offset_of(1) > 5e-5,
            "the offset moved the points visibly"
        );
    }

    #[test]
    fn the_curve_spans_the_fitted_range_inside_its_band() {
        let text = figure(&[Channel::Az]);
        let svg = ParsedSvg::parse(&text);
        let c = calibration();
        let curve = &c.channels[&Channel::Az].bias;
        let (x_of, y_of) = (
            grid_mapping(&svg, 0, "x", false),
            grid_mapping(&svg, 0, "y", false),
        );
        let line = polyline_points(&svg.with_class("series")[0]);
        assert_eq!(line.len(), CURVE_POINTS);
        let (first, last) = (line[0], line[CURVE_POINTS - 1]);
        assert!((first.0 - x_of(-40.0)).abs() < 0.05 && (last.0 - x_of(60.0)).abs() < 0.05);
        assert!((first.1 - y_of(m_per_s2_to_mg(curve.value_at(-40.0)))).abs() < 0.05);
        let band = polyline_points(&svg.with_class("band")[0]);
        assert_eq!(band.len(), 2 * CURVE_POINTS);
        let (value, half) = curve.band_at(-40.0);
        assert!((band[0].1 - y_of(m_per_s2_to_mg(value + half))).abs() < 0.05);
        assert!((band[2 * CURVE_POINTS - 1].1 - y_of(m_per_s2_to_mg(value - half))).abs() < 0.05);
    }
}
