//! The report's summary, the first thing on the page: each claim in words with its verdict,
//! the paired difference it rests on (mean, 95 % interval, p) and the one figure that shows
//! it; all read from what the run wrote (evaluation.json, demo.json), nothing recomputed.

use crate::html::figure_data::{number, rms_series, text};
use serde_json::Value;
use thermonav_plot::figures::claims::{Lead, LeadSeries, paired_leads_figure};
use thermonav_plot::figures::navigation::rms_versus_temperature_figure;
use thermonav_plot::html::{Finding, InlineFigure, Outcome, Section};

/// Where the summary's findings come from: the tournament, the demo's scenarios, and the
/// page's sections (each finding links to the one with its details).
pub struct SummarySources<'a> {
    /// evaluation.json, when there is one.
    pub evaluation: Option<&'a Value>,
    /// demo.json, when there is one.
    pub demo: Option<&'a Value>,
    /// The page's sections, in order.
    pub sections: &'a [Section],
}

/// The findings of the summary: the tournament's ranking, each temperature scenario's claim and
/// the survey × model matrix, those the run has.
pub fn findings(sources: &SummarySources) -> Vec<Finding> {
    let mut out: Vec<Finding> = sources
        .evaluation
        .map(|e| tournament_finding(e, sources))
        .into_iter()
        .collect();
    let scenarios = sources.demo.and_then(|d| d.get("temperature_scenarios"));
    if let Some(s) = scenarios {
        out.extend(
            ["temperature_matters", "warming_survey"]
                .iter()
                .filter_map(|key| s.get(*key))
                .map(|scenario| claim_finding(scenario, sources.sections)),
        );
        out.extend(
            s.get("matrix")
                .filter(|m| !m.is_null())
                .map(|m| matrix_finding(m, sources.sections)),
        );
    }
    out
}

/// The index of the first section whose heading starts with `start`.
fn section_starting(sections: &[Section], start: &str) -> Option<usize> {
    sections.iter().position(|s| s.heading.starts_with(start))
}

/// "holds" or "does not hold", coloured accordingly.
fn verdict(holds: bool) -> (String, Outcome) {
    match holds {
        true => ("holds".into(), Outcome::Holds),
        false => ("does not hold".into(), Outcome::Fails),
    }
}

/// A lead with its interval and p: `12.3 m (95 % CI 4.5 to 20.1 m), p = 1.2e-3`.
fn lead_words(lead_m: f64, ci95_m: Option<[f64; 2]>, p: Option<f64>) -> String {
    let interval = ci95_m.map_or(String::new(), |[low, high]| {
        format!(" (95 % CI {low:.1} to {high:.1} m)")
    });
    let p = p.map_or("no paired test".into(), |p| {
        format!("paired p = {}", p_words(p))
    });
    format!("{lead_m:.1} m{interval}, {p}")
}

/// A p-value as people read it: three decimals from 0.01 on, else in powers of ten with three
/// digits (1.60e-3), so that a p just under 0.01 never reads as 1.0e-2 beside a verdict that
/// needs p < 0.01.
fn p_words(p: f64) -> String {
    match p >= 0.01 {
        true => format!("{p:.3}"),
        false => format!("{p:.2e}"),
    }
}

/// The test of the winner against the runner-up on the horizontal error, with its filter.
fn horizontal_test(e: &Value) -> Option<&Value> {
    e.pointer("/significance/tests")?
        .as_array()?
        .iter()
        .find(|t| text(t, "metric") == "rms_horizontal")
}

/// The tournament's ranking: is its winner on the horizontal error better than the runner-up?
/// The paper's set-up (claim (a)) when the demo ran it.
fn tournament_finding(e: &Value, sources: &SummarySources) -> Finding {
    let test = horizontal_test(e);
    let field = |key: &str| test.map(|t| text(t, key)).unwrap_or_default();
    let temperature_c = number(e, "operating_temperature_c").unwrap_or(f64::NAN);
    let statement = format!(
        "At {temperature_c:.1} °C with the {}, the model with the lowest horizontal error ({}) beats the runner-up ({}) with paired p < 0.05.",
        field("filter").to_uppercase(),
        field("winner"),
        field("runner_up"),
    );
    let evidence = test.map_or("No paired test (fewer than two replicates).".into(), |t| {
        let pointer = |p: &str| t.pointer(p).and_then(Value::as_f64);
        let ci = [
            pointer("/test/ci95_difference/1"),
            pointer("/test/ci95_difference/0"),
        ];
        format!(
            "Lead over the runner-up: {}.",
            lead_words(
                -pointer("/test/mean_difference").unwrap_or(f64::NAN),
                ci[0].zip(ci[1]).map(|(high, low)| [-high, -low]),
                pointer("/test/p_value"),
            )
        )
    });
    Finding {
        heading: tournament_heading(sources.demo.is_some()),
        statement,
        verdict: Some(verdict(
            test.and_then(|t| t.get("significant")) == Some(&Value::Bool(true)),
        )),
        evidence,
        figure: Some(tournament_figure(e)),
        details: section_starting(sources.sections, crate::html::ranking::NAVIGATION_HEADING),
    }
}

/// The tournament finding's heading: the demo's claim (a), or the tournament alone.
fn tournament_heading(demo: bool) -> String {
    match demo {
        true => "The paper's set-up (a)".into(),
        false => "The tournament".into(),
    }
}

/// The mean horizontal error of every model against its temperature.
fn tournament_figure(e: &Value) -> InlineFigure {
    let models = e
        .get("models")
        .and_then(Value::as_array)
        .map_or(&[][..], Vec::as_slice);
    let filters: Vec<String> = e
        .get("filters")
        .and_then(Value::as_array)
        .map_or(&[][..], Vec::as_slice)
        .iter()
        .filter_map(|f| f.as_str().map(str::to_string))
        .collect();
    InlineFigure {
        svg: rms_versus_temperature_figure(
            "Horizontal error per model",
            "horizontal",
            "m",
            &rms_series(models, &filters, "rms_horizontal_m"),
        ),
        caption: "Mean of per-outage RMS horizontal error against the model's temperature".into(),
    }
}

/// The comparisons of a claim, the first that fails before the others.
fn deciding_comparison(comparisons: &[Value]) -> Option<&Value> {
    comparisons
        .iter()
        .find(|c| c.get("holds") != Some(&Value::Bool(true)))
        .or_else(|| {
            comparisons.iter().max_by(|a, b| {
                let p = |c: &Value| number(c, "p_value").unwrap_or(f64::INFINITY);
                p(a).total_cmp(&p(b))
            })
        })
}

/// One comparison in words: `A against B: lead ...`.
fn comparison_words(c: &Value) -> String {
    format!(
        "{} against {}: {}",
        text(c, "better"),
        text(c, "worse"),
        lead_words(
            number(c, "mean_difference_m").unwrap_or(f64::NAN),
            interval_of(c),
            number(c, "p_value"),
        )
    )
}

/// A comparison's 95 % interval, when demo.json has it.
fn interval_of(c: &Value) -> Option<[f64; 2]> {
    let bound = |i: usize| c.pointer(&format!("/ci95_difference_m/{i}"))?.as_f64();
    Some([bound(0)?, bound(1)?])
}

/// A temperature scenario's claim: statement, verdict, the comparison that decides it, the
/// oracle's, and the figure of its paired leads.
fn claim_finding(scenario: &Value, sections: &[Section]) -> Finding {
    let name = scenario
        .get("name")
        .and_then(Value::as_str)
        .unwrap_or_default();
    let claim = scenario.get("claim").unwrap_or(&Value::Null);
    let comparisons = claim
        .get("comparisons")
        .and_then(Value::as_array)
        .map_or(&[][..], Vec::as_slice);
    let held = comparisons
        .iter()
        .filter(|c| c.get("holds") == Some(&Value::Bool(true)))
        .count();
    let mut evidence = format!("{held} of {} comparisons hold", comparisons.len());
    if let Some(c) = deciding_comparison(comparisons) {
        evidence.push_str(&format!("; the weakest: {}", comparison_words(c)));
    }
    if let Some(o) = claim.get("oracle_bound") {
        evidence.push_str(&format!("; the oracle, {}", comparison_words(o)));
    }
    Finding {
        heading: capitalised(name),
        statement: format!("{}.", capitalised(&text(claim, "statement"))),
        verdict: Some(verdict(claim.get("holds") == Some(&Value::Bool(true)))),
        evidence: format!("{evidence}."),
        figure: Some(claim_figure(scenario, comparisons)),
        details: section_starting(
            sections,
            &format!("{}{name}", crate::html::temperature::SCENARIO_HEADING),
        ),
    }
}

/// `text` with its first letter in upper case.
fn capitalised(text: &str) -> String {
    let mut chars = text.chars();
    chars.next().map_or(String::new(), |first| {
        first.to_uppercase().chain(chars).collect()
    })
}

/// The claim's paired leads against each rival's temperature: one series per kind of rival,
/// and the oracle's.
fn claim_figure(scenario: &Value, comparisons: &[Value]) -> InlineFigure {
    let models = scenario
        .pointer("/tournament/models")
        .and_then(Value::as_array)
        .map_or(&[][..], Vec::as_slice);
    let rival = |c: &Value| models.iter().find(|m| text(m, "label") == text(c, "worse"));
    let mut series: Vec<LeadSeries> = Vec::new();
    let oracle = scenario.pointer("/claim/oracle_bound");
    for (c, is_oracle) in comparisons
        .iter()
        .map(|c| (c, false))
        .chain(oracle.map(|o| (o, true)))
    {
        let Some(m) = rival(c) else { continue };
        let Some(lead) = lead_of(c, m) else { continue };
        let name = series_name(c, m, is_oracle);
        match series.iter_mut().find(|s| s.name == name) {
            Some(s) => s.leads.push(lead),
            None => series.push(LeadSeries {
                name,
                leads: vec![lead],
            }),
        }
    }
    let better = comparisons
        .first()
        .map(|c| text(c, "better"))
        .unwrap_or_default();
    InlineFigure {
        svg: paired_leads_figure(
            &format!("Paired leads of {better}"),
            "rival's horizontal error − claimed model's (m)",
            &series,
        ),
        caption: format!(
            "Lead of {better} over each rival (above zero: it is better), with the 95 % interval of the mean over the replicates"
        ),
    }
}

/// A comparison as a lead at its rival's temperature (none for a rival without one).
fn lead_of(c: &Value, rival: &Value) -> Option<Lead> {
    Some(Lead {
        rival_temperature_c: number(rival, "temperature_c")?,
        lead_m: number(c, "mean_difference_m")?,
        ci95_m: interval_of(c),
    })
}

/// The legend text of a comparison's series: the kind of rival, or the oracle.
fn series_name(c: &Value, rival: &Value, is_oracle: bool) -> String {
    if is_oracle {
        return format!("oracle: {}", text(c, "better"));
    }
    match text(rival, "kind").as_str() {
        "entry" => "against fixed bank models".into(),
        "compensated_entry" => "against a fixed model + compensation".into(),
        kind => format!("against {kind} models"),
    }
}

/// The survey × model matrix: which model temperature is best on each survey temperature.
fn matrix_finding(m: &Value, sections: &[Section]) -> Finding {
    let column = |key: &str| -> Vec<f64> {
        m.get(key)
            .and_then(Value::as_array)
            .map_or(&[][..], Vec::as_slice)
            .iter()
            .filter_map(Value::as_f64)
            .collect()
    };
    let best: Vec<String> = column("survey_temperatures_c")
        .iter()
        .zip(column("best_model_c"))
        .map(|(survey, model)| format!("{survey} °C → {model} °C"))
        .collect();
    Finding {
        heading: "Survey × model temperature".into(),
        statement: "Every fixed bank model on surveys at every bank temperature: is the model made at the survey's temperature the best one?".into(),
        verdict: None,
        evidence: format!("Best model per survey temperature: {}.", best.join(", ")),
        figure: Some(crate::html::temperature::matrix_figure(m)),
        details: section_starting(sections, crate::html::temperature::MATRIX_HEADING),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_p_just_under_the_threshold_never_reads_as_the_threshold() {
        assert_eq!(p_words(0.00995), "9.95e-3");
        assert_eq!(p_words(0.0016), "1.60e-3");
        assert_eq!(p_words(0.658), "0.658");
    }
}
