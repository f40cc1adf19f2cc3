//! NMEA 0183 against published example sentences and the values their documents state.
//!
//! Sources (sentences copied verbatim unless said otherwise):
//! - GGA `$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47`, RMC
//!   `$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A` and VTG
//!   `$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48`: the gpsinformation.org NMEA reference (Dale
//!   DePriest), reproduced in gpsd's "NMEA Revealed" and many receiver notes: "fix taken at
//!   12:35:19 UTC, latitude 48 deg 07.038' N, longitude 11 deg 31.000' E, fix quality 1,
//!   8 satellites, HDOP 0.9, altitude 545.4 m above mean sea level, height of geoid above WGS84
//!   ellipsoid 46.9 m"; RMC "speed over the ground 22.4 knots, track angle 84.4 deg true, date
//!   23rd of March 1994"; VTG "true track 54.7 deg, ground speed 5.5 knots, 10.2 km/h".
//! - HDT `$GPHDT,123.456,T*00`: Trimble R750 help, "NMEA-0183 message: HDT" (heading 123.456°
//!   from true north). Its `*00` is not the sentence's checksum (that is `*32`): it serves here
//!   as a real bad-checksum line, and the corrected sentence as the valid one.
//! - u-blox 8 / M8 Receiver Description including Protocol Specification, NMEA messages:
//!   GGA `$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5B`
//!   (09:27:25.00 UTC, 47°17.11399′ N, 8°33.91590′ E, quality 1, altitude 499.6 m, geoid
//!   separation 48.0 m) and RMC `$GPRMC,083559.00,A,4717.11437,N,00833.91522,E,0.004,77.52,
//!   091202,,,A*57` (08:35:59.00 UTC, 0.004 kn, 77.52°, 9 December 2002); the empty sentences
//!   a u-blox receiver sends before its first fix, `$GPGGA,,,,,,0,00,99.99,,,,,,*48` and
//!   `$GPRMC,,V,,,,,,,,,,N*53`.
//! - THS `$HETHS,316.70,E*1A`: Navis NavDP-4000 manual, "THS Message: True Heading and Status"
//!   (heading 316.70° true, mode E = estimated).

use thermonav::time::{Duration, NANOS_PER_SECOND};
use thermonav::units::deg_to_rad;
use thermonav_io::Strictness;
use thermonav_io::nmea::{NmeaSettings, read_nmea};

const GGA: &str = "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47";
const RMC: &str = "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A";
const VTG: &str = "$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48";
const HDT_PUBLISHED: &str = "$GPHDT,123.456,T*00";
const HDT: &str = "$GPHDT,123.456,T*32";
const THS: &str = "$HETHS,316.70,E*1A";

/// Unix seconds of 1994-03-23 12:35:19 UTC (GNU `date -u -d … +%s`).
const FIX_UTC_S: i64 = 764_426_119;

/// Unix seconds of 2002-12-09 09:27:25 UTC (GNU `date -u -d … +%s`).
const UBLOX_GGA_UTC_S: i64 = 1_039_426_045;

/// GPS − UTC on 1994-03-23: TAI − UTC was 28 s (IERS Bulletin C, 1993-07-01 to 1994-07-01)
/// and GPS − TAI is −19 s, so 9 s.
fn settings_1994() -> NmeaSettings {
    NmeaSettings {
        gpst_minus_utc: Duration::from_nanos(9 * NANOS_PER_SECOND),
        heading_sd_rad: Some(deg_to_rad(0.2)),
        level_velocity: true,
        ..NmeaSettings::default()
    }
}

fn log(lines: &[&str]) -> String {
    lines.iter().map(|l| format!("{l}\r\n")).collect()
}

/// Degrees within 1e-12° (the decoded minutes are divided by 60 once).
fn close_deg(rad: f64, deg: f64) -> bool {
    (rad.to_degrees() - deg).abs() < 1e-12
}

#[test]
fn gga_and_rmc_give_the_documented_position_time_and_velocity() {
    let fixes = read_nmea(log(&[GGA, RMC]).as_bytes(), "log.nmea", settings_1994()).unwrap();
    assert_eq!(fixes.len(), 1);
    let fix = fixes[0];
    // 48° 07.038′ N = 48.1173°, 11° 31.000′ E = 11.51666…°.
    assert!(
        close_deg(fix.latitude_rad, 48.0 + 7.038 / 60.0),
        "{}",
        fix.latitude_rad
    );
    assert!(close_deg(fix.longitude_rad, 11.0 + 31.0 / 60.0));
    // Ellipsoidal height = 545.4 m above MSL + 46.9 m geoid height.
    assert!((fix.height_m - 592.3).abs() < 1e-9, "{}", fix.height_m);
    assert_eq!(fix.time.as_nanos(), (FIX_UTC_S + 9) * NANOS_PER_SECOND);
    // 22.4 kn (1 kn = 1852 m/h) along 84.4° true; down set to 0 by the level-velocity setting.
    let [vn, ve, vd] = fix.velocity_ned_m_s.unwrap();
    let speed = 22.4 * 1852.0 / 3600.0;
    assert!((vn - speed * 84.4_f64.to_radians().cos()).abs() < 1e-12);
    assert!((ve - speed * 84.4_f64.to_radians().sin()).abs() < 1e-12);
    assert_eq!(vd, 0.0);
    assert_eq!(fix.position_sd_ned_m, None);
    assert_eq!(fix.heading, None);
}

#[test]
fn vtg_hdt_and_ths_join_the_latest_epoch() {
    let text = log(&[RMC, GGA, VTG, HDT]);
    let fix = read_nmea(text.as_bytes(), "log.nmea", settings_1994()).unwrap()[0];
    // VTG: 54.7° true, 5.5 kn.
    let [vn, ve, _] = fix.velocity_ned_m_s.unwrap();
    let speed = 5.5 * 1852.0 / 3600.0;
    assert!((vn.hypot(ve) - speed).abs() < 1e-12);
    assert!(close_deg(ve.atan2(vn), 54.7));
    let heading = fix.heading.unwrap();
    assert!(close_deg(heading.heading_rad, 123.456));
    assert_eq!(heading.sd_rad, deg_to_rad(0.2));
    let text = log(&[RMC, GGA, THS]);
    let fix = read_nmea(text.as_bytes(), "log.nmea", settings_1994()).unwrap()[0];
    assert!(close_deg(fix.heading.unwrap().heading_rad, 316.70));
    // Mode V (not valid) is dropped.
    let invalid = "$HETHS,316.70,V*09";
    let fix = read_nmea(
        log(&[RMC, GGA, invalid]).as_bytes(),
        "log.nmea",
        settings_1994(),
    )
    .unwrap()[0];
    assert_eq!(fix.heading, None);
}

#[test]
fn defaults_drop_uncertain_quantities_and_add_18_leap_seconds() {
    let fix = read_nmea(
        log(&[GGA, RMC, HDT]).as_bytes(),
        "log.nmea",
        NmeaSettings::default(),
    )
    .unwrap()[0];
    assert_eq!(fix.velocity_ned_m_s, None);
    assert_eq!(fix.heading, None);
    assert_eq!(fix.time.as_nanos(), (FIX_UTC_S + 18) * NANOS_PER_SECOND);
}

#[test]
fn gga_only_log_needs_a_date() {
    let message = read_nmea(log(&[GGA]).as_bytes(), "log.nmea", NmeaSettings::default())
        .unwrap_err()
        .to_string();
    assert_eq!(
        message,
        "log.nmea: no RMC sentence gives the date: give the UTC date of the first epoch"
    );
    let settings = NmeaSettings {
        date: Some((1994, 3, 23)),
        ..settings_1994()
    };
    let fix = read_nmea(log(&[GGA]).as_bytes(), "log.nmea", settings).unwrap()[0];
    assert_eq!(fix.time.as_nanos(), (FIX_UTC_S + 9) * NANOS_PER_SECOND);
}

fn strict_error(lines: &[&str]) -> String {
    match read_nmea(log(lines).as_bytes(), "log.nmea", settings_1994()) {
        Ok(fixes) => panic!("expected an error, read {} fixes", fixes.len()),
        Err(error) => error.to_string(),
    }
}

#[test]
fn bad_checksum_is_an_error_when_strict_and_skipped_when_lenient() {
    assert_eq!(
        strict_error(&[GGA, RMC, HDT_PUBLISHED]),
        "log.nmea:3: NMEA checksum: the sentence ends in \"*00\" but its characters give *32"
    );
    let lenient = NmeaSettings {
        strictness: Strictness::Lenient,
        ..settings_1994()
    };
    let text = log(&[GGA, RMC, HDT_PUBLISHED, "garbage"]);
    let fix = read_nmea(text.as_bytes(), "log.nmea", lenient).unwrap()[0];
    assert_eq!(fix.heading, None);
    assert!(close_deg(fix.latitude_rad, 48.0 + 7.038 / 60.0));
}

#[test]
fn bad_input_names_file_line_and_expectation() {
    assert_eq!(
        read_nmea(&b""[..], "log.nmea", NmeaSettings::default())
            .unwrap_err()
            .to_string(),
        "log.nmea: no data (expected NMEA 0183 sentences such as $GPGGA,…*hh)"
    );
    // Truncated: the line is cut before its checksum.
    assert_eq!(
        strict_error(&[RMC, "$GPGGA,123519,4807.038,N,011"]),
        "log.nmea:2: NMEA checksum: the sentence ends in \"*\" but its characters give *3B"
    );
    assert_eq!(
        strict_error(&["\u{0}\u{1}binary\u{2}"]),
        "log.nmea:1: field 1 (sentence): expected an NMEA sentence starting with $, found \
         \"\u{0}\u{1}binary\u{2}\""
    );
    // Semicolons instead of commas: the checksum still matches (14 separators, and the XOR of
    // an even number of changes cancels), the address does not.
    let semicolons = "$GPGGA;123519;4807.038;N;01131.000;E;1;08;0.9;545.4;M;46.9;M;;*47";
    let message = strict_error(&[semicolons]);
    assert!(
        message.starts_with(
            "log.nmea:1: field 1 (sentence address): expected a talker and sentence type such \
             as GPGGA, then comma-separated fields, found \"GPGGA;123519;"
        ),
        "{message}"
    );
    // NaN altitude, with a correct checksum.
    let nan = "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,NaN,M,46.9,M,,*08";
    assert_eq!(
        strict_error(&[RMC, nan]),
        "log.nmea:2: column GGA altitude (field 10): value \"NaN\" is not finite (strict reading)"
    );
    let bad_hemisphere = "$GPGGA,123519,4807.038,X,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*51";
    assert_eq!(
        strict_error(&[RMC, bad_hemisphere]),
        "log.nmea:2: field 4 (hemisphere): expected N or S after a latitude, E or W after a \
         longitude, found \"X\""
    );
    let beyond_pole = "$GPGGA,123519,9507.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47";
    let message = strict_error(&[RMC, beyond_pole]);
    assert_eq!(
        message,
        "log.nmea:2: field 3 (latitude (ddmm.mmm)): expected at most 90° with minutes below 60, found \"9507.038\""
    );
    let no_fix = "$GPGGA,123519,4807.038,N,01131.000,E,0,08,0.9,545.4,M,46.9,M,,*46";
    assert_eq!(
        strict_error(&[RMC, no_fix]),
        "log.nmea: no GGA sentence with a valid fix (quality above 0): nothing to convert"
    );
}

#[test]
fn ublox_examples_date_a_later_gga_and_skip_sentences_before_the_first_fix() {
    let text = log(&[
        "$GPGGA,,,,,,0,00,99.99,,,,,,*48",
        "$GPRMC,,V,,,,,,,,,,N*53",
        "$GPRMC,083559.00,A,4717.11437,N,00833.91522,E,0.004,77.52,091202,,,A*57",
        "$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5B",
    ]);
    // GPS − UTC in December 2002: 13 s (TAI − UTC 32 s from 1999-01-01, IERS Bulletin C).
    let settings = NmeaSettings {
        gpst_minus_utc: Duration::from_nanos(13 * NANOS_PER_SECOND),
        ..NmeaSettings::default()
    };
    let fixes = read_nmea(text.as_bytes(), "ublox.nmea", settings).unwrap();
    // The RMC epoch has no GGA (no height): only the GGA epoch gives a fix, dated by the
    // earlier RMC.
    assert_eq!(fixes.len(), 1);
    let fix = fixes[0];
    assert_eq!(
        fix.time.as_nanos(),
        (UBLOX_GGA_UTC_S + 13) * NANOS_PER_SECOND
    );
    assert!(close_deg(fix.latitude_rad, 47.0 + 17.11399 / 60.0));
    assert!(close_deg(fix.longitude_rad, 8.0 + 33.91590 / 60.0));
    assert!((fix.height_m - (499.6 + 48.0)).abs() < 1e-9);
}

/// `body` (the text between `$` and `*`) as a sentence with its checksum (XOR of the bytes).
fn sentence(body: &str) -> String {
    let sum = body.bytes().fold(0u8, |acc, b| acc ^ b);
    format!("${body}*{sum:02X}")
}

// Values that parse as numbers but are no position or date: a longitude past 180°, minutes
// of 60 or more, 31 February. Each is refused naming the line, the field and the range.
#[test]
fn impossible_angles_and_dates_are_refused() {
    let longitude = sentence("GPGGA,123519,4807.038,N,18130.000,E,1,08,0.9,545.4,M,46.9,M,,");
    let error = strict_error(&[RMC, &longitude]);
    assert!(
        error.contains("log.nmea:2") && error.contains("at most 180°"),
        "{error}"
    );
    let minutes = sentence("GPGGA,123519,4867.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,");
    let error = strict_error(&[RMC, &minutes]);
    assert!(
        error.contains("minutes below 60") && error.contains("latitude"),
        "{error}"
    );
    let february = sentence("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,310294,003.1,W");
    let error = strict_error(&[&february, GGA]);
    assert!(
        error.contains("log.nmea:1") && error.contains("ddmmyy"),
        "{error}"
    );
    // 29 February of a leap year is a date.
    let leap = sentence("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,290296,003.1,W");
    assert!(read_nmea(log(&[&leap, GGA]).as_bytes(), "log.nmea", settings_1994()).is_ok());
}
