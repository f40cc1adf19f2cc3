//! A PX4 user's thermal calibration: the chamber campaign's sweep written as a ULog of raw
//! sensor_gyro/sensor_accel (binary32 values, µs times, device ids), `characterize --sweep
//! LOG.ulg` against the same sweep as CSV, and `bank export` taking the log's device ids and
//! a chosen instance.

use crate::thermal::{campaign, characterize_with_sweep, read_json};
use crate::ulog_writer::{Record, data, format, log_start, subscribe_instance};
use crate::{arg, outcome, thermonav};
use std::path::Path;
use thermonav::imu::Channel;
use thermonav::stoch::bank::ModelBank;
use thermonav_io::{Strictness, read_imu_file};

const GYRO_ID: u32 = 2_490_378;
const ACCEL_ID: u32 = 1_310_988;

/// One raw sensor record: timestamp, timestamp_sample, device_id, x, y, z, temperature,
/// error_count.
fn raw_record(boot_us: u64, id: u32, v: [f64; 3], temperature_c: f64) -> Vec<u8> {
    let mut bytes = Record::default().u64(boot_us + 50).u64(boot_us).0;
    bytes.extend_from_slice(&id.to_le_bytes());
    let r = Record(bytes)
        .f32(v[0] as f32)
        .f32(v[1] as f32)
        .f32(v[2] as f32);
    let mut bytes = r.f32(temperature_c as f32).0;
    bytes.extend_from_slice(&0_u32.to_le_bytes());
    bytes
}

/// The IMU CSV at `csv` as a ULog of instance `instance` at `out`.
pub fn write_sweep_ulog(csv: &Path, out: &Path, instance: u8) {
    write_sweep_ulog_of(csv, out, instance, GYRO_ID);
}

/// As [`write_sweep_ulog`], with the gyro's device id `gyro_id`.
fn write_sweep_ulog_of(csv: &Path, out: &Path, instance: u8, gyro_id: u32) {
    let series = read_imu_file(csv, Strictness::Strict).unwrap();
    let mut log = log_start();
    for topic in ["sensor_gyro", "sensor_accel"] {
        let fields = "uint64_t timestamp;uint64_t timestamp_sample;uint32_t device_id;float x;\
                      float y;float z;float temperature;uint32_t error_count;";
        format(&mut log, &format!("{topic}:{fields}"));
    }
    subscribe_instance(&mut log, 0, "sensor_gyro", instance);
    subscribe_instance(&mut log, 1, "sensor_accel", instance);
    let temperature = series.temperature_c.as_ref().unwrap();
    for (k, (time, &temperature_c)) in series.time.iter().zip(temperature).enumerate() {
        let boot_us = 1_000_000 + (time.as_nanos() / 1_000) as u64;
        let column = |c: Channel| series.channel(c)[k];
        let gyro = [Channel::Gx, Channel::Gy, Channel::Gz].map(column);
        let accel = [Channel::Ax, Channel::Ay, Channel::Az].map(column);
        data(
            &mut log,
            0,
            &raw_record(boot_us, gyro_id, gyro, temperature_c),
        );
        data(
            &mut log,
            1,
            &raw_record(boot_us, ACCEL_ID, accel, temperature_c),
        );
    }
    std::fs::write(out, log).unwrap();
}

fn bank_of(path: &Path) -> ModelBank {
    serde_json::from_value(read_json(path)).unwrap()
}

// The ULog sweep and the CSV sweep are the same samples (to binary32 and whole µs): their
// curves agree to a thousandth of the band at every set point, and the log's sensors are
// recorded in the bank.
#[test]
fn a_ulog_sweep_calibrates_like_its_csv_and_keeps_the_device_ids() {
    let dir = tempfile::tempdir().unwrap();
    let tc = campaign(dir.path());
    let log = dir.path().join("sweep.ulg");
    write_sweep_ulog(&tc.join("imu_ramp.csv"), &log, 0);
    let (from_csv, from_log) = (dir.path().join("csv.json"), dir.path().join("ulog.json"));
    characterize_with_sweep(&tc, &from_csv, &tc.join("imu_ramp.csv"));
    characterize_with_sweep(&tc, &from_log, &log);
    let (a, b) = (
        bank_of(&from_csv).thermal.unwrap(),
        bank_of(&from_log).thermal.unwrap(),
    );
    for channel in Channel::ALL {
        let (ca, cb) = (&a.channels[&channel].bias, &b.channels[&channel].bias);
        for t in [-40.0, -20.0, 0.0, 20.0, 40.0, 60.0] {
            let (value, half_width) = ca.band_at(t);
            let gap = (cb.value_at(t) - value).abs();
            assert!(
                gap < 1e-3 * half_width,
                "{channel:?} at {t} °C: {gap} of {half_width}"
            );
        }
    }
    let devices = b.devices.expect("the ULog's sensors");
    assert_eq!(devices.instance, 0);
    assert_eq!(
        (devices.gyro_device_id, devices.accel_device_id),
        (Some(GYRO_ID), Some(ACCEL_ID))
    );
    assert!(a.devices.is_none());
    exports_take_the_device_ids_and_the_instance(dir.path(), &from_log);
}

fn export(bank: &Path, out: &Path, extra: &[&str]) -> (i32, String, String) {
    let mut args = vec!["bank", "export", arg(bank), "--out", arg(out)];
    args.extend_from_slice(extra);
    outcome(&thermonav(&args))
}

fn exports_take_the_device_ids_and_the_instance(dir: &Path, bank: &Path) {
    let params = dir.join("tc.params");
    let (status, _, stderr) = export(bank, &params, &["--format", "px4-tc"]);
    assert_eq!(status, 0, "{stderr}");
    let text = std::fs::read_to_string(&params).unwrap();
    assert!(
        text.contains(&format!("\tTC_G0_ID\t{GYRO_ID}\t6\n")),
        "{text}"
    );
    assert!(
        text.contains(&format!("\tTC_A0_ID\t{ACCEL_ID}\t6\n")),
        "{text}"
    );
    assert!(!text.contains("are 0") && !text.contains("is 0"), "{text}");
    let (status, _, stderr) = export(bank, &params, &["--format", "px4-tc", "--instance", "1"]);
    assert_eq!(status, 0, "{stderr}");
    let text = std::fs::read_to_string(&params).unwrap();
    assert!(
        text.contains("\tTC_G1_X0_2\t") && text.contains("\tTC_A1_TREF\t"),
        "{text}"
    );
    assert!(
        !text.contains("TC_G0_") && !text.contains("TC_A0_"),
        "{text}"
    );
    let tcal = dir.join("tcal.param");
    let (status, _, stderr) = export(
        bank,
        &tcal,
        &["--format", "ardupilot-tcal", "--instance", "2"],
    );
    assert_eq!(status, 0, "{stderr}");
    let text = std::fs::read_to_string(&tcal).unwrap();
    assert!(
        text.contains("INS_TCAL3_ENABLE") && !text.contains("INS_TCAL1_"),
        "{text}"
    );
    let (status, _, stderr) = export(
        bank,
        &tcal,
        &["--format", "ardupilot-tcal", "--instance", "3"],
    );
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("--instance") && stderr.contains("0..=2"),
        "{stderr}"
    );
}

/// `dir/s.csv`: `rows` samples at 10 Hz of a level static unit with small deterministic
/// variations, its temperature 20 °C rising by `warming_c_per_sample` each sample.
fn static_record(dir: &Path, rows: usize, warming_c_per_sample: f64) -> std::path::PathBuf {
    let mut text = String::from("t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c\n");
    for k in 1..=rows {
        let (a, b) = (1e-3 * (k as f64).sin(), 1e-3 * (0.7 * k as f64).cos());
        let t = 20.0 + k as f64 * warming_c_per_sample;
        text += &format!("{},{a},{b},{a},{b},{a},{},{t}\n", k as f64 * 0.1, b - 9.8);
    }
    let path = dir.join("s.csv");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_ulog_sweep_without_the_instance_is_refused_naming_the_topic() {
    let dir = tempfile::tempdir().unwrap();
    let csv = static_record(dir.path(), 2000, 0.0);
    let log = dir.path().join("s.ulg");
    write_sweep_ulog(&csv, &log, 0);
    let bank = dir.path().join("b");
    let (status, _, stderr) = outcome(&thermonav(&[
        "characterize",
        arg(&csv),
        "--temperature-c",
        "20",
        "--sweep",
        arg(&log),
        "--sweep-instance",
        "1",
        "--out",
        arg(&bank),
    ]));
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("s.ulg") && stderr.contains("no topic sensor_gyro of instance 1"),
        "{stderr}"
    );
}

#[test]
fn ulog_sweeps_of_different_sensors_are_refused_naming_their_ids() {
    let dir = tempfile::tempdir().unwrap();
    let csv = static_record(dir.path(), 12_000, 1e-3);
    let (one, two) = (dir.path().join("one.ulg"), dir.path().join("two.ulg"));
    write_sweep_ulog_of(&csv, &one, 0, GYRO_ID);
    write_sweep_ulog_of(&csv, &two, 0, GYRO_ID + 1);
    let bank = dir.path().join("b.json");
    let (status, _, stderr) = outcome(&thermonav(&[
        "characterize",
        arg(&csv),
        "--sweep",
        arg(&one),
        "--sweep",
        arg(&two),
        "--sweep-block-s",
        "60",
        "--out",
        arg(&bank),
    ]));
    assert_eq!(status, 1, "{stderr}");
    let ids = format!("0, {GYRO_ID}, {ACCEL_ID}; 0, {}, {ACCEL_ID}", GYRO_ID + 1);
    assert!(
        stderr.contains("different sensors") && stderr.contains(&ids),
        "{stderr}"
    );
    assert!(!bank.exists());
}
