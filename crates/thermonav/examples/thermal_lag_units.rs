//! The sweep calibration on simulated units whose MEMS structure lags its temperature sensor:
//! is the lag found, does its interval hold the truth, does it predict an unseen cycle better
//! than the curve in T alone, and is it left out when there is none?
//!
//! Each unit runs a chamber program 25 → −5 → 55 → 25 °C at ±R °C/min with 10-minute dwells at
//! the turns, logged at 2 Hz. Its structure follows the sensor's temperature through a
//! first-order lag, dT_s/dt = (T − T_s)/τ_true, with τ_true drawn per channel from 30..300 s (or
//! 0: no lag), and each channel reads b(T_s) = c1 (T_s − 20) + c2 (T_s − 20)² with c1, c2 drawn
//! per channel (c1 of 0.5..1.5 times a typical sensitivity, either sign), plus white noise. To first order T_s ≈ T − τ_true dT/dt, so the fitted τ of
//! b(T + τ dT/dt) should be −τ_true.
//!
//! For each unit a second cycle (new noise, same unit) is held out: the shape RMS of the
//! 30 s block residuals (`bank check`'s `rms_after_offset_removed`) of the chosen model against
//! that of the best curve in T alone.
//!
//! `cargo run --release -p thermonav --example thermal_lag_units [-- UNITS]`

use rand::SeedableRng;
use rand_distr::{Distribution, Normal, Uniform};
use std::collections::BTreeMap;
use thermonav::imu::{Channel, ImuSeries, SampleKind, Sensor};
use thermonav::rng::named_rng;
use thermonav::stoch::thermal::check::check_record;
use thermonav::stoch::thermal::sweep_model::{SweepPiece, calibrate_from_sweeps, sweep_blocks};
use thermonav::stoch::thermal::{ScaleFactorCalibration, ThermalCalibration};
use thermonav::time::Timestamp;

const RATE_HZ: f64 = 2.0;
const DWELL_S: f64 = 600.0;

/// One simulated unit: per channel τ_true (s) and the curve's c1, c2.
struct Unit {
    tau_s: [f64; 6],
    c1: [f64; 6],
    c2: [f64; 6],
    noise: [f64; 6],
}

/// The chamber program's temperature at `t` s for `rate` °C/min.
fn program(t: f64, rate_c_per_min: f64) -> f64 {
    let r = rate_c_per_min / 60.0;
    let legs: [(f64, f64); 3] = [(25.0, -5.0), (-5.0, 55.0), (55.0, 25.0)];
    let mut start = 0.0;
    for (from, to) in legs {
        let ramp = (to - from).abs() / r;
        if t < start + ramp {
            return from + (to - from).signum() * r * (t - start);
        }
        start += ramp;
        if t < start + DWELL_S {
            return to;
        }
        start += DWELL_S;
    }
    25.0
}

fn duration_s(rate_c_per_min: f64) -> f64 {
    120.0 / (rate_c_per_min / 60.0) + 3.0 * DWELL_S
}

fn draw_unit(seed: u64, lagging: bool) -> Unit {
    let mut rng = named_rng(seed, "thermal lag unit");
    let tau = Uniform::new(30.0, 300.0).expect("a range");
    let normal = Normal::new(0.0, 1.0).expect("unit normal");
    let magnitude = Uniform::new(0.5, 1.5).expect("a range");
    let mut unit = Unit {
        tau_s: [0.0; 6],
        c1: [0.0; 6],
        c2: [0.0; 6],
        noise: [0.0; 6],
    };
    for c in Channel::ALL {
        let k = c.index();
        // Gyros: about 10 deg/h per °C (4.8e-5 rad/s), noise 2e-4 rad/s a sample; accelerometers
        // about 0.2 mg per °C (2e-3 m/s²), noise 2e-3 m/s² a sample.
        let (slope, noise) = match c.sensor() {
            Sensor::Gyro => (4.8e-5, 2e-4),
            Sensor::Accelerometer => (2e-3, 2e-3),
        };
        unit.tau_s[k] = if lagging { tau.sample(&mut rng) } else { 0.0 };
        // A sensitivity of 0.5..1.5 times the typical slope, either sign: a channel without
        // one has no lag to find.
        let sign = if normal.sample(&mut rng) < 0.0 {
            -1.0
        } else {
            1.0
        };
        unit.c1[k] = sign * slope * magnitude.sample(&mut rng);
        unit.c2[k] = slope / 30.0 * normal.sample(&mut rng);
        unit.noise[k] = noise;
    }
    unit
}

/// A cycle of `unit` with noise from `noise_seed`.
fn record(unit: &Unit, rate_c_per_min: f64, noise_seed: u64) -> ImuSeries {
    let n = (duration_s(rate_c_per_min) * RATE_HZ) as usize;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(noise_seed);
    let normal = Normal::new(0.0, 1.0).expect("unit normal");
    let mut series = ImuSeries::new(SampleKind::Rates);
    let dt = 1.0 / RATE_HZ;
    let mut structure = [program(0.0, rate_c_per_min); 6];
    let mut temperatures = Vec::with_capacity(n);
    for k in 0..n {
        let t = k as f64 * dt;
        let sensor = program(t, rate_c_per_min);
        series.time.push(Timestamp::from_nanos((t * 1e9) as i64));
        temperatures.push(sensor);
        for c in Channel::ALL {
            let i = c.index();
            if unit.tau_s[i] > 0.0 && k > 0 {
                // The first-order lag's closed form over an interval where the program's
                // temperature is linear (it is piecewise linear, with its knots on samples at
                // the rates used): T_s(dt) = T(dt) − τm + (T_s(0) − T(0) + τm) e^(−dt/τ).
                let tau = unit.tau_s[i];
                let before = program(t - dt, rate_c_per_min);
                let m = (sensor - before) / dt;
                let a = (-dt / tau).exp();
                structure[i] = sensor - tau * m + (structure[i] - before + tau * m) * a;
            } else {
                structure[i] = sensor;
            }
            let d = structure[i] - 20.0;
            let bias = unit.c1[i] * d + unit.c2[i] * d * d;
            series.channels[i].push(bias + unit.noise[i] * normal.sample(&mut rng));
        }
    }
    series.temperature_c = Some(temperatures);
    series
}

fn calibration_of(series: &ImuSeries) -> ThermalCalibration {
    let time: Vec<f64> = series.time.iter().map(|t| t.as_seconds()).collect();
    let temperatures = series.temperature_c.as_deref().expect("temperatures");
    let columns: Vec<(Channel, &[f64], f64)> = Channel::ALL
        .iter()
        .map(|&c| (c, series.channel(c), 0.0))
        .collect();
    let piece = SweepPiece {
        time_s: &time,
        temperature_c: temperatures,
        channels: &columns,
    };
    let block_s = thermonav::stoch::thermal::sweep_model::default_block_s(&time, temperatures);
    let (blocks, _) = sweep_blocks(piece, 1, 1, block_s).expect("a valid sweep");
    ThermalCalibration {
        channels: calibrate_from_sweeps(&blocks).expect("a calibration"),
        power_ons: 1,
        scale_factor: ScaleFactorCalibration::static_sweeps(),
        removed_signal: BTreeMap::new(),
        observations: BTreeMap::new(),
        devices: None,
        legs: Vec::new(),
        sweep_blocks: blocks,
    }
}

/// Per channel: (lag chosen, τ̂ and its interval, held-out shape RMS chosen / T alone).
struct UnitResult {
    lag_chosen: [bool; 6],
    covered: [bool; 6],
    ratio: [f64; 6],
}

fn run_unit(unit: &Unit, rate: f64, seed: u64) -> UnitResult {
    let fitted = record(unit, rate, seed * 2 + 1);
    let unseen = record(unit, rate, seed * 2 + 2);
    let calibration = calibration_of(&fitted);
    let mut t_only = calibration.clone();
    t_only.channels.values_mut().for_each(|c| c.lagged = None);
    let chosen = check_record(&calibration, &unseen, 30.0, None).expect("a check");
    let alone = check_record(&t_only, &unseen, 30.0, None).expect("a check");
    let mut out = UnitResult {
        lag_chosen: [false; 6],
        covered: [false; 6],
        ratio: [1.0; 6],
    };
    for c in Channel::ALL {
        let i = c.index();
        let cal = &calibration.channels[&c];
        out.lag_chosen[i] = cal.lagged.is_some();
        out.covered[i] = cal.lagged.as_ref().is_some_and(|l| {
            let truth = -unit.tau_s[i];
            let [lo, hi] = l.lag.tau_interval_s;
            lo.is_none_or(|lo| lo <= truth) && hi.is_none_or(|hi| truth <= hi)
        });
        out.ratio[i] = chosen[&c].rms_after_offset_removed / alone[&c].rms_after_offset_removed;
    }
    out
}

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

fn main() {
    let units: u64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(20);
    println!("{units} units per case; per channel gx gy gz ax ay az");
    for rate in [2.0, 5.0] {
        let results: Vec<UnitResult> = (0..units)
            .map(|s| run_unit(&draw_unit(s, true), rate, s))
            .collect();
        let count = |f: &dyn Fn(&UnitResult, usize) -> bool| -> Vec<usize> {
            (0..6)
                .map(|i| results.iter().filter(|r| f(r, i)).count())
                .collect()
        };
        let ratios: Vec<f64> = (0..6)
            .map(|i| median(results.iter().map(|r| r.ratio[i]).collect()))
            .collect();
        println!("±{rate} °C/min, lagging units (τ_true 30..300 s):");
        println!(
            "  lag chosen:               {:?} of {units}",
            count(&|r, i| r.lag_chosen[i])
        );
        println!(
            "  -τ_true in τ's 95 % interval: {:?} of {units}",
            count(&|r, i| r.covered[i])
        );
        println!(
            "  held-out shape RMS, chosen / T alone, median: {}",
            ratios
                .iter()
                .map(|r| format!("{r:.3}"))
                .collect::<Vec<_>>()
                .join(" ")
        );
        let none: Vec<UnitResult> = (0..units)
            .map(|s| run_unit(&draw_unit(1000 + s, false), rate, 1000 + s))
            .collect();
        let chosen: usize = none
            .iter()
            .map(|r| r.lag_chosen.iter().filter(|&&b| b).count())
            .sum();
        println!(
            "±{rate} °C/min, units without lag: lag chosen on {chosen} of {} channels",
            6 * units
        );
    }
}
