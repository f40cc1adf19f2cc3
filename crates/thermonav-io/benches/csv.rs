//! Parsing speed of the canonical IMU CSV: a 3-hour 200 Hz log (2.16 M rows, 8 columns), once
//! with full-precision noisy values as the writer produces them (~160 bytes a row, the worst
//! case), once at a sensor's resolution as loggers write them (~75 bytes a row).
//!
//! Run with `cargo bench -p thermonav-io --bench csv`; throughput is reported in bytes/s, and
//! rows/s follows from the row count printed at start.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::io::{BufWriter, Write};
use std::path::Path;
use std::time::Duration;
use thermonav_io::{ImuReader, Strictness, read_imu_file};

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

fn bench_file(c: &mut Criterion, digits: Digits) {
    let dir = tempfile::tempdir().expect("temporary directory");
    let path = dir.path().join("imu.csv");
    generate(&path, digits).expect("bench file written");
    let bytes = std::fs::metadata(&path).expect("bench file size").len();
    eprintln!("bench file {digits:?}: {ROWS} rows, {bytes} bytes");

    let mut group = c.benchmark_group(format!("imu_csv_{digits:?}"));
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(20));
    group.throughput(Throughput::Bytes(bytes));
    group.bench_function("read_imu_file", |b| {
        b.iter(|| read_imu_file(&path, Strictness::Strict).expect("bench file reads"))
    });
    group.bench_function("stream_count", |b| {
        b.iter(|| {
            let reader = ImuReader::open(&path, Strictness::Strict).expect("bench file opens");
            reader.map(|s| s.expect("row reads").gyro[0]).sum::<f64>()
        })
    });
    group.finish();
}

criterion_group!(benches, imu_csv);
criterion_main!(benches);
