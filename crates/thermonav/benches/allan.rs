//! Overlapping Allan deviation of 2^21 samples on the octave and decade grids.

use criterion::{Criterion, criterion_group, criterion_main};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use thermonav::stoch::allan::{TauGrid, overlapping_adev};

fn white_noise(n: usize) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    (0..n).map(|_| StandardNormal.sample(&mut rng)).collect()
}

fn bench_oadev(c: &mut Criterion) {
    let y = white_noise(1 << 21);
    let mut group = c.benchmark_group("oadev_2pow21");
    group.sample_size(20);
    for (name, grid) in [("octave", TauGrid::Octave), ("decade", TauGrid::Decade)] {
        group.bench_function(name, |b| {
            b.iter(|| overlapping_adev(std::hint::black_box(&y), 100.0, &grid).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench_oadev);
criterion_main!(benches);
