//! Times `fit_ar` on a raw little-endian `f64` file and prints the fits as JSON, for
//! `bench/ar_vs_statsmodels.py`, which compares them with statsmodels.
//!
//! ```text
//! cargo run --release -p thermonav --example ar_timing -- FILE [ORDER]
//! ```
//!
//! For each method: the best of three wall-clock times of one `fit_ar(x, Order::Fixed(ORDER),
//! method)` call (mean removal, validation and fitting included), the coefficients and the
//! innovation variance.

use std::process::ExitCode;
use std::time::Instant;

use serde_json::json;
use thermonav::stoch::ar::{ArMethod, ArModel, Order, fit_ar};

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("ar_timing: {message}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args.first().ok_or("usage: ar_timing FILE [ORDER]")?;
    let order: usize = match args.get(1) {
        Some(s) => s.parse().map_err(|e| format!("ORDER '{s}': {e}"))?,
        None => 4,
    };
    let x = read_f64_le(path)?;
    let mut fits = serde_json::Map::new();
    for method in ArMethod::ALL {
        let (seconds, model) = best_of_three(&x, order, method)?;
        fits.insert(method.name().to_owned(), fit_json(seconds, &model));
    }
    println!("{}", json!({ "n": x.len(), "order": order, "fits": fits }));
    Ok(())
}

/// The samples of a raw little-endian `f64` file.
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

/// Fastest of three fits, in seconds, and the model.
fn best_of_three(x: &[f64], order: usize, method: ArMethod) -> Result<(f64, ArModel), String> {
    let mut best = f64::INFINITY;
    let mut model = None;
    for _ in 0..3 {
        let start = Instant::now();
        let fit = fit_ar(x, Order::Fixed(order), method).map_err(|e| e.to_string())?;
        best = best.min(start.elapsed().as_secs_f64());
        model = Some(fit);
    }
    Ok((best, model.expect("three fits ran")))
}

fn fit_json(seconds: f64, model: &ArModel) -> serde_json::Value {
    json!({
        "seconds": seconds,
        "coefficients": model.coefficients,
        "noise_variance": model.noise_variance,
        "coefficient_std_errors": model.coefficient_std_errors,
    })
}
