//! Times the paper's AR-based Gauss-Markov characterisation of six channels, for
//! `bench/compare.py`: per channel, the Kaiser low-pass of `characterize` (odd taps), one-pass
//! zero-phase filtering, decimation to the modelling rate, Burg AR(1) and
//! Tc = −dt / ln c₁, σ² = var(w) / (1 − c₁²).
//!
//! Usage: `gm_pipeline_timing FILE RATE_HZ CUTOFF_HZ TRANSITION_HZ RIPPLE_DB MODELLING_RATE_HZ`
//! where FILE holds the six channels one after the other as little-endian f64. Prints one JSON
//! line: best-of-3 times with the channels in parallel on the default rayon pool (`_s`) and on a
//! one-thread pool (`_1t_s`), and per channel c₁, Tc and σ.

use rayon::prelude::*;
use std::time::Instant;
use thermonav::signal::decimate::decimation_factor;
use thermonav::signal::kaiser::{FirFilter, KaiserSpec, design_kaiser_lowpass};
use thermonav::signal::streaming_decimate::filter_and_decimate;
use thermonav::stoch::ar::{ArMethod, fit_ar};
use thermonav::stoch::gauss_markov::{Ar1Estimate, GaussMarkovOutcome, ar_based};

/// c₁, Tc in s and σ of one channel.
type ChannelFit = (f64, f64, f64);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 7 {
        return Err("usage: gm_pipeline_timing FILE RATE_HZ CUTOFF_HZ TRANSITION_HZ RIPPLE_DB MODELLING_RATE_HZ".into());
    }
    let bytes = std::fs::read(&args[1])?;
    let all: Vec<f64> = bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
        .collect();
    let numbers: Vec<f64> = args[2..7]
        .iter()
        .map(|a| a.parse())
        .collect::<Result<_, _>>()?;
    let (rate_hz, modelling_rate_hz) = (numbers[0], numbers[4]);
    let spec = KaiserSpec::new(rate_hz, numbers[1], numbers[2], numbers[3])?;
    let filter = design_kaiser_lowpass(&spec)?.with_odd_taps(&spec);
    let factor = decimation_factor(rate_hz, modelling_rate_hz)?;
    let channels: Vec<&[f64]> = all.chunks_exact(all.len() / 6).collect();
    let run = || -> Result<Vec<ChannelFit>, String> {
        channels
            .par_iter()
            .map(|x| ar_based_fit(&filter, x, factor, rate_hz))
            .collect()
    };
    let (best, fits) = best_of_3(run)?;
    let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let (best_1t, _) = one_thread.install(|| best_of_3(run))?;
    let column = |k: usize| {
        let values: Vec<String> = fits
            .iter()
            .map(|f| format!("{:e}", [f.0, f.1, f.2][k]))
            .collect();
        values.join(",")
    };
    println!(
        "{{\"samples_per_channel\":{},\"num_taps\":{},\"decimation_factor\":{factor},\"threads\":{},\"pipeline_s\":{best},\"pipeline_1t_s\":{best_1t},\"c1\":[{}],\"correlation_time_s\":[{}],\"sigma\":[{}]}}",
        channels[0].len(),
        filter.num_taps(),
        rayon::current_num_threads(),
        column(0),
        column(1),
        column(2)
    );
    Ok(())
}

/// The shortest of three runs of `run`, s, and its last result.
fn best_of_3<T>(run: impl Fn() -> Result<T, String>) -> Result<(f64, T), String> {
    let mut best = f64::INFINITY;
    let mut out = run()?;
    for _ in 0..3 {
        let start = Instant::now();
        out = run()?;
        best = best.min(start.elapsed().as_secs_f64());
    }
    Ok((best, out))
}

/// The paper's conditioning and AR-based Gauss-Markov model of one channel, as `characterize`
/// does it.
fn ar_based_fit(
    filter: &FirFilter,
    x: &[f64],
    factor: usize,
    rate_hz: f64,
) -> Result<ChannelFit, String> {
    let conditioned = filter_and_decimate(filter, x, factor).map_err(|e| e.to_string())?;
    let ar1 = fit_ar(&conditioned, 1, ArMethod::Burg).map_err(|e| e.to_string())?;
    let estimate = Ar1Estimate {
        c1: ar1.coefficients[0],
        c1_std_error: ar1.std_errors[0],
        innovation_variance: ar1.noise_variance,
        dt_s: factor as f64 / rate_hz,
    };
    match ar_based(&estimate) {
        GaussMarkovOutcome::Model { model, .. } => {
            Ok((estimate.c1, model.correlation_time_s, model.sigma))
        }
        GaussMarkovOutcome::NoEquivalent { reason } => Err(reason),
    }
}
