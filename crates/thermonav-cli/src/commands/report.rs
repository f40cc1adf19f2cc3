//! `thermonav report DIR`: one self-contained HTML page (inline SVG, no script, no network)
//! from what `demo` (or `characterize` + `evaluate`) wrote under DIR: the noise models, the
//! correlation times against temperature, the survey with its outages, the INS-only errors
//! per model, the RMS per model against temperature (the paper's Figures 13-15), the ranking
//! and its significance, what was run and how to reproduce it.

use super::bank::read_bank;
use crate::args::ReportArgs;
use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use serde_json::Value;
use std::path::Path;
use thermonav::geo::position::Geodetic;
use thermonav::stoch::bank::{GaussMarkovSource, ModelBank};
use thermonav_io::{Strictness, read_trajectory_file, write_atomically};
use thermonav_plot::figures::DisplayUnits;
use thermonav_plot::figures::allan::{allan_curves_of_entry, allan_deviation_figure};
use thermonav_plot::figures::correlation::{correlation_time_figure, correlation_time_series};
use thermonav_plot::figures::navigation::{
    Innovations, ModelErrors, RmsSeries, Trajectory, innovations_figure, outage_errors_figure,
    rms_versus_temperature_figure, trajectory_figure,
};
use thermonav_plot::html::{Block, InlineFigure, Page, Section, Table, render_page};

/// Runs `report`.
pub fn run(args: &ReportArgs) -> Result<(), Failure> {
    let path = write_report(&args.dir)?;
    println!("report written: {}", path.display());
    Ok(())
}

/// Builds DIR/report.html and returns its path.
pub fn write_report(dir: &Path) -> Result<std::path::PathBuf, Failure> {
    let bank = read_bank(&dir.join("bank.json"))?;
    let demo = read_json_if_present(&dir.join("demo.json"))?;
    let evaluation = read_json_if_present(&dir.join("evaluation/evaluation.json"))?;
    let mut sections = vec![run_section(dir, demo.as_ref()), models_section(&bank)];
    if let Some(e) = &evaluation {
        sections.push(navigation_section(dir, e)?);
    }
    let page = Page {
        title: "thermonav report".into(),
        sections,
    };
    let out = dir.join("report.html");
    let html = render_page(&page);
    write_atomically(&out, |file| {
        Ok(std::io::Write::write_all(file, html.as_bytes())?)
    })
    .data()?;
    Ok(out)
}

fn read_json_if_present(path: &Path) -> Result<Option<Value>, Failure> {
    if !path.exists() {
        return Ok(None);
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| anyhow!("{}: cannot read: {e}", path.display()))
        .data()?;
    serde_json::from_str(&text)
        .map(Some)
        .map_err(|e| anyhow!("{}:{}: not JSON: {e}", path.display(), e.line()))
        .data()
}

fn figure(svg: String, caption: &str) -> Block {
    Block::Figure(InlineFigure {
        svg,
        caption: caption.into(),
    })
}

fn paragraph(text: impl Into<String>) -> Block {
    Block::Paragraph(text.into())
}

fn run_section(dir: &Path, demo: Option<&Value>) -> Section {
    let mut rows = vec![
        vec!["thermonav version".into(), env!("CARGO_PKG_VERSION").into()],
        vec!["folder".into(), dir.display().to_string()],
    ];
    let mut reproduce = format!("thermonav report {}", dir.display());
    if let Some(d) = demo {
        let field = |key: &str| d.get(key).map(|v| v.to_string()).unwrap_or_default();
        for (label, key) in [
            ("seed", "seed"),
            ("quick", "quick"),
            ("chamber record per temperature (s)", "chamber_duration_s"),
            ("chamber sample rate (Hz)", "chamber_rate_hz"),
            (
                "exact-ML intervals covering the true Tc",
                "ml_intervals_covering_truth",
            ),
            ("exact-ML intervals judged", "ml_intervals"),
            ("run time (s)", "elapsed_s"),
        ] {
            rows.push(vec![label.into(), field(key)]);
        }
        let quick = if d.get("quick") == Some(&Value::Bool(true)) {
            " --quick"
        } else {
            ""
        };
        reproduce = format!(
            "thermonav demo --out {}{quick} --seed {}",
            dir.display(),
            field("seed")
        );
    }
    Section {
        heading: "What was run".into(),
        blocks: vec![
            Block::Table(Table {
                caption: "Inputs and options".into(),
                header: vec!["item".into(), "value".into()],
                rows,
            }),
            paragraph(format!(
                "Reproduce with: {reproduce}. Every random draw comes from a generator seeded by the seed above and named after its use."
            )),
        ],
    }
}

fn models_section(bank: &ModelBank) -> Section {
    let mut blocks = vec![paragraph(
        "Overlapping Allan deviation of each static record with its confidence band and the IEEE 952 noise terms, then the bias correlation time of each channel against temperature for the three Gauss-Markov estimators, with 95 % intervals.",
    )];
    for entry in &bank.entries {
        let title = format!("Allan deviation at {:.1} °C", entry.temperature_c);
        blocks.push(figure(
            allan_deviation_figure(
                &title,
                &allan_curves_of_entry(entry),
                DisplayUnits::Navigation,
            ),
            &title,
        ));
    }
    let families = [
        GaussMarkovSource::IrregularMl,
        GaussMarkovSource::ArBased,
        GaussMarkovSource::AcfFit,
    ];
    blocks.push(figure(
        correlation_time_figure(
            "Bias correlation time against temperature",
            &correlation_time_series(bank, &families),
        ),
        "Correlation time against temperature (the paper's Figures 8-9)",
    ));
    Section {
        heading: "Noise models per temperature".into(),
        blocks,
    }
}

fn number(v: &Value, key: &str) -> Option<f64> {
    v.get(key).and_then(Value::as_f64)
}

fn text(v: &Value, key: &str) -> String {
    v.get(key)
        .and_then(Value::as_str)
        .unwrap_or_default()
        .to_string()
}

fn navigation_section(dir: &Path, e: &Value) -> Result<Section, Failure> {
    let empty = Vec::new();
    let models = e.get("models").and_then(Value::as_array).unwrap_or(&empty);
    let outages: Vec<(f64, f64)> = e
        .get("outages")
        .and_then(Value::as_array)
        .unwrap_or(&empty)
        .iter()
        .filter_map(|o| Some((number(o, "start_s")?, number(o, "end_s")?)))
        .collect();
    let filters: Vec<String> = e
        .get("filters")
        .and_then(Value::as_array)
        .unwrap_or(&empty)
        .iter()
        .filter_map(|f| f.as_str().map(str::to_string))
        .collect();
    let mut blocks = Vec::new();
    let reference = dir.join("vessel/reference.csv");
    if reference.exists() {
        blocks.push(figure(
            trajectory_figure(
                "Survey with its GNSS outages",
                &trajectory_of(&reference)?,
                &outages,
            ),
            "The survey, outages drawn thick (the paper's Figure 6)",
        ));
    }
    if let Some(filter) = filters.first() {
        let errors = outage_errors(models, filter)?;
        if !errors.is_empty() {
            blocks.push(figure(
                outage_errors_figure(
                    &format!("INS-only errors in the first outage ({})", filter.to_uppercase()),
                    &errors,
                    None,
                ),
                "North, east and heading errors in the first outage, one line per model (Figures 10-12)",
            ));
        }
    }
    for (key, quantity, unit) in [
        ("rms_north_m", "north RMS error", "m"),
        ("rms_east_m", "east RMS error", "m"),
        ("rms_heading_deg", "heading RMS error", "deg"),
    ] {
        let series = rms_series(models, &filters, key);
        blocks.push(figure(
            rms_versus_temperature_figure(
                &format!("{quantity} per model"),
                quantity,
                unit,
                &series,
            ),
            &format!("{quantity} against the model's temperature (Figures 13-15)"),
        ));
    }
    let innovations = dir.join("solution/solution.innovations.csv");
    if innovations.exists() {
        blocks.push(figure(
            innovations_figure(
                "Innovations of the UKF with the interpolated model (solution/)",
                &innovations_of(&innovations)?,
            ),
            "GNSS innovations with their ±3σ bounds (none inside the outages)",
        ));
    }
    blocks.push(Block::Table(ranking_table(models)));
    blocks.push(Block::Table(significance_table(e)));
    Ok(Section {
        heading: format!(
            "Navigation through GNSS outages at {:.1} °C",
            number(e, "operating_temperature_c").unwrap_or(f64::NAN)
        ),
        blocks,
    })
}

fn trajectory_of(path: &Path) -> Result<Trajectory, Failure> {
    let points = read_trajectory_file(path, Strictness::Strict).data()?;
    let position = |p: &thermonav::trajectory::TrajectoryPoint| Geodetic {
        latitude_rad: p.latitude_rad,
        longitude_rad: p.longitude_rad,
        height_m: p.height_m,
    };
    let origin = points
        .first()
        .map(position)
        .ok_or_else(|| Failure::Data(anyhow!("{}: no point", path.display())))?;
    let step = (points.len() / 4000).max(1);
    let local: Vec<(f64, [f64; 3])> = points
        .iter()
        .step_by(step)
        .map(|p| {
            (
                p.time.as_seconds(),
                position(p).ned_from(&origin).to_array(),
            )
        })
        .collect();
    Ok(Trajectory {
        time_s: local.iter().map(|(t, _)| *t).collect(),
        north_m: local.iter().map(|(_, n)| n[0]).collect(),
        east_m: local.iter().map(|(_, n)| n[1]).collect(),
    })
}

/// Position (north, east, down) and heading innovations of an `integrate` innovations file,
/// accepted updates only, times from the first update.
pub fn innovations_of(path: &Path) -> Result<Vec<Innovations>, Failure> {
    let bytes = std::fs::read(path)
        .map_err(|e| anyhow!("{}: cannot read: {e}", path.display()))
        .data()?;
    // Bytes that are not UTF-8 become U+FFFD and fail the check of their line.
    let csv = String::from_utf8_lossy(&bytes);
    let rows: Vec<Vec<&str>> = checked_innovation_rows(path, &csv)?
        .into_iter()
        .filter(|f| f.len() == 12 && f[10] == "1")
        .collect();
    if rows.is_empty() {
        return Err(anyhow!(
            "{}: no accepted update (expected rows with accepted = 1)",
            path.display()
        ))
        .data();
    }
    let t0 = rows
        .first()
        .and_then(|r| r[0].parse::<f64>().ok())
        .unwrap_or(0.0);
    let component = |kind: &str, k: usize, name: &str| {
        let of_kind: Vec<&Vec<&str>> = rows.iter().filter(|r| r[1] == kind).collect();
        let column = |c: usize| -> Vec<f64> {
            of_kind
                .iter()
                .map(|r| r[c].parse().unwrap_or(f64::NAN))
                .collect()
        };
        Innovations {
            name: name.into(),
            unit: of_kind.first().map_or("", |r| r[2]).into(),
            time_s: column(0).iter().map(|t| t - t0).collect(),
            innovation: column(3 + k),
            sigma: column(6 + k),
        }
    };
    Ok([
        component("position", 0, "north position"),
        component("position", 1, "east position"),
        component("position", 2, "down position"),
        component("heading", 0, "heading"),
    ]
    .into_iter()
    .filter(|c| !c.time_s.is_empty())
    .collect())
}

/// Header of the innovations CSV that `integrate` writes.
const INNOVATIONS_HEADER: &str =
    "t_s,kind,unit,innovation_1,innovation_2,innovation_3,sd_1,sd_2,sd_3,nis,accepted,forced";

/// The rows of an innovations CSV split into fields, each checked: the header, then `t_s`,
/// kind, unit, finite numbers, and 0 or 1 for `accepted` and `forced`; the error names the line.
fn checked_innovation_rows<'a>(path: &Path, csv: &'a str) -> Result<Vec<Vec<&'a str>>, Failure> {
    let mut lines = csv.lines();
    if lines.next() != Some(INNOVATIONS_HEADER) {
        return Err(anyhow!(
            "{}:1: expected the innovations header {INNOVATIONS_HEADER}",
            path.display()
        ))
        .data();
    }
    lines
        .enumerate()
        .map(|(k, line)| {
            let fields: Vec<&str> = line.split(',').collect();
            match is_innovation_row(&fields) {
                true => Ok(fields),
                false => Err(anyhow!(
                    "{}:{}: expected {INNOVATIONS_HEADER} (finite numbers, accepted and forced 0 or 1)",
                    path.display(),
                    k + 2
                ))
                .data(),
            }
        })
        .collect()
}

/// Whether `fields` is one innovations row: time, kind, unit, numbers, then two flags.
fn is_innovation_row(fields: &[&str]) -> bool {
    let finite = |f: &&str| f.parse::<f64>().is_ok_and(f64::is_finite);
    let flag = |f: &&str| matches!(*f, "0" | "1");
    fields.len() >= 6
        && finite(&fields[0])
        && fields[3..fields.len() - 2].iter().all(finite)
        && fields[fields.len() - 2..].iter().all(flag)
}

/// The first outage's errors of every model of `filter`, from their CSVs.
pub fn outage_errors(models: &[Value], filter: &str) -> Result<Vec<ModelErrors>, Failure> {
    let mut out = Vec::new();
    for m in models.iter().filter(|m| text(m, "filter") == filter) {
        let Some(path) = m.get("errors_csv").and_then(Value::as_str) else {
            continue;
        };
        let csv = std::fs::read_to_string(path)
            .map_err(|e| anyhow!("{path}: cannot read: {e}"))
            .data()?;
        let rows: Vec<Vec<f64>> = csv
            .lines()
            .skip(1)
            .filter(|l| l.starts_with("1,"))
            .map(|l| l.split(',').filter_map(|x| x.parse().ok()).collect())
            .filter(|v: &Vec<f64>| v.len() == 7)
            .collect();
        let column = |k: usize| rows.iter().map(|r| r[k]).collect();
        out.push(ModelErrors {
            model: text(m, "label"),
            time_s: column(2),
            north_m: column(3),
            east_m: column(4),
            heading_deg: column(6),
        });
    }
    Ok(out)
}

/// Per filter, the bank entries' values at their temperatures, and the interpolated model at
/// the operating temperature as its own series.
pub fn rms_series(models: &[Value], filters: &[String], key: &str) -> Vec<RmsSeries> {
    let mut series = Vec::new();
    for filter in filters {
        for (kind, name) in [("entry", "bank models"), ("interpolated", "interpolated")] {
            let points: Vec<(f64, f64)> = models
                .iter()
                .filter(|m| text(m, "filter") == *filter && text(m, "kind") == kind)
                .filter_map(|m| Some((number(m, "temperature_c")?, number(m, key)?)))
                .collect();
            if !points.is_empty() {
                series.push(RmsSeries {
                    model: format!("{} ({})", name, filter.to_uppercase()),
                    temperature_c: points.iter().map(|p| p.0).collect(),
                    rms: points.iter().map(|p| p.1).collect(),
                });
            }
        }
    }
    series
}

fn cell(v: &Value, key: &str) -> String {
    match (v.pointer(&format!("/ci95/{key}")), number(v, key)) {
        (Some(ci), _) => format!(
            "{:.2} [{:.2}, {:.2}]",
            number(ci, "mean").unwrap_or(f64::NAN),
            number(ci, "low").unwrap_or(f64::NAN),
            number(ci, "high").unwrap_or(f64::NAN)
        ),
        (None, Some(x)) => format!("{x:.2}"),
        (None, None) => "failed".into(),
    }
}

fn ranking_table(models: &[Value]) -> Table {
    let keys = [
        "rms_north_m",
        "rms_east_m",
        "rms_horizontal_m",
        "rms_heading_deg",
        "max_drift_horizontal_m",
    ];
    Table {
        caption: "INS-only errors per model: mean over replicates [95 % interval of the mean] (mean of per-outage RMS; max drift = RMS of per-outage maxima)".into(),
        header: ["model", "filter", "north m", "east m", "horizontal m", "heading deg", "max drift m"]
            .map(String::from)
            .to_vec(),
        rows: models
            .iter()
            .map(|m| {
                let mut row = vec![text(m, "label"), text(m, "filter")];
                row.extend(keys.iter().map(|k| cell(m, k)));
                row
            })
            .collect(),
    }
}

fn significance_table(e: &Value) -> Table {
    let empty = Vec::new();
    let tests = e
        .pointer("/significance/tests")
        .and_then(Value::as_array)
        .unwrap_or(&empty);
    Table {
        caption: format!(
            "Is the ranking real? Paired t-tests of winner against runner-up over {} replicates ({})",
            e.pointer("/significance/replicates")
                .map(Value::to_string)
                .unwrap_or_default(),
            e.pointer("/significance/replicates_differ_by")
                .and_then(Value::as_str)
                .unwrap_or_default()
        ),
        header: [
            "filter",
            "metric",
            "winner",
            "runner-up",
            "p-value",
            "verdict",
        ]
        .map(String::from)
        .to_vec(),
        rows: tests
            .iter()
            .map(|t| {
                let p = t.pointer("/test/p_value").and_then(Value::as_f64);
                vec![
                    text(t, "filter"),
                    text(t, "metric"),
                    text(t, "winner"),
                    text(t, "runner_up"),
                    p.map_or("n/a".into(), |p| format!("{p:.3}")),
                    if t.get("significant") == Some(&Value::Bool(true)) {
                        "significant".into()
                    } else {
                        "not significant".into()
                    },
                ]
            })
            .collect(),
    }
}
