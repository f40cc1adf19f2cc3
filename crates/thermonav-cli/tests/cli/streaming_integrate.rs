//! `integrate` streamed (issue 18, bounded memory): the IMU read as a stream and the files
//! written as the filter goes give the whole-record path's files byte for byte (the oracle:
//! `--in-memory`, which reads the record whole and writes the kept solution with the
//! whole-solution writers), and bad data met on the way leaves no output.

use crate::{arg, outcome, thermonav};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// A 240 s vessel run at 17 °C (`imu.csv`, `gnss.csv`, `reference.csv`) and a sensor profile.
fn vessel(dir: &Path) -> (PathBuf, PathBuf) {
    let vessel = dir.join("vessel");
    let profile = dir.join("profile.toml");
    let seeded = ["--duration-s", "240", "--seed", "4", "--quiet"];
    let mut simulate = vec!["simulate", "vessel", "--out", arg(&vessel)];
    simulate.extend(seeded);
    let profile_args = ["simulate", "profile", "--out", arg(&profile), "--quiet"];
    for args in [&simulate[..], &profile_args[..]] {
        let (status, _, stderr) = outcome(&thermonav(args));
        assert_eq!(status, 0, "{args:?}: {stderr}");
    }
    (vessel, profile)
}

/// `integrate` of `imu` with the vessel's GNSS and `profile`, writing `out`, with `extra`:
/// exit code, the JSON (when it succeeded) and stderr.
fn integrate(
    imu: &Path,
    vessel: &Path,
    profile: &Path,
    out: &Path,
    extra: &[&str],
) -> (i32, Value, String) {
    let gnss = vessel.join("gnss.csv");
    let mut args = vec![
        "integrate",
        "--imu",
        arg(imu),
        "--gnss",
        arg(&gnss),
        "--profile",
        arg(profile),
        "--lever-arm-m",
        "0.3,0,-2.5",
        "--out",
        arg(out),
        "--json",
        "--quiet",
    ];
    args.extend(extra);
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    let json = serde_json::from_str(&stdout).unwrap_or(Value::Null);
    (status, json, stderr)
}

/// The files of a solution written to `out` (the smoothed ones when asked for).
fn files_of(out: &Path, smoothed: bool) -> Vec<PathBuf> {
    let stem = out.with_extension("");
    let mut suffixes = vec![".csv", ".states.csv", ".innovations.csv"];
    if smoothed {
        suffixes.extend([".smoothed.csv", ".smoothed.states.csv"]);
    }
    suffixes
        .iter()
        .map(|s| PathBuf::from(format!("{}{s}", stem.display())))
        .collect()
}

/// The JSON without what differs between two runs of the same data: wall time and the
/// files' names.
fn comparable(mut json: Value) -> Value {
    let object = json.as_object_mut().unwrap();
    for key in [
        "processing_time_s",
        "real_time_factor",
        "files",
        "imu_reading",
    ] {
        object.remove(key);
    }
    json
}

// Four runs that reach every part of the streamed path (alignment from GNSS with the head
// read in doubling spans, the reference start, outages, the EKF and the UKF, solution and
// covariance at 200 Hz, the smoother's history): each streamed run's files are those of the
// whole-record run byte for byte, and so is its report (innovation statistics accumulated
// record by record against those of the kept innovations).
#[test]
fn streamed_integrate_writes_the_whole_record_runs_files_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let (vessel, profile) = vessel(dir.path());
    let imu = vessel.join("imu.csv");
    let reference = vessel.join("reference.csv");
    let runs: [(&str, Vec<&str>); 4] = [
        ("aligned", vec!["--outages", "60+30,150+20"]),
        (
            "reference",
            vec![
                "--initial-from",
                arg(&reference),
                "--no-heading",
                "--no-velocity",
                "--outages",
                "every:60,20,100,2",
                "--covariance-rate-hz",
                "200",
                "--output-rate-hz",
                "200",
            ],
        ),
        ("ukf", vec!["--filter", "ukf", "--outages", "100+30"]),
        ("smoothed", vec!["--smooth", "--outages", "120+60"]),
    ];
    for (name, extra) in runs {
        let streamed = dir.path().join(format!("{name}_streamed.csv"));
        let whole = dir.path().join(format!("{name}_whole.csv"));
        let (status, streamed_json, stderr) = integrate(&imu, &vessel, &profile, &streamed, &extra);
        assert_eq!(status, 0, "{name}: {stderr}");
        assert_eq!(streamed_json["imu_reading"], "streamed", "{name}");
        let mut in_memory = extra.clone();
        in_memory.push("--in-memory");
        let (status, whole_json, stderr) = integrate(&imu, &vessel, &profile, &whole, &in_memory);
        assert_eq!(status, 0, "{name}: {stderr}");
        assert_eq!(whole_json["imu_reading"], "whole", "{name}");
        let smoothed = name == "smoothed";
        for (a, b) in files_of(&streamed, smoothed)
            .iter()
            .zip(files_of(&whole, smoothed))
        {
            let (a_bytes, b_bytes) = (std::fs::read(a).unwrap(), std::fs::read(&b).unwrap());
            assert!(
                a_bytes.len() > 1000,
                "{name}: {} is nearly empty",
                a.display()
            );
            assert!(
                a_bytes == b_bytes,
                "{name}: {} differs from {}",
                a.display(),
                b.display()
            );
        }
        assert_eq!(comparable(streamed_json), comparable(whole_json), "{name}");
    }
}

/// `imu.csv` of the vessel with line `line` (1-based, the header is line 1) replaced by
/// `replacement` lines, written to `dir/name`.
fn edited_imu(
    vessel: &Path,
    dir: &Path,
    name: &str,
    lines: std::ops::Range<usize>,
    with: &str,
) -> PathBuf {
    let text = std::fs::read_to_string(vessel.join("imu.csv")).unwrap();
    let mut out: Vec<&str> = Vec::new();
    for (k, line) in text.lines().enumerate() {
        match lines.contains(&(k + 1)) {
            true if k + 1 == lines.start && !with.is_empty() => out.push(with),
            true => {}
            false => out.push(line),
        }
    }
    let path = dir.join(name);
    std::fs::write(&path, out.join("\n") + "\n").unwrap();
    path
}

/// Every file in `dir`, for a check that a failed run left nothing (hidden temporaries too).
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

// A bad row in the middle of the IMU file (line 30 000 of 48 001, two minutes after the
// alignment) is refused with the file and line, exit 1, and no output file or temporary is
// left; so is a 1.5 s gap in the middle (300 rows removed at 200 Hz), which the streamed
// filter refuses when it arrives, after it has written lines into its temporary files.
#[test]
fn bad_data_in_the_middle_of_a_streamed_imu_names_it_and_leaves_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let (vessel, profile) = vessel(dir.path());
    let out_dir = dir.path().join("out");
    std::fs::create_dir(&out_dir).unwrap();
    let out = out_dir.join("sol.csv");
    let bad_row = edited_imu(
        &vessel,
        dir.path(),
        "bad_row.csv",
        30_000..30_001,
        "150.0,0.1,x,0,0,0,-9.8,17",
    );
    let (status, _, stderr) = integrate(&bad_row, &vessel, &profile, &out, &[]);
    assert_eq!(status, 1, "{stderr}");
    assert!(stderr.contains("bad_row.csv:30000"), "{stderr}");
    assert_eq!(listing(&out_dir), Vec::<String>::new());
    let gap = edited_imu(&vessel, dir.path(), "gap.csv", 30_000..30_300, "");
    let (status, _, stderr) = integrate(&gap, &vessel, &profile, &out, &[]);
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("gap.csv") && stderr.contains("gap of 1.5"),
        "{stderr}"
    );
    assert_eq!(listing(&out_dir), Vec::<String>::new());
}
