//! Raw IMU CSV logged by RTKLIB with its time-tag file (`imu.csv` + `imu.csv.tag`), as in
//! GitHub `rtklibexplorer/GNSS_IMU` (`data/*/imu_*.csv`, converter `src/convert_imu_file.py`).
//!
//! The CSV has no header and 7 comma-separated columns: `ax ay az` (g), `gx gy gz` (deg/s),
//! `tick` (ms since IMU power-up). The first and the last line are partial (the logger starts
//! and stops mid-line) and are dropped unread, as the author's converter does.
//!
//! The `.tag` file (binary, little-endian): a 60-byte text header starting `TIMETAG`, `u32`
//! tick of the start, `u32` start time (whole seconds since 1970 counted in GPST, no leap
//! seconds), `f64` fraction of a second, then pairs `u32 tick_ms` (since the start),
//! `u32 file offset`. Sample `i` is timed by stretching the IMU's tick counter onto the span
//! of the tag file: `t_i = start + (tick_i − tick_first) / (tick_last − tick_first) · span`,
//! with `span` = the last pair's `tick_ms` / 1000, computed here in exact integer nanoseconds
//! (rounded to the nearest). Times are on the GPST scale of [`crate::gpst`].
//!
//! Units become SI (g × 9.80665, deg/s × π/180). Frame: the data stays in the sensor's frame
//! ([`ImuFrame::Sensor`]), in which the drive's accelerometer reads az ≈ +1 g at rest (z up);
//! navigation in thermonav needs forward-right-down body axes, so either rotate downstream or
//! choose [`ImuFrame::DriveMountingFrd`], the author's documented mounting of the drive
//! (roll 180°, pitch 0°, yaw 180°: x_b = −x_s, y_b = y_s, z_b = −z_s; the further small
//! misalignment the author estimates, [0, −6.79, 5.35]°, is not applied). The author also
//! shifts the IMU times by −0.125 s (logging delay); [`RawImuSettings::time_offset`] does that
//! when asked, and is zero by default.

use crate::Strictness;
use crate::error::{ReadError, ReadErrorKind};
use crate::fixed::{TimeOrder, expect_fields, numbers, split_on, whole_number};
use crate::lines::Lines;
use std::io::BufRead;
use std::path::Path;
use thermonav::imu::{ImuSample, ImuSeries, SampleKind};
use thermonav::time::{Duration, NANOS_PER_SECOND, Timestamp};
use thermonav::units::{deg_to_rad, g_to_m_per_s2};

/// What a time-tag file says: when the log started and how long it lasted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TimeTag {
    /// Start of the log, GPST-counted seconds since 1970 (as nanoseconds).
    pub start: Timestamp,
    /// The receiver's tick at the start, ms (`tick_f`, informative).
    pub start_tick_ms: u32,
    /// Span of the log: the last pair's tick, since the start.
    pub span: Duration,
    /// Number of tick/offset pairs.
    pub pairs: usize,
}

/// Length of the text header of a tag file, bytes.
const TAG_TEXT_BYTES: usize = 60;
/// Header, tick, whole seconds and fraction, bytes.
const TAG_HEADER_BYTES: usize = TAG_TEXT_BYTES + 4 + 4 + 8;
/// One tick/offset pair, bytes.
const TAG_PAIR_BYTES: usize = 8;

/// Decodes the bytes of a time-tag file, named `input` in errors.
///
/// # Errors
/// [`ReadErrorKind::BadBinary`] with the byte offset: a file shorter than its header, a header
/// not starting `TIMETAG`, a fraction outside [0, 1), a trailing partial pair, or no pair.
pub fn decode_time_tag(bytes: &[u8], input: &str) -> Result<TimeTag, ReadError> {
    let error = |offset: usize, expected| {
        ReadError::new(
            input,
            None,
            ReadErrorKind::BadBinary {
                offset: offset as u64,
                expected,
            },
        )
    };
    if bytes.len() < TAG_HEADER_BYTES {
        return Err(error(bytes.len(), "a 76-byte RTKLIB time-tag header"));
    }
    if !bytes.starts_with(b"TIMETAG") {
        return Err(error(0, "the text TIMETAG (an RTKLIB time-tag file)"));
    }
    let u32_at = |offset: usize| {
        u32::from_le_bytes([
            bytes[offset],
            bytes[offset + 1],
            bytes[offset + 2],
            bytes[offset + 3],
        ])
    };
    let fraction = f64::from_le_bytes(std::array::from_fn(|i| bytes[TAG_TEXT_BYTES + 8 + i]));
    if !(0.0..1.0).contains(&fraction) {
        return Err(error(
            TAG_TEXT_BYTES + 8,
            "a fraction of a second in [0, 1)",
        ));
    }
    let pairs = &bytes[TAG_HEADER_BYTES..];
    if pairs.len() % TAG_PAIR_BYTES != 0 {
        let partial = TAG_HEADER_BYTES + pairs.len() / TAG_PAIR_BYTES * TAG_PAIR_BYTES;
        return Err(error(partial, "whole 8-byte tick/offset pairs"));
    }
    if pairs.is_empty() {
        return Err(error(TAG_HEADER_BYTES, "at least one tick/offset pair"));
    }
    let last_tick_ms = u32_at(bytes.len() - TAG_PAIR_BYTES);
    // Rounded to the nanosecond: the fraction is a binary double (0.854 is 0.85399999…).
    let fraction_nanos = (fraction * NANOS_PER_SECOND as f64).round() as i64;
    let start_seconds = i64::from(u32_at(TAG_TEXT_BYTES + 4));
    Ok(TimeTag {
        start: Timestamp::from_nanos(start_seconds * NANOS_PER_SECOND + fraction_nanos),
        start_tick_ms: u32_at(TAG_TEXT_BYTES),
        span: Duration::from_nanos(i64::from(last_tick_ms) * 1_000_000),
        pairs: pairs.len() / TAG_PAIR_BYTES,
    })
}

/// Reads a time-tag file.
///
/// # Errors
/// [`ReadErrorKind::Open`] or [`ReadErrorKind::Read`], and those of [`decode_time_tag`].
pub fn read_time_tag_file(path: impl AsRef<Path>) -> Result<TimeTag, ReadError> {
    let (bytes, input) = crate::read_whole_file(path.as_ref())?;
    decode_time_tag(&bytes, &input)
}

/// The axes the samples are given in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ImuFrame {
    /// As recorded (the drive's sensor: z up, az ≈ +1 g at rest).
    #[default]
    Sensor,
    /// Forward-right-down by the drive's documented mounting (roll 180°, yaw 180°):
    /// x_b = −x_s, y_b = y_s, z_b = −z_s (misalignment not applied).
    DriveMountingFrd,
}

impl ImuFrame {
    /// A sensor-frame vector in this frame.
    fn apply(self, v: [f64; 3]) -> [f64; 3] {
        match self {
            ImuFrame::Sensor => v,
            ImuFrame::DriveMountingFrd => [-v[0], v[1], -v[2]],
        }
    }
}

/// How a raw IMU CSV is read.
#[derive(Debug, Clone, Copy)]
pub struct RawImuSettings {
    /// NaN values and ticks that do not increase are errors under strict reading.
    pub strictness: Strictness,
    /// The axes of the result.
    pub frame: ImuFrame,
    /// Added to every time (the drive's author uses −0.125 s for the logging delay).
    pub time_offset: Duration,
}

impl Default for RawImuSettings {
    fn default() -> Self {
        Self {
            strictness: Strictness::Strict,
            frame: ImuFrame::Sensor,
            time_offset: Duration::from_nanos(0),
        }
    }
}

const RAW_LAYOUT: &str = "ax,ay,az (g), gx,gy,gz (deg/s), tick (ms)";

/// One kept row: tick and SI values in the sensor frame.
struct RawRow {
    tick_ms: i64,
    gyro: [f64; 3],
    accel: [f64; 3],
}

/// Reads a raw IMU CSV from `reader` (named `input` in errors), timed by `tag`.
///
/// # Errors
/// [`ReadErrorKind::NoData`] for fewer than three lines (two are dropped), a line without 7
/// fields, a field that is not a number or a tick that is not a whole number, NaN (strict), a
/// tick that does not increase (strict; the message gives ticks as seconds since power-up),
/// each with its line; [`ReadErrorKind::Unusable`] when the first and last kept ticks are
/// equal or a time falls outside the representable range.
pub fn read_raw_imu(
    reader: impl BufRead,
    input: impl Into<String>,
    tag: &TimeTag,
    settings: RawImuSettings,
) -> Result<ImuSeries, ReadError> {
    let mut lines = Lines::new(reader, input.into());
    let mut pending: Option<Vec<u8>> = None;
    let mut pending_line = 0;
    let mut rows = Vec::new();
    let mut order = TimeOrder::default();
    let mut first_seen = false;
    while lines.advance()? {
        if !first_seen {
            // The first line is partial: dropped unread.
            first_seen = true;
            continue;
        }
        if let Some(text) = pending.replace(lines.current().to_vec()) {
            let row = decode_row(&text, settings.strictness)
                .and_then(|row| {
                    let tick = Timestamp::from_nanos(row.tick_ms * 1_000_000);
                    order.check(tick, pending_line, settings.strictness)?;
                    Ok(row)
                })
                .map_err(|kind| lines.error_at(pending_line, kind))?;
            rows.push(row);
        }
        pending_line = lines.number();
    }
    // `pending` now holds the last line, partial: dropped unread.
    if rows.is_empty() {
        return Err(lines.error_in_input(ReadErrorKind::NoData {
            expected: "at least 3 lines of ax,ay,az,gx,gy,gz,tick; the first and last are \
                       partial and dropped",
        }));
    }
    series_from_rows(&rows, tag, settings).map_err(|kind| lines.error_in_input(kind))
}

/// Reads `csv` timed by its tag file `tag` (usually `csv` + `.tag`).
///
/// # Errors
/// Those of [`read_time_tag_file`] and [`read_raw_imu`], plus [`ReadErrorKind::Open`].
pub fn read_raw_imu_files(
    csv: impl AsRef<Path>,
    tag: impl AsRef<Path>,
    settings: RawImuSettings,
) -> Result<ImuSeries, ReadError> {
    let tag = read_time_tag_file(tag)?;
    let (file, input) = crate::open_file(csv.as_ref())?;
    read_raw_imu(file, input, &tag, settings)
}

/// One CSV line as a row in SI units (sensor frame).
fn decode_row(line: &[u8], strictness: Strictness) -> Result<RawRow, ReadErrorKind> {
    let fields = split_on(line, b',');
    expect_fields(&fields, 7, RAW_LAYOUT)?;
    let accel_g = numbers(&fields, 0, ["ax (g)", "ay (g)", "az (g)"], strictness)?;
    let gyro_deg_s = numbers(
        &fields,
        3,
        ["gx (deg/s)", "gy (deg/s)", "gz (deg/s)"],
        strictness,
    )?;
    let tick = whole_number(
        &fields,
        6,
        "tick",
        9_000_000_000_000_000,
        "whole milliseconds since power-up",
    )?;
    Ok(RawRow {
        tick_ms: tick as i64,
        gyro: gyro_deg_s.map(deg_to_rad),
        accel: accel_g.map(g_to_m_per_s2),
    })
}

/// The series of kept rows, timed by stretching their ticks onto the tag's span.
fn series_from_rows(
    rows: &[RawRow],
    tag: &TimeTag,
    settings: RawImuSettings,
) -> Result<ImuSeries, ReadErrorKind> {
    let first = rows[0].tick_ms;
    let ticks = rows[rows.len() - 1].tick_ms - first;
    if ticks == 0 {
        return Err(ReadErrorKind::Unusable(format!(
            "the first and last kept rows have the same tick {first} ms (need at least two \
             distinct ticks to map onto the tag file's span)"
        )));
    }
    let start = tag.start.checked_add(settings.time_offset);
    let mut series = ImuSeries::new(SampleKind::Rates);
    for row in rows {
        let elapsed = row.tick_ms - first;
        let time = start
            .zip(stretched_nanos(elapsed, ticks, tag.span.as_nanos()))
            .and_then(|(start, offset)| start.checked_add(Duration::from_nanos(offset)))
            .ok_or_else(|| {
                ReadErrorKind::Unusable(format!(
                    "tick {} ms maps outside the time range (±292 years) with this tag file \
                     and time offset",
                    row.tick_ms
                ))
            })?;
        series.push(&ImuSample {
            time,
            gyro: settings.frame.apply(row.gyro),
            accel: settings.frame.apply(row.accel),
            temperature_c: None,
        });
    }
    Ok(series)
}

/// `elapsed / total · span`, in integer arithmetic rounded to the nearest nanosecond.
/// `None` when the result does not fit (ticks far outside the first-to-last range, which only
/// lenient reading lets through).
fn stretched_nanos(elapsed_ticks: i64, total_ticks: i64, span_nanos: i64) -> Option<i64> {
    let numerator = i128::from(elapsed_ticks) * i128::from(span_nanos);
    let total = i128::from(total_ticks);
    let rounded = (2 * numerator + total).div_euclid(2 * total);
    i64::try_from(rounded).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stretching_maps_the_ends_exactly_and_rounds_to_nearest() {
        assert_eq!(stretched_nanos(0, 3, 1_000), Some(0));
        assert_eq!(stretched_nanos(3, 3, 1_000), Some(1_000));
        // 1/3 of 1000 ns = 333.33… → 333; 2/3 → 666.67 → 667.
        assert_eq!(stretched_nanos(1, 3, 1_000), Some(333));
        assert_eq!(stretched_nanos(2, 3, 1_000), Some(667));
        assert_eq!(stretched_nanos(i64::MAX / 2, 1, i64::MAX), None);
    }
}
