//! Bad input: a clear message naming file, line and expectation; exit 1 for data, 2 for usage;
//! no partial output file; never a panic.

use crate::{IMU_HEADER, arg, files_in, imu_csv, outcome, thermonav, write_file};
use std::path::Path;

/// Runs `filter` on `input` into a fresh output path and checks the failure's shape.
fn filter_fails(dir: &Path, input: &Path, extra: &[&str], code: i32) -> String {
    let out = dir.join("out.csv");
    let mut args = vec!["filter", arg(input), "--cutoff-hz", "5", "--out", arg(&out)];
    args.extend_from_slice(extra);
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, code, "stderr: {stderr}");
    assert!(stdout.is_empty(), "nothing on stdout on failure: {stdout}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!out.exists(), "no output file after a failure");
    assert!(
        !dir.join("out.csv.json").exists(),
        "no sidecar after a failure"
    );
    let leftovers: Vec<_> = files_in(dir)
        .into_iter()
        .filter(|n| n.starts_with("out"))
        .collect();
    assert!(
        leftovers.is_empty(),
        "no temporary file left: {leftovers:?}"
    );
    stderr
}

fn good_rows() -> String {
    imu_csv(400, 200.0, |c, t| (c as f64) + (t * 3.0).sin())
}

#[test]
fn missing_file_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("nope.csv");
    let stderr = filter_fails(dir.path(), &missing, &[], 1);
    assert!(stderr.contains("nope.csv"), "{stderr}");
    let (status, _, stderr) = outcome(&thermonav(&["inspect", arg(&missing)]));
    assert_eq!(status, 1);
    assert!(stderr.contains("nope.csv"), "{stderr}");
}

#[test]
fn empty_file_and_header_only_are_data_errors() {
    let dir = tempfile::tempdir().unwrap();
    let empty = write_file(dir.path(), "empty.csv", "");
    let stderr = filter_fails(dir.path(), &empty, &[], 1);
    assert!(
        stderr.contains("empty.csv") && stderr.contains("empty"),
        "{stderr}"
    );
    let header = write_file(dir.path(), "header.csv", &format!("{IMU_HEADER}\n"));
    let stderr = filter_fails(dir.path(), &header, &[], 1);
    assert!(stderr.contains("header.csv"), "{stderr}");
}

#[test]
fn unknown_and_missing_columns_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let unknown = good_rows().replacen("gy_rad_s", "wobble", 1);
    let path = write_file(dir.path(), "unknown.csv", &unknown);
    let stderr = filter_fails(dir.path(), &path, &[], 1);
    assert!(
        stderr.contains("wobble") && stderr.contains(":1"),
        "{stderr}"
    );
    let missing = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2\n0,1,2,3,4,5\n";
    let path = write_file(dir.path(), "missing.csv", missing);
    let stderr = filter_fails(dir.path(), &path, &[], 1);
    assert!(stderr.contains("az_m_s2"), "{stderr}");
}

#[test]
fn wrong_field_count_and_text_name_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let mut short = good_rows();
    short.push_str("2.5,1,2,3\n");
    let path = write_file(dir.path(), "short.csv", &short);
    let stderr = filter_fails(dir.path(), &path, &[], 1);
    assert!(stderr.contains("short.csv:402"), "{stderr}");
    let text = good_rows().replacen(",1,", ",abc,", 1);
    let path = write_file(dir.path(), "text.csv", &text);
    let stderr = filter_fails(dir.path(), &path, &[], 1);
    assert!(
        stderr.contains("text.csv:2") && stderr.contains("abc"),
        "{stderr}"
    );
}

#[test]
fn nan_and_inf_are_refused_by_filter_and_counted_by_inspect() {
    let dir = tempfile::tempdir().unwrap();
    let rows = imu_csv(
        400,
        200.0,
        |c, t| if c == 2 && t == 0.5 { f64::NAN } else { 1.0 },
    );
    let nan = write_file(
        dir.path(),
        "nan.csv",
        &rows.replacen(",1,1,1,1\n", ",1,1,inf,1\n", 1),
    );
    let stderr = filter_fails(dir.path(), &nan, &[], 1);
    assert!(stderr.contains("nan.csv:"), "{stderr}");
    let (status, stdout, stderr) = outcome(&thermonav(&["inspect", arg(&nan), "--json"]));
    assert_eq!(status, 0, "{stderr}");
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(json["non_finite_count"], 2);
}

#[test]
fn backwards_and_duplicate_timestamps_are_refused_by_filter() {
    let dir = tempfile::tempdir().unwrap();
    let mut rows = good_rows();
    rows.push_str("2.0,0,0,0,0,0,0\n2.0,0,0,0,0,0,0\n");
    let dup = write_file(dir.path(), "dup.csv", &rows);
    let stderr = filter_fails(dir.path(), &dup, &[], 1);
    assert!(stderr.contains("dup.csv:403"), "{stderr}");
    let mut rows = good_rows();
    rows.push_str("0.5,0,0,0,0,0,0\n");
    let back = write_file(dir.path(), "back.csv", &rows);
    let stderr = filter_fails(dir.path(), &back, &[], 1);
    assert!(stderr.contains("back.csv:402"), "{stderr}");
}

#[test]
fn cutoff_at_or_above_nyquist_is_a_usage_error() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_file(dir.path(), "ok.csv", &good_rows());
    let out = dir.path().join("out.csv");
    let args = [
        "filter",
        arg(&path),
        "--cutoff-hz",
        "100",
        "--out",
        arg(&out),
    ];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.to_lowercase().contains("nyquist"), "{stderr}");
    assert!(!out.exists());
    let fir = ["fir", "--fs-hz", "200", "--cutoff-hz", "120"];
    assert_eq!(outcome(&thermonav(&fir)).0, 2);
}

#[test]
fn non_positive_ripple_is_a_usage_error() {
    for ripple in ["0", "-3"] {
        let args = [
            "fir",
            "--fs-hz",
            "200",
            "--cutoff-hz",
            "5",
            "--ripple-db",
            ripple,
        ];
        let (status, _, stderr) = outcome(&thermonav(&args));
        assert_eq!(status, 2, "ripple {ripple}: {stderr}");
        assert!(stderr.contains("ripple"), "{stderr}");
    }
}

#[test]
fn unknown_flag_is_a_usage_error() {
    assert_eq!(outcome(&thermonav(&["inspect", "--frobnicate"])).0, 2);
    assert_eq!(outcome(&thermonav(&["nonsense"])).0, 2);
}
