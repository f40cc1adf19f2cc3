//! `thermonav convert` on ROS bags (the io crate's tests/data/ros, written by
//! `tools/oracles/ros_bags.py` with rosbags 0.11.9 and mcap 1.6.0; values in expected.json),
//! `characterize` and `allan` on a bag directly, and the README's two commands from a static
//! MCAP bag to a Kalibr imu.yaml.

use crate::{arg, files_in, outcome, thermonav};
use std::path::{Path, PathBuf};
use thermonav_io::{Strictness, read_gnss_file, read_imu_file};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../thermonav-io/tests/data/ros")
        .join(name)
}

fn expected(name: &str) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(data(name)).unwrap()).unwrap()
}

/// `thermonav ARGS`: status, stdout, stderr.
fn run(args: &[&str]) -> (i32, String, String) {
    outcome(&thermonav(args))
}

#[test]
fn each_bag_format_converts_to_the_written_values_in_frd_with_temperature_and_gnss() {
    let expected = expected("expected.json");
    let first = &expected["imu"][0];
    let fix = &expected["fixes"][0];
    for name in ["static_none.mcap", "static.db3", "static_bz2.bag"] {
        let dir = tempfile::tempdir().unwrap();
        let (imu, gnss) = (dir.path().join("imu.csv"), dir.path().join("gnss.csv"));
        let bag = data(name);
        let args = [
            "convert",
            arg(&bag),
            "--out",
            arg(&imu),
            "--gnss-out",
            arg(&gnss),
        ];
        let (status, stdout, stderr) = run(&args);
        assert_eq!(status, 0, "{name}: {stderr}");
        assert!(
            stdout.contains("150 IMU samples (rates)") && stdout.contains("8 GNSS fixes"),
            "{stdout}"
        );
        let series = read_imu_file(&imu, Strictness::Strict).unwrap();
        assert_eq!(series.len(), 150);
        assert_eq!(
            series.time[0].as_nanos(),
            first["stamp_ns"].as_i64().unwrap()
        );
        let g = |k: usize| first["gyro"][k].as_f64().unwrap();
        let a = |k: usize| first["accel"][k].as_f64().unwrap();
        let frd = [g(0), -g(1), -g(2), a(0), -a(1), -a(2)];
        for (c, v) in frd.iter().enumerate() {
            assert_eq!(series.channels[c][0], *v, "{name} channel {c}");
        }
        assert!(
            series.temperature_c.is_some(),
            "{name}: temp_c from /imu/temperature"
        );
        let fixes = read_gnss_file(&gnss, Strictness::Strict).unwrap();
        assert_eq!(fixes.len(), 8);
        assert_eq!(fixes[0].height_m, fix["altitude_m"].as_f64().unwrap());
        let sidecar: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(dir.path().join("imu.csv.json")).unwrap(),
        )
        .unwrap();
        assert_eq!(sidecar["imu"]["topic"], "/imu/data");
        assert!(
            sidecar["imu"]["frame"]
                .as_str()
                .unwrap()
                .contains("(x, -y, -z)")
        );
        assert!(
            sidecar["imu"]["time"]
                .as_str()
                .unwrap()
                .contains("header stamp")
        );
        assert_eq!(sidecar["imu"]["stamp_lag_s"]["max_s"], -0.002);
    }
}

#[test]
fn an_ambiguous_imu_topic_is_listed_and_topic_chooses_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("imu.csv");
    let bag = data("static_zstd.mcap");
    let (status, _, stderr) = run(&["convert", arg(&bag), "--out", arg(&out)]);
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("/imu/data (sensor_msgs/msg/Imu, 150 messages), /imu/raw (sensor_msgs/msg/Imu, 5 messages); choose one with --topic"),
        "{stderr}"
    );
    assert!(files_in(dir.path()).is_empty());
    let args = [
        "convert",
        arg(&bag),
        "--format",
        "ros2-mcap",
        "--topic",
        "/imu/raw",
        "--out",
        arg(&out),
    ];
    let (status, stdout, stderr) = run(&args);
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("5 IMU samples"), "{stdout}");
}

#[test]
fn topic_options_belong_to_bags_only() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("x.pos");
    std::fs::write(&input, "% RTKLIB\n").unwrap();
    let out = dir.path().join("o.csv");
    let (status, _, stderr) = run(&[
        "convert",
        arg(&input),
        "--topic",
        "/imu",
        "--out",
        arg(&out),
    ]);
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("--topic, --gnss-topic and --temperature-topic go with"),
        "{stderr}"
    );
}

#[test]
fn allan_reads_a_bag_as_its_converted_csv() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("imu.csv");
    let bag = data("static.db3");
    assert_eq!(run(&["convert", arg(&bag), "--out", arg(&csv)]).0, 0);
    let (status, from_bag, stderr) = run(&["allan", arg(&bag), "--json"]);
    assert_eq!(status, 0, "{stderr}");
    let (_, from_csv, _) = run(&["allan", arg(&csv), "--json"]);
    let strip = |text: &str| {
        let mut v: serde_json::Value = serde_json::from_str(text).unwrap();
        v.as_object_mut().unwrap().remove("file");
        v
    };
    assert_eq!(strip(&from_bag), strip(&from_csv));
}

// The README's bag-to-Kalibr block is run as written in readme.rs; here its bank is the one
// characterize builds from the converted CSV (the bag read as the CSV).
#[test]
fn a_static_mcap_bag_characterizes_as_its_converted_csv() {
    let dir = tempfile::tempdir().unwrap();
    let bank = dir.path().join("bank.json");
    let bag = data("static_10hz.mcap");
    let (status, _, stderr) = run(&["characterize", arg(&bag), "--out", arg(&bank)]);
    assert_eq!(status, 0, "{stderr}");
    let csv = dir.path().join("imu.csv");
    assert_eq!(run(&["convert", arg(&bag), "--out", arg(&csv)]).0, 0);
    let from_csv = dir.path().join("csv-bank.json");
    assert_eq!(
        run(&["characterize", arg(&csv), "--out", arg(&from_csv)]).0,
        0
    );
    let read = |p: &Path| {
        std::fs::read_to_string(p)
            .unwrap()
            .replace("static_10hz.mcap", "imu.csv")
    };
    assert_eq!(read(&bank), read(&from_csv));
    let series = read_imu_file(&csv, Strictness::Strict).unwrap();
    let summary = expected("expected_10hz.json");
    assert_eq!(series.len() as u64, summary["imu_count"].as_u64().unwrap());
    let last = &summary["imu_last"];
    assert_eq!(
        series.time[series.len() - 1].as_nanos(),
        last["stamp_ns"].as_i64().unwrap()
    );
    assert_eq!(
        series.channels[5][series.len() - 1],
        -last["accel"][2].as_f64().unwrap()
    );
    assert_eq!(series.temperature_c.unwrap()[0], 25.0);
}

/// The oracle bag `name` with the 8 bytes of `from` (little-endian, as the bag stores it)
/// replaced by `to`, saved in `dir`.
fn bag_with(dir: &Path, name: &str, from: f64, to: f64) -> PathBuf {
    let mut bytes = std::fs::read(data(name)).unwrap();
    let at = bytes
        .windows(8)
        .position(|w| w == from.to_le_bytes())
        .unwrap();
    bytes[at..at + 8].copy_from_slice(&to.to_le_bytes());
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

#[test]
fn bags_holding_a_value_no_reader_accepts_are_refused_naming_the_message_and_nothing_is_written() {
    let expected = expected("expected.json");
    let temperature = expected["temperature"][0]["temperature_c"]
        .as_f64()
        .unwrap();
    let ax = expected["imu"][0]["accel"][0].as_f64().unwrap();
    let cases = [
        (
            "static_none.mcap",
            temperature,
            298.15,
            "/imu/temperature message 0: temperature 298.15 °C is outside -80..150 °C, the \
             range of a sensor's temperature (in kelvin? 298.15 K is 25.00 °C)",
        ),
        (
            "static.bag",
            temperature,
            1e30,
            "/imu/temperature message 0: temperature 1000000000000000000000000000000 °C is \
             outside -80..150 °C",
        ),
        (
            "static.db3",
            ax,
            -1e300,
            "/imu/data message 0: ax is -1e300 in SI, beyond the 1e15 any sensor reading stays \
             within (in FRD)",
        ),
    ];
    for (name, from, to, message) in cases {
        let dir = tempfile::tempdir().unwrap();
        let bag = bag_with(dir.path(), name, from, to);
        let out = dir.path().join("imu.csv");
        let (status, stdout, stderr) = run(&["convert", arg(&bag), "--out", arg(&out)]);
        assert_eq!(status, 1, "{name}: {stderr}");
        assert!(stdout.is_empty(), "{stdout}");
        assert!(
            stderr.contains(&format!("{}: at byte ", bag.display())) && stderr.contains(message),
            "{name}: {stderr}"
        );
        assert_eq!(
            files_in(dir.path()),
            vec![name.to_string()],
            "nothing written"
        );
    }
    // allan and characterize read the bag directly: the same refusal, naming the same place.
    let dir = tempfile::tempdir().unwrap();
    let bag = bag_with(dir.path(), "static.db3", ax, -1e300);
    let bank = dir.path().join("bank.json");
    for args in [
        vec!["allan", arg(&bag)],
        vec!["characterize", arg(&bag), "--out", arg(&bank)],
    ] {
        let (status, _, stderr) = run(&args);
        assert_eq!(status, 1, "{args:?}: {stderr}");
        assert!(
            stderr.contains(&bag.display().to_string())
                && stderr.contains("/imu/data message 0: ax is -1e300 in SI"),
            "{args:?}: {stderr}"
        );
        assert_eq!(files_in(dir.path()), vec!["static.db3".to_string()]);
    }
}

#[test]
fn characterize_streams_an_mcap_bag_to_the_bank_it_builds_in_memory() {
    let dir = tempfile::tempdir().unwrap();
    let bag = data("static_10hz.mcap");
    let bank = |reading: &str| {
        let out = dir.path().join(format!("{reading}.json"));
        let args = [
            "characterize",
            arg(&bag),
            "--out",
            arg(&out),
            "--reading",
            reading,
        ];
        let (status, _, stderr) = run(&args);
        assert_eq!(status, 0, "{reading}: {stderr}");
        let text = std::fs::read_to_string(&out).unwrap();
        serde_json::from_str::<serde_json::Value>(&text).unwrap()
    };
    let (memory, streamed) = (bank("in-memory"), bank("streaming"));
    let (m, s) = (&memory["entries"][0], &streamed["entries"][0]);
    // The bag's temperature (25 C, its only Temperature topic) and its samples, read either way.
    assert_eq!(m["temperature_c"], s["temperature_c"]);
    assert_eq!(m["preprocessing"], s["preprocessing"]);
    for channel in ["gx", "gy", "gz", "ax", "ay", "az"] {
        let (mc, sc) = (&m["channels"][channel], &s["channels"][channel]);
        assert!(mc["ar"]["coefficients"].is_array(), "{channel}: {mc}");
        assert_eq!(mc["ar"], sc["ar"], "{channel}");
    }
}

#[test]
fn characterize_streaming_a_bag_refuses_a_bad_sample_naming_it_and_writes_nothing() {
    let expected = expected("expected.json");
    let ax = expected["imu"][0]["accel"][0].as_f64().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let bag = bag_with(dir.path(), "static_none.mcap", ax, -1e300);
    let bank = dir.path().join("bank.json");
    let args = [
        "characterize",
        arg(&bag),
        "--out",
        arg(&bank),
        "--reading",
        "streaming",
    ];
    let (status, _, stderr) = run(&args);
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains(&format!("{}: at byte ", bag.display()))
            && stderr.contains("/imu/data message 0: ax is -1e300 in SI"),
        "{stderr}"
    );
    assert_eq!(files_in(dir.path()), vec!["static_none.mcap".to_string()]);
}
