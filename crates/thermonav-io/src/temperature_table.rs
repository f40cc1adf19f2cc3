//! Temperature tables: a sensor's temperature over time, one `t_s,temp_c` row per instant.
//!
//! ```text
//! t_s,temp_c
//! 0,-10
//! 600,5.5
//! 1800,17
//! ```
//!
//! `t_s` is the time since the start of the record, s (finite, 0 on the first row, strictly
//! increasing); `temp_c` the temperature, °C, within [`crate::SENSOR_TEMPERATURE_RANGE_C`].
//! Between rows the temperature is linear in time; before the first row and after the last
//! the end values hold. `simulate vessel --temperature-file` (the sensor's temperature during
//! a survey) and `simulate chamber --ramp-file` (a chamber's programmed sweep) read it.

use crate::error::{ReadError, ReadErrorKind};
use crate::lines::Lines;
use crate::text::parse_value_prefix;
use std::io::BufRead;
use std::path::Path;

/// The header a temperature table starts with.
pub const TEMPERATURE_TABLE_HEADER: &str = "t_s,temp_c";

/// Most rows of a table (a row a second for eleven days).
pub const MAX_TEMPERATURE_ROWS: usize = 1_000_000;

/// A temperature table as read: times since the start, s, and temperatures, °C.
#[derive(Debug, Clone, PartialEq)]
pub struct TemperatureTable {
    /// Times since the start, s (strictly increasing, from 0).
    pub t_s: Vec<f64>,
    /// Temperatures, °C.
    pub temperature_c: Vec<f64>,
}

/// Reads the temperature table in `path`.
///
/// # Errors
/// A [`ReadError`] naming the file and line: a header other than `t_s,temp_c`, a row without
/// exactly two numbers, a first time other than 0, a time that is negative, not finite or not
/// after the previous one, a
/// temperature outside [`crate::SENSOR_TEMPERATURE_RANGE_C`], no row, or more than
/// [`MAX_TEMPERATURE_ROWS`].
pub fn read_temperature_table(path: impl AsRef<Path>) -> Result<TemperatureTable, ReadError> {
    let (reader, input) = crate::open_file(path.as_ref())?;
    parse_temperature_table(reader, input)
}

/// Parses a temperature table from `reader`, named `input` in errors.
///
/// # Errors
/// As [`read_temperature_table`].
pub fn parse_temperature_table(
    reader: impl BufRead,
    input: impl Into<String>,
) -> Result<TemperatureTable, ReadError> {
    let mut lines = Lines::new(reader, input.into());
    if !lines.advance()? {
        return Err(lines.error_in_input(ReadErrorKind::Empty));
    }
    check_header(&lines)?;
    let mut table = TemperatureTable {
        t_s: Vec::new(),
        temperature_c: Vec::new(),
    };
    while lines.advance()? {
        let (t_s, temperature_c) = table_row(lines.current()).map_err(|k| lines.error_here(k))?;
        check_row(&table, t_s, temperature_c).map_err(|k| lines.error_here(k))?;
        table.t_s.push(t_s);
        table.temperature_c.push(temperature_c);
    }
    match table.t_s.is_empty() {
        true => Err(lines.error_in_input(ReadErrorKind::HeaderOnly)),
        false => Ok(table),
    }
}

fn check_header<R: BufRead>(lines: &Lines<R>) -> Result<(), ReadError> {
    let header = String::from_utf8_lossy(lines.current());
    let header = header.trim_start_matches('\u{feff}').trim();
    match header == TEMPERATURE_TABLE_HEADER {
        true => Ok(()),
        false => Err(lines.error_here(ReadErrorKind::Unusable(format!(
            "expected the header \"{TEMPERATURE_TABLE_HEADER}\" of a temperature table, found \"{header}\""
        )))),
    }
}

/// The two numbers of a row.
fn table_row(line: &[u8]) -> Result<(f64, f64), ReadErrorKind> {
    let text = String::from_utf8_lossy(line);
    let fields: Vec<&str> = text.split(',').map(str::trim).collect();
    if fields.len() != 2 {
        return Err(ReadErrorKind::FieldCount {
            expected: 2,
            header: TEMPERATURE_TABLE_HEADER.into(),
            found: fields.len(),
        });
    }
    let number = |column: &str, field: &str| match parse_value_prefix(field.as_bytes()) {
        Some((value, used)) if used == field.len() => Ok(value),
        _ => Err(ReadErrorKind::NotANumber {
            column: column.into(),
            found: field.into(),
        }),
    };
    Ok((number("t_s", fields[0])?, number("temp_c", fields[1])?))
}

/// A row's values against the rules and the previous row.
fn check_row(table: &TemperatureTable, t_s: f64, temperature_c: f64) -> Result<(), ReadErrorKind> {
    if !(t_s.is_finite() && t_s >= 0.0) {
        return Err(ReadErrorKind::OutOfRange {
            column: "t_s",
            found: t_s,
            expected: "a finite time since the start of the record, 0 s or later",
        });
    }
    if table.t_s.is_empty() && t_s != 0.0 {
        return Err(ReadErrorKind::OutOfRange {
            column: "t_s",
            found: t_s,
            expected: "0 s on the first row: the table starts with the record (a time since the start, not a clock time)",
        });
    }
    if let Some(&previous) = table.t_s.last()
        && t_s <= previous
    {
        return Err(ReadErrorKind::Unusable(format!(
            "t_s {t_s} s is not after the previous row's {previous} s (times must increase)"
        )));
    }
    if !crate::is_sensor_temperature(temperature_c) {
        return Err(crate::temperature_out_of_range("temp_c", temperature_c));
    }
    if table.t_s.len() >= MAX_TEMPERATURE_ROWS {
        return Err(ReadErrorKind::Unusable(format!(
            "more than {MAX_TEMPERATURE_ROWS} rows, more than a temperature table needs"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<TemperatureTable, String> {
        parse_temperature_table(text.as_bytes(), "t.csv").map_err(|e| e.to_string())
    }

    #[test]
    fn a_table_reads_its_rows_in_order() {
        let table = parse("t_s,temp_c\n0,-10\n\n600, 5.5\r\n1800,17\n").unwrap();
        assert_eq!(table.t_s, vec![0.0, 600.0, 1800.0]);
        assert_eq!(table.temperature_c, vec![-10.0, 5.5, 17.0]);
    }

    #[test]
    fn bad_tables_are_refused_naming_the_line_and_what_was_expected() {
        let cases = [
            ("", "t.csv: file is empty"),
            (
                "t_s,temp\n0,1\n",
                "t.csv:1: expected the header \"t_s,temp_c\"",
            ),
            ("t_s,temp_c\n", "header only"),
            ("t_s,temp_c\n0,1,2\n", "t.csv:2: expected 2 fields"),
            (
                "t_s,temp_c\n0,warm\n",
                "t.csv:2: column temp_c: expected a number",
            ),
            ("t_s,temp_c\n-1,20\n", "t.csv:2: column t_s: value -1"),
            ("t_s,temp_c\n0,20\n0,21\n", "t.csv:3: t_s 0 s is not after"),
            (
                "t_s,temp_c\n0,20\n5,-300\n",
                "t.csv:3: column temp_c: value -300",
            ),
            ("t_s,temp_c\n0,nan\n", "t.csv:2: column temp_c: value NaN"),
            ("t_s,temp_c\ninf,20\n", "t.csv:2: column t_s: value inf"),
            // A clock time where the time since the start belongs (issue 37).
            (
                "t_s,temp_c\n1700000000,20\n1700000600,21\n",
                "t.csv:2: column t_s: value 1700000000",
            ),
            ("t_s,temp_c\n5,20\n", "0 s on the first row"),
        ];
        for (text, needle) in cases {
            let error = parse(text).unwrap_err();
            assert!(error.contains(needle), "{text:?}: {error}");
        }
    }
}
