//! ArduPilot DataFlash logs: the files of tests/data/dataflash, written by
//! `tools/oracles/dataflash.py` from the format's documentation with Python's `struct` and read
//! back there by pymavlink 2.4.50's DFReader, against the values the script wrote
//! (`expected.json`), value for value.
//!
//! Exactness: float fields are binary32 in the log and written to the JSON as the binary64
//! value they widen to (Python's repr round-trips, serde_json's float_roundtrip parses it
//! back), so they compare with `==`; scaled integers (`c`, `C`, `e`, `E`, `L`) are the stored
//! integer divided by 100 or 1e7, a correctly rounded IEEE division in both languages, so they
//! compare with `==` too. Times are integer µs and ns. The one computed quantity, velocity
//! north/east = Spd·cos(GCrs), Spd·sin(GCrs), goes through libm's cos/sin, which may differ by
//! an ulp between Rust and Python: those compare within 4 ulp of 1 m/s (1e-15 m/s).

use serde_json::Value;
use thermonav::units::deg_to_rad;
use thermonav_io::dataflash::ardupilot::{
    TimeScale, gnss_fixes, imu_instances, imu_series, time_scale,
};
use thermonav_io::dataflash::{DataFlash, Value as Field, decode_dataflash, read_dataflash_file};

fn dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/dataflash")
}

fn expected() -> Value {
    let text = std::fs::read_to_string(dir().join("expected.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn log(name: &str) -> DataFlash {
    read_dataflash_file(dir().join(name)).unwrap()
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

fn bytes(name: &str) -> Vec<u8> {
    std::fs::read(dir().join(name)).unwrap()
}

#[test]
fn every_imu_record_of_instance_0_is_read_exactly_at_gpst() {
    let expected = expected();
    let want = &expected["static"];
    let log = log("static.bin");
    let scale = time_scale(&log);
    let offset = want["boot_to_gpst_ns"].as_i64().unwrap();
    assert_eq!(
        scale,
        TimeScale::Gpst {
            boot_to_gpst_ns: offset
        }
    );
    let imu = imu_series(&log, Some(0), "--imu-instance", "static.bin", scale).unwrap();
    let records = want["imu0"].as_array().unwrap();
    assert_eq!(imu.series.len(), records.len());
    let temperature = imu.series.temperature_c.as_ref().unwrap();
    for (k, r) in records.iter().enumerate() {
        let time_ns = r["time_us"].as_i64().unwrap() * 1_000 + offset;
        assert_eq!(imu.series.time[k].as_nanos(), time_ns, "record {k}");
        for c in 0..3 {
            assert_eq!(
                imu.series.channels[c][k],
                f(&r["gyro"][c]),
                "gyro {c} at {k}"
            );
            assert_eq!(
                imu.series.channels[3 + c][k],
                f(&r["accel"][c]),
                "accel {c} at {k}"
            );
        }
        assert_eq!(temperature[k], f(&r["temp_c"]), "T at {k}");
    }
    assert_eq!(imu.instance, 0);
    assert!(imu.units.contains("confirmed"), "{}", imu.units);
}

#[test]
fn the_second_imu_instance_is_listed_and_read_when_asked_for() {
    let expected = expected();
    let want = &expected["static"];
    let log = log("static.bin");
    let instances = imu_instances(&log);
    let counts: Vec<(u64, usize)> = instances.iter().map(|s| (s.instance, s.count)).collect();
    let n1 = want["imu1_count"].as_u64().unwrap() as usize;
    assert_eq!(
        counts,
        vec![(0, want["imu0"].as_array().unwrap().len()), (1, n1)]
    );
    let scale = time_scale(&log);
    let err = imu_series(&log, None, "--imu-instance", "static.bin", scale).unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("2 IMU instances: 0 (IMU, 100 records), 1 (IMU, 10 records); choose one with --imu-instance"),
        "{text}"
    );
    let imu = imu_series(&log, Some(1), "--imu-instance", "static.bin", scale).unwrap();
    assert_eq!(imu.series.len(), n1);
    let first = &want["imu1_first"];
    assert_eq!(imu.series.channels[2][0], f(&first["gyro"][2]));
    assert_eq!(imu.series.temperature_c.unwrap()[0], f(&first["temp_c"]));
    let err = imu_series(&log, Some(7), "--imu-instance", "static.bin", scale).unwrap_err();
    assert!(
        err.to_string()
            .contains("no IMU instance 7 (instances: 0 (IMU, 100 records), 1")
    );
}

#[test]
fn gps_fixes_are_the_3d_fixes_of_instance_0_at_their_gps_time_with_gpa_accuracy() {
    let expected = expected();
    let want = &expected["static"];
    let log = log("static.bin");
    let gnss = gnss_fixes(&log, "static.bin", time_scale(&log)).unwrap();
    let fixes = want["fixes"].as_array().unwrap();
    assert_eq!(gnss.fixes.len(), fixes.len());
    assert_eq!(
        gnss.records_without_3d_fix as u64,
        want["gps_records"].as_u64().unwrap() - fixes.len() as u64
    );
    assert_eq!(
        gnss.other_instance_records as u64,
        want["other_gps_records"].as_u64().unwrap()
    );
    for (fix, w) in gnss.fixes.iter().zip(fixes) {
        assert_eq!(fix.time.as_nanos(), w["gpst_ns"].as_i64().unwrap());
        assert_eq!(fix.latitude_rad, deg_to_rad(f(&w["lat_deg"])));
        assert_eq!(fix.longitude_rad, deg_to_rad(f(&w["lng_deg"])));
        assert_eq!(fix.height_m, f(&w["alt_m"]));
        let (h, v) = (f(&w["hacc_m"]), f(&w["vacc_m"]));
        assert_eq!(fix.position_sd_ned_m, Some([h, h, v]));
        let velocity = fix.velocity_ned_m_s.unwrap();
        let (speed, course) = (f(&w["spd_m_s"]), deg_to_rad(f(&w["gcrs_deg"])));
        assert!((velocity[0] - speed * course.cos()).abs() <= 1e-15);
        assert!((velocity[1] - speed * course.sin()).abs() <= 1e-15);
        assert_eq!(velocity[2], f(&w["vz_m_s"]));
    }
    assert!(gnss.height.contains("mean sea level"));
}

#[test]
fn every_format_character_decodes_to_the_documented_value() {
    let expected = expected();
    let log = log("static.bin");
    for name in ["TYP1", "TYP2"] {
        let t = log.message(name).unwrap();
        assert_eq!(t.len(), 1);
        let want = expected["static"]["typ"][name].as_array().unwrap();
        for (c, w) in want.iter().enumerate() {
            let got = t.value(c, 0);
            let column = &t.columns[c];
            match (&got, w) {
                (Field::Array(a), Value::Array(items)) => {
                    let items: Vec<i64> = items.iter().map(|v| v.as_i64().unwrap()).collect();
                    assert_eq!(a.iter().map(|&x| i64::from(x)).collect::<Vec<_>>(), items);
                }
                (Field::Text(s), Value::String(w)) => assert_eq!(s, w, "{name}.{column}"),
                (Field::Float(x), w) => assert_eq!(*x, f(w), "{name}.{column}"),
                (Field::Int(x), w) => assert_eq!(Some(*x), w.as_i64(), "{name}.{column}"),
                (Field::UInt(x), w) => assert_eq!(Some(*x), w.as_u64(), "{name}.{column}"),
                other => panic!("{name}.{column}: {other:?}"),
            }
        }
    }
}

#[test]
fn a_log_without_gps_stays_on_boot_time() {
    let expected = expected();
    let log = log("boot.bin");
    let scale = time_scale(&log);
    assert_eq!(scale, TimeScale::Boot);
    let imu = imu_series(&log, None, "--imu-instance", "boot.bin", scale).unwrap();
    let records = expected["boot"]["imu0"].as_array().unwrap();
    assert_eq!(imu.series.len(), records.len());
    for (k, r) in records.iter().enumerate() {
        assert_eq!(
            imu.series.time[k].as_nanos(),
            r["time_us"].as_i64().unwrap() * 1_000
        );
        assert_eq!(imu.series.channels[5][k], f(&r["accel"][2]));
    }
    assert!(imu.units.contains("no FMTU"), "{}", imu.units);
    let err = gnss_fixes(&log, "boot.bin", scale).unwrap_err();
    assert!(err.to_string().contains("no GPS message"), "{err}");
}

#[test]
fn a_gyro_the_log_says_is_in_deg_s_is_refused() {
    let log = log("deg_units.bin");
    let err = imu_series(
        &log,
        None,
        "--imu-instance",
        "deg_units.bin",
        TimeScale::Boot,
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("deg_units.bin: IMU.GyrX: the log's FMTU, UNIT and MULT records give the unit deg/s, expected rad/s"),
        "{err}"
    );
}

/// The error of decoding `bytes`.
fn refusal(bytes: &[u8]) -> String {
    decode_dataflash(bytes, "log.bin").unwrap_err().to_string()
}

/// Offset of the FMT record that defines `name`.
fn fmt_of(bytes: &[u8], name: &[u8]) -> usize {
    (0..bytes.len() - 89)
        .find(|&i| bytes[i..i + 3] == [0xA3, 0x95, 128] && bytes[i + 5..].starts_with(name))
        .unwrap()
}

#[test]
fn broken_logs_are_refused_with_the_byte_and_the_expectation() {
    let good = bytes("boot.bin");
    let text = refusal(b"t_s,gx_rad_s\n");
    assert!(
        text.contains("log.bin: at byte 0: expected a record header 0xA3 0x95, found 0x74 0x5F"),
        "{text}"
    );
    // Cut inside the IMU's FMT record.
    let imu_fmt = fmt_of(&good, b"IMU");
    let text = refusal(&good[..imu_fmt + 40]);
    assert!(
        text.contains(&format!(
            "at byte {imu_fmt}: the file ends inside an FMT record (40 of its 89 bytes"
        )),
        "{text}"
    );
    // The IMU's FMT renumbered: its records come before any definition of their type.
    let mut orphan = good.clone();
    orphan[imu_fmt + 3] = 200;
    let text = refusal(&orphan);
    assert!(
        text.contains("a record of message type 130, which no earlier FMT record defines"),
        "{text}"
    );
    // An impossible length: 255 bytes for a 54-byte IMU record.
    let mut long = good.clone();
    long[imu_fmt + 4] = 255;
    let text = refusal(&long);
    assert!(
        text.contains(&format!(
            "at byte {imu_fmt}: FMT of IMU (type 130): expected a length of 54 bytes (3 header \
             bytes and format \"QBffffffIIfBBHH\"), found 255"
        )),
        "{text}"
    );
    let mut unknown = good.clone();
    unknown[imu_fmt + 9] = b'x';
    let text = refusal(&unknown);
    assert!(
        text.contains("format character 'x' is not one of"),
        "{text}"
    );
    assert!(refusal(b"").contains("empty"));
}

#[test]
fn a_log_cut_inside_a_data_record_keeps_its_whole_records_and_says_so() {
    let good = bytes("boot.bin");
    let cut = &good[..good.len() - 10];
    let log = decode_dataflash(cut, "cut.bin").unwrap();
    assert_eq!(log.truncated_tail_bytes, 54 - 10);
    let imu = imu_series(&log, None, "--imu-instance", "cut.bin", TimeScale::Boot).unwrap();
    assert_eq!(imu.series.len(), 19);
}

#[test]
fn every_cut_and_random_corruption_of_the_logs_gives_an_error_or_a_log_never_a_panic() {
    use rand::{RngExt, SeedableRng};
    use thermonav_io::parsers::Parser;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(16);
    for name in ["static.bin", "boot.bin", "deg_units.bin"] {
        let good = bytes(name);
        for cut in (0..good.len()).step_by(7) {
            let _ = Parser::DataFlash.record_count(&good[..cut], "cut");
        }
        for _ in 0..300 {
            let mut damaged = good.clone();
            for _ in 0..rng.random_range(1..8) {
                let at = rng.random_range(0..damaged.len());
                damaged[at] = rng.random();
            }
            let _ = Parser::DataFlash.record_count(&damaged, name);
        }
    }
}

/// boot.bin with the f32 at `field_byte` of IMU record 0 replaced by `value`.
fn boot_with_imu_field(field_byte: usize, value: f32) -> Vec<u8> {
    let mut bytes = bytes("boot.bin");
    let log = decode_dataflash(&bytes, "boot.bin").unwrap();
    let at = log.message("IMU").unwrap().offset(0) as usize;
    assert_eq!(
        bytes[at..at + 2],
        [0xA3, 0x95],
        "a record starts with its header"
    );
    bytes[at + field_byte..at + field_byte + 4].copy_from_slice(&value.to_le_bytes());
    bytes
}

// Issue 37 row 6: the CSV reader's value checks apply to every IMU record. The IMU record is
// "QBffffffIIf...": header 3 bytes, TimeUS 8, I 1, gyro 12, AccX at byte 24, EG/EA 8, T at 44.
#[test]
fn a_temperature_in_kelvin_or_a_huge_accelerometer_is_refused_naming_the_record() {
    let refusal_of = |bytes: Vec<u8>| {
        let log = decode_dataflash(&bytes, "boot.bin").unwrap();
        imu_series(&log, None, "--imu-instance", "boot.bin", TimeScale::Boot)
            .unwrap_err()
            .to_string()
    };
    let kelvin = refusal_of(boot_with_imu_field(44, 298.15));
    assert!(
        kelvin.contains("boot.bin")
            && kelvin.contains("IMU record 0")
            && kelvin.contains("in kelvin?"),
        "{kelvin}"
    );
    let huge = refusal_of(boot_with_imu_field(24, -1e30));
    assert!(
        huge.contains("at byte 342: IMU record 0: ax is -1.0000000150474662e30 in SI"),
        "{huge}"
    );
}
