//! Thermal calibration from sweeps alone: the legs of a real record against an independent
//! implementation, a lagging unit on a non-integer, jittered rate, the check against the
//! compensated record, ULog sweeps, and bad sweeps refused naming the file.

use crate::{arg, outcome, thermonav, write_file};
use rand::RngExt;
use serde_json::Value;
use std::fmt::Write as _;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};

/// The CATS record of `shared/data` (see its README, section 1.9).
fn cats_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/cats-tempcal/cats_temperature_calib.csv.gz")
}

/// The legs found by `bench/thermal_peers/cats.py`, an independent implementation of the
/// issue's leg rule in Python (`tools/oracles/cats_legs.json`).
fn cats_oracle() -> Value {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tools/oracles/cats_legs.json");
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Writes period `from..=to` (t_s) of the CATS record as a canonical IMU CSV (gyros from
/// mrad/s to rad/s).
fn write_cats_period(path: &Path, from: f64, to: f64) {
    let file = std::fs::File::open(cats_file()).expect("shared/ is beside the repository");
    let lines = BufReader::new(flate2::read::GzDecoder::new(file)).lines();
    let mut text = String::from("t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c\n");
    for line in lines.skip(1) {
        let line = line.unwrap();
        let f: Vec<&str> = line.split(',').collect();
        let t: f64 = f[0].parse().unwrap();
        if !(from..=to).contains(&t) {
            continue;
        }
        let g = |k: usize| f[k].parse::<f64>().unwrap() * 1e-3;
        let _ = writeln!(
            text,
            "{t},{:e},{:e},{:e},{},{},{},{}",
            g(4),
            g(5),
            g(6),
            f[1],
            f[2],
            f[3],
            f[11]
        );
    }
    std::fs::write(path, text).unwrap();
}

fn bank_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

// The real record's legs (three periods of a CATS tag, 1 Hz) are those of the Python
// implementation: the same turning points to the sample (the rule is exact arithmetic on the
// same samples; 1 s allows for a tie of the smoothed extreme) and spans to 0.01 °C (the oracle
// rounds to 1e-4, and the two means sum in other orders).
#[test]
fn the_legs_of_a_real_chamber_record_are_those_of_an_independent_implementation() {
    let dir = tempfile::tempdir().unwrap();
    let oracle = cats_oracle();
    for (name, period) in oracle["periods"].as_object().unwrap() {
        let from = period["from_t_s"].as_f64().unwrap();
        let to = period["to_t_s"].as_f64().unwrap();
        let csv = dir.path().join(format!("{name}.csv"));
        write_cats_period(&csv, from, to);
        let bank = dir.path().join(format!("{name}.json"));
        let (code, _, err) = outcome(&thermonav(&[
            "characterize",
            "--sweep",
            arg(&csv),
            "--out",
            arg(&bank),
        ]));
        assert_eq!(code, 0, "{err}");
        let ours = &bank_json(&bank)["thermal"]["legs"];
        let theirs = period["legs"].as_array().unwrap();
        assert_eq!(
            ours.as_array().unwrap().len(),
            theirs.len(),
            "{name}: {ours}"
        );
        for (a, b) in ours.as_array().unwrap().iter().zip(theirs) {
            let start = a["t_s"][0].as_f64().unwrap();
            let end = a["t_s"][1].as_f64().unwrap();
            assert!(
                (start - b["start_t_s"].as_f64().unwrap()).abs() <= 1.0,
                "{name} {a} {b}"
            );
            assert!(
                (end - b["end_t_s"].as_f64().unwrap()).abs() <= 1.0,
                "{name} {a} {b}"
            );
            let span = a["span_c"].as_f64().unwrap();
            assert!(
                (span - b["span_c"].as_f64().unwrap()).abs() < 0.01,
                "{name} {a} {b}"
            );
            let direction = if b["direction"] == "heating" {
                "warming"
            } else {
                "cooling"
            };
            assert_eq!(a["direction"], direction, "{name}");
        }
    }
}

/// The chamber program of the lag tests: 25 → 5 → 45 → 25 °C at `rate` °C/min.
fn program(t_s: f64, rate_c_per_min: f64) -> (f64, f64) {
    let r = rate_c_per_min / 60.0;
    let legs: [(f64, f64); 3] = [(25.0, 5.0), (5.0, 45.0), (45.0, 25.0)];
    let mut start = 0.0;
    for (from, to) in legs {
        let duration = (to - from).abs() / r;
        if t_s <= start + duration {
            let sign = (to - from).signum();
            return (from + sign * r * (t_s - start), sign * r);
        }
        start += duration;
    }
    (25.0, 0.0)
}

/// The true bias of the lagging unit: gx a quadratic in its structure's temperature, az a line
/// in the sensor's temperature (no lag), the others flat.
fn lagging_bias(channel: usize, sensor_c: f64, structure_c: f64) -> f64 {
    match channel {
        0 => 2e-4 * (structure_c - 20.0) + 4e-6 * (structure_c - 20.0).powi(2),
        5 => 1e-3 * (sensor_c - 20.0),
        _ => 0.0,
    }
}

/// A sweep of the lagging unit at 1.98 Hz with µs jitter: its structure follows the program's
/// temperature through a first-order lag of `lag_s` (dT_s/dt = (T − T_s)/lag, integrated
/// numerically), white noise of
/// 1e-4 (rad/s and m/s² alike) from the named generator, a level unit (az reads −9.81 on top).
fn lagging_sweep(dir: &Path, name: &str, lag_s: f64, seed: u64) -> PathBuf {
    let rate_hz = 1.98;
    let mut rng = thermonav::rng::named_rng(seed, "thermal lag sweep noise");
    let mut normal = || {
        // Box-Muller from two uniforms.
        let (u, v): (f64, f64) = (rng.random(), rng.random());
        (-2.0 * (1.0 - u).ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    };
    let duration = 20.0 / 2.0 * 60.0 + 40.0 / 2.0 * 60.0 + 20.0 / 2.0 * 60.0;
    let n = (duration * rate_hz) as usize;
    let mut text = String::from("t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c\n");
    let (mut structure, mut before) = (program(0.0, 2.0).0, (0.0, program(0.0, 2.0).0));
    for k in 0..n {
        let jitter = (normal() * 2e-6).clamp(-5e-6, 5e-6);
        let t = k as f64 / rate_hz + jitter;
        let (temp, _) = program(t, 2.0);
        let dt = t - before.0;
        if dt > 0.0 && lag_s > 0.0 {
            // Integrated with 100 explicit Euler steps per interval on the program itself (its
            // own turns included), independent of the product's closed form.
            let h = dt / 100.0;
            for j in 0..100 {
                let sensor = program(before.0 + j as f64 * h, 2.0).0;
                structure += h * (sensor - structure) / lag_s;
            }
        }
        before = (t, temp);
        let _ = write!(text, "{t:.6}");
        for c in 0..6 {
            let gravity = if c == 5 { -9.81 } else { 0.0 };
            let v = gravity + lagging_bias(c, temp, structure) + 1e-4 * normal();
            let _ = write!(text, ",{v:.9e}");
        }
        let _ = writeln!(text, ",{temp:.4}");
    }
    write_file(dir, name, &text)
}

fn characterize_sweeps(sweeps: &[&Path], bank: &Path) -> (i32, String, String) {
    let mut args = vec!["characterize"];
    for s in sweeps {
        args.extend(["--sweep", arg(s)]);
    }
    args.extend(["--out", arg(bank)]);
    outcome(&thermonav(&args))
}

// A unit whose gx structure lags its sensor through a first-order lag of 120 s, swept at
// 2 °C/min on a 1.98 Hz log with µs jitter: the lag model is chosen for gx by its held-out legs and τ's interval holds the
// truth; az, with no lag, keeps its line in T alone; the flat channels are left at order 0.
#[test]
fn a_lagging_unit_on_a_jittered_non_integer_rate_gets_its_lag() {
    let dir = tempfile::tempdir().unwrap();
    let tau = -120.0;
    let sweep = lagging_sweep(dir.path(), "cycle.csv", -tau, 1);
    let bank = dir.path().join("bank.json");
    let (code, out, err) = characterize_sweeps(&[&sweep], &bank);
    assert_eq!(code, 0, "{out}{err}");
    let thermal = &bank_json(&bank)["thermal"];
    assert_eq!(thermal["legs"].as_array().unwrap().len(), 3);
    let gx = &thermal["channels"]["gx"];
    assert_eq!(
        gx["selection"]["chosen"]["lag"], true,
        "{}",
        gx["selection"]
    );
    let lag = &gx["lagged"]["lag"];
    let (low, high) = (
        lag["tau_interval_s"][0].as_f64().unwrap(),
        lag["tau_interval_s"][1].as_f64().unwrap(),
    );
    assert!(low <= tau && tau <= high, "{lag}");
    // `--json` says the same in brief.
    let again = dir.path().join("again.json");
    let (code, out, err) = outcome(&thermonav(&[
        "characterize",
        "--sweep",
        arg(&sweep),
        "--out",
        arg(&again),
        "--json",
    ]));
    assert_eq!(code, 0, "{err}");
    let brief: Value = serde_json::from_str(&out).unwrap();
    let chosen = &brief["thermal"]["channels"]["gx"]["chosen_on_held_out"];
    assert_eq!(chosen["thermal_lag_s"], lag["tau_s"], "{chosen}");
    assert_eq!(brief["thermal"]["legs"], 3);
    assert_eq!(
        thermal["channels"]["az"]["selection"]["chosen"]["lag"],
        false
    );
    assert!(thermal["channels"]["az"]["bias"]["order"].as_u64().unwrap() >= 1);
    for flat in ["gy", "gz", "ax", "ay"] {
        let chosen = &thermal["channels"][flat]["selection"]["chosen"];
        assert_eq!(
            chosen["order"], 0,
            "{flat}: {}",
            thermal["channels"][flat]["selection"]
        );
    }
}

/// `bank check --json` of `record` against `bank`.
fn check_json(bank: &Path, record: &Path) -> Value {
    let (code, out, err) = outcome(&thermonav(&[
        "bank",
        "check",
        arg(bank),
        arg(record),
        "--json",
    ]));
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

// `compensate` and `bank check` take off the same thing: the 30 s block means of the
// compensated record scatter about their mean as the check's residuals do, within 5 % on every
// channel (the check evaluates the model at each block's mean temperature and rate, the
// compensation at every sample's). The lag model also predicts an unseen record of the unit,
// and its band covers most blocks.
#[test]
fn check_and_compensate_agree_and_the_lag_predicts_an_unseen_record() {
    let dir = tempfile::tempdir().unwrap();
    let fitted = lagging_sweep(dir.path(), "fitted.csv", 120.0, 1);
    let unseen = lagging_sweep(dir.path(), "unseen.csv", 120.0, 2);
    let bank = dir.path().join("bank.json");
    assert_eq!(characterize_sweeps(&[&fitted], &bank).0, 0);
    let check = check_json(&bank, &unseen);
    let out = dir.path().join("compensated.csv");
    let (code, _, err) = outcome(&thermonav(&[
        "compensate",
        arg(&unseen),
        "--bank",
        arg(&bank),
        "--out",
        arg(&out),
    ]));
    assert_eq!(code, 0, "{err}");
    assert!(dir.path().join("compensated.csv.json").exists());
    let compensated = thermonav_io::read_imu_file(&out, thermonav_io::Strictness::Strict).unwrap();
    let time: Vec<f64> = compensated.time.iter().map(|t| t.as_seconds()).collect();
    let ranges = thermonav::stoch::thermal::sweep_model::block_ranges(&time, 30.0);
    for channel in thermonav::imu::Channel::ALL {
        let c = &check["channels"][channel.name()];
        let column = compensated.channel(channel);
        let means: Vec<f64> = ranges
            .iter()
            .map(|&(a, b)| column[a..b].iter().sum::<f64>() / (b - a) as f64)
            .collect();
        let m = means.iter().sum::<f64>() / means.len() as f64;
        let rms = (means.iter().map(|x| (x - m).powi(2)).sum::<f64>() / means.len() as f64).sqrt();
        let expected = c["rms_after_offset_removed"].as_f64().unwrap();
        assert!(
            (rms / expected - 1.0).abs() < 0.05,
            "{}: compensated {rms} against the check's {expected}",
            channel.name()
        );
    }
    let gx = &check["channels"]["gx"];
    // The lag model takes off at least 90 % of gx's thermal error on the unseen record (RMS).
    let (before, after) = (
        gx["rms_before"].as_f64().unwrap(),
        gx["rms_after_offset_removed"].as_f64().unwrap(),
    );
    assert!(after < 0.1 * before, "{before} -> {after}");
    assert!(gx["coverage_offset_removed"].as_f64().unwrap() >= 0.8);
}

/// Two banks of the same samples, one read from a binary log (binary32 values, whole-µs
/// times): the same model is chosen for gx and az, and the curves agree to well within the
/// noise (1e-4 per sample).
fn assert_same_calibration(a: &Value, b: &Value) {
    for channel in ["gx", "az"] {
        let (ca, cb) = (
            &a["thermal"]["channels"][channel],
            &b["thermal"]["channels"][channel],
        );
        assert_eq!(
            ca["selection"]["chosen"], cb["selection"]["chosen"],
            "{channel}"
        );
        let (va, vb) = (
            &ca["bias"]["coefficients"][0],
            &cb["bias"]["coefficients"][0],
        );
        assert!(
            (va.as_f64().unwrap() - vb.as_f64().unwrap()).abs() < 1e-6,
            "{va} {vb}"
        );
    }
}

// A PX4 user's one log of the board warming: a ULog sweep alone calibrates as its CSV does.
#[test]
fn a_ulog_sweep_alone_calibrates_like_its_csv() {
    let dir = tempfile::tempdir().unwrap();
    let csv = lagging_sweep(dir.path(), "cycle.csv", 120.0, 3);
    let ulog = dir.path().join("cycle.ulg");
    crate::thermal_ulog::write_sweep_ulog(&csv, &ulog, 0);
    let (from_csv, from_ulog) = (dir.path().join("csv.json"), dir.path().join("ulg.json"));
    assert_eq!(characterize_sweeps(&[&csv], &from_csv).0, 0);
    let (code, _, err) = characterize_sweeps(&[&ulog], &from_ulog);
    assert_eq!(code, 0, "{err}");
    let (a, b) = (bank_json(&from_csv), bank_json(&from_ulog));
    assert_eq!(b["thermal"]["devices"]["instance"], 0);
    assert_same_calibration(&a, &b);
}

/// A sweep CSV of `rows` samples at 1 Hz with temperatures `temp(k)` and flat channels.
fn sweep_csv(dir: &Path, name: &str, rows: usize, temp: impl Fn(usize) -> String) -> PathBuf {
    let mut text = String::from("t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c\n");
    for k in 0..rows {
        let t = if k >= rows / 2 && name.contains("gap") {
            k as f64 + 5000.0
        } else {
            k as f64
        };
        let _ = writeln!(text, "{t},0.001,0,0,0,0,-9.81,{}", temp(k));
    }
    write_file(dir, name, &text)
}

// Bad sweeps: each is refused with exit 1, naming the file and what is wrong, and no bank is
// written.
#[test]
fn bad_sweeps_are_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let warming = |k: usize| format!("{:.3}", 10.0 + k as f64 * 0.01);
    let cases: Vec<(PathBuf, &str)> = vec![
        (
            sweep_csv(dir.path(), "narrow.csv", 3000, |k| {
                format!("{:.3}", 20.0 + k as f64 * 5e-4)
            }),
            "must cover at least 2 °C",
        ),
        (
            sweep_csv(dir.path(), "constant.csv", 3000, |_| "20".into()),
            "must cover at least 2 °C",
        ),
        (
            sweep_csv(dir.path(), "kelvin.csv", 3000, |k| {
                format!("{:.3}", 293.0 + k as f64 * 0.01)
            }),
            "temp_c",
        ),
        (
            sweep_csv(dir.path(), "nan.csv", 3000, |k| {
                if k == 7 { "nan".into() } else { warming(k) }
            }),
            "temp_c",
        ),
        (sweep_csv(dir.path(), "gap.csv", 3000, warming), "gap of"),
        (
            sweep_csv(dir.path(), "short.csv", 400, |k| {
                format!("{:.3}", 10.0 + k as f64 * 0.01)
            }),
            "at least 3",
        ),
    ];
    for (file, expected) in cases {
        let bank = dir.path().join("bank.json");
        let args = [
            "characterize",
            "--sweep",
            arg(&file),
            "--sweep-block-s",
            "200",
            "--out",
            arg(&bank),
        ];
        let (code, _, err) = outcome(&thermonav(&args));
        assert_eq!(code, 1, "{}: {err}", file.display());
        assert!(
            err.contains(file.file_name().unwrap().to_str().unwrap()),
            "{err}"
        );
        assert!(err.contains(expected), "{}: {err}", file.display());
        assert!(!bank.exists());
    }
}

/// A DataFlash record: the header 0xA3 0x95, the type, the packed fields.
fn dataflash_record(type_id: u8, fields: &[u8]) -> Vec<u8> {
    let mut out = vec![0xA3, 0x95, type_id];
    out.extend_from_slice(fields);
    out
}

/// A FMT record (format "BBnNZ") defining `type_id`.
fn dataflash_fmt(type_id: u8, length: u8, name: &str, format: &str, columns: &str) -> Vec<u8> {
    let padded = |text: &str, width: usize| {
        let mut bytes = text.as_bytes().to_vec();
        bytes.resize(width, 0);
        bytes
    };
    let mut fields = vec![type_id, length];
    fields.extend(padded(name, 4));
    fields.extend(padded(format, 16));
    fields.extend(padded(columns, 64));
    dataflash_record(128, &fields)
}

/// The samples of an IMU CSV as an ArduPilot DataFlash log of IMU records (format
/// "QBffffffIIfBBHH", the documented layout; no GPS, so times stay since boot), written from
/// the format's documentation as `tools/oracles/dataflash.py` does.
fn write_sweep_dataflash(csv: &Path, out: &Path) {
    let series = thermonav_io::read_imu_file(csv, thermonav_io::Strictness::Strict).unwrap();
    let mut log = dataflash_fmt(128, 89, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns");
    let columns = "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,EG,EA,T,GH,AH,GHz,AHz";
    log.extend(dataflash_fmt(
        130,
        3 + 8 + 1 + 24 + 8 + 4 + 2 + 4,
        "IMU",
        "QBffffffIIfBBHH",
        columns,
    ));
    let temperature = series.temperature_c.as_ref().unwrap();
    for (k, time) in series.time.iter().enumerate() {
        let mut fields = (1_000_000 + (time.as_nanos() / 1_000) as u64)
            .to_le_bytes()
            .to_vec();
        fields.push(0);
        for channel in thermonav::imu::Channel::ALL {
            fields.extend((series.channel(channel)[k] as f32).to_le_bytes());
        }
        fields.extend([0u8; 8]);
        fields.extend((temperature[k] as f32).to_le_bytes());
        fields.extend([1, 1]);
        fields.extend(100u16.to_le_bytes());
        fields.extend(100u16.to_le_bytes());
        log.extend(dataflash_record(130, &fields));
    }
    std::fs::write(out, log).unwrap();
}

// An ArduPilot user's log of the board warming and cooling: a DataFlash sweep alone calibrates
// as its CSV does (binary32 values, whole-µs times).
#[test]
fn a_dataflash_sweep_alone_calibrates_like_its_csv() {
    let dir = tempfile::tempdir().unwrap();
    let csv = lagging_sweep(dir.path(), "cycle.csv", 120.0, 4);
    let log = dir.path().join("cycle.bin");
    write_sweep_dataflash(&csv, &log);
    let (from_csv, from_log) = (dir.path().join("csv.json"), dir.path().join("bin.json"));
    assert_eq!(characterize_sweeps(&[&csv], &from_csv).0, 0);
    let (code, _, err) = characterize_sweeps(&[&log], &from_log);
    assert_eq!(code, 0, "{err}");
    let (a, b) = (bank_json(&from_csv), bank_json(&from_log));
    assert_eq!(a["thermal"]["legs"].as_array().unwrap().len(), 3);
    assert_eq!(b["thermal"]["legs"].as_array().unwrap().len(), 3);
    assert_same_calibration(&a, &b);
}

/// A quiet profile (white noise and a Gauss-Markov bias well below the lag's effect, a linear
/// bias in T on every channel) as TOML.
fn quiet_profile_toml() -> String {
    let mut text = String::from("name = \"quiet\"\nreference_temperature_c = 25.0\n");
    for c in ["gx", "gy", "gz"] {
        let _ = write!(
            text,
            "[channels.{c}]\nwhite_noise_deg_per_sqrt_h = 0.5\nbias_tempco_deg_s_per_c = 0.01\n\
             bias_gauss_markov = [{{ temperature_c = 20.0, correlation_time_s = 100.0, sigma_deg_h = 0.5 }}]\n"
        );
    }
    for c in ["ax", "ay", "az"] {
        let _ = write!(
            text,
            "[channels.{c}]\nwhite_noise_m_s_per_sqrt_h = 0.02\nbias_tempco_mg_per_c = 0.05\n\
             bias_gauss_markov = [{{ temperature_c = 20.0, correlation_time_s = 100.0, sigma_mg = 0.005 }}]\n"
        );
    }
    text
}

// `simulate chamber --temperature-file` replays a chamber program (cool, heat, cool at
// 2 °C/min with 10 min dwells) with the unit's structure lagging by `--thermal-lag-s`; the
// truth says the lag, the record follows the program, and `characterize --sweep` finds the
// lag of every gyro with an interval that holds the truth (the lag moves a gyro's bias by
// 36 deg/h per °C × 4 °C, against block noise of about 6 deg/h).
#[test]
fn a_replayed_chamber_program_with_a_lagging_unit_gives_its_lag_back() {
    let dir = tempfile::tempdir().unwrap();
    let program = write_file(
        dir.path(),
        "program.csv",
        "t_s,temp_c\n0,25\n900,-5\n1500,-5\n3300,55\n3900,55\n4800,25\n5400,25\n",
    );
    let profile = write_file(dir.path(), "quiet.toml", &quiet_profile_toml());
    let out = dir.path().join("campaign");
    let (code, stdout, err) = outcome(&thermonav(&[
        "simulate",
        "chamber",
        "--out",
        arg(&out),
        "--temperature-file",
        arg(&program),
        "--rate-hz",
        "2",
        "--thermal-lag-s",
        "120",
        "--profile",
        arg(&profile),
    ]));
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("imu_program.csv"), "{stdout}");
    let truth = bank_json(&out.join("truth.json"));
    let record = &truth["further_records"][0];
    assert_eq!(record["truth"]["chamber"]["kind"], "program");
    assert_eq!(record["truth"]["channels"]["az"]["thermal_lag_s"], 120.0);
    assert!(truth["files"].as_array().unwrap().is_empty());
    let bank = dir.path().join("bank.json");
    let (code, stdout, err) = characterize_sweeps(&[&out.join("imu_program.csv")], &bank);
    assert_eq!(code, 0, "{stdout}{err}");
    let thermal = &bank_json(&bank)["thermal"];
    assert_eq!(thermal["legs"].as_array().unwrap().len(), 3);
    for c in ["gx", "gy", "gz"] {
        let lag = &thermal["channels"][c]["lagged"]["lag"];
        let interval = &lag["tau_interval_s"];
        let (low, high) = (interval[0].as_f64().unwrap(), interval[1].as_f64().unwrap());
        assert!(low <= -120.0 && -120.0 <= high, "{c}: {lag}");
    }
    let refused = |extra: &[&str]| {
        let mut args = vec!["simulate", "chamber", "--out", arg(&out)];
        args.extend_from_slice(extra);
        outcome(&thermonav(&args))
    };
    let (code, _, err) = refused(&["--thermal-lag-s", "-1"]);
    assert!(code == 2 && err.contains("--thermal-lag-s"), "{err}");
    let (code, _, err) = refused(&["--temperature-file", arg(&program), "--ramp", "0:10:1"]);
    assert!(code == 2 && err.contains("--ramp"), "{err}");
}

// `bank check` says when a calibration makes a record worse, on the real record where it does:
// the CATS tag's first cooling leg (t_s 480..5521, 16 → 4.9 °C) calibrates gx with a slope
// that its long warming leg (5521..92460) does not follow (the bench's P0 fold: 138.6 deg/h of
// shape uncompensated, 265.9 compensated; PX4's and ArduPilot's cubics 241 and 262). The
// uncompensated shape is checked against the RMS of the blocks' observed means about their
// own mean, computed here.
#[test]
fn check_says_when_a_calibration_makes_an_unseen_leg_worse() {
    let dir = tempfile::tempdir().unwrap();
    let fitted = dir.path().join("cooling.csv");
    let unseen = dir.path().join("warming.csv");
    write_cats_period(&fitted, 480.0, 5521.0);
    write_cats_period(&unseen, 5521.0, 92460.0);
    let bank = dir.path().join("bank.json");
    let (code, _, err) = characterize_sweeps(&[&fitted], &bank);
    assert_eq!(code, 0, "{err}");
    let check = check_json(&bank, &unseen);
    for channel in thermonav::imu::Channel::ALL {
        let c = &check["channels"][channel.name()];
        let observed: Vec<f64> = (c["blocks"].as_array().unwrap().iter())
            .map(|b| b["observed"].as_f64().unwrap())
            .collect();
        let m = observed.iter().sum::<f64>() / observed.len() as f64;
        let shape =
            (observed.iter().map(|x| (x - m).powi(2)).sum::<f64>() / observed.len() as f64).sqrt();
        let reported = c["rms_before_offset_removed"].as_f64().unwrap();
        assert!(
            (reported / shape - 1.0).abs() < 1e-9,
            "{channel:?}: {reported} {shape}"
        );
    }
    let gx = &check["channels"]["gx"];
    let (before, after) = (
        gx["rms_before_offset_removed"].as_f64().unwrap(),
        gx["rms_after_offset_removed"].as_f64().unwrap(),
    );
    assert!(after > 1.5 * before, "{before} -> {after}");
    let (code, out, err) = outcome(&thermonav(&["bank", "check", arg(&bank), arg(&unseen)]));
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("gx: compensation makes this record worse"),
        "{out}"
    );
    // `bank show` says the choice saw one leg, and what that cannot show.
    let (code, shown, err) = outcome(&thermonav(&["bank", "show", arg(&bank)]));
    assert_eq!(code, 0, "{err}");
    assert!(shown.contains("(1 leg;"), "{shown}");
    assert!(
        shown.contains("95 % band from the held-out spread"),
        "{shown}"
    );
    assert!(
        shown.contains("note: where the blocks were left out a fifth at a time"),
        "{shown}"
    );
    // A channel left uncompensated (order 0) is not said to be made worse.
    let bank_doc = bank_json(&bank);
    for (name, c) in bank_doc["thermal"]["channels"].as_object().unwrap() {
        if c["selection"]["chosen"]["order"] == 0 {
            assert!(
                !out.contains(&format!("{name}: compensation makes")),
                "{out}"
            );
        }
    }
}

// CATS period P0 (a cool-down, then a day's warm-up, of one power-on): gx falls over time on
// both legs, so its slope against temperature flips sign between them, and `bank show` says
// it follows the clock; no other channel does. Oracle: `bench/thermal_peers/time_or_temperature.py`
// (numpy, 300 s blocks): +29.1 ± 4.4 deg/h per °C cooling, −25.8 ± 1.0 warming; thermonav's
// slopes on its own blocks must lie within those 95 % intervals.
#[test]
fn a_channel_that_drifts_with_time_is_named_on_a_real_record() {
    let dir = tempfile::tempdir().unwrap();
    let sweep = dir.path().join("p0.csv");
    write_cats_period(&sweep, 480.0, 92460.0);
    let bank = dir.path().join("bank.json");
    let (status, _, stderr) = characterize_sweeps(&[&sweep], &bank);
    assert_eq!(status, 0, "{stderr}");
    let (status, text, stderr) = outcome(&thermonav(&["bank", "show", arg(&bank)]));
    assert_eq!(status, 0, "{stderr}");
    let notes: Vec<&str> = text
        .lines()
        .filter(|l| l.contains("follows the clock"))
        .collect();
    assert_eq!(notes.len(), 1, "{text}");
    assert!(
        notes[0].starts_with("note: gx follows the clock"),
        "{}",
        notes[0]
    );
    // "... +29.520 ± 4.608 deg/h per °C on leg 1 (cooling), -25.756 ± 2.560 on leg 2 ...":
    // each slope is the word before a " ± ".
    let parts: Vec<&str> = notes[0].split(" ± ").collect();
    let slope = |k: usize| -> f64 {
        let word = parts[k].split_whitespace().last().unwrap();
        word.parse().unwrap()
    };
    let (cooling, warming) = (slope(0), slope(1));
    assert!((cooling - 29.1).abs() <= 4.4, "{cooling}");
    assert!((warming + 25.8).abs() <= 1.0, "{warming}");
}
