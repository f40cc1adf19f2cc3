//! The text formats of KF-GINS (GitHub `i2Nav-WHU/KF-GINS`, README §2.2 "Data format", the
//! same as `awesome-gins-datasets`): numbers separated by blanks, no header.
//!
//! | file | columns |
//! |---|---|
//! | IMU | GNSS seconds of week (s); X-Y-Z angle increments (rad); X-Y-Z velocity increments (m/s) (further columns, e.g. odometer, are ignored: KF-GINS reads the first 7) |
//! | GNSS | seconds of week (s); latitude, longitude (deg); ellipsoidal height (m); position STD north-east-down (m) |
//! | GNSS with velocity (13 columns) | seconds of week; lat, lon, h; vn, ve, vd (m/s); position STD n-e-d (m); velocity STD n-e-d (m/s) |
//! | navigation result / ground truth (`.nav`) | GNSS week; seconds of week (s); lat, lon (deg); h (m); vn, ve, vd (m/s); roll, pitch, yaw (deg) |
//!
//! The README defines the 7-column GNSS file only. The 13-column layout is the one KF-GINS's
//! `gnssfileloader.h` reads ("13-column GNSS files contain GNSS velocity": the STD is taken
//! from columns 8–10); the velocity in columns 5–7 is taken as north-east-down like every
//! other vector of these files, and the velocity STD (columns 11–13) is not kept.
//!
//! The IMU frame is forward-right-down (README §2.1); the increments are kept as they are
//! ([`SampleKind::Increments`]). Times: IMU and GNSS files carry seconds of week only, so
//! without a week they stay seconds of week; with `gps_week` they are put on the GPST scale of
//! [`crate::gpst`]. The `.nav` file carries its own week: a week of 0 (as some datasets
//! write) leaves seconds of week, any other week gives the GPST scale.

use crate::Strictness;
use crate::error::{ReadError, ReadErrorKind};
use crate::fixed::{numbers, read_records, seconds, split_blanks, whole_number};
use crate::gpst;
use std::io::BufRead;
use std::path::Path;
use thermonav::gnss::GnssFix;
use thermonav::imu::{ImuSample, ImuSeries, SampleKind};
use thermonav::time::Timestamp;
use thermonav::trajectory::TrajectoryPoint;
use thermonav::units::deg_to_rad;

const IMU_LAYOUT: &str = "time dthx dthy dthz dvx dvy dvz";
const GNSS_LAYOUT: &str = "time lat lon h sdn sde sdd, or 13 with vn ve vd after h";
const NAV_LAYOUT: &str = "week time lat lon h vn ve vd roll pitch yaw";

/// Reads a KF-GINS IMU file (increments, FRD) from `reader`, named `input` in errors.
///
/// # Errors
/// [`ReadErrorKind::NoData`], fewer than 7 fields, a field that is not a number, NaN (strict)
/// or times that do not increase (strict), each with its line.
pub fn read_kf_gins_imu(
    reader: impl BufRead,
    input: impl Into<String>,
    gps_week: Option<u32>,
    strictness: Strictness,
) -> Result<ImuSeries, ReadError> {
    let samples = read_records(reader, input.into(), strictness, IMU_LAYOUT, |line| {
        let fields = split_blanks(line);
        if fields.len() < 7 {
            return Err(too_few_fields(fields.len(), 7, IMU_LAYOUT));
        }
        let time = week_time(seconds(&fields, 0, "time")?, gps_week)?;
        let [gx, gy, gz, ax, ay, az] = numbers(
            &fields,
            1,
            ["dthx", "dthy", "dthz", "dvx", "dvy", "dvz"],
            strictness,
        )?;
        let sample = ImuSample {
            time,
            gyro: [gx, gy, gz],
            accel: [ax, ay, az],
            temperature_c: None,
        };
        Ok(Some((time, sample)))
    })?;
    let mut series = ImuSeries::new(SampleKind::Increments);
    for sample in &samples {
        series.push(sample);
    }
    Ok(series)
}

/// Reads a KF-GINS GNSS file (7 columns, or 13 with velocity).
///
/// # Errors
/// As [`read_kf_gins_imu`], plus a line whose field count is neither 7 nor 13, or differs from
/// the first line's, and (strict) a latitude beyond ±90° or a negative STD.
pub fn read_kf_gins_gnss(
    reader: impl BufRead,
    input: impl Into<String>,
    gps_week: Option<u32>,
    strictness: Strictness,
) -> Result<Vec<GnssFix>, ReadError> {
    let mut width = None;
    read_records(reader, input.into(), strictness, GNSS_LAYOUT, |line| {
        let fields = split_blanks(line);
        let expected = *width.get_or_insert(fields.len());
        if fields.len() != expected || !(expected == 7 || expected == 13) {
            return Err(ReadErrorKind::FieldCount {
                expected: if expected == 13 { 13 } else { 7 },
                header: GNSS_LAYOUT.to_owned(),
                found: fields.len(),
            });
        }
        let time = week_time(seconds(&fields, 0, "time")?, gps_week)?;
        let [lat, lon, h] = numbers(&fields, 1, ["lat", "lon", "h"], strictness)?;
        let (velocity, sd_first) = match expected {
            13 => (
                Some(numbers(&fields, 4, ["vn", "ve", "vd"], strictness)?),
                7,
            ),
            _ => (None, 4),
        };
        let sd = numbers(&fields, sd_first, ["sdn", "sde", "sdd"], strictness)?;
        let fix = GnssFix {
            time,
            latitude_rad: deg_to_rad(lat),
            longitude_rad: deg_to_rad(lon),
            height_m: h,
            position_sd_ned_m: Some(sd),
            velocity_ned_m_s: velocity,
            heading: None,
        };
        if strictness == Strictness::Strict {
            crate::gnss::check_ranges(&fix)?;
        }
        Ok(Some((time, fix)))
    })
}

/// Reads a KF-GINS navigation result or ground-truth file (`.nav`, 11 columns).
///
/// # Errors
/// As [`read_kf_gins_imu`], with exactly 11 fields per line and (strict) latitudes within ±90°.
pub fn read_kf_gins_nav(
    reader: impl BufRead,
    input: impl Into<String>,
    strictness: Strictness,
) -> Result<Vec<TrajectoryPoint>, ReadError> {
    read_records(reader, input.into(), strictness, NAV_LAYOUT, |line| {
        let fields = split_blanks(line);
        crate::fixed::expect_fields(&fields, 11, NAV_LAYOUT)?;
        let week = whole_number(
            &fields,
            0,
            "week",
            u32::MAX.into(),
            "a whole GPS week number",
        )?;
        let week = week as u32;
        let time = week_time(seconds(&fields, 1, "time")?, (week != 0).then_some(week))?;
        let [lat, lon, h, vn, ve, vd, roll, pitch, yaw] = numbers(
            &fields,
            2,
            ["lat", "lon", "h", "vn", "ve", "vd", "roll", "pitch", "yaw"],
            strictness,
        )?;
        let point = TrajectoryPoint {
            time,
            latitude_rad: deg_to_rad(lat),
            longitude_rad: deg_to_rad(lon),
            height_m: h,
            velocity_ned_m_s: [vn, ve, vd],
            roll_rad: deg_to_rad(roll),
            pitch_rad: deg_to_rad(pitch),
            yaw_rad: deg_to_rad(yaw),
        };
        if strictness == Strictness::Strict {
            crate::check_latitude(point.latitude_rad)?;
        }
        Ok(Some((time, point)))
    })
}

/// Reads a KF-GINS IMU file from `path`.
///
/// # Errors
/// As [`read_kf_gins_imu`], plus [`ReadErrorKind::Open`].
pub fn read_kf_gins_imu_file(
    path: impl AsRef<Path>,
    gps_week: Option<u32>,
    strictness: Strictness,
) -> Result<ImuSeries, ReadError> {
    let (file, input) = crate::open_file(path.as_ref())?;
    read_kf_gins_imu(file, input, gps_week, strictness)
}

/// Reads a KF-GINS GNSS file from `path`.
///
/// # Errors
/// As [`read_kf_gins_gnss`], plus [`ReadErrorKind::Open`].
pub fn read_kf_gins_gnss_file(
    path: impl AsRef<Path>,
    gps_week: Option<u32>,
    strictness: Strictness,
) -> Result<Vec<GnssFix>, ReadError> {
    let (file, input) = crate::open_file(path.as_ref())?;
    read_kf_gins_gnss(file, input, gps_week, strictness)
}

/// Reads a KF-GINS `.nav` file from `path`.
///
/// # Errors
/// As [`read_kf_gins_nav`], plus [`ReadErrorKind::Open`].
pub fn read_kf_gins_nav_file(
    path: impl AsRef<Path>,
    strictness: Strictness,
) -> Result<Vec<TrajectoryPoint>, ReadError> {
    let (file, input) = crate::open_file(path.as_ref())?;
    read_kf_gins_nav(file, input, strictness)
}

fn too_few_fields(found: usize, expected: usize, layout: &'static str) -> ReadErrorKind {
    ReadErrorKind::FieldCount {
        expected,
        header: format!("{layout}, at least"),
        found,
    }
}

/// Seconds of week as they are, or on the GPST scale when the week is known.
fn week_time(
    seconds_of_week: Timestamp,
    gps_week: Option<u32>,
) -> Result<Timestamp, ReadErrorKind> {
    match gps_week {
        None => Ok(seconds_of_week),
        Some(week) => gpst::from_week_and_nanos(i64::from(week), seconds_of_week.as_nanos()).ok_or(
            ReadErrorKind::OutOfRange {
                column: "week",
                found: f64::from(week),
                expected: "a GPS week within the time range",
            },
        ),
    }
}
