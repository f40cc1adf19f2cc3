//! `thermonav convert` on ArduPilot DataFlash logs (the io crate's tests/data/dataflash,
//! written by `tools/oracles/dataflash.py` from the format's documentation and read back there
//! by pymavlink 2.4.50; values in expected.json), `characterize`, `allan` and `gmwm` on a log
//! directly, and the README's two commands.
//!
//! The CSV writer prints the shortest text that reads back to the same binary64, so the values
//! compare exactly (binary32 fields widened, scaled integers divided as documented; see the io
//! crate's tests/it/dataflash.rs).

use crate::{arg, files_in, outcome, thermonav};
use std::path::{Path, PathBuf};
use thermonav_io::{Strictness, read_gnss_file, read_imu_file};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../thermonav-io/tests/data/dataflash")
        .join(name)
}

fn expected(name: &str) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(data(name)).unwrap()).unwrap()
}

fn run(args: &[&str]) -> (i32, String, String) {
    outcome(&thermonav(args))
}

fn f(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap()
}

#[test]
fn a_log_converts_to_the_written_values_with_temperature_gnss_and_a_sidecar() {
    let expected = expected("expected.json");
    let want = &expected["static"];
    let dir = tempfile::tempdir().unwrap();
    let (imu, gnss) = (dir.path().join("imu.csv"), dir.path().join("gnss.csv"));
    let log = data("static.bin");
    let args = [
        "convert",
        arg(&log),
        "--imu-instance",
        "0",
        "--out",
        arg(&imu),
        "--gnss-out",
        arg(&gnss),
    ];
    let (status, stdout, stderr) = run(&args);
    assert_eq!(status, 0, "{stderr}");
    assert!(
        stdout.contains("100 IMU samples (rates)") && stdout.contains("5 GNSS fixes"),
        "{stdout}"
    );
    let series = read_imu_file(&imu, Strictness::Strict).unwrap();
    let records = want["imu0"].as_array().unwrap();
    assert_eq!(series.len(), records.len());
    let offset = want["boot_to_gpst_ns"].as_i64().unwrap();
    let temperature = series.temperature_c.as_ref().unwrap();
    for (k, r) in records.iter().enumerate() {
        let time = r["time_us"].as_i64().unwrap() * 1_000 + offset;
        assert_eq!(series.time[k].as_nanos(), time);
        let values = [&r["gyro"][0], &r["gyro"][1], &r["gyro"][2], &r["accel"][0]];
        for (c, v) in values.iter().enumerate() {
            assert_eq!(series.channels[c][k], f(v), "channel {c} at {k}");
        }
        assert_eq!(series.channels[5][k], f(&r["accel"][2]));
        assert_eq!(temperature[k], f(&r["temp_c"]));
    }
    let fixes = read_gnss_file(&gnss, Strictness::Strict).unwrap();
    let want_fixes = want["fixes"].as_array().unwrap();
    assert_eq!(fixes.len(), want_fixes.len());
    assert_eq!(fixes[0].height_m, f(&want_fixes[0]["alt_m"]));
    assert_eq!(
        fixes[0].time.as_nanos(),
        want_fixes[0]["gpst_ns"].as_i64().unwrap()
    );
    let sidecar: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("imu.csv.json")).unwrap())
            .unwrap();
    assert_eq!(sidecar["time_scale"]["scale"], "gpst");
    assert_eq!(sidecar["time_scale"]["boot_to_gpst_ns"], offset);
    assert_eq!(sidecar["imu"]["instance"], 0);
    assert_eq!(sidecar["imu"]["instances"][1]["count"], 10);
    assert!(
        sidecar["imu"]["units"]
            .as_str()
            .unwrap()
            .contains("confirmed")
    );
    assert!(
        sidecar["gnss"]["height"]
            .as_str()
            .unwrap()
            .contains("mean sea level")
    );
}

#[test]
fn an_ambiguous_imu_instance_is_listed_and_imu_instance_chooses_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("imu.csv");
    let log = data("static.bin");
    let (status, _, stderr) = run(&["convert", arg(&log), "--out", arg(&out)]);
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("2 IMU instances: 0 (IMU, 100 records), 1 (IMU, 10 records); choose one with --imu-instance"),
        "{stderr}"
    );
    assert!(files_in(dir.path()).is_empty());
    let args = [
        "convert",
        arg(&log),
        "--format",
        "dataflash",
        "--imu-instance",
        "1",
        "--out",
        arg(&out),
    ];
    let (status, stdout, stderr) = run(&args);
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("10 IMU samples"), "{stdout}");
    // allan names the instances and says how to choose one.
    let (status, _, stderr) = run(&["allan", arg(&log)]);
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("choose one with --imu-instance")
            && stderr.contains("convert the log first"),
        "{stderr}"
    );
}

#[test]
fn imu_instance_belongs_to_dataflash_only() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("x.pos");
    std::fs::write(&input, "% RTKLIB\n").unwrap();
    let out = dir.path().join("o.csv");
    let args = [
        "convert",
        arg(&input),
        "--imu-instance",
        "1",
        "--out",
        arg(&out),
    ];
    let (status, _, stderr) = run(&args);
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("--imu-instance goes with --format dataflash only"),
        "{stderr}"
    );
}

/// `command FILE --json` without its `file` field.
fn json_without_file(command: &str, file: &Path) -> serde_json::Value {
    let (status, stdout, stderr) = run(&[command, arg(file), "--json"]);
    assert_eq!(status, 0, "{command}: {stderr}");
    let mut v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    v.as_object_mut().unwrap().remove("file");
    v
}

#[test]
fn allan_and_gmwm_read_a_log_as_its_converted_csv() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("imu.csv");
    let log = data("static_10hz.bin.gz");
    assert_eq!(run(&["convert", arg(&log), "--out", arg(&csv)]).0, 0);
    for command in ["allan", "gmwm"] {
        assert_eq!(
            json_without_file(command, &log),
            json_without_file(command, &csv),
            "{command}"
        );
    }
    let (status, _, stderr) = run(&["allan", arg(&log), "--rate-hz", "10"]);
    assert_eq!(status, 1, "{stderr}");
    assert!(stderr.contains("has its own times (TimeUS)"), "{stderr}");
}

#[test]
fn readme_an_ardupilot_log_to_csvs_and_a_bank_in_two_commands() {
    let dir = tempfile::tempdir().unwrap();
    let (csv, bank) = (dir.path().join("imu.csv"), dir.path().join("bank.json"));
    let log = data("static_10hz.bin.gz");
    let (status, _, stderr) = run(&["convert", arg(&log), "--out", arg(&csv)]);
    assert_eq!(status, 0, "{stderr}");
    assert!(
        stderr.contains("seconds since the autopilot booted"),
        "{stderr}"
    );
    let (status, _, stderr) = run(&["characterize", arg(&log), "--out", arg(&bank)]);
    assert_eq!(status, 0, "{stderr}");
    // The bank is the one characterize builds from the converted CSV.
    let from_csv = dir.path().join("csv-bank.json");
    assert_eq!(
        run(&["characterize", arg(&csv), "--out", arg(&from_csv)]).0,
        0
    );
    let read = |p: &Path| {
        std::fs::read_to_string(p)
            .unwrap()
            .replace("static_10hz.bin.gz", "imu.csv")
    };
    assert_eq!(read(&bank), read(&from_csv));
    let series = read_imu_file(&csv, Strictness::Strict).unwrap();
    let summary = expected("expected_10hz.json");
    assert_eq!(series.len() as u64, summary["imu_count"].as_u64().unwrap());
    let last = &summary["imu_last"];
    let n = series.len() - 1;
    assert_eq!(
        series.time[n].as_nanos(),
        last["time_us"].as_i64().unwrap() * 1_000
    );
    assert_eq!(series.channels[5][n], f(&last["accel"][2]));
    assert_eq!(series.temperature_c.unwrap()[0], 25.0);
}
