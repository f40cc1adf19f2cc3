//! KF-GINS text files against the column definitions of the KF-GINS README (§2.2 "Data
//! format"): hand-written lines in that layout, each value checked where the README puts it.

use thermonav::imu::SampleKind;
use thermonav::time::NANOS_PER_SECOND;
use thermonav::units::deg_to_rad;
use thermonav_io::Strictness;
use thermonav_io::kf_gins::{read_kf_gins_gnss, read_kf_gins_imu, read_kf_gins_nav};

const STRICT: Strictness = Strictness::Strict;

#[test]
fn imu_columns_are_time_then_angle_then_velocity_increments() {
    // README: 1 GNSS seconds of week [s]; 2–4 X-Y-Z incremental angles [rad]; 5–7 X-Y-Z
    // incremental velocity [m/s]. An eighth column (odometer) is ignored, as KF-GINS does.
    let text = "456300.005 1.5e-5 -2.0e-5 3.0e-6 0.0012 -0.0007 -0.049 0.01\n\
                456300.010 1.0e-5 -1.0e-5 2.0e-6 0.0010 -0.0005 -0.048 0.01\n";
    let series = read_kf_gins_imu(text.as_bytes(), "imu.txt", None, STRICT).unwrap();
    assert_eq!(series.kind, Some(SampleKind::Increments));
    assert_eq!(series.len(), 2);
    assert_eq!(series.time[0].as_nanos(), 456_300_005_000_000);
    let first: Vec<f64> = series.channels.iter().map(|c| c[0]).collect();
    assert_eq!(first, [1.5e-5, -2.0e-5, 3.0e-6, 0.0012, -0.0007, -0.049]);
    // With a week, seconds of week land on the GPST scale: week 2000 began 2018-05-06, Unix
    // 1 525 564 800 s (GNU date).
    let series = read_kf_gins_imu(text.as_bytes(), "imu.txt", Some(2000), STRICT).unwrap();
    assert_eq!(
        series.time[0].as_nanos(),
        1_525_564_800 * NANOS_PER_SECOND + 456_300_005_000_000
    );
}

#[test]
fn gnss_columns_are_position_then_ned_std_or_velocity_first() {
    // README: 1 seconds of week; 2 latitude [deg]; 3 longitude [deg]; 4 ellipsoidal height
    // [m]; 5–7 position STD north-east-down [m].
    let seven =
        "456250.000    30.4447858054   114.4718661162     21.095    0.010    0.009    0.019\n";
    let fix = read_kf_gins_gnss(seven.as_bytes(), "gnss.txt", None, STRICT).unwrap()[0];
    assert_eq!(fix.time.as_nanos(), 456_250 * NANOS_PER_SECOND);
    assert_eq!(fix.latitude_rad, deg_to_rad(30.4447858054));
    assert_eq!(fix.longitude_rad, deg_to_rad(114.4718661162));
    assert_eq!(fix.height_m, 21.095);
    assert_eq!(fix.position_sd_ned_m, Some([0.010, 0.009, 0.019]));
    assert_eq!(fix.velocity_ned_m_s, None);
    // 13 columns (gnssfileloader.h): velocity in 5–7, position STD in 8–10, velocity STD 11–13.
    let thirteen = "456250.000 30.4 114.4 21.0 1.5 -2.5 0.1 0.010 0.009 0.019 0.05 0.05 0.08\n";
    let fix = read_kf_gins_gnss(thirteen.as_bytes(), "gnss.txt", None, STRICT).unwrap()[0];
    assert_eq!(fix.velocity_ned_m_s, Some([1.5, -2.5, 0.1]));
    assert_eq!(fix.position_sd_ned_m, Some([0.010, 0.009, 0.019]));
}

#[test]
fn nav_columns_are_week_time_position_velocity_attitude() {
    // README: 1 GNSS week; 2 seconds of week; 3 lat; 4 lon [deg]; 5 h [m]; 6–8 v NED [m/s];
    // 9–11 roll, pitch, yaw [deg].
    let text = "2000 456300.000 30.44 114.47 20.5 1.0 2.0 -0.1 0.5 -1.5 270.0\n\
                0 456300.005 30.44 114.47 20.5 1.0 2.0 -0.1 0.5 -1.5 270.0\n";
    let points = read_kf_gins_nav(text.as_bytes(), "truth.nav", Strictness::Lenient).unwrap();
    let p = points[0];
    assert_eq!(
        p.time.as_nanos(),
        (1_525_564_800 + 456_300) * NANOS_PER_SECOND
    );
    assert_eq!(p.latitude_rad, deg_to_rad(30.44));
    assert_eq!(p.height_m, 20.5);
    assert_eq!(p.velocity_ned_m_s, [1.0, 2.0, -0.1]);
    assert_eq!(
        [p.roll_rad, p.pitch_rad, p.yaw_rad],
        [deg_to_rad(0.5), deg_to_rad(-1.5), deg_to_rad(270.0)]
    );
    // Week 0 ("set to 0" in some datasets) keeps seconds of week.
    assert_eq!(points[1].time.as_nanos(), 456_300_005_000_000);
}

fn error_of<T>(result: Result<T, thermonav_io::ReadError>) -> String {
    match result {
        Ok(_) => panic!("expected an error"),
        Err(error) => error.to_string(),
    }
}

#[test]
fn bad_input_names_file_line_and_expectation() {
    let imu = |text: &str| error_of(read_kf_gins_imu(text.as_bytes(), "imu.txt", None, STRICT));
    let gnss = |text: &str| error_of(read_kf_gins_gnss(text.as_bytes(), "gnss.txt", None, STRICT));
    let nav = |text: &str| error_of(read_kf_gins_nav(text.as_bytes(), "truth.nav", STRICT));
    assert_eq!(
        imu(""),
        "imu.txt: no data (expected time dthx dthy dthz dvx dvy dvz)"
    );
    assert_eq!(
        imu("1 0 0 0 0 0 0\n2 0 0 0\n"),
        "imu.txt:2: expected 7 fields (time dthx dthy dthz dvx dvy dvz, at least), found 4"
    );
    assert_eq!(
        imu("1,0,0,0,0,0,0\n"),
        "imu.txt:1: expected 7 fields (time dthx dthy dthz dvx dvy dvz, at least), found 1"
    );
    assert_eq!(
        imu("1 0 0 NaN 0 0 0\n"),
        "imu.txt:1: column dthz (field 4): value \"NaN\" is not finite (strict reading)"
    );
    assert!(
        imu("\u{0}\u{1}\u{2} \u{3} \u{4} \u{5} \u{6} \u{7} \u{8}\n")
            .starts_with("imu.txt:1: column time (field 1)")
    );
    assert_eq!(
        gnss("1 30 114 20 0.01 0.01 0.02\n2 30 114 20 0.01 0.01 0.02 1 2 3 0.1 0.1 0.1\n"),
        "gnss.txt:2: expected 7 fields (time lat lon h sdn sde sdd, or 13 with vn ve vd after \
         h), found 13"
    );
    assert_eq!(
        gnss("1 95 114 20 0.01 0.01 0.02\n"),
        "gnss.txt:1: column lat_deg: value 95 is out of range (expected -90 to 90; strict reading)"
    );
    assert_eq!(
        nav("0 1 30 114 20 0 0 0 0 0 0\n0 1 30 114 20 0 0 0 0 0 0\n"),
        "truth.nav:2: time 1.000000000 s does not increase after 1.000000000 s on line 1 \
         (strict reading)"
    );
    assert_eq!(
        nav("1.5 1 30 114 20 0 0 0 0 0 0\n"),
        "truth.nav:1: field 1 (week): expected a whole GPS week number, found \"1.5\""
    );
}
