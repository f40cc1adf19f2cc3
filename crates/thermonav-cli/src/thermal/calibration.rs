//! The thermal calibration of a bank: its records' means (one power-on), further power-ons'
//! records and temperature sweeps, fitted with `stoch::thermal::calibrate`.

use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use thermonav::geo::gravity::normal_gravity_m_s2;
use thermonav::imu::Channel;
use thermonav::imu::ImuSeries;
use thermonav::sim::chamber::Site;
use thermonav::stoch::bank::ModelBank;
use thermonav::stoch::thermal::sweep_model::default_block_s;
use thermonav::stoch::thermal::{
    FitSettings, PowerOnRecord, RecordMean, SensorDevices, ThermalCalibration, bank_power_on,
    calibrate, calibrate_level_unit, merge_records, power_on_records, record_mean, sweep_records,
};
use thermonav_io::ros::extract::TopicNames;
use thermonav_io::ulog::px4::{default_gpst_minus_utc, raw_sensor_series, time_scale};
use thermonav_io::ulog::read_ulog_file;
use thermonav_io::{ImuOptions, Strictness, read_imu_file_with};

/// What a thermal calibration is fitted to beyond the bank's own records (by default none,
/// at the library's default site).
#[derive(Debug, Clone, Default)]
pub struct ThermalInputs {
    /// Further power-ons, each a list of static records.
    pub power_ons: Vec<Vec<PathBuf>>,
    /// Temperature sweeps, each its own power-on: the files (pieces) of each.
    pub sweeps: Vec<Vec<PathBuf>>,
    /// Block length of a sweep's block means, s; `None`: each piece's default
    /// ([`thermonav::stoch::thermal::sweep_model::default_block_s`]).
    pub sweep_block_s: Option<f64>,
    /// The IMU instance of a ULog sweep.
    pub sweep_instance: u8,
    /// Where the chamber stands: latitude (rad) and height (m), for the gravity a level unit's
    /// az reads.
    pub site: Site,
    /// How the records are read (the bank's records' mounting and rate).
    pub imu: ImuOptions,
    /// The topics of the records that are ROS bags.
    pub topics: TopicNames,
}

impl ThermalInputs {
    /// True when some input beyond the bank's records is given.
    fn given(&self) -> bool {
        !self.power_ons.is_empty() || !self.sweeps.is_empty()
    }
}

/// The calibration of `bank` and `inputs`: `None` (said on stderr) when the bank's records
/// alone span fewer than two temperatures or cannot be fitted.
///
/// # Errors
/// A further record or sweep that cannot be read or fitted.
pub fn calibrate_bank(
    bank: &ModelBank,
    inputs: &ThermalInputs,
) -> Result<Option<ThermalCalibration>, Failure> {
    let mut parts = vec![bank_power_on(bank)];
    for (k, files) in inputs.power_ons.iter().enumerate() {
        parts.push(power_on_records(
            k as u32 + 2,
            &means_of(files, &inputs.imu)?,
        ));
    }
    let first_sweep = inputs.power_ons.len() as u32 + 2;
    let mut devices = Vec::new();
    for (k, files) in inputs.sweeps.iter().enumerate() {
        for file in files {
            let sweep = sweep_series(file, inputs.sweep_instance, (&inputs.imu, &inputs.topics))?;
            devices.extend(sweep.devices);
            parts.push(sweep_of(
                &sweep.series,
                file,
                first_sweep + k as u32,
                inputs,
            )?);
        }
    }
    let gravity = normal_gravity_m_s2(inputs.site.latitude_rad, inputs.site.height_m);
    let sweep_files: Vec<PathBuf> = inputs.sweeps.iter().flatten().cloned().collect();
    let devices = common_devices(&devices, &sweep_files)?;
    Ok(fit(parts, gravity, inputs.given())?.map(|mut c| {
        c.devices = devices;
        c
    }))
}

/// A sweep's samples and, from a ULog, the sensors they came from.
pub struct Sweep {
    /// The samples, body axes.
    pub series: ImuSeries,
    /// The ULog's sensors.
    pub devices: Option<SensorDevices>,
}

/// The sweep in `path`: an IMU CSV, a bag (its topics as `topics` choose) or a DataFlash log,
/// or a PX4 ULog's raw sensors of `instance`.
pub fn sweep_series(
    path: &Path,
    instance: u8,
    (imu, topics): (&ImuOptions, &TopicNames),
) -> Result<Sweep, Failure> {
    crate::inputs::readable_twice(path, "characterize --sweep")?;
    if !is_ulog(path) {
        let series = crate::inputs::read_imu_input(path, imu, topics)?;
        return Ok(Sweep {
            series,
            devices: None,
        });
    }
    let log = read_ulog_file(path).data()?;
    let scale = time_scale(&log, default_gpst_minus_utc());
    let raw = raw_sensor_series(&log, &path.display().to_string(), scale, instance).data()?;
    let devices = SensorDevices {
        instance,
        gyro_device_id: raw.gyro_device_id,
        accel_device_id: raw.accel_device_id,
    };
    Ok(Sweep {
        series: crate::inputs::to_body(raw.series, imu),
        devices: Some(devices),
    })
}

/// True when the file starts with the ULog magic bytes.
fn is_ulog(path: &Path) -> bool {
    use std::io::Read;
    let mut head = [0u8; 7];
    let read = thermonav_io::open_input(path).and_then(|mut f| f.read_exact(&mut head));
    read.is_ok() && head.starts_with(&thermonav_io::ulog::MAGIC)
}

/// "instance, gyro id, accelerometer id" of a ULog sweep's sensors ("none" for a missing id).
fn devices_text(d: &SensorDevices) -> String {
    let id = |v: Option<u32>| v.map_or("none".to_string(), |v| v.to_string());
    format!(
        "{}, {}, {}",
        d.instance,
        id(d.gyro_device_id),
        id(d.accel_device_id)
    )
}

/// The sensors of the ULog sweeps, which must all be the same ones.
pub fn common_devices(
    devices: &[SensorDevices],
    sweeps: &[PathBuf],
) -> Result<Option<SensorDevices>, Failure> {
    match devices {
        [] => Ok(None),
        [first, rest @ ..] if rest.iter().all(|d| d == first) => Ok(Some(*first)),
        _ => Err(Failure::Data(anyhow!(
            "the ULog sweeps {} come from different sensors (instance, gyro and accelerometer device ids: {}): one calibration is of one unit",
            sweeps
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
            devices
                .iter()
                .map(devices_text)
                .collect::<Vec<_>>()
                .join("; ")
        ))),
    }
}

/// Why a bank built from its records alone has no thermal calibration: what fitting their
/// means says.
pub fn missing_reason(bank: &ModelBank) -> String {
    let observations = merge_records(vec![bank_power_on(bank)]);
    match calibrate(&observations, FitSettings::default()) {
        Err(e) => format!("the records' means alone: {e}"),
        Ok(c) if c.channels.is_empty() => "the records carry no means to fit".into(),
        Ok(_) => "the bank was written without one".into(),
    }
}

/// The calibration of the power-ons `parts` of a level unit under `gravity_m_s2`; a failed
/// fit is an error when further inputs were given (`required`), else a note and none.
fn fit(
    parts: Vec<BTreeMap<Channel, Vec<PowerOnRecord>>>,
    gravity_m_s2: f64,
    required: bool,
) -> Result<Option<ThermalCalibration>, Failure> {
    match calibrate_level_unit(parts, gravity_m_s2) {
        Ok(calibration) => Ok(calibration),
        Err(e) if required => Err(Failure::Data(anyhow!("thermal calibration: {e}"))),
        Err(e) => {
            eprintln!("note: no thermal calibration: {e}");
            Ok(None)
        }
    }
}

/// The means of static records of one power-on, each at its temp_c mean.
fn means_of(files: &[PathBuf], imu: &ImuOptions) -> Result<Vec<RecordMean>, Failure> {
    files.iter().map(|f| mean_of(f, imu)).collect()
}

fn mean_of(path: &Path, imu: &ImuOptions) -> Result<RecordMean, Failure> {
    let series = read_imu_file_with(path, Strictness::Strict, imu).data()?;
    let temperature_c = series.mean_temperature_c().ok_or_else(|| {
        Failure::Data(anyhow!(
            "{}: a power-on record needs a temp_c column",
            path.display()
        ))
    })?;
    crate::inputs::recorded_temperature(path, temperature_c)?;
    record_mean(&series, temperature_c)
        .ok_or_else(|| Failure::Data(anyhow!("{}: no IMU sample", path.display())))
}

fn sweep_of(
    series: &ImuSeries,
    path: &Path,
    power_on: u32,
    inputs: &ThermalInputs,
) -> Result<BTreeMap<Channel, Vec<PowerOnRecord>>, Failure> {
    let block_s = match inputs.sweep_block_s {
        Some(b) => b,
        None => {
            let time: Vec<f64> = series.time.iter().map(|t| t.as_seconds()).collect();
            let temperatures = series.temperature_c.as_deref().unwrap_or_default();
            default_block_s(&time, temperatures)
        }
    };
    sweep_records(power_on, series, block_s)
        .map_err(|e| anyhow!("{}: {e}", path.display()))
        .data()
}
