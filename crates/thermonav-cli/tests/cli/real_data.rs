//! Real data end to end: the rtklibexplorer car drive (consumer MEMS IMU at 100 Hz, RTK GNSS at
//! 4 Hz) converted, then navigated through 10 s GNSS outages, against the RTK solution itself.
//!
//! Bounds from physics and the sensor class, not from our output:
//! - aided: the RTK positions are cm-level and the filter follows them at 4 Hz, so between
//!   outages (from 5 s after each one ends) the solution stays within 0.3 m RMS (lever arm and
//!   timing residuals included);
//! - a 10 s outage: a consumer MEMS unit aided before the outage keeps tilt errors ≲ 0.5° and
//!   accelerometer bias errors ≲ 5 mg, i.e. a horizontal acceleration error ≲ g·sin 0.5° + 5 mg
//!   ≈ 0.135 m/s², plus a velocity error ≲ 0.1 m/s: ½·0.135·10² + 0.1·10 ≈ 7.8 m. The mean over
//!   outages of the per-outage maximum must stay below 8 m.

use super::convert::{DRIVE, shared_data};
use crate::{arg, outcome, thermonav};
use std::path::Path;

fn run_ok(args: &[&str]) {
    let (status, _, stderr) = outcome(&thermonav(args));
    assert_eq!(status, 0, "{args:?}: {stderr}");
}

/// (t_s, lat_deg, lon_deg) of a canonical CSV.
fn positions(path: &Path) -> Vec<[f64; 3]> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').take(3).map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect()
}

/// Horizontal distance, m, of the solution (interpolated to `t`) from a fix.
fn error_at(solution: &[[f64; 3]], fix: &[f64; 3]) -> Option<f64> {
    let k = solution.partition_point(|p| p[0] < fix[0]);
    let (a, b) = (solution.get(k.checked_sub(1)?)?, solution.get(k)?);
    let w = (fix[0] - a[0]) / (b[0] - a[0]);
    let lat = a[1] + w * (b[1] - a[1]);
    let lon = a[2] + w * (b[2] - a[2]);
    let north = (lat - fix[1]).to_radians() * 6_371_000.0;
    let east = (lon - fix[2]).to_radians() * 6_371_000.0 * fix[1].to_radians().cos();
    Some(north.hypot(east))
}

#[test]
fn drive_0708_through_ten_second_outages() {
    let dir = tempfile::tempdir().unwrap();
    let (imu, gnss, out) = (
        dir.path().join("imu.csv"),
        dir.path().join("gnss.csv"),
        dir.path().join("sol.csv"),
    );
    let raw = shared_data(&format!("{DRIVE}/imu_1934.csv"));
    let pos = shared_data(&format!("{DRIVE}/gnss_1934_sf.pos"));
    run_ok(&[
        "convert",
        arg(&raw),
        "--imu-frame",
        "drive-frd",
        "--time-offset-s=-0.125",
        "--out",
        arg(&imu),
    ]);
    run_ok(&["convert", arg(&pos), "--out", arg(&gnss)]);
    let fixes = positions(&gnss);
    let first = fixes[0][0];
    let (start, duration, period, count) = (first + 100.0, 10.0, 70.0, 6);
    let spec = format!("every:{start},{duration},{period},{count}");
    let profile =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/profiles/drive_0708_imu.toml");
    for filter in ["ekf", "ukf"] {
        run_ok(&[
            "integrate",
            "--imu",
            arg(&imu),
            "--gnss",
            arg(&gnss),
            "--profile",
            arg(&profile),
            "--process-noise-scale",
            "10",
            "--velocity-sd-m-s",
            "0.1",
            "--lever-arm-m",
            "0,-0.05,0",
            "--filter",
            filter,
            "--outages",
            &spec,
            "--out",
            arg(&out),
            "--quiet",
        ]);
        let solution = positions(&out);
        let in_outage = |t: f64| {
            (0..count).any(|k| {
                let a = start + k as f64 * period;
                (a..a + duration).contains(&t)
            })
        };
        // The first seconds after an outage still carry its drift while the filter pulls back.
        let recovering = |t: f64| {
            (0..count).any(|k| {
                let end = start + k as f64 * period + duration;
                (end..end + 5.0).contains(&t)
            })
        };
        let mut maxima = vec![0.0f64; count];
        let mut aided = Vec::new();
        for fix in &fixes {
            let Some(e) = error_at(&solution, fix) else {
                continue;
            };
            if in_outage(fix[0]) {
                let k = ((fix[0] - start) / period).floor() as usize;
                maxima[k] = maxima[k].max(e);
            } else if fix[0] > solution[0][0] + 30.0 && !recovering(fix[0]) {
                aided.push(e);
            }
        }
        let mean_max = maxima.iter().sum::<f64>() / count as f64;
        let aided_rms = (aided.iter().map(|e| e * e).sum::<f64>() / aided.len() as f64).sqrt();
        assert!(
            maxima.iter().all(|m| *m > 0.0),
            "{filter}: every outage has fixes to compare"
        );
        assert!(
            mean_max < 8.0,
            "{filter}: mean per-outage maximum {mean_max} m ({maxima:?})"
        );
        assert!(aided_rms < 0.3, "{filter}: aided RMS {aided_rms} m");
    }
}
