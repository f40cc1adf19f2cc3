//! Draws of a composite process: the parametric bootstrap's replicates and the tests' series.
//!
//! Here rather than in `sim`: the bootstrap is part of the estimator, and `stoch` may not depend
//! on `sim`. The generator is always passed in (DESIGN.md, "Why named random generators?").

use rand::Rng;
use rand_distr::{Distribution, StandardNormal};

use super::model::Term;

/// `n` samples of the sum of `terms`, each process started in its stationary state (the random
/// walk and the drift at zero).
pub fn simulate(terms: &[Term], n: usize, rng: &mut impl Rng) -> Vec<f64> {
    let mut y = vec![0.0; n];
    for term in terms {
        add_term(term, &mut y, rng);
    }
    y
}

fn normal(rng: &mut impl Rng) -> f64 {
    StandardNormal.sample(rng)
}

fn add_term(term: &Term, y: &mut [f64], rng: &mut impl Rng) {
    match *term {
        Term::White { variance } => {
            let s = variance.sqrt();
            y.iter_mut().for_each(|v| *v += s * normal(rng));
        }
        Term::Quantisation { variance } => {
            let s = variance.sqrt();
            let mut previous = s * normal(rng);
            for v in y.iter_mut() {
                let x = s * normal(rng);
                *v += x - previous;
                previous = x;
            }
        }
        Term::RandomWalk { variance } => {
            let s = variance.sqrt();
            let mut level = 0.0;
            for v in y.iter_mut() {
                level += s * normal(rng);
                *v += level;
            }
        }
        Term::Drift { slope } => {
            y.iter_mut()
                .enumerate()
                .for_each(|(t, v)| *v += slope * t as f64);
        }
        Term::GaussMarkov {
            correlation_samples,
            variance,
        } => add_gauss_markov(correlation_samples, variance, y, rng),
    }
}

/// x_k = φ x_{k−1} + s √(1 − φ²) z_k, x_0 ~ N(0, s²).
fn add_gauss_markov(correlation_samples: f64, variance: f64, y: &mut [f64], rng: &mut impl Rng) {
    let phi = (-1.0 / correlation_samples).exp();
    let s = variance.sqrt();
    let innovation = s * (-(-2.0 / correlation_samples).exp_m1()).sqrt();
    let mut x = s * normal(rng);
    for v in y.iter_mut() {
        *v += x;
        x = phi * x + innovation * normal(rng);
    }
}
