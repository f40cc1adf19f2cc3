//! Writing SVG elements: escaped text and attribute values, compact coordinates.

use std::fmt::Write as _;

/// Fonts tried in order; all are common or generic, none is fetched.
pub const FONT_FAMILY: &str = "'DejaVu Sans', 'Liberation Sans', Arial, Helvetica, sans-serif";

/// `text` with the five XML special characters replaced by entities, safe in element content
/// and in quoted attribute values of both XML (SVG) and HTML.
pub fn escape_markup(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

/// A pixel coordinate with at most two decimals and no trailing zeros.
pub fn coordinate(value: f64) -> String {
    let text = format!("{value:.2}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_owned()
    } else {
        text.to_owned()
    }
}

/// An SVG document being written, element by element.
#[derive(Debug)]
pub struct SvgWriter {
    out: String,
}

impl SvgWriter {
    /// Opens a `width` × `height` pixel document on a white background.
    pub fn new(width: f64, height: f64) -> Self {
        let mut writer = Self { out: String::new() };
        let (w, h) = (coordinate(width), coordinate(height));
        let _ = writeln!(
            writer.out,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
             viewBox=\"0 0 {w} {h}\" font-family=\"{}\" font-size=\"12\">",
            escape_markup(FONT_FAMILY)
        );
        writer.empty(
            "rect",
            &[
                ("width", w.clone()),
                ("height", h.clone()),
                ("fill", "#ffffff".into()),
            ],
        );
        writer
    }

    /// An element without content: `<name a="v" .../>`.
    pub fn empty(&mut self, name: &str, attributes: &[(&str, String)]) {
        self.open_tag(name, attributes);
        self.out.push_str("/>\n");
    }

    /// An element holding escaped `text`.
    pub fn text_element(&mut self, name: &str, attributes: &[(&str, String)], text: &str) {
        self.open_tag(name, attributes);
        let _ = writeln!(self.out, ">{}</{name}>", escape_markup(text));
    }

    /// An element holding markup that the caller has built from escaped parts.
    pub fn markup_element(&mut self, name: &str, attributes: &[(&str, String)], markup: &str) {
        self.open_tag(name, attributes);
        let _ = writeln!(self.out, ">{markup}</{name}>");
    }

    /// Opens an element that later [`SvgWriter::close`] ends.
    pub fn start(&mut self, name: &str, attributes: &[(&str, String)]) {
        self.open_tag(name, attributes);
        self.out.push_str(">\n");
    }

    /// Ends the element `name` opened by [`SvgWriter::start`].
    pub fn close(&mut self, name: &str) {
        let _ = writeln!(self.out, "</{name}>");
    }

    /// The finished document.
    pub fn finish(mut self) -> String {
        self.out.push_str("</svg>\n");
        self.out
    }

    fn open_tag(&mut self, name: &str, attributes: &[(&str, String)]) {
        let _ = write!(self.out, "<{name}");
        for (key, value) in attributes {
            let _ = write!(self.out, " {key}=\"{}\"", escape_markup(value));
        }
    }
}

/// Space-separated `x,y` pairs of a polyline.
pub fn points_attribute(points: &[(f64, f64)]) -> String {
    points
        .iter()
        .map(|&(x, y)| format!("{},{}", coordinate(x), coordinate(y)))
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markup_characters_become_entities_and_parse_back() {
        let nasty = "a<b & c>\"d\" 'e' </svg>";
        let mut svg = SvgWriter::new(10.0, 10.0);
        svg.text_element("text", &[("data-note", nasty.into())], nasty);
        let doc = svg.finish();
        let tree = roxmltree::Document::parse(&doc).expect("the SVG is well-formed XML");
        let text = tree.descendants().find(|n| n.has_tag_name("text")).unwrap();
        assert_eq!(text.text(), Some(nasty));
        assert_eq!(text.attribute("data-note"), Some(nasty));
    }

    #[test]
    fn coordinates_are_short_and_never_negative_zero() {
        assert_eq!(coordinate(12.0), "12");
        assert_eq!(coordinate(12.346), "12.35");
        assert_eq!(coordinate(0.5), "0.5");
        assert_eq!(coordinate(-0.001), "0");
    }
}
