//! The ranking table of a tournament's models read back from `evaluation.json`: each model's
//! label, filter and five outage metrics (the mean and its 95 % interval when replicated). Shared
//! by the HTML report's navigation section and its temperature scenarios.

use crate::html::figure_data::{number, text};
use serde_json::Value;
use thermonav_plot::html::{Block, Table};

/// The start of the navigation section's heading (its temperature follows; the summary links
/// to the section by it).
pub const NAVIGATION_HEADING: &str = "Navigation through GNSS outages";

/// One metric of a model: its mean with the 95 % interval when replicated, else the value, else
/// `failed`.
fn cell(v: &Value, key: &str) -> String {
    match (v.pointer(&format!("/ci95/{key}")), number(v, key)) {
        (Some(ci), _) => format!(
            "{:.2} [{:.2}, {:.2}]",
            number(ci, "mean").unwrap_or(f64::NAN),
            number(ci, "low").unwrap_or(f64::NAN),
            number(ci, "high").unwrap_or(f64::NAN)
        ),
        (None, Some(x)) => format!("{x:.2}"),
        (None, None) if v.get("failure").is_none_or(Value::is_null) => "not scored".into(),
        (None, None) => "failed".into(),
    }
}

/// The report's word on what was not scored (heading, against a position-only reference),
/// when something was not.
pub fn not_scored_note(evaluation: &Value) -> Option<Block> {
    let note = evaluation.pointer("/reference/not_scored")?.as_str()?;
    Some(Block::Paragraph(format!("Not scored: {note}.")))
}

/// The INS-only errors of every model, one row per model.
pub fn ranking_table(models: &[Value]) -> Table {
    Table {
        caption: "INS-only errors per model: mean over replicates [95 % interval of the mean] (mean of per-outage RMS; max drift = RMS of per-outage maxima)".into(),
        header: ["model", "filter", "north m", "east m", "horizontal m", "heading deg", "max drift m"]
            .map(String::from)
            .to_vec(),
        rows: models.iter().map(ranking_row).collect(),
    }
}

/// One model's row of the ranking table: label, filter and its five metrics.
fn ranking_row(m: &Value) -> Vec<String> {
    let keys = [
        "rms_north_m",
        "rms_east_m",
        "rms_horizontal_m",
        "rms_heading_deg",
        "max_drift_horizontal_m",
    ];
    let mut row = vec![text(m, "label"), text(m, "filter")];
    row.extend(keys.iter().map(|k| cell(m, k)));
    row
}
