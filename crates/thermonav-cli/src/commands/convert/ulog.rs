//! `thermonav convert LOG.ulg`: a PX4 ULog to the canonical IMU CSV (`--out`), optionally the
//! canonical GNSS CSV (`--gnss-out`), and a sidecar `OUT.json` saying what was read: the topics,
//! the time scale (GPST from GNSS UTC time, or seconds since boot), what was skipped.
//! Everything is read and checked before the first file is written.

use crate::args::ConvertArgs;
use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use serde::Serialize;
use thermonav_io::ulog::px4::{
    GnssExtract, ImuExtract, TimeScale, gnss_fixes, imu_series, time_scale,
};
use thermonav_io::ulog::{Ulog, read_ulog_file};

/// This format's sidecar.
type UlogRecord<'a> = super::LogSidecar<'a, TimeScale, ImuExtract, GnssExtract, LogSummary>;

/// The container's own figures.
#[derive(Serialize)]
struct LogSummary {
    ulog_version: u8,
    start_timestamp_us: u64,
    last_timestamp_us: u64,
    dropouts: usize,
    dropout_total_ms: u64,
    skipped_unknown_type_messages: usize,
    skipped_unsubscribed_data_messages: usize,
    truncated_tail_bytes: usize,
}

impl LogSummary {
    /// The figures of one parsed log.
    fn of(log: &Ulog) -> Self {
        Self {
            ulog_version: log.version,
            start_timestamp_us: log.start_timestamp_us,
            last_timestamp_us: log.last_timestamp_us,
            dropouts: log.dropouts_ms.len(),
            dropout_total_ms: log.dropouts_ms.iter().map(|&d| u64::from(d)).sum(),
            skipped_unknown_type_messages: log.skipped.unknown_types.values().sum(),
            skipped_unsubscribed_data_messages: log.skipped.unsubscribed_data,
            truncated_tail_bytes: log.skipped.truncated_tail_bytes,
        }
    }
}

/// Converts a ULog; returns the number of IMU samples and what they are.
pub fn convert(args: &ConvertArgs) -> Result<(usize, &'static str), Failure> {
    let input = args.input.display().to_string();
    let leap = super::gpst_minus_utc(args)?;
    let log = read_ulog_file(&args.input).data()?;
    let scale = time_scale(&log, leap);
    let mut imu = imu_series(&log, &input, scale).data()?;
    let options = crate::settings::imu::rotation_only(&args.rotation);
    imu.series = crate::inputs::to_body(imu.series, &options);
    let gnss = match &args.gnss_out {
        Some(_) => Some(gnss_fixes(&log, &input, scale).data()?),
        None => None,
    };
    let record = UlogRecord {
        input,
        time_scale: scale,
        time_scale_note: time_scale_note(scale),
        imu: &imu,
        imu_rotation: crate::settings::imu::rotation_text(&options),
        imu_samples: imu.series.len(),
        gnss: gnss.as_ref(),
        gnss_fixes: gnss.as_ref().map(|g| g.fixes.len()),
        log: LogSummary::of(&log),
    };
    report_notes(&record);
    let fixes = gnss.as_ref().map(|g| g.fixes.as_slice());
    super::write_log_outputs(args, &imu.series, fixes, &record)?;
    Ok((imu.series.len(), imu_samples_kind(imu.topic)))
}

/// What the `t_s` column means on this time scale.
fn time_scale_note(scale: TimeScale) -> &'static str {
    match scale {
        TimeScale::Gpst { .. } => "t_s is GPST seconds since 1970 (no leap seconds)",
        TimeScale::Boot => {
            "t_s is seconds since the autopilot booted: the log has no GNSS UTC time"
        }
    }
}

/// Increments from `vehicle_imu`, rates from the raw sensor topics.
fn imu_samples_kind(topic: &str) -> &'static str {
    match topic {
        "vehicle_imu" => "IMU samples (increments)",
        _ => "IMU samples (rates)",
    }
}

/// Notes on stderr about the time scale, temperature and skipped messages.
fn report_notes(record: &UlogRecord<'_>) {
    if record.time_scale == TimeScale::Boot {
        eprintln!("note: {}", record.time_scale_note);
    }
    if record.imu.temperature_source.is_none() {
        eprintln!(
            "note: no IMU temperature topic (sensor_accel, vehicle_imu_status, sensor_gyro): \
             no temp_c column"
        );
    }
    let skipped = record.log.skipped_unknown_type_messages;
    if skipped > 0 {
        eprintln!("note: {skipped} messages of unknown type skipped");
    }
    if record.log.truncated_tail_bytes > 0 {
        eprintln!(
            "note: the log ends in a partial message ({} bytes), dropped",
            record.log.truncated_tail_bytes
        );
    }
}

/// The error for options that make no sense with a ULog.
pub fn reject_gnss_out(args: &ConvertArgs) -> Result<(), Failure> {
    match &args.gnss_out {
        Some(_) => Err(anyhow!(
            "--gnss-out goes with --format px4-ulog, ros2-mcap, ros2-db3, ros1-bag or dataflash only"
        ))
        .usage(),
        None => Ok(()),
    }
}
