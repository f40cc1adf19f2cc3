//! The report's sections for the demo's scenarios in which temperature matters: each claim,
//! whether it holds, its paired comparisons and the scenario's ranking; and the demo unit's
//! thermal calibration on a sweep it was not fitted to.

use crate::failure::{Classify, Failure};
use crate::html::ranking::ranking_table;
use anyhow::anyhow;
use serde_json::Value;
use std::path::Path;
use thermonav::imu::Channel;
use thermonav_plot::figures::DisplayUnits;
use thermonav_plot::figures::navigation::{RmsSeries, rms_versus_temperature_figure};
use thermonav_plot::html::{Block, InlineFigure, Section, Table};

/// One section per scenario of demo.json's `temperature_scenarios` (none without it), and
/// the survey × model temperature matrix when there is one.
pub fn temperature_sections(demo: &Value) -> Vec<Section> {
    let Some(s) = demo.get("temperature_scenarios") else {
        return Vec::new();
    };
    let mut sections: Vec<Section> = ["temperature_matters", "warming_survey"]
        .iter()
        .filter_map(|key| s.get(*key))
        .map(scenario_section)
        .collect();
    sections.extend(s.get("matrix").filter(|m| !m.is_null()).map(matrix_section));
    sections
}

fn numbers(v: &Value, key: &str) -> Vec<Option<f64>> {
    v.get(key)
        .and_then(Value::as_array)
        .map_or(&[][..], Vec::as_slice)
        .iter()
        .map(Value::as_f64)
        .collect()
}

/// The start of a scenario section's heading (the scenario's name follows).
pub const SCENARIO_HEADING: &str = "Temperature in the loop: ";

/// The heading of the matrix section.
pub const MATRIX_HEADING: &str =
    "Survey temperature × model temperature (the paper's Figures 13-15 as a matrix)";

/// The numbers under `key` of the matrix, those that are numbers.
fn finite_numbers(m: &Value, key: &str) -> Vec<f64> {
    numbers(m, key).into_iter().flatten().collect()
}

/// The matrix's mean horizontal errors, one row per survey temperature.
fn matrix_rows(m: &Value) -> Vec<Vec<Option<f64>>> {
    m.get("mean_horizontal_m")
        .and_then(Value::as_array)
        .map_or(&[][..], Vec::as_slice)
        .iter()
        .map(|row| {
            row.as_array()
                .map_or(Vec::new(), |r| r.iter().map(Value::as_f64).collect())
        })
        .collect()
}

/// The matrix as a figure: one line per survey temperature against the model's temperature.
pub fn matrix_figure(m: &Value) -> InlineFigure {
    let models = finite_numbers(m, "model_temperatures_c");
    let series: Vec<RmsSeries> = finite_numbers(m, "survey_temperatures_c")
        .iter()
        .zip(&matrix_rows(m))
        .map(|(t, row)| survey_series(*t, &models, row))
        .collect();
    InlineFigure {
        svg: rms_versus_temperature_figure("Mean horizontal error per survey temperature", "horizontal", "m", &series),
        caption: "Mean of per-outage RMS horizontal error of every fixed bank model (x: the model's temperature), one line per survey temperature".into(),
    }
}

/// The matrix as a figure and a table.
fn matrix_section(m: &Value) -> Section {
    let models = finite_numbers(m, "model_temperatures_c");
    let surveys = finite_numbers(m, "survey_temperatures_c");
    let mut header = vec!["survey °C".to_string()];
    header.extend(models.iter().map(|t| format!("model {t} °C, m")));
    let table_rows = surveys
        .iter()
        .zip(&matrix_rows(m))
        .map(|(t, row)| {
            let mut cells = vec![format!("{t}")];
            cells.extend(
                row.iter()
                    .map(|e| e.map_or("-".into(), |e| format!("{e:.1}"))),
            );
            cells
        })
        .collect();
    Section {
        heading: MATRIX_HEADING.into(),
        blocks: vec![
            Block::Figure(matrix_figure(m)),
            Block::Table(Table {
                caption:
                    "Mean of per-outage RMS horizontal error, m, over shifted-outage replicates"
                        .into(),
                header,
                rows: table_rows,
            }),
        ],
    }
}

fn survey_series(survey_c: f64, models: &[f64], row: &[Option<f64>]) -> RmsSeries {
    let (temperature_c, rms) = models
        .iter()
        .zip(row)
        .filter_map(|(t, e)| e.map(|e| (*t, e)))
        .unzip();
    RmsSeries {
        model: format!("survey {survey_c} °C"),
        temperature_c,
        rms,
    }
}

fn scenario_section(scenario: &Value) -> Section {
    let text = |pointer: &str| {
        scenario
            .pointer(pointer)
            .and_then(Value::as_str)
            .unwrap_or_default()
            .to_string()
    };
    let holds = scenario.pointer("/claim/holds") == Some(&Value::Bool(true));
    let verdict = if holds { "holds" } else { "does not hold" };
    let models = scenario
        .pointer("/tournament/models")
        .and_then(Value::as_array)
        .map_or(&[][..], Vec::as_slice);
    Section {
        heading: format!("{SCENARIO_HEADING}{}", text("/name")),
        blocks: vec![
            Block::Paragraph(format!("Claim ({verdict}): {}.", text("/claim/statement"))),
            Block::Table(comparison_table(scenario)),
            Block::Table(ranking_table(models)),
        ],
    }
}

fn comparison_table(scenario: &Value) -> Table {
    let rows = scenario
        .pointer("/claim/comparisons")
        .and_then(Value::as_array)
        .map_or(&[][..], Vec::as_slice)
        .iter()
        .chain(scenario.pointer("/claim/oracle_bound"))
        .map(comparison_row)
        .collect();
    Table {
        caption: "The claim's paired comparisons (mean over the replicates of the worse model's horizontal error minus the better one's; each must be positive with p < 0.01); a last row of \"truth scheduled\" or \"truth scheduled on calibrated\" is the oracle, the simulator's true noise models scheduled on the record the claimed model runs on: what no noise model can beat".into(),
        header: [
            "model",
            "against",
            "lead m",
            "paired p",
            "replicates for p < 0.01 (80 % power)",
            "shown",
        ]
            .map(String::from)
            .to_vec(),
        rows,
    }
}

fn comparison_row(c: &Value) -> Vec<String> {
    let s = |key: &str| {
        c.get(key)
            .and_then(Value::as_str)
            .unwrap_or_default()
            .to_string()
    };
    let lead = c.get("mean_difference_m").and_then(Value::as_f64);
    let p = c.get("p_value").and_then(Value::as_f64);
    vec![
        s("better"),
        s("worse"),
        lead.map_or("n/a".into(), |v| format!("{v:.2}")),
        p.map_or("n/a".into(), |p| format!("{p:.2e}")),
        c.get("replicates_needed")
            .and_then(Value::as_u64)
            .map_or("n/a".into(), |n| n.to_string()),
        if c.get("holds") == Some(&Value::Bool(true)) {
            "yes"
        } else {
            "no"
        }
        .into(),
    ]
}

/// The demo's thermal calibration on a sweep it was not fitted to: its figure (written by the
/// demo beside the scenarios' bank) and a row per channel; none when the demo wrote no check.
///
/// # Errors
/// A figure that demo.json names but that cannot be read.
pub fn held_out_check_section(dir: &Path, demo: &Value) -> Result<Option<Section>, Failure> {
    let Some(check) = demo.pointer("/temperature_scenarios/held_out_check") else {
        return Ok(None);
    };
    let name = check
        .get("figure")
        .and_then(Value::as_str)
        .unwrap_or_default();
    let path = dir.join("temperature").join(name);
    let svg = std::fs::read_to_string(&path)
        .map_err(|e| anyhow!("{}: {e}", path.display()))
        .data()?;
    let lag = check
        .get("true_lag_s")
        .and_then(Value::as_f64)
        .unwrap_or(0.0);
    Ok(Some(Section {
        heading: "The thermal calibration on a sweep it was not fitted to".into(),
        blocks: vec![
            Block::Paragraph(format!(
                "The demo unit's MEMS structure lags its temperature sensor by {lag} s. Its thermal calibration comes from a chamber program of its own power-on (cool, heat, cool at 3 °C/min: the lag chosen on held-out legs); here it predicts the 30 s block means of another power-on's sweep (−30 → 50 °C at 2 °C/min), which it never saw. The level between the two differs by the new power-on's offset, which no calibration knows (the navigation filter estimates it); the table scores the shape, each record's mean taken off."
            )),
            Block::Figure(InlineFigure {
                svg,
                caption: "Observed block means, the prediction and its 95 % band, against time and against temperature".into(),
            }),
            Block::Table(held_out_table(check)),
        ],
    }))
}

fn held_out_table(check: &Value) -> Table {
    let rows = check
        .get("channels")
        .and_then(Value::as_object)
        .map(|channels| {
            channels
                .iter()
                .map(|(name, c)| held_out_row(name, c))
                .collect()
        })
        .unwrap_or_default();
    Table {
        caption: "Per channel: the lag chosen, and the shape RMS of the sweep's block means (each mean taken off) before and after compensation, with the band's coverage".into(),
        header: [
            "channel",
            "lag chosen s",
            "shape rms before",
            "shape rms after",
            "unit",
            "band coverage",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}

fn held_out_row(name: &str, c: &Value) -> Vec<String> {
    let number = |key: &str| c.get(key).and_then(Value::as_f64);
    let sensor = Channel::from_name(name).map(Channel::sensor);
    let show = |v: Option<f64>| match (v, sensor) {
        (Some(v), Some(s)) => format!("{:.2}", DisplayUnits::Navigation.rate(s, v)),
        _ => "n/a".into(),
    };
    vec![
        name.to_string(),
        number("tau_s").map_or("n/a".into(), |t| format!("{t:.0}")),
        show(number("rms_before_offset_removed")),
        show(number("rms_after_offset_removed")),
        sensor
            .map_or("n/a", |s| DisplayUnits::Navigation.rate_unit(s))
            .to_string(),
        number("coverage_offset_removed").map_or("n/a".into(), |v| format!("{:.0} %", 100.0 * v)),
    ]
}
