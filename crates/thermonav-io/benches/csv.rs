//! Parsing speed of the canonical IMU CSV: a 3-hour 200 Hz log (2.16 M rows, 8 columns), once
//! with full-precision noisy values as the writer produces them (~160 bytes a row, the worst
//! case), once at a sensor's resolution as loggers write them (~75 bytes a row).
//!
//! Run with `cargo bench -p thermonav-io --bench csv`; throughput is reported in bytes/s, and
//! rows/s follows from the row count printed at start. The `imu_csv_*_per_core` groups time the
//! one-thread readers in CPU time of the benchmarking thread (Linux), so that they give the speed
//! per core even while other work shares the machine; the others are wall time.

use criterion::measurement::{Measurement, ValueFormatter, WallTime};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::io::{BufWriter, Write};
use std::path::Path;
use std::time::Duration;
use thermonav_io::{ImuReader, Strictness, read_imu, read_imu_file};

/// 3 h at 200 Hz.
const ROWS: u64 = 3 * 3600 * 200;

/// How many digits the values of a bench file carry.
#[derive(Debug, Clone, Copy)]
enum Digits {
    /// Shortest round-trip form of a random `f64` (`{}`): 16-17 significant digits.
    Full,
    /// Fixed decimals at a MEMS sensor's resolution: 1e-6 rad/s, 1e-4 m/s², 0.01 °C.
    SensorResolution,
}

fn write_values(out: &mut impl Write, values: &[f64; 7], digits: Digits) -> std::io::Result<()> {
    match digits {
        Digits::Full => values.iter().try_for_each(|v| write!(out, ",{v}")),
        Digits::SensorResolution => {
            let [gx, gy, gz, ax, ay, az, t] = values;
            write!(
                out,
                ",{gx:.6},{gy:.6},{gz:.6},{ax:.4},{ay:.4},{az:.4},{t:.2}"
            )
        }
    }
}

/// Writes a rate file with gyro noise of ~0.01 rad/s, accelerometer noise of ~0.05 m/s² about
/// gravity on z, and a slowly drifting temperature.
fn generate(path: &Path, digits: Digits) -> std::io::Result<()> {
    let mut rng = ChaCha8Rng::seed_from_u64(2009);
    let mut out = BufWriter::new(std::fs::File::create(path)?);
    writeln!(
        out,
        "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c"
    )?;
    for row in 0..ROWS {
        let nanos = row * 5_000_000;
        write!(
            out,
            "{}.{:09}",
            nanos / 1_000_000_000,
            nanos % 1_000_000_000
        )?;
        let mut noise = |scale: f64| scale * (rng.random::<f64>() - 0.5);
        let values = [
            noise(0.02),
            noise(0.02),
            noise(0.02),
            noise(0.1),
            noise(0.1),
            -9.80665 + noise(0.1),
            20.0 + row as f64 * 1e-6 + noise(0.01),
        ];
        write_values(&mut out, &values, digits)?;
        writeln!(out)?;
    }
    out.flush()
}

fn imu_csv(c: &mut Criterion) {
    for digits in [Digits::Full, Digits::SensorResolution] {
        bench_file(c, digits);
    }
}

fn imu_csv_per_core(c: &mut Criterion<ThreadCpuTime>) {
    for digits in [Digits::Full, Digits::SensorResolution] {
        bench_file_per_core(c, digits);
    }
}

/// A generated bench file in its temporary directory, and its size in bytes.
fn bench_input(digits: Digits) -> (tempfile::TempDir, std::path::PathBuf, u64) {
    let dir = tempfile::tempdir().expect("temporary directory");
    let path = dir.path().join("imu.csv");
    generate(&path, digits).expect("bench file written");
    let bytes = std::fs::metadata(&path).expect("bench file size").len();
    eprintln!("bench file {digits:?}: {ROWS} rows, {bytes} bytes");
    (dir, path, bytes)
}

fn bench_file(c: &mut Criterion, digits: Digits) {
    let (_dir, path, bytes) = bench_input(digits);
    let mut group = c.benchmark_group(format!("imu_csv_{digits:?}"));
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(20));
    group.throughput(Throughput::Bytes(bytes));
    group.bench_function("read_imu_file", |b| {
        b.iter(|| read_imu_file(&path, Strictness::Strict).expect("bench file reads"))
    });
    group.bench_function("stream_count", |b| b.iter(|| stream_count(&path)));
    group.finish();
}

fn bench_file_per_core(c: &mut Criterion<ThreadCpuTime>, digits: Digits) {
    let (_dir, path, bytes) = bench_input(digits);
    let mut group = c.benchmark_group(format!("imu_csv_{digits:?}_per_core"));
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(10));
    group.throughput(Throughput::Bytes(bytes));
    group.bench_function("read_imu_one_thread", |b| {
        b.iter(|| {
            let file = std::fs::File::open(&path).expect("bench file opens");
            read_imu(
                std::io::BufReader::with_capacity(1 << 18, file),
                "bench",
                Strictness::Strict,
            )
            .expect("bench file reads")
        })
    });
    group.bench_function("stream_count", |b| b.iter(|| stream_count(&path)));
    group.finish();
}

/// Sum of the x gyro over the streaming reader (no series built).
fn stream_count(path: &Path) -> f64 {
    let reader = ImuReader::open(path, Strictness::Strict).expect("bench file opens");
    reader.map(|s| s.expect("row reads").gyro[0]).sum::<f64>()
}

/// CPU time of the benchmarking thread in ns (Linux: the first field of
/// `/proc/thread-self/schedstat`), for timing one-thread work on a shared machine.
struct ThreadCpuTime;

/// Formats nanoseconds as criterion's wall clock does.
static WALL_TIME: WallTime = WallTime;

fn thread_cpu_ns() -> u64 {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat")
        .expect("/proc/thread-self/schedstat (Linux) is readable");
    text.split_whitespace()
        .next()
        .and_then(|field| field.parse().ok())
        .expect("schedstat starts with the CPU time in ns")
}

impl Measurement for ThreadCpuTime {
    type Intermediate = u64;
    type Value = u64;

    fn start(&self) -> u64 {
        thread_cpu_ns()
    }

    fn end(&self, start: u64) -> u64 {
        thread_cpu_ns().saturating_sub(start)
    }

    fn add(&self, a: &u64, b: &u64) -> u64 {
        a + b
    }

    fn zero(&self) -> u64 {
        0
    }

    fn to_f64(&self, value: &u64) -> f64 {
        *value as f64
    }

    fn formatter(&self) -> &dyn ValueFormatter {
        WALL_TIME.formatter()
    }
}

criterion_group!(benches, imu_csv);
criterion_group! {
    name = per_core;
    config = Criterion::default().with_measurement(ThreadCpuTime);
    targets = imu_csv_per_core
}
criterion_main!(benches, per_core);
