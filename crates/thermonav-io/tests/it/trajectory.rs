//! Reference trajectory CSV: all columns required, degrees to radians.

use crate::support::within_ulps;
use std::f64::consts::PI;
use thermonav_io::{Strictness, read_trajectory};

#[test]
fn trajectory_is_read_in_any_column_order_and_converted() {
    let text = "yaw_deg,t_s,lat_deg,lon_deg,h_m,vn_m_s,ve_m_s,vd_m_s,roll_deg,pitch_deg\n\
                -180,0.5,60,10,12.5,1,2,3,1,-45\n";
    let points = read_trajectory(text.as_bytes(), "ref.csv", Strictness::Strict).unwrap();
    assert_eq!(points.len(), 1);
    let p = points[0];
    assert_eq!(p.time.as_nanos(), 500_000_000);
    // deg·fl(π/180) rounds once: within 1 ulp of the closed forms π/3, π/18, -π/4, -π.
    assert!(within_ulps(p.latitude_rad, PI / 3.0, 1));
    assert!(within_ulps(p.longitude_rad, PI / 18.0, 1));
    assert_eq!(p.height_m, 12.5);
    assert_eq!(p.velocity_ned_m_s, [1.0, 2.0, 3.0]);
    assert_eq!(p.roll_rad, PI / 180.0);
    assert!(within_ulps(p.pitch_rad, -PI / 4.0, 1));
    assert!(within_ulps(p.yaw_rad, -PI, 1));
}

#[test]
fn every_trajectory_column_is_required() {
    let text = "t_s,lat_deg,lon_deg,h_m,vn_m_s,ve_m_s,vd_m_s,roll_deg,yaw_deg\n0,0,0,0,0,0,0,0,0\n";
    let error = read_trajectory(text.as_bytes(), "ref.csv", Strictness::Strict).unwrap_err();
    assert_eq!(error.to_string(), "ref.csv:1: missing column pitch_deg");
}

#[test]
fn strict_trajectory_rejects_nan_attitude() {
    let text = "t_s,lat_deg,lon_deg,h_m,vn_m_s,ve_m_s,vd_m_s,roll_deg,pitch_deg,yaw_deg\n\
                0,0,0,0,0,0,0,0,nan,0\n";
    let error = read_trajectory(text.as_bytes(), "ref.csv", Strictness::Strict).unwrap_err();
    assert_eq!(
        error.to_string(),
        "ref.csv:2: column pitch_deg: value \"nan\" is not finite (strict reading)"
    );
    let kept = read_trajectory(text.as_bytes(), "ref.csv", Strictness::Lenient).unwrap();
    assert!(kept[0].pitch_rad.is_nan());
}
