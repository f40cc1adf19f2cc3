//! Navigation figures: a generic line chart with a legend, INS-only errors during an outage
//! per model (the paper's Figures 10-12), RMS error per model versus temperature (Figures
//! 13-15), filter innovations with their ±3σ bounds, and the trajectory with outage segments
//! highlighted (Figure 6).

use crate::chart::{self, Chart, Dash, Figure, Layer, Marker, Shape, Stroke};
use crate::palette;
use crate::scale::Axis;

/// A named curve `y(x)`.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedSeries {
    /// Legend text.
    pub name: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates.
    pub y: Vec<f64>,
}

impl NamedSeries {
    fn points(&self) -> Vec<(f64, f64)> {
        self.x.iter().copied().zip(self.y.iter().copied()).collect()
    }
}

/// A line chart: one line per series, optional shaded x intervals.
#[derive(Debug, Clone, PartialEq)]
pub struct LineChart {
    /// Panel title.
    pub title: String,
    /// Horizontal axis (label with unit).
    pub x: Axis,
    /// Vertical axis (label with unit).
    pub y: Axis,
    /// The lines.
    pub series: Vec<NamedSeries>,
    /// Shaded x intervals and their legend text (e.g. GNSS outages).
    pub shaded: Option<(String, Vec<(f64, f64)>)>,
}

impl LineChart {
    /// The chart as a panel: shading first, then a line per series in palette order.
    pub fn to_chart(&self) -> Chart {
        let shading = self.shaded.iter().map(|(name, ranges)| Layer::Spans {
            name: name.clone(),
            ranges: ranges.clone(),
            fill: palette::HIGHLIGHT,
        });
        let lines = self.series.iter().enumerate().map(|(i, s)| Layer::Line {
            name: s.name.clone(),
            points: s.points(),
            stroke: Stroke::solid(palette::series_color(i)),
        });
        Chart {
            title: self.title.clone(),
            x: self.x.clone(),
            y: self.y.clone(),
            layers: shading.chain(lines).collect(),
        }
    }
}

/// A figure of line charts stacked in one column.
pub fn line_chart_figure(title: &str, charts: &[LineChart]) -> String {
    Figure::stacked(title, charts.iter().map(LineChart::to_chart).collect()).to_svg()
}

/// INS-only errors of one model over time.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelErrors {
    /// The model's name (e.g. `model of 20 °C`).
    pub model: String,
    /// Times, s.
    pub time_s: Vec<f64>,
    /// North position error, m.
    pub north_m: Vec<f64>,
    /// East position error, m.
    pub east_m: Vec<f64>,
    /// Heading error, deg (empty when scored against a position-only reference).
    pub heading_deg: Vec<f64>,
}

/// North, east and heading errors during an outage, one line per model (Figures 10-12); the
/// outage interval is shaded. Without any heading error (a position-only reference) the
/// heading panel is left out.
pub fn outage_errors_figure(
    title: &str,
    models: &[ModelErrors],
    outage_s: Option<(f64, f64)>,
) -> String {
    let panel = |name: &str, unit: &str, pick: fn(&ModelErrors) -> &Vec<f64>| LineChart {
        title: format!("{name} error"),
        x: Axis::linear("time (s)"),
        y: Axis::linear(format!("{name} error ({unit})")),
        series: models
            .iter()
            .map(|m| NamedSeries {
                name: m.model.clone(),
                x: m.time_s.clone(),
                y: pick(m).clone(),
            })
            .collect(),
        shaded: outage_s.map(|range| ("GNSS outage".to_owned(), vec![range])),
    };
    let mut panels = vec![
        panel("north", "m", |m| &m.north_m),
        panel("east", "m", |m| &m.east_m),
    ];
    if models.iter().any(|m| !m.heading_deg.is_empty()) {
        panels.push(panel("heading", "deg", |m| &m.heading_deg));
    }
    line_chart_figure(title, &panels)
}

/// RMS error at each temperature: the temperature a model stands for (the paper's Figures
/// 13-15), or the operating temperature when one model is run at several.
#[derive(Debug, Clone, PartialEq)]
pub struct RmsSeries {
    /// The model's name.
    pub model: String,
    /// Operating temperatures, °C.
    pub temperature_c: Vec<f64>,
    /// RMS error at each temperature, in the figure's unit.
    pub rms: Vec<f64>,
}

/// RMS error per model versus temperature (Figures 13-15), with a marker at every point.
pub fn rms_versus_temperature_figure(
    title: &str,
    quantity: &str,
    unit: &str,
    models: &[RmsSeries],
) -> String {
    let mut layers = Vec::new();
    for (i, m) in models.iter().enumerate() {
        let color = palette::series_color(i);
        let points: Vec<(f64, f64)> = m
            .temperature_c
            .iter()
            .copied()
            .zip(m.rms.iter().copied())
            .collect();
        layers.push(Layer::Line {
            name: m.model.clone(),
            points: points.clone(),
            stroke: Stroke::solid(color),
        });
        layers.push(Layer::Markers {
            name: String::new(),
            points,
            marker: Marker::filled(Shape::Circle, color),
        });
    }
    let chart = Chart {
        title: format!("RMS {quantity} error"),
        x: Axis::linear("model temperature (°C)"),
        y: Axis::linear(format!("RMS {quantity} error ({unit})")),
        layers,
    };
    Figure::stacked(title, vec![chart]).to_svg()
}

/// Innovations of one measurement component with their predicted standard deviations.
#[derive(Debug, Clone, PartialEq)]
pub struct Innovations {
    /// The component (e.g. `north position`).
    pub name: String,
    /// Its unit.
    pub unit: String,
    /// Update times, s.
    pub time_s: Vec<f64>,
    /// Innovation at each update.
    pub innovation: Vec<f64>,
    /// Predicted innovation standard deviation at each update.
    pub sigma: Vec<f64>,
}

/// Index ranges of `times` without a gap longer than five times the median step (a GNSS
/// outage), so that bound lines are not drawn across it.
pub fn contiguous_runs(times: &[f64]) -> Vec<std::ops::Range<usize>> {
    if times.len() < 2 {
        return std::iter::once(0..times.len()).collect();
    }
    let mut steps: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
    steps.sort_by(f64::total_cmp);
    let limit = 5.0 * steps[steps.len() / 2];
    let mut runs = Vec::new();
    let mut start = 0;
    for k in 1..times.len() {
        if times[k] - times[k - 1] > limit {
            runs.push(start..k);
            start = k;
        }
    }
    runs.push(start..times.len());
    runs
}

/// A panel per component: the innovations as markers between ±3σ lines (broken at gaps).
pub fn innovations_figure(title: &str, components: &[Innovations]) -> String {
    let panels = components
        .iter()
        .map(|c| {
            let bound = |sign: f64, range: std::ops::Range<usize>| -> Vec<(f64, f64)> {
                c.time_s[range.clone()]
                    .iter()
                    .zip(&c.sigma[range])
                    .map(|(&t, &s)| (t, sign * 3.0 * s))
                    .collect()
            };
            let bound_stroke = Stroke {
                color: palette::series_color(3),
                width: 1.2,
                dash: Dash::Dashed,
            };
            Chart {
                title: c.name.clone(),
                x: Axis::linear("time (s)"),
                y: Axis::linear(format!("innovation ({})", c.unit)),
                layers: std::iter::once(Layer::Markers {
                    name: "innovation".into(),
                    points: c
                        .time_s
                        .iter()
                        .copied()
                        .zip(c.innovation.iter().copied())
                        .collect(),
                    marker: Marker {
                        radius: 1.8,
                        ..Marker::filled(Shape::Circle, palette::series_color(0))
                    },
                })
                .chain(contiguous_runs(&c.time_s).into_iter().flat_map(|run| {
                    [1.0, -1.0].map(|sign| Layer::Line {
                        name: "±3σ".into(),
                        points: bound(sign, run.clone()),
                        stroke: bound_stroke,
                    })
                }))
                .collect(),
            }
        })
        .collect();
    Figure::stacked(title, panels).to_svg()
}

/// A horizontal trajectory in a local frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    /// Times, s.
    pub time_s: Vec<f64>,
    /// East coordinate, m.
    pub east_m: Vec<f64>,
    /// North coordinate, m.
    pub north_m: Vec<f64>,
}

/// East versus north at equal metres per pixel on both axes, the parts inside the outage
/// intervals (times, s) drawn thick, start and end marked (Figure 6).
pub fn trajectory_figure(title: &str, trajectory: &Trajectory, outages_s: &[(f64, f64)]) -> String {
    let points: Vec<(f64, f64)> = trajectory
        .east_m
        .iter()
        .copied()
        .zip(trajectory.north_m.iter().copied())
        .collect();
    let in_outage = |t: f64| outages_s.iter().any(|&(a, b)| (a..=b).contains(&t));
    let highlighted = trajectory
        .time_s
        .iter()
        .zip(&points)
        .map(|(&t, &p)| {
            if in_outage(t) {
                p
            } else {
                (f64::NAN, f64::NAN)
            }
        })
        .collect();
    let (x_range, y_range) = equal_aspect_ranges(&points);
    let mut layers = vec![Layer::Line {
        name: "trajectory".into(),
        points: points.clone(),
        stroke: Stroke::solid(palette::series_color(0)),
    }];
    if !outages_s.is_empty() {
        layers.push(Layer::Line {
            name: "GNSS outage".into(),
            points: highlighted,
            stroke: Stroke {
                color: palette::series_color(3),
                width: 4.0,
                dash: Dash::Solid,
            },
        });
    }
    for (name, point, shape) in [
        ("start", points.first(), Shape::Triangle),
        ("end", points.last(), Shape::Square),
    ] {
        if let Some(&p) = point {
            layers.push(Layer::Markers {
                name: name.into(),
                points: vec![p],
                marker: Marker::filled(shape, palette::INK),
            });
        }
    }
    let chart = Chart {
        title: "horizontal trajectory".into(),
        x: Axis::linear("east (m)").with_range(x_range.0, x_range.1),
        y: Axis::linear("north (m)").with_range(y_range.0, y_range.1),
        layers,
    };
    Figure::stacked(title, vec![chart]).to_svg()
}

/// Ranges around the points' extent (plus 5 %) with the same metres per pixel along both
/// axes of a panel's plot area.
fn equal_aspect_ranges(points: &[(f64, f64)]) -> ((f64, f64), (f64, f64)) {
    let finite = points.iter().filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in finite {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if !(x0.is_finite() && y0.is_finite()) {
        return ((0.0, 1.0), (0.0, 1.0));
    }
    let (width, height) = chart::plot_area_size();
    let metres_per_px = ((x1 - x0) / width).max((y1 - y0) / height).max(1e-9) * 1.05;
    let half = |px: f64| metres_per_px * px / 2.0;
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    (
        (cx - half(width), cx + half(width)),
        (cy - half(height), cy + half(height)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    // Steps of 1 s with one 9 s gap (an outage): two runs, split at the gap.
    #[test]
    fn runs_break_at_outage_gaps() {
        let t = [0.0, 1.0, 2.0, 11.0, 12.0, 13.0];
        assert_eq!(contiguous_runs(&t), vec![0..3, 3..6]);
        assert_eq!(contiguous_runs(&t[..3]).len(), 1);
        assert_eq!(contiguous_runs(&[]).len(), 1);
    }
    use crate::parsed_svg::{
        ParsedSvg, assert_complete_figure, grid_mapping, number, polyline_points,
    };

    fn ramp(slope: f64) -> Vec<f64> {
        (0..=100).map(|k| slope * f64::from(k)).collect()
    }

    #[test]
    fn outage_errors_have_three_panels_and_the_outage_shaded_where_it_happened() {
        let time_s: Vec<f64> = (0..=100).map(|k| 100.0 + f64::from(k)).collect();
        let model = |name: &str, slope: f64| ModelErrors {
            model: name.into(),
            time_s: time_s.clone(),
            north_m: ramp(slope),
            east_m: ramp(-slope),
            heading_deg: ramp(slope / 100.0),
        };
        let text = outage_errors_figure(
            "INS-only errors",
            &[model("model of 20 °C", 0.5), model("model of -20 °C", 1.0)],
            Some((130.0, 190.0)),
        );
        let svg = ParsedSvg::parse(&text);
        assert_complete_figure(&svg);
        assert_eq!(
            svg.texts("axis-label y"),
            ["north error (m)", "east error (m)", "heading error (deg)"]
        );
        assert_eq!(
            &svg.texts("legend-entry")[..3],
            ["GNSS outage", "model of 20 °C", "model of -20 °C"]
        );
        let x_of = grid_mapping(&svg, 0, "x", false);
        let span = svg.with_class("span")[0];
        assert!((number(&span, "x") - x_of(130.0)).abs() < 0.02);
        assert!((number(&span, "width") - (x_of(190.0) - x_of(130.0))).abs() < 0.02);
    }

    #[test]
    fn innovations_lie_between_bounds_drawn_at_three_sigma() {
        let time_s: Vec<f64> = (0..50).map(f64::from).collect();
        let component = Innovations {
            name: "north position".into(),
            unit: "m".into(),
            innovation: time_s.iter().map(|t| (t * 0.7).sin()).collect(),
            sigma: vec![0.5; 50],
            time_s,
        };
        let text = innovations_figure("Innovations", &[component]);
        let svg = ParsedSvg::parse(&text);
        assert_complete_figure(&svg);
        assert_eq!(svg.texts("legend-entry"), ["innovation", "±3σ"]);
        let y_of = grid_mapping(&svg, 0, "y", false);
        let bounds = svg.with_class("series");
        assert!(
            polyline_points(&bounds[0])
                .iter()
                .all(|p| (p.1 - y_of(1.5)).abs() < 0.02)
        );
        assert!(
            polyline_points(&bounds[1])
                .iter()
                .all(|p| (p.1 - y_of(-1.5)).abs() < 0.02)
        );
    }

    #[test]
    fn rms_versus_temperature_has_a_line_and_markers_per_model() {
        let m = |name: &str, base: f64| RmsSeries {
            model: name.into(),
            temperature_c: vec![-40.0, 0.0, 40.0],
            rms: vec![base, base * 2.0, base * 3.0],
        };
        let text =
            rms_versus_temperature_figure("RMS", "north", "m", &[m("AR", 1.0), m("ML", 2.0)]);
        let svg = ParsedSvg::parse(&text);
        assert_complete_figure(&svg);
        assert_eq!(svg.texts("legend-entry"), ["AR", "ML"]);
        assert_eq!(svg.with_class("marker").len(), 6);
        let (x_of, y_of) = (
            grid_mapping(&svg, 0, "x", false),
            grid_mapping(&svg, 0, "y", false),
        );
        let last = svg.with_class("marker")[5];
        assert!((number(&last, "cx") - x_of(40.0)).abs() < 0.02);
        assert!((number(&last, "cy") - y_of(6.0)).abs() < 0.02);
    }

    #[test]
    fn the_trajectory_has_equal_scales_and_one_thick_run_per_outage() {
        let time_s: Vec<f64> = (0..=200).map(f64::from).collect();
        let east_m: Vec<f64> = time_s.iter().map(|t| 300.0 * (t / 40.0).cos()).collect();
        let north_m: Vec<f64> = time_s.iter().map(|t| 100.0 * (t / 40.0).sin()).collect();
        let trajectory = Trajectory {
            time_s,
            east_m,
            north_m,
        };
        let no_outage = trajectory_figure("Survey", &trajectory, &[]);
        assert!(!no_outage.contains("GNSS outage"));
        let text = trajectory_figure("Survey", &trajectory, &[(20.0, 40.0), (120.0, 150.0)]);
        let svg = ParsedSvg::parse(&text);
        assert_complete_figure(&svg);
        let (x_of, y_of) = (
            grid_mapping(&svg, 0, "x", false),
            grid_mapping(&svg, 0, "y", false),
        );
        let metre_x = x_of(1.0) - x_of(0.0);
        let metre_y = y_of(0.0) - y_of(1.0);
        assert!(
            (metre_x / metre_y - 1.0).abs() < 1e-3,
            "{metre_x} vs {metre_y}"
        );
        let series = svg.with_class("series");
        assert_eq!(series.len(), 3, "the whole path and two outage runs");
        assert_eq!(polyline_points(&series[1]).len(), 21);
        assert_eq!(polyline_points(&series[2]).len(), 31);
    }
}
