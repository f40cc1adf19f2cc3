//! Writers of the KF-GINS text formats (the columns are those of [`crate::kf_gins`], from
//! KF-GINS's README §2.2): blank-separated numbers, no header, every number printed so that it
//! reads back to the same bits, written atomically.
//!
//! - IMU: seconds of week, then the X-Y-Z angle increments (rad) and velocity increments
//!   (m/s) in FRD. A series of increments is written as it is; a series of rates is turned
//!   into increments over each sample's interval (the rate held over the interval that ends at
//!   the sample, as our filters take it), so its first sample, which has no interval, is left
//!   out.
//! - GNSS: the 7-column file the README defines: seconds of week, latitude, longitude (deg),
//!   ellipsoidal height (m), position STD north-east-down (m). Every fix must carry a position
//!   STD (KF-GINS weights its updates by it); velocities and headings are not written (the
//!   13-column layout also needs velocity STDs, which our fixes do not carry).
//! - Navigation result (`.nav`): GNSS week, seconds of week, lat, lon (deg), h (m), vn, ve, vd
//!   (m/s), roll, pitch, yaw (deg), yaw in [0°, 360°) as KF-GINS's result files give it.
//!
//! Times: a time on the GPST scale of [`crate::gpst`] (at or after the GPS epoch) is split into
//! its GPS week and seconds of week; the whole file must lie in one week (the IMU and GNSS
//! files carry no week), and the week is returned so it can be given back to the readers
//! (`gps_week`). A time before the GPS epoch is taken as seconds of week already and must lie
//! in [0, 604 800) s; the `.nav` week is then written as 0, which its reader reads back as
//! seconds of week.

use crate::atomic::write_atomically;
use crate::error::WriteError;
use crate::finite::write_finite;
use crate::gpst::{GPS_EPOCH_UNIX_S, SECONDS_PER_WEEK};
use crate::text::{SecondsText, degrees_reading_back_exactly};
use std::io::Write;
use std::path::Path;
use thermonav::gnss::GnssFix;
use thermonav::imu::{ImuSeries, SampleKind};
use thermonav::nav::engine::increments_from_series;
use thermonav::time::{NANOS_PER_SECOND, Timestamp};
use thermonav::trajectory::TrajectoryPoint;

/// How a file's times become seconds of week.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WeekTime {
    /// GPST times of this GPS week.
    Week(u32),
    /// Times that are seconds of week already (before the GPS epoch on our scale).
    SecondsOfWeek,
}

impl WeekTime {
    /// The week, when the times were GPST.
    pub fn week(self) -> Option<u32> {
        match self {
            WeekTime::Week(week) => Some(week),
            WeekTime::SecondsOfWeek => None,
        }
    }
}

const NANOS_PER_WEEK: i64 = SECONDS_PER_WEEK * NANOS_PER_SECOND;
const GPS_EPOCH_NANOS: i64 = GPS_EPOCH_UNIX_S * NANOS_PER_SECOND;

/// The week of `times` (told by the first), each checked to fall in it.
///
/// # Errors
/// [`WriteError::Empty`] for no time, [`WriteError::WeekTime`] for a time in another week (or
/// outside [0, 604 800) s when the times are seconds of week).
pub fn week_of(mut times: impl Iterator<Item = Timestamp>) -> Result<WeekTime, WriteError> {
    let first = times.next().ok_or(WriteError::Empty { what: "records" })?;
    let mode = match first.as_nanos() >= GPS_EPOCH_NANOS {
        true => {
            let week = (first.as_nanos() - GPS_EPOCH_NANOS) / NANOS_PER_WEEK;
            WeekTime::Week(u32::try_from(week).map_err(|_| week_error(0, first, "a GPS week"))?)
        }
        false => WeekTime::SecondsOfWeek,
    };
    check_week(mode, 0, first)?;
    for (k, t) in times.enumerate() {
        check_week(mode, k + 1, t)?;
    }
    Ok(mode)
}

fn check_week(mode: WeekTime, index: usize, t: Timestamp) -> Result<(), WriteError> {
    let nanos = seconds_of_week_nanos(mode, t);
    match (0..NANOS_PER_WEEK).contains(&nanos) {
        true => Ok(()),
        false => Err(week_error(
            index,
            t,
            match mode {
                WeekTime::Week(_) => {
                    "the first record's GPS week (KF-GINS's IMU and GNSS files carry seconds of week only: split the file at the week boundary)"
                }
                WeekTime::SecondsOfWeek => {
                    "seconds of week, 0 to 604800 s (or a GPST time on the scale of thermonav_io::gpst)"
                }
            },
        )),
    }
}

fn week_error(index: usize, t: Timestamp, expected: &'static str) -> WriteError {
    WriteError::WeekTime {
        index,
        time_s: t.as_seconds(),
        expected,
    }
}

/// Nanoseconds of week of `t`.
fn seconds_of_week_nanos(mode: WeekTime, t: Timestamp) -> i64 {
    match mode {
        WeekTime::Week(week) => t.as_nanos() - GPS_EPOCH_NANOS - i64::from(week) * NANOS_PER_WEEK,
        WeekTime::SecondsOfWeek => t.as_nanos(),
    }
}

/// Writes `t`'s seconds of week with nine decimals.
fn write_seconds_of_week(
    out: &mut impl Write,
    mode: WeekTime,
    t: Timestamp,
) -> std::io::Result<()> {
    let sow = Timestamp::from_nanos(seconds_of_week_nanos(mode, t));
    write!(out, "{}", SecondsText(sow))
}

/// Writes each value after a blank, then the line's end.
fn write_values(out: &mut impl Write, values: &[f64]) -> std::io::Result<()> {
    for &value in values {
        out.write_all(b" ")?;
        write_finite(out, value)?;
    }
    out.write_all(b"\n")
}

/// Writes a KF-GINS IMU file (increments) of `series`; returns how its times were written.
///
/// # Errors
/// [`WriteError::Empty`] (no increment), [`WriteError::UnknownKind`], [`WriteError::WeekTime`],
/// [`WriteError::Io`] (a NaN is refused there).
pub fn write_kf_gins_imu(mut out: impl Write, series: &ImuSeries) -> Result<WeekTime, WriteError> {
    let rows = imu_rows(series)?;
    let mode = week_of(rows.iter().map(|r| r.0))?;
    for (time, values) in &rows {
        write_seconds_of_week(&mut out, mode, *time)?;
        write_values(&mut out, values)?;
    }
    out.flush()?;
    Ok(mode)
}

/// The (time, increments) rows of a series: as they are, or from rates over each interval.
fn imu_rows(series: &ImuSeries) -> Result<Vec<(Timestamp, [f64; 6])>, WriteError> {
    match series.kind.ok_or(WriteError::UnknownKind)? {
        SampleKind::Increments => Ok((0..series.len())
            .map(|k| {
                (
                    series.time[k],
                    std::array::from_fn(|c| series.channels[c][k]),
                )
            })
            .collect()),
        SampleKind::Rates => Ok(increments_from_series(series)
            .iter()
            .map(|i| {
                let (a, v) = (i.delta_angle.to_array(), i.delta_velocity.to_array());
                (i.time, [a[0], a[1], a[2], v[0], v[1], v[2]])
            })
            .collect()),
    }
}

/// Writes a 7-column KF-GINS GNSS file of `fixes`; returns how its times were written.
///
/// # Errors
/// [`WriteError::Empty`], [`WriteError::MissingPositionSd`], [`WriteError::WeekTime`],
/// [`WriteError::Io`].
pub fn write_kf_gins_gnss(mut out: impl Write, fixes: &[GnssFix]) -> Result<WeekTime, WriteError> {
    let mode = week_of(fixes.iter().map(|f| f.time))?;
    if let Some(index) = fixes.iter().position(|f| f.position_sd_ned_m.is_none()) {
        return Err(WriteError::MissingPositionSd { index });
    }
    for fix in fixes {
        let [sn, se, sd] = fix.position_sd_ned_m.unwrap_or_default();
        write_seconds_of_week(&mut out, mode, fix.time)?;
        let lat = degrees_reading_back_exactly(fix.latitude_rad);
        let lon = degrees_reading_back_exactly(fix.longitude_rad);
        write_values(&mut out, &[lat, lon, fix.height_m, sn, se, sd])?;
    }
    out.flush()?;
    Ok(mode)
}

/// Writes a KF-GINS navigation result (`.nav`) of `points`; returns how its times were written.
///
/// # Errors
/// [`WriteError::Empty`], [`WriteError::WeekTime`], [`WriteError::Io`].
pub fn write_kf_gins_nav(
    mut out: impl Write,
    points: &[TrajectoryPoint],
) -> Result<WeekTime, WriteError> {
    let mode = week_of(points.iter().map(|p| p.time))?;
    for p in points {
        write!(out, "{} ", mode.week().unwrap_or(0))?;
        write_seconds_of_week(&mut out, mode, p.time)?;
        let deg = degrees_reading_back_exactly;
        let yaw = deg(p.yaw_rad);
        let yaw = if yaw < 0.0 { yaw + 360.0 } else { yaw };
        let [vn, ve, vd] = p.velocity_ned_m_s;
        let values = [
            deg(p.latitude_rad),
            deg(p.longitude_rad),
            p.height_m,
            vn,
            ve,
            vd,
        ];
        write_values(
            &mut out,
            &[&values[..], &[deg(p.roll_rad), deg(p.pitch_rad), yaw]].concat(),
        )?;
    }
    out.flush()?;
    Ok(mode)
}

/// [`write_kf_gins_imu`] to `path`, atomically.
///
/// # Errors
/// As [`write_kf_gins_imu`], wrapped with the path, plus those of [`write_atomically`].
pub fn write_kf_gins_imu_file(
    path: impl AsRef<Path>,
    series: &ImuSeries,
) -> Result<WeekTime, WriteError> {
    let mut mode = WeekTime::SecondsOfWeek;
    write_atomically(path, |file| {
        mode = write_kf_gins_imu(file, series)?;
        Ok(())
    })?;
    Ok(mode)
}

/// [`write_kf_gins_gnss`] to `path`, atomically.
///
/// # Errors
/// As [`write_kf_gins_gnss`], wrapped with the path, plus those of [`write_atomically`].
pub fn write_kf_gins_gnss_file(
    path: impl AsRef<Path>,
    fixes: &[GnssFix],
) -> Result<WeekTime, WriteError> {
    let mut mode = WeekTime::SecondsOfWeek;
    write_atomically(path, |file| {
        mode = write_kf_gins_gnss(file, fixes)?;
        Ok(())
    })?;
    Ok(mode)
}

/// [`write_kf_gins_nav`] to `path`, atomically.
///
/// # Errors
/// As [`write_kf_gins_nav`], wrapped with the path, plus those of [`write_atomically`].
pub fn write_kf_gins_nav_file(
    path: impl AsRef<Path>,
    points: &[TrajectoryPoint],
) -> Result<WeekTime, WriteError> {
    let mut mode = WeekTime::SecondsOfWeek;
    write_atomically(path, |file| {
        mode = write_kf_gins_nav(file, points)?;
        Ok(())
    })?;
    Ok(mode)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Strictness;
    use crate::kf_gins::{read_kf_gins_gnss, read_kf_gins_imu, read_kf_gins_nav};
    use thermonav::imu::ImuSample;

    /// GPS week 2300 plus `sow_nanos`, on the GPST scale.
    fn gpst(sow_nanos: i64) -> Timestamp {
        crate::gpst::from_week_and_nanos(2300, sow_nanos).unwrap()
    }

    fn increments(times: &[Timestamp]) -> ImuSeries {
        let mut series = ImuSeries::new(SampleKind::Increments);
        for (k, &time) in times.iter().enumerate() {
            let x = k as f64;
            series.push(&ImuSample {
                time,
                gyro: [1e-4 + x, -2.5e-6, 3.0e-3],
                accel: [0.098, -0.0123, -0.0980665 - x],
                temperature_c: None,
            });
        }
        series
    }

    // The IMU line has the README's 7 columns: seconds of week, dθx dθy dθz (rad), dvx dvy dvz
    // (m/s); GPST times give their week, and the reader given that week gives back the same
    // series bit for bit.
    #[test]
    fn imu_increments_follow_the_readme_and_read_back() {
        let times = [gpst(357_906_005_000_000), gpst(357_906_010_000_000)];
        let series = increments(&times);
        let mut out = Vec::new();
        assert_eq!(
            write_kf_gins_imu(&mut out, &series).unwrap(),
            WeekTime::Week(2300)
        );
        let text = String::from_utf8(out.clone()).unwrap();
        let first = text.lines().next().unwrap();
        assert_eq!(
            first,
            "357906.005000000 0.0001 -2.5e-6 0.003 0.098 -0.0123 -0.0980665"
        );
        let back = read_kf_gins_imu(&out[..], "imu.txt", Some(2300), Strictness::Strict).unwrap();
        assert_eq!(back.time, series.time);
        assert_eq!(back.channels, series.channels);
        assert_eq!(back.kind, Some(SampleKind::Increments));
    }

    // Rates become increments over each interval (rate × dt, the first sample left out):
    // 0.5 rad/s held for 0.01 s is 0.005 rad.
    #[test]
    fn rates_become_increments_over_each_interval() {
        let mut series = ImuSeries::new(SampleKind::Rates);
        for k in 0..3 {
            series.push(&ImuSample {
                time: Timestamp::from_nanos(10_000_000 * k),
                gyro: [0.5, 0.0, 0.0],
                accel: [0.0, 0.0, -9.8],
                temperature_c: None,
            });
        }
        let mut out = Vec::new();
        assert_eq!(
            write_kf_gins_imu(&mut out, &series).unwrap(),
            WeekTime::SecondsOfWeek
        );
        let back = read_kf_gins_imu(&out[..], "imu.txt", None, Strictness::Strict).unwrap();
        assert_eq!(back.len(), 2);
        assert_eq!(back.time[0], Timestamp::from_nanos(10_000_000));
        assert!((back.channels[0][0] - 0.005).abs() < 1e-15);
        assert!((back.channels[5][1] - -0.098).abs() < 1e-15);
    }

    // A file that crosses a week boundary, a time before 0 s of week, a fix without STD: each
    // refused, naming the record.
    #[test]
    fn times_outside_one_week_and_fixes_without_std_are_refused() {
        let times = [gpst(604_799_000_000_000), gpst(604_800_000_000_000)];
        let error = write_kf_gins_imu(&mut Vec::new(), &increments(&times)).unwrap_err();
        assert!(error.to_string().contains("record 1 at"), "{error}");
        assert!(error.to_string().contains("GPS week"), "{error}");
        let negative = [Timestamp::from_nanos(-1)];
        let error = write_kf_gins_imu(&mut Vec::new(), &increments(&negative)).unwrap_err();
        assert!(error.to_string().contains("0 to 604800 s"), "{error}");
        let fix = GnssFix {
            time: gpst(1_000_000_000),
            latitude_rad: 0.5,
            longitude_rad: 2.0,
            height_m: 20.0,
            position_sd_ned_m: None,
            velocity_ned_m_s: None,
            heading: None,
        };
        let error = write_kf_gins_gnss(&mut Vec::new(), &[fix]).unwrap_err();
        assert!(
            matches!(error, WriteError::MissingPositionSd { index: 0 }),
            "{error}"
        );
    }

    // GNSS: seconds of week, lat, lon (deg), h (m), STD n e d (m), as the README's 7 columns;
    // read back to the same fix.
    #[test]
    fn gnss_fixes_follow_the_readme_and_read_back() {
        let fix = GnssFix {
            time: gpst(1_500_000_000),
            latitude_rad: 30.5_f64.to_radians(),
            longitude_rad: 114.25_f64.to_radians(),
            height_m: 20.125,
            position_sd_ned_m: Some([0.5, 0.25, 1.0]),
            velocity_ned_m_s: None,
            heading: None,
        };
        let mut out = Vec::new();
        write_kf_gins_gnss(&mut out, &[fix]).unwrap();
        let text = String::from_utf8(out.clone()).unwrap();
        let fields: Vec<&str> = text.trim_end().split(' ').collect();
        assert_eq!(fields.len(), 7, "{text}");
        assert_eq!(fields[0], "1.500000000");
        assert_eq!(fields[3..], ["20.125", "0.5", "0.25", "1"]);
        let back = read_kf_gins_gnss(&out[..], "gnss.txt", Some(2300), Strictness::Strict).unwrap();
        assert_eq!(back, vec![fix]);
    }

    // .nav: week, seconds of week, lat, lon, h, vn, ve, vd, roll, pitch, yaw (deg); a yaw of
    // −90° is written as 270° (KF-GINS's 0..360), and read back it is the same heading.
    #[test]
    fn nav_epochs_carry_their_week_and_a_yaw_in_0_360() {
        let point = TrajectoryPoint {
            time: gpst(2_250_000_000),
            latitude_rad: 30.5_f64.to_radians(),
            longitude_rad: 114.25_f64.to_radians(),
            height_m: 20.125,
            velocity_ned_m_s: [1.5, -0.25, 0.0],
            roll_rad: 1.0_f64.to_radians(),
            pitch_rad: -2.0_f64.to_radians(),
            yaw_rad: -90.0_f64.to_radians(),
        };
        let mut out = Vec::new();
        write_kf_gins_nav(&mut out, &[point]).unwrap();
        let text = String::from_utf8(out.clone()).unwrap();
        let fields: Vec<&str> = text.trim_end().split(' ').collect();
        assert_eq!(fields.len(), 11, "{text}");
        assert_eq!(fields[..2], ["2300", "2.250000000"]);
        assert_eq!(fields[4..8], ["20.125", "1.5", "-0.25", "0"]);
        let yaw: f64 = fields[10].parse().unwrap();
        assert!((yaw - 270.0).abs() < 1e-12, "{text}");
        let back = read_kf_gins_nav(&out[..], "x.nav", Strictness::Strict).unwrap();
        assert_eq!(back[0].time, point.time);
        assert_eq!(back[0].latitude_rad, point.latitude_rad);
        let d = thermonav::units::wrap_pi(back[0].yaw_rad - point.yaw_rad);
        assert!(d.abs() < 1e-12, "{d}");
    }
}
