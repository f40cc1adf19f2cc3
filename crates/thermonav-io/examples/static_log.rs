//! Writes a long static IMU record (canonical CSV) without holding it in memory, for the
//! bounded-memory characterisation measurement (`bench/day_at_1khz.sh`).
//!
//! Usage: `static_log OUT.csv HOURS RATE_HZ`. Each channel: the static signal plus white noise
//! plus a first-order Gauss-Markov bias (Tc 300 s), seeded; temp_c a constant 25 °C plus
//! 0.01 °C white noise.

use std::fs::File;
use std::io::BufWriter;
use thermonav::imu::{ImuSample, SampleKind};
use thermonav::rng::named_rng;
use thermonav::sim::errors::{gauss_markov_step, standard_normal};
use thermonav::time::Timestamp;
use thermonav_io::{ImuWriter, TemperatureColumn};

/// Static signal, white-noise sigma and GM sigma per channel (rad/s, m/s^2).
const CHANNELS: [(f64, f64, f64); 6] = [
    (5.0e-5, 2.0e-3, 1.0e-4),
    (0.0, 2.0e-3, 1.0e-4),
    (-5.6e-5, 2.0e-3, 1.0e-4),
    (0.0, 5.0e-3, 2.0e-4),
    (0.0, 5.0e-3, 2.0e-4),
    (-9.81, 5.0e-3, 2.0e-4),
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let [_, out, hours, rate] = args.as_slice() else {
        return Err("usage: static_log OUT.csv HOURS RATE_HZ".into());
    };
    let (hours, rate_hz): (f64, f64) = (hours.parse()?, rate.parse()?);
    let rows = (hours * 3600.0 * rate_hz).round() as u64;
    let dt_s = 1.0 / rate_hz;
    let step_ns = (1e9 / rate_hz).round() as i64;
    let mut rng = named_rng(2024, "static_log");
    let mut bias = [0.0_f64; 6];
    let mut writer = ImuWriter::new(
        BufWriter::with_capacity(1 << 20, File::create(out)?),
        SampleKind::Rates,
        TemperatureColumn::Written,
    )?;
    for k in 0..rows {
        let mut value = [0.0; 6];
        for (c, &(signal, white, gm)) in CHANNELS.iter().enumerate() {
            bias[c] = gauss_markov_step(bias[c], dt_s, 300.0, gm, standard_normal(&mut rng));
            value[c] = signal + bias[c] + white * standard_normal(&mut rng);
        }
        writer.write_sample(&ImuSample {
            time: Timestamp::from_nanos(k as i64 * step_ns),
            gyro: [value[0], value[1], value[2]],
            accel: [value[3], value[4], value[5]],
            temperature_c: Some(25.0 + 0.01 * standard_normal(&mut rng)),
        })?;
    }
    writer.finish()?;
    Ok(())
}
