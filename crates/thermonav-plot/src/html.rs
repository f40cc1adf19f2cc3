//! Self-contained HTML pages: a title, a summary of findings that opens the page, a table of
//! contents, and sections of paragraphs, tables, inline SVG figures and grids of small
//! figures, with inline CSS (the system's fonts) and no script or external reference.
//!
//! All text is escaped. The markup is also well-formed XML (void elements are self-closed),
//! so a page can be checked with an XML parser. Figures are the SVG documents of this crate's
//! figure functions; each one's element ids get a prefix of its own, so that several figures
//! on one page never share an id.

use crate::chart::prefix_ids;
use crate::svg::escape_markup;
use std::fmt::Write as _;

/// A page: title, the findings it opens with, and sections in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Page {
    /// The page title (also the top heading).
    pub title: String,
    /// The findings shown first, side by side, before the contents (none: no summary).
    pub summary: Vec<Finding>,
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
    /// Figures of one kind side by side in a grid (small multiples), under a caption.
    SmallMultiples {
        /// Caption of the grid (plain text).
        caption: String,
        /// The figures, in reading order.
        figures: Vec<InlineFigure>,
    },
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

/// Whether a finding's claim is borne out (it colours the verdict).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// The claim holds.
    Holds,
    /// It does not.
    Fails,
}

/// A finding of the summary: what was claimed, the verdict, the numbers it rests on, the one
/// figure that shows it and the section that has the details.
#[derive(Debug, Clone, PartialEq)]
pub struct Finding {
    /// Short name (a heading).
    pub heading: String,
    /// The claim in words.
    pub statement: String,
    /// The verdict in words and whether it is borne out; `None` for a finding without one.
    pub verdict: Option<(String, Outcome)>,
    /// The numbers the verdict rests on (plain text).
    pub evidence: String,
    /// The figure that shows it.
    pub figure: Option<InlineFigure>,
    /// The index in [`Page::sections`] of the section with the details.
    pub details: Option<usize>,
}

const STYLE: &str = "body{font-family:system-ui,-apple-system,'Segoe UI',Roboto,\
'Helvetica Neue',Arial,sans-serif;font-size:16px;line-height:1.5;color:#1f2328;\
background:#fff;max-width:1240px;margin:0 auto;padding:0.5rem 1.25rem 3rem}\
h1{font-size:1.6rem;line-height:1.2;margin:0.6rem 0 0.4rem}\
h2{font-size:1.3rem;line-height:1.25;margin:2.2rem 0 0.6rem;padding-bottom:0.2rem;\
border-bottom:1px solid #d0d7de}h3{font-size:1rem;margin:0 0 0.3rem}\
p{max-width:85ch;margin:0.5rem 0}a{color:#0b5cad}\
table{border-collapse:collapse;margin:1rem 0;font-size:0.875rem;\
font-variant-numeric:tabular-nums}caption{text-align:left;font-weight:600;\
padding:0.3rem 0;max-width:85ch}th,td{border-bottom:1px solid #d8dee4;\
padding:0.25rem 0.6rem;text-align:right}th{background:#f3f5f7;font-weight:600}\
th:first-child,td:first-child{text-align:left}tbody tr:nth-child(even){background:#f9fafb}\
figure{margin:1.2rem 0}figure svg{display:block;max-width:100%;height:auto}\
figcaption{font-size:0.875rem;color:#57606a;margin-top:0.3rem}\
.summary h2{margin-top:0.4rem}\
table.findings{width:100%;margin:0.4rem 0 0.8rem}\
.findings th,.findings td{text-align:left;vertical-align:top;padding:0.35rem 0.6rem}\
.findings th[scope=row]{background:none;width:13%}\
.findings td:nth-child(2){width:34%}.findings td:nth-child(4){width:42%}\
.verdict{display:inline-block;font-weight:700;padding:0 0.5rem;border-radius:4px;\
white-space:nowrap}\
.verdict.holds{background:#dafbe1;color:#116329}.verdict.fails{background:#ffebe9;color:#a40e26}\
.summary-figures{display:grid;grid-template-columns:repeat(auto-fit,minmax(460px,1fr));\
gap:0.6rem 1rem}.summary-figures figure{margin:0}\
.evidence{font-variant-numeric:tabular-nums}\
.contents ol{columns:2;column-gap:2rem;margin:0.3rem 0;padding-left:1.4rem}\
.multiples{display:grid;grid-template-columns:repeat(auto-fill,minmax(280px,1fr));\
gap:0.6rem 0.8rem;margin:1rem 0}.multiples figure{margin:0}\
.multiples figcaption{font-size:0.8rem}";

/// The anchor of the section at `index` (links from the contents and the summary).
fn section_anchor(index: usize) -> String {
    format!("section-{}", index + 1)
}

/// The page as one HTML document.
pub fn render_page(page: &Page) -> String {
    let title = escape_markup(&page.title);
    let mut out = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>\n\
         <title>{title}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<h1>{title}</h1>\n"
    );
    let mut figures = 0;
    out.push_str(&summary_markup(&page.summary, &mut figures));
    out.push_str(&contents_markup(page));
    for (index, section) in page.sections.iter().enumerate() {
        let _ = writeln!(
            out,
            "<section id=\"{}\">\n<h2>{}</h2>",
            section_anchor(index),
            escape_markup(&section.heading)
        );
        for block in &section.blocks {
            out.push_str(&block_markup(block, &mut figures));
        }
        out.push_str("</section>\n");
    }
    out.push_str("</body>\n</html>\n");
    out
}

/// One block's markup; `figures` counts the figures placed so far (for their id prefixes).
fn block_markup(block: &Block, figures: &mut usize) -> String {
    match block {
        Block::Paragraph(text) => format!("<p>{}</p>\n", escape_markup(text)),
        Block::Table(table) => table_markup(table),
        Block::Figure(figure) => numbered_figure(figure, figures),
        Block::SmallMultiples {
            caption,
            figures: grid,
        } => {
            let cells: String = grid.iter().map(|f| numbered_figure(f, figures)).collect();
            format!(
                "<p class=\"multiples-caption\">{}</p>\n<div class=\"multiples\">\n{cells}</div>\n",
                escape_markup(caption)
            )
        }
    }
}

/// The figure's markup with the next number.
fn numbered_figure(figure: &InlineFigure, figures: &mut usize) -> String {
    *figures += 1;
    figure_markup(figure, *figures)
}

/// The summary section (nothing without findings): a table of the findings, one row each
/// (name linking to the details, statement, verdict, evidence), then their figures side by
/// side, each captioned with its finding's name.
fn summary_markup(findings: &[Finding], figures: &mut usize) -> String {
    if findings.is_empty() {
        return String::new();
    }
    let rows: String = findings.iter().map(finding_row).collect();
    let grid: String = findings
        .iter()
        .filter_map(|f| {
            let figure = f.figure.as_ref()?;
            Some(numbered_figure(
                &InlineFigure {
                    svg: figure.svg.clone(),
                    caption: format!("{}: {}", f.heading, figure.caption),
                },
                figures,
            ))
        })
        .collect();
    format!(
        "<section id=\"summary\" class=\"summary\">\n<h2>Summary</h2>\n\
         <table class=\"findings\">\n<thead>\n<tr><th>claim</th><th>statement</th><th>verdict</th>\
         <th>what it rests on</th></tr>\n</thead>\n<tbody>\n{rows}</tbody>\n</table>\n\
         <div class=\"summary-figures\">\n{grid}</div>\n</section>\n"
    )
}

/// One finding as a row: its name (a link to its details), statement, verdict and evidence.
fn finding_row(finding: &Finding) -> String {
    let name = escape_markup(&finding.heading);
    let name = match finding.details {
        Some(index) => format!("<a href=\"#{}\">{name}</a>", section_anchor(index)),
        None => name,
    };
    let verdict = finding
        .verdict
        .as_ref()
        .map_or(String::new(), |(words, outcome)| {
            let class = match outcome {
                Outcome::Holds => "holds",
                Outcome::Fails => "fails",
            };
            format!(
                "<span class=\"verdict {class}\">{}</span>",
                escape_markup(words)
            )
        });
    format!(
        "<tr><th scope=\"row\">{name}</th><td>{}</td><td>{verdict}</td><td class=\"evidence\">{}</td></tr>\n",
        escape_markup(&finding.statement),
        escape_markup(&finding.evidence)
    )
}

/// The table of contents: the summary and every section (nothing for a one-section page).
fn contents_markup(page: &Page) -> String {
    if page.sections.len() < 2 && page.summary.is_empty() {
        return String::new();
    }
    let mut items = String::new();
    if !page.summary.is_empty() {
        items.push_str("<li><a href=\"#summary\">Summary</a></li>\n");
    }
    for (index, section) in page.sections.iter().enumerate() {
        let _ = writeln!(
            items,
            "<li><a href=\"#{}\">{}</a></li>",
            section_anchor(index),
            escape_markup(&section.heading)
        );
    }
    format!(
        "<nav id=\"contents\" class=\"contents\">\n<h2>Contents</h2>\n<ol>\n{items}</ol>\n</nav>\n"
    )
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
            summary: Vec::new(),
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

    fn summarised_page() -> Page {
        let finding = |name: &str, outcome| Finding {
            heading: name.into(),
            statement: format!("{name} beats the rest"),
            verdict: Some((format!("{name} verdict"), outcome)),
            evidence: "lead 3.0 m [1.0, 5.0], p = 0.004".into(),
            figure: Some(InlineFigure {
                svg: small_figure(name),
                caption: format!("{name} figure"),
            }),
            details: Some(1),
        };
        let mut page = page();
        page.summary = vec![
            finding("claim b", Outcome::Holds),
            finding("claim c", Outcome::Fails),
        ];
        page.sections.push(Section {
            heading: "Allan".into(),
            blocks: vec![Block::SmallMultiples {
                caption: "one per temperature".into(),
                figures: vec![
                    InlineFigure {
                        svg: small_figure("cold"),
                        caption: "cold".into(),
                    },
                    InlineFigure {
                        svg: small_figure("hot"),
                        caption: "hot".into(),
                    },
                ],
            }],
        });
        page
    }

    #[test]
    fn the_summary_opens_the_page_then_the_contents_then_the_sections() {
        let html = render_page(&summarised_page());
        let doc = parse(&html);
        let summary = html.find("id=\"summary\"").expect("a summary");
        let contents = html.find("id=\"contents\"").expect("contents");
        let first_section = html
            .find("id=\"section-1\"")
            .expect("sections have anchors");
        assert!(summary < contents && contents < first_section);
        let verdicts: Vec<&str> = doc
            .descendants()
            .filter(|n| {
                n.attribute("class")
                    .is_some_and(|c| c.starts_with("verdict"))
            })
            .filter_map(|n| n.text())
            .collect();
        assert_eq!(verdicts, ["claim b verdict", "claim c verdict"]);
        assert!(
            html.contains("class=\"verdict holds\"") && html.contains("class=\"verdict fails\"")
        );
        let links: Vec<&str> = doc
            .descendants()
            .filter_map(|n| n.attribute("href"))
            .collect();
        assert_eq!(
            links,
            [
                "#section-2",
                "#section-2",
                "#summary",
                "#section-1",
                "#section-2"
            ]
        );
        let ids: Vec<&str> = doc
            .descendants()
            .filter_map(|n| n.attribute("id"))
            .collect();
        for link in links {
            assert!(ids.contains(&&link[1..]), "{link} resolves");
        }
    }

    #[test]
    fn small_multiples_sit_in_one_grid_with_unique_ids() {
        let html = render_page(&summarised_page());
        let doc = parse(&html);
        let grid = doc
            .descendants()
            .find(|n| n.attribute("class") == Some("multiples"))
            .expect("a grid");
        let figures = grid.children().filter(|n| n.has_tag_name("figure")).count();
        assert_eq!(figures, 2);
        let svgs = doc.descendants().filter(|n| n.has_tag_name("svg")).count();
        assert_eq!(
            svgs, 6,
            "two in the summary, two in the first section, two in the grid"
        );
        let ids: Vec<&str> = doc
            .descendants()
            .filter_map(|n| n.attribute("id"))
            .collect();
        let mut unique = ids.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), ids.len());
    }

    #[test]
    fn the_page_names_no_external_resource_or_font() {
        let html = render_page(&summarised_page());
        let doc = parse(&html);
        for node in doc.descendants() {
            for attribute in ["src", "href"] {
                if let Some(value) = node.attribute(attribute) {
                    assert!(value.starts_with('#'), "{attribute}={value}");
                }
            }
        }
        assert!(
            !html.contains("@import") && !html.contains("url(http") && !html.contains("@font-face")
        );
        assert!(html.contains("font-family:system-ui"));
    }
}
