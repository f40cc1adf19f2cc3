//! Raw IMU CSV + RTKLIB time tag: the real drive of shared/data/rtklibexplorer-gnss-imu against
//! the numbers its README documents; bad CSV and tag files.

use crate::support::shared_data;
use thermonav::imu::{Channel, SampleKind};
use thermonav::time::{Duration, NANOS_PER_SECOND};
use thermonav::units::STANDARD_GRAVITY_M_S2;
use thermonav_io::Strictness;
use thermonav_io::raw_imu::{
    ImuFrame, RawImuSettings, TimeTag, decode_time_tag, read_raw_imu, read_raw_imu_files,
    read_time_tag_file,
};

const CSV: &str = "rtklibexplorer-gnss-imu/drive_0708/imu_1934.csv";
const TAG: &str = "rtklibexplorer-gnss-imu/drive_0708/imu_1934.csv.tag";

/// Unix seconds of 2025-07-08 19:34:21 (GNU `date -u -d … +%s`): the documented drive start
/// 19:34:21.854 GPST on the GPST-counted scale.
const START_WHOLE_SECOND: i64 = 1_752_003_261;

#[test]
fn tag_file_gives_the_documented_start_and_span() {
    let tag = read_time_tag_file(shared_data(TAG)).unwrap();
    // README: drive start 2025-07-08 19:34:21.854 GPST, span 548.731 s.
    assert_eq!(
        tag.start.as_nanos(),
        START_WHOLE_SECOND * NANOS_PER_SECOND + 854_000_000
    );
    assert_eq!(tag.span.as_nanos(), 548_731_000_000);
}

#[test]
fn drive_imu_has_the_documented_rows_span_and_gravity() {
    let series = read_raw_imu_files(
        shared_data(CSV),
        shared_data(TAG),
        RawImuSettings::default(),
    )
    .unwrap();
    // README: 54 860 rows; the first and last (partial) lines are dropped.
    assert_eq!(series.len(), 54_860 - 2);
    assert_eq!(series.kind, Some(SampleKind::Rates));
    let first = series.time[0];
    let last = series.time[series.len() - 1];
    assert_eq!(
        first.as_nanos(),
        START_WHOLE_SECOND * NANOS_PER_SECOND + 854_000_000
    );
    // The ticks are stretched onto the tag's span: the last sample is exactly 548.731 s later.
    assert_eq!(last.since(first).as_nanos(), 548_731_000_000);
    // README: 100 Hz over 549 s. Mean rate within 0.5 % of 100 Hz (the IMU clock and GPST
    // differ by the stretch, a few hundred ppm at most).
    let rate_hz = (series.len() - 1) as f64 / last.since(first).as_seconds();
    assert!((rate_hz - 100.0).abs() < 0.5, "{rate_hz}");
    // README: at rest az ≈ +1.0 g (sensor z up). The car stands still at the start (the RTK
    // velocity is below 0.03 m/s there); the mean of the first second is within 3 % of 1 g
    // (MEMS bias and scale error, and the roof's tilt).
    let az: f64 = series.channel(Channel::Az)[..100].iter().sum::<f64>() / 100.0;
    assert!(
        (az / STANDARD_GRAVITY_M_S2 - 1.0).abs() < 0.03,
        "az = {az} m/s²"
    );
    // First kept line: 0.116,0.031,0.985,-0.359,0.946,0.168 → SI by g and π/180.
    assert_eq!(
        series.channel(Channel::Ax)[0],
        0.116 * STANDARD_GRAVITY_M_S2
    );
    assert_eq!(
        series.channel(Channel::Gy)[0],
        thermonav::units::deg_to_rad(0.946)
    );
}

#[test]
fn drive_mounting_turns_the_sensor_frame_into_frd() {
    let settings = RawImuSettings {
        frame: ImuFrame::DriveMountingFrd,
        time_offset: Duration::from_nanos(-125_000_000),
        ..RawImuSettings::default()
    };
    let series = read_raw_imu_files(shared_data(CSV), shared_data(TAG), settings).unwrap();
    // z down: specific force at rest points up, so az ≈ −1 g; x is negated, y kept.
    let az: f64 = series.channel(Channel::Az)[..100].iter().sum::<f64>() / 100.0;
    assert!((az / STANDARD_GRAVITY_M_S2 + 1.0).abs() < 0.03, "{az}");
    assert_eq!(
        series.channel(Channel::Ax)[0],
        -0.116 * STANDARD_GRAVITY_M_S2
    );
    assert_eq!(
        series.channel(Channel::Ay)[0],
        0.031 * STANDARD_GRAVITY_M_S2
    );
    // The author's logging delay, −0.125 s.
    assert_eq!(
        series.time[0].as_nanos(),
        START_WHOLE_SECOND * NANOS_PER_SECOND + 729_000_000
    );
}

/// A tag file starting at 1 000 s with a 2-s span.
fn small_tag() -> TimeTag {
    let mut bytes = b"TIMETAG RTKLIB test".to_vec();
    bytes.resize(60, 0);
    bytes.extend(7_u32.to_le_bytes());
    bytes.extend(1_000_u32.to_le_bytes());
    bytes.extend(0.5_f64.to_le_bytes());
    for (tick, offset) in [(0_u32, 0_u32), (2_000, 120)] {
        bytes.extend(tick.to_le_bytes());
        bytes.extend(offset.to_le_bytes());
    }
    decode_time_tag(&bytes, "small.tag").unwrap()
}

fn raw_error(text: &str) -> String {
    match read_raw_imu(
        text.as_bytes(),
        "imu.csv",
        &small_tag(),
        RawImuSettings::default(),
    ) {
        Ok(series) => panic!("expected an error, read {} samples", series.len()),
        Err(error) => error.to_string(),
    }
}

const GOOD: &str = "0,0,1,0,0,0,100\n";

#[test]
fn small_file_is_stretched_onto_the_tag_span() {
    let text = format!("partial\n{GOOD}0,0,1,0,0,0,110\n0,0,1,0,0,0,120\n0,0,");
    let series = read_raw_imu(
        text.as_bytes(),
        "imu.csv",
        &small_tag(),
        RawImuSettings::default(),
    )
    .unwrap();
    let times: Vec<i64> = series.time.iter().map(|t| t.as_nanos()).collect();
    // Start 1000.5 s; ticks 100, 110, 120 stretched onto 2 s: 0, 1, 2 s after the start.
    assert_eq!(
        times,
        [1_000_500_000_000, 1_001_500_000_000, 1_002_500_000_000]
    );
}

#[test]
fn bad_csv_names_file_line_and_expectation() {
    assert_eq!(
        raw_error(""),
        "imu.csv: no data (expected at least 3 lines of ax,ay,az,gx,gy,gz,tick; the first and \
         last are partial and dropped)"
    );
    assert_eq!(
        raw_error(&format!("x\n{GOOD}0,0,1,0\n{GOOD}x\n")),
        "imu.csv:3: expected 7 fields (ax,ay,az (g), gx,gy,gz (deg/s), tick (ms)), found 4"
    );
    assert_eq!(
        raw_error(&format!("x\n{GOOD}0;0;1;0;0;0;110\nx\n")),
        "imu.csv:3: expected 7 fields (ax,ay,az (g), gx,gy,gz (deg/s), tick (ms)), found 1"
    );
    assert_eq!(
        raw_error(&format!("x\n{GOOD}0,NaN,1,0,0,0,110\nx\n")),
        "imu.csv:3: column ay (g) (field 2): value \"NaN\" is not finite (strict reading)"
    );
    assert_eq!(
        raw_error(&format!("x\n{GOOD}0,0,1,0,0,0,100.5\nx\n")),
        "imu.csv:3: field 7 (tick): expected whole milliseconds since power-up, found \"100.5\""
    );
    assert!(
        raw_error(&format!("x\n{GOOD}{GOOD}x\n")).starts_with("imu.csv:3: time 0.100000000 s"),
        "{}",
        raw_error(&format!("x\n{GOOD}{GOOD}x\n"))
    );
    let garbage = "\u{0}\u{1}\n\u{2}\u{3},\u{4}\u{5},\u{6},\u{7},\u{8},\u{e},\u{f}\n\u{10}\n";
    assert!(raw_error(garbage).starts_with("imu.csv:2: column ax (g) (field 1)"));
    assert!(raw_error(&format!("x\n{GOOD}x\n")).contains("same tick 100 ms"));
    // Lenient reading keeps NaN.
    let text = format!("x\n{GOOD}0,NaN,1,0,0,0,110\nx\n");
    let settings = RawImuSettings {
        strictness: Strictness::Lenient,
        ..RawImuSettings::default()
    };
    let series = read_raw_imu(text.as_bytes(), "imu.csv", &small_tag(), settings).unwrap();
    assert!(series.channel(Channel::Ay)[1].is_nan());
}

#[test]
fn bad_tag_files_name_the_byte() {
    let message = |bytes: &[u8]| decode_time_tag(bytes, "x.tag").unwrap_err().to_string();
    assert_eq!(
        message(b""),
        "x.tag: at byte 0: expected a 76-byte RTKLIB time-tag header"
    );
    assert_eq!(
        message(&[0xAB; 100]),
        "x.tag: at byte 0: expected the text TIMETAG (an RTKLIB time-tag file)"
    );
    let mut header = b"TIMETAG".to_vec();
    header.resize(76, 0);
    assert_eq!(
        message(&header),
        "x.tag: at byte 76: expected at least one tick/offset pair"
    );
    header.extend([1, 2, 3]);
    assert_eq!(
        message(&header),
        "x.tag: at byte 76: expected whole 8-byte tick/offset pairs"
    );
    let mut nan = b"TIMETAG".to_vec();
    nan.resize(68, 0);
    nan.extend(f64::NAN.to_le_bytes());
    nan.extend([0; 8]);
    assert_eq!(
        message(&nan),
        "x.tag: at byte 68: expected a fraction of a second in [0, 1)"
    );
}
