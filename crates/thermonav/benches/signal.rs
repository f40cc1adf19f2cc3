//! Zero-phase Kaiser filtering of 2^21 samples (≈ 3 h at 200 Hz) with the 727-tap design of
//! the README example (fs 200 Hz, cut-off 5 Hz, transition 1 Hz, 60 dB).

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use thermonav::signal::kaiser::{KaiserSpec, design_kaiser_lowpass};
use thermonav::signal::zero_phase::{ZeroPhaseMode, filter_zero_phase};

fn signal(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| (0.01 * k as f64).sin() + 0.3 * (2.9 * k as f64).cos())
        .collect()
}

fn zero_phase(c: &mut Criterion) {
    let filter =
        design_kaiser_lowpass(&KaiserSpec::new(200.0, 5.0, 1.0, 60.0).expect("valid spec"))
            .expect("design");
    let x = signal(1 << 21);
    let mut group = c.benchmark_group("kaiser_727_taps_2pow21_samples");
    group.sample_size(10);
    group.bench_function("delay_compensated", |b| {
        b.iter(|| filter_zero_phase(&filter, black_box(&x), ZeroPhaseMode::DelayCompensated))
    });
    group.bench_function("forward_backward", |b| {
        b.iter(|| filter_zero_phase(&filter, black_box(&x), ZeroPhaseMode::ForwardBackward))
    });
    group.finish();
}

criterion_group!(benches, zero_phase);
criterion_main!(benches);
