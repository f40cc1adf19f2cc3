//! `thermonav integrate` end to end: simulated chamber → bank, simulated vessel → solution,
//! compared with the simulated truth; and its refusals of bad input.

use crate::{arg, outcome, thermonav};
use std::path::{Path, PathBuf};

fn json_of<S: AsRef<str>>(args: &[S]) -> serde_json::Value {
    let args: Vec<&str> = args.iter().map(AsRef::as_ref).collect();
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "stderr: {stderr}");
    serde_json::from_str(&stdout).expect("stdout is one JSON document")
}

/// A bank from two short chamber records, and a 240 s vessel run at 17 °C.
fn inputs(dir: &Path) -> (PathBuf, PathBuf) {
    let chamber = json_of(&[
        "simulate",
        "chamber",
        "--out",
        arg(&dir.join("chamber")),
        "--temperatures-c",
        "10,25",
        "--duration-s",
        "600",
        "--rate-hz",
        "50",
        "--seed",
        "3",
        "--json",
    ]);
    let files: Vec<String> = chamber["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap().to_string())
        .collect();
    let bank = dir.join("bank.json");
    let mut args = vec!["characterize"];
    args.extend(files.iter().map(String::as_str));
    args.extend(["--out", arg(&bank), "--json"]);
    json_of(&args);
    let vessel = dir.join("vessel");
    json_of(&[
        "simulate",
        "vessel",
        "--out",
        arg(&vessel),
        "--duration-s",
        "240",
        "--seed",
        "4",
        "--json",
    ]);
    (bank, vessel)
}

/// `integrate` on the vessel run with the bank's 25 °C model, writing `out`, with `extra`.
fn integrate_args<'a>(
    vessel: &'a Path,
    bank: &'a Path,
    out: &'a Path,
    extra: &[&'a str],
) -> Vec<String> {
    let (imu, gnss) = (vessel.join("imu.csv"), vessel.join("gnss.csv"));
    let mut args: Vec<String> = [
        "integrate",
        "--imu",
        arg(&imu),
        "--gnss",
        arg(&gnss),
        "--bank",
        arg(bank),
        "--model-temperature-c",
        "25",
        "--lever-arm-m",
        "0.3,0,-2.5",
        "--out",
        arg(out),
        "--json",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

/// (t_s, lat_deg, lon_deg) rows of a trajectory CSV.
fn positions(path: &Path) -> Vec<(f64, f64, f64)> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .map(|line| {
            let v: Vec<f64> = line
                .split(',')
                .take(3)
                .map(|x| x.parse().unwrap())
                .collect();
            (v[0], v[1], v[2])
        })
        .collect()
}

// The solution follows the simulated truth: with 0.5 m GNSS every second, every epoch after
// 30 s of convergence is within 2 m horizontally (four GNSS sigmas); during a 30 s outage the
// drift stays below 60 m (a consumer MEMS IMU with a well-estimated bias drifts tens of metres
// in 30 s; an unaided run with the 1 °/s turn-on bias would be kilometres off). The JSON follows
// the contract and the state file sits beside the solution.
#[test]
fn integrate_follows_the_truth_and_reports_innovations() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let out = dir.path().join("solution.csv");
    let json = json_of(&integrate_args(
        &vessel,
        &bank,
        &out,
        &["--outages", "150+30"],
    ));
    assert_eq!(json["filter"], "ekf");
    assert_eq!(json["initial"], "dual_antenna_heading");
    assert!((json["model"]["temperature_c"].as_f64().unwrap() - 25.0).abs() < 1e-9);
    assert_eq!(json["model"]["gauss_markov_source"], "irregular_ml");
    assert_eq!(json["outages"][0]["start_s"], 150.0);
    let innovations = json["innovations"].as_array().unwrap();
    assert_eq!(innovations[0]["kind"], "position");
    assert!(innovations[0]["rms_innovation_ned_m"].is_array());
    assert!(
        innovations
            .iter()
            .all(|i| i["rejected"].as_u64().unwrap() <= 2)
    );
    assert!(json["final"]["sd_position_ned_m"][0].as_f64().unwrap() < 1.0);
    let states = dir.path().join("solution.states.csv");
    assert_eq!(json["files"]["states"].as_str().unwrap(), arg(&states));
    let header = std::fs::read_to_string(&states).unwrap();
    assert!(header.starts_with("t_s,sd_n_m,sd_e_m,sd_d_m,"));

    let truth = positions(&vessel.join("reference.csv"));
    let mut worst_aided: f64 = 0.0;
    let mut worst_outage: f64 = 0.0;
    for (t, lat, lon) in positions(&out) {
        // Truth linearly interpolated to the epoch (solution epochs at GNSS times fall
        // between the jittered IMU samples; 5 ms at 6 m/s leaves sub-mm interpolation error).
        let k = truth.partition_point(|p| p.0 < t).clamp(1, truth.len() - 1);
        let (a, b) = (truth[k - 1], truth[k]);
        let w = ((t - a.0) / (b.0 - a.0)).clamp(0.0, 1.0);
        let (tlat, tlon) = (a.1 + w * (b.1 - a.1), a.2 + w * (b.2 - a.2));
        let north = (lat - tlat).to_radians() * 6_367_000.0;
        let east = (lon - tlon).to_radians() * 6_388_000.0 * tlat.to_radians().cos();
        let error = north.hypot(east);
        if (150.0..180.0).contains(&t) {
            worst_outage = worst_outage.max(error);
        } else if t > 30.0 {
            worst_aided = worst_aided.max(error);
        }
    }
    assert!(worst_aided < 2.0, "aided error {worst_aided} m");
    assert!(
        worst_outage < 60.0 && worst_outage > worst_aided,
        "outage error {worst_outage} m"
    );
}

// The UKF on the same data, started from the reference trajectory, agrees with the EKF's
// end state to well under the GNSS noise.
#[test]
fn ukf_from_the_reference_agrees_with_the_ekf() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let run = |filter: &str| {
        let out = dir.path().join(format!("{filter}.csv"));
        let reference = vessel.join("reference.csv");
        let extra = ["--initial-from", arg(&reference), "--filter", filter];
        json_of(&integrate_args(&vessel, &bank, &out, &extra));
        *positions(&out).last().unwrap()
    };
    let (ekf, ukf) = (run("ekf"), run("ukf"));
    let north = (ekf.1 - ukf.1).to_radians() * 6_367_000.0;
    let east = (ekf.2 - ukf.2).to_radians() * 6_388_000.0 * ekf.1.to_radians().cos();
    assert!(north.hypot(east) < 0.1, "EKF-UKF {north} m N, {east} m E");
}

// Bad input: clear messages, the right exit code, and no output file left behind.
#[test]
fn integrate_refuses_bad_input_without_partial_output() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let out = dir.path().join("bad.csv");
    let imu = vessel.join("imu.csv");
    let gnss = vessel.join("gnss.csv");
    let fails = |extra: &[&str], code: i32, needle: &str| {
        let args = integrate_args(&vessel, &bank, &out, extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (status, _, stderr) = outcome(&thermonav(&args));
        assert_eq!(status, code, "{extra:?}: {stderr}");
        assert!(stderr.contains(needle), "{extra:?}: {stderr}");
        assert!(!out.exists() && !dir.path().join("bad.states.csv").exists());
    };
    fails(&["--outages", "1000+30"], 2, "not inside the data");
    fails(&["--outages", "100+30,110+30"], 2, "overlap");
    fails(&["--outages", "100-30"], 2, "START+DURATION");
    fails(&["--baseline", "0,0,1"], 2, "horizontal");
    fails(&["--lever-arm-m", "1,2"], 2, "three finite numbers");
    fails(&["--covariance-rate-hz", "0"], 2, "positive");
    fails(
        &["--operating-temperature-c", "20"],
        2,
        "cannot be used with",
    );
    let one_fix = dir.path().join("one.csv");
    let text = std::fs::read_to_string(&gnss).unwrap();
    std::fs::write(
        &one_fix,
        text.lines().take(2).collect::<Vec<_>>().join("\n") + "\n",
    )
    .unwrap();
    let (status, _, stderr) = outcome(&thermonav(&[
        "integrate",
        "--imu",
        arg(&imu),
        "--gnss",
        arg(&one_fix),
        "--bank",
        arg(&bank),
        "--model-temperature-c",
        "25",
        "--out",
        arg(&out),
    ]));
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("one.csv") && stderr.contains("at least two GNSS fixes"),
        "{stderr}"
    );
    assert!(!out.exists());
}
