//! Successful runs: what each command prints and writes, against closed forms.

use crate::{IMU_HEADER, arg, imu_csv, outcome, thermonav, write_file};

fn json_of(args: &[&str]) -> serde_json::Value {
    let (status, stdout, stderr) = outcome(&thermonav(args));
    assert_eq!(status, 0, "stderr: {stderr}");
    serde_json::from_str(&stdout).expect("stdout is one JSON document")
}

#[test]
fn inspect_reports_rate_gaps_duplicates_and_reversals() {
    let dir = tempfile::tempdir().unwrap();
    // 200 Hz; a gap of 3 intervals after row 10, a duplicate and a reversal at the end.
    let mut text = format!("{IMU_HEADER},temp_c\n");
    let times: Vec<f64> = (0..10)
        .map(|k| k as f64 * 0.005)
        .chain((12..20).map(|k| k as f64 * 0.005))
        .chain([0.095, 0.09])
        .collect();
    for (k, t) in times.iter().enumerate() {
        text.push_str(&format!(
            "{t:.9},1,2,3,4,5,{},{}\n",
            -9.8 + k as f64 * 0.01,
            20.0 + k as f64
        ));
    }
    let path = write_file(dir.path(), "imu.csv", &text);
    let json = json_of(&["inspect", arg(&path), "--json"]);
    assert_eq!(json["rows"], 20);
    assert_eq!(json["nominal_rate_hz"], 200.0);
    assert_eq!(json["gap_count"], 1);
    // The gap runs from row 10 (file line 11) to row 11 (line 12).
    assert_eq!(json["gaps"][0]["start_line"], 11);
    assert!((json["gaps"][0]["length_s"].as_f64().unwrap() - 0.015).abs() < 1e-12);
    assert_eq!(json["duplicate_count"], 1);
    assert_eq!(json["non_monotonic_count"], 1);
    assert_eq!(json["non_monotonic"][0]["line"], 21);
    assert_eq!(json["temperature"]["min_c"], 20.0);
    assert_eq!(json["temperature"]["max_c"], 39.0);
    let gx = &json["channels"][0];
    assert_eq!(
        (gx["channel"].as_str(), gx["unit"].as_str()),
        (Some("gx"), Some("rad/s"))
    );
    assert_eq!(gx["mean"], 1.0);
    assert_eq!(gx["std"], 0.0);
}

#[test]
fn inspect_text_output_names_units() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_file(dir.path(), "imu.csv", &imu_csv(50, 100.0, |c, _| c as f64));
    let (status, stdout, _) = outcome(&thermonav(&["inspect", arg(&path)]));
    assert_eq!(status, 0);
    assert!(stdout.contains("100.000000 Hz"), "{stdout}");
    assert!(
        stdout.contains("m/s^2") && stdout.contains("rad/s"),
        "{stdout}"
    );
}

#[test]
fn filter_keeps_a_constant_and_removes_a_tone_far_above_cut_off() {
    let dir = tempfile::tempdir().unwrap();
    // Channel gx: constant 0.25; channel gy: a 40 Hz tone (cut-off 5 Hz, 60 dB design).
    let tone = |t: f64| (2.0 * std::f64::consts::PI * 40.0 * t).sin();
    let text = imu_csv(4000, 200.0, |c, t| match c {
        0 => 0.25,
        1 => tone(t),
        _ => 0.0,
    });
    let input = write_file(dir.path(), "in.csv", &text);
    let out = dir.path().join("out.csv");
    let record = json_of(&[
        "filter",
        arg(&input),
        "--cutoff-hz",
        "5",
        "--out",
        arg(&out),
        "--json",
    ]);
    assert_eq!(record["rows_out"], 4000);
    assert!(dir.path().join("out.csv.json").exists(), "sidecar written");
    let filtered = std::fs::read_to_string(&out).unwrap();
    let rows: Vec<Vec<f64>> = filtered
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    // DC gain of the design is 1 (firwin scaling), and the odd extension of a constant is the
    // same constant, so the constant survives to rounding (1e-12).
    assert!(rows.iter().all(|r| (r[1] - 0.25).abs() < 1e-12));
    // A one-pass Kaiser design guarantees at least ripple_db = 60 dB (amplitude 1e-3) in the
    // stop band; away from the edges (one filter length) the tone must be below that.
    let taps = record["filter"]["num_taps"].as_u64().unwrap() as usize;
    let interior = &rows[taps..rows.len() - taps];
    let peak = interior.iter().map(|r| r[2].abs()).fold(0.0, f64::max);
    assert!(peak < 1e-3, "residual tone {peak}");
    // Timestamps are untouched.
    assert_eq!(rows[1][0], 0.005);
}

#[test]
fn decimation_keeps_every_nth_timestamp() {
    let dir = tempfile::tempdir().unwrap();
    let input = write_file(dir.path(), "in.csv", &imu_csv(2010, 200.0, |_, _| 1.0));
    let out = dir.path().join("out.csv");
    let args = [
        "filter",
        arg(&input),
        "--cutoff-hz",
        "2",
        "--transition-hz",
        "2",
        "--decimate-to-hz",
        "10",
        "--out",
        arg(&out),
        "--json",
    ];
    let record = json_of(&args);
    assert_eq!(record["decimation_factor"], 20);
    assert_eq!(record["output_rate_hz"], 10.0);
    // 2010 samples, 365 taps (Kaiser 60 dB, 2 Hz transition at 200 Hz): every 20th index from
    // the first whose 365-sample window lies inside the record, i.e. 182 <= j <= 2009 - 182:
    // 200, 220, ..., 1820 -> 82 rows from 1.0 s to 9.1 s. (Before the edge fix: every 20th
    // from the first, 0..2000, 101 rows to 10.0 s; the first row was the raw first sample and
    // the last ones read the reflected record.)
    assert_eq!(record["filter"]["num_taps"], 365);
    assert_eq!(record["edge_samples_dropped"], 182);
    assert_eq!(record["rows_out"], 82);
    let times = first_column(&std::fs::read_to_string(&out).unwrap());
    assert_eq!((times[0], times[times.len() - 1]), (1.0, 9.1));
    assert!(times.windows(2).all(|w| (w[1] - w[0] - 0.1).abs() < 1e-9));
}

/// The first column (times) of a CSV with a header.
fn first_column(text: &str) -> Vec<f64> {
    text.lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect()
}

#[test]
fn filter_takes_the_characterize_defaults() {
    // cut-off 0.4 Hz + half the 0.2 Hz transition = 0.5 Hz, the Nyquist frequency of 1 Hz: the
    // stop band starts exactly there, so nothing above it folds back unattenuated (the rule
    // was cut-off + the whole transition, which refused characterize's own defaults).
    // 20 000 samples at 100 Hz, 1815 taps, delay 907: kept 1000, 1100, ..., 19000 (j <= 19092).
    let dir = tempfile::tempdir().unwrap();
    let input = write_file(dir.path(), "in.csv", &imu_csv(20_000, 100.0, |_, _| 1.0));
    let out = dir.path().join("out.csv");
    let mut args = vec![
        "filter",
        arg(&input),
        "--cutoff-hz",
        "0.4",
        "--transition-hz",
        "0.2",
        "--decimate-to-hz",
        "1",
        "--out",
        arg(&out),
        "--json",
    ];
    let record = json_of(&args);
    assert_eq!(
        (
            record["decimation_factor"].as_u64(),
            record["rows_out"].as_u64()
        ),
        (Some(100), Some(181))
    );
    let times = first_column(&std::fs::read_to_string(&out).unwrap());
    assert_eq!((times[0], times[180]), (10.0, 190.0));
    // 0.41 Hz + 0.1 Hz passes 0.5 Hz: refused as usage, before the input is read.
    std::fs::remove_file(&out).unwrap();
    args[3] = "0.41";
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("Nyquist") && stderr.contains("0.51"),
        "{stderr}"
    );
    assert!(!out.exists());
}

#[test]
fn decimation_that_would_alias_is_a_usage_error() {
    let dir = tempfile::tempdir().unwrap();
    let input = write_file(dir.path(), "in.csv", &imu_csv(410, 200.0, |_, _| 1.0));
    let out = dir.path().join("out.csv");
    let args = [
        "filter",
        arg(&input),
        "--cutoff-hz",
        "5",
        "--decimate-to-hz",
        "10",
        "--out",
        arg(&out),
    ];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 2, "{stderr}");
    assert!(!out.exists());
}

#[test]
fn inspect_reads_gnss_and_reference_files_by_their_header() {
    let dir = tempfile::tempdir().unwrap();
    let gnss =
        "t_s,lat_deg,lon_deg,h_m\n1,51.0,-114.0,1100\n2,51.0,-114.0,1102\n4,51.0,-114.0,1104\n";
    let path = write_file(dir.path(), "gnss.csv", gnss);
    let json = json_of(&["inspect", arg(&path), "--json"]);
    assert_eq!(json["content"], "gnss");
    assert_eq!(json["rows"], 3);
    assert_eq!(
        json["gap_count"], 1,
        "the 2 s interval is a gap at a 1 s nominal rate"
    );
    let h = json["channels"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["channel"] == "h")
        .unwrap();
    assert_eq!(
        (h["unit"].as_str(), h["mean"].as_f64()),
        (Some("m"), Some(1102.0))
    );
    let reference = "t_s,lat_deg,lon_deg,h_m,vn_m_s,ve_m_s,vd_m_s,roll_deg,pitch_deg,yaw_deg\n0,51,-114,1100,1,0,0,0,0,90\n0.5,51,-114,1100,1,0,0,0,0,90\n";
    let path = write_file(dir.path(), "ref.csv", reference);
    let json = json_of(&["inspect", arg(&path), "--json"]);
    assert_eq!(json["content"], "reference_trajectory");
    assert_eq!(json["nominal_rate_hz"], 2.0);
}

// A comma-separated list that starts with a negative number (`-20,20`) is a value, not an
// unknown flag: the chamber writes one file per set point, and characterize takes the same list.
#[test]
fn negative_temperature_lists_are_values() {
    let dir = tempfile::tempdir().unwrap();
    let chamber = dir.path().join("chamber");
    let (status, _, stderr) = outcome(&thermonav(&[
        "simulate",
        "chamber",
        "--temperatures-c",
        "-20,20",
        "--duration-s",
        "60",
        "--rate-hz",
        "100",
        "--quiet",
        "--out",
        arg(&chamber),
    ]));
    assert_eq!(status, 0, "stderr: {stderr}");
    let cold = chamber.join("imu_-20C.csv");
    let warm = chamber.join("imu_20C.csv");
    assert!(cold.exists() && warm.exists());
    let bank = dir.path().join("bank.json");
    let json = json_of(&[
        "characterize",
        arg(&cold),
        arg(&warm),
        "--temperature-c",
        "-20,20",
        "--quiet",
        "--out",
        arg(&bank),
        "--json",
    ]);
    assert_eq!(json["temperatures_c"], serde_json::json!([-20.0, 20.0]));
}
