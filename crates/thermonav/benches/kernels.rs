//! The hot kernels on 2^21 samples (≈ 3 h at 200 Hz) of a seeded AR(1) + white series: octave
//! overlapping Allan deviation, Burg AR(4), FFT autocovariance to 10 000 lags; and one
//! 21-state EKF step (covariance propagation + a 3-D Joseph update) and one UKF
//! predict/update, as the navigation engine runs them.

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{SMatrix, SVector};
use rand_distr::{Distribution, StandardNormal};
use std::hint::black_box;
use thermonav::filter::ekf::{joseph_update, propagate_covariance};
use thermonav::filter::sigma_points::SigmaPointScheme;
use thermonav::filter::ukf::Ukf;
use thermonav::rng::named_rng;
use thermonav::stoch::acf::{Demean, autocovariance};
use thermonav::stoch::allan::{TauGrid, overlapping_adev};
use thermonav::stoch::ar::{ArMethod, fit_ar};

fn series(n: usize) -> Vec<f64> {
    let mut rng = named_rng(1, "bench/series");
    let mut state = 0.0;
    (0..n)
        .map(|_| {
            let (a, b): (f64, f64) = (
                StandardNormal.sample(&mut rng),
                StandardNormal.sample(&mut rng),
            );
            state = 0.999 * state + 0.05 * a;
            state + b
        })
        .collect()
}

fn stochastic(c: &mut Criterion) {
    let y = series(1 << 21);
    let mut group = c.benchmark_group("stochastic_2pow21_samples");
    group.sample_size(10);
    group.bench_function("allan_octave", |b| {
        b.iter(|| overlapping_adev(black_box(&y), 200.0, &TauGrid::Octave).expect("allan"))
    });
    group.bench_function("burg_ar4", |b| {
        b.iter(|| fit_ar(black_box(&y), 4, ArMethod::Burg).expect("burg"))
    });
    group.bench_function("fft_autocovariance_10000_lags", |b| {
        b.iter(|| autocovariance(black_box(&y), 10_000, Demean::Subtract).expect("acf"))
    });
    group.finish();
}

type State = SVector<f64, 21>;
type Cov = SMatrix<f64, 21, 21>;

fn filter_steps(c: &mut Criterion) {
    let f = Cov::from_fn(|i, j| {
        if i == j {
            1.0
        } else if j == i + 3 {
            0.01
        } else {
            0.0
        }
    });
    let q = Cov::from_diagonal_element(1e-6);
    let p0 = Cov::from_fn(|i, j| if i == j { 1.0 + 0.1 * i as f64 } else { 0.01 });
    let h = SMatrix::<f64, 3, 21>::from_fn(|i, j| if i == j { 1.0 } else { 0.0 });
    let r = SMatrix::<f64, 3, 3>::from_diagonal_element(0.25);
    let z = SVector::<f64, 3>::new(0.3, -0.2, 0.1);
    c.bench_function("ekf_21_states_propagate_and_update", |b| {
        b.iter(|| {
            let mut p = propagate_covariance(black_box(&p0), &f, &q);
            let mut x = State::zeros();
            joseph_update(&mut x, &mut p, &z, &h, &r).expect("update")
        })
    });
    let scheme = SigmaPointScheme::MerweScaled {
        alpha: 1.0,
        beta: 2.0,
        kappa: 0.0,
    };
    c.bench_function("ukf_21_states_predict_and_update", |b| {
        b.iter(|| {
            let mut ukf = Ukf::new(State::zeros(), black_box(p0), scheme);
            ukf.predict(|s| f * s, &q).expect("predict");
            ukf.update(&z, |s| h * s, &r).expect("update")
        })
    });
}

criterion_group!(benches, stochastic, filter_steps);
criterion_main!(benches);
