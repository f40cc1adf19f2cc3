//! Production lots end to end: `characterize --manifest`, `--unit-index` jobs, `lot summarize`,
//! and bad manifests.

use crate::{arg, outcome, thermonav};
use serde_json::Value;
use std::path::{Path, PathBuf};

const SERIALS: [&str; 3] = ["SN001", "SN002", "SN003"];

/// Three units (seeds 1, 2, 3), each with 0 and 20 °C records of 5 min at 50 Hz, and a manifest
/// naming them by paths relative to its folder; returns the manifest.
fn simulate_lot(dir: &Path) -> PathBuf {
    for (k, serial) in SERIALS.iter().enumerate() {
        let (status, _, stderr) = outcome(&thermonav(&[
            "simulate",
            "chamber",
            "--out",
            arg(&dir.join(serial)),
            "--temperatures-c",
            "0,20",
            "--duration-s",
            "300",
            "--rate-hz",
            "50",
            "--seed",
            &(k + 1).to_string(),
            "--quiet",
        ]));
        assert_eq!(status, 0, "stderr: {stderr}");
    }
    let mut text = String::from("name = \"test lot\"\n");
    for serial in SERIALS {
        text += &format!(
            "\n[[unit]]\nserial = \"{serial}\"\nfiles = [\"{serial}/imu_0C.csv\", \"{serial}/imu_20C.csv\"]\n"
        );
    }
    crate::write_file(dir, "lot.toml", &text)
}

fn run_ok(args: &[&str]) -> String {
    let (status, stdout, stderr) = outcome(&thermonav(args));
    assert_eq!(status, 0, "{args:?}\nstderr: {stderr}");
    stdout
}

fn json_file(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("file exists")).expect("JSON")
}

/// The value of a summary quantity in a bank channel, read straight from the bank's JSON.
fn bank_value(channel: &Value, quantity: &str) -> Option<f64> {
    let gauss_markov = |family: &str, field: &str| {
        let estimate = &channel["gauss_markov"][family];
        (estimate["status"] == "model").then(|| estimate[field].as_f64().unwrap())
    };
    let families = ["irregular_ml", "ar_based", "acf_fit"];
    for family in families {
        if quantity == format!("{family}_correlation_time_s") {
            return gauss_markov(family, "correlation_time_s");
        }
        if quantity.starts_with(&format!("{family}_sigma_")) {
            return gauss_markov(family, "sigma");
        }
    }
    let allan = match quantity.split('_').next().unwrap() {
        "white" => "white_noise_density",
        "bias" => "bias_instability",
        "rate" => "rate_random_walk",
        other => panic!("unexpected quantity {other}"),
    };
    channel["allan"][allan].as_f64()
}

/// Plain median of a sorted slice.
fn median(sorted: &[f64]) -> f64 {
    let n = sorted.len();
    match n % 2 {
        1 => sorted[n / 2],
        _ => (sorted[n / 2 - 1] + sorted[n / 2]) / 2.0,
    }
}

/// Every key the summary must have per sensor: three families' Tc and σ, three Allan terms.
fn expected_keys(gyro: bool) -> Vec<String> {
    let (rate, density, walk) = match gyro {
        true => ("rad_s", "rad_per_sqrt_s", "rad_s_per_sqrt_s"),
        false => ("m_s2", "m_s_per_sqrt_s", "m_s2_per_sqrt_s"),
    };
    let mut keys = Vec::new();
    for family in ["irregular_ml", "ar_based", "acf_fit"] {
        keys.push(format!("{family}_correlation_time_s"));
        keys.push(format!("{family}_sigma_{rate}"));
    }
    keys.push(format!("white_noise_density_{density}"));
    keys.push(format!("bias_instability_{rate}"));
    keys.push(format!("rate_random_walk_{walk}"));
    keys
}

// The summary against an independent computation from the per-unit banks: the banks' entries
// matched by position (both units have 0 and 20 °C), values sorted, median and MAD by hand,
// outliers by |x − median| > 3 · 1.4826 · MAD. Same arithmetic on the same doubles, so the
// tolerance is a few ulps (1e-12 relative covers any reordering of the subtraction).
#[test]
fn lot_summary_matches_an_independent_computation_from_the_banks() {
    let dir = tempfile::tempdir().unwrap();
    let manifest = simulate_lot(dir.path());
    let out = dir.path().join("out");
    let stdout = run_ok(&[
        "characterize",
        "--manifest",
        arg(&manifest),
        "--out",
        arg(&out),
        "--json",
    ]);
    let run: Value = serde_json::from_str(&stdout).unwrap();
    let summary = json_file(&out.join("lot-summary.json"));
    assert_eq!(run["summary"], summary);
    assert_eq!(summary["units"], serde_json::json!(SERIALS));
    let banks: Vec<Value> = SERIALS
        .iter()
        .map(|s| json_file(&out.join(s).join("bank.json")))
        .collect();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs());
    let (mut flagged, mut unflagged) = (0, 0);
    for (p, point) in summary["points"].as_array().unwrap().iter().enumerate() {
        for (channel, spreads) in point["channels"].as_object().unwrap() {
            let mut keys: Vec<&String> = spreads.as_object().unwrap().keys().collect();
            let mut expected = expected_keys(channel.starts_with('g'));
            keys.sort();
            expected.sort();
            // A quantity may be absent only when no unit has a value.
            for key in &expected {
                let values: Vec<(usize, f64)> = banks
                    .iter()
                    .enumerate()
                    .filter_map(|(u, b)| {
                        Some((u, bank_value(&b["entries"][p]["channels"][channel], key)?))
                    })
                    .collect();
                let Some(spread) = spreads.get(key) else {
                    assert!(
                        values.is_empty(),
                        "{channel} {key} missing from the summary"
                    );
                    continue;
                };
                let mut sorted: Vec<f64> = values.iter().map(|v| v.1).collect();
                sorted.sort_by(f64::total_cmp);
                let m = median(&sorted);
                let mut deviations: Vec<f64> = sorted.iter().map(|v| (v - m).abs()).collect();
                deviations.sort_by(f64::total_cmp);
                let mad = median(&deviations);
                assert!(
                    close(spread["median"].as_f64().unwrap(), m),
                    "{channel} {key}"
                );
                assert!(
                    close(spread["mad"].as_f64().unwrap(), mad),
                    "{channel} {key}"
                );
                assert_eq!(spread["min"].as_f64().unwrap(), sorted[0]);
                assert_eq!(spread["max"].as_f64().unwrap(), sorted[sorted.len() - 1]);
                assert_eq!(spread["units_with_value"], sorted.len());
                let outliers: Vec<&str> = values
                    .iter()
                    .filter(|(_, v)| mad > 0.0 && (v - m).abs() > 3.0 * 1.4826 * mad)
                    .map(|(u, _)| SERIALS[*u])
                    .collect();
                let reported: Vec<&str> = spread["outliers"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|o| o["serial"].as_str().unwrap())
                    .collect();
                assert_eq!(reported, outliers, "{channel} {key}");
                flagged += outliers.len();
                unflagged += values.len() - outliers.len();
            }
            assert!(keys.iter().all(|k| expected.contains(k)), "{keys:?}");
        }
    }
    // The seeds give both kinds, so both sides of the rule are exercised.
    assert!(flagged > 0 && unflagged > 0, "{flagged} {unflagged}");
    assert_eq!(summary["outliers"].as_array().unwrap().len(), flagged);
    // Lot points sit at the median of the units' entry temperatures, near the set points.
    let t0 = summary["points"][0]["temperature_c"].as_f64().unwrap();
    assert!(t0.abs() < 0.5, "{t0}");
}

// A unit's bank is what plain `characterize` writes for that unit's files, and the unit jobs
// (--unit-index, --unit) followed by `lot summarize` give the all-units summary.
#[test]
fn unit_jobs_and_summarize_equal_the_all_units_run() {
    let dir = tempfile::tempdir().unwrap();
    let manifest = simulate_lot(dir.path());
    let all = dir.path().join("all");
    run_ok(&[
        "characterize",
        "--manifest",
        arg(&manifest),
        "--out",
        arg(&all),
    ]);
    let plain = dir.path().join("plain.json");
    let unit = dir.path().join("SN002");
    run_ok(&[
        "characterize",
        arg(&unit.join("imu_0C.csv")),
        arg(&unit.join("imu_20C.csv")),
        "--out",
        arg(&plain),
    ]);
    assert_eq!(json_file(&plain), json_file(&all.join("SN002/bank.json")));

    let jobs = dir.path().join("jobs");
    for index in ["0", "1"] {
        let m = arg(&manifest);
        run_ok(&[
            "characterize",
            "--manifest",
            m,
            "--unit-index",
            index,
            "--out",
            arg(&jobs),
        ]);
    }
    let by_serial = [
        "characterize",
        "--manifest",
        arg(&manifest),
        "--unit",
        "SN003",
        "--out",
        arg(&jobs),
    ];
    run_ok(&by_serial);
    assert!(
        !jobs.join("lot-summary.json").exists(),
        "a unit job summarised"
    );
    let stdout = run_ok(&[
        "lot",
        "summarize",
        arg(&jobs),
        "--manifest",
        arg(&manifest),
        "--json",
    ]);
    let summary = json_file(&jobs.join("lot-summary.json"));
    assert_eq!(serde_json::from_str::<Value>(&stdout).unwrap(), summary);
    assert_eq!(summary, json_file(&all.join("lot-summary.json")));
    for serial in SERIALS {
        let bank = |d: &Path| json_file(&d.join(serial).join("bank.json"));
        assert_eq!(bank(&jobs), bank(&all), "{serial}");
    }
    // The text table carries the units in its keys and the rule.
    let text = run_ok(&["lot", "summarize", arg(&jobs), "--manifest", arg(&manifest)]);
    assert!(text.contains("irregular_ml_correlation_time_s"), "{text}");
    assert!(
        text.contains("white_noise_density_m_s_per_sqrt_s"),
        "{text}"
    );
    assert!(
        text.contains("outlier rule: |value - median| > 3"),
        "{text}"
    );
}

// A failing unit is named with its file (and line), the others complete, nothing partial is
// left, and the run exits 1. The folder held a whole earlier run: the failed units' banks and
// the lot summary from it are removed, so no summary can mix stale banks with new ones.
#[test]
fn a_failing_unit_does_not_stop_the_others() {
    let dir = tempfile::tempdir().unwrap();
    let manifest = simulate_lot(dir.path());
    let out = dir.path().join("out");
    run_ok(&[
        "characterize",
        "--manifest",
        arg(&manifest),
        "--out",
        arg(&out),
    ]);
    assert!(out.join("lot-summary.json").exists() && out.join("SN001/bank.json").exists());
    let broken = dir.path().join("SN001/imu_20C.csv");
    let text = std::fs::read_to_string(&broken).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    lines[4] = "1.0,not-a-number,0,0,0,0,0,20";
    std::fs::write(&broken, lines.join("\n")).unwrap();
    std::fs::remove_file(dir.path().join("SN003/imu_0C.csv")).unwrap();
    let (status, stdout, stderr) = outcome(&thermonav(&[
        "characterize",
        "--manifest",
        arg(&manifest),
        "--out",
        arg(&out),
    ]));
    assert_eq!(status, 1, "{stderr}");
    assert!(stderr.contains("2 of 3 units failed"), "{stderr}");
    let sn001 = format!("unit SN001: {}:5: column ", broken.display());
    assert!(stderr.contains(&sn001), "{stderr}");
    assert!(
        stderr.contains("unit SN003: ") && stderr.contains("imu_0C.csv"),
        "{stderr}"
    );
    assert!(
        stdout.contains("SN002            bank written to"),
        "{stdout}"
    );
    assert!(out.join("SN002/bank.json").exists());
    // A failed unit leaves neither its stale bank nor an empty folder (issue 37).
    assert!(!out.join("SN001").exists() && !out.join("SN003").exists());
    assert!(!out.join("lot-summary.json").exists());
    // Summarising that folder names the units without a bank.
    let (status, _, stderr) = outcome(&thermonav(&[
        "lot",
        "summarize",
        arg(&out),
        "--manifest",
        arg(&manifest),
    ]));
    assert_eq!(status, 1);
    assert!(stderr.contains("2 of 3 banks cannot be used"), "{stderr}");
    assert!(
        stderr.contains("unit SN001: ") && stderr.contains("SN001/bank.json"),
        "{stderr}"
    );
}

#[test]
fn bad_manifests_are_refused_with_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let run = |text: &str| {
        let manifest = crate::write_file(dir.path(), "lot.toml", text);
        outcome(&thermonav(&[
            "characterize",
            "--manifest",
            arg(&manifest),
            "--out",
            arg(&out),
        ]))
    };
    let unit = |serial: &str| format!("\n[[unit]]\nserial = \"{serial}\"\nfiles = [\"a.csv\"]\n");
    let (status, _, stderr) = run(&format!("name = \"x\"\n{}{}", unit("A"), unit("A")));
    assert_eq!(status, 1);
    assert!(
        stderr.contains("lot.toml:8: serial \"A\" already names the unit on line 4"),
        "{stderr}"
    );
    let (status, _, stderr) = run(&format!("name = \"x\"\ncolour = \"red\"\n{}", unit("A")));
    assert_eq!(status, 1);
    assert!(
        stderr.contains("line 2") && stderr.contains("colour"),
        "{stderr}"
    );
    let (status, _, stderr) = run("name = \"x\"\n");
    assert_eq!(status, 1);
    assert!(stderr.contains("no [[unit]] entries"), "{stderr}");
    let (status, _, stderr) = run(&format!("name = \"x\"\n{}", unit("A")));
    assert_eq!(status, 1);
    assert!(
        stderr.contains("unit A: ") && stderr.contains("a.csv: cannot open"),
        "{stderr}"
    );
    assert!(!out.join("lot-summary.json").exists());
    let (status, _, stderr) = outcome(&thermonav(&[
        "characterize",
        "--manifest",
        arg(&dir.path().join("lot.toml")),
        "--unit-index",
        "3",
        "--out",
        arg(&out),
    ]));
    assert_eq!(status, 2);
    assert!(stderr.contains("has 1 units (expected 0 to 0)"), "{stderr}");
    let (status, _, stderr) = outcome(&thermonav(&[
        "characterize",
        "--manifest",
        arg(&dir.path().join("lot.toml")),
        "--unit",
        "B",
        "--out",
        arg(&out),
    ]));
    assert_eq!(status, 2);
    assert!(
        stderr.contains("--unit B: no such unit") && stderr.contains("serials: A)"),
        "{stderr}"
    );
}

// The example manifest parses (the index is out of range, so nothing runs).
#[test]
fn the_example_manifest_is_valid() {
    let example = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/lot/lot.toml");
    let out = tempfile::tempdir().unwrap();
    let (status, _, stderr) = outcome(&thermonav(&[
        "characterize",
        "--manifest",
        example,
        "--unit-index",
        "99",
        "--out",
        arg(out.path()),
    ]));
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.contains("has 3 units"), "{stderr}");
}
