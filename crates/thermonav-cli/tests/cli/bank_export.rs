//! `bank export`: a bank's thermal calibration as PX4 and ArduPilot parameter files.

use crate::{arg, imu_csv, outcome, thermonav, write_file};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use thermonav::imu::Channel;
use thermonav::stoch::thermal::{FitSettings, PowerOnRecord, ThermalCalibration, calibrate};

/// Quadratic bias curves over -10..+50 °C, two power-ons with their own offsets.
fn calibration() -> ThermalCalibration {
    let records = |channel: Channel| -> Vec<PowerOnRecord> {
        let k = channel.index() as f64;
        (0..24)
            .map(|i| {
                let power_on = (i % 2) as u32;
                let t = -10.0 + 60.0 * (i / 2) as f64 / 11.0;
                let bias = 1e-3 * (1.0 + k) + 2e-5 * (t - 20.0) - 3e-7 * (t - 20.0).powi(2);
                let offset = if power_on == 0 { 1e-5 } else { -1e-5 };
                let noise = 1e-8 * (3.7 * i as f64).sin();
                PowerOnRecord {
                    power_on,
                    temperature_c: t,
                    value: bias + offset + noise,
                }
            })
            .collect()
    };
    let observations: BTreeMap<Channel, Vec<PowerOnRecord>> =
        Channel::ALL.iter().map(|&c| (c, records(c))).collect();
    calibrate(&observations, FitSettings::default()).expect("calibrates")
}

/// A bank characterised from a static record, without a thermal calibration.
pub fn plain_bank(dir: &Path) -> PathBuf {
    let imu = write_file(
        dir,
        "imu.csv",
        &imu_csv(6000, 100.0, |c, t| {
            1e-3 * (t * (c as f64 + 5.0)).sin() - if c == 5 { 9.80665 } else { 0.0 }
        }),
    );
    let bank = dir.join("plain.json");
    let args = [
        "characterize",
        arg(&imu),
        "--temperature-c",
        "20",
        "--out",
        arg(&bank),
    ];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    bank
}

/// The plain bank with `calibration` as its `thermal` field.
fn thermal_bank(dir: &Path, calibration: &ThermalCalibration) -> PathBuf {
    let text = std::fs::read_to_string(plain_bank(dir)).unwrap();
    let mut bank: serde_json::Value = serde_json::from_str(&text).unwrap();
    bank["thermal"] = serde_json::to_value(calibration).unwrap();
    write_file(
        dir,
        "bank.json",
        &serde_json::to_string_pretty(&bank).unwrap(),
    )
}

#[test]
fn px4_export_writes_the_params_file_and_a_json_summary() {
    let dir = tempfile::tempdir().unwrap();
    let calibration = calibration();
    let bank = thermal_bank(dir.path(), &calibration);
    let out = dir.path().join("thermal.params");
    let args = [
        "bank",
        "export",
        arg(&bank),
        "--format",
        "px4-tc",
        "--out",
        arg(&out),
    ];
    let mut with_id = args.to_vec();
    with_id.extend(["--device-id", "2490378", "--json"]);
    let (status, stdout, stderr) = outcome(&thermonav(&with_id));
    assert_eq!(status, 0, "{stderr}");
    let summary: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(summary["format"], "px4_tc");
    assert_eq!(summary["parameters"], 34);
    assert_eq!(summary["sensors"][0]["sensor"], "gyro");
    assert_eq!(
        summary["sensors"][1]["temperature_range_c"],
        serde_json::json!([-10.0, 50.0])
    );
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains("1\t1\tTC_G0_ID\t2490378\t6\n"), "{text}");
    assert!(text.contains("1\t1\tTC_G_ENABLE\t1\t6\n"), "{text}");
    // At T = TREF PX4's offset is X0: the bank's curve there, to f32 rounding.
    let value = |name: &str| -> f64 {
        let line = text
            .lines()
            .find(|l| l.split('\t').nth(2) == Some(name))
            .unwrap();
        line.split('\t').nth(3).unwrap().parse().unwrap()
    };
    for (axis, channel) in [Channel::Ax, Channel::Ay, Channel::Az]
        .into_iter()
        .enumerate()
    {
        let expected = calibration.bias_at(channel, value("TC_A0_TREF")).unwrap();
        let x0 = value(&format!("TC_A0_X0_{axis}"));
        assert!(
            (x0 - expected).abs() <= 1e-7 * expected.abs(),
            "{x0} vs {expected}"
        );
    }
}

#[test]
fn ardupilot_export_writes_the_param_file_and_names_it() {
    let dir = tempfile::tempdir().unwrap();
    let bank = thermal_bank(dir.path(), &calibration());
    let out = dir.path().join("tcal.param");
    let args = [
        "bank",
        "export",
        arg(&bank),
        "--format",
        "ardupilot-tcal",
        "--out",
        arg(&out),
    ];
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    assert!(
        stdout.contains("written") && stdout.contains("tcal.param"),
        "{stdout}"
    );
    assert!(
        stdout.contains("TMIN..TMAX -10..50 °C, reference 35 °C"),
        "{stdout}"
    );
    let text = std::fs::read_to_string(&out).unwrap();
    let parameters: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(parameters.len(), 21, "{text}");
    assert!(
        parameters
            .iter()
            .all(|l| l.starts_with("INS_TCAL1_") && l.split(',').count() == 2)
    );
    assert!(
        parameters.contains(&"INS_TCAL1_ENABLE,1") && parameters.contains(&"INS_TCAL1_TMIN,-10")
    );
}
