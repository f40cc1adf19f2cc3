//! ArduPilot messages of a DataFlash log as thermonav series: the IMU with its temperature, and
//! GPS fixes.
//!
//! - IMU: `IMU` records (`TimeUS`, instance `I`, `GyrX..Z` rad/s, `AccX..Z` m/s², `T` °C) of
//!   one instance, as rates timed at `TimeUS`; older logs without the `I` column write
//!   instances 1 and 2 as `IMU2` and `IMU3`. Axes are ArduPilot's body frame,
//!   forward-right-down, as thermonav expects (a level unit at rest reads AccZ ≈ −g), so the
//!   values are written as logged. `temp_c` is each record's own `T`. The instance is the one
//!   asked for, else the only one; several and none asked for is an error listing them.
//! - GNSS: `GPS` records of the lowest instance with `Status` ≥ 3 (3D fix or better): `Lat`,
//!   `Lng` (1e-7 deg), `Alt` (cm, above mean sea level: the height is MSL, not ellipsoidal,
//!   which [`GnssExtract::height`] says), velocity north/east from `Spd` (m/s) and `GCrs`
//!   (deg), down from `VZ` (m/s); standard deviations north and east = `HAcc`, down = `VAcc`
//!   from the `GPA` record of the same instance and `TimeUS`, when there is one.
//! - Units: when the log has `FMTU` records (with `UNIT` and `MULT`), the unit and multiplier
//!   of every column read must be the ones assumed here (rad/s, m/s/s, degC, ...; a
//!   multiplier equal to the format character's own scale), else the log is refused naming
//!   the column: a deg/s gyro is never read as rad/s.
//!
//! Time: `TimeUS` is µs since boot. When GPS fixes give the GPS week and time of week (`GWk`,
//! `GMS`), boot time is put on the GPST scale of [`crate::gpst`]: offset = median (the upper
//! one of an even count) over the 3D fixes of the lowest GPS instance of GPST(`GWk`, `GMS`) −
//! `TimeUS`; the fixes themselves are timed at their own GPST(`GWk`, `GMS`). Otherwise every
//! time stays seconds since boot, and [`TimeScale::Boot`] says so.

use super::{DataFlash, MessageType, Value};
use crate::error::{ReadError, ReadErrorKind};
use crate::gpst::from_week_and_nanos;
use crate::sample_checks::imu_sample_problem;
use serde::Serialize;
use std::collections::BTreeMap;
use thermonav::gnss::GnssFix;
use thermonav::imu::{ImuSample, ImuSeries, SampleKind};
use thermonav::time::Timestamp;
use thermonav::units::deg_to_rad;

/// What was done to the axes, for the sidecar.
pub const FRAME_NOTE: &str = "ArduPilot's IMU axes are its body frame, forward-right-down \
    (a level unit at rest reads AccZ = -g), as thermonav's: written as logged";

/// How temperatures are assigned, for the sidecar.
pub const TEMPERATURE_NOTE: &str = "each IMU record's own T (degC)";

/// The time scale of the extracted series.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(tag = "scale", rename_all = "snake_case")]
pub enum TimeScale {
    /// GPST seconds since 1970 (no leap seconds), from the GPS week and time of week.
    Gpst {
        /// GPST minus boot time, ns.
        boot_to_gpst_ns: i64,
    },
    /// Seconds since the autopilot booted (no GPS time in the log).
    Boot,
}

impl TimeScale {
    /// Boot time `time_us` on this scale.
    fn at(self, time_us: u64) -> Option<Timestamp> {
        let ns = i64::try_from(time_us).ok()?.checked_mul(1_000)?;
        let shift = match self {
            TimeScale::Gpst { boot_to_gpst_ns } => boot_to_gpst_ns,
            TimeScale::Boot => 0,
        };
        ns.checked_add(shift).map(Timestamp::from_nanos)
    }

    /// What `t_s` means on this scale, for the sidecar.
    pub fn note(self) -> &'static str {
        match self {
            TimeScale::Gpst { .. } => {
                "t_s is GPST seconds since 1970 (no leap seconds): IMU samples at TimeUS plus \
                 the median of GPST(GWk, GMS) - TimeUS over the GPS fixes (so they carry the \
                 receiver-to-log latency, ArduPilot's GPS_DELAY_MS), fixes at their own \
                 GPST(GWk, GMS)"
            }
            TimeScale::Boot => {
                "t_s is TimeUS, seconds since the autopilot booted: the log has no GPS week \
                 and time of week"
            }
        }
    }
}

/// A problem with a message of the log.
fn unusable(input: &str, what: String) -> ReadError {
    ReadError::new(input, None, ReadErrorKind::Unusable(what))
}

/// Column `name` of `t`, or an error naming both.
fn column(t: &MessageType, name: &str, input: &str) -> Result<usize, ReadError> {
    t.column(name).ok_or_else(|| {
        unusable(
            input,
            format!(
                "message {} has no column {name} (columns: {})",
                t.name,
                t.columns.join(",")
            ),
        )
    })
}

/// A numeric field, or an error naming the record.
fn number(t: &MessageType, c: usize, r: usize, input: &str) -> Result<f64, ReadError> {
    t.value(c, r).as_f64().ok_or_else(|| {
        unusable(
            input,
            format!(
                "at byte {}: {}.{} is text, expected a number",
                t.offset(r),
                t.name,
                t.columns[c]
            ),
        )
    })
}

/// An unsigned integer field (`TimeUS`, `I`, `Status`, ...), or an error naming the record.
fn unsigned(t: &MessageType, c: usize, r: usize, input: &str) -> Result<u64, ReadError> {
    t.value(c, r).as_u64().ok_or_else(|| {
        unusable(
            input,
            format!(
                "at byte {}: {}.{} is {:?}, expected a non-negative integer",
                t.offset(r),
                t.name,
                t.columns[c],
                t.value(c, r)
            ),
        )
    })
}

/// The time scale of `log`: GPST when the 3D fixes of the lowest GPS instance (the one
/// [`gnss_fixes`] reads) give the week, else boot time.
pub fn time_scale(log: &DataFlash) -> TimeScale {
    let Some(gps) = log.message("GPS") else {
        return TimeScale::Boot;
    };
    let (Some(time), Some(status), Some(week), Some(ms)) = (
        gps.column("TimeUS"),
        gps.column("Status"),
        gps.column("GWk"),
        gps.column("GMS"),
    ) else {
        return TimeScale::Boot;
    };
    let u = |c: usize, r: usize| gps.value(c, r).as_u64();
    let instance = |r: usize| gps.column("I").map_or(Some(0), |c| u(c, r));
    let lowest = (0..gps.len()).filter_map(instance).min();
    let mut offsets: Vec<i64> = (0..gps.len())
        .filter(|&r| instance(r) == lowest && u(status, r).is_some_and(|s| s >= 3))
        .filter_map(|r| {
            let gpst = gps_time(u(week, r)?, u(ms, r)?)?;
            gpst.as_nanos()
                .checked_sub(i64::try_from(u(time, r)?).ok()?.checked_mul(1_000)?)
        })
        .collect();
    offsets.sort_unstable();
    match offsets.get(offsets.len() / 2) {
        Some(&boot_to_gpst_ns) => TimeScale::Gpst { boot_to_gpst_ns },
        None => TimeScale::Boot,
    }
}

/// GPST of GPS week `week` (not 0: not yet known) and `ms` into it.
fn gps_time(week: u64, ms: u64) -> Option<Timestamp> {
    if week == 0 || ms >= 604_800_000 {
        return None;
    }
    let ns = i64::try_from(ms).ok()?.checked_mul(1_000_000)?;
    from_week_and_nanos(i64::try_from(week).ok()?, ns)
}

/// The units and multipliers the log's UNIT, MULT and FMTU records give its columns.
#[derive(Debug, Clone, Default)]
pub struct Units {
    labels: BTreeMap<u8, String>,
    multipliers: BTreeMap<u8, f64>,
    /// Per type id: (unit ids, multiplier ids), one character per column.
    by_type: BTreeMap<u64, (String, String)>,
}

impl Units {
    /// The units of `log`; empty when it has no FMTU records.
    pub fn of(log: &DataFlash) -> Self {
        let mut units = Units::default();
        let pairs = |name: &str, value: &str| -> Vec<(u8, Value)> {
            let Some(t) = log.message(name) else {
                return Vec::new();
            };
            let (Some(id), Some(v)) = (t.column("Id"), t.column(value)) else {
                return Vec::new();
            };
            let id_byte = |r| t.value(id, r).as_f64().map(|x| x as i64 as u8);
            (0..t.len())
                .filter_map(|r| Some((id_byte(r)?, t.value(v, r))))
                .collect()
        };
        for (id, v) in pairs("UNIT", "Label") {
            units
                .labels
                .insert(id, v.as_text().unwrap_or("").to_string());
        }
        for (id, v) in pairs("MULT", "Mult") {
            units.multipliers.insert(id, v.as_f64().unwrap_or(f64::NAN));
        }
        if let Some(t) = log.message("FMTU") {
            let cols = (
                t.column("FmtType"),
                t.column("UnitIds"),
                t.column("MultIds"),
            );
            if let (Some(ty), Some(u), Some(m)) = cols {
                for r in 0..t.len() {
                    let text = |c| t.value(c, r).as_text().unwrap_or("").to_string();
                    if let Some(id) = t.value(ty, r).as_u64() {
                        units.by_type.insert(id, (text(u), text(m)));
                    }
                }
            }
        }
        units
    }

    /// True when the log states units for type `t`.
    pub fn states(&self, t: &MessageType) -> bool {
        self.by_type.contains_key(&u64::from(t.id))
    }

    /// Checks that column `name` of `t` is in `unit` (a UNIT label) with the multiplier its
    /// format character implies, where the log says either.
    ///
    /// # Errors
    /// [`ReadErrorKind::Unusable`] naming the column, the unit or multiplier found and the one
    /// expected.
    pub fn check(
        &self,
        t: &MessageType,
        name: &str,
        unit: &str,
        input: &str,
    ) -> Result<(), ReadError> {
        let implied = t.column(name).map(|c| 1.0 / t.field_type(c).divisor());
        self.check_scaled(t, name, unit, implied.unwrap_or(1.0), input)
    }

    /// As [`Units::check`], with the multiplier `expected` (`TimeUS`: 1e-6, µs to s).
    ///
    /// # Errors
    /// As [`Units::check`].
    pub fn check_scaled(
        &self,
        t: &MessageType,
        name: &str,
        unit: &str,
        expected: f64,
        input: &str,
    ) -> Result<(), ReadError> {
        let (Some((unit_ids, mult_ids)), Some(c)) =
            (self.by_type.get(&u64::from(t.id)), t.column(name))
        else {
            return Ok(());
        };
        let refuse = |what: String| {
            unusable(
                input,
                format!(
                    "{}.{name}: the log's FMTU, UNIT and MULT records give {what}",
                    t.name
                ),
            )
        };
        let label = unit_ids.as_bytes().get(c).and_then(|u| self.labels.get(u));
        if let Some(found) = label.filter(|l| l.as_str() != unit) {
            return Err(refuse(format!("the unit {found}, expected {unit}")));
        }
        let multiplier = mult_ids.as_bytes().get(c).and_then(|m| match m {
            b'-' | b'?' => None,
            m => self.multipliers.get(m),
        });
        match multiplier {
            Some(&m) if (m - expected).abs() > 1e-9 * expected => Err(refuse(format!(
                "a multiplier of {m}, expected {expected} (format character '{}')",
                t.field_type(c).character()
            ))),
            _ => Ok(()),
        }
    }
}

/// One IMU instance of the log.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct InstanceSummary {
    /// The instance (`I`, or 1 and 2 for `IMU2` and `IMU3`).
    pub instance: u64,
    /// The message its records are in.
    pub message: String,
    /// Records.
    pub count: usize,
}

/// The IMU instances of `log`, by instance.
pub fn imu_instances(log: &DataFlash) -> Vec<InstanceSummary> {
    let mut found: BTreeMap<u64, InstanceSummary> = BTreeMap::new();
    for (name, legacy) in [("IMU", 0), ("IMU2", 1), ("IMU3", 2)] {
        let Some(t) = log.message(name) else { continue };
        for r in 0..t.len() {
            let instance = match t.column("I") {
                Some(c) => t.value(c, r).as_u64().unwrap_or(u64::MAX),
                None => legacy,
            };
            found
                .entry(instance)
                .or_insert_with(|| InstanceSummary {
                    instance,
                    message: name.to_string(),
                    count: 0,
                })
                .count += 1;
        }
    }
    found.into_values().collect()
}

/// The instances as `0 (IMU, 100 records), ...`.
fn listing(instances: &[InstanceSummary]) -> String {
    let items: Vec<String> = instances
        .iter()
        .map(|s| format!("{} ({}, {} records)", s.instance, s.message, s.count))
        .collect();
    items.join(", ")
}

/// The instance to read: `requested`, else the only one.
///
/// # Errors
/// [`ReadErrorKind::Unusable`]: no IMU record, the requested instance absent, or several and
/// none requested (listing them and naming `option`).
pub fn select_instance(
    log: &DataFlash,
    requested: Option<u64>,
    option: &str,
    input: &str,
) -> Result<InstanceSummary, ReadError> {
    let instances = imu_instances(log);
    if instances.is_empty() {
        return Err(unusable(
            input,
            "no IMU record: expected IMU messages (TimeUS,I,GyrX..Z,AccX..Z,T)".to_string(),
        ));
    }
    let chosen = match requested {
        Some(n) => instances.iter().find(|s| s.instance == n),
        None if instances.len() == 1 => instances.first(),
        None => {
            return Err(unusable(
                input,
                format!(
                    "{} IMU instances: {}; choose one with {option}",
                    instances.len(),
                    listing(&instances)
                ),
            ));
        }
    };
    chosen.cloned().ok_or_else(|| {
        unusable(
            input,
            format!(
                "no IMU instance {} (instances: {})",
                requested.unwrap_or_default(),
                listing(&instances)
            ),
        )
    })
}

/// What [`imu_series`] took from the log.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ImuExtract {
    /// The rates, FRD, timed at `TimeUS` on the time scale.
    #[serde(skip)]
    pub series: ImuSeries,
    /// The message read.
    pub message: String,
    /// The instance read.
    pub instance: u64,
    /// Every IMU instance of the log.
    pub instances: Vec<InstanceSummary>,
    /// Where `temp_c` comes from.
    pub temperature: &'static str,
    /// What was done to the axes.
    pub frame: &'static str,
    /// Whether the log's own units confirmed the columns' units.
    pub units: &'static str,
}

/// The note on units.
fn units_note(stated: bool) -> &'static str {
    match stated {
        true => "confirmed by the log's FMTU, UNIT and MULT records",
        false => "the log has no FMTU record for this message: LogStructure.h's units assumed",
    }
}

/// The IMU columns read, with their units.
const IMU_COLUMNS: [(&str, &str); 7] = [
    ("GyrX", "rad/s"),
    ("GyrY", "rad/s"),
    ("GyrZ", "rad/s"),
    ("AccX", "m/s/s"),
    ("AccY", "m/s/s"),
    ("AccZ", "m/s/s"),
    ("T", "degC"),
];

/// The IMU of `log` (instance `requested`, else the only one) on `scale`.
///
/// # Errors
/// Those of [`select_instance`] (naming `option`); a missing column; a unit the log states
/// otherwise; a non-finite value or a `TimeUS` that does not increase (with the record's byte
/// offset).
pub fn imu_series(
    log: &DataFlash,
    requested: Option<u64>,
    option: &str,
    input: &str,
    scale: TimeScale,
) -> Result<ImuExtract, ReadError> {
    let chosen = select_instance(log, requested, option, input)?;
    let t = log
        .message(&chosen.message)
        .ok_or_else(|| unusable(input, format!("no {} message", chosen.message)))?;
    let units = Units::of(log);
    let mut columns = [0; 7];
    for (k, (name, unit)) in IMU_COLUMNS.iter().enumerate() {
        columns[k] = column(t, name, input)?;
        units.check(t, name, unit, input)?;
    }
    units.check_scaled(t, "TimeUS", "s", 1e-6, input)?;
    let time = column(t, "TimeUS", input)?;
    let instance = t.column("I");
    let mut series = ImuSeries::new(SampleKind::Rates);
    for r in 0..t.len() {
        if let Some(c) = instance {
            if t.value(c, r).as_u64() != Some(chosen.instance) {
                continue;
            }
        }
        let sample = imu_sample(t, r, time, &columns, scale, input)?;
        check_after(&series, &sample, t, r, input)?;
        series.push(&sample);
    }
    Ok(ImuExtract {
        series,
        message: chosen.message.clone(),
        instance: chosen.instance,
        instances: imu_instances(log),
        temperature: TEMPERATURE_NOTE,
        frame: FRAME_NOTE,
        units: units_note(units.states(t)),
    })
}

/// Record `r` of `t` as a sample.
fn imu_sample(
    t: &MessageType,
    r: usize,
    time: usize,
    columns: &[usize; 7],
    scale: TimeScale,
    input: &str,
) -> Result<ImuSample, ReadError> {
    let mut v = [0.0; 7];
    for (value, &c) in v.iter_mut().zip(columns) {
        *value = number(t, c, r, input)?;
    }
    let (gyro, accel) = ([v[0], v[1], v[2]], [v[3], v[4], v[5]]);
    if let Some(problem) = imu_sample_problem(gyro, accel, Some(v[6])) {
        return Err(unusable(
            input,
            format!("at byte {}: {} record {r}: {problem}", t.offset(r), t.name),
        ));
    }
    let us = unsigned(t, time, r, input)?;
    let time = scale.at(us).ok_or_else(|| {
        unusable(
            input,
            format!("at byte {}: TimeUS {us} is out of range", t.offset(r)),
        )
    })?;
    Ok(ImuSample {
        time,
        gyro,
        accel,
        temperature_c: Some(v[6]),
    })
}

/// `sample` is after the last sample of `series`.
fn check_after(
    series: &ImuSeries,
    sample: &ImuSample,
    t: &MessageType,
    r: usize,
    input: &str,
) -> Result<(), ReadError> {
    match series.time.last() {
        Some(&previous) if sample.time <= previous => Err(unusable(
            input,
            format!(
                "at byte {}: {} record {r} is at {:.6} s, not after the previous record's {:.6} s",
                t.offset(r),
                t.name,
                sample.time.as_seconds(),
                previous.as_seconds()
            ),
        )),
        _ => Ok(()),
    }
}

/// What [`gnss_fixes`] took from the log.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GnssExtract {
    /// The fixes.
    #[serde(skip)]
    pub fixes: Vec<GnssFix>,
    /// The GPS instance read (the lowest in the log).
    pub instance: u64,
    /// Records of that instance left out: `Status` < 3, or no GPS week on the GPST scale.
    pub records_without_3d_fix: usize,
    /// Records of other GPS instances, not read.
    pub other_instance_records: usize,
    /// What the height is.
    pub height: &'static str,
    /// Where the standard deviations come from.
    pub accuracy: &'static str,
    /// Whether the log's own units confirmed the columns' units.
    pub units: &'static str,
}

/// What the height is.
const HEIGHT_NOTE: &str =
    "GPS.Alt: above mean sea level (the log gives no geoid separation), not the WGS84 ellipsoid";

/// The GPS columns read, with their units.
const GPS_COLUMNS: [(&str, &str); 6] = [
    ("Lat", "deglatitude"),
    ("Lng", "deglongitude"),
    ("Alt", "m"),
    ("Spd", "m/s"),
    ("GCrs", "degheading"),
    ("VZ", "m/s"),
];

/// The GPS fixes of `log` on `scale` (the lowest instance).
///
/// # Errors
/// [`ReadErrorKind::Unusable`]: no GPS message, a missing column, a unit the log states
/// otherwise, no 3D fix, a non-finite position or a time that does not increase (with the
/// record's byte offset).
pub fn gnss_fixes(
    log: &DataFlash,
    input: &str,
    scale: TimeScale,
) -> Result<GnssExtract, ReadError> {
    let t = log.message("GPS").ok_or_else(|| {
        unusable(
            input,
            "no GPS message: expected GPS records (TimeUS,I,Status,GMS,GWk,...,Lat,Lng,Alt,Spd,GCrs,VZ)"
                .to_string(),
        )
    })?;
    let units = Units::of(log);
    let fields = GpsFields::of(t, &units, input)?;
    let accuracy = Accuracy::of(log, &units, input)?;
    let instance = (0..t.len())
        .filter_map(|r| fields.instance(t, r))
        .min()
        .unwrap_or(0);
    let mut extract = GnssExtract {
        fixes: Vec::new(),
        instance,
        records_without_3d_fix: 0,
        other_instance_records: 0,
        height: HEIGHT_NOTE,
        accuracy: accuracy.note(),
        units: units_note(units.states(t)),
    };
    for r in 0..t.len() {
        if fields.instance(t, r).unwrap_or(0) != instance {
            extract.other_instance_records += 1;
            continue;
        }
        match fields.fix(t, r, scale, &accuracy, input)? {
            Some(fix) => push_fix(&mut extract.fixes, fix, t, r, input)?,
            None => extract.records_without_3d_fix += 1,
        }
    }
    if extract.fixes.is_empty() {
        return Err(unusable(
            input,
            format!(
                "GPS instance {instance} has no 3D fix (Status >= 3) in {} records",
                t.len() - extract.other_instance_records
            ),
        ));
    }
    Ok(extract)
}

/// Appends `fix` when it is after the last one.
fn push_fix(
    fixes: &mut Vec<GnssFix>,
    fix: GnssFix,
    t: &MessageType,
    r: usize,
    input: &str,
) -> Result<(), ReadError> {
    if fixes.last().is_some_and(|p| fix.time <= p.time) {
        return Err(unusable(
            input,
            format!(
                "at byte {}: GPS record {r} is not after the previous fix",
                t.offset(r)
            ),
        ));
    }
    fixes.push(fix);
    Ok(())
}

/// The GPS columns.
struct GpsFields {
    time: usize,
    instance: Option<usize>,
    status: usize,
    week: usize,
    ms: usize,
    values: [usize; 6],
}

impl GpsFields {
    /// Finds the columns and checks their units.
    fn of(t: &MessageType, units: &Units, input: &str) -> Result<Self, ReadError> {
        let mut values = [0; 6];
        for (k, (name, unit)) in GPS_COLUMNS.iter().enumerate() {
            values[k] = column(t, name, input)?;
            units.check(t, name, unit, input)?;
        }
        units.check_scaled(t, "TimeUS", "s", 1e-6, input)?;
        Ok(Self {
            time: column(t, "TimeUS", input)?,
            instance: t.column("I"),
            status: column(t, "Status", input)?,
            week: column(t, "GWk", input)?,
            ms: column(t, "GMS", input)?,
            values,
        })
    }

    /// The instance of record `r` (0 without an `I` column).
    fn instance(&self, t: &MessageType, r: usize) -> Option<u64> {
        match self.instance {
            Some(c) => t.value(c, r).as_u64(),
            None => Some(0),
        }
    }

    /// Record `r` as a fix; `None` without a 3D fix (or without GPS time on the GPST scale).
    fn fix(
        &self,
        t: &MessageType,
        r: usize,
        scale: TimeScale,
        accuracy: &Accuracy,
        input: &str,
    ) -> Result<Option<GnssFix>, ReadError> {
        if unsigned(t, self.status, r, input)? < 3 {
            return Ok(None);
        }
        let time_us = unsigned(t, self.time, r, input)?;
        let time = match scale {
            TimeScale::Gpst { .. } => gps_time(
                unsigned(t, self.week, r, input)?,
                unsigned(t, self.ms, r, input)?,
            ),
            TimeScale::Boot => scale.at(time_us),
        };
        let Some(time) = time else { return Ok(None) };
        let mut v = [0.0; 6];
        for (value, &c) in v.iter_mut().zip(&self.values) {
            *value = number(t, c, r, input)?;
        }
        let [lat, lng, alt, speed, course, down] = v;
        if !v.iter().all(|x| x.is_finite()) || lat.abs() > 90.0 || lng.abs() > 180.0 {
            return Err(unusable(
                input,
                format!(
                    "at byte {}: GPS record {r} has a position or velocity out of range \
                     (Lat {lat}, Lng {lng}, Alt {alt} m)",
                    t.offset(r)
                ),
            ));
        }
        let course = deg_to_rad(course);
        Ok(Some(GnssFix {
            time,
            latitude_rad: deg_to_rad(lat),
            longitude_rad: deg_to_rad(lng),
            height_m: alt,
            position_sd_ned_m: accuracy.sd(self.instance(t, r), time_us),
            velocity_ned_m_s: Some([speed * course.cos(), speed * course.sin(), down]),
            heading: None,
        }))
    }
}

/// The GPA accuracies by (instance, `TimeUS`): (HAcc, VAcc), m.
struct Accuracy {
    by_record: BTreeMap<(u64, u64), (f64, f64)>,
    present: bool,
}

impl Accuracy {
    /// The GPA records of `log`, their units checked.
    fn of(log: &DataFlash, units: &Units, input: &str) -> Result<Self, ReadError> {
        let Some(t) = log.message("GPA") else {
            return Ok(Self {
                by_record: BTreeMap::new(),
                present: false,
            });
        };
        let (time, hacc, vacc) = (
            column(t, "TimeUS", input)?,
            column(t, "HAcc", input)?,
            column(t, "VAcc", input)?,
        );
        units.check(t, "HAcc", "m", input)?;
        units.check(t, "VAcc", "m", input)?;
        let mut by_record = BTreeMap::new();
        for r in 0..t.len() {
            let instance = match t.column("I") {
                Some(c) => unsigned(t, c, r, input)?,
                None => 0,
            };
            let key = (instance, unsigned(t, time, r, input)?);
            let sd = (number(t, hacc, r, input)?, number(t, vacc, r, input)?);
            by_record.insert(key, sd);
        }
        Ok(Self {
            by_record,
            present: true,
        })
    }

    /// Standard deviations north, east, down of the fix of `instance` at `time_us`.
    fn sd(&self, instance: Option<u64>, time_us: u64) -> Option<[f64; 3]> {
        let &(h, v) = self.by_record.get(&(instance?, time_us))?;
        let usable = [h, v].iter().all(|x| x.is_finite() && *x > 0.0);
        usable.then_some([h, h, v])
    }

    /// Where the standard deviations come from.
    fn note(&self) -> &'static str {
        match self.present {
            true => {
                "GPA.HAcc north and east, GPA.VAcc down (the GPA record of the fix's instance and TimeUS)"
            }
            false => "none: the log has no GPA records",
        }
    }
}
