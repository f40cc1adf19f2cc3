//! PNG images of this crate's figures, rasterised in pure Rust (tiny-skia) with the bundled
//! DejaVu Sans font (ab_glyph), so a PNG looks the same on every machine.
//!
//! This is not a general SVG renderer: it draws the subset of SVG that [`crate::chart`]
//! writes — `rect`, `line`, `polyline`, `polygon`, `circle`, `text` with `tspan` (raised
//! exponents) and a −90° rotation, and groups clipped by a rectangular `clipPath` — with
//! solid fills and strokes, opacities and dash patterns. Anything else is skipped.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};
use roxmltree::{Document, Node};
use std::collections::HashMap;
use tiny_skia::{
    FillRule, Mask, Paint, Path, PathBuilder, Pixmap, PremultipliedColorU8, Rect, Stroke,
    StrokeDash, Transform,
};

/// Why a figure could not be rasterised.
#[derive(Debug, thiserror::Error)]
pub enum PngError {
    /// The SVG text is not well-formed XML.
    #[error("the figure is not well-formed SVG: {0}")]
    Svg(#[from] roxmltree::Error),
    /// The root lacks a positive width or height.
    #[error("the figure has no usable width and height")]
    Size,
    /// The bundled font could not be read.
    #[error("the bundled font cannot be read")]
    Font,
    /// Encoding failed.
    #[error("PNG encoding failed: {0}")]
    Encode(String),
}

/// The figure's SVG rendered at its own pixel size, encoded as PNG.
///
/// # Errors
/// [`PngError`] when the SVG does not parse, has no size, or encoding fails.
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, PngError> {
    let document = Document::parse(svg)?;
    let root = document.root_element();
    let (width, height) = (number(root, "width", 0.0), number(root, "height", 0.0));
    if !(width >= 1.0 && height >= 1.0 && width <= 20_000.0 && height <= 20_000.0) {
        return Err(PngError::Size);
    }
    let mut pixmap =
        Pixmap::new(width.round() as u32, height.round() as u32).ok_or(PngError::Size)?;
    pixmap.fill(tiny_skia::Color::WHITE);
    let font = FontRef::try_from_slice(dejavu::sans::regular()).map_err(|_| PngError::Font)?;
    let clips = clip_rectangles(&document);
    let mut canvas = Canvas {
        pixmap,
        font,
        clips,
        default_font_size: number(root, "font-size", 12.0),
    };
    canvas.draw_children(root, None);
    canvas
        .pixmap
        .encode_png()
        .map_err(|e| PngError::Encode(e.to_string()))
}

/// The rectangles of the `clipPath` elements, by id.
fn clip_rectangles(document: &Document) -> HashMap<String, Rect> {
    document
        .descendants()
        .filter(|n| n.has_tag_name("clipPath"))
        .filter_map(|clip| {
            let id = clip.attribute("id")?.to_owned();
            let rect = clip.children().find(|c| c.has_tag_name("rect"))?;
            let area = Rect::from_xywh(
                number(rect, "x", 0.0) as f32,
                number(rect, "y", 0.0) as f32,
                number(rect, "width", 0.0) as f32,
                number(rect, "height", 0.0) as f32,
            )?;
            Some((id, area))
        })
        .collect()
}

fn number(node: Node, name: &str, default: f64) -> f64 {
    node.attribute(name)
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or(default)
}

/// `#rrggbb` (or `none`) with an opacity, as a paint; `None` for no paint.
fn paint_of(color: Option<&str>, opacity: f64) -> Option<Paint<'static>> {
    let hex = color?.strip_prefix('#')?;
    if hex.len() != 6 {
        return None;
    }
    let channel = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
    let alpha = (opacity.clamp(0.0, 1.0) * 255.0).round() as u8;
    let mut paint = Paint::default();
    paint.set_color_rgba8(channel(0)?, channel(2)?, channel(4)?, alpha);
    paint.anti_alias = true;
    Some(paint)
}

fn polyline_path(points: &str, closed: bool) -> Option<Path> {
    let mut builder = PathBuilder::new();
    for (i, pair) in points.split_whitespace().enumerate() {
        let (x, y) = pair.split_once(',')?;
        let (x, y) = (x.parse().ok()?, y.parse().ok()?);
        if i == 0 {
            builder.move_to(x, y);
        } else {
            builder.line_to(x, y);
        }
    }
    if closed {
        builder.close();
    }
    builder.finish()
}

fn geometry(node: Node) -> Option<Path> {
    let n = |name: &str| number(node, name, 0.0) as f32;
    match node.tag_name().name() {
        "rect" => Some(PathBuilder::from_rect(Rect::from_xywh(
            n("x"),
            n("y"),
            n("width"),
            n("height"),
        )?)),
        "line" => {
            let mut builder = PathBuilder::new();
            builder.move_to(n("x1"), n("y1"));
            builder.line_to(n("x2"), n("y2"));
            builder.finish()
        }
        "polyline" => polyline_path(node.attribute("points")?, false),
        "polygon" => polyline_path(node.attribute("points")?, true),
        "circle" => PathBuilder::from_circle(n("cx"), n("cy"), n("r")),
        _ => None,
    }
}

fn stroke_of(node: Node) -> Stroke {
    let dash = node.attribute("stroke-dasharray").and_then(|d| {
        let values: Option<Vec<f32>> = d.split_whitespace().map(|v| v.parse().ok()).collect();
        StrokeDash::new(values?, 0.0)
    });
    Stroke {
        width: number(node, "stroke-width", 1.0) as f32,
        line_join: tiny_skia::LineJoin::Round,
        dash,
        ..Stroke::default()
    }
}

/// A run of text at one size and baseline shift.
struct TextRun {
    text: String,
    size: f32,
    dy: f32,
}

struct Canvas<'f> {
    pixmap: Pixmap,
    font: FontRef<'f>,
    clips: HashMap<String, Rect>,
    default_font_size: f64,
}

impl Canvas<'_> {
    fn draw_children(&mut self, parent: Node, mask: Option<&Mask>) {
        for child in parent.children().filter(Node::is_element) {
            match child.tag_name().name() {
                "clipPath" => {}
                "g" => {
                    let clip = child
                        .attribute("clip-path")
                        .and_then(|r| r.strip_prefix("url(#")?.strip_suffix(')'))
                        .and_then(|id| self.mask_of(id));
                    self.draw_children(child, clip.as_ref().or(mask));
                }
                "text" => self.draw_text(child),
                _ => self.draw_shape(child, mask),
            }
        }
    }

    fn mask_of(&self, id: &str) -> Option<Mask> {
        let rect = self.clips.get(id)?;
        let mut mask = Mask::new(self.pixmap.width(), self.pixmap.height())?;
        mask.fill_path(
            &PathBuilder::from_rect(*rect),
            FillRule::Winding,
            false,
            Transform::identity(),
        );
        Some(mask)
    }

    fn draw_shape(&mut self, node: Node, mask: Option<&Mask>) {
        let Some(path) = geometry(node) else {
            return;
        };
        let fill_opacity = number(node, "fill-opacity", 1.0);
        // SVG fills by default; the chart module always says `none` where it means none.
        let fill = node.attribute("fill").or(Some("#000000"));
        if let Some(paint) = paint_of(fill, fill_opacity) {
            if node.tag_name().name() != "line" {
                self.pixmap.fill_path(
                    &path,
                    &paint,
                    FillRule::Winding,
                    Transform::identity(),
                    mask,
                );
            }
        }
        if let Some(paint) = paint_of(node.attribute("stroke"), 1.0) {
            self.pixmap
                .stroke_path(&path, &paint, &stroke_of(node), Transform::identity(), mask);
        }
    }

    fn text_runs(&self, node: Node) -> Vec<TextRun> {
        let size = number(node, "font-size", self.default_font_size) as f32;
        let mut runs = Vec::new();
        let mut dy = 0.0;
        for child in node.children() {
            if child.is_text() {
                runs.push(TextRun {
                    text: child.text().unwrap_or_default().to_owned(),
                    size,
                    dy,
                });
            } else if child.has_tag_name("tspan") {
                dy += number(child, "dy", 0.0) as f32;
                runs.push(TextRun {
                    text: child.text().unwrap_or_default().to_owned(),
                    size: number(child, "font-size", f64::from(size)) as f32,
                    dy,
                });
            }
        }
        runs
    }

    fn scale(&self, size: f32) -> PxScale {
        let units_per_em = self.font.units_per_em().unwrap_or(2048.0);
        PxScale::from(size * self.font.height_unscaled() / units_per_em)
    }

    fn advance(&self, run: &TextRun) -> f32 {
        let scaled = self.font.as_scaled(self.scale(run.size));
        run.text
            .chars()
            .map(|c| scaled.h_advance(scaled.glyph_id(c)))
            .sum()
    }

    fn draw_text(&mut self, node: Node) {
        let runs = self.text_runs(node);
        let width: f32 = runs.iter().map(|r| self.advance(r)).sum();
        let (x, y) = (number(node, "x", 0.0) as f32, number(node, "y", 0.0) as f32);
        let start = match node.attribute("text-anchor") {
            Some("middle") => x - width / 2.0,
            Some("end") => x - width,
            _ => x,
        };
        let rotation = rotation_centre(node.attribute("transform"));
        let color = node.attribute("fill").unwrap_or("#000000");
        let Some(paint) = paint_of(Some(color), 1.0) else {
            return;
        };
        let rgb = paint_rgb(&paint);
        let mut pen = start;
        for run in &runs {
            let scale = self.scale(run.size);
            let scaled = self.font.as_scaled(scale);
            for c in run.text.chars() {
                let id = scaled.glyph_id(c);
                let glyph = id.with_scale_and_position(scale, point(pen, y + run.dy));
                pen += scaled.h_advance(id);
                if let Some(outline) = self.font.outline_glyph(glyph) {
                    let bounds = outline.px_bounds();
                    let pixmap = &mut self.pixmap;
                    outline.draw(|gx, gy, coverage| {
                        let px = bounds.min.x + gx as f32;
                        let py = bounds.min.y + gy as f32;
                        let (px, py) = match rotation {
                            Some((cx, cy)) => (cx + (py - cy), cy - (px - cx)),
                            None => (px, py),
                        };
                        blend(pixmap, px, py, rgb, coverage);
                    });
                }
            }
        }
    }
}

/// The centre of a `rotate(-90 cx cy)` transform (the only rotation the charts use).
fn rotation_centre(transform: Option<&str>) -> Option<(f32, f32)> {
    let inner = transform?
        .trim()
        .strip_prefix("rotate(")?
        .strip_suffix(')')?;
    let values: Vec<f32> = inner
        .split([' ', ','])
        .filter(|v| !v.is_empty())
        .filter_map(|v| v.parse().ok())
        .collect();
    match values[..] {
        [angle, cx, cy] if (angle + 90.0).abs() < 1e-3 => Some((cx, cy)),
        _ => None,
    }
}

fn paint_rgb(paint: &Paint) -> [u8; 3] {
    match &paint.shader {
        tiny_skia::Shader::SolidColor(c) => {
            let c = c.to_color_u8();
            [c.red(), c.green(), c.blue()]
        }
        _ => [0, 0, 0],
    }
}

/// Paints `rgb` over the pixel at `(x, y)` with `coverage` in [0, 1].
fn blend(pixmap: &mut Pixmap, x: f32, y: f32, rgb: [u8; 3], coverage: f32) {
    let (width, height) = (pixmap.width() as f32, pixmap.height() as f32);
    if !(x >= 0.0 && y >= 0.0 && x < width && y < height) {
        return;
    }
    let index = y as usize * pixmap.width() as usize + x as usize;
    let a = coverage.clamp(0.0, 1.0);
    let pixels = pixmap.pixels_mut();
    let old = pixels[index];
    let mix = |src: u8, dst: u8| (f32::from(src) * a + f32::from(dst) * (1.0 - a)).round() as u8;
    let alpha = mix(255, old.alpha());
    let color = PremultipliedColorU8::from_rgba(
        mix(rgb[0], old.red()).min(alpha),
        mix(rgb[1], old.green()).min(alpha),
        mix(rgb[2], old.blue()).min(alpha),
        alpha,
    );
    if let Some(color) = color {
        pixels[index] = color;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chart::{Chart, Figure, Layer, Marker, Shape};
    use crate::palette;
    use crate::parsed_svg::{ParsedSvg, number as attribute};
    use crate::scale::Axis;

    fn decode(png: &[u8]) -> Pixmap {
        Pixmap::decode_png(png).expect("the PNG decodes")
    }

    fn rgb(pixmap: &Pixmap, x: f64, y: f64) -> [u8; 3] {
        let p = pixmap.pixel(x as u32, y as u32).expect("inside the image");
        [p.red(), p.green(), p.blue()]
    }

    fn chart_with(layers: Vec<Layer>) -> String {
        Figure::stacked(
            "PNG test",
            vec![Chart {
                title: "panel".into(),
                x: Axis::linear("x (m)").with_range(0.0, 10.0),
                y: Axis::linear("y (m)").with_range(0.0, 10.0),
                layers,
            }],
        )
        .to_svg()
    }

    #[test]
    fn the_image_has_the_figure_size_and_markers_land_where_the_svg_puts_them() {
        let svg = chart_with(vec![Layer::Markers {
            name: "big".into(),
            points: vec![(3.0, 7.0)],
            marker: Marker {
                radius: 6.0,
                ..Marker::filled(Shape::Circle, palette::series_color(0))
            },
        }]);
        let image = decode(&svg_to_png(&svg).unwrap());
        let parsed = ParsedSvg::parse(&svg);
        let root = roxmltree::Document::parse(&svg).unwrap();
        assert_eq!(
            f64::from(image.width()),
            attribute(&root.root_element(), "width")
        );
        assert_eq!(
            f64::from(image.height()),
            attribute(&root.root_element(), "height")
        );
        let marker = parsed.with_class("marker")[0];
        let (cx, cy) = (attribute(&marker, "cx"), attribute(&marker, "cy"));
        assert_eq!(rgb(&image, cx, cy), [0x00, 0x72, 0xb2]);
        // Ten pixels right of the marker there is only the white plot background.
        assert_eq!(rgb(&image, cx + 10.0, cy), [255, 255, 255]);
    }

    #[test]
    fn data_are_clipped_to_the_plot_area() {
        let svg = chart_with(vec![Layer::Line {
            name: "long".into(),
            points: vec![(-100.0, 5.0), (100.0, 5.0)],
            stroke: crate::chart::Stroke {
                width: 4.0,
                ..crate::chart::Stroke::solid(palette::INK)
            },
        }]);
        let image = decode(&svg_to_png(&svg).unwrap());
        let area = ParsedSvg::parse(&svg).plot_areas()[0];
        let y = area.top + area.height / 2.0;
        assert_eq!(rgb(&image, area.left + 20.0, y), [0x33, 0x33, 0x33]);
        assert_eq!(rgb(&image, area.left - 3.0, y), [255, 255, 255]);
        assert_eq!(
            rgb(&image, area.left + area.width + 3.0, y),
            [255, 255, 255]
        );
    }

    /// The bounding box (width, height) of the non-white pixels.
    fn ink_extent(pixmap: &Pixmap) -> (u32, u32) {
        let (mut x0, mut y0, mut x1, mut y1) = (u32::MAX, u32::MAX, 0, 0);
        for y in 0..pixmap.height() {
            for x in 0..pixmap.width() {
                let p = pixmap.pixel(x, y).unwrap();
                if p.red() < 128 {
                    (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
                }
            }
        }
        assert!(x1 >= x0, "some text was drawn");
        (x1 - x0 + 1, y1 - y0 + 1)
    }

    #[test]
    fn text_is_drawn_with_the_bundled_font_and_turned_by_rotate_minus_90() {
        let text = |transform: &str| {
            format!(
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200\" height=\"200\" \
                 font-size=\"20\"><text x=\"100\" y=\"100\" text-anchor=\"middle\" \
                 fill=\"#000000\"{transform}>averaging τ (s)</text></svg>"
            )
        };
        let flat = ink_extent(&decode(&svg_to_png(&text("")).unwrap()));
        let turned = " transform=\"rotate(-90 100 100)\"";
        let upright = ink_extent(&decode(&svg_to_png(&text(turned)).unwrap()));
        assert!(flat.0 > 3 * flat.1, "a line of text is wide: {flat:?}");
        assert_eq!(
            (upright.0, upright.1),
            (flat.1, flat.0),
            "the same text on its side"
        );
    }

    #[test]
    fn malformed_or_sizeless_svg_is_an_error() {
        assert!(matches!(svg_to_png("<svg"), Err(PngError::Svg(_))));
        let sizeless = "<svg xmlns=\"http://www.w3.org/2000/svg\"></svg>";
        assert!(matches!(svg_to_png(sizeless), Err(PngError::Size)));
    }
}
