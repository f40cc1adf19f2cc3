//! NMEA 0183 logs: GGA, RMC, VTG, HDT and THS sentences combined per epoch into [`GnssFix`]es.
//!
//! Every sentence must end in `*hh`, the XOR of its characters between `$` and `*`; under
//! [`Strictness::Strict`] a line that is not a sentence, or whose checksum is missing or wrong,
//! is an error naming the line, under [`Strictness::Lenient`] it is skipped. Any talker is
//! accepted (`GP`, `GN`, `GL`, `HE`, `IN`, …); other sentence types are ignored.
//!
//! Epochs: GGA and RMC carry the UTC time of day (sentences with an empty time, sent before
//! a first fix, are ignored); sentences with the same time form one epoch.
//! VTG, HDT and THS carry no time and join the latest timed epoch (receivers send them right
//! after its GGA/RMC). An epoch gives a fix when it has a GGA with fix quality > 0:
//! - position: GGA latitude and longitude; height = GGA altitude above mean sea level + geoid
//!   separation, i.e. ellipsoidal (an empty separation counts as 0);
//! - velocity (only with [`NmeaSettings::level_velocity`]): RMC or VTG speed over ground and
//!   true course as north and east, with down set to 0 — NMEA has no vertical speed, so this
//!   is an assumption and off by default;
//! - heading (only with [`NmeaSettings::heading_sd_rad`], as NMEA gives no uncertainty): HDT,
//!   or THS unless its mode is `V` (not valid).
//!
//! No standard deviation is read (GST is not decoded). Time: the date comes from RMC (the
//! latest one before the epoch, or the first one for epochs before it; days roll over when the
//! time of day decreases); without any RMC, [`NmeaSettings::date`] must give it. UTC is put on
//! the GPST scale of [`crate::gpst`] by adding [`NmeaSettings::gpst_minus_utc`] (18 s from
//! 2017 on).

use crate::Strictness;
use crate::error::{ReadError, ReadErrorKind};
use crate::fixed::{number, read_records, seconds, shown, split_on};
use crate::gpst;
use std::io::BufRead;
use std::path::Path;
use thermonav::gnss::{GnssFix, HeadingObservation};
use thermonav::time::{Duration, NANOS_PER_SECOND};
use thermonav::units::deg_to_rad;

/// How an NMEA log is read.
#[derive(Debug, Clone, Copy)]
pub struct NmeaSettings {
    /// Bad lines and checksums: errors (strict) or skipped (lenient); NaN rejected (strict).
    pub strictness: Strictness,
    /// GPST − UTC, added to every time (leap seconds; 18 s from 2017-01-01).
    pub gpst_minus_utc: Duration,
    /// The UTC date (year, month, day) of the first epoch when the log has no RMC sentence.
    pub date: Option<(i32, u32, u32)>,
    /// Standard deviation given to HDT/THS headings, rad; `None` drops headings.
    pub heading_sd_rad: Option<f64>,
    /// Turn speed over ground and course into a velocity with down = 0.
    pub level_velocity: bool,
}

impl Default for NmeaSettings {
    fn default() -> Self {
        Self {
            strictness: Strictness::Strict,
            gpst_minus_utc: Duration::from_nanos(gpst::GPST_MINUS_UTC_S * NANOS_PER_SECOND),
            date: None,
            heading_sd_rad: None,
            level_velocity: false,
        }
    }
}

/// What one epoch's sentences said.
#[derive(Debug, Clone, Default)]
struct Epoch {
    /// UTC time of day, ns.
    time_of_day: i64,
    /// Days since 1970-01-01 from RMC.
    date: Option<i64>,
    /// GGA latitude, longitude (rad) and ellipsoidal height, with a valid fix.
    position: Option<[f64; 3]>,
    /// Course over ground (rad, true) and speed (m/s).
    course_speed: Option<(f64, f64)>,
    /// True heading, rad.
    heading: Option<f64>,
}

/// Reads an NMEA log from `reader` (named `input` in errors).
///
/// # Errors
/// [`ReadErrorKind::NoData`]; under strict reading a line that is not a sentence or has a bad
/// checksum; a field that is not what its sentence expects; [`ReadErrorKind::Unusable`] when
/// no epoch has a GGA fix, or no date is known.
pub fn read_nmea(
    reader: impl BufRead,
    input: impl Into<String>,
    settings: NmeaSettings,
) -> Result<Vec<GnssFix>, ReadError> {
    let input = input.into();
    let mut epochs: Vec<Epoch> = Vec::new();
    read_records::<()>(
        reader,
        input.clone(),
        settings.strictness,
        EXPECTED,
        |line| {
            let Some(fields) = sentence_fields(line, settings.strictness)? else {
                return Ok(None);
            };
            decode_sentence(&fields, &mut epochs, settings.strictness)?;
            Ok(None)
        },
    )?;
    fixes_of(&epochs, &settings).map_err(|kind| ReadError::new(input, None, kind))
}

/// Reads an NMEA log from `path`.
///
/// # Errors
/// As [`read_nmea`], plus [`ReadErrorKind::Open`].
pub fn read_nmea_file(
    path: impl AsRef<Path>,
    settings: NmeaSettings,
) -> Result<Vec<GnssFix>, ReadError> {
    let (file, input) = crate::open_file(path.as_ref())?;
    read_nmea(file, input, settings)
}

const EXPECTED: &str = "NMEA 0183 sentences such as $GPGGA,…*hh";

/// The fields of a sentence after its checksum is verified (the first is talker + type);
/// `None` for a line skipped under lenient reading.
fn sentence_fields(
    line: &[u8],
    strictness: Strictness,
) -> Result<Option<Vec<&[u8]>>, ReadErrorKind> {
    let line = line.trim_ascii();
    let checked = match line.strip_prefix(b"$") {
        None => Err(ReadErrorKind::BadField {
            index: 1,
            column: "sentence",
            expected: "an NMEA sentence starting with $",
            found: shown(line),
        }),
        Some(sentence) => verified_body(sentence),
    };
    match (checked, strictness) {
        (Ok(body), _) => Ok(Some(split_on(body, b','))),
        (Err(_), Strictness::Lenient) => Ok(None),
        (Err(kind), Strictness::Strict) => Err(kind),
    }
}

/// The characters between `$` and `*` when the two hex digits after `*` are their XOR.
fn verified_body(sentence: &[u8]) -> Result<&[u8], ReadErrorKind> {
    let (body, given) = match sentence.iter().rposition(|&b| b == b'*') {
        Some(star) => (&sentence[..star], &sentence[star + 1..]),
        None => (sentence, &b""[..]),
    };
    let computed = body.iter().fold(0_u8, |sum, &b| sum ^ b);
    let matches = std::str::from_utf8(given)
        .ok()
        .filter(|text| text.len() == 2)
        .and_then(|text| u8::from_str_radix(text, 16).ok())
        == Some(computed);
    match matches {
        true => Ok(body),
        false => Err(ReadErrorKind::Checksum {
            given: format!("*{}", shown(given)),
            computed,
        }),
    }
}

/// Adds what one sentence says to the epochs.
fn decode_sentence(
    fields: &[&[u8]],
    epochs: &mut Vec<Epoch>,
    strictness: Strictness,
) -> Result<(), ReadErrorKind> {
    let address = fields[0];
    let proprietary = address.first() == Some(&b'P');
    if !(proprietary || address.len() == 5) || !address.iter().all(u8::is_ascii_alphanumeric) {
        return Err(ReadErrorKind::BadField {
            index: 1,
            column: "sentence address",
            expected: "a talker and sentence type such as GPGGA, then comma-separated fields",
            found: shown(address),
        });
    }
    let kind = &address[address.len().saturating_sub(3)..];
    let field = |index: usize| fields.get(index).copied().unwrap_or_default();
    if matches!(kind, b"GGA" | b"RMC") && field(1).is_empty() {
        // No time yet (receivers send empty sentences before their first fix).
        return Ok(());
    }
    match kind {
        b"GGA" => {
            let time = time_of_day(field(1))?;
            if strictness == Strictness::Strict {
                check_epoch_order(epochs, time, field(1), true)?;
            }
            add_gga(fields, epoch_at(epochs, time), strictness)
        }
        b"RMC" => {
            let time = time_of_day(field(1))?;
            if strictness == Strictness::Strict {
                check_epoch_order(epochs, time, field(1), false)?;
            }
            add_rmc(fields, epoch_at(epochs, time), strictness)
        }
        b"VTG" => add_vtg(fields, epochs.last_mut(), strictness),
        b"HDT" | b"THS" => {
            let valid = kind == b"HDT" || field(2) != b"V";
            let heading = optional(fields, 1, "heading (deg true)", strictness)?;
            if let (Some(epoch), Some(heading), true) = (epochs.last_mut(), heading, valid) {
                epoch.heading = Some(deg_to_rad(heading));
            }
            Ok(())
        }
        _ => Ok(()),
    }
}

/// GGA: the position when the fix quality is above 0 (height made ellipsoidal).
fn add_gga(
    fields: &[&[u8]],
    epoch: &mut Epoch,
    strictness: Strictness,
) -> Result<(), ReadErrorKind> {
    let quality = number(fields, 6, "GGA fix quality", strictness)?;
    if quality > 0.0 {
        let [latitude, longitude] = latitude_longitude(fields, 2, strictness)?;
        if strictness == Strictness::Strict {
            crate::check_latitude(latitude)?;
        }
        let altitude = number(fields, 9, "GGA altitude", strictness)?;
        let separation = optional(fields, 11, "GGA geoid separation", strictness)?;
        epoch.position = Some([latitude, longitude, altitude + separation.unwrap_or(0.0)]);
    }
    Ok(())
}

/// RMC: the date, and course and speed when the status is valid (`A`).
fn add_rmc(
    fields: &[&[u8]],
    epoch: &mut Epoch,
    strictness: Strictness,
) -> Result<(), ReadErrorKind> {
    let field = |index: usize| fields.get(index).copied().unwrap_or_default();
    if !field(9).is_empty() {
        epoch.date = Some(rmc_date(field(9))?);
    }
    if field(2) == b"A" {
        let speed = optional(fields, 7, "RMC speed (knots)", strictness)?;
        let course = optional(fields, 8, "RMC course (deg)", strictness)?;
        if let (Some(knots), Some(course)) = (speed, course) {
            epoch.course_speed = Some((deg_to_rad(course), knots_to_m_s(knots)));
        }
    }
    Ok(())
}

/// VTG: true course and speed (knots, else km/h) for the latest epoch.
fn add_vtg(
    fields: &[&[u8]],
    epoch: Option<&mut Epoch>,
    strictness: Strictness,
) -> Result<(), ReadErrorKind> {
    let course = optional(fields, 1, "VTG course (deg true)", strictness)?;
    let knots = optional(fields, 5, "VTG speed (knots)", strictness)?;
    let km_h = optional(fields, 7, "VTG speed (km/h)", strictness)?;
    let speed = knots.map(knots_to_m_s).or(km_h.map(|v| v / 3.6));
    if let (Some(epoch), Some(course), Some(speed)) = (epoch, course, speed) {
        epoch.course_speed = Some((deg_to_rad(course), speed));
    }
    Ok(())
}

/// The epoch at `time_of_day`: the latest one when its time matches, else a new one.
fn epoch_at(epochs: &mut Vec<Epoch>, time_of_day: i64) -> &mut Epoch {
    if epochs.last().is_none_or(|e| e.time_of_day != time_of_day) {
        epochs.push(Epoch {
            time_of_day,
            ..Epoch::default()
        });
    }
    let last = epochs.len() - 1;
    &mut epochs[last]
}

/// Times of day further back than this from the previous epoch are a day rollover (a log
/// running across midnight UTC); nearer ones are times going backwards.
const ROLLOVER_MIN_BACK_NS: i64 = 12 * 3600 * NANOS_PER_SECOND;

/// Strict reading: refuses a GGA/RMC time before the previous epoch's (unless it crosses
/// midnight) and, for GGA, a second position fix at the same time (a duplicate epoch).
fn check_epoch_order(
    epochs: &[Epoch],
    time_of_day: i64,
    field: &[u8],
    gga: bool,
) -> Result<(), ReadErrorKind> {
    let Some(last) = epochs.last() else {
        return Ok(());
    };
    let back_ns = last.time_of_day - time_of_day;
    let expected = match back_ns {
        0 if gga && last.position.is_some() => "one GGA fix per epoch (this time already has one)",
        1..ROLLOVER_MIN_BACK_NS => {
            "a time after the previous epoch's (a time of day goes back only across midnight)"
        }
        _ => return Ok(()),
    };
    Err(ReadErrorKind::BadField {
        index: 2,
        column: "UTC time",
        expected,
        found: shown(field),
    })
}

/// Field `index` as a number, or `None` when empty.
fn optional(
    fields: &[&[u8]],
    index: usize,
    column: &'static str,
    strictness: Strictness,
) -> Result<Option<f64>, ReadErrorKind> {
    match fields.get(index).is_none_or(|f| f.is_empty()) {
        true => Ok(None),
        false => number(fields, index, column, strictness).map(Some),
    }
}

/// A knot is 1852 m per hour (international nautical mile).
fn knots_to_m_s(knots: f64) -> f64 {
    knots * 1852.0 / 3600.0
}

/// `hhmmss[.ss]` as nanoseconds into the UTC day.
fn time_of_day(field: &[u8]) -> Result<i64, ReadErrorKind> {
    let bad = || ReadErrorKind::BadField {
        index: 2,
        column: "UTC time",
        expected: "hhmmss.ss",
        found: shown(field),
    };
    let digits = |range: std::ops::Range<usize>| -> Option<i64> {
        let text = field.get(range)?;
        text.iter()
            .all(u8::is_ascii_digit)
            .then(|| text.iter().fold(0, |n, &d| n * 10 + i64::from(d - b'0')))
    };
    let (Some(hours @ 0..=23), Some(minutes @ 0..=59)) = (digits(0..2), digits(2..4)) else {
        return Err(bad());
    };
    let second = field
        .get(4..)
        .filter(|rest| rest.first().is_some_and(u8::is_ascii_digit))
        .and_then(|rest| seconds(&[rest], 0, "seconds").ok())
        .filter(|s| (0..61 * NANOS_PER_SECOND).contains(&s.as_nanos()))
        .ok_or_else(bad)?;
    Ok((hours * 3600 + minutes * 60) * NANOS_PER_SECOND + second.as_nanos())
}

/// RMC `ddmmyy` as days since 1970 (years 80–99 are 19xx, 00–79 are 20xx).
fn rmc_date(field: &[u8]) -> Result<i64, ReadErrorKind> {
    let two = |at: usize| -> Option<u32> {
        let text = field.get(at..at + 2)?;
        text.iter()
            .all(u8::is_ascii_digit)
            .then(|| u32::from(text[0] - b'0') * 10 + u32::from(text[1] - b'0'))
    };
    match (field.len(), two(0), two(2), two(4)) {
        (6, Some(day @ 1..=31), Some(month @ 1..=12), Some(year))
            if day <= days_in_month(nmea_year(year), month) =>
        {
            Ok(gpst::days_from_civil(nmea_year(year), month, day))
        }
        _ => Err(ReadErrorKind::BadField {
            index: 10,
            column: "RMC date",
            expected: "ddmmyy",
            found: shown(field),
        }),
    }
}

/// The year of an RMC `yy`: 80–99 are 19xx, 00–79 are 20xx.
fn nmea_year(yy: u32) -> i64 {
    i64::from(yy) + if yy >= 80 { 1900 } else { 2000 }
}

/// Days in `month` (1–12) of `year` in the Gregorian calendar.
fn days_in_month(year: i64, month: u32) -> u32 {
    let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    match month {
        2 if leap => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

/// Latitude and longitude (rad) from `ddmm.mmm,N,dddmm.mmm,E` starting at field `first`.
fn latitude_longitude(
    fields: &[&[u8]],
    first: usize,
    strictness: Strictness,
) -> Result<[f64; 2], ReadErrorKind> {
    let latitude = degrees_minutes(fields, first, ("latitude (ddmm.mmm)", 90.0), strictness)?;
    let longitude = degrees_minutes(
        fields,
        first + 2,
        ("longitude (dddmm.mmm)", 180.0),
        strictness,
    )?;
    let sign = |index: usize, positive: &[u8], negative: &[u8]| match fields.get(index) {
        Some(h) if *h == positive => Ok(1.0),
        Some(h) if *h == negative => Ok(-1.0),
        found => Err(ReadErrorKind::BadField {
            index: index + 1,
            column: "hemisphere",
            expected: "N or S after a latitude, E or W after a longitude",
            found: shown(found.copied().unwrap_or_default()),
        }),
    };
    Ok([
        deg_to_rad(sign(first + 1, b"N", b"S")? * latitude),
        deg_to_rad(sign(first + 3, b"E", b"W")? * longitude),
    ])
}

/// `dddmm.mmm` as degrees: the digits before the last two of the integer part are degrees,
/// the rest minutes (split as text, so `4807.038` is 48° + 7.038′ without cancellation).
/// Minutes must be below 60 and the angle at most `max_degrees` (90 for a latitude, 180 for a
/// longitude).
fn degrees_minutes(
    fields: &[&[u8]],
    index: usize,
    (column, max_degrees): (&'static str, f64),
    strictness: Strictness,
) -> Result<f64, ReadErrorKind> {
    let field = fields.get(index).copied().unwrap_or_default();
    let integer_digits = field.iter().position(|&b| b == b'.').unwrap_or(field.len());
    if integer_digits < 3 || !field[..integer_digits].iter().all(u8::is_ascii_digit) {
        return Err(ReadErrorKind::BadField {
            index: index + 1,
            column,
            expected: "degrees and minutes (ddmm.mmm)",
            found: shown(field),
        });
    }
    let (degrees, minutes) = field.split_at(integer_digits - 2);
    let degrees = number(&[degrees], 0, column, strictness)?;
    let minutes = number(&[minutes], 0, column, strictness)?;
    let angle = degrees + minutes / 60.0;
    if !(minutes < 60.0 && angle <= max_degrees) {
        return Err(ReadErrorKind::BadField {
            index: index + 1,
            column,
            expected: if max_degrees > 90.0 {
                "at most 180° with minutes below 60"
            } else {
                "at most 90° with minutes below 60"
            },
            found: shown(field),
        });
    }
    Ok(angle)
}

/// The fixes of the epochs with a GGA position, dated and put on the GPST scale.
fn fixes_of(epochs: &[Epoch], settings: &NmeaSettings) -> Result<Vec<GnssFix>, ReadErrorKind> {
    let days = epoch_days(epochs, settings.date)?;
    let fixes: Vec<GnssFix> = epochs
        .iter()
        .zip(days)
        .filter_map(|(epoch, day)| {
            let [latitude, longitude, height] = epoch.position?;
            let utc = gpst::from_day_and_nanos(day, epoch.time_of_day)?;
            let time = utc + settings.gpst_minus_utc;
            let velocity = epoch
                .course_speed
                .filter(|_| settings.level_velocity)
                .map(|(course, speed)| [speed * course.cos(), speed * course.sin(), 0.0]);
            let heading =
                epoch
                    .heading
                    .zip(settings.heading_sd_rad)
                    .map(|(heading_rad, sd_rad)| HeadingObservation {
                        heading_rad,
                        sd_rad,
                    });
            Some(GnssFix {
                time,
                latitude_rad: latitude,
                longitude_rad: longitude,
                height_m: height,
                position_sd_ned_m: None,
                velocity_ned_m_s: velocity,
                heading,
            })
        })
        .collect();
    match fixes.is_empty() {
        true => Err(ReadErrorKind::Unusable(
            "no GGA sentence with a valid fix (quality above 0): nothing to convert".into(),
        )),
        false => Ok(fixes),
    }
}

/// The day (since 1970) of every epoch: RMC dates carried forward (with a day added when the
/// time of day decreases) and backward to the epochs before the first RMC.
fn epoch_days(
    epochs: &[Epoch],
    fallback: Option<(i32, u32, u32)>,
) -> Result<Vec<i64>, ReadErrorKind> {
    let first_dated = epochs.iter().position(|e| e.date.is_some());
    let (anchor_index, anchor_day) = match (first_dated, fallback) {
        (Some(index), _) => (index, epochs[index].date.unwrap_or_default()),
        (None, Some((year, month, day))) => (0, gpst::days_from_civil(i64::from(year), month, day)),
        (None, None) => {
            return Err(ReadErrorKind::Unusable(
                "no RMC sentence gives the date: give the UTC date of the first epoch".into(),
            ));
        }
    };
    let mut days = vec![anchor_day; epochs.len()];
    for index in (0..anchor_index).rev() {
        let rolled = epochs[index].time_of_day > epochs[index + 1].time_of_day;
        days[index] = days[index + 1] - i64::from(rolled);
    }
    for index in anchor_index + 1..epochs.len() {
        let rolled = epochs[index].time_of_day < epochs[index - 1].time_of_day;
        days[index] = epochs[index]
            .date
            .unwrap_or(days[index - 1] + i64::from(rolled));
    }
    Ok(days)
}
