//! `thermonav convert` on a PX4 ULog: the PX4 v1.8 SITL sample of the io crate (values from
//! pyulog 1.3.0, see `thermonav-io/tests/data/ulog/README.md`), and damaged copies of it:
//! exit 1 naming the file, the byte and what was expected, and no output file.

use crate::{arg, files_in, outcome, thermonav};
use std::path::{Path, PathBuf};
use thermonav_io::{Strictness, read_gnss_file, read_imu_file};

fn sample() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../thermonav-io/tests/data/ulog/px4_sitl_v1.8.ulg")
}

/// `thermonav convert INPUT --out OUT --gnss-out GNSS`: status, stdout, stderr.
fn convert_with_gnss(input: &Path, out: &Path, gnss: &Path) -> (i32, String, String) {
    outcome(&thermonav(&[
        "convert",
        arg(input),
        "--out",
        arg(out),
        "--gnss-out",
        arg(gnss),
    ]))
}

/// The `imu.csv.json` sidecar in `dir`.
fn sidecar_of(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("imu.csv.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

#[test]
fn a_ulog_is_detected_and_gives_imu_gnss_and_a_sidecar() {
    let dir = tempfile::tempdir().unwrap();
    let (imu, gnss) = (dir.path().join("imu.csv"), dir.path().join("gnss.csv"));
    let input = sample();
    let (status, stdout, stderr) = convert_with_gnss(&input, &imu, &gnss);
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("4445 IMU samples (rates)"), "{stdout}");
    assert!(
        stderr.contains("seconds since the autopilot booted"),
        "{stderr}"
    );
    // pyulog 1.3.0: sensor_combined 4445 records, first timestamp 375484685 µs;
    // vehicle_gps_position 260 records (all fix_type 3), first 375408345 µs.
    let series = read_imu_file(&imu, Strictness::Strict).unwrap();
    assert_eq!(series.len(), 4445);
    assert_eq!(series.time[0].as_nanos(), 375_484_685_000);
    let fixes = read_gnss_file(&gnss, Strictness::Strict).unwrap();
    assert_eq!(fixes.len(), 260);
    assert_eq!(fixes[0].time.as_nanos(), 375_408_345_000);
    let sidecar = sidecar_of(dir.path());
    assert_eq!(sidecar["time_scale"]["scale"], "boot");
    assert_eq!(sidecar["imu"]["topic"], "sensor_combined");
    assert_eq!(sidecar["log"]["dropouts"], 0);
}

/// Runs convert on `bytes` with a GNSS output; returns the stderr of a run that must fail
/// with exit 1 and leave the folder with only the input.
fn failing(bytes: &[u8]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("log.ulg");
    std::fs::write(&input, bytes).unwrap();
    let (imu, gnss) = (dir.path().join("imu.csv"), dir.path().join("gnss.csv"));
    let args = [
        "convert",
        arg(&input),
        "--format",
        "px4-ulog",
        "--out",
        arg(&imu),
        "--gnss-out",
        arg(&gnss),
    ];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 1, "{stderr}");
    assert_eq!(files_in(dir.path()), ["log.ulg"]);
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

#[test]
fn bad_ulogs_fail_cleanly_with_the_place_and_the_expectation() {
    let good = std::fs::read(sample()).unwrap();
    let stderr = failing(b"t_s,gx_rad_s\n1,2\n");
    assert!(
        stderr.contains("log.ulg: at byte 0: expected the ULog magic"),
        "{stderr}"
    );
    let stderr = failing(&good[..3000]);
    assert!(
        stderr.contains("ends inside a message of the definitions"),
        "{stderr}"
    );
    assert!(stderr.contains("log.ulg: at byte "), "{stderr}");
    let stderr = failing(&good[..0]);
    assert!(
        stderr.contains("ends inside the 16-byte ULog header"),
        "{stderr}"
    );
    // The GNSS topic renamed away (same length, in its format and subscription).
    let mut renamed = good.clone();
    let name = b"vehicle_gps_position";
    let mut i = 0;
    while i + name.len() <= renamed.len() {
        if &renamed[i..i + name.len()] == name {
            renamed[i + 13] = b'X';
        }
        i += 1;
    }
    let stderr = failing(&renamed);
    assert!(
        stderr.contains("no GNSS topic: expected vehicle_gps_position or sensor_gps"),
        "{stderr}"
    );
}

#[test]
fn gnss_out_belongs_to_ulog_only() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("x.pos");
    std::fs::write(&input, "% RTKLIB\n").unwrap();
    let out = dir.path().join("o.csv");
    let gnss = dir.path().join("g.csv");
    let (status, _, stderr) = convert_with_gnss(&input, &out, &gnss);
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains(
            "--gnss-out goes with --format px4-ulog, ros2-mcap, ros2-db3, ros1-bag or dataflash only"
        ),
        "{stderr}"
    );
}

#[test]
fn a_log_still_being_written_converts_its_whole_records_and_says_so() {
    // The last 7 bytes missing: the final message is partial, as when the logger is cut off.
    let good = std::fs::read(sample()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("live.ulg");
    std::fs::write(&input, &good[..good.len() - 7]).unwrap();
    let imu = dir.path().join("imu.csv");
    let (status, _, stderr) = outcome(&thermonav(&["convert", arg(&input), "--out", arg(&imu)]));
    assert_eq!(status, 0, "{stderr}");
    assert!(stderr.contains("ends in a partial message"), "{stderr}");
    let sidecar = sidecar_of(dir.path());
    let tail = sidecar["log"]["truncated_tail_bytes"].as_u64().unwrap();
    assert!(tail > 0 && tail < 100, "{tail}");
}

// A GNSS output that cannot be written (its folder is missing) fails the run before anything
// is read or written (a usage error since issue 38: outputs are checked first); an absurd
// --leap-seconds is a usage error, not an overflow.
#[test]
fn a_failed_ulog_conversion_writes_nothing_and_leap_seconds_are_bounded() {
    let dir = tempfile::tempdir().unwrap();
    let input = sample();
    let imu = dir.path().join("imu.csv");
    let gnss = dir.path().join("missing").join("gnss.csv");
    let (status, _, stderr) = convert_with_gnss(&input, &imu, &gnss);
    assert_eq!(status, 2, "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(
        files_in(dir.path()).is_empty(),
        "{:?}",
        files_in(dir.path())
    );
    let args = [
        "convert",
        arg(&input),
        "--out",
        arg(&imu),
        "--leap-seconds",
        "10000000000",
    ];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.contains("--leap-seconds"), "{stderr}");
    assert!(files_in(dir.path()).is_empty());
}
