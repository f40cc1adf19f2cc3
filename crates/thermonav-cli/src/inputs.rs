//! Input files read into library types, each failure classified as bad data (exit 1) and
//! naming the file.

use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use std::path::Path;
use thermonav::imu::{ImuSeries, SampleKind};
use thermonav::nav::run::{RunError, operating_temperature_c};
use thermonav::sensor::{SensorProfile, adis16364_like, temperature_sensitive};
use thermonav::signal::timestamps::interval_stats;
use thermonav::stoch::bank::ModelBank;
use thermonav::stoch::thermal::ThermalCalibration;
use thermonav_io::profile::read_profile;
use thermonav_io::ros::BagFormat;
use thermonav_io::ros::extract::{TopicChoice, TopicNames, imu_series, stream_imu_extract};
use thermonav_io::ros::folder::read_bag_folder;
use thermonav_io::{ImuOptions, Strictness, read_imu_file_into};

/// A record's mean temp_c when it is a temperature a sensor is characterised at (else the
/// column holds something else, or another unit): a data error naming the file.
pub fn recorded_temperature(path: &Path, mean_c: f64) -> Result<f64, Failure> {
    let source = format!("{}: the mean of temp_c", path.display());
    thermonav_io::check_characterization_temperature(&source, mean_c)
        .map_err(|message| Failure::Data(anyhow!(message)))
}

/// Reads and validates a bank file.
pub fn read_bank(path: &Path) -> Result<ModelBank, Failure> {
    thermonav_io::bank::read_bank_file(path).data()
}

/// The bank's thermal calibration, or a data error naming the file.
pub fn thermal_calibration_of<'a>(
    bank: &'a ModelBank,
    path: &Path,
) -> Result<&'a ThermalCalibration, Failure> {
    bank.thermal.as_ref().ok_or_else(|| no_thermal(path))
}

/// The thermal calibration of the bank in `path`, or a data error naming the file.
pub fn read_thermal_calibration(path: &Path) -> Result<ThermalCalibration, Failure> {
    read_bank(path)?.thermal.ok_or_else(|| no_thermal(path))
}

/// A bank without a thermal calibration, naming the file.
fn no_thermal(path: &Path) -> Failure {
    Failure::Data(anyhow!(
        "{}: the bank has no thermal calibration (no 'thermal' field): characterize records at two or more temperatures (with --power-on or --sweep to separate power-ons) to fit one",
        path.display()
    ))
}

/// Reads an IMU record (a CSV as `options` say, a ROS bag (its topics as `topics` choose) or a
/// DataFlash log) of rates and its nominal sample rate, Hz; `purpose` names what needs rates in
/// the error for a file of increments.
pub fn read_rates(
    path: &Path,
    purpose: &str,
    (options, topics): (&ImuOptions, &TopicNames),
) -> Result<(ImuSeries, f64), Failure> {
    let series = read_imu_input(path, options, topics)?;
    if series.kind == Some(SampleKind::Increments) {
        return Err(Failure::Data(anyhow!(
            "{}: {purpose} needs rates; the file holds increments",
            path.display()
        )));
    }
    let rate_hz = nominal_rate_hz(&series, path)?;
    Ok((series, rate_hz))
}

/// `series` in body axes by the mounting of `options`: for the IMU records of readers other
/// than the canonical CSV's (ULog, raw IMU, KF-GINS), which the canonical reader's options do
/// not reach.
pub fn to_body(mut series: ImuSeries, options: &ImuOptions) -> ImuSeries {
    if let Some(mounting) = options.mounting {
        mounting.series_to_body(&mut series);
    }
    series
}

/// The nominal sample rate of a series (its median interval), Hz.
pub fn nominal_rate_hz(series: &ImuSeries, path: &Path) -> Result<f64, Failure> {
    interval_stats(&series.time)
        .map(|s| s.nominal_rate_hz())
        .ok_or_else(|| Failure::Data(anyhow!("{}: fewer than two samples", path.display())))
}

/// Refuses an input that cannot be read twice (a pipe, a FIFO, a process substitution such as
/// `<(cat f)`) for a command that reads its first bytes to tell its format and then reads it
/// again; a missing file passes, for the reader to name.
pub fn readable_twice(path: &Path, command: &str) -> Result<(), Failure> {
    match std::fs::metadata(path) {
        Ok(m) if !m.is_file() && !m.is_dir() => Err(Failure::Data(anyhow!(
            "{}: not a regular file (a pipe or a process substitution such as <(cat f)): {command} reads its first bytes to tell its format and then reads it again; save it to a file first",
            path.display()
        ))),
        _ => Ok(()),
    }
}

/// An IMU record: a canonical IMU CSV read as `options` say, or a ROS bag (a file told by its
/// magic bytes, or a ROS 2 bag folder told by its metadata.yaml) whose `sensor_msgs/Imu` topic
/// (`--topic`, else the only one holding messages) is read in FRD, with `temp_c` from its
/// temperature topic (`--temperature-topic`, else the only one, if any). A bag carries its own
/// times and axes: a mounting or a rate for it is refused (convert the bag, then rotate the
/// CSV); topics for a file that is no bag are refused.
pub fn read_imu_input(
    path: &Path,
    options: &ImuOptions,
    topics: &TopicNames,
) -> Result<ImuSeries, Failure> {
    read_imu_input_into(path, (options, topics), None)
}

/// [`read_imu_input`], a CSV into the columns of `spare` (a series done with; see
/// [`thermonav_io::read_imu_file_into`]).
pub fn read_imu_input_into(
    path: &Path,
    (options, topics): (&ImuOptions, &TopicNames),
    spare: Option<ImuSeries>,
) -> Result<ImuSeries, Failure> {
    let bag = bag_format_at(path)?;
    if bag.is_none() && !topics.is_empty() {
        return Err(Failure::Usage(anyhow!(
            "{}: --topic and --temperature-topic choose the topics of a ROS bag, and this is              not one (a bag file, or a ROS 2 bag folder with its metadata.yaml)",
            path.display()
        )));
    }
    if is_dataflash(path) {
        return read_dataflash_imu(path, options);
    }
    match bag {
        Some(_) if options.mounting.is_some() || options.rate_hz.is_some() => {
            Err(Failure::Data(anyhow!(
                "{}: a ROS bag has its own times and is read in FRD from ROS body axes: \
                 --imu-rotation and --rate-hz apply to CSV input (thermonav convert BAG --out \
                 imu.csv, then give the options with imu.csv)",
                path.display()
            )))
        }
        Some(format) => read_bag_imu(path, format, topics.choice()),
        None => read_imu_file_into(path, Strictness::Strict, options, spare).data(),
    }
}

/// True when the file at `path` is a ROS bag or a DataFlash log read whole (never streamed): every
/// one but an MCAP or ROS 1 bag not gzip-compressed ([`is_streamed_bag`]).
pub fn is_whole_log(path: &Path) -> bool {
    (bag_format_of(path).is_some() && !is_streamed_bag(path)) || is_dataflash(path)
}

/// The first `n` bytes of the regular file at `path`, decompressed when it is gzip (`None`: not
/// a regular file, or unreadable, for the CSV reader to name; a pipe is never read ahead).
fn head_of(path: &Path, n: u64) -> Option<Vec<u8>> {
    use std::io::Read;
    if !std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
        return None;
    }
    let mut head = Vec::new();
    let file = thermonav_io::open_input(path).ok()?;
    file.take(n).read_to_end(&mut head).ok()?;
    Some(head)
}

/// True when the file at `path` starts like an ArduPilot DataFlash log.
pub fn is_dataflash(path: &Path) -> bool {
    head_of(path, 16).is_some_and(|head| thermonav_io::dataflash::looks_like_dataflash(&head))
}

/// The IMU of a DataFlash log (its only instance), turned by the mounting of `options`; a rate
/// is refused (the log has its own times).
fn read_dataflash_imu(path: &Path, options: &ImuOptions) -> Result<ImuSeries, Failure> {
    use thermonav_io::dataflash::ardupilot::{imu_series, time_scale};
    if options.rate_hz.is_some() {
        return Err(Failure::Data(anyhow!(
            "{}: a DataFlash log has its own times (TimeUS): --rate-hz applies to CSV input",
            path.display()
        )));
    }
    let log = thermonav_io::dataflash::read_dataflash_file(path).data()?;
    let input = path.display().to_string();
    match imu_series(&log, None, "--imu-instance", &input, time_scale(&log)) {
        Ok(extract) => Ok(to_body(extract.series, options)),
        Err(e) => Err(Failure::Data(anyhow!(
            "{e} (to choose the instance, convert the log first: thermonav convert LOG.bin \
             --imu-instance N --out imu.csv)"
        ))),
    }
}

/// The bag format of `path`: of a file, told by its first bytes (`None`: not a bag, not a
/// regular file (a pipe is never read ahead: its bytes would be gone for the CSV reader), or
/// unreadable, for the CSV reader to name); of a folder, the storage its metadata.yaml names.
///
/// # Errors
/// A folder that is no ROS 2 bag folder (no metadata.yaml, or one that does not read), naming
/// the folder or the file and what was expected.
pub fn bag_format_at(path: &Path) -> Result<Option<BagFormat>, Failure> {
    match path.is_dir() {
        true => Ok(Some(read_bag_folder(path).data()?.format)),
        false => Ok(head_of(path, 16).and_then(|head| BagFormat::detect(&head))),
    }
}

/// [`bag_format_at`], `None` for a folder that is no bag folder (for the reader to name).
pub fn bag_format_of(path: &Path) -> Option<BagFormat> {
    bag_format_at(path).ok().flatten()
}

/// True when `path` is an MCAP bag or a ROS 1 bag that is not gzip-compressed (read record by
/// record), or a ROS 2 bag folder (read file after file, an MCAP file record by record, a db3
/// file whole): one that `characterize` can stream
/// ([`thermonav_io::ros::extract::stream_imu_series`]), and whose refusals name the storage
/// file they are about.
pub fn is_streamed_bag(path: &Path) -> bool {
    match bag_format_of(path) {
        Some(_) if path.is_dir() => true,
        Some(BagFormat::Ros2Mcap | BagFormat::Ros1Bag) => !thermonav_io::is_compressed(path),
        _ => false,
    }
}

/// The IMU of a bag, its topics chosen by `choice` as [`imu_series`] does.
/// An MCAP or ROS 1 bag is read record by record: memory is the series, not the bag.
fn read_bag_imu(
    path: &Path,
    format: BagFormat,
    choice: TopicChoice<'_>,
) -> Result<ImuSeries, Failure> {
    let input = path.display().to_string();
    let extract = match is_streamed_bag(path) {
        true => stream_imu_extract(path, choice).map(|(extract, _)| extract),
        false => thermonav_io::ros::read_bag_file(path, Some(format))
            .and_then(|bag| imu_series(&bag, choice, &input)),
    };
    extract.map(|e| e.series).map_err(bag_failure)
}

/// A bag's refusal as a data error, pointing to the options that choose its topics.
pub fn bag_failure(e: thermonav_io::ReadError) -> Failure {
    Failure::Data(anyhow!(
        "{e} (the topics are chosen with --topic T and --temperature-topic T2)"
    ))
}

/// The name that selects the built-in temperature-sensitive profile instead of a file.
pub const TEMPERATURE_SENSITIVE_PROFILE: &str = "builtin:temperature-sensitive";

/// True for the name of a profile built into thermonav.
pub fn is_builtin_profile(path: &Path) -> bool {
    path == Path::new(TEMPERATURE_SENSITIVE_PROFILE)
}

/// The profile of `--profile` (a TOML file, or [`TEMPERATURE_SENSITIVE_PROFILE`]), or the
/// built-in ADIS16364-like one.
pub fn load_profile(path: Option<&Path>) -> Result<SensorProfile, Failure> {
    match path {
        Some(p) if is_builtin_profile(p) => Ok(temperature_sensitive()),
        Some(p) => read_profile(p).data(),
        None => Ok(adis16364_like()),
    }
}

/// The operating temperature: given, or the mean of the IMU file's temp_c column.
pub fn operating_temperature(
    given: Option<f64>,
    series: &ImuSeries,
    imu: &Path,
) -> Result<f64, Failure> {
    operating_temperature_c(given, series).map_err(|_| no_temperature(imu))
}

/// A record without temp_c and no temperature given: a usage error naming the options (the
/// library's [`RunError::no_temperature`] in the command line's words).
pub(crate) fn no_temperature(imu: &Path) -> Failure {
    let message = RunError::no_temperature(thermonav::setting::flag);
    Failure::Usage(anyhow!("{}{message}", prefix(imu)))
}

/// `PATH: `, the start of a message about a file.
pub(crate) fn prefix(path: &Path) -> String {
    format!("{}: ", path.display())
}
