//! Times the canonical IMU CSV reader on one file, for `bench/compare.py`.
//!
//! Usage: `imu_csv_timing FILE OUT_PREFIX`. Prints one JSON line with the file size and the
//! best-of-3 times of [`read_imu_file`] (large files in two halves on two threads, `_s`) and of
//! the same read in one pass on one thread (`_1t_s`, [`FileSplit::OnePass`], as `characterize`
//! reads each record of a campaign), the least CPU time of that thread over the three
//! runs (`read_1t_cpu_s`, from Linux's `/proc/thread-self/schedstat`; absent elsewhere), which
//! gives the speed per core when other work shares the cores, and writes OUT_PREFIX.f64: t_s, the six channels and
//! temp_c as they were read, one column after the other in little-endian f64, so that the script
//! can compare them with pandas value by value.

use std::time::Instant;
use thermonav::imu::ImuSeries;
use thermonav_io::{
    FileSplit, ImuOptions, ReadError, Strictness, read_imu_file, read_imu_file_with,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 3 {
        return Err("usage: imu_csv_timing FILE OUT_PREFIX".into());
    }
    let path = &args[1];
    let bytes = std::fs::metadata(path)?.len();
    let (best, series) = best_of_3(|| read_imu_file(path, Strictness::Strict))?;
    let cpu_s = std::cell::Cell::new(f64::INFINITY);
    let (best_1t, _) = best_of_3(|| {
        let start = thread_cpu_s();
        let one_pass = ImuOptions {
            split: FileSplit::OnePass,
            ..ImuOptions::default()
        };
        let series = read_imu_file_with(path, Strictness::Strict, &one_pass);
        if let (Some(start), Some(end)) = (start, thread_cpu_s()) {
            cpu_s.set(cpu_s.get().min(end - start));
        }
        series
    })?;
    let cpu = match cpu_s.get() {
        s if s.is_finite() => format!(",\"read_1t_cpu_s\":{s}"),
        _ => String::new(),
    };
    std::fs::write(format!("{}.f64", args[2]), columns_le_bytes(&series))?;
    println!(
        "{{\"bytes\":{bytes},\"rows\":{},\"read_s\":{best},\"read_1t_s\":{best_1t}{cpu}}}",
        series.len()
    );
    Ok(())
}

/// The shortest of three runs of `read`, s, and its last series.
fn best_of_3(
    read: impl Fn() -> Result<ImuSeries, ReadError>,
) -> Result<(f64, ImuSeries), ReadError> {
    let mut best = f64::INFINITY;
    let mut series = ImuSeries::default();
    for _ in 0..3 {
        let start = Instant::now();
        series = read()?;
        best = best.min(start.elapsed().as_secs_f64());
    }
    Ok((best, series))
}

/// CPU time of the calling thread so far, s (Linux: the first field of
/// `/proc/thread-self/schedstat`, in ns).
fn thread_cpu_s() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let nanos: u64 = text.split_whitespace().next()?.parse().ok()?;
    Some(nanos as f64 * 1e-9)
}

/// t_s, the channels and the temperature (when present), column after column.
fn columns_le_bytes(series: &ImuSeries) -> Vec<u8> {
    let time = series.time.iter().map(|t| t.as_seconds());
    let channels = series.channels.iter().flatten().copied();
    let temperature = series.temperature_c.iter().flatten().copied();
    time.chain(channels)
        .chain(temperature)
        .flat_map(f64::to_le_bytes)
        .collect()
}
