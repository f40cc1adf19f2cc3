//! `evaluate --truth`: the oracle candidates built from a simulated survey's truth.json, ranked
//! apart, every model's gap to them, and bad truth files refused.

use crate::{arg, outcome, thermonav, write_file};
use std::path::{Path, PathBuf};
use thermonav::nav::sensor_model::{ImuStochasticModel, ScaleFactorPrior};
use thermonav::sensor::temperature_sensitive;
use thermonav_io::truth::read_truth_file;

/// A 600 s survey of the temperature-sensitive sensor warming up from −10 °C, in `dir/v`.
fn warming_survey(dir: &Path) -> PathBuf {
    simulated_warming(dir, "600", &[])
}

/// A survey of `duration_s` of the temperature-sensitive sensor warming up from −10 °C, with
/// `extra` options of `simulate vessel`, in `dir/v`.
fn simulated_warming(dir: &Path, duration_s: &str, extra: &[&str]) -> PathBuf {
    let out = dir.join("v");
    let mut args = vec![
        "simulate",
        "vessel",
        "--profile",
        "builtin:temperature-sensitive",
        "--duration-s",
        duration_s,
        "--warm-up-from-c=-10",
        "--out",
        arg(&out),
    ];
    args.extend_from_slice(extra);
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    out
}

/// `evaluate` of the survey in `v` against the built-in profile with `extra` arguments.
fn evaluate(v: &Path, out: &Path, extra: &[&str]) -> (i32, String, String) {
    let (imu, gnss, reference) = (
        v.join("imu.csv"),
        v.join("gnss.csv"),
        v.join("reference.csv"),
    );
    let mut args = vec![
        "evaluate",
        "--imu",
        arg(&imu),
        "--gnss",
        arg(&gnss),
        "--reference",
        arg(&reference),
        "--profile",
        "builtin:temperature-sensitive",
        "--filter",
        "ekf",
        "--outages",
        "spread:3,60",
        "--out",
        arg(out),
        "--json",
    ];
    args.extend_from_slice(extra);
    outcome(&thermonav(&args))
}

fn horizontal(models: &[serde_json::Value], label: &str) -> f64 {
    let model = models.iter().find(|m| m["label"] == label).unwrap();
    model["rms_horizontal_m"].as_f64().unwrap()
}

// The truth.json that `simulate vessel` writes, read back, gives at every grid temperature
// the profile's own model (the simulator's source); 1e-12 relative covers the grid
// temperature's last bit (k · 0.1 written, low + k · 0.1 asked for here).
#[test]
fn the_truth_read_back_is_the_simulators_profile_model() {
    let dir = tempfile::tempdir().unwrap();
    let v = warming_survey(dir.path());
    let scale = ScaleFactorPrior::default();
    let truth = read_truth_file(v.join("truth.json"), &scale).unwrap();
    let profile = temperature_sensitive();
    let [low, high] = truth.range_c();
    assert!(low <= -10.0 && high >= 3.0, "{low}..{high} °C");
    let steps = ((high - low) / 0.1).round() as usize;
    for k in 0..=steps {
        let t = low + k as f64 * 0.1;
        let want = profile.stochastic_model(t, &scale).unwrap();
        let got = truth.model_at(t);
        let axes = |m: &ImuStochasticModel| {
            let all = m.gyro.iter().chain(&m.accel);
            all.flat_map(|a| {
                [
                    a.white_noise_density,
                    a.bias.correlation_time_s,
                    a.bias.sigma,
                ]
            })
            .collect::<Vec<f64>>()
        };
        for (g, w) in axes(got).into_iter().zip(axes(&want)) {
            assert!(
                (g - w).abs() <= 1e-12 * w.abs(),
                "at {t} °C: {g} against {w}"
            );
        }
    }
}

#[test]
fn the_oracle_is_ranked_apart_and_every_model_is_measured_against_it() {
    let dir = tempfile::tempdir().unwrap();
    let v = warming_survey(dir.path());
    let truth = v.join("truth.json");
    let (status, stdout, stderr) = evaluate(&v, &dir.path().join("ev"), &["--truth", arg(&truth)]);
    assert_eq!(status, 0, "{stderr}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let models = report["models"].as_array().unwrap();
    let kinds: Vec<&str> = models.iter().map(|m| m["kind"].as_str().unwrap()).collect();
    assert!(kinds.contains(&"oracle") && kinds.contains(&"oracle_compensated"));
    assert!(models.iter().all(|m| m["failure"].is_null()), "{stdout}");
    for label in report["best"].as_object().unwrap().values() {
        assert!(!label.as_str().unwrap().starts_with("truth"), "{label}");
    }
    // The scheduled truth on the raw record and the scheduled profile are the same models up
    // to the grid (the truth at multiples of 0.1 °C, the profile at the record's own grid).
    let (truth_h, profile_h) = (
        horizontal(models, "truth scheduled"),
        horizontal(models, "profile scheduled"),
    );
    assert!(
        (truth_h / profile_h - 1.0).abs() < 0.02,
        "{truth_h} {profile_h}"
    );
    let oracle_h = ["truth scheduled", "truth scheduled compensated"]
        .map(|l| horizontal(models, l))
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    let gaps = report["oracle_gaps"].as_array().unwrap();
    assert_eq!(gaps.len(), models.len() - 2);
    for gap in gaps {
        let own = horizontal(models, gap["label"].as_str().unwrap());
        assert_eq!(gap["oracle_rms_horizontal_m"].as_f64().unwrap(), oracle_h);
        assert!((gap["excess_m"].as_f64().unwrap() - (own - oracle_h)).abs() < 1e-9);
        assert!((gap["ratio"].as_f64().unwrap() - own / oracle_h).abs() < 1e-12);
    }
}

#[test]
fn a_record_without_temperatures_leaves_the_oracle_out_saying_why() {
    let dir = tempfile::tempdir().unwrap();
    let v = warming_survey(dir.path());
    let text = std::fs::read_to_string(v.join("imu.csv")).unwrap();
    let without: String = text
        .lines()
        .map(|l| l.rsplit_once(',').unwrap().0.to_owned() + "\n")
        .collect();
    std::fs::write(v.join("imu.csv"), without).unwrap();
    let truth = v.join("truth.json");
    let (status, stdout, stderr) = evaluate(
        &v,
        &dir.path().join("ev"),
        &["--truth", arg(&truth), "--operating-temperature-c", "0"],
    );
    assert_eq!(status, 0, "{stderr}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let excluded = report["excluded"].as_array().unwrap();
    let oracle = excluded.iter().find(|e| e["label"] == "truth scheduled");
    assert!(
        oracle.unwrap()["reason"]
            .as_str()
            .unwrap()
            .contains("temp_c")
    );
    assert!(report["oracle_gaps"].as_array().unwrap().is_empty());
}

#[test]
fn unusable_truth_files_are_refused_naming_the_file_and_what_was_expected() {
    let dir = tempfile::tempdir().unwrap();
    let v = warming_survey(dir.path());
    let good = std::fs::read_to_string(v.join("truth.json")).unwrap();
    let mut document: serde_json::Value = serde_json::from_str(&good).unwrap();
    document["models"][1]["temperature_c"] = document["models"][0]["temperature_c"].clone();
    let cases = [
        (
            "bank.json",
            "{\"entries\": []}\n".to_owned(),
            "not a survey truth",
        ),
        ("cut.json", good[..good.len() / 2].to_owned(), "line"),
        ("twice.json", document.to_string(), "strictly increasing"),
    ];
    for (name, text, needle) in cases {
        let path = write_file(dir.path(), name, &text);
        let out = dir.path().join(name.replace(".json", ""));
        let (status, stdout, stderr) = evaluate(&v, &out, &["--truth", arg(&path)]);
        assert_eq!(status, 1, "{name}: {stderr}");
        assert!(
            stderr.contains(name) && stderr.contains(needle),
            "{name}: {stderr}"
        );
        assert!(stdout.is_empty() && !out.join("evaluation.json").exists());
    }
    let missing = dir.path().join("none.json");
    let (status, _, stderr) = evaluate(&v, &dir.path().join("m"), &["--truth", arg(&missing)]);
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("none.json") && stderr.contains("cannot open"),
        "{stderr}"
    );
}

// A lagging unit's truth.json states each channel's lag, and `evaluate --truth` reads it: the
// oracle's compensation then reads the true bias at the structure's lagged temperature
// (closed form in the library's oracle tests). A lag that is negative or not a number is
// refused, naming the channel.
#[test]
fn a_lagging_units_truth_states_its_lags_and_bad_lags_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = simulated_warming(dir.path(), "120", &["--thermal-lag-s", "90"]);
    let text = std::fs::read_to_string(out.join("truth.json")).unwrap();
    let mut truth: serde_json::Value = serde_json::from_str(&text).unwrap();
    for channel in ["gx", "gy", "gz", "ax", "ay", "az"] {
        assert_eq!(truth["thermal_lag_s"][channel], 90.0, "{channel}");
    }
    let scale = ScaleFactorPrior::default();
    assert!(read_truth_file(out.join("truth.json"), &scale).is_ok());
    truth["thermal_lag_s"]["gy"] = serde_json::json!(-5.0);
    let bad = write_file(
        dir.path(),
        "bad_truth.json",
        &serde_json::to_string(&truth).unwrap(),
    );
    let error = read_truth_file(&bad, &scale).unwrap_err().to_string();
    assert!(error.contains("thermal_lag_s of gy is -5"), "{error}");
}
