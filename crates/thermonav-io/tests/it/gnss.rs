//! GNSS CSV: required columns, all-or-nothing optional groups, degrees to radians.

use crate::support::within_ulps;
use std::f64::consts::PI;
use thermonav::gnss::HeadingObservation;
use thermonav_io::{ReadErrorKind, Strictness, read_gnss};

const NAME: &str = "gnss.csv";

fn gnss(text: &str, strictness: Strictness) -> Result<Vec<thermonav::gnss::GnssFix>, String> {
    read_gnss(text.as_bytes(), NAME, strictness).map_err(|e| e.to_string())
}

#[test]
fn position_only_file_has_no_optional_groups() {
    let fixes = gnss(
        "t_s,lat_deg,lon_deg,h_m\n1,45,-90,100.5\n2,-30,180,-3\n",
        Strictness::Strict,
    )
    .unwrap();
    assert_eq!(fixes.len(), 2);
    let fix = fixes[0];
    // 45° = π/4 and -90° = -π/2: one rounding of (deg·fl(π/180)), within 1 ulp.
    assert!(within_ulps(fix.latitude_rad, PI / 4.0, 1));
    assert!(within_ulps(fix.longitude_rad, -PI / 2.0, 1));
    assert_eq!(fix.height_m, 100.5);
    assert_eq!(fix.time.as_nanos(), 1_000_000_000);
    assert_eq!(fix.position_sd_ned_m, None);
    assert_eq!(fix.velocity_ned_m_s, None);
    assert_eq!(fix.heading, None);
    assert!(within_ulps(fixes[1].longitude_rad, PI, 1));
}

#[test]
fn every_optional_group_is_read_in_any_column_order() {
    let text = "sd_heading_deg,vd_m_s,t_s,sd_u_m,lon_deg,ve_m_s,heading_deg,sd_e_m,h_m,vn_m_s,\
                sd_n_m,lat_deg\n\
                0.5,-0.1,10.25,3,1,2.5,90,1.5,50,-1.25,1,0\n";
    let fix = gnss(text, Strictness::Strict).unwrap()[0];
    assert_eq!(fix.time.as_nanos(), 10_250_000_000);
    assert_eq!(fix.latitude_rad, 0.0);
    // 1° = π/180 (bit-equal: the conversion factor itself).
    assert_eq!(fix.longitude_rad, PI / 180.0);
    assert_eq!(fix.height_m, 50.0);
    assert_eq!(fix.position_sd_ned_m, Some([1.0, 1.5, 3.0]));
    assert_eq!(fix.velocity_ned_m_s, Some([-1.25, 2.5, -0.1]));
    let HeadingObservation {
        heading_rad,
        sd_rad,
    } = fix.heading.unwrap();
    // 90° = π/2 within 1 ulp; 0.5° = π/360 exactly (halving the factor is exact).
    assert!(within_ulps(heading_rad, PI / 2.0, 1));
    assert_eq!(sd_rad, PI / 360.0);
}

#[test]
fn partial_groups_are_errors() {
    assert_eq!(
        gnss(
            "t_s,lat_deg,lon_deg,h_m,sd_n_m,sd_e_m\n0,0,0,0,1,1\n",
            Strictness::Strict
        )
        .unwrap_err(),
        "gnss.csv:1: incomplete column group sd_n_m,sd_e_m,sd_u_m: has sd_n_m but not sd_u_m"
    );
    assert_eq!(
        gnss(
            "t_s,lat_deg,lon_deg,h_m,vd_m_s\n0,0,0,0,1\n",
            Strictness::Strict
        )
        .unwrap_err(),
        "gnss.csv:1: incomplete column group vn_m_s,ve_m_s,vd_m_s: has vd_m_s but not vn_m_s"
    );
    assert_eq!(
        gnss(
            "t_s,lat_deg,lon_deg,h_m,heading_deg\n0,0,0,0,1\n",
            Strictness::Lenient
        )
        .unwrap_err(),
        "gnss.csv:1: incomplete column group heading_deg,sd_heading_deg: \
         has heading_deg but not sd_heading_deg"
    );
}

#[test]
fn required_and_unknown_columns() {
    assert_eq!(
        gnss("t_s,lat_deg,h_m\n0,0,0\n", Strictness::Strict).unwrap_err(),
        "gnss.csv:1: missing column lon_deg"
    );
    let error = read_gnss(
        &b"t_s,lat_deg,lon_deg,h_m,speed\n"[..],
        NAME,
        Strictness::Strict,
    )
    .unwrap_err();
    assert!(matches!(error.kind, ReadErrorKind::UnknownColumn { ref name, .. } if name == "speed"));
}

#[test]
fn strict_rejects_impossible_latitudes_and_negative_deviations_lenient_keeps_them() {
    let bad_latitude = "t_s,lat_deg,lon_deg,h_m\n0,10,0,0\n1,90.5,0,0\n";
    assert_eq!(
        gnss(bad_latitude, Strictness::Strict).unwrap_err(),
        "gnss.csv:3: column lat_deg: value 90.5 is out of range (expected -90 to 90; strict reading)"
    );
    let negative_sd = "t_s,lat_deg,lon_deg,h_m,sd_n_m,sd_e_m,sd_u_m\n0,0,0,0,1,-2,3\n";
    assert_eq!(
        gnss(negative_sd, Strictness::Strict).unwrap_err(),
        "gnss.csv:2: column sd_e_m: value -2 is out of range \
         (expected a standard deviation > 0 (a fix of zero spread would be trusted without limit); strict reading)"
    );
    let negative_heading_sd =
        "t_s,lat_deg,lon_deg,h_m,heading_deg,sd_heading_deg\n0,0,0,0,1,-0.25\n";
    assert_eq!(
        gnss(negative_heading_sd, Strictness::Strict).unwrap_err(),
        "gnss.csv:2: column sd_heading_deg: value -0.25 is out of range \
         (expected a standard deviation > 0 (a fix of zero spread would be trusted without limit); strict reading)"
    );
    let zero_sd = "t_s,lat_deg,lon_deg,h_m,sd_n_m,sd_e_m,sd_u_m\n0,0,0,0,1,0,3\n";
    assert!(
        gnss(zero_sd, Strictness::Strict)
            .unwrap_err()
            .contains("column sd_e_m: value 0 is out of range")
    );
    let huge_height = "t_s,lat_deg,lon_deg,h_m\n0,10,0,1e300\n";
    assert!(
        gnss(huge_height, Strictness::Strict)
            .unwrap_err()
            .starts_with("gnss.csv:2: column h_m: value \"1e300\" is too large")
    );
    let high = "t_s,lat_deg,lon_deg,h_m\n0,10,0,200000\n";
    assert!(
        gnss(high, Strictness::Strict)
            .unwrap_err()
            .contains("column h_m: value 200000 is out of range (expected -12000 to 100000 m")
    );
    let kept = gnss(bad_latitude, Strictness::Lenient).unwrap();
    assert!(kept[1].latitude_rad > PI / 2.0);
    // Exactly ±90° is a latitude.
    assert!(
        gnss(
            "t_s,lat_deg,lon_deg,h_m\n0,90,0,0\n1,-90,0,0\n",
            Strictness::Strict
        )
        .is_ok()
    );
}

#[test]
fn strict_rejects_unordered_fix_times() {
    assert_eq!(
        gnss(
            "t_s,lat_deg,lon_deg,h_m\n2,0,0,0\n1,0,0,0\n",
            Strictness::Strict
        )
        .unwrap_err(),
        "gnss.csv:3: time 1.000000000 s does not increase after 2.000000000 s on line 2 \
         (strict reading)"
    );
}

#[test]
fn groups_missing_at_some_fixes_are_dropped_from_all() {
    use thermonav_io::keep_common_groups;
    let text = "t_s,lat_deg,lon_deg,h_m,vn_m_s,ve_m_s,vd_m_s\n1,45,-90,100,1,2,3\n";
    let with_velocity = gnss(text, Strictness::Strict).unwrap()[0];
    let mut fixes = vec![with_velocity, with_velocity];
    assert!(keep_common_groups(&mut fixes).is_empty());
    assert!(fixes.iter().all(|f| f.velocity_ned_m_s.is_some()));
    fixes[1].velocity_ned_m_s = None;
    assert_eq!(keep_common_groups(&mut fixes), ["vn_m_s,ve_m_s,vd_m_s"]);
    assert!(fixes.iter().all(|f| f.velocity_ned_m_s.is_none()));
    let mut out = Vec::new();
    thermonav_io::write_gnss(&mut out, &fixes).unwrap();
}
