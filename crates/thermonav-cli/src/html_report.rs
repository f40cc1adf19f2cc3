//! The HTML report (`thermonav report DIR`, and the last step of `demo`): one self-contained HTML page (inline SVG, no script, no network)
//! from what `demo` (or `characterize` + `evaluate`) wrote under DIR: the noise models, the
//! correlation times against temperature, the survey with its outages, the INS-only errors
//! per model, the RMS per model against temperature (the paper's Figures 13-15), the ranking
//! and its significance, what was run and how to reproduce it.

use crate::failure::{Classify, Failure};
use crate::figure_data::{innovations_of, number, outage_errors, rms_series, text};
use crate::inputs::read_bank;
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
    Trajectory, innovations_figure, outage_errors_figure, rms_versus_temperature_figure,
    trajectory_figure,
};
use thermonav_plot::html::{Block, InlineFigure, Page, Section, Table, render_page};

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
