//! Times octave and decade overlapping Allan deviation of a raw little-endian f64 file, for
//! `bench/compare.py`. Usage: `allan_timing FILE RATE_HZ OUT_PREFIX`; prints one JSON line with
//! best-of-3 times and writes OUT_PREFIX.{octave,decade}.f64 (the deviations) for comparison.

use std::time::Instant;
use thermonav::stoch::allan::{TauGrid, overlapping_adev};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 4 {
        return Err("usage: allan_timing FILE RATE_HZ OUT_PREFIX".into());
    }
    let bytes = std::fs::read(&args[1])?;
    let y: Vec<f64> = bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
        .collect();
    let rate: f64 = args[2].parse()?;
    let mut times = Vec::new();
    for (name, grid) in [("octave", TauGrid::Octave), ("decade", TauGrid::Decade)] {
        let mut best = f64::INFINITY;
        let mut curve = None;
        for _ in 0..3 {
            let start = Instant::now();
            curve = Some(overlapping_adev(&y, rate, &grid)?);
            best = best.min(start.elapsed().as_secs_f64());
        }
        let adev = curve.map(|c| c.adev).unwrap_or_default();
        let raw: Vec<u8> = adev.iter().flat_map(|v| v.to_le_bytes()).collect();
        std::fs::write(format!("{}.{name}.f64", args[3]), raw)?;
        times.push(best);
    }
    println!(
        "{{\"samples\":{},\"octave_s\":{},\"decade_s\":{}}}",
        y.len(),
        times[0],
        times[1]
    );
    Ok(())
}
