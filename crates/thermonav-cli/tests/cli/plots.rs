//! `thermonav plot`: figures from simulated chamber records, their bank and `allan --json`.

use crate::modelling::chamber;
use crate::{arg, outcome, thermonav};
use std::path::{Path, PathBuf};

/// Runs `thermonav args…`, expecting success, and returns stdout.
fn succeed(args: &[&str]) -> String {
    let (status, stdout, stderr) = outcome(&thermonav(args));
    assert_eq!(status, 0, "{args:?}: {stderr}");
    stdout
}

/// Two short chamber records (0 and 20 °C) and their bank, in `dir`.
fn records_and_bank(dir: &Path) -> (Vec<String>, PathBuf) {
    let truth = chamber(dir);
    let files: Vec<String> = truth["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap().to_owned())
        .collect();
    let bank = dir.join("bank.json");
    let mut args = vec!["characterize"];
    args.extend(files.iter().map(String::as_str));
    args.extend(["--out", arg(&bank), "--quiet"]);
    succeed(&args);
    (files, bank)
}

/// The axis labels of an SVG file, after checking that it is well-formed SVG.
fn axis_labels(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&text).expect("the figure is well-formed XML");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    assert!(doc.descendants().all(|n| !n.has_tag_name("script")));
    doc.descendants()
        .filter(|n| {
            n.attribute("class")
                .is_some_and(|c| c.starts_with("axis-label"))
        })
        .map(|n| n.text().unwrap_or_default().to_owned())
        .collect()
}

#[test]
fn figures_from_the_bank_allan_output_and_a_record() {
    let dir = tempfile::tempdir().unwrap();
    let (files, bank) = records_and_bank(dir.path());

    let png = dir.path().join("tc.png");
    succeed(&["plot", "correlation-time", arg(&bank), "--out", arg(&png)]);
    let bytes = std::fs::read(&png).unwrap();
    assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "a PNG file");

    let tc = dir.path().join("tc.svg");
    succeed(&["plot", "correlation-time", arg(&bank), "--out", arg(&tc)]);
    let labels = axis_labels(&tc);
    assert!(labels.iter().any(|l| l == "correlation time Tc (s)"));
    assert!(labels.iter().any(|l| l == "temperature (°C)"));

    let from_bank = dir.path().join("allan-bank.svg");
    succeed(&[
        "plot",
        "allan",
        arg(&bank),
        "--temperature-c",
        "20",
        "--units",
        "si",
        "--out",
        arg(&from_bank),
    ]);
    let labels = axis_labels(&from_bank);
    assert!(labels.contains(&"Allan deviation σ(τ) (rad/s)".to_owned()));
    assert!(labels.contains(&"Allan deviation σ(τ) (m/s²)".to_owned()));

    let allan_json = dir.path().join("allan.json");
    std::fs::write(&allan_json, succeed(&["allan", &files[0], "--json"])).unwrap();
    let from_allan = dir.path().join("allan.svg");
    succeed(&["plot", "allan", arg(&allan_json), "--out", arg(&from_allan)]);
    let labels = axis_labels(&from_allan);
    assert!(labels.contains(&"Allan deviation σ(τ) (deg/h)".to_owned()));
    assert!(labels.contains(&"Allan deviation σ(τ) (mg)".to_owned()));
    assert!(
        std::fs::read_to_string(&from_allan)
            .unwrap()
            .contains("68.3 % confidence")
    );

    let acf = dir.path().join("acf.svg");
    succeed(&[
        "plot",
        "autocorrelation",
        &files[1],
        "--channel",
        "az",
        "--max-lag-s",
        "60",
        "--out",
        arg(&acf),
    ]);
    assert_eq!(axis_labels(&acf), ["lag τ (s)", "autocovariance ((mg)²)"]);
}

#[test]
fn bad_plot_requests_fail_with_the_right_code_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let (files, bank) = records_and_bank(dir.path());
    let out = dir.path().join("figure.svg");
    let code = |args: &[&str]| {
        let (status, _, stderr) = outcome(&thermonav(args));
        (status, stderr)
    };
    let (status, stderr) = code(&["plot", "allan", arg(&bank), "--out", arg(&out)]);
    assert_eq!(status, 2, "two entries and no --temperature-c: {stderr}");
    assert!(stderr.contains("--temperature-c"));
    let pdf = dir.path().join("figure.pdf");
    let (status, _) = code(&["plot", "correlation-time", arg(&bank), "--out", arg(&pdf)]);
    assert_eq!(status, 2);
    let (status, stderr) = code(&["plot", "correlation-time", &files[0], "--out", arg(&out)]);
    assert_eq!(status, 1, "a CSV is not a bank: {stderr}");
    let (status, _) = code(&[
        "plot",
        "autocorrelation",
        &files[0],
        "--channel",
        "gw",
        "--out",
        arg(&out),
    ]);
    assert_eq!(status, 2);
    assert!(!out.exists() && !pdf.exists());
}

#[test]
fn the_trajectory_figure_highlights_each_outage() {
    let dir = tempfile::tempdir().unwrap();
    let vessel = dir.path().join("vessel");
    succeed(&[
        "simulate",
        "vessel",
        "--out",
        arg(&vessel),
        "--duration-s",
        "120",
        "--seed",
        "3",
        "--quiet",
    ]);
    let out = dir.path().join("trajectory.svg");
    let reference = vessel.join("reference.csv");
    succeed(&[
        "plot",
        "trajectory",
        arg(&reference),
        "--outages",
        "20+15,70+20",
        "--out",
        arg(&out),
    ]);
    assert_eq!(axis_labels(&out), ["east (m)", "north (m)"]);
    let text = std::fs::read_to_string(&out).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let thick = doc
        .descendants()
        .filter(|n| {
            n.attribute("class") == Some("series") && n.attribute("stroke-width") == Some("4")
        })
        .count();
    assert_eq!(thick, 2, "one highlighted run per outage");
    let (status, _, _) = outcome(&thermonav(&[
        "plot",
        "trajectory",
        arg(&reference),
        "--outages",
        "20+-5",
        "--out",
        arg(&out),
    ]));
    assert_eq!(status, 2);
}

// `plot allan` of `allan --kind K --json` draws that kind: its name in the title and on the
// y axis with its unit (the rate's times seconds for tdev), no confidence band (those kinds
// carry none). The record is 2000 samples at 100 Hz of a fixed pseudo-random pattern.
#[test]
fn plot_allan_draws_the_kind_the_file_carries() {
    let dir = tempfile::tempdir().unwrap();
    let text = crate::imu_csv(2000, 100.0, |c, t| {
        let k = (t * 100.0).round() as usize;
        ((k * 7919 + c * 104_729) % 1013) as f64 * 1e-4
    });
    let record = crate::write_file(dir.path(), "record.csv", &text);
    for (kind, gyro_label) in [
        ("mdev", "Modified Allan deviation mod σ(τ) (deg/h)"),
        ("hdev", "Hadamard deviation Hσ(τ) (deg/h)"),
        ("ohdev", "Overlapping Hadamard deviation Hσ(τ) (deg/h)"),
        ("tdev", "Time deviation σx(τ) (deg/h·s)"),
        ("totdev", "Total deviation σtotal(τ) (deg/h)"),
    ] {
        let json = dir.path().join(format!("{kind}.json"));
        let doc = succeed(&["allan", arg(&record), "--kind", kind, "--json"]);
        std::fs::write(&json, doc).unwrap();
        let svg = dir.path().join(format!("{kind}.svg"));
        succeed(&["plot", "allan", arg(&json), "--out", arg(&svg)]);
        assert!(axis_labels(&svg).contains(&gyro_label.to_owned()), "{kind}");
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(!text.contains("% confidence"), "{kind}");
    }
}
