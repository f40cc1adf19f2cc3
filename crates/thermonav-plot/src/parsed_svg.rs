//! Reading back the SVG this crate writes, for tests: the elements of a class, plot areas,
//! legend and axis texts.

use roxmltree::{Document, Node};

/// A parsed SVG document (panics on malformed XML: that is a test failure).
pub struct ParsedSvg<'a> {
    document: Document<'a>,
}

/// A plot area rectangle, px.
#[derive(Debug, Clone, Copy)]
pub struct Rectangle {
    pub left: f64,
    pub top: f64,
    pub width: f64,
    pub height: f64,
}

impl Rectangle {
    pub fn bottom(&self) -> f64 {
        self.top + self.height
    }
}

impl<'a> ParsedSvg<'a> {
    pub fn parse(text: &'a str) -> Self {
        let document = Document::parse(text).expect("the SVG is well-formed XML");
        let root = document.root_element();
        assert_eq!(root.tag_name().name(), "svg");
        assert_eq!(
            root.tag_name().namespace(),
            Some("http://www.w3.org/2000/svg")
        );
        Self { document }
    }

    /// Elements whose class list holds every one of `classes` (space-separated).
    pub fn with_class(&self, classes: &str) -> Vec<Node<'_, 'a>> {
        let wanted: Vec<&str> = classes.split_whitespace().collect();
        self.document
            .descendants()
            .filter(|n| {
                n.attribute("class").is_some_and(|c| {
                    let have: Vec<&str> = c.split_whitespace().collect();
                    wanted.iter().all(|w| have.contains(w))
                })
            })
            .collect()
    }

    /// The text of each element of the classes, tspans included.
    pub fn texts(&self, classes: &str) -> Vec<String> {
        self.with_class(classes)
            .iter()
            .map(|n| {
                n.descendants()
                    .filter(Node::is_text)
                    .filter_map(|t| t.text())
                    .collect()
            })
            .collect()
    }

    /// The plot areas of the panels, in drawing order.
    pub fn plot_areas(&self) -> Vec<Rectangle> {
        self.with_class("plot-area")
            .iter()
            .map(|n| Rectangle {
                left: number(n, "x"),
                top: number(n, "y"),
                width: number(n, "width"),
                height: number(n, "height"),
            })
            .collect()
    }

    /// Every element (for whole-document checks).
    pub fn all(&self) -> impl Iterator<Item = Node<'_, 'a>> {
        self.document.descendants().filter(Node::is_element)
    }
}

/// A numeric attribute.
pub fn number(node: &Node, name: &str) -> f64 {
    node.attribute(name)
        .unwrap_or_else(|| panic!("<{}> has {name}", node.tag_name().name()))
        .parse()
        .expect("a number")
}

/// Checks what every figure must have: no script or external reference, a legend entry and a
/// unit in parentheses in both axis labels of every panel.
pub fn assert_complete_figure(svg: &ParsedSvg) {
    for node in svg.all() {
        assert_ne!(node.tag_name().name(), "script");
        for attribute in node.attributes() {
            assert!(
                !attribute.name().contains("href"),
                "no external reference: {attribute:?}"
            );
        }
    }
    let panels = svg.with_class("panel");
    assert!(!panels.is_empty());
    for panel in panels {
        let texts_of = |class: &str| -> Vec<String> {
            panel
                .descendants()
                .filter(|n| n.attribute("class") == Some(class))
                .map(|n| n.text().unwrap_or_default().to_owned())
                .collect()
        };
        for label in texts_of("axis-label x")
            .iter()
            .chain(&texts_of("axis-label y"))
        {
            assert!(
                label.contains('(') && label.ends_with(')'),
                "axis label with a unit: {label}"
            );
        }
        assert_eq!(texts_of("axis-label x").len(), 1);
        assert_eq!(texts_of("axis-label y").len(), 1);
        assert!(
            !texts_of("legend-entry").is_empty(),
            "every panel has a legend"
        );
    }
}

/// The pixel of a data value on one axis of one panel, read off two of its labelled grid
/// lines (`data-value` and position); `log` takes log₁₀ of values first.
pub fn grid_mapping(svg: &ParsedSvg, panel: usize, axis: &str, log: bool) -> impl Fn(f64) -> f64 {
    let panel_node = svg.with_class("panel")[panel];
    let lines: Vec<(f64, f64)> = panel_node
        .descendants()
        .filter(|n| n.attribute("class") == Some(&format!("grid major {axis}")))
        .map(|n| {
            let value: f64 = n.attribute("data-value").unwrap().parse().unwrap();
            let pixel = number(&n, if axis == "x" { "x1" } else { "y1" });
            (if log { value.log10() } else { value }, pixel)
        })
        .collect();
    assert!(lines.len() >= 2, "two grid lines to read the mapping from");
    let ((v0, p0), (v1, p1)) = (lines[0], lines[lines.len() - 1]);
    move |value: f64| {
        let t = if log { value.log10() } else { value };
        p0 + (t - v0) / (v1 - v0) * (p1 - p0)
    }
}

/// The `(x, y)` pairs of a polyline's `points` attribute.
pub fn polyline_points(node: &Node) -> Vec<(f64, f64)> {
    node.attribute("points")
        .unwrap()
        .split(' ')
        .map(|pair| {
            let (x, y) = pair.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// The layer groups named `name`.
pub fn layers_named<'d, 'i>(svg: &'d ParsedSvg<'i>, name: &str) -> Vec<Node<'d, 'i>> {
    svg.with_class("layer")
        .into_iter()
        .filter(|n| n.attribute("data-name") == Some(name))
        .collect()
}
