//! `thermonav convert LOG.bin`: an ArduPilot DataFlash log to the canonical IMU CSV (`--out`,
//! one IMU instance, FRD as logged, `temp_c` from its `T`), optionally the canonical GNSS CSV
//! (`--gnss-out`, GPS with GPA accuracies), and a sidecar `OUT.json` saying what was read: the
//! instances, the time scale (GPST from the GPS week and time of week, or seconds since boot),
//! the units and what was skipped. Everything is read and checked before the first file is
//! written.

use crate::args::{ConvertArgs, ForeignFormatArg};
use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use serde::Serialize;
use thermonav_io::dataflash::ardupilot::{
    GnssExtract, ImuExtract, TimeScale, gnss_fixes, imu_series, time_scale,
};
use thermonav_io::dataflash::{DataFlash, read_dataflash_file};

/// This format's sidecar.
type DataFlashRecord<'a> = super::LogSidecar<'a, TimeScale, ImuExtract, GnssExtract, LogSummary>;

/// The container's own figures.
#[derive(Serialize)]
struct LogSummary {
    records: usize,
    message_types: usize,
    truncated_tail_bytes: usize,
}

impl LogSummary {
    /// The figures of one decoded log.
    fn of(log: &DataFlash) -> Self {
        Self {
            records: log.record_count(),
            message_types: log.message_types().count(),
            truncated_tail_bytes: log.truncated_tail_bytes,
        }
    }
}

/// Converts a DataFlash log; returns the number of IMU samples and what they are.
pub fn convert(args: &ConvertArgs) -> Result<(usize, &'static str), Failure> {
    let input = args.input.display().to_string();
    let log = read_dataflash_file(&args.input).data()?;
    let scale = time_scale(&log);
    let mut imu = imu_series(&log, args.imu_instance, "--imu-instance", &input, scale).data()?;
    let options = crate::settings::imu::rotation_only(&args.rotation);
    imu.series = crate::inputs::to_body(imu.series, &options);
    let gnss = match &args.gnss_out {
        Some(_) => Some(gnss_fixes(&log, &input, scale).data()?),
        None => None,
    };
    let record = DataFlashRecord {
        input,
        time_scale: scale,
        time_scale_note: scale.note(),
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
    Ok((imu.series.len(), "IMU samples (rates)"))
}

/// Notes on stderr about the time scale and a partial last record.
fn report_notes(record: &DataFlashRecord<'_>) {
    if record.time_scale == TimeScale::Boot {
        eprintln!("note: {}", record.time_scale_note);
    }
    if record.log.truncated_tail_bytes > 0 {
        eprintln!(
            "note: the log ends in a partial record ({} bytes), dropped",
            record.log.truncated_tail_bytes
        );
    }
}

/// Refuses `--imu-instance` for a format that is not a DataFlash log.
pub fn reject_instance(format: ForeignFormatArg, args: &ConvertArgs) -> Result<(), Failure> {
    match args.imu_instance.is_some() && format != ForeignFormatArg::Dataflash {
        true => Err(anyhow!("--imu-instance goes with --format dataflash only")).usage(),
        false => Ok(()),
    }
}
