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
