//! `bank export` of the noise model: each file read back by a parser written from the target's
//! documentation, its values equal to the bank's after the unit conversion, the factors
//! written here from first principles (1 deg = π/180 rad, 1 h = 3600 s, 1 mGal = 1e-5 m/s²);
//! and the refusals.

use crate::bank_export::plain_bank;
use crate::{arg, outcome, thermonav, write_file};
use serde_json::{Value, json};
use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

const CHANNELS: [&str; 6] = ["gx", "gy", "gz", "ax", "ay", "az"];
const GYRO: [usize; 3] = [0, 1, 2];
const ACCEL: [usize; 3] = [3, 4, 5];
/// rad/√s → deg/√h: (180/π) deg/rad × √(3600 s/h).
const DEG_PER_SQRT_H_PER_RAD_PER_SQRT_S: f64 = (180.0 / PI) * 60.0;
/// rad/s → deg/h.
const DEG_PER_H_PER_RAD_PER_S: f64 = (180.0 / PI) * 3600.0;
/// m/s/√s → m/s/√h.
const PER_SQRT_H_PER_PER_SQRT_S: f64 = 60.0;
/// m/s² → mGal (1 Gal = 1 cm/s²).
const MGAL_PER_M_S2: f64 = 1.0e5;
/// The record's rate in the fixture, Hz.
const RATE_HZ: f64 = 100.0;

/// The values set in entry `e` (0: 20 °C, 1: 40 °C) for channel `c`, SI.
#[derive(Debug, Clone, Copy)]
struct Truth {
    n: f64,
    b: f64,
    k: f64,
    sigma: f64,
    tc_s: f64,
}

fn truth(e: usize, c: usize) -> Truth {
    let (e, c) = ((1 + e) as f64, c as f64);
    Truth {
        n: (1.0 + c) * 1e-4 * e,
        b: (2.0 + c) * 1e-5 * e,
        k: (3.0 + c) * 1e-6 * e,
        sigma: (4.0 + c) * 1e-4 * e,
        tc_s: 100.0 * (1.0 + c) * e,
    }
}

/// The truth at 25 °C, a quarter of the way from 20 to 40 °C.
fn truth_at_25(c: usize) -> Truth {
    let (lo, hi) = (truth(0, c), truth(1, c));
    let lerp = |a: f64, b: f64| a + 0.25 * (b - a);
    Truth {
        n: lerp(lo.n, hi.n),
        b: lerp(lo.b, hi.b),
        k: lerp(lo.k, hi.k),
        sigma: lerp(lo.sigma, hi.sigma),
        tc_s: lerp(lo.tc_s, hi.tc_s),
    }
}

/// A characterised bank's entry at 20 °C, copied to 40 °C, both given the [`truth`] values.
fn two_entry_bank(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(plain_bank(dir)).unwrap();
    let mut bank: Value = serde_json::from_str(&text).unwrap();
    let first = bank["entries"][0].clone();
    let entries: Vec<Value> = (0..2).map(|e| entry_with_truth(&first, e)).collect();
    bank["entries"] = Value::Array(entries);
    write_bank(dir, "two.json", &bank)
}

fn entry_with_truth(first: &Value, e: usize) -> Value {
    let mut entry = first.clone();
    entry["temperature_c"] = json!(20.0 + 20.0 * e as f64);
    entry["preprocessing"]["input_rate_hz"] = json!(RATE_HZ);
    for (c, name) in CHANNELS.iter().enumerate() {
        let t = truth(e, c);
        let channel = &mut entry["channels"][*name];
        channel["allan"]["white_noise_density"] = json!(t.n);
        channel["allan"]["bias_instability"] = json!(t.b);
        channel["allan"]["rate_random_walk"] = json!(t.k);
        channel["gauss_markov"]["irregular_ml"] = json!({
            "status": "model", "correlation_time_s": t.tc_s, "sigma": t.sigma,
            "ci95_correlation_time_s": [t.tc_s / 2.0, null]
        });
    }
    entry
}

fn write_bank(dir: &Path, name: &str, bank: &Value) -> PathBuf {
    write_file(dir, name, &serde_json::to_string_pretty(bank).unwrap())
}

/// The two-entry bank with `edit` applied to channel `channel` of every entry.
fn edited_bank(dir: &Path, channel: &str, edit: impl Fn(&mut Value)) -> PathBuf {
    edited_channels(dir, &[channel], edit).0
}

/// The two-entry bank with `edit` applied to `channels` of every entry; its path and JSON.
fn edited_channels(dir: &Path, channels: &[&str], edit: impl Fn(&mut Value)) -> (PathBuf, Value) {
    let text = std::fs::read_to_string(two_entry_bank(dir)).unwrap();
    let mut bank: Value = serde_json::from_str(&text).unwrap();
    for entry in bank["entries"].as_array_mut().unwrap() {
        for channel in channels {
            edit(&mut entry["channels"][*channel]);
        }
    }
    (write_bank(dir, "edited.json", &bank), bank)
}

/// Exports `bank` as `format` to `out`: exit code and stderr.
fn export_to(bank: &Path, format: &str, out: &Path, extra: &[&str]) -> (i32, String) {
    let mut args = vec![
        "bank",
        "export",
        arg(bank),
        "--format",
        format,
        "--out",
        arg(out),
    ];
    args.extend_from_slice(extra);
    let (status, _, stderr) = outcome(&thermonav(&args));
    (status, stderr)
}

/// Runs the export; returns the file's text, failing the test on a non-zero exit.
fn exported(bank: &Path, format: &str, extra: &[&str]) -> String {
    let out = bank.with_file_name(format!("out-{format}"));
    let (status, stderr) = export_to(bank, format, &out, extra);
    assert_eq!(status, 0, "{stderr}");
    std::fs::read_to_string(out).unwrap()
}

/// The file `format` exports from the two-entry bank at `temperature_c`.
fn export_of_fixture(format: &str, temperature_c: &str, extra: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let mut args = vec!["--temperature-c", temperature_c];
    args.extend_from_slice(extra);
    exported(&two_entry_bank(dir.path()), format, &args)
}

/// Runs a failing export: its exit code and message; no output file is left.
fn refused(bank: &Path, format: &str, extra: &[&str]) -> (i32, String) {
    let out = bank.with_file_name("refused.out");
    let (status, stderr) = export_to(bank, format, &out, extra);
    assert!(!out.exists(), "no file after a refusal: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    (status, stderr)
}

fn close(found: f64, expected: f64, relative: f64, what: &str) {
    let scale = expected.abs().max(f64::MIN_POSITIVE);
    assert!(
        ((found - expected) / scale).abs() <= relative,
        "{what}: found {found}, expected {expected}"
    );
}

fn close_all(found: &[f64], expected: &[f64], relative: f64, what: &str) {
    assert_eq!(found.len(), expected.len(), "{what}: {found:?}");
    for (f, e) in found.iter().zip(expected) {
        close(*f, *e, relative, what);
    }
}

/// Values of a YAML file as the targets write them (YAML 1.1/1.2 block mappings of scalars
/// and flow sequences, `#` comments): the dotted key path → its numbers, or its string.
fn yaml_values(text: &str) -> BTreeMap<String, Result<Vec<f64>, String>> {
    let mut values = BTreeMap::new();
    let mut parents: Vec<(usize, String)> = Vec::new();
    for line in text.lines() {
        let content = strip_yaml_comment(line);
        if content.trim().is_empty() {
            continue;
        }
        let indent = content.len() - content.trim_start().len();
        let (key, value) = content.trim().split_once(':').expect("key: value");
        parents.retain(|(i, _)| *i < indent);
        let path: Vec<&str> = parents
            .iter()
            .map(|(_, k)| k.as_str())
            .chain([key])
            .collect();
        match value.trim() {
            "" => parents.push((indent, key.to_string())),
            v => {
                values.insert(path.join("."), yaml_scalar_or_list(v));
            }
        }
    }
    values
}

fn strip_yaml_comment(line: &str) -> &str {
    let mut quoted = false;
    for (k, ch) in line.char_indices() {
        match ch {
            '"' => quoted = !quoted,
            '#' if !quoted => return &line[..k],
            _ => {}
        }
    }
    line
}

/// YAML 1.1 floats need a '.' and a signed exponent (PyYAML); anything else is a string.
fn yaml_scalar_or_list(value: &str) -> Result<Vec<f64>, String> {
    let items: Vec<&str> = match value.strip_prefix('[').and_then(|v| v.strip_suffix(']')) {
        Some(inner) => inner.split(',').map(str::trim).collect(),
        None => vec![value],
    };
    let floats: Option<Vec<f64>> = items.iter().map(|i| yaml11_float(i)).collect();
    floats.ok_or_else(|| value.trim_matches('"').to_string())
}

fn yaml11_float(item: &str) -> Option<f64> {
    let (mantissa, exponent) = item.split_once(['e', 'E']).unwrap_or((item, "+0"));
    let signed = exponent.starts_with(['+', '-']);
    (mantissa.contains('.') && signed).then(|| item.parse().ok())?
}

fn numbers(values: &BTreeMap<String, Result<Vec<f64>, String>>, key: &str) -> Vec<f64> {
    values[key]
        .clone()
        .unwrap_or_else(|s| panic!("{key} is a string {s}"))
}

/// The truth of `pick` over `axes` at 20 °C.
fn at_20(axes: [usize; 3], pick: fn(Truth) -> f64) -> Vec<f64> {
    axes.iter().map(|&c| pick(truth(0, c))).collect()
}

fn largest(values: Vec<f64>) -> f64 {
    values.into_iter().fold(f64::MIN, f64::max)
}

fn geometric_mean_tc_s(of: impl Fn(usize) -> Truth) -> f64 {
    let product: f64 = (0..6).map(|c| of(c).tc_s).product();
    product.powf(1.0 / 6.0)
}

#[test]
fn kalibr_export_holds_continuous_si_densities_and_the_rate() {
    let text = export_of_fixture("kalibr", "20", &["--rostopic", "/imu/data"]);
    let v = yaml_values(&text);
    // Kalibr: rad/s/√Hz = rad/√s, one value per sensor (the largest axis).
    let expected = [
        ("gyroscope_noise_density", largest(at_20(GYRO, |t| t.n))),
        ("gyroscope_random_walk", largest(at_20(GYRO, |t| t.k))),
        (
            "accelerometer_noise_density",
            largest(at_20(ACCEL, |t| t.n)),
        ),
        ("accelerometer_random_walk", largest(at_20(ACCEL, |t| t.k))),
        ("update_rate", RATE_HZ),
    ];
    for (key, value) in expected {
        close_all(&numbers(&v, key), &[value], 1e-15, key);
    }
    assert_eq!(v["rostopic"], Err("/imu/data".to_string()));
    assert!(text.contains("continuous"), "{text}");
}

#[test]
fn kalibr_export_without_a_random_walk_writes_the_gauss_markov_stand_in() {
    let dir = tempfile::tempdir().unwrap();
    let bank = edited_bank(dir.path(), "gz", |ch| {
        ch["allan"]["rate_random_walk"] = Value::Null
    });
    let text = exported(&bank, "kalibr", &["--temperature-c", "40"]);
    // gz at 40 °C: the stand-in sigma √(2/Tc) (GM driving-noise density) is the largest.
    let gz = truth(1, 2);
    let stand_in = gz.sigma * (2.0 / gz.tc_s).sqrt();
    assert!(stand_in > truth(1, 1).k);
    close(
        numbers(&yaml_values(&text), "gyroscope_random_walk")[0],
        stand_in,
        1e-15,
        "stand-in",
    );
    assert!(
        text.contains("gz: no rate random walk K") && text.contains("sigma*sqrt(2/Tc)"),
        "{text}"
    );
}

#[test]
fn kalibr_export_of_white_noise_alone_writes_the_largest_random_walk_the_curve_allows() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, json) = edited_channels(dir.path(), &["gx", "gy", "gz"], |ch| {
        ch["allan"]["rate_random_walk"] = Value::Null;
        ch["gauss_markov"]["irregular_ml"] = json!({"status": "no_equivalent", "reason": "white"});
    });
    let text = exported(&bank, "kalibr", &["--temperature-c", "20"]);
    // IEEE Std 952: a rate random walk K gives sigma(tau) = K sqrt(tau/3); the largest K under
    // the curve's last point (tau, sigma) is sigma sqrt(3/tau).
    let bound = |name: &str| {
        let allan = &json["entries"][0]["channels"][name]["allan"];
        let last = |key: &str| {
            allan[key]
                .as_array()
                .unwrap()
                .last()
                .unwrap()
                .as_f64()
                .unwrap()
        };
        last("adev") * (3.0 / last("tau_s")).sqrt()
    };
    let expected = largest(["gx", "gy", "gz"].map(bound).to_vec());
    close(
        numbers(&yaml_values(&text), "gyroscope_random_walk")[0],
        expected,
        1e-15,
        "bound",
    );
    assert!(
        text.contains("the largest K the Allan curve allows"),
        "{text}"
    );
}

#[test]
fn kf_gins_export_holds_its_units_and_3_vectors() {
    let v = yaml_values(&export_of_fixture(
        "kf-gins",
        "20",
        &["--scale-factor-std-ppm", "1000"],
    ));
    let scaled = |axes, pick, factor: f64| at_20(axes, pick).iter().map(|x| x * factor).collect();
    let expected: [(&str, Vec<f64>); 7] = [
        (
            "imunoise.arw",
            scaled(GYRO, |t| t.n, DEG_PER_SQRT_H_PER_RAD_PER_SQRT_S),
        ),
        (
            "imunoise.vrw",
            scaled(ACCEL, |t| t.n, PER_SQRT_H_PER_PER_SQRT_S),
        ),
        (
            "imunoise.gbstd",
            scaled(GYRO, |t| t.sigma, DEG_PER_H_PER_RAD_PER_S),
        ),
        ("imunoise.abstd", scaled(ACCEL, |t| t.sigma, MGAL_PER_M_S2)),
        ("imunoise.gsstd", vec![1000.0; 3]),
        ("imunoise.asstd", vec![1000.0; 3]),
        (
            "imunoise.corrtime",
            vec![geometric_mean_tc_s(|c| truth(0, c)) / 3600.0],
        ),
    ];
    for (key, values) in expected {
        close_all(&numbers(&v, key), &values, 1e-14, key);
    }
}

#[test]
fn kf_gins_export_interpolates_linearly_between_entries() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "--temperature-c",
        "25",
        "--method",
        "linear",
        "--scale-factor-std-ppm",
        "500",
    ];
    let v = yaml_values(&exported(&two_entry_bank(dir.path()), "kf-gins", &args));
    let arw: Vec<f64> = GYRO
        .iter()
        .map(|&c| truth_at_25(c).n * DEG_PER_SQRT_H_PER_RAD_PER_SQRT_S)
        .collect();
    let abstd: Vec<f64> = ACCEL
        .iter()
        .map(|&c| truth_at_25(c).sigma * MGAL_PER_M_S2)
        .collect();
    close_all(&numbers(&v, "imunoise.arw"), &arw, 1e-14, "arw at 25 °C");
    close_all(
        &numbers(&v, "imunoise.abstd"),
        &abstd,
        1e-14,
        "abstd at 25 °C",
    );
    close(
        numbers(&v, "imunoise.corrtime")[0],
        geometric_mean_tc_s(truth_at_25) / 3600.0,
        1e-14,
        "corrtime",
    );
    // Nearest at 25 °C: the 20 °C entry as it is.
    let v = yaml_values(&export_of_fixture(
        "kf-gins",
        "25",
        &["--scale-factor-std-ppm", "500"],
    ));
    close_all(
        &numbers(&v, "imunoise.arw"),
        &at_20(GYRO, |t| t.n * DEG_PER_SQRT_H_PER_RAD_PER_SQRT_S),
        1e-14,
        "nearest",
    );
}

#[test]
fn ob_gins_export_holds_scalars_in_its_units() {
    let v = yaml_values(&export_of_fixture("ob-gins", "20", &[]));
    let expected = [
        (
            "imumodel.arw",
            largest(at_20(GYRO, |t| t.n)) * DEG_PER_SQRT_H_PER_RAD_PER_SQRT_S,
        ),
        (
            "imumodel.vrw",
            largest(at_20(ACCEL, |t| t.n)) * PER_SQRT_H_PER_PER_SQRT_S,
        ),
        (
            "imumodel.gbstd",
            largest(at_20(GYRO, |t| t.sigma)) * DEG_PER_H_PER_RAD_PER_S,
        ),
        (
            "imumodel.abstd",
            largest(at_20(ACCEL, |t| t.sigma)) * MGAL_PER_M_S2,
        ),
        (
            "imumodel.corrtime",
            geometric_mean_tc_s(|c| truth(0, c)) / 3600.0,
        ),
    ];
    for (key, value) in expected {
        close_all(&numbers(&v, key), &[value], 1e-14, key);
    }
    assert!(!v.contains_key("imumodel.gsstd"));
}

/// `'key': np.array([a, b, c]),` lines of a Python dict literal.
fn python_arrays(text: &str) -> BTreeMap<String, Vec<f64>> {
    let mut arrays = BTreeMap::new();
    for line in text.lines().map(|l| l.split('#').next().unwrap().trim()) {
        let Some((key, rest)) = line
            .strip_prefix('\'')
            .and_then(|l| l.split_once("': np.array(["))
        else {
            continue;
        };
        let inner = rest.split_once("])").expect("closed array").0;
        let values = inner
            .split(',')
            .map(|x| x.trim().parse().expect("a Python float"))
            .collect();
        arrays.insert(key.to_string(), values);
    }
    arrays
}

#[test]
fn gnss_ins_sim_export_holds_its_imu_err_keys_and_units() {
    let text = export_of_fixture("gnss-ins-sim", "20", &[]);
    assert!(
        text.contains("import numpy as np") && text.contains("imu_err = {"),
        "{text}"
    );
    let a = python_arrays(&text);
    let scaled = |axes, pick, factor: f64| at_20(axes, pick).iter().map(|x| x * factor).collect();
    let expected: [(&str, Vec<f64>); 8] = [
        ("gyro_b", vec![0.0; 3]),
        (
            "gyro_arw",
            scaled(GYRO, |t| t.n, DEG_PER_SQRT_H_PER_RAD_PER_SQRT_S),
        ),
        (
            "gyro_b_stability",
            scaled(GYRO, |t| t.sigma, DEG_PER_H_PER_RAD_PER_S),
        ),
        ("gyro_b_corr", at_20(GYRO, |t| t.tc_s)),
        ("accel_b", vec![0.0; 3]),
        (
            "accel_vrw",
            scaled(ACCEL, |t| t.n, PER_SQRT_H_PER_PER_SQRT_S),
        ),
        ("accel_b_stability", at_20(ACCEL, |t| t.sigma)),
        ("accel_b_corr", at_20(ACCEL, |t| t.tc_s)),
    ];
    assert_eq!(a.len(), expected.len());
    for (key, values) in expected {
        close_all(&a[key], &values, 1e-14, key);
    }
}

/// A QGroundControl `.params` file: `#` comments, then vehicle, component, name, value and
/// type (9 = REAL32), tab-separated.
fn qgc_parameters(text: &str) -> BTreeMap<String, f64> {
    let rows = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    rows.map(|line| {
        let fields: Vec<&str> = line.split('\t').collect();
        assert_eq!(fields.len(), 5, "{line}");
        assert_eq!((fields[0], fields[1], fields[4]), ("1", "1", "9"), "{line}");
        (fields[2].to_string(), fields[3].parse().unwrap())
    })
    .collect()
}

/// An ArduPilot `.parm` file: `#` comments, then `NAME VALUE` (or `NAME,VALUE`) lines.
fn ardupilot_parameters(text: &str) -> BTreeMap<String, f64> {
    let rows = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    rows.map(|line| {
        let fields: Vec<&str> = line
            .split([' ', ',', '\t'])
            .filter(|f| !f.is_empty())
            .collect();
        assert_eq!(fields.len(), 2, "{line}");
        (fields[0].to_string(), fields[1].parse().unwrap())
    })
    .collect()
}

/// Per-step values of an EKF stepping every `dt_s`: N/√dt and K/√dt at 20 °C.
fn per_step(dt_s: f64) -> [f64; 4] {
    let step = |values: Vec<f64>| largest(values) / dt_s.sqrt();
    [
        step(at_20(GYRO, |t| t.n)),
        step(at_20(ACCEL, |t| t.n)),
        step(at_20(GYRO, |t| t.k)),
        step(at_20(ACCEL, |t| t.k)),
    ]
}

type ParameterParser = fn(&str) -> BTreeMap<String, f64>;

#[test]
fn px4_ekf2_and_ardupilot_ek3_exports_hold_per_step_noise_for_their_steps() {
    let targets: [(&str, ParameterParser, [&str; 4], f64); 2] = [
        (
            "px4-ekf2",
            qgc_parameters,
            [
                "EKF2_GYR_NOISE",
                "EKF2_ACC_NOISE",
                "EKF2_GYR_B_NOISE",
                "EKF2_ACC_B_NOISE",
            ],
            0.010,
        ),
        (
            "ardupilot-ek3",
            ardupilot_parameters,
            [
                "EK3_GYRO_P_NSE",
                "EK3_ACC_P_NSE",
                "EK3_GBIAS_P_NSE",
                "EK3_ABIAS_P_NSE",
            ],
            0.012,
        ),
    ];
    for (format, parse, names, dt_s) in targets {
        let p = parse(&export_of_fixture(format, "20", &[]));
        assert_eq!(p.len(), names.len());
        for (name, expected) in names.iter().zip(per_step(dt_s)) {
            // 32-bit float storage: 2^-24 relative.
            close(p[*name], expected, 1e-7, name);
        }
    }
}

/// `'Property', [a b c]` of the `function(...)` call that assigns `variable` in a MATLAB script.
fn matlab_property(text: &str, variable: &str, property: &str) -> Vec<f64> {
    let start = text
        .find(&format!("{variable} = "))
        .expect("the assignment");
    let call = &text[start..start + text[start..].find(");").expect("the call ends")];
    let after = call
        .split_once(&format!("'{property}', ["))
        .expect("the property")
        .1;
    let inner = after.split_once(']').unwrap().0;
    inner
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect()
}

#[test]
fn matlab_export_sets_gyroparams_and_accelparams_in_si() {
    let text = export_of_fixture("matlab", "40", &[]);
    let at_40 = |axes: [usize; 3], pick: fn(Truth) -> f64| axes.map(|c| pick(truth(1, c))).to_vec();
    for (variable, axes) in [("gyro", GYRO), ("accel", ACCEL)] {
        close_all(
            &matlab_property(&text, variable, "NoiseDensity"),
            &at_40(axes, |t| t.n),
            0.0,
            "N",
        );
        close_all(
            &matlab_property(&text, variable, "BiasInstability"),
            &at_40(axes, |t| t.b),
            0.0,
            "B",
        );
        close_all(
            &matlab_property(&text, variable, "RandomWalk"),
            &at_40(axes, |t| t.k),
            0.0,
            "K",
        );
    }
    assert!(text.contains("gyro = gyroparams(") && text.contains("accel = accelparams("));
    assert!(
        text.contains("imuSensor('accel-gyro', 'SampleRate', 1.0e+2"),
        "{text}"
    );
}

#[test]
fn ros_export_holds_per_sample_variances_row_major() {
    let v = yaml_values(&export_of_fixture("ros-imu-covariance", "20", &[]));
    for (key, axes) in [
        ("angular_velocity_covariance", GYRO),
        ("linear_acceleration_covariance", ACCEL),
    ] {
        let mut expected = vec![0.0; 9];
        for (k, c) in axes.iter().enumerate() {
            // Discrete per-sample variance: density² × rate.
            expected[4 * k] = truth(0, *c).n.powi(2) * RATE_HZ;
        }
        close_all(&numbers(&v, key), &expected, 1e-14, key);
    }
    assert_eq!(numbers(&v, "orientation_covariance")[0], -1.0);
}

#[test]
fn export_outside_the_range_is_refused_for_nearest_and_linear() {
    let dir = tempfile::tempdir().unwrap();
    let bank = two_entry_bank(dir.path());
    for (t, method) in [("60", "nearest"), ("-5", "linear")] {
        let (status, stderr) =
            refused(&bank, "kalibr", &["--temperature-c", t, "--method", method]);
        assert_eq!(status, 1, "{stderr}");
        assert!(
            stderr.contains(&format!("{t} °C is outside the bank's range 20 to 40 °C")),
            "{stderr}"
        );
    }
    let (status, stderr) = refused(&bank, "kalibr", &[]);
    assert_eq!(status, 1);
    assert!(
        stderr.contains("give the operating temperature (--temperature-c)"),
        "{stderr}"
    );
}

#[test]
fn export_of_a_missing_bank_or_a_missing_term_names_it() {
    let dir = tempfile::tempdir().unwrap();
    let (status, stderr) = refused(&dir.path().join("nope.json"), "kalibr", &[]);
    assert_eq!(status, 1);
    assert!(stderr.contains("nope.json"), "{stderr}");
    let bank = edited_bank(dir.path(), "gy", |ch| {
        ch["allan"]["white_noise_density"] = Value::Null;
        ch["allan"]["absent_terms"] = json!({"white_noise_density": "no region of slope -0.5"});
    });
    let (status, stderr) = refused(&bank, "kalibr", &["--temperature-c", "20"]);
    assert_eq!(status, 1);
    assert!(
        stderr.contains("kalibr needs the white-noise density N (ARW/VRW) of gy at 20 °C")
            && stderr.contains("no region of slope -0.5"),
        "{stderr}"
    );
    let bank = edited_bank(dir.path(), "ax", |ch| {
        ch["gauss_markov"]["irregular_ml"] =
            json!({"status": "no_equivalent", "reason": "not significant"});
    });
    // Since issue 38 (row 11) a missing Gauss-Markov model is replaced by the stand-in that
    // reproduces the Allan minimum, named in the file with the bank's reason
    // (tests/cli/frictions.rs checks its values).
    let text = exported(&bank, "gnss-ins-sim", &["--temperature-c", "20"]);
    assert!(
        text.contains("# ax: no Gauss-Markov model in the bank (not significant); stand-in"),
        "{text}"
    );
    let (status, stderr) = refused(
        &two_entry_bank(dir.path()),
        "kf-gins",
        &["--temperature-c", "20"],
    );
    assert_eq!(status, 2, "a missing option is a usage error");
    assert!(stderr.contains("--scale-factor-std-ppm"), "{stderr}");
}

#[test]
fn export_never_overwrites_the_bank() {
    let dir = tempfile::tempdir().unwrap();
    let bank = two_entry_bank(dir.path());
    let before = std::fs::read(&bank).unwrap();
    let (status, stderr) = export_to(&bank, "kalibr", &bank, &["--temperature-c", "20"]);
    assert_eq!(status, 2, "a usage error, before any file is read");
    assert!(stderr.contains("would overwrite the input"), "{stderr}");
    assert_eq!(std::fs::read(&bank).unwrap(), before);
}

#[test]
fn export_options_of_the_other_kind_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let bank = two_entry_bank(dir.path());
    let (status, stderr) = refused(
        &bank,
        "kalibr",
        &["--temperature-c", "20", "--instance", "1"],
    );
    assert_eq!(status, 2);
    assert!(
        stderr.contains("--instance does not apply to --format kalibr"),
        "{stderr}"
    );
    let (status, stderr) = refused(&bank, "px4-tc", &["--temperature-c", "20"]);
    assert_eq!(status, 2);
    assert!(
        stderr.contains("--temperature-c does not apply to --format px4-tc"),
        "{stderr}"
    );
}

#[test]
fn linear_export_drops_a_term_that_one_of_the_two_entries_lacks() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(two_entry_bank(dir.path())).unwrap();
    let mut bank: Value = serde_json::from_str(&text).unwrap();
    bank["entries"][1]["channels"]["gz"]["allan"]["rate_random_walk"] = Value::Null;
    let bank = write_bank(dir.path(), "one_side.json", &bank);
    let args = ["--temperature-c", "25", "--method", "linear"];
    let text = exported(&bank, "matlab", &args);
    // gz's K exists at 20 °C only: absent at 25 °C, so MATLAB's RandomWalk is 0 and gx, gy
    // are interpolated.
    let expected = [truth_at_25(0).k, truth_at_25(1).k, 0.0];
    close_all(
        &matlab_property(&text, "gyro", "RandomWalk"),
        &expected,
        1e-14,
        "K",
    );
    assert!(text.contains("gz: no rate random walk K"), "{text}");
}

// Issue 37 row 11: a white noise of 1e300 (finite in the bank) overflows the autopilots'
// 32-bit float parameters; the export is refused naming the parameter, and nothing is written
// (it used to write `EKF2_GYR_NOISE inf`, exit 0).
#[test]
fn ekf_exports_refuse_a_value_beyond_a_32_bit_float() {
    let dir = tempfile::tempdir().unwrap();
    let bank = edited_bank(dir.path(), "gx", |channel| {
        channel["allan"]["white_noise_density"] = json!(1e300);
    });
    for (format, name) in [
        ("px4-ekf2", "EKF2_GYR_NOISE"),
        ("ardupilot-ek3", "EK3_GYRO_P_NSE"),
    ] {
        let (status, stderr) = refused(&bank, format, &["--temperature-c", "20"]);
        assert_eq!(status, 1, "{format}: {stderr}");
        assert!(
            stderr.contains(name)
                && stderr.contains("cannot be stored as a 32-bit float parameter"),
            "{format}: {stderr}"
        );
    }
}
