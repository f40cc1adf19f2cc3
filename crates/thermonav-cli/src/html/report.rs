//! The HTML report (`thermonav report DIR`, and the last step of `demo`): one self-contained HTML page (inline SVG, no script, no network)
//! from what `demo` (or `characterize` + `evaluate`) wrote under DIR: the noise models, the
//! correlation times against temperature, the survey with its outages, the INS-only errors
//! per model, the RMS per model against temperature (the paper's Figures 13-15), the ranking
//! and its significance, what was run and how to reproduce it.

use crate::failure::{Classify, Failure};
use crate::html::figure_data::{innovations_of, number, outage_errors, rms_series, text};
use crate::html::ranking::{NAVIGATION_HEADING, not_scored_note, ranking_table};
use crate::html::summary::{SummarySources, findings};
use crate::inputs::read_bank;
use anyhow::anyhow;
use serde_json::Value;
use std::path::Path;
use thermonav::geo::position::Geodetic;
use thermonav::stoch::bank::{GaussMarkovSource, ModelBank, TemperatureEntry};
use thermonav::stoch::thermal::ThermalCalibration;
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::write_atomically;
use thermonav_plot::figures::DisplayUnits;
use thermonav_plot::figures::allan::{allan_curves_of_entry, allan_deviation_figure};
use thermonav_plot::figures::correlation::{correlation_time_figure, correlation_time_series};
use thermonav_plot::figures::navigation::{
    Trajectory, innovations_figure, outage_errors_figure, rms_versus_temperature_figure,
    trajectory_figure,
};
use thermonav_plot::figures::thermal::{thermal_bias_figure, thermal_bias_panels};
use thermonav_plot::html::{Block, InlineFigure, Page, Section, Table, render_page};

/// Builds DIR/report.html and returns its path: from what `demo` (or `characterize` +
/// `evaluate`) wrote, or from a folder `evaluate` wrote (the tournament alone).
pub fn write_report(dir: &Path) -> Result<std::path::PathBuf, Failure> {
    if !dir.join("bank.json").is_file() && dir.join("evaluation.json").is_file() {
        return write_tournament_report(dir);
    }
    let bank = read_bank(&required(dir, "bank.json")?)?;
    let demo = read_json_if_present(&dir.join("demo.json"))?;
    let evaluation = read_json_if_present(&dir.join("evaluation/evaluation.json"))?;
    let mut sections = vec![run_section(dir, demo.as_ref()), models_section(&bank)];
    if let Some(e) = &evaluation {
        sections.push(navigation_section(dir, &dir.join("evaluation"), e)?);
    }
    if let Some(d) = &demo {
        sections.extend(crate::html::temperature::temperature_sections(d));
        sections.extend(crate::html::temperature::held_out_check_section(dir, d)?);
    }
    let summary = findings(&SummarySources {
        evaluation: evaluation.as_ref(),
        demo: demo.as_ref(),
        sections: &sections,
    });
    let page = Page {
        title: "thermonav report".into(),
        summary,
        sections,
    };
    let out = dir.join("report.html");
    write_html(&out, &render_page(&page))?;
    Ok(out)
}

/// The report of a folder `evaluate --out DIR` wrote: what was run and the tournament, without
/// the noise-model sections (they need characterize's bank.json).
fn write_tournament_report(dir: &Path) -> Result<std::path::PathBuf, Failure> {
    let path = dir.join("evaluation.json");
    let evaluation = read_json_if_present(&path)?
        .ok_or_else(|| anyhow!("{}: missing; report DIR reads {LAYOUT}", path.display()))
        .data()?;
    let mut run = run_section(dir, None);
    run.blocks.push(paragraph(TOURNAMENT_ONLY));
    let sections = vec![run, navigation_section(dir, dir, &evaluation)?];
    let summary = findings(&SummarySources {
        evaluation: Some(&evaluation),
        demo: None,
        sections: &sections,
    });
    let page = Page {
        title: "thermonav report: tournament".into(),
        summary,
        sections,
    };
    let out = dir.join("report.html");
    write_html(&out, &render_page(&page))?;
    Ok(out)
}

/// What the report of an evaluate folder leaves out, and how to have it.
const TOURNAMENT_ONLY: &str = "This folder holds a tournament alone (evaluate --out DIR): the noise-model sections need the bank, as characterize --out DIR/bank.json with the tournament in DIR/evaluation (evaluate --out DIR/evaluation).";

/// The layout `report DIR` reads, in words (for its help and its errors).
pub const LAYOUT: &str = "DIR/bank.json (required: characterize --out DIR/bank.json); optional: DIR/demo.json, DIR/evaluation/evaluation.json with its errors/ (evaluate --out DIR/evaluation), DIR/vessel/reference.csv, DIR/solution/solution.innovations.csv (integrate --out DIR/solution/solution.csv); or a folder evaluate wrote: DIR/evaluation.json with its errors/ (evaluate --out DIR), reported without the bank's sections";

/// `dir/name`, or a data error naming it and the layout.
fn required(dir: &Path, name: &str) -> Result<std::path::PathBuf, Failure> {
    let path = dir.join(name);
    match path.is_file() {
        true => Ok(path),
        false => Err(anyhow!(
            "{}: missing; report DIR reads {LAYOUT}",
            path.display()
        ))
        .data(),
    }
}

/// Writes the page to `out` atomically.
fn write_html(out: &Path, html: &str) -> Result<(), Failure> {
    write_atomically(out, |file| {
        Ok(std::io::Write::write_all(file, html.as_bytes())?)
    })
    .data()
}

/// The JSON document at `path`, or `None` when there is no such file.
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

/// An inline SVG figure with its caption.
fn figure(svg: String, caption: &str) -> Block {
    Block::Figure(InlineFigure {
        svg,
        caption: caption.into(),
    })
}

/// A paragraph of text.
fn paragraph(text: impl Into<String>) -> Block {
    Block::Paragraph(text.into())
}

/// The inputs and options of the run and the command that reproduces it.
fn run_section(dir: &Path, demo: Option<&Value>) -> Section {
    let mut rows = vec![
        vec!["thermonav version".into(), env!("CARGO_PKG_VERSION").into()],
        vec!["folder".into(), dir.display().to_string()],
    ];
    let mut reproduce = format!("thermonav report {}", dir.display());
    if let Some(d) = demo {
        rows.extend(demo_rows(d));
        reproduce = demo_command(dir, d);
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

/// A field of demo.json as JSON text, empty when absent.
fn demo_field(demo: &Value, key: &str) -> String {
    demo.get(key).map(|v| v.to_string()).unwrap_or_default()
}

/// The rows of the inputs table taken from demo.json.
fn demo_rows(demo: &Value) -> Vec<Vec<String>> {
    [
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
    ]
    .iter()
    .map(|(label, key)| vec![label.to_string(), demo_field(demo, key)])
    .collect()
}

/// The `thermonav demo` command line that reproduces the run.
fn demo_command(dir: &Path, demo: &Value) -> String {
    let quick = if demo.get("quick") == Some(&Value::Bool(true)) {
        " --quick"
    } else {
        ""
    };
    format!(
        "thermonav demo --out {}{quick} --seed {}",
        dir.display(),
        demo_field(demo, "seed")
    )
}

/// The Allan deviation figure of each temperature, the correlation times against temperature,
/// and the bias against temperature when the bank has a thermal calibration.
fn models_section(bank: &ModelBank) -> Section {
    let mut blocks = vec![paragraph(
        "Overlapping Allan deviation of each static record with its confidence band and the IEEE 952 noise terms, then the bias correlation time of each channel against temperature for the three Gauss-Markov estimators, with 95 % intervals.",
    )];
    blocks.push(Block::SmallMultiples {
        caption: "Allan deviation at each temperature of the bank (gyros above, accelerometers below); zoom in for the labels".into(),
        figures: bank.entries.iter().map(allan_figure).collect(),
    });
    blocks.push(correlation_figure(bank));
    blocks.extend(bank.thermal.as_ref().map(thermal_figure));
    Section {
        heading: "Noise models per temperature".into(),
        blocks,
    }
}

/// The Allan deviation figure of one bank entry.
fn allan_figure(entry: &TemperatureEntry) -> InlineFigure {
    let title = format!("Allan deviation at {:.1} °C", entry.temperature_c);
    InlineFigure {
        svg: allan_deviation_figure(
            &title,
            &allan_curves_of_entry(entry),
            DisplayUnits::Navigation,
        ),
        caption: title,
    }
}

/// Bias against temperature of the unit's thermal calibration.
fn thermal_figure(calibration: &ThermalCalibration) -> Block {
    let panels = thermal_bias_panels(calibration, &[]);
    let title = "Bias against temperature (thermal calibration)";
    figure(
        thermal_bias_figure(title, &panels, DisplayUnits::Navigation),
        "Repeatable bias against temperature with its simultaneous 95 % band; the observations by power-on, each power-on's offset removed",
    )
}

/// The bias correlation time against temperature for the Gauss-Markov families every bank has.
fn correlation_figure(bank: &ModelBank) -> Block {
    let families: Vec<GaussMarkovSource> = GaussMarkovSource::in_listing_order()
        .filter(|s| s.always_fitted())
        .collect();
    figure(
        correlation_time_figure(
            "Bias correlation time against temperature",
            &correlation_time_series(bank, &families),
        ),
        "Correlation time against temperature (the paper's Figures 8-9)",
    )
}

/// The survey, the errors in the first outage, the RMS against temperature, the innovations,
/// the ranking and its significance.
/// `evaluation_dir` holds evaluation.json and its errors/.
fn navigation_section(dir: &Path, evaluation_dir: &Path, e: &Value) -> Result<Section, Failure> {
    let models = array(e, "models");
    let filters = filters_of(e);
    let mut blocks = Vec::new();
    blocks.extend(survey_figure(dir, &outages_of(e))?);
    if let Some(filter) = filters.first() {
        blocks.extend(first_outage_figure(models, filter, evaluation_dir)?);
    }
    blocks.extend(rms_figures(models, &filters));
    blocks.extend(innovations_block(dir)?);
    blocks.push(Block::Table(ranking_table(models)));
    blocks.extend(not_scored_note(e));
    blocks.push(Block::Table(significance_table(e)));
    Ok(Section {
        heading: format!(
            "{NAVIGATION_HEADING} at {:.1} °C",
            number(e, "operating_temperature_c").unwrap_or(f64::NAN)
        ),
        blocks,
    })
}

/// The array under `key`, empty when absent or not an array.
fn array<'a>(v: &'a Value, key: &str) -> &'a [Value] {
    v.get(key)
        .and_then(Value::as_array)
        .map_or(&[], Vec::as_slice)
}

/// The outages of evaluation.json as (start, end) in seconds.
fn outages_of(e: &Value) -> Vec<(f64, f64)> {
    array(e, "outages")
        .iter()
        .filter_map(|o| Some((number(o, "start_s")?, number(o, "end_s")?)))
        .collect()
}

/// The filters of evaluation.json, in their order.
fn filters_of(e: &Value) -> Vec<String> {
    array(e, "filters")
        .iter()
        .filter_map(|f| f.as_str().map(str::to_string))
        .collect()
}

/// The survey with its outages, when the reference trajectory is there.
fn survey_figure(dir: &Path, outages: &[(f64, f64)]) -> Result<Option<Block>, Failure> {
    let reference = dir.join("vessel/reference.csv");
    if !reference.exists() {
        return Ok(None);
    }
    Ok(Some(figure(
        trajectory_figure(
            "Survey with its GNSS outages",
            &trajectory_of(&reference)?,
            outages,
        ),
        "The survey, outages drawn thick (the paper's Figure 6)",
    )))
}

/// The INS-only errors of every model in the first outage with `filter`, when there are any.
fn first_outage_figure(
    models: &[Value],
    filter: &str,
    evaluation_dir: &Path,
) -> Result<Option<Block>, Failure> {
    let errors = outage_errors(models, filter, evaluation_dir)?;
    if errors.is_empty() {
        return Ok(None);
    }
    Ok(Some(figure(
        outage_errors_figure(
            &format!(
                "INS-only errors in the first outage ({})",
                filter.to_uppercase()
            ),
            &errors,
            None,
        ),
        "North, east and heading errors in the first outage, one line per model (Figures 10-12)",
    )))
}

/// The north, east and heading RMS per model against temperature (Figures 13-15).
fn rms_figures(models: &[Value], filters: &[String]) -> Vec<Block> {
    [
        ("rms_north_m", "north", "m"),
        ("rms_east_m", "east", "m"),
        ("rms_heading_deg", "heading", "deg"),
    ]
    .iter()
    .map(|(key, quantity, unit)| {
        figure(
            rms_versus_temperature_figure(
                &format!("RMS {quantity} error per model"),
                quantity,
                unit,
                &rms_series(models, filters, key),
            ),
            &format!("RMS {quantity} error against the model's temperature (Figures 13-15)"),
        )
    })
    .collect()
}

/// The innovations of the solution's filter, when solution/ holds them.
fn innovations_block(dir: &Path) -> Result<Option<Block>, Failure> {
    let innovations = dir.join("solution/solution.innovations.csv");
    if !innovations.exists() {
        return Ok(None);
    }
    Ok(Some(figure(
        innovations_figure(
            "Innovations of the UKF with the interpolated model (solution/)",
            &innovations_of(&innovations)?,
        ),
        "GNSS innovations with their ±3σ bounds (none inside the outages)",
    )))
}

/// The reference trajectory in north/east metres from its first point, thinned to about 4000
/// points.
fn trajectory_of(path: &Path) -> Result<Trajectory, Failure> {
    let points = crate::navigation::reference_input::read_reference(path)?.points;
    let origin = points
        .first()
        .map(geodetic)
        .ok_or_else(|| Failure::Data(anyhow!("{}: no point", path.display())))?;
    let step = (points.len() / 4000).max(1);
    let local: Vec<(f64, [f64; 3])> = points
        .iter()
        .step_by(step)
        .map(|p| {
            (
                p.time.as_seconds(),
                geodetic(p).ned_from(&origin).to_array(),
            )
        })
        .collect();
    Ok(Trajectory {
        time_s: local.iter().map(|(t, _)| *t).collect(),
        north_m: local.iter().map(|(_, n)| n[0]).collect(),
        east_m: local.iter().map(|(_, n)| n[1]).collect(),
    })
}

/// The position of a trajectory point.
fn geodetic(p: &TrajectoryPoint) -> Geodetic {
    Geodetic {
        latitude_rad: p.latitude_rad,
        longitude_rad: p.longitude_rad,
        height_m: p.height_m,
    }
}

/// The paired t-tests of winner against runner-up, one row per filter and metric.
fn significance_table(e: &Value) -> Table {
    let tests = e
        .pointer("/significance/tests")
        .and_then(Value::as_array)
        .map_or(&[][..], Vec::as_slice);
    Table {
        caption: significance_caption(e),
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
        rows: tests.iter().map(significance_row).collect(),
    }
}

/// The caption of the significance table: how many replicates and how they differ.
fn significance_caption(e: &Value) -> String {
    format!(
        "Is the ranking real? Paired t-tests of winner against runner-up over {} replicates ({})",
        e.pointer("/significance/replicates")
            .map(Value::to_string)
            .unwrap_or_default(),
        e.pointer("/significance/replicates_differ_by")
            .and_then(Value::as_str)
            .unwrap_or_default()
    )
}

/// One test's row: filter, metric, the two models, the p-value and the verdict.
fn significance_row(t: &Value) -> Vec<String> {
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
}
