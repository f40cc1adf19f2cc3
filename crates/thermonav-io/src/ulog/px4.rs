//! PX4 topics of a ULog file as thermonav series: the IMU, its temperature and GNSS fixes.
//!
//! - IMU: `sensor_combined` (instance 0): `gyro_rad[0..3]` (rad/s) and `accelerometer_m_s2[0..3]`
//!   (m/s²), the means over their integration intervals, as rates timed at `timestamp` (the
//!   gyro's time; the accelerometer's `accelerometer_timestamp_relative` offset is reported,
//!   not applied, and a sample whose offset is the "invalid" marker 2³¹−1 is left out). When
//!   there is no `sensor_combined`, `vehicle_imu` (instance 0): `delta_angle` (rad) and
//!   `delta_velocity` (m/s) as increments timed at `timestamp_sample` (else `timestamp`).
//!   Axes are PX4's body frame, forward-right-down, as thermonav expects.
//! - Temperature (`temp_c`): `sensor_accel` `temperature`, else `vehicle_imu_status`
//!   `temperature_accel`, else `sensor_gyro` `temperature` (instance 0, finite values only);
//!   each IMU sample takes the value of the **nearest** temperature record in time (ties to
//!   the earlier). No such topic: no `temp_c` column.
//! - GNSS: `vehicle_gps_position`, else `sensor_gps` (instance 0), fixes with `fix_type` ≥ 3
//!   (3D) only. Latitude/longitude from `lat`/`lon` (1e-7 deg) or `latitude_deg`/`longitude_deg`;
//!   height from `alt_ellipsoid` (mm) or `altitude_ellipsoid_m` when the log fills it (not all
//!   zero), else from the mean-sea-level `alt` (mm) / `altitude_msl_m`, and then the height is
//!   MSL, not ellipsoidal, which [`GnssExtract::height`] says; standard deviations north and
//!   east = `eph`, up = `epv` (PX4's EKF2 uses `eph` as the per-axis horizontal sd); velocity
//!   `vel_n_m_s`, `vel_e_m_s`, `vel_d_m_s` where `vel_ned_valid`.
//!
//! Time: ULog timestamps are µs since boot. When GNSS gives `time_utc_usec` (non-zero on a 3D
//! fix), boot time is put on the GPST scale of [`crate::gpst`]: offset = median over those
//! fixes of `time_utc_usec − timestamp`, plus GPST − UTC (the leap seconds, 18 s since 2017,
//! given by the caller since the log does not carry it). Otherwise times stay seconds since
//! boot, and [`TimeScale::Boot`] says so.

use super::format::FlatField;
use super::{Topic, Ulog};
use crate::error::{ReadError, ReadErrorKind};
use crate::gpst::GPST_MINUS_UTC_S;
use crate::sample_checks::{imu_sample_problem, inertial_values_problem, temperature_problem};
use serde::Serialize;
use thermonav::gnss::GnssFix;
use thermonav::imu::{ImuSample, ImuSeries, SampleKind};
use thermonav::time::{Duration, Timestamp};
use thermonav::units::deg_to_rad;

/// The time scale of the extracted series.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(tag = "scale", rename_all = "snake_case")]
pub enum TimeScale {
    /// GPST seconds since 1970 (no leap seconds), from GNSS UTC time.
    Gpst {
        /// GPST minus boot time, ns.
        boot_to_gpst_ns: i64,
        /// GPST minus UTC applied, s.
        gpst_minus_utc_s: i64,
    },
    /// Seconds since the autopilot booted (no GNSS UTC time in the log).
    Boot,
}

impl TimeScale {
    /// Boot time in µs on this scale.
    fn at(self, boot_us: u64) -> Option<Timestamp> {
        let boot_ns = i64::try_from(boot_us).ok()?.checked_mul(1_000)?;
        let shift = match self {
            TimeScale::Gpst {
                boot_to_gpst_ns, ..
            } => boot_to_gpst_ns,
            TimeScale::Boot => 0,
        };
        boot_ns.checked_add(shift).map(Timestamp::from_nanos)
    }
}

/// The GNSS topic of a log: `vehicle_gps_position` or `sensor_gps`, instance 0.
fn gnss_topic(log: &Ulog) -> Option<Topic<'_>> {
    log.topic("vehicle_gps_position", 0)
        .or_else(|| log.topic("sensor_gps", 0))
}

/// The time scale of `log`: GPST when GNSS gives UTC time, else boot time.
pub fn time_scale(log: &Ulog, gpst_minus_utc: Duration) -> TimeScale {
    let Some(topic) = gnss_topic(log) else {
        return TimeScale::Boot;
    };
    let (Some(utc), Some(stamp), Some(fix)) = (
        topic.field("time_utc_usec"),
        topic.field("timestamp"),
        topic.field("fix_type"),
    ) else {
        return TimeScale::Boot;
    };
    let mut offsets_us: Vec<i128> = (0..topic.len())
        .filter(|&i| topic.integer(fix, i).unwrap_or(0) >= 3)
        .filter_map(|i| {
            let utc = topic.integer(utc, i).filter(|&u| u > 0)?;
            Some(utc - topic.integer(stamp, i)?)
        })
        .collect();
    if offsets_us.is_empty() {
        return TimeScale::Boot;
    }
    offsets_us.sort_unstable();
    let median_us = offsets_us[offsets_us.len() / 2];
    let boot_to_utc_ns = i64::try_from(median_us * 1_000).ok();
    match boot_to_utc_ns.and_then(|ns| ns.checked_add(gpst_minus_utc.as_nanos())) {
        Some(boot_to_gpst_ns) => TimeScale::Gpst {
            boot_to_gpst_ns,
            gpst_minus_utc_s: gpst_minus_utc.as_nanos() / 1_000_000_000,
        },
        None => TimeScale::Boot,
    }
}

/// The default GPST − UTC: 18 s, in force since 2017-01-01.
pub fn default_gpst_minus_utc() -> Duration {
    Duration::from_nanos(GPST_MINUS_UTC_S * 1_000_000_000)
}

/// What [`imu_series`] took from the log.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ImuExtract {
    /// The series (rates from `sensor_combined`, increments from `vehicle_imu`).
    #[serde(skip)]
    pub series: ImuSeries,
    /// The topic read.
    pub topic: &'static str,
    /// The temperature topic and field, when there is one.
    pub temperature_source: Option<String>,
    /// How temperatures are assigned to samples.
    pub temperature_assignment: &'static str,
    /// Samples left out because the accelerometer's relative timestamp was marked invalid.
    pub invalid_accelerometer_samples: usize,
    /// Largest |accelerometer_timestamp_relative| of the kept samples, µs (not applied).
    pub max_accelerometer_offset_us: i64,
}

/// A problem with a topic of the log.
fn topic_error(input: &str, what: String) -> ReadError {
    ReadError::new(input, None, ReadErrorKind::Unusable(what))
}

/// The IMU of `log` on `scale`.
///
/// # Errors
/// [`ReadErrorKind::Unusable`] naming the topic: neither `sensor_combined` nor `vehicle_imu`,
/// a missing field, a non-finite value or a time that does not increase (with the record's
/// byte offset), or no sample at all.
pub fn imu_series(log: &Ulog, input: &str, scale: TimeScale) -> Result<ImuExtract, ReadError> {
    let mut extract = match (log.topic("sensor_combined", 0), log.topic("vehicle_imu", 0)) {
        (Some(topic), _) => rates_from_sensor_combined(topic, input, scale)?,
        (None, Some(topic)) => increments_from_vehicle_imu(topic, input, scale)?,
        (None, None) => {
            return Err(topic_error(
                input,
                "no IMU topic: expected sensor_combined or vehicle_imu (instance 0)".to_string(),
            ));
        }
    };
    if extract.series.is_empty() {
        return Err(topic_error(
            input,
            format!("topic {} has no usable sample", extract.topic),
        ));
    }
    if let Some((name, times, values)) = temperature_records(log, input, scale)? {
        let column = nearest_values(&extract.series.time, &times, &values);
        extract.series.temperature_c = Some(column);
        extract.temperature_source = Some(name);
    }
    Ok(extract)
}

/// Field `name` of `topic`, or an error naming both.
fn required<'a>(topic: Topic<'a>, name: &str, input: &str) -> Result<&'a FlatField, ReadError> {
    topic
        .field(name)
        .ok_or_else(|| topic_error(input, format!("topic {} has no field {name}", topic.name())))
}

/// Fields `base[0]`, `base[1]`, `base[2]` of `topic`.
fn vector_fields<'a>(
    topic: Topic<'a>,
    base: &str,
    input: &str,
) -> Result<[&'a FlatField; 3], ReadError> {
    Ok([
        required(topic, &format!("{base}[0]"), input)?,
        required(topic, &format!("{base}[1]"), input)?,
        required(topic, &format!("{base}[2]"), input)?,
    ])
}

/// Accumulates samples, checking finiteness and strictly increasing times.
struct SeriesBuilder<'a> {
    topic: Topic<'a>,
    input: &'a str,
    scale: TimeScale,
    series: ImuSeries,
}

impl SeriesBuilder<'_> {
    /// Adds record `index`: its time from `stamp` (µs since boot), its gyro and accelerometer
    /// vectors from the three fields of each.
    fn push_record(
        &mut self,
        index: usize,
        stamp: &FlatField,
        gyro: [&FlatField; 3],
        accel: [&FlatField; 3],
    ) -> Result<(), ReadError> {
        let topic = self.topic;
        let g = gyro.map(|f| topic.real(f, index));
        let a = accel.map(|f| topic.real(f, index));
        self.push(index, topic.integer(stamp, index), g, a)
    }

    /// The extract, with the accelerometer-offset figures of `sensor_combined`.
    fn finish(self, invalid_accelerometer_samples: usize, max_offset_us: i64) -> ImuExtract {
        let topic = match self.topic.name() {
            "vehicle_imu" => "vehicle_imu",
            _ => "sensor_combined",
        };
        ImuExtract {
            series: self.series,
            topic,
            temperature_source: None,
            temperature_assignment: NEAREST,
            invalid_accelerometer_samples,
            max_accelerometer_offset_us: max_offset_us,
        }
    }

    /// Adds record `index`, timed at `boot_us`.
    fn push(
        &mut self,
        index: usize,
        boot_us: Option<i128>,
        gyro: [f64; 3],
        accel: [f64; 3],
    ) -> Result<(), ReadError> {
        let at = self.topic.file_offset(index);
        let name = self.topic.name();
        let time = boot_us
            .and_then(|us| u64::try_from(us).ok())
            .and_then(|us| self.scale.at(us))
            .ok_or_else(|| {
                topic_error(
                    self.input,
                    format!("at byte {at}: {name} record {index} has no usable timestamp"),
                )
            })?;
        if let Some(problem) = imu_sample_problem(gyro, accel, None) {
            return Err(topic_error(
                self.input,
                format!("at byte {at}: {name} record {index}: {problem}"),
            ));
        }
        let previous = self.series.time.last().copied();
        if let Some(previous) = previous.filter(|&p| time <= p) {
            return Err(topic_error(
                self.input,
                format!(
                    "at byte {at}: {name} record {index} is timed {:.6} s, not after the \
                     previous record's {:.6} s",
                    time.as_seconds(),
                    previous.as_seconds()
                ),
            ));
        }
        self.series.push(&ImuSample {
            time,
            gyro,
            accel,
            temperature_c: None,
        });
        Ok(())
    }
}

/// The i32 marking an invalid relative timestamp in PX4 (`RELATIVE_TIMESTAMP_INVALID`).
const RELATIVE_TIMESTAMP_INVALID: i128 = i32::MAX as i128;

/// `sensor_combined` as rates.
fn rates_from_sensor_combined(
    topic: Topic<'_>,
    input: &str,
    scale: TimeScale,
) -> Result<ImuExtract, ReadError> {
    let stamp = required(topic, "timestamp", input)?;
    let gyro = vector_fields(topic, "gyro_rad", input)?;
    let accel = vector_fields(topic, "accelerometer_m_s2", input)?;
    let relative = topic.field("accelerometer_timestamp_relative");
    let mut builder = SeriesBuilder {
        topic,
        input,
        scale,
        series: ImuSeries::new(SampleKind::Rates),
    };
    let (mut invalid, mut max_offset) = (0, 0);
    for i in 0..topic.len() {
        let offset = relative.and_then(|f| topic.integer(f, i)).unwrap_or(0);
        if offset == RELATIVE_TIMESTAMP_INVALID {
            invalid += 1;
            continue;
        }
        max_offset = max_offset.max(offset.abs());
        builder.push_record(i, stamp, gyro, accel)?;
    }
    Ok(builder.finish(invalid, max_offset as i64))
}

/// How temperatures are assigned.
const NEAREST: &str = "nearest temperature record in time (ties to the earlier)";

/// `vehicle_imu` as increments.
fn increments_from_vehicle_imu(
    topic: Topic<'_>,
    input: &str,
    scale: TimeScale,
) -> Result<ImuExtract, ReadError> {
    let stamp = topic
        .first_field(&["timestamp_sample", "timestamp"])
        .ok_or_else(|| topic_error(input, "topic vehicle_imu has no timestamp".to_string()))?;
    let angle = vector_fields(topic, "delta_angle", input)?;
    let velocity = vector_fields(topic, "delta_velocity", input)?;
    let mut builder = SeriesBuilder {
        topic,
        input,
        scale,
        series: ImuSeries::new(SampleKind::Increments),
    };
    for i in 0..topic.len() {
        builder.push_record(i, stamp, angle, velocity)?;
    }
    Ok(builder.finish(0, 0))
}

/// Temperature records (name, times, °C) from the first topic that has them. A NaN
/// temperature is PX4's "not measured" and is left out; a finite one outside the sensor range
/// (kelvin, a corrupt value) is refused, naming the record.
fn temperature_records(
    log: &Ulog,
    input: &str,
    scale: TimeScale,
) -> Result<Option<TemperatureRecords>, ReadError> {
    let sources = [
        ("sensor_accel", "temperature"),
        ("vehicle_imu_status", "temperature_accel"),
        ("sensor_gyro", "temperature"),
    ];
    for &(topic_name, field_name) in &sources {
        let Some(topic) = log.topic(topic_name, 0) else {
            continue;
        };
        let (Some(field), Some(stamp)) = (topic.field(field_name), topic.field("timestamp")) else {
            continue;
        };
        let mut records = Vec::new();
        for i in 0..topic.len() {
            let value = topic.real(field, i);
            if let Some(problem) = value
                .is_finite()
                .then(|| temperature_problem(value))
                .flatten()
            {
                let at = topic.file_offset(i);
                return Err(topic_error(
                    input,
                    format!("at byte {at}: {topic_name} record {i}: {field_name}: {problem}"),
                ));
            }
            let boot_us = topic.integer(stamp, i).and_then(|v| u64::try_from(v).ok());
            if let Some(time) = boot_us
                .and_then(|us| scale.at(us))
                .filter(|_| value.is_finite())
            {
                records.push((time, value));
            }
        }
        // In time order for the nearest-record lookup (a log may hold them otherwise).
        records.sort_by_key(|&(time, _)| time);
        let (times, values): (Vec<_>, Vec<_>) = records.into_iter().unzip();
        if !times.is_empty() {
            return Ok(Some((format!("{topic_name}.{field_name}"), times, values)));
        }
    }
    Ok(None)
}

/// A temperature source's name (`sensor_accel.temperature`), its record times and values, °C.
type TemperatureRecords = (String, Vec<Timestamp>, Vec<f64>);

/// For each of `at` (increasing), the value of the nearest of `times` (increasing, not
/// empty); a tie goes to the earlier record.
pub fn nearest_values(at: &[Timestamp], times: &[Timestamp], values: &[f64]) -> Vec<f64> {
    let mut j = 0;
    at.iter()
        .map(|&t| {
            while j + 1 < times.len() && times[j + 1] <= t {
                j += 1;
            }
            let later_is_nearer = j + 1 < times.len() && times[j + 1] - t < t - times[j];
            values[if later_is_nearer { j + 1 } else { j }]
        })
        .collect()
}

/// What [`gnss_fixes`] took from the log.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GnssExtract {
    /// The 3D fixes.
    #[serde(skip)]
    pub fixes: Vec<GnssFix>,
    /// The topic read.
    pub topic: &'static str,
    /// The field the height came from and what it is.
    pub height: &'static str,
    /// Records left out because `fix_type` < 3.
    pub records_without_3d_fix: usize,
}

/// The GNSS fixes of `log` on `scale`.
///
/// # Errors
/// [`ReadErrorKind::Unusable`] naming the topic: neither `vehicle_gps_position` nor
/// `sensor_gps`, a missing field, no 3D fix, a non-finite position or a time that does not
/// increase (with the record's byte offset).
pub fn gnss_fixes(log: &Ulog, input: &str, scale: TimeScale) -> Result<GnssExtract, ReadError> {
    let topic = gnss_topic(log).ok_or_else(|| {
        topic_error(
            input,
            "no GNSS topic: expected vehicle_gps_position or sensor_gps (instance 0)".to_string(),
        )
    })?;
    let topic_name = match topic.name() {
        "sensor_gps" => "sensor_gps",
        _ => "vehicle_gps_position",
    };
    let fields = GnssFields::of(topic, input)?;
    let mut fixes: Vec<GnssFix> = Vec::new();
    let mut without_fix = 0;
    for i in 0..topic.len() {
        if topic.integer(fields.fix_type, i).unwrap_or(0) < 3 {
            without_fix += 1;
            continue;
        }
        let fix = fields.fix(topic, i, scale, input)?;
        if fixes
            .last()
            .is_some_and(|previous| fix.time <= previous.time)
        {
            return Err(topic_error(
                input,
                format!(
                    "at byte {}: {topic_name} record {i} is not after the previous fix",
                    topic.file_offset(i)
                ),
            ));
        }
        fixes.push(fix);
    }
    if fixes.is_empty() {
        return Err(topic_error(
            input,
            format!(
                "topic {topic_name} has no 3D fix (fix_type >= 3) in {} records",
                topic.len()
            ),
        ));
    }
    Ok(GnssExtract {
        fixes,
        topic: topic_name,
        height: fields.height_text,
        records_without_3d_fix: without_fix,
    })
}

/// The GNSS fields of a topic and how to scale them.
struct GnssFields<'a> {
    stamp: &'a FlatField,
    fix_type: &'a FlatField,
    latitude: (&'a FlatField, f64),
    longitude: (&'a FlatField, f64),
    height: (&'a FlatField, f64),
    height_text: &'static str,
    eph: Option<&'a FlatField>,
    epv: Option<&'a FlatField>,
    velocity: Option<[&'a FlatField; 3]>,
    velocity_valid: Option<&'a FlatField>,
}

impl<'a> GnssFields<'a> {
    /// Finds the fields (old integer or newer floating-point names).
    fn of(topic: Topic<'a>, input: &str) -> Result<Self, ReadError> {
        let pick = |names: [(&str, f64); 2], what: &str| {
            names
                .iter()
                .find_map(|&(n, scale)| topic.field(n).map(|f| (f, scale)))
                .ok_or_else(|| {
                    topic_error(
                        input,
                        format!(
                            "topic {} has no {what} field ({} or {})",
                            topic.name(),
                            names[0].0,
                            names[1].0
                        ),
                    )
                })
        };
        let latitude = pick([("lat", 1e-7), ("latitude_deg", 1.0)], "latitude")?;
        let longitude = pick([("lon", 1e-7), ("longitude_deg", 1.0)], "longitude")?;
        let msl = pick([("alt", 1e-3), ("altitude_msl_m", 1.0)], "altitude")?;
        let ellipsoid = [("alt_ellipsoid", 1e-3), ("altitude_ellipsoid_m", 1.0)]
            .iter()
            .find_map(|&(n, s)| topic.field(n).map(|f| (f, s)))
            .filter(|&(f, _)| (0..topic.len()).any(|i| topic.real(f, i) != 0.0));
        let (height, height_text) = match ellipsoid {
            Some(h) => (h, "ellipsoidal (alt_ellipsoid / altitude_ellipsoid_m)"),
            None => (
                msl,
                "mean sea level (alt / altitude_msl_m): the log gives no ellipsoidal height, \
                 so h_m is MSL, off the WGS84 ellipsoid by the geoid undulation",
            ),
        };
        let velocity = ["vel_n_m_s", "vel_e_m_s", "vel_d_m_s"].map(|n| topic.field(n));
        Ok(Self {
            stamp: required(topic, "timestamp", input)?,
            fix_type: required(topic, "fix_type", input)?,
            latitude,
            longitude,
            height,
            height_text,
            eph: topic.field("eph"),
            epv: topic.field("epv"),
            velocity: match velocity {
                [Some(n), Some(e), Some(d)] => Some([n, e, d]),
                _ => None,
            },
            velocity_valid: topic.field("vel_ned_valid"),
        })
    }

    /// Record `i` as a fix.
    fn fix(
        &self,
        topic: Topic<'_>,
        i: usize,
        scale: TimeScale,
        input: &str,
    ) -> Result<GnssFix, ReadError> {
        let at = topic.file_offset(i);
        let bad = |what: &str| {
            topic_error(
                input,
                format!("at byte {at}: {} record {i}: {what}", topic.name()),
            )
        };
        let time = topic
            .integer(self.stamp, i)
            .and_then(|us| u64::try_from(us).ok())
            .and_then(|us| scale.at(us))
            .ok_or_else(|| bad("no usable timestamp"))?;
        let value = |(field, unit): (&FlatField, f64)| topic.real(field, i) * unit;
        let (lat_deg, lon_deg, height_m) = (
            value(self.latitude),
            value(self.longitude),
            value(self.height),
        );
        if !(lat_deg.is_finite() && lon_deg.is_finite() && height_m.is_finite())
            || lat_deg.abs() > 90.0
            || lon_deg.abs() > 180.0
        {
            return Err(bad(&format!(
                "expected a finite position within ±90°/±180°, found {lat_deg}°, {lon_deg}°, \
                 {height_m} m"
            )));
        }
        let sd = match (self.eph, self.epv) {
            (Some(h), Some(v)) => {
                let (h, v) = (topic.real(h, i), topic.real(v, i));
                (h.is_finite() && v.is_finite() && h > 0.0 && v > 0.0).then_some([h, h, v])
            }
            _ => None,
        };
        let valid = self
            .velocity_valid
            .is_none_or(|f| topic.integer(f, i).unwrap_or(0) != 0);
        let velocity = self
            .velocity
            .filter(|_| valid)
            .map(|fields| fields.map(|f| topic.real(f, i)))
            .filter(|v| v.iter().all(|x| x.is_finite()));
        Ok(GnssFix {
            time,
            latitude_rad: deg_to_rad(lat_deg),
            longitude_rad: deg_to_rad(lon_deg),
            height_m,
            position_sd_ned_m: sd,
            velocity_ned_m_s: velocity,
            heading: None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Slow obviously-correct nearest: scan every record.
    fn nearest_by_scan(at: &[Timestamp], times: &[Timestamp], values: &[f64]) -> Vec<f64> {
        at.iter()
            .map(|t| {
                let mut best = 0;
                for (k, s) in times.iter().enumerate() {
                    let d = (*s - *t).as_nanos().abs();
                    if d < (times[best] - *t).as_nanos().abs() {
                        best = k;
                    }
                }
                values[best]
            })
            .collect()
    }

    #[test]
    fn nearest_values_match_a_full_scan_including_ties_and_ends() {
        let ts = |v: &[i64]| {
            v.iter()
                .map(|&n| Timestamp::from_nanos(n))
                .collect::<Vec<_>>()
        };
        let times = ts(&[10, 20, 40, 41, 100]);
        let values = [1.0, 2.0, 3.0, 4.0, 5.0];
        // Before the first, ties (15, 30), between, equal, after the last.
        let at = ts(&[0, 15, 19, 30, 31, 40, 41, 70, 71, 500]);
        let fast = nearest_values(&at, &times, &values);
        assert_eq!(fast, nearest_by_scan(&at, &times, &values));
        assert_eq!(fast, [1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 5.0, 5.0]);
    }
}

/// What [`raw_sensor_series`] took from the log: one instance of the raw `sensor_gyro` and
/// `sensor_accel` topics, the data before PX4's own thermal and other calibrations (the
/// topics PX4's thermal calibration fits, never the corrected `sensor_combined`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RawSensorExtract {
    /// Rates at the gyro's sample times, each with the nearest accelerometer sample, and the
    /// gyro's own temperature (°C) as `temp_c`.
    #[serde(skip)]
    pub series: ImuSeries,
    /// The topic instance (`multi_id`) read.
    pub instance: u8,
    /// The gyro's `device_id`, when the topic has the field and it is constant.
    pub gyro_device_id: Option<u32>,
    /// The accelerometer's `device_id`, likewise.
    pub accel_device_id: Option<u32>,
    /// Gyro records left out because their temperature was not finite.
    pub records_without_temperature: usize,
}

/// The raw gyro and accelerometer of `instance` on `scale`.
///
/// # Errors
/// [`ReadErrorKind::Unusable`] naming the topic: `sensor_gyro` or `sensor_accel` of that
/// instance missing, a missing field (`timestamp`, `x`, `y`, `z`, `temperature`), a non-finite
/// value or a time that does not increase (with the record's byte offset), or no sample.
pub fn raw_sensor_series(
    log: &Ulog,
    input: &str,
    scale: TimeScale,
    instance: u8,
) -> Result<RawSensorExtract, ReadError> {
    let topic_of = |name: &str| {
        log.topic(name, instance).ok_or_else(|| {
            topic_error(
                input,
                format!("no topic {name} of instance {instance} (a raw-sensor sweep needs sensor_gyro and sensor_accel)"),
            )
        })
    };
    let (gyro, accel) = (topic_of("sensor_gyro")?, topic_of("sensor_accel")?);
    let accel_samples = raw_vectors(accel, input, scale)?;
    let gyro_samples = raw_vectors(gyro, input, scale)?;
    let mut extract = RawSensorExtract {
        series: ImuSeries::new(SampleKind::Rates),
        instance,
        gyro_device_id: constant_device_id(gyro),
        accel_device_id: constant_device_id(accel),
        records_without_temperature: 0,
    };
    let accel_times: Vec<Timestamp> = accel_samples.iter().map(|s| s.time).collect();
    let nearest_accel = |axis: usize| {
        let values: Vec<f64> = accel_samples.iter().map(|s| s.vector[axis]).collect();
        let times: Vec<Timestamp> = gyro_samples.iter().map(|s| s.time).collect();
        nearest_values(&times, &accel_times, &values)
    };
    let accel_columns = [nearest_accel(0), nearest_accel(1), nearest_accel(2)];
    for (k, sample) in gyro_samples.iter().enumerate() {
        let Some(temperature_c) = sample.temperature_c.filter(|t| t.is_finite()) else {
            extract.records_without_temperature += 1;
            continue;
        };
        extract.series.push(&ImuSample {
            time: sample.time,
            gyro: sample.vector,
            accel: accel_columns.each_ref().map(|c| c[k]),
            temperature_c: Some(temperature_c),
        });
    }
    match extract.series.is_empty() {
        true => Err(topic_error(
            input,
            format!("sensor_gyro of instance {instance} has no sample with a finite temperature"),
        )),
        false => Ok(extract),
    }
}

/// One record of a raw sensor topic.
struct RawSample {
    time: Timestamp,
    vector: [f64; 3],
    temperature_c: Option<f64>,
}

/// The records of a raw sensor topic (`timestamp_sample` when logged, else `timestamp`),
/// checked for finite vectors and strictly increasing times.
fn raw_vectors(
    topic: Topic<'_>,
    input: &str,
    scale: TimeScale,
) -> Result<Vec<RawSample>, ReadError> {
    let name = topic.name();
    let stamp = topic
        .first_field(&["timestamp_sample", "timestamp"])
        .ok_or_else(|| topic_error(input, format!("topic {name} has no timestamp")))?;
    let axes = [
        required(topic, "x", input)?,
        required(topic, "y", input)?,
        required(topic, "z", input)?,
    ];
    let temperature = required(topic, "temperature", input)?;
    let mut samples: Vec<RawSample> = Vec::with_capacity(topic.len());
    for i in 0..topic.len() {
        let at = topic.file_offset(i);
        let time = topic
            .integer(stamp, i)
            .and_then(|us| u64::try_from(us).ok())
            .and_then(|us| scale.at(us))
            .ok_or_else(|| {
                topic_error(
                    input,
                    format!("at byte {at}: {name} record {i} has no usable timestamp"),
                )
            })?;
        let vector = axes.map(|f| topic.real(f, i));
        let temperature_c = topic.real(temperature, i);
        // A NaN temperature is "not measured" (the record is counted and left out later).
        let problem = inertial_values_problem(&["x", "y", "z"], &vector).or_else(|| {
            temperature_c
                .is_finite()
                .then(|| temperature_problem(temperature_c))
                .flatten()
        });
        if let Some(problem) = problem {
            return Err(topic_error(
                input,
                format!("at byte {at}: {name} record {i}: {problem}"),
            ));
        }
        if let Some(previous) = samples.last().map(|s| s.time).filter(|&p| time <= p) {
            return Err(topic_error(
                input,
                format!(
                    "at byte {at}: {name} record {i} is timed {:.6} s, not after the previous record's {:.6} s",
                    time.as_seconds(),
                    previous.as_seconds()
                ),
            ));
        }
        samples.push(RawSample {
            time,
            vector,
            temperature_c: Some(temperature_c),
        });
    }
    match samples.is_empty() {
        true => Err(topic_error(input, format!("topic {name} has no record"))),
        false => Ok(samples),
    }
}

/// The topic's `device_id` when it has the field and every record gives the same one.
fn constant_device_id(topic: Topic<'_>) -> Option<u32> {
    let field = topic.field("device_id")?;
    let mut ids = (0..topic.len()).map(|i| topic.integer(field, i));
    let first = ids.next()??;
    match ids.all(|id| id == Some(first)) {
        true => u32::try_from(first).ok(),
        false => None,
    }
}
