//! Issue 38 row 16: a bank made at 100 Hz from another sensor, used on a 152 Hz IMU, ran
//! without a word. `integrate` now says when the bank's records were sampled at another rate
//! than the IMU record (beyond 5 %), in a note on stderr and in `--json`'s `record_notes`, and
//! goes on: the bank's terms are densities and continuous-time processes, which the filter
//! discretises at the record's own intervals.

use crate::{arg, outcome, thermonav};
use std::path::Path;

/// `integrate` of the vessel run with `bank` (the bank's 25 °C model), as JSON, and its stderr.
fn integrate(dir: &Path, vessel: &Path, bank: &Path) -> (serde_json::Value, String) {
    let out = dir.join("solution.csv");
    let args = crate::navigation::integrate_args(vessel, bank, &out, &[]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    (
        serde_json::from_str(&stdout).expect("one JSON document"),
        stderr,
    )
}

/// A bank from chamber records at 10 and 25 °C sampled at `rate_hz` (those of
/// [`crate::navigation::inputs`] at another rate).
fn bank_at(dir: &Path, rate_hz: &str) -> std::path::PathBuf {
    let chamber = dir.join(format!("chamber-{rate_hz}"));
    let simulate = [
        "simulate",
        "chamber",
        "--out",
        arg(&chamber),
        "--temperatures-c",
        "10,25",
        "--duration-s",
        "600",
        "--rate-hz",
        rate_hz,
        "--seed",
        "3",
    ];
    let (status, _, stderr) = outcome(&thermonav(&simulate));
    assert_eq!(status, 0, "{stderr}");
    let bank = dir.join(format!("bank-{rate_hz}.json"));
    let records = ["imu_10C.csv", "imu_25C.csv"].map(|name| chamber.join(name));
    let characterize = [
        "characterize",
        arg(&records[0]),
        arg(&records[1]),
        "--out",
        arg(&bank),
    ];
    let (status, _, stderr) = outcome(&thermonav(&characterize));
    assert_eq!(status, 0, "{stderr}");
    bank
}

// The user's step with the rates of our simulators: a bank characterized from 50 Hz chamber
// records, used on the vessel's 200 Hz IMU. The run goes on, and says so: the two rates (the
// record's from its median interval, 200 Hz to well under 1 % despite the simulated jitter),
// the bank's records, and why the densities still apply. A bank made at the record's own rate
// gets no note.
#[test]
fn a_bank_made_at_another_rate_is_noted_and_the_run_goes_on() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = crate::navigation::inputs(dir.path());
    let (json, stderr) = integrate(dir.path(), &vessel, &bank);
    let notes = json["record_notes"].as_array().expect("record_notes");
    assert_eq!(notes.len(), 1, "{json}");
    let note = &notes[0];
    assert_eq!(note["differs"], "sample_rate");
    let rate = |key: &str| note[key].as_f64().unwrap();
    assert!((rate("bank_rate_hz") / 50.0 - 1.0).abs() < 0.01, "{note}");
    assert!(
        (rate("record_rate_hz") / 200.0 - 1.0).abs() < 0.01,
        "{note}"
    );
    assert_eq!(note["tolerance"], 0.05);
    assert_eq!(note["bank_sources"].as_array().unwrap().len(), 2);
    let text = note["note"].as_str().unwrap();
    for words in [
        "at 50.0 Hz",
        "(+300 %",
        "densities",
        "rad/sqrt(s)",
        "discretises",
    ] {
        assert!(text.contains(words), "{words}: {text}");
    }
    let printed = stderr.lines().filter(|l| l.starts_with("note:")).count();
    assert_eq!(printed, 1, "{stderr}");
    assert!(stderr.contains(text), "{stderr}");
    assert!(json["imu_samples"].as_u64().unwrap() > 0, "the run went on");

    let same_rate = bank_at(dir.path(), "200");
    let (json, stderr) = integrate(dir.path(), &vessel, &same_rate);
    assert_eq!(json["record_notes"].as_array().unwrap().len(), 0, "{json}");
    assert!(!stderr.contains("the bank was made from"), "{stderr}");
}
