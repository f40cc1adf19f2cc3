//! Correlation time versus temperature (the paper's Figures 8-9): a panel per channel,
//! gyros in the left column and accelerometers in the right, one series per Gauss-Markov
//! family with its 95 % interval as error bars on a log axis.

use crate::chart::{Bound, Chart, ErrorBar, Figure, Layer, Marker, Shape, Stroke};
use crate::palette;
use crate::scale::Axis;
use thermonav::imu::Channel;
use thermonav::stoch::bank::{GaussMarkovEstimate, GaussMarkovSource, ModelBank};

/// Horizontal distance between the error bars of neighbouring families at one temperature, px.
pub const FAMILY_SPACING_PX: f64 = 8.0;

/// A correlation time at one temperature with its 95 % interval as the bank records it:
/// `None` on a side the data do not bound; `None` on both sides means no interval was given
/// (the autocorrelation fit gives none), drawn as a marker alone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CorrelationTimePoint {
    /// Temperature, °C.
    pub temperature_c: f64,
    /// Correlation time Tc, s.
    pub correlation_time_s: f64,
    /// 95 % interval of Tc, s.
    pub ci95_s: [Option<f64>; 2],
}

/// The correlation times of one channel estimated by one model family.
#[derive(Debug, Clone, PartialEq)]
pub struct CorrelationTimeSeries {
    /// The channel.
    pub channel: Channel,
    /// The family's name, as shown in the legend.
    pub family: String,
    /// One point per temperature that has a model.
    pub points: Vec<CorrelationTimePoint>,
}

/// The figure: a panel per channel present, in rows (gx ax), (gy ay), (gz az).
pub fn correlation_time_figure(title: &str, series: &[CorrelationTimeSeries]) -> String {
    let families = family_names(series);
    let order = [
        Channel::Gx,
        Channel::Ax,
        Channel::Gy,
        Channel::Ay,
        Channel::Gz,
        Channel::Az,
    ];
    let panels = order
        .into_iter()
        .filter(|&channel| series.iter().any(|s| s.channel == channel))
        .map(|channel| correlation_panel(channel, series, &families))
        .collect();
    Figure {
        title: title.to_owned(),
        columns: 2,
        panels,
    }
    .to_svg()
}

/// Distinct family names in order of first appearance.
fn family_names(series: &[CorrelationTimeSeries]) -> Vec<&str> {
    let mut names: Vec<&str> = Vec::new();
    for s in series {
        if !names.contains(&s.family.as_str()) {
            names.push(&s.family);
        }
    }
    names
}

fn correlation_panel(
    channel: Channel,
    series: &[CorrelationTimeSeries],
    families: &[&str],
) -> Chart {
    let mut layers = Vec::new();
    for s in series.iter().filter(|s| s.channel == channel) {
        let index = families.iter().position(|f| *f == s.family).unwrap_or(0);
        let color = palette::series_color(index);
        let centre = (families.len() as f64 - 1.0) / 2.0;
        layers.push(Layer::ErrorBars {
            name: s.family.clone(),
            bars: s
                .points
                .iter()
                .map(|p| ErrorBar {
                    x: p.temperature_c,
                    y: p.correlation_time_s,
                    interval: interval_of(p.ci95_s),
                })
                .collect(),
            marker: Marker::filled(family_shape(index), color),
            stroke: Stroke::solid(color),
            offset_px: (index as f64 - centre) * FAMILY_SPACING_PX,
        });
    }
    Chart {
        title: format!("{} (95 % intervals)", channel.name()),
        x: Axis::linear("temperature (°C)"),
        y: Axis::log10("correlation time Tc (s)"),
        layers,
    }
}

/// The bar of a bank interval: none when neither side is given.
fn interval_of(ci95_s: [Option<f64>; 2]) -> Option<[Bound; 2]> {
    match ci95_s {
        [None, None] => None,
        sides => Some(sides.map(Bound::from_option)),
    }
}

fn family_shape(index: usize) -> Shape {
    [
        Shape::Circle,
        Shape::Square,
        Shape::Triangle,
        Shape::Diamond,
    ][index % 4]
}

/// The series of a bank: per channel and per requested family, the entries that have a model.
pub fn correlation_time_series(
    bank: &ModelBank,
    families: &[GaussMarkovSource],
) -> Vec<CorrelationTimeSeries> {
    let mut all = Vec::new();
    for channel in Channel::ALL {
        for &source in families {
            let points: Vec<CorrelationTimePoint> = bank
                .entries
                .iter()
                .filter_map(|entry| {
                    let model = entry.channels.get(&channel)?;
                    match model.gauss_markov.get(source) {
                        GaussMarkovEstimate::Model {
                            correlation_time_s,
                            ci95_correlation_time_s,
                            ..
                        } => Some(CorrelationTimePoint {
                            temperature_c: entry.temperature_c,
                            correlation_time_s: *correlation_time_s,
                            ci95_s: *ci95_correlation_time_s,
                        }),
                        GaussMarkovEstimate::NoEquivalent { .. } => None,
                    }
                })
                .collect();
            if !points.is_empty() {
                all.push(CorrelationTimeSeries {
                    channel,
                    family: source.label().to_owned(),
                    points,
                });
            }
        }
    }
    all
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parsed_svg::{ParsedSvg, assert_complete_figure, grid_mapping, number};

    fn series(channel: Channel, family: &str, scale: f64) -> CorrelationTimeSeries {
        let point = |t: f64, tc: f64, high: Option<f64>| CorrelationTimePoint {
            temperature_c: t,
            correlation_time_s: tc * scale,
            ci95_s: [Some(tc * scale / 2.0), high.map(|h| h * scale)],
        };
        CorrelationTimeSeries {
            channel,
            family: family.into(),
            points: vec![
                point(-40.0, 20.0, Some(40.0)),
                point(20.0, 100.0, Some(300.0)),
                point(60.0, 200.0, None),
                CorrelationTimePoint {
                    temperature_c: 0.0,
                    correlation_time_s: 50.0,
                    ci95_s: [None, None],
                },
            ],
        }
    }

    fn figure() -> String {
        correlation_time_figure(
            "Correlation time",
            &[
                series(Channel::Gx, "exact ML", 1.0),
                series(Channel::Gx, "AR(1)-based", 0.5),
                series(Channel::Ax, "exact ML", 2.0),
            ],
        )
    }

    #[test]
    fn every_channel_gets_a_panel_with_a_legend_of_its_families() {
        let text = figure();
        let svg = ParsedSvg::parse(&text);
        assert_complete_figure(&svg);
        assert_eq!(
            svg.texts("panel-title"),
            ["gx (95 % intervals)", "ax (95 % intervals)"]
        );
        assert_eq!(
            svg.texts("legend-entry"),
            ["exact ML", "AR(1)-based", "exact ML"]
        );
        assert_eq!(svg.texts("axis-label x")[0], "temperature (°C)");
        assert_eq!(svg.texts("axis-label y")[0], "correlation time Tc (s)");
    }

    #[test]
    fn error_bars_span_the_intervals_on_the_log_axis_beside_their_temperature() {
        let text = figure();
        let svg = ParsedSvg::parse(&text);
        let x_of = grid_mapping(&svg, 0, "x", false);
        let y_of = grid_mapping(&svg, 0, "y", true);
        let area = svg.plot_areas()[0];
        // Panel 0 (gx): family 0 ("exact ML") sits half a spacing left of the temperature.
        let bars = svg.with_class("error-bar");
        let first = bars[0];
        assert!((number(&first, "x1") - (x_of(-40.0) - FAMILY_SPACING_PX / 2.0)).abs() < 0.02);
        assert!((number(&first, "y1") - y_of(10.0)).abs() < 0.02);
        assert!((number(&first, "y2") - y_of(40.0)).abs() < 0.02);
        // The unbounded upper side at 60 °C runs past the top of the plot area.
        assert!(number(&bars[2], "y2") < area.top);
        // Family 1 at 20 °C: half a spacing right, interval (25, 150) s.
        let shifted = bars[4];
        assert!((number(&shifted, "x1") - (x_of(20.0) + FAMILY_SPACING_PX / 2.0)).abs() < 0.02);
        assert!((number(&shifted, "y1") - y_of(25.0)).abs() < 0.02);
        assert!((number(&shifted, "y2") - y_of(150.0)).abs() < 0.02);
    }
}
