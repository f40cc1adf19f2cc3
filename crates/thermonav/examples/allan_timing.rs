//! Times octave and decade overlapping Allan deviation of a raw little-endian f64 file, for
//! `bench/compare.py`. Usage: `allan_timing FILE RATE_HZ OUT_PREFIX`; prints one JSON line with
//! best-of-3 times on the default rayon pool (all cores) and on a one-thread pool (`_1t_s`), and
//! writes OUT_PREFIX.{octave,decade}.f64 (the deviations) for comparison.

use std::time::Instant;
use thermonav::stoch::allan::{AllanError, TauGrid, overlapping_adev};

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
    let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let mut times = Vec::new();
    for (name, grid) in [("octave", TauGrid::Octave), ("decade", TauGrid::Decade)] {
        let (best, adev) = best_of_3(&y, rate, &grid)?;
        let raw: Vec<u8> = adev.iter().flat_map(|v| v.to_le_bytes()).collect();
        std::fs::write(format!("{}.{name}.f64", args[3]), raw)?;
        let (best_1t, _) = one_thread.install(|| best_of_3(&y, rate, &grid))?;
        times.push((best, best_1t));
    }
    println!(
        "{{\"samples\":{},\"threads\":{},\"octave_s\":{},\"decade_s\":{},\"octave_1t_s\":{},\"decade_1t_s\":{}}}",
        y.len(),
        rayon::current_num_threads(),
        times[0].0,
        times[1].0,
        times[0].1,
        times[1].1
    );
    Ok(())
}

/// The shortest of three runs, s, and the deviations.
fn best_of_3(y: &[f64], rate: f64, grid: &TauGrid) -> Result<(f64, Vec<f64>), AllanError> {
    let mut best = f64::INFINITY;
    let mut adev = Vec::new();
    for _ in 0..3 {
        let start = Instant::now();
        adev = overlapping_adev(y, rate, grid)?.adev;
        best = best.min(start.elapsed().as_secs_f64());
    }
    Ok((best, adev))
}
