//! Times the octave overlapping Allan deviation of a raw little-endian f64 file.
//!
//! Usage: `cargo run --release -p thermonav --example allan_timing -- FILE [RATE_HZ]`
//!
//! Prints the best wall time of five runs (`elapsed_s <seconds>`), then one line per
//! averaging factor: `m n_terms oadev` (oadev with 17 significant digits). Used by
//! `bench/allan_vs_allantools.py` to compare speed and values with allantools.

use std::process::ExitCode;
use std::time::Instant;

use thermonav::stoch::allan::{AllanCurve, TauGrid, overlapping_adev};

fn read_f64_le(path: &str) -> Result<Vec<f64>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
    if bytes.len() % 8 != 0 {
        return Err(format!(
            "{path}: {} bytes is not a whole number of f64",
            bytes.len()
        ));
    }
    Ok(bytes
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes(b.try_into().expect("chunks of 8")))
        .collect())
}

fn best_of_five(y: &[f64], rate_hz: f64) -> Result<(f64, AllanCurve), String> {
    let mut best = f64::INFINITY;
    let mut curve = None;
    for _ in 0..5 {
        let start = Instant::now();
        let c = overlapping_adev(y, rate_hz, &TauGrid::Octave).map_err(|e| e.to_string())?;
        best = best.min(start.elapsed().as_secs_f64());
        curve = Some(c);
    }
    Ok((best, curve.expect("five runs")))
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args.first().ok_or("usage: allan_timing FILE [RATE_HZ]")?;
    let rate_hz: f64 = match args.get(1) {
        Some(r) => r.parse().map_err(|e| format!("rate {r}: {e}"))?,
        None => 100.0,
    };
    let y = read_f64_le(path)?;
    let (elapsed_s, curve) = best_of_five(&y, rate_hz)?;
    println!("elapsed_s {elapsed_s:.6}");
    for ((m, n), adev) in curve
        .averaging_factor
        .iter()
        .zip(&curve.n_terms)
        .zip(&curve.adev)
    {
        println!("{m} {n} {adev:.16e}");
    }
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("allan_timing: {e}");
            ExitCode::FAILURE
        }
    }
}
