//! Issue 38 row 19: the page `demo` writes opens with its answer. Its summary (each claim's
//! statement, verdict and paired difference with its interval and p, and the figure that shows
//! it) comes before every other figure, a table of contents follows, the Allan figures are small
//! multiples in one grid, and the page is one self-contained file.

use crate::{arg, outcome, thermonav};
use serde_json::Value;
use std::path::Path;

/// The JSON document at `path`.
fn json_file(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("readable")).expect("JSON")
}

/// The markup from `start` to the end of the element it is in (the first `</tag>` after it;
/// none of the elements looked for nest their own kind).
fn element<'a>(html: &'a str, start: &str, tag: &str) -> &'a str {
    let from = html
        .find(start)
        .unwrap_or_else(|| panic!("{start} in the page"));
    let close = format!("</{tag}>");
    let to = html[from..].find(&close).expect("closed") + from;
    &html[from..to]
}

/// The summary's row of the finding named `heading` (a link to its section).
fn row_of<'a>(summary: &'a str, heading: &str) -> &'a str {
    element(summary, &format!("\">{heading}</a></th>"), "tr")
}

/// The text of the verdict in the summary's row of the finding named `heading`.
fn verdict_of<'a>(summary: &'a str, heading: &str) -> &'a str {
    let card = row_of(summary, heading);
    let after = &card[card.find("class=\"verdict").expect("a verdict")..];
    let text = &after[after.find('>').expect("tag") + 1..];
    &text[..text.find('<').expect("end")]
}

/// `text` with its first letter in upper case.
fn capitalised(text: &str) -> String {
    let mut chars = text.chars();
    chars
        .next()
        .map_or(String::new(), |c| c.to_uppercase().chain(chars).collect())
}

/// `text` as the page writes it (markup characters as entities).
fn escaped(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&#39;")
}

/// Every `attribute="..."` value in the page.
fn attribute_values<'a>(html: &'a str, attribute: &str) -> Vec<&'a str> {
    let needle = format!(" {attribute}=\"");
    html.match_indices(&needle)
        .map(|(at, _)| {
            let value = &html[at + needle.len()..];
            &value[..value.find('"').expect("closed")]
        })
        .collect()
}

#[test]
fn the_demo_report_opens_with_the_claims_verdicts_and_stays_self_contained() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("demo");
    let (status, _, stderr) = outcome(&thermonav(&["demo", "--quick", "--out", arg(&out)]));
    assert_eq!(status, 0, "{stderr}");
    // Issue 38 row 18: the steps counted 1/4 ... 4/4 and then 5/5; now each of the five once,
    // in order, out of the same total.
    let steps: Vec<&str> = (stderr.lines())
        .filter_map(|l| l.split_whitespace().next())
        .filter(|w| w.len() == 3 && w.as_bytes()[1] == b'/')
        .collect();
    assert_eq!(steps, ["1/5", "2/5", "3/5", "4/5", "5/5"], "{stderr}");
    // The quick demo's survey runs at its chamber records' rate (100 Hz), so the bank's model
    // is used at the rate it was made at and no rate note is printed (it was, at 200 Hz).
    assert!(
        !stderr.contains("the bank was made from records at"),
        "{stderr}"
    );
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();

    // The summary comes first: before the contents, the first section and every figure
    // outside it.
    let summary = element(&html, "<section id=\"summary\"", "section");
    let summary_at = html.find(summary).unwrap();
    let summary_end = summary_at + summary.len();
    assert!(html[..summary_at].find("<figure").is_none());
    assert!(html[..summary_at].find("<table").is_none());
    let contents = html
        .find("<nav id=\"contents\"")
        .expect("a table of contents");
    let first_section = html.find("<section id=\"section-1\"").expect("sections");
    assert!(summary_end < contents && contents < first_section);
    assert!(html[summary_end..].find("<figure").unwrap() + summary_end > first_section);

    // Each claim of the demo: its statement and verdict, as demo.json has them.
    let demo = json_file(&out.join("demo.json"));
    for key in ["temperature_matters", "warming_survey"] {
        let scenario = &demo["temperature_scenarios"][key];
        let name = escaped(&capitalised(scenario["name"].as_str().unwrap()));
        let holds = scenario["claim"]["holds"].as_bool().unwrap();
        let expected = if holds { "holds" } else { "does not hold" };
        assert_eq!(verdict_of(summary, &name), expected, "{name}");
        let statement = escaped(&capitalised(
            scenario["claim"]["statement"].as_str().unwrap(),
        ));
        assert!(summary.contains(&statement), "{statement}");
        let interval = scenario["claim"]["comparisons"][0]["ci95_difference_m"].as_array();
        assert_eq!(
            interval.map(Vec::len),
            Some(2),
            "demo.json keeps the interval"
        );
    }
    // The paper's set-up (a): the winner against the runner-up on the horizontal error.
    let evaluation = json_file(&out.join("evaluation/evaluation.json"));
    let tests = evaluation["significance"]["tests"].as_array().unwrap();
    let horizontal = tests
        .iter()
        .find(|t| t["metric"] == "rms_horizontal")
        .unwrap();
    let significant = horizontal["significant"].as_bool().unwrap();
    let expected = if significant {
        "holds"
    } else {
        "does not hold"
    };
    assert_eq!(verdict_of(summary, "The paper&#39;s set-up (a)"), expected);
    let card = row_of(summary, "The paper&#39;s set-up (a)");
    let p = horizontal["test"]["p_value"].as_f64().unwrap();
    let p = if p >= 0.01 {
        format!("{p:.3}")
    } else {
        format!("{p:.2e}")
    };
    assert!(card.contains(&format!("paired p = {p}")), "{card}");
    assert!(summary.matches("95 % CI").count() >= 3 && summary.matches("<svg").count() == 3);
    assert!(summary.matches("<a href=\"#section-").count() == 3);

    // Each claim's oracle runs on the record its claimed model runs on: (b)'s the true models
    // on the raw record, (c)'s on the record compensated with the bank's own calibration (so
    // the bound asks what (c) asks, scheduling, not also a better compensation), and the
    // oracles are ranked apart.
    let bound_of = |key: &str| {
        demo["temperature_scenarios"][key]["claim"]["oracle_bound"]["better"]
            .as_str()
            .map(str::to_owned)
    };
    assert_eq!(
        bound_of("temperature_matters").as_deref(),
        Some("truth scheduled")
    );
    assert_eq!(
        bound_of("warming_survey").as_deref(),
        Some("truth scheduled on calibrated")
    );
    let warming = json_file(&out.join("temperature/warming_survey/evaluation.json"));
    let kinds: Vec<&str> = (warming["models"].as_array().unwrap().iter())
        .map(|m| m["kind"].as_str().unwrap())
        .collect();
    assert!(kinds.contains(&"oracle_on_calibrated") && kinds.contains(&"oracle_compensated"));
    for label in warming["best"].as_object().unwrap().values() {
        assert!(!label.as_str().unwrap().starts_with("truth"), "{label}");
    }

    // The Allan figures: one grid, one figure per temperature of the bank.
    let bank = json_file(&out.join("bank.json"));
    let grid = element(&html, "<div class=\"multiples\"", "div");
    let entries = bank["entries"].as_array().unwrap().len();
    assert_eq!(
        grid.matches("<figcaption>Allan deviation at").count(),
        entries
    );

    // One self-contained file: links only to its own anchors, no script, stylesheet, image or
    // font from elsewhere.
    for attribute in ["src", "href", "xlink:href"] {
        for value in attribute_values(&html, attribute) {
            assert!(value.starts_with('#'), "{attribute}=\"{value}\"");
        }
    }
    for forbidden in [
        "<script",
        "<link",
        "<img",
        "<iframe",
        "@import",
        "url(http",
        "@font-face",
    ] {
        assert!(!html.contains(forbidden), "{forbidden}");
    }

    // Issue 38 row 18: the quick demo wrote 361 MB, nine tenths of it chamber records that
    // only the banks need. They are removed once the banks are built (their truth stays, and
    // demo.json says how much went); what a user goes on with (the survey, banks, evaluations,
    // report) stays.
    let records = &demo["chamber_records"];
    assert_eq!(records["kind"], "removed", "{records}");
    assert!(records["size_mb"].as_f64().unwrap() > 100.0, "{records}");
    for folder in ["chamber", "temperature/chamber"] {
        let left: Vec<_> = walk(&out.join(folder))
            .into_iter()
            .filter(|p| p.extension().is_some_and(|e| e == "csv"))
            .collect();
        assert!(left.is_empty(), "{left:?}");
        assert!(out.join(folder).join("truth.json").is_file());
    }
    for kept in ["vessel/imu.csv", "vessel/gnss.csv", "vessel/reference.csv"] {
        assert!(out.join(kept).is_file(), "{kept}");
    }
    let written: u64 = walk(&out).iter().map(|p| p.metadata().unwrap().len()).sum();
    assert!(
        written < 100_000_000,
        "the quick demo wrote {written} bytes"
    );
}

/// Every file under `folder`, at any depth.
fn walk(folder: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(folder).unwrap() {
        let path = entry.unwrap().path();
        match path.is_dir() {
            true => files.extend(walk(&path)),
            false => files.push(path),
        }
    }
    files
}
