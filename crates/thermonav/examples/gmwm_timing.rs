//! Times the Haar wavelet variance plus the GMWM fit (no bootstrap) of one channel of
//! 2.16 M samples (3 h at 200 Hz) on a one-thread pool, best of 3, for `bench/gmwm.sh`.
//! Usage: `gmwm_timing [SAMPLES]`; prints one JSON line per composite.

use std::time::Instant;
use thermonav::rng::named_rng;
use thermonav::stoch::gmwm::{ModelSpec, Term, fit_gmwm, simulate};
use thermonav::stoch::wavelet_variance::haar_wavelet_variance;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = std::env::args()
        .nth(1)
        .map_or(Ok(2_160_000), |s| s.parse())?;
    let dt = 1.0 / 200.0;
    let truth = [
        Term::white_from_density(0.01, dt),
        Term::random_walk_from_k(1e-4, dt),
        Term::gauss_markov_from(0.5, 0.01, dt),
        Term::gauss_markov_from(100.0, 0.005, dt),
    ];
    let y = simulate(&truth, n, &mut named_rng(1, "bench/gmwm"));
    let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    for spec in ["wn+gm", "wn+rw+2gm", "wn+qn+rw+2gm"] {
        let model: ModelSpec = spec.parse()?;
        let mut best = (f64::INFINITY, f64::INFINITY);
        for _ in 0..3 {
            let (wv_s, fit_s) =
                one_thread.install(|| time_once(&y, dt, model).map_err(|e| e.to_string()))?;
            best = (best.0.min(wv_s), best.1.min(fit_s));
        }
        println!(
            "{{\"model\":\"{spec}\",\"samples\":{n},\"wavelet_variance_1t_s\":{},\"fit_1t_s\":{},\"total_1t_s\":{}}}",
            best.0,
            best.1,
            best.0 + best.1
        );
    }
    Ok(())
}

fn time_once(
    y: &[f64],
    dt: f64,
    model: ModelSpec,
) -> Result<(f64, f64), Box<dyn std::error::Error>> {
    let start = Instant::now();
    let wv = haar_wavelet_variance(y, 1.0 / dt, None, 0.95)?;
    let wv_s = start.elapsed().as_secs_f64();
    fit_gmwm(&wv, model)?;
    Ok((wv_s, start.elapsed().as_secs_f64() - wv_s))
}
