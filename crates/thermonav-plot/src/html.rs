//! Self-contained HTML pages: a title and sections of paragraphs, tables and inline SVG
//! figures, with inline CSS and no script or external reference.
//!
//! All text is escaped. The markup is also well-formed XML (void elements are self-closed),
//! so a page can be checked with an XML parser. Figures are the SVG documents of this crate's
//! figure functions; each one's element ids get a prefix of its own, so that several figures
//! on one page never share an id.

use crate::chart::prefix_ids;
use crate::svg::{FONT_FAMILY, escape_markup};
use std::fmt::Write as _;

/// A page: title and sections in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Page {
    /// The page title (also the top heading).
    pub title: String,
    /// The sections.
    pub sections: Vec<Section>,
}

/// A headed section.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    /// Heading.
    pub heading: String,
    /// Content, in order.
    pub blocks: Vec<Block>,
}

/// One piece of section content.
#[derive(Debug, Clone, PartialEq)]
pub enum Block {
    /// A paragraph of plain text.
    Paragraph(String),
    /// A table of plain-text cells.
    Table(Table),
    /// An SVG figure with a caption.
    Figure(InlineFigure),
}

/// A table with a caption and a header row.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Caption (plain text).
    pub caption: String,
    /// Column headings.
    pub header: Vec<String>,
    /// Rows of cells.
    pub rows: Vec<Vec<String>>,
}

/// An SVG document written by this crate's figure functions, and its caption (plain text).
#[derive(Debug, Clone, PartialEq)]
pub struct InlineFigure {
    /// The SVG document (trusted markup: it is inserted as it is, apart from id prefixes).
    pub svg: String,
    /// Caption.
    pub caption: String,
}

const STYLE: &str = "body{max-width:1500px;margin:2em auto;padding:0 1em;color:#222;\
line-height:1.45}table{border-collapse:collapse;margin:1em 0}caption{text-align:left;\
font-weight:bold;padding:0.3em 0}th,td{border:1px solid #bbb;padding:0.25em 0.6em;\
text-align:right}th{background:#f2f2f2}figure{margin:1.5em 0}figure svg{max-width:100%;\
height:auto}figcaption{font-style:italic;margin-top:0.4em}";

/// The page as one HTML document.
pub fn render_page(page: &Page) -> String {
    let mut out = String::new();
    let title = escape_markup(&page.title);
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>\n\
         <title>{title}</title>\n<style>body{{font-family:{}}}{STYLE}</style>\n</head>\n\
         <body>\n<h1>{title}</h1>\n",
        escape_markup(FONT_FAMILY)
    );
    let mut figure_count = 0;
    for section in &page.sections {
        let _ = writeln!(
            out,
            "<section>\n<h2>{}</h2>",
            escape_markup(&section.heading)
        );
        for block in &section.blocks {
            match block {
                Block::Paragraph(text) => {
                    let _ = writeln!(out, "<p>{}</p>", escape_markup(text));
                }
                Block::Table(table) => out.push_str(&table_markup(table)),
                Block::Figure(figure) => {
                    figure_count += 1;
                    out.push_str(&figure_markup(figure, figure_count));
                }
            }
        }
        out.push_str("</section>\n");
    }
    out.push_str("</body>\n</html>\n");
    out
}

fn table_markup(table: &Table) -> String {
    let row = |cells: &[String], tag: &str| -> String {
        let cells: String = cells
            .iter()
            .map(|c| format!("<{tag}>{}</{tag}>", escape_markup(c)))
            .collect();
        format!("<tr>{cells}</tr>\n")
    };
    let body: String = table.rows.iter().map(|r| row(r, "td")).collect();
    format!(
        "<table>\n<caption>{}</caption>\n<thead>\n{}</thead>\n<tbody>\n{body}</tbody>\n</table>\n",
        escape_markup(&table.caption),
        row(&table.header, "th"),
    )
}

fn figure_markup(figure: &InlineFigure, number: usize) -> String {
    let svg = prefix_ids(figure.svg.trim(), &format!("figure-{number}-"));
    format!(
        "<figure>\n{svg}\n<figcaption>{}</figcaption>\n</figure>\n",
        escape_markup(&figure.caption)
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chart::{Chart, Figure, Layer, Marker, Shape};
    use crate::palette;
    use crate::scale::Axis;

    const NASTY: &str = "<script>alert('x')</script> & \"quotes\" </p>";

    fn small_figure(title: &str) -> String {
        Figure::stacked(
            title,
            vec![Chart {
                title: "p".into(),
                x: Axis::linear("x (s)"),
                y: Axis::linear("y (m)"),
                layers: vec![Layer::Markers {
                    name: "m".into(),
                    points: vec![(1.0, 2.0)],
                    marker: Marker::filled(Shape::Circle, palette::INK),
                }],
            }],
        )
        .to_svg()
    }

    /// Parses a page as XML (its doctype is a DTD to the parser).
    fn parse(html: &str) -> roxmltree::Document<'_> {
        let options = roxmltree::ParsingOptions {
            allow_dtd: true,
            ..Default::default()
        };
        roxmltree::Document::parse_with_options(html, options).expect("the page is well-formed")
    }

    fn page() -> Page {
        Page {
            title: format!("Report {NASTY}"),
            sections: vec![Section {
                heading: NASTY.into(),
                blocks: vec![
                    Block::Paragraph(NASTY.into()),
                    Block::Table(Table {
                        caption: NASTY.into(),
                        header: vec!["T (°C)".into(), "<b>Tc</b> (s)".into()],
                        rows: vec![vec!["20".into(), NASTY.into()]],
                    }),
                    Block::Figure(InlineFigure {
                        svg: small_figure("one"),
                        caption: NASTY.into(),
                    }),
                    Block::Figure(InlineFigure {
                        svg: small_figure("two"),
                        caption: "second".into(),
                    }),
                ],
            }],
        }
    }

    #[test]
    fn text_is_escaped_and_reads_back_unchanged() {
        let html = render_page(&page());
        let doc = parse(&html);
        let text_of = |tag: &str| -> Vec<String> {
            doc.descendants()
                .filter(|n| n.has_tag_name(tag))
                .map(|n| {
                    n.descendants()
                        .filter(|t| t.is_text())
                        .filter_map(|t| t.text())
                        .collect()
                })
                .collect()
        };
        assert_eq!(text_of("title"), [format!("Report {NASTY}")]);
        assert_eq!(text_of("h2"), [NASTY]);
        assert_eq!(text_of("p"), [NASTY]);
        assert_eq!(text_of("caption"), [NASTY]);
        assert_eq!(text_of("th"), ["T (°C)", "<b>Tc</b> (s)"]);
        assert_eq!(text_of("td"), ["20", NASTY]);
        assert_eq!(text_of("figcaption"), [NASTY, "second"]);
        assert!(doc.descendants().all(|n| !n.has_tag_name("script")));
        assert!(doc.descendants().all(|n| !n.has_tag_name("b")));
    }

    #[test]
    fn figures_are_inline_and_their_ids_unique_and_resolvable() {
        let html = render_page(&page());
        let doc = parse(&html);
        let svgs = doc.descendants().filter(|n| n.has_tag_name("svg")).count();
        assert_eq!(svgs, 2);
        let ids: Vec<&str> = doc
            .descendants()
            .filter_map(|n| n.attribute("id"))
            .collect();
        let mut unique = ids.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), ids.len(), "{ids:?}");
        for node in doc.descendants() {
            if let Some(reference) = node.attribute("clip-path") {
                let id = reference.trim_start_matches("url(#").trim_end_matches(')');
                assert!(ids.contains(&id), "{reference} resolves");
            }
            for attribute in node.attributes() {
                assert!(!attribute.value().contains("http:") || attribute.name() == "xmlns");
            }
        }
    }
}
