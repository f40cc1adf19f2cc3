//! Times zero-phase Kaiser filtering of a raw little-endian f64 file, for
//! `bench/compare.py`: prints one JSON line with best-of-3 times and the outputs' checksums.
//!
//! Usage: `filter_timing FILE FS_HZ CUTOFF_HZ TRANSITION_HZ RIPPLE_DB OUT_PREFIX`; writes
//! OUT_PREFIX.filtfilt.f64 so the script can compare with SciPy sample by sample.

use std::time::Instant;
use thermonav::signal::kaiser::{KaiserSpec, design_kaiser_lowpass};
use thermonav::signal::zero_phase::{ZeroPhaseMode, filter_zero_phase};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 7 {
        return Err(
            "usage: filter_timing FILE FS_HZ CUTOFF_HZ TRANSITION_HZ RIPPLE_DB OUT_PREFIX".into(),
        );
    }
    let bytes = std::fs::read(&args[1])?;
    let x: Vec<f64> = bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
        .collect();
    let numbers: Vec<f64> = args[2..6]
        .iter()
        .map(|a| a.parse())
        .collect::<Result<_, _>>()?;
    let filter = design_kaiser_lowpass(&KaiserSpec::new(
        numbers[0], numbers[1], numbers[2], numbers[3],
    )?)?;
    let mut times = Vec::new();
    let mut outputs = Vec::new();
    for mode in [
        ZeroPhaseMode::DelayCompensated,
        ZeroPhaseMode::ForwardBackward,
    ] {
        let mut best = f64::INFINITY;
        let mut y = Vec::new();
        for _ in 0..3 {
            let start = Instant::now();
            y = filter_zero_phase(&filter, &x, mode)?;
            best = best.min(start.elapsed().as_secs_f64());
        }
        times.push(best);
        outputs.push(y);
    }
    let raw: Vec<u8> = outputs[1].iter().flat_map(|v| v.to_le_bytes()).collect();
    std::fs::write(format!("{}.filtfilt.f64", args[6]), raw)?;
    println!(
        "{{\"num_taps\":{},\"samples\":{},\"zero_phase_s\":{},\"filtfilt_s\":{}}}",
        filter.num_taps(),
        x.len(),
        times[0],
        times[1]
    );
    Ok(())
}
