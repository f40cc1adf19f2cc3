//! The report's sections for the demo's scenarios in which temperature matters: each claim,
//! whether it holds, its paired comparisons and the scenario's ranking.

use crate::html_report::ranking_table;
use serde_json::Value;
use thermonav_plot::html::{Block, Section, Table};

/// One section per scenario of demo.json's `temperature_scenarios` (none without it).
pub fn temperature_sections(demo: &Value) -> Vec<Section> {
    let Some(s) = demo.get("temperature_scenarios") else {
        return Vec::new();
    };
    ["temperature_matters", "warming_survey"]
        .iter()
        .filter_map(|key| s.get(*key))
        .map(scenario_section)
        .collect()
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
        heading: format!("Temperature in the loop: {}", text("/name")),
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
        .map(comparison_row)
        .collect();
    Table {
        caption: "The claim's paired comparisons (mean over the replicates of the worse model's horizontal error minus the better one's; each must be positive with p < 0.01)".into(),
        header: ["model", "against", "lead m", "paired p", "shown"]
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
        if c.get("holds") == Some(&Value::Bool(true)) {
            "yes"
        } else {
            "no"
        }
        .into(),
    ]
}
