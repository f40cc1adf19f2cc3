//! Issue 38 rows 13 and 14: `simulate vessel` for a slow vehicle (a speed, the GNSS rate and
//! sd, position-only fixes, a turn-on gyro bias, an IMU-GNSS time offset),
//! `integrate --estimate-time-offset` saying when the offset is not observable, and the
//! rover's heading kept on seeds whose alignment used to take the course through a turn.
//! Expected values are worked out here from the options and the written files.

use crate::{arg, outcome, thermonav};
use std::path::{Path, PathBuf};

/// The first data row of a CSV, split.
fn first_row(path: &Path) -> (Vec<String>, Vec<f64>) {
    let (header, rows) = table(path);
    (header, rows[0].clone())
}

/// A sensor profile from `simulate profile`, in `dir`.
fn sensor_profile(dir: &Path) -> PathBuf {
    let path = dir.join("profile.toml");
    let (status, _, stderr) = outcome(&thermonav(&["simulate", "profile", "--out", arg(&path)]));
    assert_eq!(status, 0, "{stderr}");
    path
}

/// `integrate` of the simulated files in `rover` with `profile`, the solution to `solution`,
/// with `extra` options; its stdout and stderr, after checking that it succeeded.
fn integrate(rover: &Path, profile: &Path, solution: &Path, extra: &[&str]) -> (String, String) {
    let (imu, gnss) = (rover.join("imu.csv"), rover.join("gnss.csv"));
    let mut args = vec![
        "integrate",
        "--imu",
        arg(&imu),
        "--gnss",
        arg(&gnss),
        "--profile",
        arg(profile),
        "--out",
        arg(solution),
        "--quiet",
    ];
    args.extend(extra);
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    (stdout, stderr)
}

/// `simulate vessel` of the rover into `out`: 0.4 m/s, 20 Hz, 0.7 m position-only
/// fixes, −100 deg/h on z, for `duration_s`, with `extra` options; its stdout.
fn simulate_rover(out: &Path, duration_s: &str, extra: &[&str]) -> String {
    let mut args = vec![
        "simulate",
        "vessel",
        "--out",
        arg(out),
        "--speed-m-s",
        "0.4",
        "--duration-s",
        duration_s,
        "--gnss-rate-hz",
        "20",
        "--gnss-sd-m",
        "0.7",
        "--gnss-heading",
        "none",
        "--gyro-bias-deg-h",
        "0,0,-100",
    ];
    args.extend(extra);
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    stdout
}

/// A 60 s rover with an IMU clock 0.2 s behind the GNSS (offset +0.2 s).
fn rover(dir: &Path) -> PathBuf {
    let out = dir.join("rover");
    let stdout = simulate_rover(&out, "60", &["--time-offset-s", "0.2", "--json"]);
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
    let profile = sensor_profile(dir.path());
    let solution = dir.path().join("sol.csv");
    let (stdout, stderr) = integrate(
        &out,
        &profile,
        &solution,
        &["--estimate-time-offset", "--json"],
    );
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
    let points = t["profile"].as_array().unwrap();
    assert_eq!(points.len() as u64, t["runs"].as_u64().unwrap());
    assert_eq!(points[0]["offset_s"], -0.5);
    assert_eq!(points[points.len() - 1]["offset_s"], 0.5);
    // Not determined, so not applied: the run keeps the IMU times as given, says so, and its
    // solution is the one integrate makes without the search (the maximum, at an end of the
    // bracket here, stays in the JSON for information).
    assert_eq!(t["applied"], false);
    assert_eq!(t["applied_offset_s"], 0.0);
    assert_ne!(t["time_offset_s"], 0.0);
    assert!(warning.contains("Not applied"), "{warning}");
    let plain = dir.path().join("plain.csv");
    integrate(&out, &profile, &plain, &["--in-memory"]);
    let read = |p: &Path| std::fs::read_to_string(p).unwrap();
    assert_eq!(read(&solution), read(&plain));
}

/// A CSV's header and rows of numbers.
fn table(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// Column `name` of a table.
fn column(table: &(Vec<String>, Vec<Vec<f64>>), name: &str) -> Vec<f64> {
    let k = table.0.iter().position(|h| h == name).unwrap();
    table.1.iter().map(|r| r[k]).collect()
}

/// The simulated rover of bench/slow_rover.py (300 s, offset 0) for `seed`, integrated.
fn integrated_rover(dir: &Path, profile: &Path, seed: &str) -> PathBuf {
    let out = dir.join(format!("seed{seed}"));
    simulate_rover(&out, "300", &["--seed", seed, "--unit-serial", seed]);
    integrate(&out, profile, &out.join("sol.csv"), &[]);
    out
}

/// The z gyro's true bias, deg/h: the unit's repeatable curve at the survey's temperature,
/// its power-on offset and the added bias, as truth.json states them.
fn true_z_gyro_bias_deg_h(truth: &serde_json::Value) -> f64 {
    let curve = &truth["unit"]["repeatable_bias"]["gz"];
    let c: Vec<f64> = (0..3)
        .map(|k| curve["coefficients"][k].as_f64().unwrap())
        .collect();
    let f = |v: &serde_json::Value| v.as_f64().unwrap();
    let d = f(&truth["temperature"]["temperature_c"]) - f(&curve["reference_temperature_c"]);
    let rad_s = c[0]
        + (c[1] + c[2] * d) * d
        + f(&truth["power_on_offset"]["gz"])
        + f(&truth["imu_offsets"]["gyro_bias_rad_s"][2]);
    rad_s.to_degrees() * 3600.0
}

// Issue 38 row 14, on the three seeds of bench/slow_rover.py whose heading was lost (0 % of
// epochs inside 3 sd, errors up to 36-56° at an sd of 3-5°): the course baseline of 20 Hz,
// 0.7 m fixes ran through a turn and its mean course became the heading at its start. The
// issue's criteria, each seed: the heading error inside 3 of the filter's sds in 95 % of the
// epochs, the heading sd below 10° once the rover has moved 20 m (along the reference), and
// the final z-gyro bias within 3 sds of the truth.
#[test]
fn the_slow_rover_keeps_its_heading_on_the_seeds_that_lost_it() {
    let dir = tempfile::tempdir().unwrap();
    let profile = sensor_profile(dir.path());
    for seed in ["6", "18", "20"] {
        let out = integrated_rover(dir.path(), &profile, seed);
        let reference = table(&out.join("reference.csv"));
        let (ref_t, ref_yaw) = (column(&reference, "t_s"), column(&reference, "yaw_deg"));
        let (vn, ve) = (column(&reference, "vn_m_s"), column(&reference, "ve_m_s"));
        let solution = table(&out.join("sol.csv"));
        let states = table(&out.join("sol.states.csv"));
        let (t, yaw) = (column(&solution, "t_s"), column(&solution, "yaw_deg"));
        assert_eq!(t, column(&states, "t_s"), "seed {seed}");
        let sd = column(&states, "sd_att_d_deg");
        let (mut inside, mut travelled, mut sd_at_20_m) = (0, 0.0, None);
        for k in 0..t.len() {
            // The reference sample at or just after the epoch (200 Hz against 10 Hz).
            let r = ref_t.partition_point(|&rt| rt < t[k]).min(ref_t.len() - 1);
            if k > 0 {
                travelled += vn[r].hypot(ve[r]) * (t[k] - t[k - 1]);
            }
            let error = (yaw[k] - ref_yaw[r] + 180.0).rem_euclid(360.0) - 180.0;
            inside += usize::from(error.abs() <= 3.0 * sd[k]);
            if sd_at_20_m.is_none() && travelled >= 20.0 {
                sd_at_20_m = Some(sd[k]);
            }
        }
        let share = inside as f64 / t.len() as f64;
        assert!(share >= 0.95, "seed {seed}: {share} inside 3 sd");
        let sd_at_20_m = sd_at_20_m.unwrap();
        assert!(sd_at_20_m < 10.0, "seed {seed}: {sd_at_20_m} deg at 20 m");
        let truth: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("truth.json")).unwrap())
                .unwrap();
        let last = states.1.len() - 1;
        let estimate = column(&states, "bgz_deg_h")[last];
        let bias_sd = column(&states, "sd_bgz_deg_h")[last];
        let truth = true_z_gyro_bias_deg_h(&truth);
        assert!(
            (estimate - truth).abs() <= 3.0 * bias_sd,
            "seed {seed}: {estimate} +- {bias_sd} against {truth} deg/h"
        );
    }
}
