//! PX4 ULog: the PX4 v1.8 SITL log in tests/data/ulog (see its README) against pyulog, and
//! damaged copies of it.
//!
//! Every expected number below was printed by pyulog 1.3.0 (PyPI, BSD-3) on
//! `tests/data/ulog/px4_sitl_v1.8.ulg` (`ULog(path)`, then `start_timestamp`,
//! `last_timestamp`, `dropouts`, `data_list`, `get_dataset(name).data[field][i]`), not by
//! thermonav. Decoded `float` fields are compared exactly: pyulog widens the same binary32
//! values to binary64, as we do, so both must be the same double.

use thermonav::imu::{Channel, SampleKind};
use thermonav::units::deg_to_rad;
use thermonav_io::ulog::px4::{TimeScale, default_gpst_minus_utc, gnss_fixes, imu_series};
use thermonav_io::ulog::{InfoValue, Ulog, decode_ulog, read_ulog_file};

const NAME: &str = "px4_sitl_v1.8.ulg";

fn path() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ulog/px4_sitl_v1.8.ulg")
}

fn bytes() -> Vec<u8> {
    std::fs::read(path()).unwrap()
}

fn log() -> Ulog {
    read_ulog_file(path()).unwrap()
}

/// The message of the error that decoding `bytes` must give.
fn decode_error(bytes: &[u8]) -> String {
    match decode_ulog(bytes, NAME) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e.to_string(),
    }
}

/// `bytes` with every `from` replaced by `to` (same length).
fn renamed(bytes: &[u8], from: &[u8], to: &[u8]) -> Vec<u8> {
    assert_eq!(from.len(), to.len());
    let mut out = bytes.to_vec();
    let mut i = 0;
    while i + from.len() <= out.len() {
        if &out[i..i + from.len()] == from {
            out[i..i + from.len()].copy_from_slice(to);
            i += from.len();
        } else {
            i += 1;
        }
    }
    out
}

#[test]
fn header_definitions_and_counts_match_pyulog() {
    let log = log();
    // pyulog: start_timestamp 373058900, last_timestamp 401678183, no dropouts.
    assert_eq!(log.version, 1);
    assert_eq!(log.start_timestamp_us, 373_058_900);
    assert_eq!(log.last_timestamp_us, 401_678_183);
    assert!(log.dropouts_ms.is_empty());
    // pyulog: 112 message_formats, 34 data_list entries (pyulog lists only subscriptions
    // that received data) holding 20 390 records, 544 initial and 0 changed parameters,
    // 2 logged messages, msg_info_multiple perf_counter_preflight 1.
    assert_eq!(log.formats.len(), 112);
    let with_data = log.subscriptions.iter().filter(|s| !s.is_empty()).count();
    assert_eq!(with_data, 34);
    let total: usize = log.record_counts().values().sum();
    assert_eq!(total, 20_390);
    assert_eq!(log.initial_parameters, 544);
    assert_eq!(log.changed_parameters, 0);
    assert_eq!(log.multi_info.get("perf_counter_preflight"), Some(&1));
    // pyulog: (51, 330430986, '[sensors] Accel #1 fail:  TIMEOUT!').
    assert_eq!(log.logged.len(), 2);
    assert_eq!(log.logged[0].level, 51);
    assert_eq!(log.logged[0].timestamp_us, 330_430_986);
    assert_eq!(log.logged[0].text, "[sensors] Accel #1 fail:  TIMEOUT!");
    // pyulog msg_info_dict: sys_name PX4, ver_hw SITL, ver_sw_release 17301632.
    assert_eq!(log.info["sys_name"], InfoValue::Text("PX4".into()));
    assert_eq!(log.info["ver_hw"], InfoValue::Text("SITL".into()));
    assert_eq!(log.info["ver_sw_release"], InfoValue::Integer(17_301_632));
    // pyulog ulog_info: sensor_combined 4445, vehicle_gps_position 260, vehicle_magnetometer 2304.
    let counts = log.record_counts();
    assert_eq!(counts[&("sensor_combined".to_string(), 0)], 4445);
    assert_eq!(counts[&("vehicle_gps_position".to_string(), 0)], 260);
    assert_eq!(counts[&("vehicle_magnetometer".to_string(), 0)], 2304);
    assert!(log.skipped.unknown_types.is_empty());
    assert_eq!(log.skipped.truncated_tail_bytes, 0);
    // pyulog ulog_info "(multi id, message size in bytes)": sensor_combined 44 (its format
    // ends in uint8_t[4] _padding0, not logged), vehicle_gps_position 91 (ends in
    // _padding0[5]), position_setpoint_triplet 320 (three nested position_setpoint, each
    // ending in _padding0[1], which is logged inside the nest), estimator_status 272.
    let size = |name: &str| {
        let s = log.subscriptions.iter().find(|s| s.name == name).unwrap();
        s.layout.size
    };
    assert_eq!(size("sensor_combined"), 44);
    assert_eq!(size("vehicle_gps_position"), 91);
    assert_eq!(size("position_setpoint_triplet"), 320);
    assert_eq!(size("estimator_status"), 272);
}

#[test]
fn nested_fields_decode_as_pyulog_names_them() {
    let log = log();
    let topic = log.topic("position_setpoint_triplet", 0).unwrap();
    assert_eq!(topic.len(), 1);
    let real = |name: &str| topic.real(topic.field(name).unwrap(), 0);
    // pyulog: timestamp 267219612, current.lat 40.74229991780241 (double),
    // current.alt 28.501265 (float), current.type 5, next.valid 0.
    assert_eq!(real("timestamp"), 267_219_612.0);
    assert_eq!(real("current.lat"), 40.74229991780241);
    assert_eq!(real("current.alt"), f64::from(28.501265_f32));
    assert_eq!(real("current.type"), 5.0);
    assert_eq!(real("next.valid"), 0.0);
}

#[test]
fn imu_samples_match_pyulog_on_boot_time() {
    let log = log();
    let scale = px4_time_scale(&log);
    // pyulog: every time_utc_usec of vehicle_gps_position is 0 (SITL): boot time is kept.
    assert_eq!(scale, TimeScale::Boot);
    let imu = imu_series(&log, NAME, scale).unwrap();
    let series = &imu.series;
    assert_eq!(series.kind, Some(SampleKind::Rates));
    assert_eq!(series.len(), 4445);
    // No sensor_accel, vehicle_imu_status or sensor_gyro in a v1.8 log: no temperature.
    assert_eq!(series.temperature_c, None);
    assert_eq!(imu.max_accelerometer_offset_us, 4988);
    // pyulog sensor_combined[0]: timestamp 375484685, gyro_rad[1] -0.0075456807389855385,
    // accelerometer_m_s2[2] -9.83067512512207; [4444]: 401678042, gyro_rad[2]
    // 0.007335747592151165, accelerometer_m_s2[0] 0.502689003944397.
    assert_eq!(series.time[0].as_nanos(), 375_484_685_000);
    assert_eq!(series.channel(Channel::Gy)[0], -0.0075456807389855385);
    assert_eq!(series.channel(Channel::Az)[0], -9.83067512512207);
    assert_eq!(series.time[4444].as_nanos(), 401_678_042_000);
    assert_eq!(series.channel(Channel::Gz)[4444], 0.007335747592151165);
    assert_eq!(series.channel(Channel::Ax)[4444], 0.502689003944397);
    // [1000]: 381468358, gyro_rad[0] 0.003903124714270234, accelerometer_m_s2[1] 0.05603751167654991.
    assert_eq!(series.time[1000].as_nanos(), 381_468_358_000);
    assert_eq!(series.channel(Channel::Gx)[1000], 0.003903124714270234);
    assert_eq!(series.channel(Channel::Ay)[1000], 0.05603751167654991);
}

fn px4_time_scale(log: &Ulog) -> TimeScale {
    thermonav_io::ulog::px4::time_scale(log, default_gpst_minus_utc())
}

#[test]
fn gnss_fixes_match_pyulog() {
    let log = log();
    let gnss = gnss_fixes(&log, NAME, px4_time_scale(&log)).unwrap();
    // pyulog: 260 records, all fix_type 3; vel_ned_valid 0; alt_ellipsoid all 0.
    assert_eq!(gnss.fixes.len(), 260);
    assert_eq!(gnss.records_without_3d_fix, 0);
    assert!(gnss.height.starts_with("mean sea level"));
    let (first, last) = (gnss.fixes[0], gnss.fixes[259]);
    // pyulog [0]: timestamp 375408345, lat 407423012, lon -741792999, alt 28495 (mm),
    // eph 0.29999998211860657, epv 0.3999999761581421. The expected angles are those integers
    // times 1e-7 deg; one rounding of the product apart at most.
    assert_eq!(first.time.as_nanos(), 375_408_345_000);
    assert!((first.latitude_rad - deg_to_rad(40.742_301_2)).abs() < 1e-15);
    assert!((first.longitude_rad - deg_to_rad(-74.179_299_9)).abs() < 1e-15);
    assert!((first.height_m - 28.495).abs() < 1e-12);
    assert_eq!(
        first.position_sd_ned_m,
        Some([0.29999998211860657, 0.29999998211860657, 0.3999999761581421])
    );
    assert_eq!(first.velocity_ned_m_s, None);
    // [259]: timestamp 401656441, lat 407423011, lon -741793000, alt 28497.
    assert_eq!(last.time.as_nanos(), 401_656_441_000);
    assert!((last.latitude_rad - deg_to_rad(40.742_301_1)).abs() < 1e-15);
    assert!((last.longitude_rad - deg_to_rad(-74.179_3)).abs() < 1e-15);
    assert!((last.height_m - 28.497).abs() < 1e-12);
}

#[test]
fn utc_time_puts_boot_time_on_gpst_with_the_leap_seconds() {
    // Write time_utc_usec = 1.6e15 µs (2020-09-13 12:26:40 UTC) into every GPS record,
    // 12 bytes into its data (after msg_id 2 bytes and timestamp 8): offset to boot time
    // = 1.6e15 − timestamp for each record. Expected: the upper median of those offsets,
    // computed here by sorting, plus the 18 s GPST − UTC since 2017 (IERS Bulletin C).
    let mut bytes = bytes();
    let log = decode_ulog(&bytes, NAME).unwrap();
    let gps = log.topic("vehicle_gps_position", 0).unwrap();
    let utc_field = gps.field("time_utc_usec").unwrap().offset;
    let stamps: Vec<u64> = (0..gps.len())
        .map(|i| gps.integer(gps.field("timestamp").unwrap(), i).unwrap() as u64)
        .collect();
    for i in 0..gps.len() {
        let at = gps.file_offset(i) as usize + 3 + 2 + utc_field;
        bytes[at..at + 8].copy_from_slice(&1_600_000_000_000_000_u64.to_le_bytes());
    }
    let log = decode_ulog(&bytes, NAME).unwrap();
    let mut offsets: Vec<i64> = stamps
        .iter()
        .map(|&s| 1_600_000_000_000_000 - s as i64)
        .collect();
    offsets.sort_unstable();
    let expected = offsets[130] * 1_000 + 18_000_000_000;
    assert_eq!(
        px4_time_scale(&log),
        TimeScale::Gpst {
            boot_to_gpst_ns: expected,
            gpst_minus_utc_s: 18
        }
    );
}

#[test]
fn bad_magic_and_cut_definitions_are_errors_with_the_byte_offset() {
    let mut bytes = bytes();
    assert!(decode_error(&bytes[..10]).contains("ends inside the 16-byte ULog header"));
    assert!(decode_error(&bytes[..2000]).contains("ends inside a message of the definitions"));
    bytes[0] = b'X';
    let message = decode_error(&bytes);
    assert!(message.starts_with("px4_sitl_v1.8.ulg: at byte 0: expected the ULog magic"));
}

#[test]
fn a_cut_data_section_keeps_whole_records_and_reports_the_tail() {
    let bytes = bytes();
    let log = decode_ulog(&bytes[..bytes.len() - 5], NAME).unwrap();
    assert!(log.skipped.truncated_tail_bytes > 0);
    let total: usize = log.record_counts().values().sum();
    assert_eq!(total, 20_389);
}

#[test]
fn unknown_message_types_are_skipped_and_counted() {
    let mut bytes = bytes();
    bytes.extend_from_slice(&[3, 0, b'Z', 1, 2, 3]);
    let log = decode_ulog(&bytes, NAME).unwrap();
    assert_eq!(log.skipped.unknown_types.get(&b'Z'), Some(&1));
}

#[test]
fn unknown_incompatible_flags_are_refused() {
    // The 'B' message starts at byte 16: size (2), type (1), 8 compat bytes, then incompat.
    let mut bytes = bytes();
    assert_eq!(bytes[18], b'B');
    bytes[16 + 3 + 8] = 0b10;
    assert!(decode_error(&bytes).contains("at byte 16: incompatible flag bits"));
}

#[test]
fn missing_topics_are_named() {
    let bytes = renamed(&bytes(), b"sensor_combined", b"sensor_cXmbined");
    let bytes = renamed(&bytes, b"vehicle_gps_position", b"vehicle_gps_pXsition");
    let log = decode_ulog(&bytes, NAME).unwrap();
    let scale = px4_time_scale(&log);
    let imu = imu_series(&log, NAME, scale).unwrap_err().to_string();
    assert_eq!(
        imu,
        "px4_sitl_v1.8.ulg: no IMU topic: expected sensor_combined or vehicle_imu (instance 0)"
    );
    let gnss = gnss_fixes(&log, NAME, scale).unwrap_err().to_string();
    assert!(gnss.contains("no GNSS topic: expected vehicle_gps_position or sensor_gps"));
}

#[test]
fn garbage_never_panics() {
    // Every prefix length class and a few corruptions of the real file: an error or a log,
    // never a panic.
    let good = bytes();
    let named = |result: Result<Ulog, thermonav_io::ReadError>| match result {
        Ok(_) => true,
        Err(e) => e.to_string().starts_with("px4_sitl_v1.8.ulg: at byte "),
    };
    for cut in [16, 17, 19, 59, 60, 100, 5_000, 50_000, 500_000] {
        assert!(named(decode_ulog(&good[..cut], NAME)), "cut at {cut}");
    }
    for (at, value) in [(16, 0xFF), (17, 0xFF), (5_000, 0xFF), (200_000, 0x00)] {
        let mut bad = good.clone();
        bad[at] = value;
        let decoded = decode_ulog(&bad, NAME);
        if let Err(e) = &decoded {
            assert!(e.to_string().starts_with("px4_sitl_v1.8.ulg: "), "{e}");
        }
        if let Ok(log) = decoded {
            let scale = px4_time_scale(&log);
            if let Err(e) = imu_series(&log, NAME, scale) {
                assert!(e.to_string().starts_with("px4_sitl_v1.8.ulg: "), "{e}");
            }
            if let Err(e) = gnss_fixes(&log, NAME, scale) {
                assert!(e.to_string().starts_with("px4_sitl_v1.8.ulg: "), "{e}");
            }
        }
    }
}
