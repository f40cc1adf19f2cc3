//! RTKLIB `.pos` solutions: the real drive of shared/data/rtklibexplorer-gnss-imu against the
//! numbers its README documents, the ECEF form against WGS84's defining constants, bad input.

use crate::support::shared_data;
use thermonav::time::NANOS_PER_SECOND;
use thermonav::units::deg_to_rad;
use thermonav_io::Strictness;
use thermonav_io::rtklib_pos::{PosSettings, QualitySet, read_rtklib_pos, read_rtklib_pos_file};

const DRIVE_POS: &str = "rtklibexplorer-gnss-imu/drive_0708/gnss_1934_sf.pos";

/// Unix seconds of 2025-07-08 19:34:18 and 19:43:27 (GNU `date -u -d … +%s`), which on the
/// GPST-counted scale are the same calendar times in GPST.
const FIRST_WHOLE_SECOND: i64 = 1_752_003_258;
const LAST_WHOLE_SECOND: i64 = 1_752_003_807;

fn nanos(seconds: i64, millis: i64) -> i64 {
    seconds * NANOS_PER_SECOND + millis * 1_000_000
}

#[test]
fn drive_solution_has_the_documented_epochs_and_quality_counts() {
    let solutions = read_rtklib_pos_file(shared_data(DRIVE_POS), PosSettings::default()).unwrap();
    // README: 4 Hz, 2 197 epochs (2 189 fixed Q=1, 8 float Q=2), 19:34:18.5–19:43:27.5 GPST.
    assert_eq!(solutions.len(), 2197);
    let count = |q| solutions.iter().filter(|s| s.quality == q).count();
    assert_eq!((count(1), count(2)), (2189, 8));
    // The file prints 19:34:18.499 and 19:43:27.499 (the README rounds to 0.1 s).
    let first = solutions[0].fix;
    let last = solutions[solutions.len() - 1].fix;
    assert_eq!(first.time.as_nanos(), nanos(FIRST_WHOLE_SECOND, 499));
    assert_eq!(last.time.as_nanos(), nanos(LAST_WHOLE_SECOND, 499));
    // 4 Hz: consecutive epochs 250 ms apart at the start.
    let step = solutions[1].fix.time.since(first.time).as_nanos();
    assert_eq!(step, 250_000_000);
}

#[test]
fn drive_first_epoch_decodes_every_column_as_printed() {
    let solutions = read_rtklib_pos_file(shared_data(DRIVE_POS), PosSettings::default()).unwrap();
    let first = &solutions[0];
    // Conversion as the readers do it (one multiplication by π/180).
    // First line: 40.0966268 -105.1474483 1601.4740000 Q=1 ns=21 sdn 0.0098995 sde 0.0098995
    // sdu 0.0100000 … vn 0.0100000 ve -0.0020000 vu 0.0090000.
    assert_eq!(first.fix.latitude_rad, deg_to_rad(40.0966268));
    assert_eq!(first.fix.longitude_rad, deg_to_rad(-105.1474483));
    assert_eq!(first.fix.height_m, 1601.474);
    assert_eq!(first.quality, 1);
    assert_eq!(first.satellites, Some(21));
    assert_eq!(
        first.fix.position_sd_ned_m,
        Some([0.0098995, 0.0098995, 0.01])
    );
    // Up 0.009 m/s is down -0.009 m/s.
    assert_eq!(first.fix.velocity_ned_m_s, Some([0.01, -0.002, -0.009]));
    assert_eq!(first.fix.heading, None);
}

#[test]
fn quality_setting_keeps_fixed_solutions_only() {
    let settings = PosSettings {
        qualities: QualitySet::of(&[1]),
        ..PosSettings::default()
    };
    let fixed = read_rtklib_pos_file(shared_data(DRIVE_POS), settings).unwrap();
    assert_eq!(fixed.len(), 2189);
    assert!(fixed.iter().all(|s| s.quality == 1));
}

const ECEF_HEADER: &str = "%  GPST                      x-ecef(m)      y-ecef(m)      z-ecef(m)   Q  ns   \
     sdx(m)   sdy(m)   sdz(m)  sdxy(m)  sdyz(m)  sdzx(m) age(s)  ratio    vx(m/s)    vy(m/s)    \
     vz(m/s)      sdvx     sdvy     sdvz    sdvxy    sdvyz    sdvzx\n";

#[test]
fn ecef_form_is_converted_with_wgs84_constants() {
    // On the equator at longitude 0 the point (a + h, 0, 0) has latitude 0, longitude 0 and
    // height h (a = 6 378 137 m, WGS84's defining semi-major axis); there north is +z, east +y
    // and down -x, so ECEF velocity (1, 2, 3) is NED (3, 2, -1) and ECEF SDs (1, 2, 3) without
    // cross terms are NED SDs (3, 2, 1). Tolerances: the geodetic iteration and the
    // quaternion-held rotation are exact to a few ulps of these magnitudes.
    let text = format!(
        "{ECEF_HEADER}2369 239676.000 6378237.0000 0.0000 0.0000 5 9 1.0000 2.0000 3.0000 \
         0.0000 0.0000 0.0000 0.00 0.0 1.0000 2.0000 3.0000 0.1 0.1 0.1 0 0 0\n"
    );
    let solution = read_rtklib_pos(text.as_bytes(), "ecef.pos", PosSettings::default()).unwrap()[0];
    let fix = solution.fix;
    assert!(fix.latitude_rad.abs() < 1e-15, "{}", fix.latitude_rad);
    assert_eq!(fix.longitude_rad, 0.0);
    assert!((fix.height_m - 100.0).abs() < 1e-8, "{}", fix.height_m);
    let v = fix.velocity_ned_m_s.unwrap();
    let sd = fix.position_sd_ned_m.unwrap();
    for (got, want) in v
        .iter()
        .zip([3.0, 2.0, -1.0])
        .chain(sd.iter().zip([3.0, 2.0, 1.0]))
    {
        assert!((got - want).abs() < 1e-12, "{v:?} {sd:?}");
    }
    assert_eq!((solution.quality, solution.satellites), (5, Some(9)));
    // GPS week 2369, 239 676 s: week 2000 began 2018-05-06 (Unix 1 525 564 800 s by GNU date),
    // so this is 1 525 564 800 + 369·604 800 + 239 676 on the GPST-counted scale.
    let expected = 1_525_564_800 + 369 * 604_800 + 239_676;
    assert_eq!(fix.time.as_nanos(), expected * NANOS_PER_SECOND);
}

#[test]
fn ecef_point_above_the_pole_has_latitude_90() {
    // (0, 0, b + h) with b = 6 356 752.314245 m, WGS84's semi-minor axis (NIMA TR8350.2,
    // Table 3.1): latitude 90°, height h. Height within 1 mm: b is given to the micrometre and
    // the conversion's pole branch subtracts it from z.
    let text = format!(
        "{}2369 239676.000 0.0 0.0 6356852.314245 1 9\n",
        "%  GPST x-ecef(m) y-ecef(m) z-ecef(m) Q ns\n"
    );
    let fix = read_rtklib_pos(text.as_bytes(), "pole.pos", PosSettings::default()).unwrap()[0].fix;
    assert!((fix.latitude_rad - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    assert!((fix.height_m - 100.0).abs() < 1e-3, "{}", fix.height_m);
    assert_eq!(fix.position_sd_ned_m, None);
}

#[test]
fn ecef_cross_terms_are_signed_square_roots() {
    // At the equator, longitude 0: NED north = +z, east = +y. sdyz = -1 means cov(y, z) = -1 m²
    // (RTKLIB's sign(c)·√|c|), which does not change the north and east variances (4 and 9 from
    // sdz = 2, sdy = 3): the NED SDs are the ECEF SDs permuted, the covariance only rotates.
    let text = format!(
        "{}2369 239676.000 6378137.0 0.0 0.0 1 9 5.0 3.0 2.0 0.0 -1.0 0.0 0.0 0.0\n",
        "%  GPST x-ecef(m) y-ecef(m) z-ecef(m) Q ns sdx(m) sdy(m) sdz(m) sdxy(m) sdyz(m) \
         sdzx(m) age(s) ratio\n"
    );
    let fix = read_rtklib_pos(text.as_bytes(), "ecef.pos", PosSettings::default()).unwrap()[0].fix;
    let sd = fix.position_sd_ned_m.unwrap();
    for (got, want) in sd.iter().zip([2.0, 3.0, 5.0]) {
        assert!((got - want).abs() < 1e-12, "{sd:?}");
    }
    assert_eq!(fix.velocity_ned_m_s, None);
}

fn pos_error(text: &str, strictness: Strictness) -> String {
    let settings = PosSettings {
        strictness,
        ..PosSettings::default()
    };
    match read_rtklib_pos(text.as_bytes(), "bad.pos", settings) {
        Ok(s) => panic!("expected an error, read {} solutions", s.len()),
        Err(error) => error.to_string(),
    }
}

const LLH_HEADER: &str = "%  GPST          latitude(deg) longitude(deg)  height(m)   Q  ns   sdn(m)   \
     sde(m)   sdu(m)  sdne(m)  sdeu(m)  sdun(m) age(s)  ratio\n";
const LLH_LINE: &str = "2025/07/08 19:34:18.499 40.0966268 -105.1474483 1601.4740 1 21 0.0099 \
     0.0099 0.0100 0.0000 0.0000 0.0000 0.00 0.0\n";

#[test]
fn bad_input_names_file_line_and_expectation() {
    assert_eq!(
        pos_error("", Strictness::Strict),
        "bad.pos: no data (expected RTKLIB solution lines: date time position Q ns …)"
    );
    let truncated = format!("{LLH_HEADER}{LLH_LINE}2025/07/08 19:34:18.749 40.0966268\n");
    assert_eq!(
        pos_error(&truncated, Strictness::Strict),
        "bad.pos:3: expected 15 fields (the column header's names after the time), found 3"
    );
    let nan = format!("{LLH_HEADER}{}", LLH_LINE.replace("1601.4740", "nan"));
    assert_eq!(
        pos_error(&nan, Strictness::Strict),
        "bad.pos:2: column solution value (field 5): value \"nan\" is not finite (strict reading)"
    );
    let semicolons = format!("{LLH_HEADER}{}", LLH_LINE.replace(' ', ";"));
    let message = pos_error(&semicolons, Strictness::Strict);
    assert!(
        message.starts_with("bad.pos:2: expected 15 fields"),
        "{message}"
    );
    let garbage = format!("{LLH_HEADER}\u{1}\u{2}\u{fffd}\u{7f} \u{0}\n");
    assert!(pos_error(&garbage, Strictness::Strict).starts_with("bad.pos:2: "));
    let utc = LLH_HEADER.replace("GPST", "UTC ");
    assert_eq!(
        pos_error(&format!("{utc}{LLH_LINE}"), Strictness::Strict),
        "bad.pos:1: time system \"UTC\" is not supported (expected GPST (set RTKLIB's time \
         system to GPST))"
    );
    let bad_date = format!(
        "{LLH_HEADER}{}",
        LLH_LINE.replace("2025/07/08", "2025/13/08")
    );
    assert_eq!(
        pos_error(&bad_date, Strictness::Strict),
        "bad.pos:2: field 1 (date): expected yyyy/mm/dd (or a GPS week), found \"2025/13/08\""
    );
    let backwards = format!("{LLH_HEADER}{LLH_LINE}{LLH_LINE}");
    assert!(
        pos_error(&backwards, Strictness::Strict).starts_with("bad.pos:3: time "),
        "{}",
        pos_error(&backwards, Strictness::Strict)
    );
}

#[test]
fn lenient_reading_keeps_nan_and_repeated_times() {
    let text = format!(
        "{LLH_HEADER}{LLH_LINE}{}",
        LLH_LINE.replace("1601.4740", "nan")
    );
    let settings = PosSettings {
        strictness: Strictness::Lenient,
        ..PosSettings::default()
    };
    let solutions = read_rtklib_pos(text.as_bytes(), "lenient.pos", settings).unwrap();
    assert_eq!(solutions.len(), 2);
    assert!(solutions[1].fix.height_m.is_nan());
}

#[test]
fn headerless_file_uses_the_default_layout() {
    let solutions =
        read_rtklib_pos(LLH_LINE.as_bytes(), "plain.pos", PosSettings::default()).unwrap();
    assert_eq!(solutions[0].fix.height_m, 1601.474);
    assert_eq!(
        solutions[0].fix.position_sd_ned_m,
        Some([0.0099, 0.0099, 0.01])
    );
}
