//! `evaluate` takes `integrate`'s run options, with the same names and meaning: for each
//! option, `integrate` given it and `evaluate` given it report the same resolved run options
//! (`run_options` in both JSON documents), and integrate's solution, scored by `evaluate` as an
//! outside solution through the same outages, has the outage RMS of the tournament's candidate
//! with integrate's model: the two ran the same filter.

use crate::navigation::inputs;
use crate::{arg, outcome, thermonav};
use serde_json::Value;
use std::path::Path;

/// The outages of every run here.
const OUTAGES: [&str; 2] = ["--outages", "60+30,150+30"];

/// The outages, the vessel's lever arm unless `option` gives one, and `option`.
fn common<'a>(option: &[&'a str]) -> Vec<&'a str> {
    let mut args = OUTAGES.to_vec();
    if !option.contains(&"--lever-arm-m") {
        args.extend(["--lever-arm-m", "0.3,0,-2.5"]);
    }
    args.extend(option);
    args
}

fn json_of(args: &[&str]) -> Value {
    let (status, stdout, stderr) = outcome(&thermonav(args));
    assert_eq!(status, 0, "{args:?}: {stderr}");
    serde_json::from_str(&stdout).expect("stdout is one JSON document")
}

/// What `integrate` and `evaluate` reported of one option's runs.
struct Runs {
    integrate: Value,
    evaluate: Value,
}

impl Runs {
    /// The RMS horizontal error of evaluate's row `label`.
    fn rms(&self, label: &str) -> f64 {
        let models = self.evaluate["models"].as_array().unwrap();
        let row = models.iter().find(|m| m["label"] == label);
        let row = row.unwrap_or_else(|| panic!("no row {label}: {models:?}"));
        row["rms_horizontal_m"].as_f64().unwrap()
    }
}

/// `integrate` (its model chosen by `model`, started from the reference, uncompensated) with
/// `option`, then `evaluate` (EKF, fixed candidates on the raw record) with `option` and
/// integrate's solution as an outside solution.
fn runs(dir: &Path, option: &[&str], model: &[&str]) -> Runs {
    let (bank, vessel) = inputs(dir);
    let [imu, gnss, reference] = ["imu.csv", "gnss.csv", "reference.csv"].map(|f| vessel.join(f));
    let solution = dir.join("solution.csv");
    let mut args = vec!["integrate", "--imu", arg(&imu), "--gnss", arg(&gnss)];
    args.extend(["--bank", arg(&bank), "--initial-from", arg(&reference)]);
    args.extend(["--no-compensation", "--out", arg(&solution), "--json"]);
    args.extend(model);
    args.extend(common(option));
    let integrate = json_of(&args);
    let out = dir.join("evaluation");
    let mut args = vec!["evaluate", "--imu", arg(&imu), "--gnss", arg(&gnss)];
    args.extend(["--reference", arg(&reference), "--bank", arg(&bank)]);
    args.extend(["--filter", "ekf", "--no-schedule", "--no-compensation"]);
    args.extend([
        "--solution",
        arg(&solution),
        "--solution-label",
        "integrate",
    ]);
    args.extend(["--out", arg(&out), "--json"]);
    args.extend(common(option));
    let evaluate = json_of(&args);
    Runs {
        integrate,
        evaluate,
    }
}

/// The 25 °C entry of the bank, in integrate and as a candidate.
const ENTRY_25: (&[&str], &str) = (&["--model-temperature-c", "25"], "bank 25.0 °C");

/// Checks that `option` gives the same run options in both commands, that `check` holds of
/// them, and that integrate's run and the candidate `model.1` have the same outage RMS.
fn same_run(option: &[&str], model: (&[&str], &str), check: impl Fn(&Value) -> bool) -> Runs {
    let dir = tempfile::tempdir().unwrap();
    let runs = runs(dir.path(), option, model.0);
    let options = &runs.integrate["run_options"];
    assert!(options.is_object(), "{}", runs.integrate);
    assert_eq!(options, &runs.evaluate["run_options"], "{option:?}");
    assert!(check(options), "{option:?}: {options}");
    let (ours, theirs) = (runs.rms(model.1), runs.rms("integrate"));
    assert!(
        (ours - theirs).abs() < 1e-6,
        "{option:?}: {ours} vs {theirs}"
    );
    runs
}

fn is(value: &Value, expected: Value) -> bool {
    *value == expected
}

// The scaled white noise reaches every candidate: the scaled tournament's 25 °C candidate is
// integrate's scaled run, and not the unscaled one.
#[test]
fn process_noise_scale() {
    let scaled = same_run(&["--process-noise-scale", "3"], ENTRY_25, |o| {
        is(&o["process_noise_scale"], 3.0.into())
    });
    let plain = same_run(&[], ENTRY_25, |o| is(&o["process_noise_scale"], 1.0.into()));
    let (a, b) = (scaled.rms(ENTRY_25.1), plain.rms(ENTRY_25.1));
    assert!((a - b).abs() > 1e-3, "{a} vs {b}");
}

#[test]
fn velocity_sd_m_s() {
    same_run(&["--velocity-sd-m-s", "0.2,0.2,0.4"], ENTRY_25, |o| {
        is(&o["velocity_sd_m_s"], serde_json::json!([0.2, 0.2, 0.4]))
    });
}

#[test]
fn no_velocity() {
    same_run(&["--no-velocity"], ENTRY_25, |o| {
        is(&o["aiding"]["velocity"], false.into())
    });
}

#[test]
fn no_heading() {
    same_run(&["--no-heading"], ENTRY_25, |o| {
        is(&o["aiding"]["heading"], false.into())
    });
}

#[test]
fn gate_probability() {
    same_run(&["--gate-probability", "0.99"], ENTRY_25, |o| {
        is(&o["gate_probability"], 0.99.into())
    });
    same_run(&["--gate-probability", "1"], ENTRY_25, |o| {
        o["gate_probability"].is_null()
    });
}

#[test]
fn gate_window() {
    same_run(&["--gate-window", "0"], ENTRY_25, |o| {
        is(&o["gate_window"], 0.into())
    });
}

#[test]
fn lever_arm_and_baseline() {
    same_run(
        &["--lever-arm-m", "0.3,0,-2.4", "--baseline", "1,0.1,0"],
        ENTRY_25,
        |o| {
            is(
                &o["geometry"]["lever_arm_body_m"],
                serde_json::json!([0.3, 0.0, -2.4]),
            ) && is(
                &o["geometry"]["baseline_body"],
                serde_json::json!([1.0, 0.1, 0.0]),
            )
        },
    );
}

#[test]
fn covariance_rate_hz() {
    same_run(&["--covariance-rate-hz", "5"], ENTRY_25, |o| {
        is(&o["covariance_interval_s"], 0.2.into())
    });
}

#[test]
fn max_imu_gap_s() {
    same_run(&["--max-imu-gap-s", "0.5"], ENTRY_25, |o| {
        is(&o["max_imu_gap_s"], 0.5.into())
    });
}

#[test]
fn bias_hypotheses() {
    same_run(&["--bias-hypotheses", "9"], ENTRY_25, |o| {
        is(&o["bias_hypotheses"]["members"], 9.into())
    });
}

#[test]
fn model() {
    same_run(&["--model", "ar-based"], ENTRY_25, |o| {
        is(&o["gauss_markov"], "ar_based".into())
    });
}

// The operating temperature is where integrate interpolates its model (--select linear) and
// where the tournament's interpolated candidate stands.
#[test]
fn operating_temperature_c() {
    let linear: (&[&str], &str) = (&["--select", "linear"], "interpolated 17.0 °C");
    let runs = same_run(&["--operating-temperature-c", "17"], linear, |_| true);
    assert_eq!(runs.integrate["model"]["temperature_c"], 17.0);
    assert_eq!(runs.evaluate["operating_temperature_c"], 17.0);
}

// A bad value is refused in the same words by both, before any file is read.
#[test]
fn both_refuse_a_bad_option_alike() {
    let cases: [&[&str]; 4] = [
        &["--process-noise-scale", "0"],
        &["--velocity-sd-m-s", "0.1,0.2"],
        &["--gate-probability", "1.5"],
        &["--bias-hypotheses", "4"],
    ];
    for option in cases {
        let error = refused_alike(option);
        assert!(error.contains(option[0]), "{option:?}: {error}");
    }
}

/// The usage error (exit 2) that `integrate` and `evaluate` both give for `option`, with files
/// that do not exist (so it came before any was read); asserts that the two say the same.
pub(crate) fn refused_alike(option: &[&str]) -> String {
    let missing = "/nonexistent/file.csv";
    let mut integrate = vec!["integrate", "--imu", missing, "--gnss", missing];
    integrate.extend(["--bank", missing, "--out", "/nonexistent/out.csv"]);
    let mut evaluate = vec!["evaluate", "--imu", missing, "--gnss", missing];
    evaluate.extend(["--reference", missing, "--bank", missing]);
    evaluate.extend(["--out", "/nonexistent/out"]);
    let [(a, _, a_err), (b, _, b_err)] = [integrate, evaluate].map(|mut args| {
        args.extend(option);
        outcome(&thermonav(&args))
    });
    assert_eq!((a, b), (2, 2), "{option:?}: {a_err} / {b_err}");
    assert_eq!(a_err, b_err, "{option:?}");
    a_err
}
