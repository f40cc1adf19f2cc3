//! Exact simulation of a Gauss-Markov process at arbitrary sampling times.

use rand::Rng;
use rand_distr::{Distribution, StandardNormal};

use super::intervals::SampleIntervals;
use super::model::GaussMarkov;

/// Draws one path of `model` at the sampling times of `intervals`, exactly (no discretisation
/// error at any step length): the first value from the stationary law `N(0, sigma^2)`, then
/// `x_k = exp(-dt_k/Tc) x_{k-1} + w_k` with `w_k ~ N(0, sigma^2 (1 - exp(-2 dt_k/Tc)))`
/// (eqs. 3-4), each step with its own `dt_k`. The path is therefore stationary with variance
/// `sigma^2` at every sampling rate, jitter or gap.
///
/// The caller owns the random number generator (name and seed it, e.g. `ChaCha20Rng`); one
/// standard normal is drawn per sample, in time order.
pub fn simulate_gauss_markov<R: Rng + ?Sized>(
    intervals: &SampleIntervals,
    model: &GaussMarkov,
    rng: &mut R,
) -> Vec<f64> {
    let mut draw = || -> f64 { StandardNormal.sample(rng) };
    let mut path = Vec::with_capacity(intervals.sample_count());
    let mut value = model.sigma() * draw();
    path.push(value);
    for &dt_s in intervals.dt_s() {
        value = model.next_value(value, dt_s, draw());
        path.push(value);
    }
    path
}
