//! Atomic output: the target appears whole on success; on failure neither the target nor a
//! temporary file is left, and an existing target is untouched.

use std::io::Write;
use std::path::Path;
use thermonav::imu::{ImuSeries, SampleKind};
use thermonav_io::{
    AtomicFile, WriteError, write_atomically, write_imu_file, write_json_atomically,
};

fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn failing_write(file: &mut AtomicFile) -> Result<(), WriteError> {
    file.write_all(b"half a file")?;
    Err(WriteError::Empty { what: "samples" })
}

#[test]
fn successful_write_leaves_only_the_target() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.txt");
    write_atomically(&path, |file| Ok(file.write_all(b"complete\n")?)).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "complete\n");
    assert_eq!(names_in(dir.path()), ["out.txt"]);
}

#[test]
fn failing_write_leaves_neither_target_nor_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.csv");
    let error = write_atomically(&path, failing_write).unwrap_err();
    assert_eq!(
        error.to_string(),
        format!("{}: nothing to write: no samples", path.display())
    );
    assert!(names_in(dir.path()).is_empty());
}

#[test]
fn failing_write_keeps_the_previous_target() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.csv");
    std::fs::write(&path, "previous\n").unwrap();
    assert!(write_atomically(&path, failing_write).is_err());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "previous\n");
    assert_eq!(names_in(dir.path()), ["out.csv"]);
}

#[test]
fn uncommitted_file_vanishes_when_dropped() {
    let dir = tempfile::tempdir().unwrap();
    let mut file = AtomicFile::create(dir.path().join("out.bin")).unwrap();
    file.write_all(&[0; 100_000]).unwrap();
    assert_eq!(
        names_in(dir.path()).len(),
        1,
        "the temporary file exists while writing"
    );
    drop(file);
    assert!(names_in(dir.path()).is_empty());
}

#[test]
fn invalid_series_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("imu.csv");
    assert!(write_imu_file(&path, &ImuSeries::new(SampleKind::Rates)).is_err());
    assert!(names_in(dir.path()).is_empty());
}

#[test]
fn missing_directory_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("absent").join("out.txt");
    let error = write_atomically(&path, |_| Ok(())).unwrap_err();
    assert!(
        matches!(error, WriteError::CreateTemporary { .. }),
        "{error}"
    );
    assert!(
        error
            .to_string()
            .starts_with(&format!("{}: cannot create", path.display()))
    );
}

#[test]
fn json_is_written_pretty_and_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bank.json");
    let value = serde_json::json!({"tau_s": [0.005, 1.5], "kind": "rates"});
    write_json_atomically(&path, &value).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.ends_with("}\n"));
    assert_eq!(
        serde_json::from_str::<serde_json::Value>(&text).unwrap(),
        value
    );
    assert_eq!(names_in(dir.path()), ["bank.json"]);
}
