//! AR(4) by Burg and Yule-Walker on 2^21 samples, and the autocovariance by both algorithms
//! (the crossover behind `AcfAlgorithm::Auto`).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use thermonav::stoch::acf::{AcfAlgorithm, Demean, autocovariance_with};
use thermonav::stoch::ar::{ArMethod, Order, fit_ar};

/// `n` samples of AR(1) with c = 0.9 plus an offset, ChaCha8 seed 7.
fn ar1_series(n: usize) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut y = 0.0;
    (0..n)
        .map(|_| {
            let w: f64 = StandardNormal.sample(&mut rng);
            y = 0.9 * y + w;
            y + 0.4
        })
        .collect()
}

fn bench_ar4(c: &mut Criterion) {
    let x = ar1_series(1 << 21);
    let mut group = c.benchmark_group("ar4_2pow21");
    group.sample_size(20);
    for method in ArMethod::ALL {
        group.bench_function(method.name(), |b| {
            b.iter(|| fit_ar(black_box(&x), Order::Fixed(4), method).unwrap())
        });
    }
    group.finish();
}

fn bench_autocovariance(c: &mut Criterion) {
    let x = ar1_series(1 << 21);
    let mut group = c.benchmark_group("autocovariance_2pow21");
    group.sample_size(10);
    for max_lag in [4, 64, 256] {
        for algorithm in [AcfAlgorithm::Direct, AcfAlgorithm::Fft] {
            group.bench_function(format!("{algorithm:?}_lag{max_lag}"), |b| {
                b.iter(|| {
                    autocovariance_with(black_box(&x), max_lag, Demean::SampleMean, algorithm)
                        .unwrap()
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench_ar4, bench_autocovariance);
criterion_main!(benches);
