//! Lines of foreign text formats whose fields are known by position (no header of names):
//! splitting, numbers, exact times, time order, and the loop that numbers lines for errors.

use crate::Strictness;
use crate::error::{ReadError, ReadErrorKind};
use crate::lines::Lines;
use crate::text::{parse_time_prefix, parse_value_prefix};
use std::io::BufRead;
use thermonav::time::Timestamp;

/// The fields of `line` separated by runs of blanks (spaces, tabs).
pub(crate) fn split_blanks(line: &[u8]) -> Vec<&[u8]> {
    line.split(|b| b.is_ascii_whitespace())
        .filter(|field| !field.is_empty())
        .collect()
}

/// The fields of `line` separated by `separator`, each without surrounding blanks.
pub(crate) fn split_on(line: &[u8], separator: u8) -> Vec<&[u8]> {
    line.split(|&b| b == separator)
        .map(<[u8]>::trim_ascii)
        .collect()
}

/// Fails unless there are `expected` fields; `layout` lists them for the message.
pub(crate) fn expect_fields(
    fields: &[&[u8]],
    expected: usize,
    layout: &'static str,
) -> Result<(), ReadErrorKind> {
    match fields.len() == expected {
        true => Ok(()),
        false => Err(ReadErrorKind::FieldCount {
            expected,
            header: layout.to_owned(),
            found: fields.len(),
        }),
    }
}

/// Field `index` (0-based) as a number; NaN and infinities are errors under strict reading.
pub(crate) fn number(
    fields: &[&[u8]],
    index: usize,
    column: &'static str,
    strictness: Strictness,
) -> Result<f64, ReadErrorKind> {
    let field = fields.get(index).copied().unwrap_or_default();
    let value = match parse_value_prefix(field) {
        Some((value, len)) if len == field.len() => value,
        _ => {
            return Err(ReadErrorKind::NotANumber {
                column: column_name(index, column),
                found: shown(field),
            });
        }
    };
    if strictness == Strictness::Strict && !value.is_finite() {
        return Err(ReadErrorKind::NonFinite {
            column: column_name(index, column),
            found: shown(field),
        });
    }
    Ok(value)
}

/// Field `index` (0-based) as a whole number from 0 to `max`; `expected` says what it is.
pub(crate) fn whole_number(
    fields: &[&[u8]],
    index: usize,
    column: &'static str,
    max: u64,
    expected: &'static str,
) -> Result<u64, ReadErrorKind> {
    let value = number(fields, index, column, Strictness::Strict)?;
    match value.fract() == 0.0 && (0.0..=max as f64).contains(&value) {
        true => Ok(value as u64),
        false => Err(ReadErrorKind::BadField {
            index: index + 1,
            column,
            expected,
            found: shown(fields.get(index).copied().unwrap_or_default()),
        }),
    }
}

/// `N` consecutive fields from `first` (0-based) as numbers, named by `columns`.
pub(crate) fn numbers<const N: usize>(
    fields: &[&[u8]],
    first: usize,
    columns: [&'static str; N],
    strictness: Strictness,
) -> Result<[f64; N], ReadErrorKind> {
    let mut values = [0.0; N];
    for (offset, (value, column)) in values.iter_mut().zip(columns).enumerate() {
        *value = number(fields, first + offset, column, strictness)?;
    }
    Ok(values)
}

/// Field `index` (0-based) as exact seconds (nanoseconds); never NaN.
pub(crate) fn seconds(
    fields: &[&[u8]],
    index: usize,
    column: &'static str,
) -> Result<Timestamp, ReadErrorKind> {
    let field = fields.get(index).copied().unwrap_or_default();
    match parse_time_prefix(field) {
        Some((time, len)) if len == field.len() => Ok(time),
        _ => Err(ReadErrorKind::BadTime {
            column: column_name(index, column),
            found: shown(field),
        }),
    }
}

/// A column's name for messages: its format name and 1-based field position.
fn column_name(index: usize, column: &str) -> String {
    format!("{column} (field {})", index + 1)
}

/// A field's text for an error message, cut to 40 characters.
pub(crate) fn shown(field: &[u8]) -> String {
    const LIMIT: usize = 40;
    let text = String::from_utf8_lossy(field);
    match text.char_indices().nth(LIMIT) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text.into_owned(),
    }
}

/// Under [`Strictness::Strict`], times must increase strictly from record to record.
#[derive(Debug, Default)]
pub(crate) struct TimeOrder {
    previous: Option<(Timestamp, u64)>,
}

impl TimeOrder {
    /// Records `time` of `line`; fails when it does not follow the previous time (strict).
    pub(crate) fn check(
        &mut self,
        time: Timestamp,
        line: u64,
        strictness: Strictness,
    ) -> Result<(), ReadErrorKind> {
        let previous = self.previous.replace((time, line));
        match (strictness, previous) {
            (Strictness::Strict, Some((previous, previous_line))) if time <= previous => {
                Err(ReadErrorKind::NonIncreasingTime {
                    previous,
                    previous_line,
                    current: time,
                })
            }
            _ => Ok(()),
        }
    }
}

/// Reads every line of `reader` (named `input` in errors) through `decode`, which gives a
/// timed record, or `None` for a line the format skips (comments, filtered records). Errors
/// are tied to their line; times must increase under strict reading; a file without any line
/// is [`ReadErrorKind::NoData`] with `expected` saying what the lines hold.
pub(crate) fn read_records<T>(
    reader: impl BufRead,
    input: String,
    strictness: Strictness,
    expected: &'static str,
    mut decode: impl FnMut(&[u8]) -> Result<Option<(Timestamp, T)>, ReadErrorKind>,
) -> Result<Vec<T>, ReadError> {
    let mut lines = Lines::new(reader, input);
    let mut order = TimeOrder::default();
    let mut records = Vec::new();
    let mut any_line = false;
    while lines.advance()? {
        any_line = true;
        let decoded = decode(lines.current()).map_err(|kind| lines.error_here(kind))?;
        if let Some((time, record)) = decoded {
            order
                .check(time, lines.number(), strictness)
                .map_err(|kind| lines.error_here(kind))?;
            records.push(record);
        }
    }
    match any_line {
        true => Ok(records),
        false => Err(lines.error_in_input(ReadErrorKind::NoData { expected })),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blanks_split_fields() {
        assert_eq!(split_blanks(b"  1 \t2   3 "), vec![&b"1"[..], b"2", b"3"]);
    }

    #[test]
    fn numbers_name_their_field_and_nan_is_strict_only() {
        let fields = [&b"1.5"[..], b"x", b"nan"];
        assert_eq!(number(&fields, 0, "a", Strictness::Strict).unwrap(), 1.5);
        let error = number(&fields, 1, "b", Strictness::Strict).unwrap_err();
        assert_eq!(
            error.to_string(),
            "column b (field 2): expected a number, found \"x\""
        );
        assert!(number(&fields, 2, "c", Strictness::Strict).is_err());
        assert!(
            number(&fields, 2, "c", Strictness::Lenient)
                .unwrap()
                .is_nan()
        );
    }
}
