//! Gauss-Markov: exact ML fit and exact simulation at IMU-like sizes (200 Hz, 10 min).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rand::SeedableRng;
use rand_chacha::ChaCha20Rng;
use thermonav::stoch::gauss_markov::{
    ConfidenceLevel, GaussMarkov, MeanModel, SampleIntervals, fit_gauss_markov_exact_ml,
    simulate_gauss_markov,
};

const SAMPLES: usize = 120_000;
const DT_S: f64 = 0.005;

fn bench_gauss_markov(c: &mut Criterion) {
    let intervals = SampleIntervals::regular(SAMPLES, DT_S).unwrap();
    let model = GaussMarkov::new(2.0, 1.0).unwrap();
    let values = simulate_gauss_markov(&intervals, &model, &mut ChaCha20Rng::seed_from_u64(1));
    c.bench_function("simulate_gauss_markov 120k", |b| {
        let mut rng = ChaCha20Rng::seed_from_u64(2);
        b.iter(|| simulate_gauss_markov(black_box(&intervals), &model, &mut rng))
    });
    let mut group = c.benchmark_group("fit_gauss_markov_exact_ml 120k");
    group.sample_size(10);
    for mean_model in [MeanModel::Estimated, MeanModel::Restricted] {
        group.bench_function(format!("{mean_model:?}"), |b| {
            b.iter(|| {
                fit_gauss_markov_exact_ml(
                    black_box(&intervals),
                    black_box(&values),
                    mean_model,
                    ConfidenceLevel::NINETY_FIVE_PERCENT,
                )
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench_gauss_markov);
criterion_main!(benches);
