//! Frames and shapes of the IMU input: gzip-compressed files, `--imu-rotation`, a subset of
//! the six channels, `--rate-hz` for files without times.

use crate::{arg, outcome, thermonav, write_file};
use std::io::Write;
use std::path::{Path, PathBuf};

fn json_of(args: &[&str]) -> serde_json::Value {
    let (status, stdout, stderr) = outcome(&thermonav(args));
    assert_eq!(status, 0, "stderr: {stderr}");
    serde_json::from_str(&stdout).expect("stdout is one JSON document")
}

/// `path` compressed with gzip (flate2, an encoder independent of the reader's decoder
/// settings) beside it, as `NAME.gz`.
fn gzipped(path: &Path) -> PathBuf {
    let out = PathBuf::from(format!("{}.gz", path.display()));
    let mut encoder = flate2::write::GzEncoder::new(
        std::fs::File::create(&out).unwrap(),
        flate2::Compression::default(),
    );
    encoder.write_all(&std::fs::read(path).unwrap()).unwrap();
    encoder.finish().unwrap();
    out
}

/// A simulated static record at 20 °C, 60 s at 100 Hz, in `dir`.
fn chamber_record(dir: &Path) -> PathBuf {
    let chamber = dir.join("chamber");
    let (status, _, stderr) = outcome(&thermonav(&[
        "simulate",
        "chamber",
        "--temperatures-c",
        "20",
        "--duration-s",
        "60",
        "--rate-hz",
        "100",
        "--quiet",
        "--out",
        arg(&chamber),
    ]));
    assert_eq!(status, 0, "stderr: {stderr}");
    chamber.join("imu_20C.csv")
}

/// The bank at `path` without the entries' `source` (the file name, which differs).
fn bank_without_sources(path: &Path) -> serde_json::Value {
    let mut bank: serde_json::Value =
        serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    for entry in bank["entries"].as_array_mut().unwrap() {
        entry.as_object_mut().unwrap().remove("source");
    }
    bank
}

#[test]
fn a_gzip_record_gives_the_plain_files_bank_and_allan_deviation() {
    let dir = tempfile::tempdir().unwrap();
    let plain = chamber_record(dir.path());
    let compressed = gzipped(&plain);
    let mut banks = Vec::new();
    for (input, name) in [(&plain, "plain.json"), (&compressed, "gz.json")] {
        let bank = dir.path().join(name);
        json_of(&[
            "characterize",
            arg(input),
            "--quiet",
            "--out",
            arg(&bank),
            "--json",
        ]);
        banks.push(bank_without_sources(&bank));
    }
    assert_eq!(banks[0], banks[1]);
    let allan = |input: &Path| {
        let mut json = json_of(&["allan", arg(input), "--json"]);
        json.as_object_mut().unwrap().remove("file");
        json
    };
    assert_eq!(allan(&plain), allan(&compressed));
    // The magic bytes are enough, whatever the name.
    let unnamed = dir.path().join("record");
    std::fs::copy(&compressed, &unnamed).unwrap();
    assert_eq!(allan(&plain), allan(&unnamed));
}

#[test]
fn a_corrupt_gzip_file_is_a_data_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let text = crate::imu_csv(50, 100.0, |c, t| c as f64 + t);
    let plain = write_file(dir.path(), "imu.csv", &text);
    let compressed = gzipped(&plain);
    let mut bytes = std::fs::read(&compressed).unwrap();
    bytes.truncate(bytes.len() / 2);
    std::fs::write(&compressed, bytes).unwrap();
    let (status, stdout, stderr) = outcome(&thermonav(&["allan", arg(&compressed)]));
    assert_eq!(status, 1, "stderr: {stderr}");
    assert!(stdout.is_empty());
    assert!(stderr.contains("imu.csv.gz"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// A record of `rows` samples at 100 Hz (t_s = k/100 exactly), every channel a distinct
/// deterministic wiggle around its own level (az near −g), with temp_c 25.
fn wiggly_record(rows: usize) -> String {
    let text = crate::imu_csv(rows, 100.0, |c, t| {
        let k = (t * 100.0).round();
        let level = [1e-3, -2e-3, 3e-3, 0.1, -0.2, -9.8][c];
        level + 1e-3 * ((k * (3.0 + 2.0 * c as f64)).sin() + 0.5 * (k * 0.37 + c as f64).cos())
    });
    text.lines()
        .enumerate()
        .map(|(i, line)| match i {
            0 => format!("{line},temp_c\n"),
            _ => format!("{line},25\n"),
        })
        .collect()
}

/// `allan --json` of `input` with `extra` options, without the file name.
fn allan(input: &Path, extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["allan", arg(input), "--json"];
    args.extend_from_slice(extra);
    let mut json = json_of(&args);
    json.as_object_mut().unwrap().remove("file");
    json
}

/// The closed form of an axis mapping: body gx = −(IMU gy), body gy = IMU gx, so the rotated
/// record's gx curve is the plain record's gy curve, bit for bit (negation leaves squares
/// alone), and rpy:0,0,90 (the same mounting as angles) gives it to rounding.
#[test]
fn an_axis_mapping_moves_each_channel_and_equals_its_angles() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_file(dir.path(), "imu.csv", &wiggly_record(4000));
    let plain = allan(&path, &[]);
    let mapped = allan(&path, &["--imu-rotation", "-y,x,z"]);
    assert_eq!(mapped["imu_rotation"], "-y,x,z");
    for (body, imu) in [
        ("gx", "gy"),
        ("gy", "gx"),
        ("gz", "gz"),
        ("ax", "ay"),
        ("ay", "ax"),
    ] {
        assert_eq!(
            mapped["channels"][body]["adev"], plain["channels"][imu]["adev"],
            "{body}"
        );
    }
    let angles = allan(&path, &["--imu-rotation", "rpy:0,0,90"]);
    for channel in ["gx", "gy", "gz", "ax", "ay", "az"] {
        let a = mapped["channels"][channel]["adev"].as_array().unwrap();
        let b = angles["channels"][channel]["adev"].as_array().unwrap();
        for (a, b) in a.iter().zip(b) {
            let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
            // cos(90°) is 6e-17, not 0: the other axis leaks in at that level, against
            // deviations of 1e-4..1e-3 (the levels 0.1..9.8 cancel in the differences).
            assert!(
                (a - b).abs() <= 1e-12 * a.abs().max(1e-9),
                "{channel}: {a} {b}"
            );
        }
    }
}

/// Writes a KF-GINS IMU file of two samples whose increments are (1, 2, 3)·1e-3 rad and
/// (4, 5, 6)·1e-2 m/s, converts it with `rotation` and returns the first written row's six
/// values.
fn converted_increments(dir: &Path, rotation: &str) -> [f64; 6] {
    let input = write_file(
        dir,
        "imu.txt",
        "100.00 0.001 0.002 0.003 0.04 0.05 0.06\n100.01 0.001 0.002 0.003 0.04 0.05 0.06\n",
    );
    let out = dir.join(format!("out{}.csv", rotation.len()));
    let (status, _, stderr) = outcome(&thermonav(&[
        "convert",
        arg(&input),
        "--format",
        "kf-gins-imu",
        "--imu-rotation",
        rotation,
        "--out",
        arg(&out),
    ]));
    assert_eq!(status, 0, "stderr: {stderr}");
    let text = std::fs::read_to_string(&out).unwrap();
    let row: Vec<f64> = text
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .skip(1)
        .map(|v| v.parse().unwrap())
        .collect();
    row.try_into().unwrap()
}

/// Known vectors rotated: an axis mapping exactly, angles as R_z(ψ) R_y(θ) R_x(φ) written out.
#[test]
fn convert_turns_increments_into_body_axes_by_the_closed_form() {
    let dir = tempfile::tempdir().unwrap();
    assert_eq!(
        converted_increments(dir.path(), "-y,x,z"),
        [-0.002, 0.001, 0.003, -0.05, 0.04, 0.06]
    );
    let (phi, theta, psi) = (
        30_f64.to_radians(),
        (-20_f64).to_radians(),
        70_f64.to_radians(),
    );
    let (c, s) = (|a: f64| a.cos(), |a: f64| a.sin());
    let m = [
        [
            c(psi) * c(theta),
            c(psi) * s(theta) * s(phi) - s(psi) * c(phi),
            c(psi) * s(theta) * c(phi) + s(psi) * s(phi),
        ],
        [
            s(psi) * c(theta),
            s(psi) * s(theta) * s(phi) + c(psi) * c(phi),
            s(psi) * s(theta) * c(phi) - c(psi) * s(phi),
        ],
        [-s(theta), c(theta) * s(phi), c(theta) * c(phi)],
    ];
    let rotate = |v: [f64; 3]| m.map(|row| row[0] * v[0] + row[1] * v[1] + row[2] * v[2]);
    let expected: Vec<f64> = rotate([0.001, 0.002, 0.003])
        .into_iter()
        .chain(rotate([0.04, 0.05, 0.06]))
        .collect();
    let found = converted_increments(dir.path(), "rpy:30,-20,70");
    for (f, e) in found.iter().zip(&expected) {
        assert!((f - e).abs() < 1e-15, "{found:?} against {expected:?}");
    }
}

/// The bank records the mounting, and its record means are the plain record's turned by
/// x,-y,-z (ROS's FLU against FRD): y and z negated exactly (a sum of negated values is the
/// negated sum), x unchanged.
#[test]
fn the_bank_records_the_rotation_its_records_were_read_with() {
    let dir = tempfile::tempdir().unwrap();
    let record = chamber_record(dir.path());
    let bank = |name: &str, extra: &[&str]| {
        let path = dir.path().join(name);
        let mut args = vec!["characterize", arg(&record), "--quiet", "--out", arg(&path)];
        args.extend_from_slice(extra);
        let (status, _, stderr) = outcome(&thermonav(&args));
        assert_eq!(status, 0, "stderr: {stderr}");
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
        json["entries"][0].clone()
    };
    let plain = bank("plain.json", &[]);
    let turned = bank("turned.json", &["--imu-rotation", "x,-y,-z"]);
    assert_eq!(turned["imu_rotation"], "x,-y,-z");
    assert!(plain.get("imu_rotation").is_none());
    let mean = |entry: &serde_json::Value, channel: &str| {
        entry["record_mean"]["values"][channel].as_f64().unwrap()
    };
    for (channel, sign) in [
        ("gx", 1.0),
        ("gy", -1.0),
        ("gz", -1.0),
        ("ax", 1.0),
        ("ay", -1.0),
        ("az", -1.0),
    ] {
        assert_eq!(
            mean(&turned, channel),
            sign * mean(&plain, channel),
            "{channel}"
        );
    }
    assert!(mean(&turned, "az") > 9.0, "upside down, az reads +g");
}

/// A file without t_s at --rate-hz 100 gives the Allan deviation of the same file with
/// t_s = k/100, and its bank the same models.
#[test]
fn a_rate_times_a_file_without_a_time_column() {
    let dir = tempfile::tempdir().unwrap();
    let text = wiggly_record(6000);
    let timed = write_file(dir.path(), "timed.csv", &text);
    let untimed_text: String = text
        .lines()
        .map(|line| format!("{}\n", line.split_once(',').unwrap().1))
        .collect();
    let untimed = write_file(dir.path(), "untimed.csv", &untimed_text);
    assert_eq!(allan(&timed, &[]), allan(&untimed, &["--rate-hz", "100"]));
    let banks: Vec<serde_json::Value> = [(&timed, None), (&untimed, Some("100"))]
        .into_iter()
        .enumerate()
        .map(|(k, (input, rate))| {
            let bank = dir.path().join(format!("bank{k}.json"));
            let mut args = vec![
                "characterize",
                arg(input),
                "--gmwm",
                "off",
                "--quiet",
                "--out",
                arg(&bank),
            ];
            if let Some(rate) = rate {
                args.extend(["--rate-hz", rate]);
            }
            let (status, _, stderr) = outcome(&thermonav(&args));
            assert_eq!(status, 0, "stderr: {stderr}");
            bank_without_sources(&bank)
        })
        .collect();
    assert_eq!(banks[0], banks[1]);
}

/// `wiggly_record`'s t_s, gz and temp_c columns alone: a single-gyro file.
fn single_gyro(text: &str) -> String {
    text.lines()
        .map(|line| {
            let f: Vec<&str> = line.split(',').collect();
            format!("{},{},{}\n", f[0], f[3], f[7])
        })
        .collect()
}

/// A single-gyro file gives exactly the full file's gz curve and gz model, alone; navigation
/// refuses it, naming the five absent columns.
#[test]
fn a_single_gyro_file_is_analysed_alone_and_refused_by_navigation() {
    let dir = tempfile::tempdir().unwrap();
    let text = wiggly_record(6000);
    let full = write_file(dir.path(), "full.csv", &text);
    let gyro = write_file(dir.path(), "gz.csv", &single_gyro(&text));
    let (all, one) = (allan(&full, &[]), allan(&gyro, &[]));
    let names: Vec<&String> = one["channels"].as_object().unwrap().keys().collect();
    assert_eq!(names, ["gz"]);
    assert_eq!(one["channels"]["gz"], all["channels"]["gz"]);
    let family = json_of(&["allan", arg(&gyro), "--kind", "mdev", "--json"]);
    assert_eq!(family["channels"].as_object().unwrap().len(), 1);
    let entry = |input: &Path, name: &str| {
        let bank = dir.path().join(name);
        let args = [
            "characterize",
            arg(input),
            "--gmwm",
            "off",
            "--quiet",
            "--out",
            arg(&bank),
        ];
        let (status, _, stderr) = outcome(&thermonav(&args));
        assert_eq!(status, 0, "stderr: {stderr}");
        bank_without_sources(&bank)["entries"][0].clone()
    };
    let (all, one) = (entry(&full, "full.json"), entry(&gyro, "gz.json"));
    let names: Vec<&String> = one["channels"].as_object().unwrap().keys().collect();
    assert_eq!(names, ["gz"], "the bank records the channels present");
    assert_eq!(one["channels"]["gz"], all["channels"]["gz"]);
    assert_eq!(
        one["record_mean"]["values"]["gz"],
        all["record_mean"]["values"]["gz"]
    );
    assert_eq!(one["record_mean"]["values"].as_object().unwrap().len(), 1);
    let gnss = write_file(
        dir.path(),
        "gnss.csv",
        "t_s,lat_deg,lon_deg,h_m\n0,44,-63,0\n",
    );
    let out = dir.path().join("solution.csv");
    let bank = dir.path().join("full.json");
    let (status, _, stderr) = outcome(&thermonav(&[
        "integrate",
        "--imu",
        arg(&gyro),
        "--gnss",
        arg(&gnss),
        "--bank",
        arg(&bank),
        "--out",
        arg(&out),
    ]));
    assert_eq!(status, 1, "{stderr}");
    for name in ["gx_rad_s", "gy_rad_s", "ax_m_s2", "ay_m_s2", "az_m_s2"] {
        assert!(stderr.contains(name), "{name}: {stderr}");
    }
    assert!(stderr.contains("all six channels"), "{stderr}");
    assert!(!out.exists());
}
