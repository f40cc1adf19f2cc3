//! A ULog assembled byte by byte from the format description, with values chosen in advance
//! (exact in binary32), for what the PX4 v1.8 sample lacks: `vehicle_imu` increments,
//! `sensor_accel` temperature, the newer `sensor_gps` with f64 degrees and UTC time, 'M'
//! continuation, 'O' dropouts, unknown message types and unsubscribed data.

use crate::ulog_writer::{Record, data, format, log_start, message, subscribe, subscribe_instance};
use thermonav::imu::{Channel, SampleKind};
use thermonav::time::Duration;
use thermonav::units::deg_to_rad;
use thermonav_io::ulog::decode_ulog;
use thermonav_io::ulog::px4::{TimeScale, gnss_fixes, imu_series, raw_sensor_series, time_scale};

/// UTC µs of the GNSS records minus their boot µs: 1.7e15 µs = 2023-11-14 22:13:20 UTC.
const BOOT_TO_UTC_US: u64 = 1_700_000_000_000_000;

/// Temperatures 20.5 °C at 1.000 s and 21.5 °C at 1.010 s (boot), in log order.
const TEMPERATURES: [(u64, f32); 2] = [(1_000_000, 20.5), (1_010_000, 21.5)];

fn built_log() -> Vec<u8> {
    built_log_with(TEMPERATURES)
}

/// The built log with its `sensor_accel` records in the order given.
fn built_log_with(temperatures: [(u64, f32); 2]) -> Vec<u8> {
    let mut out = log_start();
    format(
        &mut out,
        "vehicle_imu:uint64_t timestamp;uint64_t timestamp_sample;float[3] delta_angle;\
         float[3] delta_velocity;uint16_t delta_angle_dt;uint16_t delta_velocity_dt;\
         uint8_t[4] _padding0;",
    );
    format(
        &mut out,
        "sensor_accel:uint64_t timestamp;float x;float y;float z;float temperature;",
    );
    format(
        &mut out,
        "sensor_gps:uint64_t timestamp;uint64_t time_utc_usec;double latitude_deg;\
         double longitude_deg;double altitude_msl_m;double altitude_ellipsoid_m;float eph;\
         float epv;float vel_n_m_s;float vel_e_m_s;float vel_d_m_s;uint8_t fix_type;\
         bool vel_ned_valid;",
    );
    // A multi-part information value in two messages: one value.
    let mut multi = vec![0, 9];
    multi.extend_from_slice(b"char[3] a");
    multi.extend_from_slice(b"abc");
    message(&mut out, b'M', &multi);
    multi[0] = 1;
    message(&mut out, b'M', &multi);
    subscribe(&mut out, 0, "vehicle_imu");
    subscribe(&mut out, 1, "sensor_accel");
    subscribe(&mut out, 2, "sensor_gps");
    for (t, c) in temperatures {
        let r = Record::default().u64(t).f32(0.0).f32(0.0).f32(-9.75).f32(c);
        data(&mut out, 1, &r.0);
    }
    // IMU samples at 1.002, 1.004, …, 1.012 s (timestamp_sample), published 100 µs later.
    for k in 1..=6_u64 {
        let t = 1_000_000 + 2_000 * k;
        let r = Record::default()
            .u64(t + 100)
            .u64(t)
            .f32(0.001 * k as f32)
            .f32(-0.25)
            .f32(0.5)
            .f32(0.125)
            .f32(0.0)
            .f32(-0.019_5)
            .u16(2_000)
            .u16(2_000);
        data(&mut out, 0, &r.0);
    }
    message(&mut out, b'O', &25_u16.to_le_bytes());
    message(&mut out, b'Z', &[1, 2, 3]);
    data(&mut out, 9, &[0; 8]);
    // Two GNSS records: fix_type 2 (left out), then 3 with velocity.
    for (t, fix) in [(1_005_000_u64, 2_u8), (1_011_000, 3)] {
        let r = Record::default()
            .u64(t)
            .u64(BOOT_TO_UTC_US + t)
            .f64(47.397_742_5)
            .f64(8.545_594)
            .f64(488.25)
            .f64(535.5)
            .f32(0.75)
            .f32(1.5)
            .f32(1.0)
            .f32(-2.0)
            .f32(0.25)
            .u8(fix)
            .u8(1);
        data(&mut out, 2, &r.0);
    }
    out
}

#[test]
fn a_built_log_decodes_to_the_values_written_into_it() {
    let log = decode_ulog(&built_log(), "built.ulg").unwrap();
    assert_eq!(log.start_timestamp_us, 1_000);
    assert_eq!(log.multi_info.get("a"), Some(&1));
    assert_eq!(log.dropouts_ms, [25]);
    assert_eq!(log.skipped.unknown_types.get(&b'Z'), Some(&1));
    assert_eq!(log.skipped.unsubscribed_data, 1);
    assert_eq!(log.last_timestamp_us, 1_012_100);

    // Only the 3D fix sets the time scale: GPST = boot + 1.7e15 µs + 18 s.
    let scale = time_scale(&log, Duration::from_nanos(18_000_000_000));
    let boot_to_gpst_ns = (BOOT_TO_UTC_US as i64) * 1_000 + 18_000_000_000;
    assert_eq!(
        scale,
        TimeScale::Gpst {
            boot_to_gpst_ns,
            gpst_minus_utc_s: 18
        }
    );

    let imu = imu_series(&log, "built.ulg", scale).unwrap();
    assert_eq!(imu.topic, "vehicle_imu");
    let series = &imu.series;
    assert_eq!(series.kind, Some(SampleKind::Increments));
    assert_eq!(series.len(), 6);
    assert_eq!(series.time[0].as_nanos(), 1_002_000_000 + boot_to_gpst_ns);
    assert_eq!(series.channel(Channel::Gx)[2], f64::from(0.001_f32 * 3.0));
    assert_eq!(series.channel(Channel::Gy)[0], -0.25);
    assert_eq!(series.channel(Channel::Az)[5], f64::from(-0.019_5_f32));
    // Nearest temperature: 1.002-1.004 s → 20.5 (1.000 s), 1.006-1.012 s → 21.5 (1.010 s);
    // 1.005 s would be a tie, none falls on it.
    assert_eq!(
        series.temperature_c.as_deref(),
        Some(&[20.5, 20.5, 21.5, 21.5, 21.5, 21.5][..])
    );
    assert_eq!(
        imu.temperature_source.as_deref(),
        Some("sensor_accel.temperature")
    );

    let gnss = gnss_fixes(&log, "built.ulg", scale).unwrap();
    assert_eq!(gnss.topic, "sensor_gps");
    assert_eq!(gnss.records_without_3d_fix, 1);
    assert!(gnss.height.starts_with("ellipsoidal"));
    let fix = gnss.fixes[0];
    assert_eq!(fix.time.as_nanos(), 1_011_000_000 + boot_to_gpst_ns);
    assert_eq!(fix.latitude_rad, deg_to_rad(47.397_742_5));
    assert_eq!(fix.longitude_rad, deg_to_rad(8.545_594));
    assert_eq!(fix.height_m, 535.5);
    assert_eq!(fix.position_sd_ned_m, Some([0.75, 0.75, 1.5]));
    assert_eq!(fix.velocity_ned_m_s, Some([1.0, -2.0, 0.25]));
}

// Arrays of a type without bytes would make flattening loop 2^32 times in a 100-byte file
// (every element passes the size guard because none advances the offset): refused at the
// first element, naming it.
#[test]
fn nested_arrays_of_an_empty_type_are_refused_at_once() {
    let mut out = log_start();
    format(&mut out, "empty:");
    format(&mut out, "wide:empty[65535] inner;");
    format(&mut out, "wider:wide[65535] outer;");
    subscribe(&mut out, 1, "wider");
    let error = decode_ulog(&out, "empty.ulg").unwrap_err().to_string();
    assert!(
        error.contains("empty.ulg") && error.contains("outer[0].inner[0]"),
        "{error}"
    );
}

// Each 'A' message lays its format out again: 600 subscriptions to a 2000-field format
// (1.2 M fields, a file of about 30 KB) pass the cap of 2^18 fields and are refused, while a
// real log's few thousand stay far below it (the cap times the 256-byte longest name bounds
// the names to 64 MiB).
#[test]
fn subscriptions_beyond_the_layout_cap_are_refused() {
    let mut out = log_start();
    let fields: String = (0..2000).map(|k| format!("uint8_t f{k};")).collect();
    format(&mut out, &format!("wide:{fields}"));
    for id in 0..600 {
        subscribe(&mut out, id, "wide");
    }
    let error = decode_ulog(&out, "many.ulg").unwrap_err().to_string();
    assert!(
        error.contains("many.ulg") && error.contains("262144 fields"),
        "{error}"
    );
}

// Temperature records logged out of time order (two sensor instances merged, or a clock
// step) still give each IMU sample the nearest record in time: the same temp_c as in order.
#[test]
fn temperatures_out_of_order_give_the_nearest_in_time() {
    let [first, second] = TEMPERATURES;
    let temp_c = |bytes: Vec<u8>| {
        let log = decode_ulog(&bytes, "built.ulg").unwrap();
        let scale = time_scale(&log, Duration::from_nanos(18_000_000_000));
        imu_series(&log, "built.ulg", scale)
            .unwrap()
            .series
            .temperature_c
    };
    let reversed = temp_c(built_log_with([second, first]));
    assert_eq!(
        reversed.as_deref(),
        Some(&[20.5, 20.5, 21.5, 21.5, 21.5, 21.5][..])
    );
    assert_eq!(reversed, temp_c(built_log()));
}

/// Gyro records of instance 1: boot µs, x rad/s, temperature °C (one NaN).
const RAW_GYRO: [(u64, f32, f32); 5] = [
    (1_000_000, 0.0, 30.0),
    (1_004_000, 0.001, 31.0),
    (1_008_000, 0.002, f32::NAN),
    (1_012_000, 0.003, 33.0),
    (1_016_000, 0.004, 34.0),
];

/// A log with raw sensor_gyro and sensor_accel of instances 0 and 1 (instance 0 a decoy with
/// other values and ids); instance 1's accelerometer runs at half the gyro's rate, offset.
fn raw_sensor_log() -> Vec<u8> {
    let mut out = log_start();
    for topic in ["sensor_gyro", "sensor_accel"] {
        format(
            &mut out,
            &format!(
                "{topic}:uint64_t timestamp;uint64_t timestamp_sample;uint32_t device_id;float x;\
                 float y;float z;float temperature;uint32_t error_count;"
            ),
        );
    }
    subscribe_instance(&mut out, 0, "sensor_gyro", 0);
    subscribe_instance(&mut out, 1, "sensor_gyro", 1);
    subscribe_instance(&mut out, 2, "sensor_accel", 0);
    subscribe_instance(&mut out, 3, "sensor_accel", 1);
    let record = |t: u64, id: u32, v: [f32; 3], c: f32| {
        let r = Record::default().u64(t + 50).u64(t);
        let mut bytes = r.0;
        bytes.extend_from_slice(&id.to_le_bytes());
        let r = Record(bytes).f32(v[0]).f32(v[1]).f32(v[2]).f32(c);
        let mut bytes = r.0;
        bytes.extend_from_slice(&0_u32.to_le_bytes());
        bytes
    };
    for (t, x, c) in RAW_GYRO {
        data(&mut out, 0, &record(t, 111, [9.0, 9.0, 9.0], 50.0));
        data(&mut out, 1, &record(t, 2_490_378, [x, -0.002, 0.5], c));
    }
    for k in 0..3_u64 {
        let t = 1_001_000 + 8_000 * k;
        data(&mut out, 2, &record(t, 222, [9.0, 9.0, 9.0], 50.0));
        data(
            &mut out,
            3,
            &record(t, 1_310_988, [0.125 * k as f32, 0.0, -9.75], 31.0),
        );
    }
    out
}

// The raw topics of one instance: the gyro's samples with its own temperature (a NaN one left
// out), each with the nearest accelerometer sample in time, and both device ids; values are
// the binary32 numbers written above.
#[test]
fn raw_sensors_of_one_instance_give_the_sweep_and_the_device_ids() {
    let log = decode_ulog(&raw_sensor_log(), "raw.ulg").unwrap();
    let raw = raw_sensor_series(&log, "raw.ulg", TimeScale::Boot, 1).unwrap();
    assert_eq!((raw.instance, raw.records_without_temperature), (1, 1));
    assert_eq!(raw.gyro_device_id, Some(2_490_378));
    assert_eq!(raw.accel_device_id, Some(1_310_988));
    let s = &raw.series;
    let kept: Vec<_> = RAW_GYRO.iter().filter(|g| g.2.is_finite()).collect();
    assert_eq!(s.len(), kept.len());
    for (k, (t, x, c)) in kept.iter().enumerate() {
        assert_eq!(s.time[k].as_nanos(), *t as i64 * 1_000);
        assert_eq!(s.channel(Channel::Gx)[k], f64::from(*x));
        assert_eq!(s.temperature_c.as_ref().unwrap()[k], f64::from(*c));
    }
    // Gyro at 1.000, 1.004, 1.012, 1.016 s; accelerometer at 1.001, 1.009, 1.017 s.
    assert_eq!(s.channel(Channel::Ax), &[0.0, 0.0, 0.125, 0.25]);
    assert_eq!(s.channel(Channel::Az)[0], -9.75);
    let decoy = raw_sensor_series(&log, "raw.ulg", TimeScale::Boot, 0).unwrap();
    assert_eq!(decoy.gyro_device_id, Some(111));
    let missing = raw_sensor_series(&log, "raw.ulg", TimeScale::Boot, 2).unwrap_err();
    assert!(
        missing
            .to_string()
            .contains("no topic sensor_gyro of instance 2"),
        "{missing}"
    );
}

// Issue 37 rows 6 and 7: the binary reader applies the CSV reader's value checks per record.
#[test]
fn a_temperature_in_kelvin_or_absurd_is_refused_naming_the_record() {
    let kelvin = built_log_with([(1_000_000, 298.15), (1_010_000, 21.5)]);
    let log = decode_ulog(&kelvin, "k.ulg").unwrap();
    let error = imu_series(&log, "k.ulg", TimeScale::Boot)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("k.ulg")
            && error.contains("sensor_accel record 0")
            && error.contains("in kelvin?"),
        "{error}"
    );
    let absurd = built_log_with([(1_000_000, 20.5), (1_010_000, 1e30)]);
    let log = decode_ulog(&absurd, "a.ulg").unwrap();
    let error = imu_series(&log, "a.ulg", TimeScale::Boot)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("sensor_accel record 1") && error.contains("outside -80..150"),
        "{error}"
    );
}

#[test]
fn a_raw_sweep_at_1e30_degrees_is_refused_naming_the_record() {
    let mut out = log_start();
    format(
        &mut out,
        "sensor_gyro:uint64_t timestamp;float x;float y;float z;float temperature;",
    );
    format(
        &mut out,
        "sensor_accel:uint64_t timestamp;float x;float y;float z;float temperature;",
    );
    subscribe(&mut out, 0, "sensor_gyro");
    subscribe(&mut out, 1, "sensor_accel");
    let rows = [
        (1_000_000_u64, 0.001_f32, 25.0_f32),
        (1_010_000, 0.001, 1e30),
    ];
    for (t, gx, c) in rows {
        data(
            &mut out,
            0,
            &Record::default().u64(t).f32(gx).f32(0.0).f32(0.0).f32(c).0,
        );
        data(
            &mut out,
            1,
            &Record::default()
                .u64(t)
                .f32(0.0)
                .f32(0.0)
                .f32(-9.8)
                .f32(25.0)
                .0,
        );
    }
    let log = decode_ulog(&out, "sweep.ulg").unwrap();
    let error = raw_sensor_series(&log, "sweep.ulg", TimeScale::Boot, 0)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("sweep.ulg")
            && error.contains("sensor_gyro record 1")
            && error.contains("outside -80..150"),
        "{error}"
    );
}

// Issue 37 row 5: a format of 60,000 array elements under a 60,000-character name asked for
// gigabytes of names (SIGABRT under a 2 GB cap); it is refused from the name's length.
#[test]
fn a_format_with_a_huge_field_name_is_refused_before_its_names_are_built() {
    let mut out = log_start();
    let name = "n".repeat(60_000);
    format(&mut out, &format!("huge:uint8_t[60000] {name};"));
    subscribe(&mut out, 0, "huge");
    let error = decode_ulog(&out, "huge.ulg").unwrap_err().to_string();
    assert!(
        error.contains("huge.ulg") && error.contains("longer than the 256"),
        "{error}"
    );
}
