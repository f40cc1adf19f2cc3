//! Issue 38 rows 13 and 14: `simulate vessel` for a slow vehicle (a speed, the GNSS rate and
//! sd, position-only fixes, a turn-on gyro bias, an IMU-GNSS time offset), and
//! `integrate --estimate-time-offset` saying when the offset is not observable. Expected
//! values are worked out here from the options and the written files.

use crate::{arg, outcome, thermonav};
use std::path::Path;

/// The first data row of a CSV, split.
fn first_row(path: &Path) -> (Vec<String>, Vec<f64>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let row = lines
        .next()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    (header, row)
}

/// A 60 s rover at 0.4 m/s with 20 Hz, 0.7 m position-only fixes, −100 deg/h on z and an
/// IMU clock 0.2 s behind the GNSS (offset +0.2 s).
fn rover(dir: &Path) -> std::path::PathBuf {
    let out = dir.join("rover");
    let args = [
        "simulate",
        "vessel",
        "--out",
        arg(&out),
        "--speed-m-s",
        "0.4",
        "--duration-s",
        "60",
        "--gnss-rate-hz",
        "20",
        "--gnss-sd-m",
        "0.7",
        "--gnss-heading",
        "none",
        "--gyro-bias-deg-h",
        "0,0,-100",
        "--time-offset-s",
        "0.2",
        "--json",
    ];
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    let summary: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(summary["gnss"]["rate_hz"], 20.0);
    assert_eq!(summary["gnss"]["heading"], "none");
    assert!(summary["heading_sd_deg"].is_null());
    out
}

#[test]
fn simulate_vessel_makes_a_slow_rover_with_its_offsets_in_the_truth() {
    let dir = tempfile::tempdir().unwrap();
    let out = rover(dir.path());
    // Position-only fixes: no heading column; sds as given (vertical twice the horizontal).
    let (header, fix) = first_row(&out.join("gnss.csv"));
    assert!(!header.iter().any(|h| h.contains("heading")), "{header:?}");
    let sd = |name: &str| fix[header.iter().position(|h| h == name).unwrap()];
    assert_eq!([sd("sd_n_m"), sd("sd_e_m"), sd("sd_u_m")], [0.7, 0.7, 1.4]);
    // 20 Hz: the first fix at 0.05 s on the GNSS scale.
    assert!((fix[0] - 0.05).abs() < 1e-9, "{}", fix[0]);
    // The IMU's first time is the reference's first sample time (true time) − 0.2 s.
    let (_, imu) = first_row(&out.join("imu.csv"));
    let reference = std::fs::read_to_string(out.join("reference.csv")).unwrap();
    let second: f64 = reference
        .lines()
        .nth(2)
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        (imu[0] - (second - 0.2)).abs() < 1e-9,
        "{} vs {second}",
        imu[0]
    );
    let truth: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("truth.json")).unwrap()).unwrap();
    assert_eq!(truth["imu_offsets"]["time_offset_s"], 0.2);
    let z = truth["imu_offsets"]["gyro_bias_rad_s"][2].as_f64().unwrap();
    assert!((z - (-100f64 / 3600.0).to_radians()).abs() < 1e-15, "{z}");
    assert_eq!(truth["added_gyro_bias_deg_h"][2], -100.0);
    // The rover reaches 0.4 m/s after its 20 s still start and 5 s pull-away.
    let last = reference
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap());
    let v: Vec<f64> = last.collect();
    assert!((v[4].hypot(v[5]) - 0.4).abs() < 1e-9, "{v:?}");
    // Refused before any work: a bias of two values, a non-positive speed, a huge offset.
    for bad in [
        ["--gyro-bias-deg-h", "1,2"],
        ["--speed-m-s", "0"],
        ["--time-offset-s", "1e9"],
    ] {
        let o = dir.path().join("refused");
        let (status, _, stderr) = outcome(&thermonav(&[
            "simulate",
            "vessel",
            "--out",
            arg(&o),
            bad[0],
            bad[1],
        ]));
        assert_eq!(status, 2, "{bad:?}: {stderr}");
        assert!(!o.exists());
    }
}

// Row 13: on 60 s of a 0.4 m/s rover the offset cannot be determined (40 s of motion, 0.7 m
// fixes against centimetres of antenna movement per 0.1 s of offset): the interval must cover
// the simulated +0.2 s, have no sd when it is open, and the warning must be on stderr and in
// the JSON.
#[test]
fn integrate_warns_that_a_slow_rover_time_offset_is_not_observable() {
    let dir = tempfile::tempdir().unwrap();
    let out = rover(dir.path());
    let profile = dir.path().join("profile.toml");
    assert_eq!(
        outcome(&thermonav(&["simulate", "profile", "--out", arg(&profile)])).0,
        0
    );
    let (status, stdout, stderr) = outcome(&thermonav(&[
        "integrate",
        "--imu",
        arg(&out.join("imu.csv")),
        "--gnss",
        arg(&out.join("gnss.csv")),
        "--profile",
        arg(&profile),
        "--out",
        arg(&dir.path().join("sol.csv")),
        "--estimate-time-offset",
        "--quiet",
        "--json",
    ]));
    assert_eq!(status, 0, "{stderr}");
    let t = &serde_json::from_str::<serde_json::Value>(&stdout).unwrap()["time_offset"];
    println!("{t:#}");
    let (lower, upper) = (
        t["lower"]["offset_s"].as_f64().unwrap(),
        t["upper"]["offset_s"].as_f64().unwrap(),
    );
    assert!(lower <= 0.2 && 0.2 <= upper, "[{lower}, {upper}]");
    assert_ne!(t["observability"], "resolved");
    let warning = t["warning"].as_str().unwrap();
    assert!(stderr.contains(&format!("warning: {warning}")), "{stderr}");
    let open = [&t["lower"], &t["upper"]]
        .iter()
        .any(|e| e["kind"] == "at_bracket_end");
    assert_eq!(t["time_offset_sd_s"].is_null(), open);
    // The profile behind it: every run, in increasing offset, over the bracket.
    let profile = t["profile"].as_array().unwrap();
    assert_eq!(profile.len() as u64, t["runs"].as_u64().unwrap());
    assert_eq!(profile[0]["offset_s"], -0.5);
    assert_eq!(profile[profile.len() - 1]["offset_s"], 0.5);
}
