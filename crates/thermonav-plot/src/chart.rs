//! Charts: panels with two axes, grid, data layers and a legend, laid out in a grid of
//! panels under a figure title and written as one SVG document.
//!
//! Every panel draws its plot area as `<rect class="plot-area">`; a data value `(x, y)` lands
//! at the pixel that the axes' [`Mapping`]s give over that rectangle (x from its left edge to
//! its right edge, y from its bottom edge to its top edge). Named layers appear in the legend
//! to the right of the plot area, once per name.

use crate::palette::{self, Color};
use crate::scale::{Axis, Mapping, TickLabel, domain_of, major_ticks, minor_ticks, plain_number};
use crate::svg::{SvgWriter, coordinate, escape_markup, points_attribute};

/// Width of one panel cell, px.
pub const PANEL_WIDTH: f64 = 760.0;
/// Height of one panel cell, px.
pub const PANEL_HEIGHT: f64 = 330.0;
const FIGURE_TITLE_HEIGHT: f64 = 34.0;
const MARGIN_LEFT: f64 = 80.0;
const MARGIN_RIGHT: f64 = 240.0;
const MARGIN_TOP: f64 = 32.0;
const MARGIN_BOTTOM: f64 = 52.0;
const LEGEND_ROW: f64 = 18.0;
/// Start of the ids of the panels' clip paths (`plot-area-0`, `plot-area-1`, …).
const CLIP_ID_STEM: &str = "plot-area-";

/// A figure's SVG with `prefix` put before each of its element ids and the references to
/// them, so that several figures can share one HTML document.
pub fn prefix_ids(svg: &str, prefix: &str) -> String {
    svg.replace(
        &format!("id=\"{CLIP_ID_STEM}"),
        &format!("id=\"{prefix}{CLIP_ID_STEM}"),
    )
    .replace(
        &format!("url(#{CLIP_ID_STEM}"),
        &format!("url(#{prefix}{CLIP_ID_STEM}"),
    )
}

/// Line pattern.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dash {
    /// Continuous.
    Solid,
    /// Long dashes.
    Dashed,
    /// Dots.
    Dotted,
}

/// How a line is stroked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke {
    /// Colour.
    pub color: Color,
    /// Width, px.
    pub width: f64,
    /// Pattern.
    pub dash: Dash,
}

impl Stroke {
    /// A solid line of width 1.5 px.
    pub fn solid(color: Color) -> Self {
        Self {
            color,
            width: 1.5,
            dash: Dash::Solid,
        }
    }

    /// A dashed line of width 1.2 px.
    pub fn dashed(color: Color) -> Self {
        Self {
            color,
            width: 1.2,
            dash: Dash::Dashed,
        }
    }
}

/// Marker outline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// A circle.
    Circle,
    /// An axis-aligned square.
    Square,
    /// A triangle pointing up.
    Triangle,
    /// A square standing on a corner.
    Diamond,
}

/// How data points are marked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Marker {
    /// Outline.
    pub shape: Shape,
    /// Half-size (radius of a circle), px.
    pub radius: f64,
    /// Outline colour.
    pub stroke: Color,
    /// Fill colour; `None` leaves the marker hollow (white).
    pub fill: Option<Color>,
}

impl Marker {
    /// A filled marker of radius 3.5 px.
    pub fn filled(shape: Shape, color: Color) -> Self {
        Self {
            shape,
            radius: 3.5,
            stroke: color,
            fill: Some(color),
        }
    }
}

/// One end of an interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bound {
    /// The interval ends at this value.
    At(f64),
    /// The data do not bound this side: the bar runs to the plot edge.
    Unbounded,
}

impl Bound {
    /// The bound of an optional value, `None` being unbounded.
    pub fn from_option(value: Option<f64>) -> Self {
        value.map_or(Bound::Unbounded, Bound::At)
    }

    fn value(self) -> Option<f64> {
        match self {
            Bound::At(v) => Some(v),
            Bound::Unbounded => None,
        }
    }
}

/// A point with the interval around it, when one was given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorBar {
    /// Abscissa.
    pub x: f64,
    /// Estimate.
    pub y: f64,
    /// Lower and upper bounds; `None` when no interval was given (marker alone).
    pub interval: Option<[Bound; 2]>,
}

/// One kind of data drawn in a panel. Points whose coordinates the axes cannot place (NaN,
/// or ≤ 0 on a log axis) break lines and bands and are left out.
#[derive(Debug, Clone, PartialEq)]
pub enum Layer {
    /// A polyline through the points in order.
    Line {
        /// Legend text; empty for none.
        name: String,
        /// Data points.
        points: Vec<(f64, f64)>,
        /// Stroke.
        stroke: Stroke,
    },
    /// A marker at each point.
    Markers {
        /// Legend text; empty for none.
        name: String,
        /// Data points.
        points: Vec<(f64, f64)>,
        /// Marker.
        marker: Marker,
    },
    /// A marker at each estimate with a vertical bar over its interval.
    ErrorBars {
        /// Legend text; empty for none.
        name: String,
        /// The estimates and intervals.
        bars: Vec<ErrorBar>,
        /// Marker at the estimate.
        marker: Marker,
        /// Stroke of the bars.
        stroke: Stroke,
        /// Horizontal shift in pixels, so that several families at one x stay apart.
        offset_px: f64,
    },
    /// A shaded region between `low` and `high` over `x`.
    Band {
        /// Legend text; empty for none.
        name: String,
        /// Abscissae.
        x: Vec<f64>,
        /// Lower edge at each abscissa.
        low: Vec<f64>,
        /// Upper edge at each abscissa.
        high: Vec<f64>,
        /// Fill colour (drawn translucent).
        fill: Color,
    },
    /// Shaded x intervals over the whole height, e.g. GNSS outages on a time axis.
    Spans {
        /// Legend text; empty for none.
        name: String,
        /// `(start, end)` intervals.
        ranges: Vec<(f64, f64)>,
        /// Fill colour (drawn translucent).
        fill: Color,
    },
}

impl Layer {
    /// The legend text (empty for none).
    pub fn name(&self) -> &str {
        match self {
            Layer::Line { name, .. }
            | Layer::Markers { name, .. }
            | Layer::ErrorBars { name, .. }
            | Layer::Band { name, .. }
            | Layer::Spans { name, .. } => name,
        }
    }

    fn x_values(&self) -> Vec<f64> {
        match self {
            Layer::Line { points, .. } | Layer::Markers { points, .. } => {
                points.iter().map(|p| p.0).collect()
            }
            Layer::ErrorBars { bars, .. } => bars.iter().map(|b| b.x).collect(),
            Layer::Band { x, .. } => x.clone(),
            Layer::Spans { ranges, .. } => ranges.iter().flat_map(|&(a, b)| [a, b]).collect(),
        }
    }

    fn y_values(&self) -> Vec<f64> {
        match self {
            Layer::Line { points, .. } | Layer::Markers { points, .. } => {
                points.iter().map(|p| p.1).collect()
            }
            Layer::ErrorBars { bars, .. } => bars
                .iter()
                .flat_map(|b| {
                    let [low, high] = b.interval.map_or([None, None], |i| i.map(Bound::value));
                    [Some(b.y), low, high]
                })
                .flatten()
                .collect(),
            Layer::Band { low, high, .. } => low.iter().chain(high).copied().collect(),
            Layer::Spans { .. } => Vec::new(),
        }
    }
}

/// One panel: a title, two axes and the layers drawn in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    /// Panel title.
    pub title: String,
    /// Horizontal axis.
    pub x: Axis,
    /// Vertical axis.
    pub y: Axis,
    /// Data, drawn first to last.
    pub layers: Vec<Layer>,
}

/// Panels under a title, filled row by row into `columns` columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Figure title.
    pub title: String,
    /// Number of panel columns (at least 1).
    pub columns: usize,
    /// The panels.
    pub panels: Vec<Chart>,
}

impl Figure {
    /// A one-column figure.
    pub fn stacked(title: impl Into<String>, panels: Vec<Chart>) -> Self {
        Self {
            title: title.into(),
            columns: 1,
            panels,
        }
    }

    /// The figure as a standalone SVG document.
    pub fn to_svg(&self) -> String {
        let columns = self.columns.max(1);
        let rows = self.panels.len().div_ceil(columns).max(1);
        let width = columns as f64 * PANEL_WIDTH;
        let height = FIGURE_TITLE_HEIGHT + rows as f64 * PANEL_HEIGHT;
        let mut svg = SvgWriter::new(width, height);
        svg.text_element(
            "text",
            &[
                ("class", "figure-title".into()),
                ("x", coordinate(width / 2.0)),
                ("y", "22".into()),
                ("text-anchor", "middle".into()),
                ("font-size", "16".into()),
                ("font-weight", "bold".into()),
                ("fill", palette::INK.0.into()),
            ],
            &self.title,
        );
        for (index, chart) in self.panels.iter().enumerate() {
            let left = (index % columns) as f64 * PANEL_WIDTH;
            let top = FIGURE_TITLE_HEIGHT + (index / columns) as f64 * PANEL_HEIGHT;
            draw_panel(&mut svg, chart, index, left, top);
        }
        svg.finish()
    }
}

/// Width and height of a panel's plot area, px.
pub fn plot_area_size() -> (f64, f64) {
    (
        PANEL_WIDTH - MARGIN_LEFT - MARGIN_RIGHT,
        PANEL_HEIGHT - MARGIN_TOP - MARGIN_BOTTOM,
    )
}

/// A pixel position `(x, y)`.
type Pixel = (f64, f64);

/// The pixel rectangle of a panel's plot area.
#[derive(Debug, Clone, Copy, PartialEq)]
struct PlotArea {
    left: f64,
    top: f64,
    width: f64,
    height: f64,
}

impl PlotArea {
    fn right(&self) -> f64 {
        self.left + self.width
    }

    fn bottom(&self) -> f64 {
        self.top + self.height
    }
}

/// The axes' pixel mappings over a plot area.
#[derive(Debug, Clone, Copy)]
struct Frame {
    area: PlotArea,
    x: Mapping,
    y: Mapping,
}

impl Frame {
    fn point(&self, (x, y): (f64, f64)) -> Option<(f64, f64)> {
        Some((self.x.pixel(x)?, self.y.pixel(y)?))
    }
}

fn frame_of(chart: &Chart, area: PlotArea) -> Frame {
    let x_domain = domain_of(&chart.x, chart.layers.iter().flat_map(Layer::x_values));
    let y_domain = domain_of(&chart.y, chart.layers.iter().flat_map(Layer::y_values));
    Frame {
        area,
        x: Mapping {
            domain: x_domain,
            start: area.left,
            end: area.right(),
        },
        y: Mapping {
            domain: y_domain,
            start: area.bottom(),
            end: area.top,
        },
    }
}

fn draw_panel(svg: &mut SvgWriter, chart: &Chart, index: usize, left: f64, top: f64) {
    let (width, height) = plot_area_size();
    let area = PlotArea {
        left: left + MARGIN_LEFT,
        top: top + MARGIN_TOP,
        width,
        height,
    };
    let frame = frame_of(chart, area);
    let clip_id = format!("{CLIP_ID_STEM}{index}");
    svg.start("g", &[("class", "panel".into())]);
    svg.start("clipPath", &[("id", clip_id.clone())]);
    svg.empty("rect", &area_attributes(area));
    svg.close("clipPath");
    draw_grid(svg, &frame);
    svg.start(
        "g",
        &[
            ("class", "data".into()),
            ("clip-path", format!("url(#{clip_id})")),
        ],
    );
    for layer in &chart.layers {
        draw_layer(svg, &frame, layer);
    }
    svg.close("g");
    let mut frame_attributes = area_attributes(area);
    frame_attributes.extend([
        ("class", "plot-area".into()),
        ("fill", "none".into()),
        ("stroke", palette::INK.0.into()),
    ]);
    svg.empty("rect", &frame_attributes);
    draw_tick_labels(svg, &frame);
    draw_titles(svg, chart, area);
    draw_legend(svg, &chart.layers, area);
    svg.close("g");
}

fn area_attributes(area: PlotArea) -> Vec<(&'static str, String)> {
    vec![
        ("x", coordinate(area.left)),
        ("y", coordinate(area.top)),
        ("width", coordinate(area.width)),
        ("height", coordinate(area.height)),
    ]
}

fn line_attributes(from: (f64, f64), to: (f64, f64)) -> Vec<(&'static str, String)> {
    vec![
        ("x1", coordinate(from.0)),
        ("y1", coordinate(from.1)),
        ("x2", coordinate(to.0)),
        ("y2", coordinate(to.1)),
    ]
}

/// Grid lines at every major tick (and minor decade ticks) of both axes.
fn draw_grid(svg: &mut SvgWriter, frame: &Frame) {
    let a = frame.area;
    for (axis, mapping) in [("x", frame.x), ("y", frame.y)] {
        let minor = minor_ticks(&mapping.domain).into_iter().map(|v| (v, false));
        let major = major_ticks(&mapping.domain)
            .into_iter()
            .map(|t| (t.value, true));
        for (value, is_major) in minor.chain(major) {
            let Some(p) = mapping.pixel(value) else {
                continue;
            };
            let (from, to) = if axis == "x" {
                ((p, a.top), (p, a.bottom()))
            } else {
                ((a.left, p), (a.right(), p))
            };
            let (class, color) = if is_major {
                (format!("grid major {axis}"), palette::GRID)
            } else {
                (format!("grid minor {axis}"), palette::MINOR_GRID)
            };
            let mut attributes = line_attributes(from, to);
            attributes.extend([
                ("class", class),
                ("data-value", format!("{value:e}")),
                ("stroke", color.0.into()),
            ]);
            svg.empty("line", &attributes);
        }
    }
}

fn draw_tick_labels(svg: &mut SvgWriter, frame: &Frame) {
    let a = frame.area;
    for tick in major_ticks(&frame.x.domain) {
        let Some(x) = frame.x.pixel(tick.value) else {
            continue;
        };
        let attributes = [
            ("class", "tick-label x".into()),
            ("x", coordinate(x)),
            ("y", coordinate(a.bottom() + 16.0)),
            ("text-anchor", "middle".into()),
            ("fill", palette::INK.0.into()),
        ];
        svg.markup_element("text", &attributes, &tick_markup(&tick.label));
    }
    for tick in major_ticks(&frame.y.domain) {
        let Some(y) = frame.y.pixel(tick.value) else {
            continue;
        };
        let attributes = [
            ("class", "tick-label y".into()),
            ("x", coordinate(a.left - 6.0)),
            ("y", coordinate(y + 4.0)),
            ("text-anchor", "end".into()),
            ("fill", palette::INK.0.into()),
        ];
        svg.markup_element("text", &attributes, &tick_markup(&tick.label));
    }
}

/// A tick label as SVG text content: a number, or 10 with a raised exponent.
fn tick_markup(label: &TickLabel) -> String {
    match label {
        TickLabel::Plain(text) => escape_markup(text),
        TickLabel::PowerOfTen(k) => format!(
            "10<tspan dy=\"-6\" font-size=\"9\">{}</tspan>",
            plain_number(f64::from(*k), 1.0).replace('-', "\u{2212}")
        ),
    }
}

fn draw_titles(svg: &mut SvgWriter, chart: &Chart, a: PlotArea) {
    let ink = || ("fill", palette::INK.0.to_string());
    svg.text_element(
        "text",
        &[
            ("class", "panel-title".into()),
            ("x", coordinate(a.left + a.width / 2.0)),
            ("y", coordinate(a.top - 10.0)),
            ("text-anchor", "middle".into()),
            ("font-size", "13".into()),
            ink(),
        ],
        &chart.title,
    );
    svg.text_element(
        "text",
        &[
            ("class", "axis-label x".into()),
            ("x", coordinate(a.left + a.width / 2.0)),
            ("y", coordinate(a.bottom() + 38.0)),
            ("text-anchor", "middle".into()),
            ink(),
        ],
        &chart.x.label,
    );
    let (x, y) = (a.left - 58.0, a.top + a.height / 2.0);
    svg.text_element(
        "text",
        &[
            ("class", "axis-label y".into()),
            ("x", coordinate(x)),
            ("y", coordinate(y)),
            ("text-anchor", "middle".into()),
            (
                "transform",
                format!("rotate(-90 {} {})", coordinate(x), coordinate(y)),
            ),
            ink(),
        ],
        &chart.y.label,
    );
}

fn draw_layer(svg: &mut SvgWriter, frame: &Frame, layer: &Layer) {
    svg.start(
        "g",
        &[
            ("class", "layer".into()),
            ("data-name", layer.name().into()),
        ],
    );
    match layer {
        Layer::Line { points, stroke, .. } => draw_line(svg, frame, points, *stroke),
        Layer::Markers { points, marker, .. } => {
            for p in points.iter().filter_map(|&p| frame.point(p)) {
                draw_marker(svg, "marker", p, *marker);
            }
        }
        Layer::ErrorBars {
            bars,
            marker,
            stroke,
            offset_px,
            ..
        } => {
            for bar in bars {
                draw_error_bar(svg, frame, bar, *marker, *stroke, *offset_px);
            }
        }
        Layer::Band {
            x, low, high, fill, ..
        } => draw_band(svg, frame, x, low, high, *fill),
        Layer::Spans { ranges, fill, .. } => draw_spans(svg, frame, ranges, *fill),
    }
    svg.close("g");
}

fn stroke_attributes(stroke: Stroke) -> Vec<(&'static str, String)> {
    let mut attributes = vec![
        ("fill", "none".to_owned()),
        ("stroke", stroke.color.0.to_owned()),
        ("stroke-width", coordinate(stroke.width)),
        ("stroke-linejoin", "round".to_owned()),
    ];
    match stroke.dash {
        Dash::Solid => {}
        Dash::Dashed => attributes.push(("stroke-dasharray", "6 4".into())),
        Dash::Dotted => attributes.push(("stroke-dasharray", "1.5 3".into())),
    }
    attributes
}

/// Maximal runs of consecutive points that the frame can place, in pixels.
fn placeable_runs(frame: &Frame, points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut runs = vec![Vec::new()];
    for &p in points {
        match frame.point(p) {
            Some(pixel) => runs.last_mut().map_or((), |run| run.push(pixel)),
            None => runs.push(Vec::new()),
        }
    }
    runs.retain(|run| !run.is_empty());
    runs
}

fn draw_line(svg: &mut SvgWriter, frame: &Frame, points: &[(f64, f64)], stroke: Stroke) {
    for run in placeable_runs(frame, points) {
        let mut attributes = stroke_attributes(stroke);
        attributes.extend([
            ("class", "series".to_owned()),
            ("points", points_attribute(&run)),
        ]);
        svg.empty("polyline", &attributes);
    }
}

fn draw_marker(svg: &mut SvgWriter, class: &str, (cx, cy): (f64, f64), marker: Marker) {
    let r = marker.radius;
    let mut attributes = vec![
        ("class", class.to_owned()),
        ("stroke", marker.stroke.0.to_owned()),
        ("fill", marker.fill.map_or("#ffffff", |c| c.0).to_owned()),
        ("stroke-width", "1.2".to_owned()),
    ];
    let (name, geometry) = match marker.shape {
        Shape::Circle => (
            "circle",
            vec![
                ("cx", coordinate(cx)),
                ("cy", coordinate(cy)),
                ("r", coordinate(r)),
            ],
        ),
        Shape::Square => (
            "polygon",
            polygon(&[
                (cx - r, cy - r),
                (cx + r, cy - r),
                (cx + r, cy + r),
                (cx - r, cy + r),
            ]),
        ),
        Shape::Triangle => (
            "polygon",
            polygon(&[
                (cx, cy - 1.2 * r),
                (cx + 1.1 * r, cy + 0.8 * r),
                (cx - 1.1 * r, cy + 0.8 * r),
            ]),
        ),
        Shape::Diamond => (
            "polygon",
            polygon(&[
                (cx, cy - 1.3 * r),
                (cx + 1.3 * r, cy),
                (cx, cy + 1.3 * r),
                (cx - 1.3 * r, cy),
            ]),
        ),
    };
    attributes.extend(geometry);
    svg.empty(name, &attributes);
}

fn polygon(corners: &[(f64, f64)]) -> Vec<(&'static str, String)> {
    vec![("points", points_attribute(corners))]
}

fn draw_error_bar(
    svg: &mut SvgWriter,
    frame: &Frame,
    bar: &ErrorBar,
    marker: Marker,
    stroke: Stroke,
    offset_px: f64,
) {
    let Some((x, y)) = frame.point((bar.x, bar.y)) else {
        return;
    };
    let x = x + offset_px;
    if let Some(interval) = bar.interval {
        draw_interval(svg, frame, x, interval, stroke);
    }
    draw_marker(svg, "marker", (x, y), marker);
}

fn draw_interval(
    svg: &mut SvgWriter,
    frame: &Frame,
    x: f64,
    [low, high]: [Bound; 2],
    stroke: Stroke,
) {
    let a = frame.area;
    // An unbounded side, or one the axis cannot place, runs past the plot edge (clipped).
    let low_px = low
        .value()
        .and_then(|v| frame.y.pixel(v))
        .unwrap_or(a.bottom() + 2.0);
    let high_px = high
        .value()
        .and_then(|v| frame.y.pixel(v))
        .unwrap_or(a.top - 2.0);
    let mut attributes = stroke_attributes(stroke);
    attributes.extend(line_attributes((x, low_px), (x, high_px)));
    attributes.push(("class", "error-bar".into()));
    svg.empty("line", &attributes);
    for (bound, pixel) in [(low, low_px), (high, high_px)] {
        if let Bound::At(_) = bound {
            let mut cap = stroke_attributes(stroke);
            cap.extend(line_attributes((x - 4.0, pixel), (x + 4.0, pixel)));
            cap.push(("class", "error-cap".into()));
            svg.empty("line", &cap);
        }
    }
}

/// The opacity of a band's fill (and of its legend swatch).
const BAND_OPACITY: &str = "0.2";

/// The opacity of a span's fill (and of its legend swatch).
const SPAN_OPACITY: &str = "0.35";

fn draw_band(
    svg: &mut SvgWriter,
    frame: &Frame,
    x: &[f64],
    low: &[f64],
    high: &[f64],
    fill: Color,
) {
    // A column is drawn only when both of its edges can be placed; others split the band.
    let mut runs: Vec<Vec<[Pixel; 2]>> = vec![Vec::new()];
    for ((&xi, &lo), &hi) in x.iter().zip(low).zip(high) {
        match (frame.point((xi, hi)), frame.point((xi, lo))) {
            (Some(upper), Some(lower)) => runs.last_mut().map_or((), |r| r.push([upper, lower])),
            _ => runs.push(Vec::new()),
        }
    }
    for run in runs.iter().filter(|run| !run.is_empty()) {
        let outline: Vec<(f64, f64)> = run
            .iter()
            .map(|column| column[0])
            .chain(run.iter().rev().map(|column| column[1]))
            .collect();
        svg.empty(
            "polygon",
            &[
                ("class", "band".into()),
                ("points", points_attribute(&outline)),
                ("fill", fill.0.into()),
                ("fill-opacity", BAND_OPACITY.into()),
                ("stroke", "none".into()),
            ],
        );
    }
}

fn draw_spans(svg: &mut SvgWriter, frame: &Frame, ranges: &[(f64, f64)], fill: Color) {
    let a = frame.area;
    for &(from, to) in ranges {
        let (Some(x0), Some(x1)) = (frame.x.pixel(from), frame.x.pixel(to)) else {
            continue;
        };
        svg.empty(
            "rect",
            &[
                ("class", "span".into()),
                ("x", coordinate(x0.min(x1))),
                ("y", coordinate(a.top)),
                ("width", coordinate((x1 - x0).abs())),
                ("height", coordinate(a.height)),
                ("fill", fill.0.into()),
                ("fill-opacity", SPAN_OPACITY.into()),
            ],
        );
    }
}

/// One legend row per distinct layer name, right of the plot area.
fn draw_legend(svg: &mut SvgWriter, layers: &[Layer], a: PlotArea) {
    let mut seen: Vec<&str> = Vec::new();
    svg.start("g", &[("class", "legend".into())]);
    for layer in layers {
        let name = layer.name();
        if name.is_empty() || seen.contains(&name) {
            continue;
        }
        let y = a.top + 8.0 + seen.len() as f64 * LEGEND_ROW;
        seen.push(name);
        let x = a.right() + 12.0;
        draw_swatch(svg, layer, (x, y));
        svg.text_element(
            "text",
            &[
                ("class", "legend-entry".into()),
                ("x", coordinate(x + 30.0)),
                ("y", coordinate(y + 4.0)),
                ("font-size", "11".into()),
                ("fill", palette::INK.0.into()),
            ],
            name,
        );
    }
    svg.close("g");
}

fn draw_swatch(svg: &mut SvgWriter, layer: &Layer, (x, y): (f64, f64)) {
    let mid = (x + 12.0, y);
    match layer {
        Layer::Line { stroke, .. } => {
            let mut attributes = stroke_attributes(*stroke);
            attributes.extend(line_attributes((x, y), (x + 24.0, y)));
            svg.empty("line", &attributes);
        }
        Layer::Markers { marker, .. } => draw_marker(svg, "legend-swatch", mid, *marker),
        Layer::ErrorBars { marker, stroke, .. } => {
            let mut attributes = stroke_attributes(*stroke);
            attributes.extend(line_attributes((mid.0, y - 7.0), (mid.0, y + 7.0)));
            svg.empty("line", &attributes);
            draw_marker(svg, "legend-swatch", mid, *marker);
        }
        Layer::Band { fill, .. } => draw_area_swatch(svg, (x, y), *fill, BAND_OPACITY),
        Layer::Spans { fill, .. } => draw_area_swatch(svg, (x, y), *fill, SPAN_OPACITY),
    }
}

/// A legend swatch for a shaded area: a rectangle of its fill at its opacity.
fn draw_area_swatch(svg: &mut SvgWriter, (x, y): (f64, f64), fill: Color, opacity: &str) {
    svg.empty(
        "rect",
        &[
            ("class", "legend-swatch".into()),
            ("x", coordinate(x)),
            ("y", coordinate(y - 6.0)),
            ("width", "24".into()),
            ("height", "12".into()),
            ("fill", fill.0.into()),
            ("fill-opacity", opacity.into()),
        ],
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parsed_svg::{ParsedSvg, assert_complete_figure, number};

    fn one_panel(x: Axis, y: Axis, layers: Vec<Layer>) -> String {
        Figure::stacked(
            "test",
            vec![Chart {
                title: "panel".into(),
                x,
                y,
                layers,
            }],
        )
        .to_svg()
    }

    fn markers(name: &str, points: Vec<(f64, f64)>) -> Layer {
        Layer::Markers {
            name: name.into(),
            points,
            marker: Marker::filled(Shape::Circle, palette::series_color(0)),
        }
    }

    #[test]
    fn a_point_lands_where_the_axis_mappings_put_it() {
        let text = one_panel(
            Axis::linear("time (s)").with_range(0.0, 10.0),
            Axis::log10("deviation (m)").with_range(1.0, 1000.0),
            vec![markers("data", vec![(2.5, 10.0), (7.0, 300.0)])],
        );
        let svg = ParsedSvg::parse(&text);
        let area = svg.plot_areas()[0];
        let circles = svg.with_class("marker");
        assert_eq!(circles.len(), 2);
        for (circle, (x, y)) in circles.iter().zip([(2.5f64, 10.0f64), (7.0, 300.0)]) {
            let expected_x = area.left + x / 10.0 * area.width;
            let expected_y = area.bottom() - y.log10() / 3.0 * area.height;
            assert!((number(circle, "cx") - expected_x).abs() < 0.01);
            assert!((number(circle, "cy") - expected_y).abs() < 0.01);
        }
        assert_complete_figure(&svg);
    }

    #[test]
    fn log_axes_space_decades_equally_and_label_them_as_powers_of_ten() {
        let text = one_panel(
            Axis::log10("τ (s)"),
            Axis::log10("σ (rad/s)"),
            vec![markers("a", vec![(0.02, 3e-5), (700.0, 2e-2)])],
        );
        let svg = ParsedSvg::parse(&text);
        let xs: Vec<f64> = svg
            .with_class("grid major x")
            .iter()
            .map(|n| number(n, "x1"))
            .collect();
        assert_eq!(xs.len(), 6, "0.01 to 1000 s: six decades");
        let gaps: Vec<f64> = xs.windows(2).map(|w| w[1] - w[0]).collect();
        assert!(gaps.iter().all(|g| (g - gaps[0]).abs() < 0.02 && *g > 0.0));
        let area = svg.plot_areas()[0];
        assert!((xs[0] - area.left).abs() < 0.01 && (xs[5] - area.left - area.width).abs() < 0.01);
        let labels = svg.texts("tick-label x");
        assert_eq!(labels.first().map(String::as_str), Some("10\u{2212}2"));
        assert_eq!(labels.last().map(String::as_str), Some("103"));
        let ys: Vec<f64> = svg
            .with_class("grid major y")
            .iter()
            .map(|n| number(n, "y1"))
            .collect();
        let y_gaps: Vec<f64> = ys.windows(2).map(|w| w[0] - w[1]).collect();
        assert!(
            y_gaps
                .iter()
                .all(|g| (g - y_gaps[0]).abs() < 0.02 && *g > 0.0)
        );
    }

    #[test]
    fn the_legend_names_each_layer_once_and_skips_unnamed_ones() {
        let line = |name: &str| Layer::Line {
            name: name.into(),
            points: vec![(0.0, 1.0), (1.0, 2.0)],
            stroke: Stroke::solid(palette::series_color(1)),
        };
        let text = one_panel(
            Axis::linear("x (m)"),
            Axis::linear("y (m)"),
            vec![
                line("EKF"),
                line("EKF"),
                line(""),
                markers("UKF <b>", vec![(0.5, 1.5)]),
            ],
        );
        let svg = ParsedSvg::parse(&text);
        assert_eq!(svg.texts("legend-entry"), ["EKF", "UKF <b>"]);
        assert_eq!(svg.texts("axis-label x"), ["x (m)"]);
        assert_eq!(svg.texts("axis-label y"), ["y (m)"]);
    }

    /// Issue 38 row 18: a band's legend swatch has the band's colour and opacity (it was
    /// grey whatever the band's colour), and so has a span's.
    #[test]
    fn area_swatches_have_the_colour_and_opacity_of_their_area() {
        let blue = palette::series_color(0);
        let orange = palette::HIGHLIGHT;
        let text = one_panel(
            Axis::linear("x (m)"),
            Axis::linear("y (m)"),
            vec![
                Layer::Band {
                    name: "95 % band".into(),
                    x: vec![0.0, 1.0],
                    low: vec![0.0, 0.5],
                    high: vec![1.0, 1.5],
                    fill: blue,
                },
                Layer::Spans {
                    name: "outages".into(),
                    ranges: vec![(0.2, 0.4)],
                    fill: orange,
                },
            ],
        );
        let svg = ParsedSvg::parse(&text);
        let paint = |node: &roxmltree::Node| {
            (
                node.attribute("fill").unwrap().to_string(),
                node.attribute("fill-opacity").unwrap().to_string(),
            )
        };
        let swatches: Vec<_> = svg.with_class("legend-swatch").iter().map(paint).collect();
        let band = paint(&svg.with_class("band")[0]);
        let span = paint(&svg.with_class("span")[0]);
        assert_eq!(band.0, blue.0);
        assert_eq!(span.0, orange.0);
        assert_eq!(swatches, [band, span]);
    }

    #[test]
    fn unplaceable_points_break_lines_and_are_left_out() {
        let text = one_panel(
            Axis::linear("x (s)"),
            Axis::log10("y (m)"),
            vec![Layer::Line {
                name: "line".into(),
                points: vec![
                    (0.0, 1.0),
                    (1.0, 2.0),
                    (2.0, -1.0),
                    (3.0, 3.0),
                    (4.0, f64::NAN),
                    (5.0, 4.0),
                    (6.0, 5.0),
                ],
                stroke: Stroke::solid(palette::INK),
            }],
        );
        let svg = ParsedSvg::parse(&text);
        let runs: Vec<usize> = svg
            .with_class("series")
            .iter()
            .map(|n| n.attribute("points").unwrap().split(' ').count())
            .collect();
        assert_eq!(runs, [2, 1, 2]);
    }

    #[test]
    fn error_bars_end_at_their_bounds_or_run_past_the_edge_when_unbounded() {
        let text = one_panel(
            Axis::linear("T (°C)").with_range(0.0, 40.0),
            Axis::linear("Tc (s)").with_range(0.0, 100.0),
            vec![Layer::ErrorBars {
                name: "ML".into(),
                bars: vec![
                    ErrorBar {
                        x: 10.0,
                        y: 50.0,
                        interval: Some([Bound::At(40.0), Bound::At(70.0)]),
                    },
                    ErrorBar {
                        x: 30.0,
                        y: 50.0,
                        interval: Some([Bound::At(20.0), Bound::Unbounded]),
                    },
                    ErrorBar {
                        x: 35.0,
                        y: 50.0,
                        interval: None,
                    },
                ],
                marker: Marker::filled(Shape::Circle, palette::INK),
                stroke: Stroke::solid(palette::INK),
                offset_px: 0.0,
            }],
        );
        let svg = ParsedSvg::parse(&text);
        let area = svg.plot_areas()[0];
        let y_of = |v: f64| area.bottom() - v / 100.0 * area.height;
        let bars = svg.with_class("error-bar");
        let ends = |n: &roxmltree::Node| (number(n, "y1"), number(n, "y2"));
        let (low, high) = ends(&bars[0]);
        assert!((low - y_of(40.0)).abs() < 0.01 && (high - y_of(70.0)).abs() < 0.01);
        let (low, high) = ends(&bars[1]);
        assert!((low - y_of(20.0)).abs() < 0.01 && high < area.top);
        assert_eq!(svg.with_class("error-cap").len(), 3);
        assert_eq!(bars.len(), 2, "no bar without an interval");
        assert_eq!(svg.with_class("marker").len(), 3);
        let x = number(&bars[1], "x1");
        assert!((x - (area.left + 0.75 * area.width)).abs() < 0.01);
    }

    #[test]
    fn panels_fill_rows_of_the_given_columns() {
        let panel = |title: &str| Chart {
            title: title.into(),
            x: Axis::linear("x (s)"),
            y: Axis::linear("y (s)"),
            layers: vec![markers("p", vec![(0.0, 0.0)])],
        };
        let figure = Figure {
            title: "grid".into(),
            columns: 2,
            panels: vec![panel("a"), panel("b"), panel("c")],
        };
        let text = figure.to_svg();
        let svg = ParsedSvg::parse(&text);
        let areas = svg.plot_areas();
        assert_eq!(areas.len(), 3);
        assert!((areas[1].left - areas[0].left - PANEL_WIDTH).abs() < 1e-9);
        assert!((areas[2].top - areas[0].top - PANEL_HEIGHT).abs() < 1e-9);
        let root = roxmltree::Document::parse(&text).unwrap();
        assert_eq!(number(&root.root_element(), "width"), 2.0 * PANEL_WIDTH);
        assert_complete_figure(&svg);
    }
}
