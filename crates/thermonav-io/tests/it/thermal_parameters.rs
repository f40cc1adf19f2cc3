//! The exported parameter files read back as each autopilot reads them: a parser of the file's
//! text, then the target's own polynomial, reference and clamping evaluated in 32-bit floats
//! as the autopilot does (PX4 `calc_thermal_offsets_3D`; ArduPilot `polynomial_eval` and
//! `correct_sensor`, re-implemented here from their description), against the bank's
//! `ThermalCalibration::bias_at` at every temperature of the data range and beyond it.
//!
//! # Tolerance
//! Both autopilots store every value as a 32-bit float and compute in 32-bit floats, so the
//! read-back differs from the f64 curve by rounding: each stored coefficient by up to ε/2
//! relative (ε = 2⁻²⁴ ≈ 6·10⁻⁸), each product and sum by ε/2 of a partial sum no larger than
//! Σ_k |X_k| |dT|^k, and the temperature itself (an f32 reading, f32 TMIN/TMAX) by ε/2 of its
//! magnitude, which moves the curve by its slope times that. The bound asserted is 8 ε times
//! (Σ_k |X_k| |dT|^k + |T|max · Σ_k k |X_k| |dT|^(k−1)): about 5·10⁻⁷ of the terms, a few
//! times the worst case of the rounding above and far below any error of convention (a wrong
//! power, reference, scale, sign or clamp moves the value by 10⁻³ of it or more).

use std::collections::BTreeMap;
use thermonav::imu::Channel;
use thermonav::stoch::thermal::{FitSettings, PowerOnRecord, ThermalCalibration, calibrate};
use thermonav_io::thermal_parameters::{
    ExportError, ExportTarget, ardupilot_parameters, px4_parameters, reexpanded,
    write_parameter_file,
};

const EPSILON_F32: f64 = 1.0 / 16_777_216.0;

/// Cubic bias curves about 20 °C, channel unit per °C^k: gyros in rad/s, accelerometers in m/s².
fn true_curve(channel: Channel) -> [f64; 4] {
    let k = channel.index() as f64;
    match channel.index() < 3 {
        true => [2e-3 - 1e-3 * k, 3e-5 + 1e-5 * k, -4e-7, 5e-9 * (1.0 + k)],
        false => [0.05 - 0.03 * (k - 3.0), 1e-3, -2e-5 * (k - 2.0), 3e-7],
    }
}

fn cubic_at(c: [f64; 4], temperature_c: f64) -> f64 {
    let d = temperature_c - 20.0;
    c[0] + d * (c[1] + d * (c[2] + d * c[3]))
}

/// Three power-ons sweeping -20..+60 °C, each with its own offset, and a small deterministic
/// noise (so the fit has residual).
fn records(channel: Channel) -> Vec<PowerOnRecord> {
    let scale = true_curve(channel)[1].abs();
    let sweeps: [(u32, f64, f64, f64); 3] = [
        (1, -20.0, 60.0, 1.0),
        (2, -15.0, 55.0, -0.4),
        (3, -10.0, 60.0, -0.6),
    ];
    let mut out = Vec::new();
    for (power_on, from_c, to_c, offset) in sweeps {
        for step in 0..=16 {
            let temperature_c = from_c + (to_c - from_c) * step as f64 / 16.0;
            let noise = 1e-3 * scale * (7.3 * step as f64 + power_on as f64).sin();
            out.push(PowerOnRecord {
                power_on,
                temperature_c,
                value: cubic_at(true_curve(channel), temperature_c) + offset * scale + noise,
            });
        }
    }
    out
}

fn calibration() -> ThermalCalibration {
    let observations: BTreeMap<Channel, Vec<PowerOnRecord>> =
        Channel::ALL.iter().map(|&c| (c, records(c))).collect();
    // Fitted about 25 °C: neither PX4's TREF (the range's middle, 20 °C) nor ArduPilot's 35 °C,
    // so both files need the re-expansion.
    let settings = FitSettings {
        reference_temperature_c: Some(25.0),
        ..FitSettings::default()
    };
    let calibration = calibrate(&observations, settings).expect("calibrates");
    assert_eq!(calibration.power_ons, 3);
    assert!(
        calibration
            .channels
            .values()
            .all(|c| c.power_on_offsets.len() == 3)
    );
    calibration
}

/// 50 temperatures across the data range and 6 outside it, °C.
fn temperatures_c(range_c: [f64; 2]) -> Vec<f64> {
    let [low, high] = range_c;
    let mut out: Vec<f64> = (0..50)
        .map(|k| low + (high - low) * k as f64 / 49.0)
        .collect();
    out.extend([
        low - 30.0,
        low - 5.0,
        low - 0.01,
        high + 0.01,
        high + 5.0,
        high + 40.0,
    ]);
    out
}

/// A parsed parameter file: name → value (f32, as the autopilot holds it).
type Parsed = BTreeMap<String, f32>;

/// A QGroundControl `.params` file: `#` comments; vehicle id, component id, name, value,
/// MAV_PARAM_TYPE (6 = INT32, 9 = REAL32), tab-separated.
fn parse_qgc_params(text: &str) -> Parsed {
    let mut out = Parsed::new();
    for line in text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
    {
        let fields: Vec<&str> = line.split('\t').collect();
        assert_eq!(fields.len(), 5, "{line}");
        assert_eq!((fields[0], fields[1]), ("1", "1"), "{line}");
        let value = match fields[4] {
            "6" => fields[3].parse::<i32>().expect("an int32") as f32,
            "9" => fields[3].parse::<f32>().expect("a float"),
            other => panic!("type {other} in {line}"),
        };
        assert!(out.insert(fields[2].to_string(), value).is_none(), "{line}");
    }
    out
}

/// A Mission Planner `.param` file: `#` comments, `NAME,VALUE` lines.
fn parse_mission_planner_param(text: &str) -> Parsed {
    let mut out = Parsed::new();
    for line in text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
    {
        let (name, value) = line.split_once(',').expect("NAME,VALUE");
        let value: f32 = value.parse().expect("a number");
        assert!(out.insert(name.to_string(), value).is_none(), "{line}");
    }
    out
}

fn get(parsed: &Parsed, name: &str) -> f32 {
    *parsed.get(name).unwrap_or_else(|| panic!("{name} missing"))
}

/// 8 ε (Σ |X_k| |d|^k + |T|max Σ k |X_k| |d|^(k−1)) (module docs).
fn rounding_bound(x: [f64; 4], d: f64, temperature_magnitude_c: f64) -> f64 {
    let terms: f64 = (0..4).map(|k| x[k].abs() * d.abs().powi(k as i32)).sum();
    let slope: f64 = (1..4)
        .map(|k| k as f64 * x[k].abs() * d.abs().powi(k as i32 - 1))
        .sum();
    8.0 * EPSILON_F32 * (terms + temperature_magnitude_c * slope)
}

/// PX4's offset of one axis: X0 + X1 dT + X2 dT² + X3 dT³, dT = clamp(T, TMIN, TMAX) − TREF,
/// in f32.
fn px4_offset(parsed: &Parsed, prefix: &str, axis: usize, temperature_c: f32) -> (f32, f32) {
    let (tmin, tmax, tref) = (
        get(parsed, &format!("{prefix}_TMIN")),
        get(parsed, &format!("{prefix}_TMAX")),
        get(parsed, &format!("{prefix}_TREF")),
    );
    let dt = if temperature_c > tmax {
        tmax - tref
    } else if temperature_c < tmin {
        tmin - tref
    } else {
        temperature_c - tref
    };
    let x = |k: usize| get(parsed, &format!("{prefix}_X{k}_{axis}"));
    (
        x(0) + x(1) * dt + x(2) * (dt * dt) + x(3) * (dt * dt * dt),
        dt,
    )
}

fn px4_coefficients(parsed: &Parsed, prefix: &str, axis: usize) -> [f64; 4] {
    std::array::from_fn(|k| f64::from(get(parsed, &format!("{prefix}_X{k}_{axis}"))))
}

#[test]
fn px4_parameters_read_back_as_the_bank_curve_with_px4_clamping() {
    let calibration = calibration();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("tc.params");
    let file = px4_parameters(
        &calibration,
        ExportTarget {
            instance: 0,
            gyro_device_id: 2_490_378,
            accel_device_id: 2_490_378,
        },
    )
    .unwrap();
    write_parameter_file(&path, &file).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let parsed = parse_qgc_params(&text);
    assert_eq!(parsed.len(), 2 + 2 * (4 + 12));
    assert_eq!(get(&parsed, "TC_G_ENABLE"), 1.0);
    assert_eq!(get(&parsed, "TC_A0_ID"), 2_490_378.0);
    assert!(text.contains("no thermal scale-factor parameters"));
    let range_c = calibration.channels[&Channel::Gx].bias.temperature_range_c;
    assert_eq!(range_c, [-20.0, 60.0]);
    for (k, channel) in Channel::ALL.into_iter().enumerate() {
        let prefix = if k < 3 { "TC_G0" } else { "TC_A0" };
        let x = px4_coefficients(&parsed, prefix, k % 3);
        for t in temperatures_c(range_c) {
            let (offset, dt) = px4_offset(&parsed, prefix, k % 3, t as f32);
            let expected = calibration.bias_at(channel, t).unwrap();
            let bound = rounding_bound(x, f64::from(dt), t.abs().max(60.0));
            let error = f64::from(offset) - expected;
            assert!(
                error.abs() <= bound,
                "{} at {t} °C: PX4 {offset}, bank {expected}, error {error:e} > {bound:e}",
                channel.name()
            );
        }
    }
}

/// ArduPilot's p(T) = 10⁻⁶ (c1 d + c2 d² + c3 d³), d = T − 35 °C, in f32.
fn ardupilot_polynomial(c: [f32; 3], d: f32) -> f32 {
    (c[0] + (c[1] + c[2] * d) * d) * d * 1.0e-6_f32
}

fn ardupilot_coefficients(parsed: &Parsed, stem: &str, axis: &str) -> [f32; 3] {
    std::array::from_fn(|k| get(parsed, &format!("INS_TCAL1_{stem}{}_{axis}", k + 1)))
}

/// What ArduPilot removes from a reading at `temperature_c` when its offset calibration ran at
/// `calibration_temperature_c`: the offset it measured there (the raw bias, which is the bank's
/// curve) plus p(clamp T) − p(clamp T_cal) (`correct_sensor`). Returns the total and the
/// rounding bound of the two polynomial evaluations.
fn ardupilot_removed(
    parsed: &Parsed,
    c: [f32; 3],
    offset_at_calibration: f64,
    temperature_c: f64,
    calibration_temperature_c: f64,
) -> (f64, f64) {
    let (tmin, tmax) = (get(parsed, "INS_TCAL1_TMIN"), get(parsed, "INS_TCAL1_TMAX"));
    let clamped = |t: f64| (t as f32).clamp(tmin, tmax);
    let d = clamped(temperature_c) - 35.0;
    let d_cal = clamped(calibration_temperature_c) - 35.0;
    let correction = ardupilot_polynomial(c, d) - ardupilot_polynomial(c, d_cal);
    let x = [
        0.0,
        1e-6 * c[0] as f64,
        1e-6 * c[1] as f64,
        1e-6 * c[2] as f64,
    ];
    let magnitude_c = temperature_c.abs().max(60.0);
    let bound = rounding_bound(x, f64::from(d), magnitude_c)
        + rounding_bound(x, f64::from(d_cal), magnitude_c);
    (offset_at_calibration + f64::from(correction), bound)
}

#[test]
fn ardupilot_parameters_read_back_as_the_bank_curve_with_its_offset_calibration() {
    let calibration = calibration();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("tcal.param");
    let file = ardupilot_parameters(&calibration, ExportTarget::default()).unwrap();
    write_parameter_file(&path, &file).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let parsed = parse_mission_planner_param(&text);
    assert_eq!(parsed.len(), 3 + 18);
    assert_eq!(get(&parsed, "INS_TCAL1_ENABLE"), 1.0);
    assert!(text.contains("no thermal scale-factor parameters"));
    assert!(text.contains("no constant term"));
    let range_c = [-20.0, 60.0];
    for (k, channel) in Channel::ALL.into_iter().enumerate() {
        let stem = if k < 3 { "GYR" } else { "ACC" };
        let c = ardupilot_coefficients(&parsed, stem, ["X", "Y", "Z"][k % 3]);
        // The offset calibration at boot, at a few temperatures inside the range.
        for calibration_temperature_c in [-12.5, 21.0, 35.0, 58.0] {
            let offset = calibration
                .bias_at(channel, calibration_temperature_c)
                .unwrap();
            for t in temperatures_c(range_c) {
                let (removed, bound) =
                    ardupilot_removed(&parsed, c, offset, t, calibration_temperature_c);
                let expected = calibration.bias_at(channel, t).unwrap();
                let error = removed - expected;
                assert!(
                    error.abs() <= bound,
                    "{} at {t} °C (T_cal {calibration_temperature_c}): ArduPilot {removed}, bank {expected}, error {error:e} > {bound:e}",
                    channel.name()
                );
            }
        }
    }
}

#[test]
fn ardupilot_file_names_each_constant_it_leaves_to_the_offset_calibration() {
    let calibration = calibration();
    let text = ardupilot_parameters(&calibration, ExportTarget::default())
        .unwrap()
        .text();
    for channel in Channel::ALL {
        let line = text
            .lines()
            .find(|l| l.starts_with(&format!("# {} bias at 35 degC", channel.name())))
            .expect("a comment per channel");
        let (_, after) = line.split_once("): ").expect("the value after the colon");
        let value: f64 = after.split_whitespace().next().unwrap().parse().unwrap();
        let expected = calibration.bias_at(channel, 35.0).unwrap();
        assert!((value - expected).abs() <= 1e-12 * expected.abs(), "{line}");
    }
}

#[test]
fn reexpansion_keeps_the_curve_at_every_temperature() {
    let b = [1.5e-3, -2.0e-5, 3.0e-7, -4.0e-9];
    let a = reexpanded(&b, 12.25, 35.0);
    for k in 0..=40 {
        let t = -40.0 + 3.0 * k as f64;
        let original: f64 = (0..4).map(|m| b[m] * (t - 12.25).powi(m as i32)).sum();
        let moved: f64 = (0..4).map(|m| a[m] * (t - 35.0).powi(m as i32)).sum();
        assert!(
            (original - moved).abs() <= 1e-15,
            "{t}: {original} vs {moved}"
        );
    }
}

#[test]
fn channels_of_different_ranges_share_the_overlap_and_say_so() {
    let mut calibration = calibration();
    let gy = calibration.channels.get_mut(&Channel::Gy).unwrap();
    gy.bias.temperature_range_c = [-25.0, 50.0];
    let file = px4_parameters(&calibration, ExportTarget::default()).unwrap();
    let parsed = parse_qgc_params(&file.text());
    assert_eq!(get(&parsed, "TC_G0_TMIN"), -20.0);
    assert_eq!(get(&parsed, "TC_G0_TMAX"), 50.0);
    assert_eq!(get(&parsed, "TC_A0_TMAX"), 60.0);
    let text = file.text();
    assert!(
        text.contains(
            "# gx, gy, gz fitted over a wider range than the shared TMIN..TMAX -20..50 degC"
        ),
        "{text}"
    );
    assert!(text.contains("set them to the IMU's device id"));
    calibration.channels.remove(&Channel::Az);
    assert_eq!(
        ardupilot_parameters(&calibration, ExportTarget::default()).unwrap_err(),
        ExportError::MissingChannel("az")
    );
}
