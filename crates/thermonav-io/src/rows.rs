//! Data rows of a canonical CSV: fields split, parsed, converted to SI and checked.

use crate::Strictness;
use crate::error::{ReadError, ReadErrorKind};
use crate::fixed::{TimeOrder, shown};
use crate::layout::{Layout, MAX_SLOTS, Schema, Target};
use crate::lines::Lines;
use crate::text::{parse_time_prefix, parse_value_prefix};
use std::io::BufRead;
use thermonav::time::Timestamp;

/// Byte-order mark some editors put before the header.
const UTF8_BOM: &[u8] = b"\xEF\xBB\xBF";

/// Decoded rows of one input: a time and an array of SI values indexed by slot.
pub(crate) struct Rows<R> {
    lines: Lines<R>,
    layout: Layout,
    strictness: Strictness,
    values: [f64; MAX_SLOTS],
    order: TimeOrder,
    state: State,
    times: RowTimes,
    /// Data rows decoded so far.
    rows: u64,
}

/// Where the rows' times come from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum RowTimes {
    /// The `t_s` column.
    Column,
    /// No time column: row k (0-based) is at k / rate_hz s, rounded to the nanosecond.
    Rate {
        /// The sample rate, Hz (finite and positive).
        rate_hz: f64,
    },
}

impl RowTimes {
    fn rate_hz(self) -> Option<f64> {
        match self {
            RowTimes::Column => None,
            RowTimes::Rate { rate_hz } => Some(rate_hz),
        }
    }
}

/// Time of row `index` at `rate_hz`: index / rate_hz seconds, to the nearest nanosecond.
/// Computed from the index, never summed, so no error accumulates; exact whenever the
/// period is a whole number of nanoseconds (1e9 / rate_hz integral, as for 100 Hz or 2 kHz)
/// and the index below 2^53 / 1e9 · rate_hz.
pub(crate) fn time_at_rate(index: u64, rate_hz: f64) -> Timestamp {
    let nanos = (index as f64 * (1e9 / rate_hz)).round();
    // Saturates beyond ±9.2e9 s, which no file reaches (2^63 ns at 1 kHz is 9e15 rows).
    Timestamp::from_nanos(nanos as i64)
}

/// Where a row reader is in its input.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    /// Header read, no data row yet.
    BeforeFirstRow,
    /// At least one data row read.
    InRows,
    /// End reached or an error given: yields nothing more.
    Done,
}

impl<R: BufRead> Rows<R> {
    /// Reads the header of `reader` (called `input` in errors) and maps it with `schema`.
    ///
    /// # Errors
    /// [`ReadErrorKind::Empty`], a read failure, or a header error from [`Layout::from_header`].
    pub(crate) fn open(
        reader: R,
        input: String,
        schema: &Schema,
        strictness: Strictness,
    ) -> Result<Self, ReadError> {
        Self::open_timed(reader, input, schema, strictness, RowTimes::Column)
    }

    /// [`Rows::open`] with the rows' times from `times`.
    ///
    /// # Errors
    /// As [`Rows::open`]; with [`RowTimes::Rate`], a header with a `t_s` column.
    pub(crate) fn open_timed(
        reader: R,
        input: String,
        schema: &Schema,
        strictness: Strictness,
        times: RowTimes,
    ) -> Result<Self, ReadError> {
        let mut lines = Lines::new(reader, input);
        if !lines.advance()? {
            return Err(lines.error_in_input(ReadErrorKind::Empty));
        }
        let bytes = lines.current();
        let bytes = bytes.strip_prefix(UTF8_BOM).unwrap_or(bytes);
        let header = std::str::from_utf8(bytes)
            .map_err(|_| lines.error_here(ReadErrorKind::HeaderNotUtf8))?;
        let layout = Layout::from_header(header, schema, times.rate_hz())
            .map_err(|kind| lines.error_here(kind))?;
        Ok(Self {
            lines,
            layout,
            strictness,
            values: [0.0; MAX_SLOTS],
            order: TimeOrder::default(),
            state: State::BeforeFirstRow,
            times,
            rows: 0,
        })
    }

    /// The header's columns.
    pub(crate) fn layout(&self) -> &Layout {
        &self.layout
    }

    /// The reading policy.
    pub(crate) fn strictness(&self) -> Strictness {
        self.strictness
    }

    /// Length of the current line in bytes, its line end included.
    pub(crate) fn line_bytes(&self) -> u64 {
        self.lines.current().len() as u64 + 1
    }

    /// An error about the header line (for format-specific header checks).
    pub(crate) fn header_error(&self, kind: ReadErrorKind) -> ReadError {
        self.lines.error_here(kind)
    }

    /// An error about the current data line (for format-specific value checks); ends reading.
    pub(crate) fn row_error(&mut self, kind: ReadErrorKind) -> ReadError {
        self.state = State::Done;
        self.lines.error_here(kind)
    }

    /// The next row's time and values (indexed by slot; unfilled slots hold stale numbers),
    /// `None` after the last row or after an error. A header with no row after it is an error.
    pub(crate) fn next_row(&mut self) -> Option<Result<(Timestamp, &[f64; MAX_SLOTS]), ReadError>> {
        if self.state == State::Done {
            return None;
        }
        match self.advance_and_decode() {
            Ok(Some(time)) => Some(Ok((time, &self.values))),
            Ok(None) => None,
            Err(error) => {
                self.state = State::Done;
                Some(Err(error))
            }
        }
    }

    fn advance_and_decode(&mut self) -> Result<Option<Timestamp>, ReadError> {
        // The common shape straight from the unread bytes, its line end found by the decoder
        // (no separate search for it); any other line by the line-at-a-time path.
        let bound = self.fast_bound();
        let in_place = match self.state {
            State::InRows => crate::fast_row::decode_next_line(
                self.lines.unread(),
                &self.layout,
                bound,
                &mut self.values,
            ),
            _ => None,
        };
        let time = match in_place {
            Some((time, content, taken)) => {
                self.lines.take_decoded_line(content, taken);
                time
            }
            None => match self.advance_and_decode_line()? {
                Some(time) => time,
                None => return Ok(None),
            },
        };
        let time = match self.times {
            RowTimes::Column => time,
            RowTimes::Rate { rate_hz } => time_at_rate(self.rows, rate_hz),
        };
        self.rows += 1;
        self.check_time_order(time)?;
        Ok(Some(time))
    }

    /// The next non-blank line found and decoded (the one-pass decoder, then the general one);
    /// `None` at the end of the input.
    fn advance_and_decode_line(&mut self) -> Result<Option<Timestamp>, ReadError> {
        if !self.lines.advance()? {
            let first = self.state == State::BeforeFirstRow;
            self.state = State::Done;
            return match first {
                true => Err(self.lines.error_in_input(ReadErrorKind::HeaderOnly)),
                false => Ok(None),
            };
        }
        self.state = State::InRows;
        // The common shape in one pass; any other line (or a bad one) by the general decoder,
        // which gives the same values or the error.
        let fast = crate::fast_row::decode_line(
            self.lines.current_and_after(),
            self.lines.current().len(),
            &self.layout,
            self.fast_bound(),
            &mut self.values,
        );
        let time = match fast {
            Some(time) => time,
            None => decode_line(
                self.lines.current(),
                &self.layout,
                self.strictness,
                &mut self.values,
            )
            .map_err(|kind| self.lines.error_here(kind))?,
        };
        Ok(Some(time))
    }

    /// What the one-pass decoder refuses: whether reading is strict, and the strict reader's
    /// largest magnitude.
    fn fast_bound(&self) -> (bool, f64) {
        (self.strictness == Strictness::Strict, MAX_MAGNITUDE)
    }

    /// Under [`Strictness::Strict`], times must increase strictly from row to row.
    fn check_time_order(&mut self, time: Timestamp) -> Result<(), ReadError> {
        self.order
            .check(time, self.lines.number(), self.strictness)
            .map_err(|kind| self.lines.error_here(kind))
    }
}

/// Splits `line` into the layout's fields, parses each into `values` (SI) and returns the time.
/// A wrong number of fields is reported before any bad field.
pub(crate) fn decode_line(
    line: &[u8],
    layout: &Layout,
    strictness: Strictness,
    values: &mut [f64; MAX_SLOTS],
) -> Result<Timestamp, ReadErrorKind> {
    decode_fields(line, layout, strictness, values).map_err(|kind| {
        match count_fields(line) == layout.targets.len() {
            true => kind,
            false => field_count_error(line, layout),
        }
    })
}

fn decode_fields(
    line: &[u8],
    layout: &Layout,
    strictness: Strictness,
    values: &mut [f64; MAX_SLOTS],
) -> Result<Timestamp, ReadErrorKind> {
    let mut time = Timestamp::from_nanos(0);
    let mut position = 0;
    let last = layout.targets.len() - 1;
    for (column, target) in layout.targets.iter().enumerate() {
        let start = position + leading_blanks(&line[position..]);
        let field = &line[start..];
        let len = match *target {
            Target::Time => parse_time_prefix(field).map(|(t, len)| {
                time = t;
                len
            }),
            Target::Value { slot, unit } => parse_value_prefix(field).map(|(value, len)| {
                values[slot] = unit.to_si(value);
                len
            }),
        };
        let end = len.and_then(|len| field_end(line, start + len, column == last));
        let Some(end) = end else {
            return Err(field_error(line, column, layout));
        };
        if let (Target::Value { slot, .. }, Strictness::Strict) = (*target, strictness) {
            if !values[slot].is_finite() {
                return Err(non_finite_error(&line[start..end], &layout.names[column]));
            }
            if values[slot].abs() > MAX_MAGNITUDE {
                return Err(ReadErrorKind::TooLarge {
                    column: layout.names[column].clone(),
                    found: shown(&line[start..end]),
                });
            }
        }
        position = end + 1;
    }
    Ok(time)
}

/// Number of spaces and tabs at the start of `text`.
#[inline]
fn leading_blanks(text: &[u8]) -> usize {
    text.iter()
        .take_while(|&&b| b == b' ' || b == b'\t')
        .count()
}

/// Where a field whose number ends at `number_end` ends (before its comma or the line end),
/// when only blanks follow the number; `None` otherwise, or when a comma follows the last field
/// or none follows another.
#[inline]
fn field_end(line: &[u8], number_end: usize, last: bool) -> Option<usize> {
    let end = number_end + leading_blanks(&line[number_end..]);
    match (line.get(end), last) {
        (None, true) | (Some(b','), false) => Some(end),
        _ => None,
    }
}

/// The error for a field that is not a number (or a time), or for a line with too few fields.
fn field_error(line: &[u8], column: usize, layout: &Layout) -> ReadErrorKind {
    let Some(field) = line.split(|&b| b == b',').nth(column) else {
        return field_count_error(line, layout);
    };
    let field = field.trim_ascii();
    let name = layout.names[column].clone();
    match layout.targets[column] {
        Target::Time => ReadErrorKind::BadTime {
            column: name,
            found: shown(field),
        },
        Target::Value { .. } => ReadErrorKind::NotANumber {
            column: name,
            found: shown(field),
        },
    }
}

fn field_count_error(line: &[u8], layout: &Layout) -> ReadErrorKind {
    ReadErrorKind::FieldCount {
        expected: layout.targets.len(),
        header: layout.header.clone(),
        found: count_fields(line),
    }
}

fn count_fields(line: &[u8]) -> usize {
    line.iter().filter(|&&b| b == b',').count() + 1
}

/// The largest magnitude a strict reader accepts (in SI, after the unit conversion): far beyond any physical
/// reading of these files, and small enough that the squares and sums of a day of samples stay
/// finite in every estimator (a single 1e300 made the Allan deviation infinite).
pub(crate) const MAX_MAGNITUDE: f64 = 1e15;

fn non_finite_error(field: &[u8], column: &str) -> ReadErrorKind {
    ReadErrorKind::NonFinite {
        column: column.to_owned(),
        found: shown(field),
    }
}
