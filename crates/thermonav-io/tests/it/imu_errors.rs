//! Every malformed IMU input gives an error naming the file, the line and what was expected;
//! suspect values are rejected under Strict and kept under Lenient.

use crate::support::{NAME, RATE_HEADER, read, strict_error};
use std::io::ErrorKind;
use thermonav_io::{ImuReader, ReadErrorKind, Strictness, read_imu_file};

const EXPECTED_NAMES: &str = "t_s, g{x,y,z}_{rad_s,deg_s,deg_h}, a{x,y,z}_{m_s2,g,mg}, \
                              dth{x,y,z}_{rad,deg}, dv{x,y,z}_m_s, temp_c";

fn with_rows(rows: &[&str]) -> String {
    let mut text = format!("{RATE_HEADER}\n");
    for row in rows {
        text.push_str(row);
        text.push('\n');
    }
    text
}

const ROW_1: &str = "0.005,0.1,0.2,0.3,0.4,0.5,-9.8,20.5";
const ROW_2: &str = "0.010,0.1,0.2,0.3,0.4,0.5,-9.8,20.5";

#[test]
fn missing_file_cannot_be_opened() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("absent.csv");
    let error = read_imu_file(&path, Strictness::Strict).unwrap_err();
    assert!(matches!(&error.kind, ReadErrorKind::Open(e) if e.kind() == ErrorKind::NotFound));
    let message = error.to_string();
    let expected = format!("{}: cannot open: No such file or directory", path.display());
    assert!(message.starts_with(&expected), "{message}");
}

#[test]
fn empty_file_and_blank_only_file_lack_a_header() {
    for text in ["", "\n", "  \r\n\n\t\n"] {
        assert_eq!(
            strict_error(text),
            format!("{NAME}: file is empty (expected a header line)")
        );
    }
}

#[test]
fn header_without_rows_is_an_error() {
    for text in [
        RATE_HEADER.to_owned(),
        with_rows(&[]),
        with_rows(&["", "  "]),
    ] {
        assert_eq!(
            strict_error(&text),
            format!("{NAME}: header only, no data rows")
        );
    }
}

#[test]
fn unknown_column_is_named_with_the_accepted_ones() {
    let text = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,foo\n0,0,0,0,0,0,0,0\n";
    assert_eq!(
        strict_error(text),
        format!("{NAME}:1: unknown column \"foo\" (expected one of {EXPECTED_NAMES})")
    );
}

#[test]
fn missing_columns_are_named_with_their_alternatives() {
    let no_ax = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ay_m_s2,az_m_s2\n0,0,0,0,0,0\n";
    assert_eq!(
        strict_error(no_ax),
        format!("{NAME}:1: missing column ax_m_s2 (or ax_g, ax_mg){ALL_SIX}")
    );
    let no_time = "gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2\n0,0,0,0,0,0\n";
    assert_eq!(
        strict_error(no_time),
        format!(
            "{NAME}:1: missing column t_s (or, for a file without times, a sample rate: --rate-hz)"
        )
    );
    let no_dvz = "t_s,dthx_rad,dthy_rad,dthz_rad,dvx_m_s,dvy_m_s\n0,0,0,0,0,0\n";
    assert_eq!(
        strict_error(no_dvz),
        format!("{NAME}:1: missing column dvz_m_s{ALL_SIX}")
    );
    let gyros_only = "t_s,gx_rad_s,gy_rad_s,gz_rad_s\n0,0,0,0\n";
    assert_eq!(
        strict_error(gyros_only),
        format!(
            "{NAME}:1: missing columns ax_m_s2 (or ax_g, ax_mg), ay_m_s2 (or ay_g, ay_mg), az_m_s2 (or az_g, az_mg){ALL_SIX}"
        )
    );
}

/// The end of the message for absent channels where all six are needed.
const ALL_SIX: &str = ": all six channels gx..az are needed here (only the static analyses, characterize and allan, take a subset)";

#[test]
fn repeated_quantity_and_mixed_kinds_are_rejected() {
    let repeated = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,gx_deg_s\n";
    assert_eq!(
        strict_error(repeated),
        format!("{NAME}:1: columns gx_rad_s and gx_deg_s give the same quantity")
    );
    let mixed = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,dvx_m_s,dvy_m_s,dvz_m_s\n";
    assert_eq!(
        strict_error(mixed),
        format!(
            "{NAME}:1: column gx_rad_s is a rate but dvx_m_s is an increment \
             (one file holds one kind)"
        )
    );
}

#[test]
fn wrong_field_count_names_the_line_and_the_header() {
    let expected = |found| format!("{NAME}:3: expected 8 fields ({RATE_HEADER}), found {found}");
    let short = with_rows(&[ROW_1, "0.010,0.1,0.2,0.3,0.4,0.5"]);
    assert_eq!(strict_error(&short), expected(6));
    let long = with_rows(&[ROW_1, "0.010,0.1,0.2,0.3,0.4,0.5,-9.8,20.5,7"]);
    assert_eq!(strict_error(&long), expected(9));
    let trailing_comma = with_rows(&[ROW_1, "0.010,0.1,0.2,0.3,0.4,0.5,-9.8,20.5,"]);
    assert_eq!(strict_error(&trailing_comma), expected(9));
    // A bad field on a short line: the count is the first thing wrong.
    let short_and_bad = with_rows(&[ROW_1, "0.010,abc,0.2"]);
    assert_eq!(strict_error(&short_and_bad), expected(3));
}

#[test]
fn text_in_a_number_field_is_quoted() {
    let cases = [
        ("0.010,0.1,0.2,0.3,0.4,0.5,abc,20.5", "az_m_s2", "abc"),
        ("0.010,0.1,0.2,0.3,0.4,0.5,1.5x,20.5", "az_m_s2", "1.5x"),
        ("0.010,0.1,,0.3,0.4,0.5,-9.8,20.5", "gy_rad_s", ""),
        ("0.010,0.1,0.2,0.3,0.4,0.5,-9.8,2 0", "temp_c", "2 0"),
    ];
    for (row, column, found) in cases {
        assert_eq!(
            strict_error(&with_rows(&[ROW_1, row])),
            format!("{NAME}:3: column {column}: expected a number, found \"{found}\"")
        );
    }
}

#[test]
fn bad_time_is_quoted() {
    for time in ["noon", "nan", "inf", "1e10", "12:00"] {
        let row = format!("{time},0.1,0.2,0.3,0.4,0.5,-9.8,20.5");
        assert_eq!(
            strict_error(&with_rows(&[&row])),
            format!(
                "{NAME}:2: column t_s: expected a finite time in seconds within ±9.2e9 s, \
                 found \"{time}\""
            )
        );
    }
}

#[test]
fn non_finite_values_are_rejected_under_strict() {
    for (row, column, found) in [
        ("0.010,NaN,0.2,0.3,0.4,0.5,-9.8,20.5", "gx_rad_s", "NaN"),
        ("0.010,0.1,0.2,0.3,inf,0.5,-9.8,20.5", "ax_m_s2", "inf"),
        (
            "0.010,0.1,0.2,0.3,0.4,0.5,-9.8,-infinity",
            "temp_c",
            "-infinity",
        ),
    ] {
        assert_eq!(
            strict_error(&with_rows(&[ROW_1, row])),
            format!("{NAME}:3: column {column}: value \"{found}\" is not finite (strict reading)")
        );
    }
}

#[test]
fn value_overflowing_in_conversion_is_rejected_under_strict() {
    // 1e308 g is finite in the file but 9.8e308 m/s² is not.
    let text = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_g,ay_g,az_g\n0,0,0,0,1e308,0,0\n";
    assert_eq!(
        strict_error(text),
        format!("{NAME}:2: column ax_g: value \"1e308\" is not finite (strict reading)")
    );
}

#[test]
fn backward_and_repeated_times_are_rejected_under_strict() {
    let backward = with_rows(&[ROW_2, ROW_1]);
    assert_eq!(
        strict_error(&backward),
        format!(
            "{NAME}:3: time 0.005000000 s does not increase after 0.010000000 s on line 2 \
             (strict reading)"
        )
    );
    let repeated = with_rows(&[ROW_1, ROW_2, "", ROW_2]);
    assert_eq!(
        strict_error(&repeated),
        format!(
            "{NAME}:5: time 0.010000000 s does not increase after 0.010000000 s on line 3 \
             (strict reading)"
        )
    );
}

#[test]
fn lenient_keeps_non_finite_values_and_unordered_times() {
    let text = with_rows(&[
        ROW_2,
        "0.005,NaN,0.2,0.3,0.4,0.5,-9.8,20.5",
        "0.005,0.1,inf,-inf,0.4,0.5,-9.8,20.5",
    ]);
    let series = read(&text, Strictness::Lenient).unwrap();
    let nanos: Vec<i64> = series.time.iter().map(|t| t.as_nanos()).collect();
    assert_eq!(nanos, [10_000_000, 5_000_000, 5_000_000]);
    assert!(series.channels[0][1].is_nan());
    assert_eq!(series.channels[1][2], f64::INFINITY);
    assert_eq!(series.channels[2][2], f64::NEG_INFINITY);
}

#[test]
fn parse_errors_are_errors_under_lenient_too() {
    let text = with_rows(&[ROW_1, "0.010,0.1,0.2,0.3,0.4,0.5,abc,20.5"]);
    let error = read(&text, Strictness::Lenient).unwrap_err();
    assert!(matches!(error.kind, ReadErrorKind::NotANumber { .. }));
    assert_eq!(error.line, Some(3));
}

#[test]
fn blank_lines_are_skipped_but_counted_and_crlf_is_accepted() {
    let text = format!("\r\n{RATE_HEADER}\r\n\r\n{ROW_1}\r\n   \n{ROW_2}\r\n\r\n\n");
    let series = read(&text, Strictness::Strict).unwrap();
    assert_eq!(series.len(), 2);
    assert_eq!(series.temperature_c.as_deref(), Some(&[20.5, 20.5][..]));
    let bad = format!("\n{RATE_HEADER}\r\n\r\n{ROW_1}\r\n\n0.010,x,0,0,0,0,0,0\r\n");
    assert_eq!(
        strict_error(&bad),
        format!("{NAME}:6: column gx_rad_s: expected a number, found \"x\"")
    );
}

#[test]
fn spaces_around_names_and_values_and_a_byte_order_mark_are_accepted() {
    let text = "\u{feff}t_s , gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2\n\
                0.005 ,\t0.25 , 0.5,0.75,1,2,3 \n";
    let series = read(text, Strictness::Strict).unwrap();
    assert_eq!(series.channels[0], [0.25]);
    assert_eq!(series.channels[5], [3.0]);
}

#[test]
fn reader_stops_after_an_error() {
    let text = with_rows(&[ROW_1, "bad", ROW_2]);
    let mut reader = ImuReader::new(text.as_bytes(), NAME, Strictness::Strict).unwrap();
    assert!(reader.next().unwrap().is_ok());
    assert!(reader.next().unwrap().is_err());
    assert!(reader.next().is_none());
}

#[test]
fn header_that_is_not_utf8_and_endless_lines_are_rejected() {
    let error =
        thermonav_io::read_imu(&b"t_s,\xff\xfe\n0\n"[..], NAME, Strictness::Strict).unwrap_err();
    assert_eq!(
        error.to_string(),
        format!(
            "{NAME}:1: header line is not valid UTF-8 text (expected comma-separated column names such as t_s)"
        )
    );

    let endless = vec![b'1'; 3 << 20];
    let error = thermonav_io::read_imu(&endless[..], NAME, Strictness::Strict).unwrap_err();
    assert_eq!(
        error.to_string(),
        format!("{NAME}:1: line longer than 1048576 bytes")
    );
}

/// An endless IMU stream: a header, then rows 5 ms apart, produced on demand.
struct EndlessRows {
    pending: Vec<u8>,
    row: u64,
}

impl std::io::Read for EndlessRows {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if self.pending.is_empty() {
            let nanos = self.row * 5_000_000;
            self.pending = format!(
                "{}.{:09},0,0,0,0,0,-9.8\n",
                nanos / 1_000_000_000,
                nanos % 1_000_000_000
            )
            .into_bytes();
            self.row += 1;
        }
        let n = buf.len().min(self.pending.len());
        buf[..n].copy_from_slice(&self.pending[..n]);
        self.pending.drain(..n);
        Ok(n)
    }
}

#[test]
fn reader_streams_without_reading_ahead() {
    // The input never ends: a reader that slurped it would never return.
    let source = EndlessRows {
        pending: b"t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2\n".to_vec(),
        row: 0,
    };
    let reader = ImuReader::new(
        std::io::BufReader::new(source),
        "endless",
        Strictness::Strict,
    )
    .unwrap();
    let last = reader.take(100_000).last().unwrap().unwrap();
    assert_eq!(last.time.as_nanos(), 99_999 * 5_000_000);
}

// Issue 20: a temperature no sensor can have (kelvin written as °C, a corrupt field) is
// refused under Strict naming its line; Lenient keeps it for `inspect` to report.
#[test]
fn a_temperature_outside_the_sensor_range_is_refused_strictly_and_kept_leniently() {
    for (value, shown) in [("-300", "-300"), ("1e6", "1000000"), ("293.15", "293.15")] {
        let bad = ROW_2.replace("20.5", value);
        let text = with_rows(&[ROW_1, &bad]);
        let message = strict_error(&text);
        let expected = format!("{NAME}:3: column temp_c: value {shown} is out of range");
        assert!(message.starts_with(&expected), "{message}");
        assert!(message.contains("-80 to 150 °C"), "{message}");
        let kept = read(&text, Strictness::Lenient).unwrap();
        assert_eq!(
            kept.temperature_c.unwrap()[1],
            value.parse::<f64>().unwrap()
        );
    }
    let edge = with_rows(&[&ROW_1.replace("20.5", "-80"), &ROW_2.replace("20.5", "150")]);
    assert_eq!(read(&edge, Strictness::Strict).unwrap().len(), 2);
}
