//! Units other than SI are converted once, as read, against hand-computed closed forms; column
//! order does not matter; increments give increment series.

use crate::support::{read, within_ulps};
use std::f64::consts::PI;
use thermonav::imu::{Channel, SampleKind};
use thermonav_io::{ImuReader, Strictness};

#[test]
fn rate_units_convert_to_si_in_any_column_order() {
    // Columns shuffled and every rate unit used once.
    let text = "az_m_s2,temp_c,gy_deg_h,ax_g,t_s,gz_rad_s,ay_mg,gx_deg_s\n\
                -9.5,21.25,3600,1,0.005,0.125,500,1\n\
                -9.5,21.5,-7200,-2,0.010,0.25,1000,180\n";
    let series = read(text, Strictness::Strict).unwrap();
    assert_eq!(series.kind, Some(SampleKind::Rates));
    // 1 deg/s = π/180 rad/s: one rounding of the same quotient, so bit-equal.
    assert_eq!(series.channel(Channel::Gx)[0], PI / 180.0);
    // 180 deg/s = π rad/s: 180·fl(π/180) rounds once more, within 1 ulp of π.
    assert!(within_ulps(series.channel(Channel::Gx)[1], PI, 1));
    // 3600 deg/h = 1 deg/s = π/180 rad/s; two roundings (×π/180, ÷3600): within 2 ulps.
    assert!(within_ulps(series.channel(Channel::Gy)[0], PI / 180.0, 2));
    assert!(within_ulps(
        series.channel(Channel::Gy)[1],
        -2.0 * PI / 180.0,
        2
    ));
    assert_eq!(series.channel(Channel::Gz), [0.125, 0.25]);
    // 1 g = 9.80665 m/s² by definition: exact.
    assert_eq!(series.channel(Channel::Ax), [9.80665, -2.0 * 9.80665]);
    // 1000 mg = 1 g exactly (1000/1000 = 1); 500 mg = 4.903325 m/s² within 1 ulp.
    assert!(within_ulps(series.channel(Channel::Ay)[0], 4.903325, 1));
    assert_eq!(series.channel(Channel::Ay)[1], 9.80665);
    assert_eq!(series.channel(Channel::Az), [-9.5, -9.5]);
    assert_eq!(series.temperature_c.as_deref(), Some(&[21.25, 21.5][..]));
    let nanos: Vec<i64> = series.time.iter().map(|t| t.as_nanos()).collect();
    assert_eq!(nanos, [5_000_000, 10_000_000]);
}

#[test]
fn increments_in_degrees_and_si_give_an_increment_series() {
    let text = "t_s,dthx_deg,dthy_deg,dthz_rad,dvx_m_s,dvy_m_s,dvz_m_s\n\
                0.005,1,-0.5,0.001,0.01,-0.02,-0.049\n";
    let mut reader = ImuReader::new(text.as_bytes(), "inc.csv", Strictness::Strict).unwrap();
    assert_eq!(reader.kind(), SampleKind::Increments);
    assert!(!reader.has_temperature());
    let sample = reader.next().unwrap().unwrap();
    // 1 deg = π/180 rad (bit-equal, one rounding); -0.5 deg = -π/360 (halving is exact).
    assert_eq!(sample.gyro, [PI / 180.0, -PI / 360.0, 0.001]);
    assert_eq!(sample.accel, [0.01, -0.02, -0.049]);
    assert_eq!(sample.temperature_c, None);
    assert!(reader.next().is_none());

    let series = read(text, Strictness::Strict).unwrap();
    assert_eq!(series.kind, Some(SampleKind::Increments));
    assert_eq!(series.temperature_c, None);
}

#[test]
fn exact_times_keep_every_nanosecond_of_an_epoch_time() {
    // As f64, 1.7e9 s is resolved to ~0.24 µs; the reader must keep the nanoseconds.
    let text = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2\n\
                1700000000.000000001,0,0,0,0,0,0\n\
                1700000000.005000002,0,0,0,0,0,0\n\
                1700000000.0100000035,0,0,0,0,0,0\n";
    let series = read(text, Strictness::Strict).unwrap();
    let nanos: Vec<i64> = series.time.iter().map(|t| t.as_nanos()).collect();
    let epoch = 1_700_000_000_000_000_000;
    // The third has ten decimals: 3.5 ns rounds to 4 ns.
    assert_eq!(nanos, [epoch + 1, epoch + 5_000_002, epoch + 10_000_004]);
}

/// A static increments record at 100 Hz whose velocity increments are `g_value` per second.
fn static_increments(g_value: f64) -> String {
    (0..50).fold(
        "t_s,dthx_rad,dthy_rad,dthz_rad,dvx_m_s,dvy_m_s,dvz_m_s\n".to_string(),
        |text, k| text + &format!("{:.2},0,0,0,0,0,{}\n", k as f64 / 100.0, -g_value / 100.0),
    )
}

#[test]
fn accelerations_in_g_under_si_names_are_refused_at_the_header() {
    // Closed form: a static record holds |a| = 9.80665 m/s² (standard gravity). Written in g it
    // holds 1.0, which strict reading refuses at line 1, the header that names the unit; rates
    // with |a| = √(0.6² + 0.8²) = 1 likewise. Increments: |dv| / dt = 0.0980665 / 0.01.
    let error = read(&static_increments(1.0), Strictness::Strict).unwrap_err();
    assert_eq!(error.line, Some(1));
    assert!(
        error
            .to_string()
            .contains("mean |a| over the 50 samples is 1.000 m/s^2"),
        "{error}"
    );
    let rates = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2\n0,0,0,0,0.6,0,0.8\n";
    assert!(read(rates, Strictness::Strict).is_err());
    assert!(read(&static_increments(9.80665), Strictness::Strict).is_ok());
    // Lenient reading (inspect) keeps the record to report on it.
    assert!(read(&static_increments(1.0), Strictness::Lenient).is_ok());
}
