//! `thermonav convert`: a foreign file (RTKLIB, NMEA, KF-GINS, raw IMU + time tag, PX4 ULog,
//! ROS bags, ArduPilot DataFlash)
//! to the canonical GNSS, IMU or trajectory CSV, or (`--to kf-gins`) one of ours to KF-GINS. The whole input is read before anything is written,
//! and the output is written atomically, so a bad input leaves no output behind.

mod dataflash;
mod ros;
mod to_kf_gins;
mod ulog;

use crate::args::{ConvertArgs, ForeignFormatArg, ImuFrameArg};
use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use std::io::Read;
use std::path::{Path, PathBuf};
use thermonav::gnss::GnssFix;
use thermonav::imu::ImuSeries;
use thermonav::setting::positive;
use thermonav::time::Duration;
use thermonav_io::kf_gins::{read_kf_gins_gnss_file, read_kf_gins_imu_file, read_kf_gins_nav_file};
use thermonav_io::nmea::{NmeaSettings, read_nmea_file};
use thermonav_io::raw_imu::{ImuFrame, RawImuSettings, read_raw_imu_files};
use thermonav_io::rtklib_pos::{PosSettings, QualitySet, read_rtklib_pos_file};
use thermonav_io::{
    Strictness, keep_common_groups, write_gnss_file, write_imu_file, write_trajectory_file,
};

/// Runs `convert`.
pub fn run(args: &ConvertArgs) -> Result<(), Failure> {
    crate::settings::analysis::check_convert(args, &tag_path(args))?;
    if args.to.is_some() {
        let (count, what) = to_kf_gins::convert(args, strictness_of(args))?;
        println!(
            "{}: {count} {what} written to {}",
            args.input.display(),
            args.out.display()
        );
        return Ok(());
    }
    let format = match args.format {
        Some(format) => format,
        None => detect_format(&args.input, &tag_path(args))?,
    };
    if !log_with_gnss(format) {
        ulog::reject_gnss_out(args)?;
    }
    reject_rotation_without_imu(format, args)?;
    ros::reject_topics(format, args)?;
    dataflash::reject_instance(format, args)?;
    let (count, what) = convert(format, args, strictness_of(args))?;
    println!(
        "{}: {count} {what} written to {}",
        args.input.display(),
        args.out.display()
    );
    Ok(())
}

/// A log that holds GNSS fixes beside its IMU (`--gnss-out` applies).
fn log_with_gnss(format: ForeignFormatArg) -> bool {
    matches!(
        format,
        ForeignFormatArg::Px4Ulog | ForeignFormatArg::Dataflash
    ) || ros::bag_format(format).is_some()
}

/// The error for `--imu-rotation` on a format without an IMU.
fn reject_rotation_without_imu(
    format: ForeignFormatArg,
    args: &ConvertArgs,
) -> Result<(), Failure> {
    let imu = matches!(
        format,
        ForeignFormatArg::KfGinsImu
            | ForeignFormatArg::RawImuTag
            | ForeignFormatArg::Px4Ulog
            | ForeignFormatArg::Dataflash
    );
    match (imu, args.rotation.imu_rotation) {
        (false, Some(_)) => Err(anyhow!(
            "--imu-rotation goes with an IMU input (kf-gins-imu, raw-imu-tag, px4-ulog, dataflash); this input holds no IMU samples"
        ))
        .usage(),
        _ => Ok(()),
    }
}

/// `--lenient` as the readers' strictness.
fn strictness_of(args: &ConvertArgs) -> Strictness {
    match args.lenient {
        true => Strictness::Lenient,
        false => Strictness::Strict,
    }
}

/// Reads the input in `format`, writes the canonical file and says how many of what it wrote.
fn convert(
    format: ForeignFormatArg,
    args: &ConvertArgs,
    strictness: Strictness,
) -> Result<(usize, &'static str), Failure> {
    match format {
        ForeignFormatArg::RtklibPos => convert_rtklib_pos(args, strictness),
        ForeignFormatArg::Nmea => convert_nmea(args, strictness),
        ForeignFormatArg::KfGinsGnss => convert_kf_gins_gnss(args, strictness),
        ForeignFormatArg::KfGinsImu => convert_kf_gins_imu(args, strictness),
        ForeignFormatArg::RawImuTag => convert_raw_imu(args, strictness),
        ForeignFormatArg::Px4Ulog => ulog::convert(args),
        ForeignFormatArg::Dataflash => dataflash::convert(args),
        ForeignFormatArg::KfGinsNav => convert_kf_gins_nav(args, strictness),
        ForeignFormatArg::Ros2Mcap | ForeignFormatArg::Ros2Db3 | ForeignFormatArg::Ros1Bag => {
            ros::convert(format, args)
        }
    }
}

/// An RTKLIB `.pos` file to GNSS fixes, keeping the `--quality` solutions (all when none given).
fn convert_rtklib_pos(
    args: &ConvertArgs,
    strictness: Strictness,
) -> Result<(usize, &'static str), Failure> {
    let settings = PosSettings {
        strictness,
        qualities: quality_set(&args.quality),
    };
    let solutions = read_rtklib_pos_file(&args.input, settings).data()?;
    write_fixes(&args.out, solutions.iter().map(|s| s.fix).collect())
}

/// The `--quality` solutions to keep: all when none are given.
fn quality_set(quality: &[u8]) -> QualitySet {
    match quality.is_empty() {
        true => QualitySet::ALL,
        false => QualitySet::of(quality),
    }
}

/// An NMEA log to GNSS fixes.
fn convert_nmea(
    args: &ConvertArgs,
    strictness: Strictness,
) -> Result<(usize, &'static str), Failure> {
    let fixes = read_nmea_file(&args.input, nmea_settings(args, strictness)?).data()?;
    write_fixes(&args.out, fixes)
}

/// A KF-GINS GNSS file to GNSS fixes.
fn convert_kf_gins_gnss(
    args: &ConvertArgs,
    strictness: Strictness,
) -> Result<(usize, &'static str), Failure> {
    let fixes = read_kf_gins_gnss_file(&args.input, args.gps_week, strictness).data()?;
    write_fixes(&args.out, fixes)
}

/// A KF-GINS IMU file to an IMU CSV of increments.
fn convert_kf_gins_imu(
    args: &ConvertArgs,
    strictness: Strictness,
) -> Result<(usize, &'static str), Failure> {
    let series = read_kf_gins_imu_file(&args.input, args.gps_week, strictness).data()?;
    let series = to_body(series, args);
    write_imu_file(&args.out, &series).data()?;
    Ok((series.len(), "IMU samples (increments)"))
}

/// A raw IMU log and its time-tag file to an IMU CSV of rates.
fn convert_raw_imu(
    args: &ConvertArgs,
    strictness: Strictness,
) -> Result<(usize, &'static str), Failure> {
    let settings = raw_imu_settings(args, strictness)?;
    let series = read_raw_imu_files(&args.input, tag_path(args), settings).data()?;
    let series = to_body(series, args);
    write_imu_file(&args.out, &series).data()?;
    Ok((series.len(), "IMU samples (rates)"))
}

/// `series` turned by `--imu-rotation` (after the raw reader's `--imu-frame`).
fn to_body(series: ImuSeries, args: &ConvertArgs) -> ImuSeries {
    crate::inputs::to_body(series, &crate::settings::imu::rotation_only(&args.rotation))
}

/// A KF-GINS navigation result to a trajectory CSV.
fn convert_kf_gins_nav(
    args: &ConvertArgs,
    strictness: Strictness,
) -> Result<(usize, &'static str), Failure> {
    let points = read_kf_gins_nav_file(&args.input, strictness).data()?;
    write_trajectory_file(&args.out, &points).data()?;
    Ok((points.len(), "trajectory points"))
}

/// The sidecar of a converted flight log (ULog, DataFlash): where the series came from and on
/// which time scale; the scale, the IMU and GNSS extracts and the container's figures are each
/// format's own.
#[derive(serde::Serialize)]
struct LogSidecar<'a, Scale, Imu, Gnss, Log> {
    input: String,
    time_scale: Scale,
    time_scale_note: &'static str,
    imu: &'a Imu,
    /// The `--imu-rotation` the IMU series was turned by into body axes, when given.
    #[serde(skip_serializing_if = "Option::is_none")]
    imu_rotation: Option<String>,
    imu_samples: usize,
    gnss: Option<&'a Gnss>,
    gnss_fixes: Option<usize>,
    log: Log,
}

/// A log's outputs (the GNSS CSV with `--gnss-out`, the IMU CSV, its JSON sidecar), in that
/// order, each atomically; if a later one fails, the earlier ones of this run are removed, so a
/// failed run leaves no half of a conversion behind.
fn write_log_outputs(
    args: &ConvertArgs,
    series: &ImuSeries,
    fixes: Option<&[GnssFix]>,
    sidecar: &impl serde::Serialize,
) -> Result<(), Failure> {
    let mut written: Vec<PathBuf> = Vec::new();
    let mut write = || {
        if let (Some(path), Some(fixes)) = (&args.gnss_out, fixes) {
            let (count, what) = write_fixes(path, fixes.to_vec())?;
            written.push(path.clone());
            println!(
                "{}: {count} {what} written to {}",
                args.input.display(),
                path.display()
            );
        }
        thermonav_io::write_imu_file(&args.out, series).data()?;
        written.push(args.out.clone());
        let json = crate::settings::analysis::json_sidecar(&args.out);
        thermonav_io::write_json_atomically(json, sidecar).data()
    };
    let outcome = write();
    if outcome.is_err() {
        written.iter().for_each(|path| {
            let _ = std::fs::remove_file(path);
        });
    }
    outcome
}

/// Writes fixes as one GNSS CSV, dropping (with a note) the groups only some fixes carry.
fn write_fixes(out: &Path, mut fixes: Vec<GnssFix>) -> Result<(usize, &'static str), Failure> {
    for group in keep_common_groups(&mut fixes) {
        eprintln!("note: {group} is not given at every epoch and is left out");
    }
    write_gnss_file(out, &fixes).data()?;
    Ok((fixes.len(), "GNSS fixes"))
}

/// The time-tag file: `--tag`, or the input's name with `.tag` appended.
fn tag_path(args: &ConvertArgs) -> PathBuf {
    args.tag.clone().unwrap_or_else(|| {
        let mut name = args.input.clone().into_os_string();
        name.push(".tag");
        PathBuf::from(name)
    })
}

/// The raw IMU reader's settings: `--imu-frame` and `--time-offset-s`.
fn raw_imu_settings(args: &ConvertArgs, strictness: Strictness) -> Result<RawImuSettings, Failure> {
    let time_offset = Duration::from_seconds(args.time_offset_s)
        .map_err(|e| anyhow!("--time-offset-s: {e}"))
        .usage()?;
    Ok(RawImuSettings {
        strictness,
        frame: imu_frame(args.imu_frame),
        time_offset,
    })
}

/// `--imu-frame` as the raw IMU reader's frame.
fn imu_frame(frame: ImuFrameArg) -> ImuFrame {
    match frame {
        ImuFrameArg::Sensor => ImuFrame::Sensor,
        ImuFrameArg::DriveFrd => ImuFrame::DriveMountingFrd,
    }
}

/// `--leap-seconds` as a duration: GPST minus UTC, at most an hour either way.
fn gpst_minus_utc(args: &ConvertArgs) -> Result<Duration, Failure> {
    if args.leap_seconds.abs() > 3600 {
        return Err(anyhow!(
            "--leap-seconds is GPST minus UTC (18 since 2017), not {}",
            args.leap_seconds
        ))
        .usage();
    }
    Ok(Duration::from_nanos(args.leap_seconds * 1_000_000_000))
}

/// The NMEA reader's settings: `--leap-seconds`, `--date`, `--heading-sd-deg`, `--level-velocity`.
fn nmea_settings(args: &ConvertArgs, strictness: Strictness) -> Result<NmeaSettings, Failure> {
    let heading_sd_rad = (args.heading_sd_deg)
        .map(|sd| positive("heading_sd_deg", sd).map(f64::to_radians))
        .transpose()?;
    let gpst_minus_utc = gpst_minus_utc(args)?;
    Ok(NmeaSettings {
        strictness,
        gpst_minus_utc,
        date: args.date.as_deref().map(parse_date).transpose().usage()?,
        heading_sd_rad,
        level_velocity: args.level_velocity,
    })
}

/// `YYYY-MM-DD` as (year, month, day).
fn parse_date(text: &str) -> anyhow::Result<(i32, u32, u32)> {
    let bad = || anyhow!("--date: expected YYYY-MM-DD, found \"{text}\"");
    let mut parts = text.splitn(3, '-');
    let mut next = || parts.next().ok_or_else(bad);
    let (year, month, day) = (next()?, next()?, next()?);
    let year: i32 = year.parse().map_err(|_| bad())?;
    let month: u32 = month.parse().map_err(|_| bad())?;
    let day: u32 = day.parse().map_err(|_| bad())?;
    match (1..=12).contains(&month) && (1..=31).contains(&day) {
        true => Ok((year, month, day)),
        false => Err(bad()),
    }
}

/// Bytes read from the start of a file to recognise its format.
const SNIFF_BYTES: u64 = 64 * 1024;

/// The format of `input` told from its first lines, when only one format fits.
/// A folder is a ROS 2 bag folder, in the storage its metadata.yaml names.
fn detect_format(input: &Path, tag: &Path) -> Result<ForeignFormatArg, Failure> {
    crate::inputs::readable_twice(input, "convert")?;
    if let Some(bag) = crate::inputs::bag_format_at(input)?.filter(|_| input.is_dir()) {
        return Ok(ros::format_arg(bag));
    }
    let head = read_head(input)?;
    format_of_content(&head, tag)
        .map_err(|why| {
            anyhow!(
                "{}: cannot tell the format from the content ({why}); give --format",
                input.display()
            )
        })
        .usage()
}

/// The first [`SNIFF_BYTES`] of `input`.
fn read_head(input: &Path) -> Result<Vec<u8>, Failure> {
    let mut head = Vec::new();
    thermonav_io::open_input(input)
        .and_then(|file| file.take(SNIFF_BYTES).read_to_end(&mut head))
        .map_err(|e| anyhow!("{}: cannot open: {e}", input.display()))
        .data()?;
    Ok(head)
}

/// The format the first bytes fit, or why none or several fit.
fn format_of_content(head: &[u8], tag: &Path) -> Result<ForeignFormatArg, &'static str> {
    if head.starts_with(&thermonav_io::ulog::MAGIC) {
        return Ok(ForeignFormatArg::Px4Ulog);
    }
    if thermonav_io::dataflash::looks_like_dataflash(head) {
        return Ok(ForeignFormatArg::Dataflash);
    }
    if let Some(bag) = thermonav_io::ros::BagFormat::detect(head) {
        return Ok(ros::format_arg(bag));
    }
    if head.starts_with(b"TIMETAG") {
        return Err("an RTKLIB time-tag file: convert the IMU CSV it belongs to");
    }
    let text = String::from_utf8_lossy(head);
    let lines = first_lines(&text);
    let Some(first) = lines.first() else {
        return Err("the file is empty");
    };
    if let Some(format) = format_of_first_line(first) {
        return Ok(format);
    }
    // The first line of a raw IMU log is partial: look at the second.
    let probe = lines.get(1).unwrap_or(first);
    if probe.split(',').count() == 7 {
        return raw_imu_if_tagged(tag);
    }
    format_of_columns(first)
}

/// The first three lines that are not blank.
fn first_lines(text: &str) -> Vec<&str> {
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .take(3)
        .collect()
}

/// RTKLIB `.pos` (a `%` header or a slashed date) or NMEA (`$`), told by the first line alone.
fn format_of_first_line(first: &str) -> Option<ForeignFormatArg> {
    let first_token = first.split_whitespace().next().unwrap_or("");
    if first.starts_with('%') || is_slashed_date(first_token) {
        return Some(ForeignFormatArg::RtklibPos);
    }
    first.starts_with('$').then_some(ForeignFormatArg::Nmea)
}

/// A raw IMU log when its time-tag file is there.
fn raw_imu_if_tagged(tag: &Path) -> Result<ForeignFormatArg, &'static str> {
    match tag.is_file() {
        true => Ok(ForeignFormatArg::RawImuTag),
        false => Err("7 comma-separated fields like a raw IMU log, but no time-tag file"),
    }
}

/// A KF-GINS file told by its number of blank-separated columns.
fn format_of_columns(first: &str) -> Result<ForeignFormatArg, &'static str> {
    match first.split_whitespace().count() {
        11 => Ok(ForeignFormatArg::KfGinsNav),
        13 => Ok(ForeignFormatArg::KfGinsGnss),
        7 => Err("7 blank-separated columns fit both kf-gins-imu and kf-gins-gnss"),
        _ => Err("no known layout"),
    }
}

/// `yyyy/mm/dd`.
fn is_slashed_date(token: &str) -> bool {
    let parts: Vec<&str> = token.split('/').collect();
    parts.len() == 3
        && parts
            .iter()
            .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()))
        && parts[0].len() == 4
}
