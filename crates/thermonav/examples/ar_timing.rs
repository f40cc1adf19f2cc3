//! Times Burg and Yule-Walker AR(4) on a raw little-endian f64 file, for `bench/compare.py`.
//! Usage: `ar_timing FILE`; prints one JSON line with best-of-3 times and the coefficients.

use std::time::Instant;
use thermonav::stoch::ar::{ArMethod, fit_ar};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 2 {
        return Err("usage: ar_timing FILE".into());
    }
    let bytes = std::fs::read(&args[1])?;
    let x: Vec<f64> = bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
        .collect();
    let mut out = Vec::new();
    for method in [ArMethod::Burg, ArMethod::YuleWalker] {
        let mut best = f64::INFINITY;
        let mut coefficients = Vec::new();
        for _ in 0..3 {
            let start = Instant::now();
            coefficients = fit_ar(&x, 4, method)?.coefficients;
            best = best.min(start.elapsed().as_secs_f64());
        }
        out.push(format!(
            "\"{}_s\":{best},\"{}_phi\":{coefficients:?}",
            method.name().replace('-', "_"),
            method.name().replace('-', "_")
        ));
    }
    println!("{{\"samples\":{},{}}}", x.len(), out.join(","));
    Ok(())
}
