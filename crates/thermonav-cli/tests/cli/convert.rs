//! `thermonav convert`: the real rtklibexplorer drive end to end (format detected from the
//! content), hand-written NMEA and KF-GINS files, and bad input of every format: exit 1 with
//! file:line and what was expected, no output file, no panic.

use crate::{arg, files_in, outcome, thermonav, write_file};
use std::path::{Path, PathBuf};
use thermonav_io::{Strictness, read_gnss_file, read_imu_file, read_trajectory_file};

/// Path of a file under the project's `shared/data`, in the nearest ancestor that has one.
pub(crate) fn shared_data(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .ancestors()
        .map(|dir| dir.join("shared/data"))
        .find(|dir| dir.is_dir())
        .expect("a shared/data folder above the crate")
        .join(relative)
}

pub(crate) const DRIVE: &str = "rtklibexplorer-gnss-imu/drive_0708";

#[test]
fn drive_pos_and_imu_convert_with_detected_formats() {
    let dir = tempfile::tempdir().unwrap();
    let gnss = dir.path().join("gnss.csv");
    let pos = shared_data(&format!("{DRIVE}/gnss_1934_sf.pos"));
    let (status, stdout, stderr) =
        outcome(&thermonav(&["convert", arg(&pos), "--out", arg(&gnss)]));
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("2197 GNSS fixes"), "{stdout}");
    // README: 2 197 epochs, of which 2 189 fixed.
    assert_eq!(
        read_gnss_file(&gnss, Strictness::Strict).unwrap().len(),
        2197
    );
    let fixed = dir.path().join("fixed.csv");
    let args = ["convert", arg(&pos), "--quality", "1", "--out", arg(&fixed)];
    assert_eq!(outcome(&thermonav(&args)).0, 0);
    assert_eq!(
        read_gnss_file(&fixed, Strictness::Strict).unwrap().len(),
        2189
    );

    // The raw IMU CSV is recognised by its 7 comma-separated fields and the .tag beside it.
    let imu = dir.path().join("imu.csv");
    let csv = shared_data(&format!("{DRIVE}/imu_1934.csv"));
    let args = [
        "convert",
        arg(&csv),
        "--imu-frame",
        "drive-frd",
        "--out",
        arg(&imu),
    ];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    let series = read_imu_file(&imu, Strictness::Strict).unwrap();
    // README: 54 860 rows less the partial first and last; span 548.731 s.
    assert_eq!(series.len(), 54_858);
    let span = series.time[series.len() - 1].since(series.time[0]);
    assert_eq!(span.as_nanos(), 548_731_000_000);
}

#[test]
fn nmea_and_kf_gins_files_convert() {
    let dir = tempfile::tempdir().unwrap();
    // gpsinformation.org's example sentences (see thermonav-io's NMEA tests for the values).
    let nmea = write_file(
        dir.path(),
        "log.nmea",
        "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\n\
         $GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A\n",
    );
    let out = dir.path().join("nmea.csv");
    let (status, _, stderr) = outcome(&thermonav(&["convert", arg(&nmea), "--out", arg(&out)]));
    assert_eq!(status, 0, "{stderr}");
    let fix = read_gnss_file(&out, Strictness::Strict).unwrap()[0];
    assert!((fix.height_m - 592.3).abs() < 1e-9);

    let nav = write_file(
        dir.path(),
        "truth.nav",
        "0 1.0 30.44 114.47 20.5 1.0 2.0 -0.1 0.5 -1.5 270.0\n\
         0 2.0 30.44 114.47 20.5 1.0 2.0 -0.1 0.5 -1.5 270.0\n",
    );
    let out = dir.path().join("nav.csv");
    assert_eq!(
        outcome(&thermonav(&["convert", arg(&nav), "--out", arg(&out)])).0,
        0
    );
    assert_eq!(
        read_trajectory_file(&out, Strictness::Strict)
            .unwrap()
            .len(),
        2
    );

    // Seven blank-separated columns fit both KF-GINS IMU and GNSS: the format must be given.
    let seven = write_file(
        dir.path(),
        "imu.txt",
        "1.0 0 0 0 0 0 0.049\n2.0 0 0 0 0 0 0.049\n",
    );
    let out = dir.path().join("imu.csv");
    let (status, _, stderr) = outcome(&thermonav(&["convert", arg(&seven), "--out", arg(&out)]));
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.contains("give --format"), "{stderr}");
    let tag = shared_data(&format!("{DRIVE}/imu_1934.csv.tag"));
    let (status, _, stderr) = outcome(&thermonav(&["convert", arg(&tag), "--out", arg(&out)]));
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.contains("time-tag file"), "{stderr}");
    let args = [
        "convert",
        arg(&seven),
        "--format",
        "kf-gins-imu",
        "--out",
        arg(&out),
    ];
    assert_eq!(outcome(&thermonav(&args)).0, 0);
    assert_eq!(read_imu_file(&out, Strictness::Strict).unwrap().len(), 2);
}

/// Runs `convert` on `text` in `format` and checks the failure: exit 1, no output, no
/// temporary file, no panic. Returns stderr.
fn convert_fails(name: &str, text: &[u8], format: &str, extra: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join(name);
    std::fs::write(&input, text).unwrap();
    let out = dir.path().join("out.csv");
    let mut args = vec![
        "convert",
        arg(&input),
        "--format",
        format,
        "--out",
        arg(&out),
    ];
    args.extend_from_slice(extra);
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 1, "{name}: {stderr}");
    assert!(stdout.is_empty(), "{stdout}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!out.exists(), "no output after a failure");
    let leftovers: Vec<_> = files_in(dir.path())
        .into_iter()
        .filter(|n| n.starts_with("out"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    stderr
}

const POS_HEADER: &str = "%  GPST latitude(deg) longitude(deg) height(m) Q ns sdn(m) sde(m) sdu(m) \
     sdne(m) sdeu(m) sdun(m) age(s) ratio\n";
const POS_LINE: &str = "2025/07/08 19:34:18.499 40.0966268 -105.1474483 1601.474 1 21 0.0099 \
     0.0099 0.01 0 0 0 0 0\n";
const GGA: &str = "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\n";
const RMC: &str = "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A\n";
const RAW: &str = "0,0,1,0,0,0,100\n";
const BINARY: &[u8] = b"\x00\x01\x02\xff\xfe garbage \x03\x04\n\x05\x06\x07\n\x08\x09\n";

/// Each format's bad inputs: (name, content, expected part of the message).
fn bad_inputs() -> Vec<(&'static str, &'static str, Vec<u8>, &'static str)> {
    let text = |s: String| s.into_bytes();
    let mut cases = vec![
        ("a.pos", "rtklib-pos", vec![], "a.pos: no data"),
        (
            "b.pos",
            "rtklib-pos",
            text(format!("{POS_HEADER}{POS_LINE}2025/07/08 19:34:19")),
            "b.pos:3: expected 15 fields",
        ),
        (
            "c.pos",
            "rtklib-pos",
            BINARY.to_vec(),
            "c.pos:1: expected 15 fields",
        ),
        (
            "d.pos",
            "rtklib-pos",
            text(format!("{POS_HEADER}{}", POS_LINE.replace(' ', ","))),
            "d.pos:2: expected 15 fields",
        ),
        (
            "e.pos",
            "rtklib-pos",
            text(format!(
                "{POS_HEADER}{}",
                POS_LINE.replace("1601.474", "NaN")
            )),
            "e.pos:2: column solution value (field 5): value \"NaN\" is not finite",
        ),
        ("a.nmea", "nmea", vec![], "a.nmea: no data"),
        (
            "b.nmea",
            "nmea",
            text(format!("{RMC}$GPGGA,123519,4807.0")),
            "b.nmea:2: NMEA checksum",
        ),
        (
            "c.nmea",
            "nmea",
            BINARY.to_vec(),
            "c.nmea:1: field 1 (sentence): expected an NMEA sentence starting with $",
        ),
        (
            "d.nmea",
            "nmea",
            text(GGA.replace(',', ";")),
            "d.nmea:1: field 1 (sentence address)",
        ),
        (
            "e.nmea",
            "nmea",
            text(format!(
                "{RMC}$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,NaN,M,46.9,M,,*08\n"
            )),
            "e.nmea:2: column GGA altitude (field 10): value \"NaN\"",
        ),
        ("a.imu", "kf-gins-imu", vec![], "a.imu: no data"),
        (
            "b.imu",
            "kf-gins-imu",
            text("1 0 0 0 0 0 0\n2 0 0".into()),
            "b.imu:2: expected 7 fields",
        ),
        (
            "c.imu",
            "kf-gins-imu",
            BINARY.to_vec(),
            "c.imu:1: expected 7 fields",
        ),
        (
            "d.imu",
            "kf-gins-imu",
            text("1,0,0,0,0,0,0\n".into()),
            "d.imu:1: expected 7 fields",
        ),
        (
            "e.imu",
            "kf-gins-imu",
            text("1 0 0 0 nan 0 0\n".into()),
            "e.imu:1: column dvx (field 5): value \"nan\" is not finite",
        ),
        ("a.gnss", "kf-gins-gnss", vec![], "a.gnss: no data"),
        (
            "b.gnss",
            "kf-gins-gnss",
            text("1 30 114 20 0.01 0.01 0.02\n2 30 114".into()),
            "b.gnss:2: expected 7 fields",
        ),
        (
            "c.gnss",
            "kf-gins-gnss",
            BINARY.to_vec(),
            "c.gnss:1: expected 7 fields",
        ),
        (
            "d.gnss",
            "kf-gins-gnss",
            text("1;30;114;20;0.01;0.01;0.02\n".into()),
            "d.gnss:1: expected 7 fields",
        ),
        (
            "e.gnss",
            "kf-gins-gnss",
            text("1 30 114 NaN 0.01 0.01 0.02\n".into()),
            "e.gnss:1: column h (field 4): value \"NaN\"",
        ),
        ("a.nav", "kf-gins-nav", vec![], "a.nav: no data"),
        (
            "b.nav",
            "kf-gins-nav",
            text("0 1 30 114 20 0 0 0 0 0 0\n0 2 30".into()),
            "b.nav:2: expected 11 fields",
        ),
        (
            "c.nav",
            "kf-gins-nav",
            BINARY.to_vec(),
            "c.nav:1: expected 11 fields",
        ),
        (
            "d.nav",
            "kf-gins-nav",
            text("0,1,30,114,20,0,0,0,0,0,0\n".into()),
            "d.nav:1: expected 11 fields",
        ),
        (
            "e.nav",
            "kf-gins-nav",
            text("0 1 30 114 20 0 0 0 0 0 NaN\n".into()),
            "e.nav:1: column yaw (field 11): value \"NaN\"",
        ),
        ("a.csv", "raw-imu-tag", vec![], "a.csv: no data"),
        (
            "b.csv",
            "raw-imu-tag",
            text(format!("x\n{RAW}0,0,1,0\n{RAW}x\n")),
            "b.csv:3: expected 7 fields",
        ),
        (
            "c.csv",
            "raw-imu-tag",
            BINARY.to_vec(),
            "c.csv:2: expected 7 fields",
        ),
        (
            "d.csv",
            "raw-imu-tag",
            text(format!("x\n{}x\n", RAW.replace(',', ";"))),
            "d.csv:2: expected 7 fields",
        ),
        (
            "e.csv",
            "raw-imu-tag",
            text(format!("x\n{RAW}0,0,nan,0,0,0,110\nx\n")),
            "e.csv:3: column az (g) (field 3): value \"nan\"",
        ),
    ];
    cases.extend(time_order_inputs());
    cases
}

/// Times that go backwards (`f.*`) or repeat (`g.*`) in every format: refused at the line
/// of the later record.
fn time_order_inputs() -> Vec<(&'static str, &'static str, Vec<u8>, &'static str)> {
    let text = |s: String| s.into_bytes();
    let earlier_pos = POS_LINE.replace("19:34:18.499", "19:34:18.299");
    let earlier_gga =
        nmea_sentence("GPGGA,123518,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,");
    vec![
        (
            "f.pos",
            "rtklib-pos",
            text(format!("{POS_HEADER}{POS_LINE}{earlier_pos}")),
            "f.pos:3: time",
        ),
        (
            "g.pos",
            "rtklib-pos",
            text(format!("{POS_HEADER}{POS_LINE}{POS_LINE}")),
            "g.pos:3: time",
        ),
        (
            "f.nmea",
            "nmea",
            text(format!("{RMC}{GGA}{earlier_gga}")),
            "f.nmea:3:",
        ),
        (
            "g.nmea",
            "nmea",
            text(format!("{RMC}{GGA}{GGA}")),
            "g.nmea:3:",
        ),
        (
            "f.imu",
            "kf-gins-imu",
            text("1 0 0 0 0 0 0\n0.5 0 0 0 0 0 0\n".into()),
            "f.imu:2: time",
        ),
        (
            "g.imu",
            "kf-gins-imu",
            text("1 0 0 0 0 0 0\n1 0 0 0 0 0 0\n".into()),
            "g.imu:2: time",
        ),
        (
            "f.gnss",
            "kf-gins-gnss",
            text("2 30 114 20 0.01 0.01 0.02\n1 30 114 20 0.01 0.01 0.02\n".into()),
            "f.gnss:2: time",
        ),
        (
            "g.gnss",
            "kf-gins-gnss",
            text("2 30 114 20 0.01 0.01 0.02\n2 30 114 20 0.01 0.01 0.02\n".into()),
            "g.gnss:2: time",
        ),
        (
            "f.nav",
            "kf-gins-nav",
            text("0 2 30 114 20 0 0 0 0 0 0\n0 1 30 114 20 0 0 0 0 0 0\n".into()),
            "f.nav:2: time",
        ),
        (
            "g.nav",
            "kf-gins-nav",
            text("0 2 30 114 20 0 0 0 0 0 0\n0 2 30 114 20 0 0 0 0 0 0\n".into()),
            "g.nav:2: time",
        ),
        (
            "f.csv",
            "raw-imu-tag",
            text(format!("x\n0,0,1,0,0,0,110\n{RAW}x\n")),
            "f.csv:3:",
        ),
        (
            "g.csv",
            "raw-imu-tag",
            text(format!("x\n{RAW}{RAW}x\n")),
            "g.csv:3:",
        ),
    ]
}

/// `$body*XX` with its checksum, and a newline.
fn nmea_sentence(body: &str) -> String {
    let checksum = body.bytes().fold(0_u8, |x, b| x ^ b);
    format!("${body}*{checksum:02X}\n")
}

/// A valid time-tag file (start 1000.5 s, span 2 s).
fn tag_bytes() -> Vec<u8> {
    let mut bytes = b"TIMETAG RTKLIB test".to_vec();
    bytes.resize(60, 0);
    bytes.extend(7_u32.to_le_bytes());
    bytes.extend(1_000_u32.to_le_bytes());
    bytes.extend(0.5_f64.to_le_bytes());
    bytes.extend(0_u64.to_le_bytes());
    bytes.extend(2_000_u32.to_le_bytes());
    bytes.extend(120_u32.to_le_bytes());
    bytes
}

#[test]
fn bad_input_of_every_format_fails_cleanly_with_file_and_line() {
    let tags = tempfile::tempdir().unwrap();
    let tag = tags.path().join("good.tag");
    std::fs::write(&tag, tag_bytes()).unwrap();
    for (name, format, content, expected) in bad_inputs() {
        let extra = match format {
            "raw-imu-tag" => vec!["--tag", arg(&tag)],
            _ => vec![],
        };
        let stderr = convert_fails(name, &content, format, &extra);
        assert!(
            stderr.contains(expected),
            "{name}: expected {expected:?} in {stderr}"
        );
    }
}

#[test]
fn bad_time_tag_file_names_the_byte() {
    let dir = tempfile::tempdir().unwrap();
    let tag = write_file(dir.path(), "bad.tag", "not a tag file");
    let stderr = convert_fails(
        "imu.csv",
        format!("x\n{RAW}0,0,1,0,0,0,110\nx\n").as_bytes(),
        "raw-imu-tag",
        &["--tag", arg(&tag)],
    );
    assert!(
        stderr.contains("bad.tag: at byte 14: expected a 76-byte RTKLIB time-tag header"),
        "{stderr}"
    );
}
