//! GPS time (GPST) as a [`Timestamp`]: nanoseconds since 1970-01-01 00:00:00 counted in GPST.
//!
//! Every reader of a foreign format that knows the absolute time puts it on this one scale:
//! the calendar date and time of GPST are counted as if they were Unix time (86 400 s per day,
//! no leap seconds). It is the convention of RTKLIB's time-tag files (`.tag`), so IMU samples
//! timed by a tag file and RTKLIB solutions share a scale without conversion, and it is
//! [`GPS_EPOCH_UNIX_S`] + week · 604 800 + seconds of week for GPS week/second-of-week times.
//! It is *not* Unix (UTC) time: GPST ran ahead of UTC by 18 s from 2017-01-01 onwards.

use thermonav::time::{NANOS_PER_SECOND, Timestamp};

/// 1980-01-06 00:00:00 (the GPS epoch) on this scale, s: 3 657 days after 1970-01-01.
pub const GPS_EPOCH_UNIX_S: i64 = 315_964_800;

/// Seconds in one GPS week.
pub const SECONDS_PER_WEEK: i64 = 604_800;

const SECONDS_PER_DAY: i64 = 86_400;

/// GPST minus UTC from 2017-01-01 until the next leap second (none announced as of 2025), s.
pub const GPST_MINUS_UTC_S: i64 = 18;

/// Days from 1970-01-01 to the proleptic Gregorian date `year-month-day` (month 1–12), by
/// Howard Hinnant's `days_from_civil` algorithm.
pub fn days_from_civil(year: i64, month: u32, day: u32) -> i64 {
    let year = if month <= 2 { year - 1 } else { year };
    let era = year.div_euclid(400);
    let year_of_era = year - era * 400;
    let month = i64::from(month);
    let shifted_month = if month > 2 { month - 3 } else { month + 9 };
    let day_of_year = (153 * shifted_month + 2) / 5 + i64::from(day) - 1;
    let day_of_era = year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
    era * 146_097 + day_of_era - 719_468
}

/// The timestamp of a calendar day (days since 1970-01-01) plus nanoseconds into it.
pub fn from_day_and_nanos(days: i64, nanos_of_day: i64) -> Option<Timestamp> {
    let nanos = days
        .checked_mul(SECONDS_PER_DAY * NANOS_PER_SECOND)?
        .checked_add(nanos_of_day)?;
    Some(Timestamp::from_nanos(nanos))
}

/// The timestamp of GPS `week` plus `seconds_of_week` (as exact nanoseconds).
pub fn from_week_and_nanos(week: i64, nanos_of_week: i64) -> Option<Timestamp> {
    let seconds = week
        .checked_mul(SECONDS_PER_WEEK)?
        .checked_add(GPS_EPOCH_UNIX_S)?;
    let nanos = seconds
        .checked_mul(NANOS_PER_SECOND)?
        .checked_add(nanos_of_week)?;
    Some(Timestamp::from_nanos(nanos))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn civil_days_match_published_unix_dates() {
        // Unix time of 2000-01-01 00:00:00 UTC is 946 684 800 s (POSIX, 10 957 days).
        assert_eq!(days_from_civil(2000, 1, 1), 10_957);
        assert_eq!(days_from_civil(1970, 1, 1), 0);
        // The GPS epoch 1980-01-06 is 315 964 800 s after the Unix epoch (IS-GPS-200 epoch,
        // as used by every GPS-to-Unix converter).
        assert_eq!(days_from_civil(1980, 1, 6) * 86_400, GPS_EPOCH_UNIX_S);
        // A leap day: 2024-03-01 is one day after 2024-02-29.
        assert_eq!(
            days_from_civil(2024, 3, 1) - days_from_civil(2024, 2, 28),
            2
        );
    }

    #[test]
    fn week_and_seconds_land_on_the_calendar() {
        // GPS week 2000 began on 2018-05-06 (GPS week 2000 rollover notices).
        let start = from_week_and_nanos(2000, 0).unwrap();
        assert_eq!(
            start.as_nanos(),
            days_from_civil(2018, 5, 6) * 86_400 * NANOS_PER_SECOND
        );
    }
}
