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
pub(crate) fn inputs(dir: &Path) -> (PathBuf, PathBuf) {
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
pub(crate) fn integrate_args<'a>(
    vessel: &'a Path,
    bank: &'a Path,
    out: &'a Path,
    extra: &[&'a str],
) -> Vec<String> {
    let (imu, gnss) = (vessel.join("imu.csv"), vessel.join("gnss.csv"));
    let args = [
        "integrate",
        "--imu",
        arg(&imu),
        "--gnss",
        arg(&gnss),
        "--bank",
        arg(bank),
        "--model-temperature-c",
        "25",
        "--out",
        arg(out),
    ];
    owned(&args, extra)
}

/// `base`, the vessel's lever arm, `--json` and `extra`, as owned strings.
fn owned(base: &[&str], extra: &[&str]) -> Vec<String> {
    base.iter()
        .chain(&["--lever-arm-m", "0.3,0,-2.5", "--json"])
        .chain(extra)
        .map(|s| s.to_string())
        .collect()
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

// `--model gmwm` hands the filter the bank's GMWM mapping: each channel's bias state is the
// bank's `gauss_markov.gmwm` and its white noise the composite's mapped density (read back
// from the bank file here), and the aided solution still follows the truth.
#[test]
fn integrate_with_the_gmwm_model_uses_the_banks_mapping() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let out = dir.path().join("gmwm.csv");
    let json = json_of(&integrate_args(&vessel, &bank, &out, &["--model", "gmwm"]));
    assert_eq!(json["model"]["gauss_markov_source"], "gmwm");
    let bank_json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&bank).unwrap()).unwrap();
    let distance = |e: &&serde_json::Value| (e["temperature_c"].as_f64().unwrap() - 25.0).abs();
    let entry = bank_json["entries"]
        .as_array()
        .unwrap()
        .iter()
        .min_by(|a, b| distance(a).total_cmp(&distance(b)))
        .unwrap();
    for used in json["model"]["channels"].as_array().unwrap() {
        let channel = &entry["channels"][used["channel"].as_str().unwrap()];
        let bias = &channel["gauss_markov"]["gmwm"];
        assert_eq!(used["bias_correlation_time_s"], bias["correlation_time_s"]);
        assert_eq!(used["bias_sigma"], bias["sigma"]);
        assert_eq!(
            used["white_noise_density"],
            channel["gmwm"]["white_noise_density"]
        );
    }
    assert!(json["final"]["sd_position_ned_m"][0].as_f64().unwrap() < 1.0);
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
        stderr.contains("one.csv")
            && stderr.contains("two GNSS fixes at or after the first IMU sample")
            && stderr.contains("the GNSS file has 1, 1 of them from then on"),
        "{stderr}"
    );
    assert!(!out.exists());
    // Every fix before the IMU record (another time scale): the message counts them apart.
    let early = dir.path().join("early.csv");
    let mut lines = text.lines();
    let mut shifted = format!("{}\n", lines.next().unwrap());
    let mut count = 0;
    for line in lines {
        let (t, rest) = line.split_once(',').unwrap();
        shifted.push_str(&format!("{},{rest}\n", t.parse::<f64>().unwrap() - 1e5));
        count += 1;
    }
    std::fs::write(&early, shifted).unwrap();
    let (status, _, stderr) = outcome(&thermonav(&[
        "integrate",
        "--imu",
        arg(&imu),
        "--gnss",
        arg(&early),
        "--bank",
        arg(&bank),
        "--model-temperature-c",
        "25",
        "--out",
        arg(&out),
    ]));
    assert_eq!(status, 1, "{stderr}");
    let needle = format!("the GNSS file has {count}, 0 of them from then on");
    assert!(
        stderr.contains(&needle) && stderr.contains("share one time scale"),
        "{stderr}"
    );
    assert!(!out.exists());
}

/// `evaluate` on the vessel run with two 30 s outages and the EKF.
fn evaluate_args<'a>(
    vessel: &'a Path,
    bank: &'a Path,
    out: &'a Path,
    extra: &[&'a str],
) -> Vec<String> {
    let files = ["imu.csv", "gnss.csv", "reference.csv"].map(|f| vessel.join(f));
    let args = [
        "evaluate",
        "--imu",
        arg(&files[0]),
        "--gnss",
        arg(&files[1]),
        "--reference",
        arg(&files[2]),
        "--bank",
        arg(bank),
        "--filter",
        "ekf",
        "--out",
        arg(out),
    ];
    owned(&args, extra)
}

// The tournament's JSON follows the contract, and its per-outage RMS equals the RMS of the
// per-epoch errors it wrote to CSV (recomputed here from the file).
#[test]
fn evaluate_ranks_the_models_and_writes_the_errors() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let out = dir.path().join("evaluation");
    let extra = [
        "--outages",
        "60+30,150+30",
        "--monte-carlo",
        "2",
        "--operating-temperature-c",
        "30",
    ];
    let json = json_of(&evaluate_args(&vessel, &bank, &out, &extra));
    // 30 °C lies above the bank (10 and 25 °C): the interpolated model is the 25 °C one, held.
    assert_eq!(json["operating_temperature_c"], 30.0);
    let models = json["models"].as_array().unwrap();
    let labels: Vec<&str> = models
        .iter()
        .map(|m| m["label"].as_str().unwrap())
        .collect();
    for expected in ["interpolated 30.0 °C", "pooled", "data sheet"] {
        assert!(labels.contains(&expected), "{labels:?}");
    }
    let best = json["best"]["rms_north_m"].as_str().unwrap();
    assert!(labels.contains(&best));
    assert_eq!(json["significance"]["replicates"], 2);
    let model = models.iter().find(|m| m["label"] == "pooled").unwrap();
    assert_eq!(model["filter"], "ekf");
    assert_eq!(model["per_outage"].as_array().unwrap().len(), 2);
    // Stored relative to evaluation.json (issue 16), not to the folder evaluate ran in.
    let csv = std::fs::read_to_string(out.join(model["errors_csv"].as_str().unwrap())).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "outage,t_s,since_outage_start_s,north_m,east_m,horizontal_m,heading_deg"
    );
    let north: Vec<f64> = lines
        .filter(|l| l.starts_with("1,"))
        .map(|l| l.split(',').nth(3).unwrap().parse().unwrap())
        .collect();
    // 30 s at the 10 Hz output rate: 300 epochs (±1 for an epoch on the boundary).
    assert!((299..=301).contains(&north.len()), "{}", north.len());
    let rms = (north.iter().map(|x| x * x).sum::<f64>() / north.len() as f64).sqrt();
    let reported = model["per_outage"][0]["rms_north_m"].as_f64().unwrap();
    assert!(
        (rms - reported).abs() < 1e-9 * reported.max(1.0),
        "{rms} vs {reported}"
    );
    assert!(json["models"][0]["ci95"]["rms_north_m"]["low"].is_number());
}

// Bad input: outages outside the data or overlapping, a reference that does not cover an
// outage, a bank without the needed channels. Each is a clear error and leaves no report.
#[test]
fn evaluate_refuses_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let out = dir.path().join("bad");
    let fails = |bank: &Path, extra: &[&str], code: i32, needle: &str| {
        let args = evaluate_args(&vessel, bank, &out, extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (status, _, stderr) = outcome(&thermonav(&args));
        assert_eq!(status, code, "{extra:?}: {stderr}");
        assert!(stderr.contains(needle), "{extra:?}: {stderr}");
        assert!(!out.join("evaluation.json").exists());
    };
    fails(&bank, &["--outages", "5000+30"], 2, "not inside the data");
    fails(&bank, &["--outages", "60+30,80+30"], 2, "overlap");
    fails(&bank, &["--outages", "spread:50,100"], 2, "do not fit");
    fails(&bank, &["--monte-carlo", "0"], 2, "at least 1");
    let short = dir.path().join("short_reference.csv");
    let text = std::fs::read_to_string(vessel.join("reference.csv")).unwrap();
    let kept: Vec<&str> = text.lines().take(1 + 200 * 100).collect();
    std::fs::write(&short, kept.join("\n") + "\n").unwrap();
    let args = evaluate_args(&vessel, &bank, &out, &["--outages", "150+30"]);
    let mut args: Vec<&str> = args.iter().map(String::as_str).collect();
    let position = args.iter().position(|a| *a == "--reference").unwrap();
    args[position + 1] = arg(&short);
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("does not cover the outage 150.000-180.000 s"),
        "{stderr}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&bank).unwrap()).unwrap();
    let mut stripped = json.clone();
    for entry in stripped["entries"].as_array_mut().unwrap() {
        entry["channels"].as_object_mut().unwrap().remove("az");
    }
    let no_az = dir.path().join("no_az.json");
    std::fs::write(&no_az, serde_json::to_string(&stripped).unwrap()).unwrap();
    fails(
        &no_az,
        &["--outages", "150+30"],
        1,
        "no model for channel az",
    );
}

// `--datasheet PROFILE` replaces only the data-sheet candidate (by the profile's model at its
// reference temperature): every other model's figures are the same as without it, bit for
// bit, and the data-sheet figures change (the built-in profile's Tc of minutes against the
// data sheet's assumed hour).
#[test]
fn evaluate_takes_the_datasheet_candidate_from_a_profile() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let profile = dir.path().join("sheet.toml");
    let (status, _, stderr) = outcome(&thermonav(&["simulate", "profile", "--out", arg(&profile)]));
    assert_eq!(status, 0, "{stderr}");
    let outages = ["--outages", "60+30,150+30"];
    let plain = json_of(&evaluate_args(
        &vessel,
        &bank,
        &dir.path().join("a"),
        &outages,
    ));
    let with = [outages[0], outages[1], "--datasheet", arg(&profile)];
    let sheet = json_of(&evaluate_args(&vessel, &bank, &dir.path().join("b"), &with));
    let figures = |json: &serde_json::Value, label: &str| {
        let models = json["models"].as_array().unwrap();
        let m = models.iter().find(|m| m["label"] == label).unwrap();
        m["rms_horizontal_m"].as_f64().unwrap()
    };
    let labels: Vec<&str> = plain["models"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|m| m["label"].as_str())
        .filter(|l| *l != "data sheet")
        .collect();
    assert!(labels.len() >= 2, "{labels:?}");
    for label in labels {
        assert_eq!(figures(&plain, label), figures(&sheet, label), "{label}");
    }
    assert_ne!(figures(&plain, "data sheet"), figures(&sheet, "data sheet"));
}

/// `integrate` on the vessel run with `noise` (`--bank FILE` or `--profile FILE`), no
/// temperature given (so the model follows temp_c), and `extra`.
fn scheduled_args(
    imu: &Path,
    vessel: &Path,
    noise: [&str; 2],
    out: &Path,
    extra: &[&str],
) -> Vec<String> {
    let gnss = vessel.join("gnss.csv");
    let args = [
        "integrate",
        "--imu",
        arg(imu),
        "--gnss",
        arg(&gnss),
        noise[0],
        noise[1],
    ];
    owned(&[&args[..], &["--out", arg(out)]].concat(), extra)
}

// The vessel run is at a constant 17 °C: by default the summary reports a schedule over
// [17, 17] °C, and its solution is the fixed model's to the bit (the one-point grid holds the
// profile's model at 17 °C); --no-schedule reports the fixed model at 17 °C. A profile has no
// thermal calibration, so compensation is "not_available", and "off" with --no-compensation.
// (The test bank's 10 °C entry has no gx Gauss-Markov model, so it cannot serve 17 °C.)
#[test]
fn integrate_reports_its_schedule_and_compensation() {
    let dir = tempfile::tempdir().unwrap();
    let (_, vessel) = inputs(dir.path());
    let imu = vessel.join("imu.csv");
    let profile = dir.path().join("sensor.toml");
    assert_eq!(
        outcome(&thermonav(&["simulate", "profile", "--out", arg(&profile)])).0,
        0
    );
    let noise = ["--profile", arg(&profile)];
    let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
    let scheduled = json_of(&scheduled_args(&imu, &vessel, noise, &a, &[]));
    assert_eq!(scheduled["schedule"]["kind"], "scheduled");
    assert_eq!(
        scheduled["schedule"]["temperature_range_c"],
        serde_json::json!([17.0, 17.0])
    );
    assert_eq!(scheduled["schedule"]["rule"], "profile_table");
    assert_eq!(scheduled["compensation"]["status"], "not_available");
    let extra = ["--no-schedule", "--no-compensation"];
    let fixed = json_of(&scheduled_args(&imu, &vessel, noise, &b, &extra));
    assert_eq!(fixed["schedule"]["kind"], "fixed");
    assert_eq!(fixed["schedule"]["temperature_c"], 17.0);
    assert_eq!(fixed["compensation"]["status"], "off");
    assert_eq!(positions(&a), positions(&b));
}

// Without a temp_c column the run keeps one model (the profile's reference temperature),
// says so once on stderr, and reports a fixed schedule.
#[test]
fn integrate_without_temperatures_notes_it_and_runs() {
    let dir = tempfile::tempdir().unwrap();
    let vessel = dir.path().join("vessel");
    json_of(&[
        "simulate",
        "vessel",
        "--out",
        arg(&vessel),
        "--duration-s",
        "60",
        "--json",
    ]);
    let profile = dir.path().join("sensor.toml");
    assert_eq!(
        outcome(&thermonav(&["simulate", "profile", "--out", arg(&profile)])).0,
        0
    );
    let text = std::fs::read_to_string(vessel.join("imu.csv")).unwrap();
    let cut: String = text
        .lines()
        .map(|l| l.rsplit_once(',').unwrap().0.to_string() + "\n")
        .collect();
    assert!(cut.starts_with("t_s,") && !cut.contains("temp_c"));
    let imu = crate::write_file(dir.path(), "cold.csv", &cut);
    let args = scheduled_args(
        &imu,
        &vessel,
        ["--profile", arg(&profile)],
        &dir.path().join("s.csv"),
        &[],
    );
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    assert_eq!(stderr.matches("no temp_c column").count(), 1, "{stderr}");
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(json["schedule"]["kind"], "fixed");
}

// A bank tournament on a record with temp_c tries a scheduled candidate (it competes, or is
// excluded with its reason when an entry it needs lacks a model), and not with --no-schedule;
// a profile tournament (no bank) has the profile at fixed temperatures and scheduled.
#[test]
fn evaluate_adds_scheduled_candidates_and_takes_a_profile() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let outages = ["--outages", "60+30,150+30", "--no-heading"];
    let tags = |json: &serde_json::Value, list: &str, key: &str| -> Vec<String> {
        let rows = json[list].as_array().unwrap();
        rows.iter()
            .map(|m| m[key].as_str().unwrap().to_string())
            .collect()
    };
    let plain = json_of(&evaluate_args(
        &vessel,
        &bank,
        &dir.path().join("a"),
        &outages,
    ));
    let tried = |json: &serde_json::Value| -> Vec<String> {
        let mut labels = tags(json, "excluded", "label");
        labels.extend(tags(json, "models", "label"));
        labels
    };
    let labels = tried(&plain);
    assert!(
        labels.contains(&"scheduled linear".to_string()),
        "{labels:?}"
    );
    let fixed_only = [&outages[..], &["--no-schedule"]].concat();
    let fixed = json_of(&evaluate_args(
        &vessel,
        &bank,
        &dir.path().join("b"),
        &fixed_only,
    ));
    assert!(!tried(&fixed).iter().any(|l| l.contains("scheduled")));
    let profile = dir.path().join("sensor.toml");
    assert_eq!(
        outcome(&thermonav(&["simulate", "profile", "--out", arg(&profile)])).0,
        0
    );
    let mut args = evaluate_args(&vessel, &bank, &dir.path().join("c"), &outages);
    let at = args.iter().position(|a| a == "--bank").unwrap();
    args.splice(
        at..at + 2,
        ["--profile".to_string(), arg(&profile).to_string()],
    );
    let kinds = tags(&json_of(&args), "models", "kind");
    for kind in ["profile", "scheduled", "datasheet"] {
        assert!(kinds.contains(&kind.to_string()), "{kind} in {kinds:?}");
    }
}

// When no model's filter survives the data (here an x accelerometer reading 600 m/s² too
// much, which drives every solution past 3000 m/s within seconds), evaluate still writes and
// prints its report, then exits 1 saying so, instead of 0.
#[test]
fn evaluate_exits_non_zero_when_every_model_fails() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let broken = dir.path().join("broken");
    std::fs::create_dir_all(&broken).unwrap();
    for f in ["gnss.csv", "reference.csv"] {
        std::fs::copy(vessel.join(f), broken.join(f)).unwrap();
    }
    let text = std::fs::read_to_string(vessel.join("imu.csv")).unwrap();
    let mut lines = text.lines();
    let mut out = format!("{}\n", lines.next().unwrap());
    for line in lines {
        let mut fields: Vec<String> = line.split(',').map(String::from).collect();
        fields[4] = (fields[4].parse::<f64>().unwrap() + 600.0).to_string();
        out.push_str(&fields.join(","));
        out.push('\n');
    }
    std::fs::write(broken.join("imu.csv"), out).unwrap();
    let extra = ["--no-heading", "--outages", "60+30,150+30"];
    let args = evaluate_args(&broken, &bank, &dir.path().join("ev"), &extra);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 1, "{stdout}{stderr}");
    assert!(stderr.contains("every model's filter failed"), "{stderr}");
    assert!(dir.path().join("ev/evaluation.json").exists());
}

/// (t_s, north_m, east_m) of a trajectory CSV, north and east from latitude and longitude on
/// a sphere of the Earth's mean radius (enough for differences of metres).
fn planar(path: &Path) -> Vec<(f64, f64, f64)> {
    const RADIUS_M: f64 = 6_371_000.0;
    positions(path)
        .into_iter()
        .map(|(t, lat, lon)| {
            let north = lat.to_radians() * RADIUS_M;
            (
                t,
                north,
                lon.to_radians() * RADIUS_M * 44.65_f64.to_radians().cos(),
            )
        })
        .collect()
}

/// The largest horizontal distance, m, between `solution` and `reference` at the solution's
/// epochs inside `[from_s, to_s)` (the reference point at the same time, to 1 ms).
fn max_error_m(solution: &Path, reference: &Path, (from_s, to_s): (f64, f64)) -> f64 {
    let truth = planar(reference);
    planar(solution)
        .into_iter()
        .filter(|(t, _, _)| (from_s..to_s).contains(t))
        .filter_map(|(t, n, e)| {
            let k = truth.partition_point(|p| p.0 < t - 1e-3);
            let (tt, tn, te) = *truth.get(k)?;
            ((tt - t).abs() < 1e-3).then(|| (n - tn).hypot(e - te))
        })
        .fold(0.0, f64::max)
}

// Issue 18: `integrate --smooth` writes the RTS-smoothed trajectory and its states beside the
// forward solution; inside a 60 s outage its largest error against the simulated truth is
// below half the forward filter's (both ends of the outage tie it to GNSS). The UKF is
// refused (exit 2) before anything is read.
#[test]
fn integrate_smooth_writes_a_smoothed_solution_closer_to_the_truth() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let out = dir.path().join("sol.csv");
    let args = integrate_args(&vessel, &bank, &out, &["--outages", "120+60", "--smooth"]);
    let summary = json_of(&args);
    let smoothed = dir.path().join("sol.smoothed.csv");
    assert_eq!(summary["files"]["smoothed"][0], arg(&smoothed));
    assert!(dir.path().join("sol.smoothed.states.csv").exists());
    let reference = vessel.join("reference.csv");
    let forward_m = max_error_m(&out, &reference, (120.0, 180.0));
    let smoothed_m = max_error_m(&smoothed, &reference, (120.0, 180.0));
    assert!(forward_m > 1.0, "the outage drifts: {forward_m} m");
    assert!(
        smoothed_m < 0.5 * forward_m,
        "smoothed {smoothed_m} m, forward {forward_m} m"
    );
    let ukf = dir.path().join("ukf.csv");
    let args = integrate_args(&vessel, &bank, &ukf, &["--smooth", "--filter", "ukf"]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("--smooth: the RTS smoother runs on the EKF"),
        "{stderr}"
    );
    assert!(!ukf.exists());
}

// Issue 16: `plot outage-errors` on an evaluation.json in another folder finds the errors
// CSVs beside the JSON, not relative to the folder it runs in: evaluate runs in `dir` with a
// relative `--out ev` (so the report names `ev/errors/...`), plot runs in `dir/elsewhere`.
#[test]
fn plot_outage_errors_finds_the_errors_beside_the_evaluation() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let extra = ["--no-heading", "--outages", "60+30"];
    let args = evaluate_args(&vessel, &bank, Path::new("ev"), &extra);
    let run_in = |cwd: &Path, args: &[String]| {
        let output = std::process::Command::new(env!("CARGO_BIN_EXE_thermonav"))
            .args(args)
            .current_dir(cwd)
            .output()
            .unwrap();
        outcome(&output)
    };
    let (status, stdout, stderr) = run_in(dir.path(), &args);
    assert_eq!(status, 0, "{stdout}{stderr}");
    let elsewhere = dir.path().join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    let report = dir.path().join("ev/evaluation.json");
    let plot = ["plot", "outage-errors", arg(&report), "--out", "errors.svg"].map(String::from);
    let (status, stdout, stderr) = run_in(&elsewhere, &plot);
    assert_eq!(status, 0, "{stdout}{stderr}");
    let svg = std::fs::read_to_string(elsewhere.join("errors.svg")).unwrap();
    assert!(svg.contains("<polyline") || svg.contains("<path"), "{svg}");
}

// Issue 16: `integrate --help` names every outage form `integrate` accepts, spread: too.
#[test]
fn integrate_help_names_the_spread_outages() {
    let (status, stdout, _) = outcome(&thermonav(&["integrate", "--help"]));
    assert_eq!(status, 0);
    for form in [
        "START+DURATION",
        "every:FIRST,DURATION,PERIOD,COUNT",
        "spread:COUNT,DURATION",
    ] {
        assert!(stdout.contains(form), "{form} in {stdout}");
    }
}

/// `text` negated as a number's text (`-0.5` ↔ `0.5`): exact.
fn negated(text: &str) -> String {
    match text.strip_prefix('-') {
        Some(rest) => rest.to_string(),
        None => format!("-{text}"),
    }
}

/// The vessel's IMU written in the axes of an IMU mounted as `-y,x,z` (its x is body y, its y
/// body −x): `integrate --imu-rotation -y,x,z` turns it back and gives, to the bit, the
/// solution of the body-axes file, and the JSON records the rotation.
#[test]
fn integrate_turns_a_rotated_imu_back_into_body_axes() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let text = std::fs::read_to_string(vessel.join("imu.csv")).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    assert!(header.starts_with("t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2"));
    let mut rotated = format!("{header}\n");
    for line in lines {
        let mut f: Vec<String> = line.split(',').map(str::to_string).collect();
        for x in [1, 4] {
            let (body_x, body_y) = (f[x].clone(), f[x + 1].clone());
            f[x] = body_y;
            f[x + 1] = negated(&body_x);
        }
        rotated.push_str(&(f.join(",") + "\n"));
    }
    let turned = crate::write_file(dir.path(), "turned.csv", &rotated);
    let plain_out = dir.path().join("plain.csv");
    json_of(&integrate_args(&vessel, &bank, &plain_out, &[]));
    let turned_out = dir.path().join("turned_solution.csv");
    let mut args = integrate_args(&vessel, &bank, &turned_out, &["--imu-rotation", "-y,x,z"]);
    args[2] = arg(&turned).to_string();
    let json = json_of(&args);
    assert_eq!(json["imu_rotation"], "-y,x,z");
    assert_eq!(
        std::fs::read(&plain_out).unwrap(),
        std::fs::read(&turned_out).unwrap()
    );
    // evaluate: the same models and errors, and the rotation in evaluation.json.
    let evaluate = |out: &str, extra: &[&str], imu: Option<&Path>| {
        let out = dir.path().join(out);
        let mut args = evaluate_args(
            &vessel,
            &bank,
            &out,
            &[&["--outages", "60+30"], extra].concat(),
        );
        if let Some(imu) = imu {
            args[2] = arg(imu).to_string();
        }
        let mut json = json_of(&args);
        for model in json["models"].as_array_mut().unwrap() {
            model.as_object_mut().unwrap().remove("errors_csv");
        }
        json
    };
    let plain = evaluate("plain-evaluation", &[], None);
    let turned = evaluate(
        "turned-evaluation",
        &["--imu-rotation", "-y,x,z"],
        Some(&turned),
    );
    assert_eq!(turned["imu_rotation"], "-y,x,z");
    assert_eq!(plain["models"], turned["models"]);
}

// Issue 18: `integrate --bias-hypotheses N` runs the Gaussian sum over the z-gyro bias (its
// consistency is tested in the library's position_only tests) and says so in --json; a count
// that cannot split the prior, or a sum with --smooth, is refused (exit 2) naming the option,
// before anything is written.
#[test]
fn integrate_runs_a_gaussian_sum_over_the_gyro_bias_when_asked() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let out = dir.path().join("sum.csv");
    let args = integrate_args(
        &vessel,
        &bank,
        &out,
        &["--no-heading", "--bias-hypotheses", "21"],
    );
    let summary = json_of(&args);
    assert_eq!(summary["bias_hypotheses"]["members"], 21);
    assert!(std::fs::read_to_string(&out).unwrap().lines().count() > 100);
    let single = json_of(&integrate_args(
        &vessel,
        &bank,
        &dir.path().join("one.csv"),
        &["--no-heading"],
    ));
    assert!(single.get("bias_hypotheses").is_none());
    for (extra, expected) in [
        (&["--bias-hypotheses", "4"][..], "--bias-hypotheses 4"),
        (&["--bias-hypotheses", "7"][..], "--bias-hypotheses 7"),
        // Issue 37 row 14: refused before anything is allocated (it used to abort asking for
        // 37 GB).
        (&["--bias-hypotheses", "203"][..], "from 9 to 201"),
        (
            &["--bias-hypotheses", "999999999"][..],
            "--bias-hypotheses 999999999",
        ),
        (&["--bias-hypotheses", "21", "--smooth"][..], "--smooth"),
    ] {
        let refused = dir.path().join("refused.csv");
        let args = integrate_args(&vessel, &bank, &refused, extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (status, _, stderr) = outcome(&thermonav(&args));
        assert_eq!(status, 2, "{extra:?}: {stderr}");
        assert!(stderr.contains(expected), "{extra:?}: {stderr}");
        assert!(!refused.exists(), "{extra:?}");
    }
}

/// A thermal calibration from a sweep alone of the unit of [`inputs`] (serial 1): a chamber
/// program 10 → 30 → 10 °C at 2 °C/min, 10 Hz, through `characterize --sweep`.
fn sweep_bank(dir: &Path) -> PathBuf {
    let program = dir.join("program.csv");
    std::fs::write(&program, "t_s,temp_c\n0,10\n600,30\n900,30\n1500,10\n").unwrap();
    let cycle = dir.join("cycle");
    json_of(&[
        "simulate",
        "chamber",
        "--out",
        arg(&cycle),
        "--temperature-file",
        arg(&program),
        "--rate-hz",
        "10",
        "--json",
    ]);
    let bank = dir.join("sweep.json");
    let record = cycle.join("imu_program.csv");
    json_of(&[
        "characterize",
        "--sweep",
        arg(&record),
        "--out",
        arg(&bank),
        "--json",
    ]);
    bank
}

// Issue 35: `--thermal-from` joins a sweep bank's thermal calibration to the noise model of a
// bank or a profile. With a bank, the run is the run of that bank with its "thermal" replaced
// by the sweep bank's (written here by hand), position for position; with a profile, the
// record is compensated (the profile alone has nothing to compensate with). A calibration
// whose channels differ from the noise model's is refused naming both files, and `evaluate`
// refuses it with a profile.
#[test]
fn integrate_takes_its_thermal_calibration_from_a_sweep_bank() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let sweep = sweep_bank(dir.path());
    let read = |p: &Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
    };
    let mut merged = read(&bank);
    merged["thermal"] = read(&sweep)["thermal"].clone();
    let merged_bank = dir.path().join("merged.json");
    std::fs::write(&merged_bank, merged.to_string()).unwrap();
    let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
    let joined = json_of(&integrate_args(
        &vessel,
        &bank,
        &a,
        &["--thermal-from", arg(&sweep)],
    ));
    assert_eq!(joined["compensation"]["status"], "applied", "{joined}");
    assert_eq!(joined["thermal_from"], arg(&sweep));
    json_of(&integrate_args(&vessel, &merged_bank, &b, &[]));
    assert_eq!(positions(&a), positions(&b));
    let plain = dir.path().join("plain.csv");
    json_of(&integrate_args(
        &vessel,
        &bank,
        &plain,
        &["--no-compensation"],
    ));
    assert_ne!(positions(&a), positions(&plain));

    let profile = dir.path().join("sensor.toml");
    assert_eq!(
        outcome(&thermonav(&["simulate", "profile", "--out", arg(&profile)])).0,
        0
    );
    let imu = vessel.join("imu.csv");
    let noise = ["--profile", arg(&profile)];
    let c = dir.path().join("c.csv");
    let extra = ["--thermal-from", arg(&sweep)];
    let with_profile = json_of(&scheduled_args(&imu, &vessel, noise, &c, &extra));
    assert_eq!(with_profile["compensation"]["status"], "applied");

    let mut partial = read(&sweep);
    partial["thermal"]["channels"]
        .as_object_mut()
        .unwrap()
        .remove("az");
    let partial_bank = dir.path().join("partial.json");
    std::fs::write(&partial_bank, partial.to_string()).unwrap();
    let mut args = integrate_args(&vessel, &bank, &c, &["--thermal-from", arg(&partial_bank)]);
    args.retain(|a| a != "--json");
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (code, _, err) = outcome(&thermonav(&args));
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("partial.json")
            && err.contains("bank.json")
            && err.contains("gx,gy,gz,ax,ay,az"),
        "{err}"
    );
    let (code, _, err) = outcome(&thermonav(&[
        "evaluate",
        "--imu",
        arg(&imu),
        "--gnss",
        arg(&vessel.join("gnss.csv")),
        "--reference",
        arg(&vessel.join("reference.csv")),
        "--profile",
        arg(&profile),
        "--thermal-from",
        arg(&sweep),
        "--out",
        arg(&dir.path().join("tournament")),
    ]));
    assert!(code == 2 && err.contains("--thermal-from"), "{err}");
}
