//! Causal FIR convolution with a constant history: `y[n] = Σ_k h[k] x[n−k]`, with `x[m] = c` for
//! m < 0. This is what `lfilter(h, [1], x, zi=lfilter_zi(h, 1)·c)` computes (the steady-state
//! initial conditions of a constant input c are that constant's history).
//!
//! Two algorithms: the direct sum ([`convolve_direct`], the obviously correct reference, used
//! for short filters) and FFT overlap-save ([`convolve_fft`]), which costs O(log M) per sample
//! instead of O(N); [`convolve`] picks by filter length.

use realfft::RealFftPlanner;
use rustfft::num_complex::Complex;

/// Filter length from which the FFT method is used (measured: below it the direct sum wins).
pub const FFT_THRESHOLD_TAPS: usize = 48;

/// `y[n] = Σ h[k] x[n−k]`, `x[m<0] = history`, by the direct sum.
pub fn convolve_direct(x: &[f64], h: &[f64], history: f64) -> Vec<f64> {
    (0..x.len())
        .map(|n| {
            h.iter()
                .enumerate()
                .map(|(k, hk)| hk * if n >= k { x[n - k] } else { history })
                .sum()
        })
        .collect()
}

/// The same convolution by FFT overlap-save, block size the power of two ≥ 8 N.
pub fn convolve_fft(x: &[f64], h: &[f64], history: f64) -> Vec<f64> {
    let taps = h.len();
    if taps == 0 || x.is_empty() {
        return vec![0.0; x.len()];
    }
    let size = (8 * taps).next_power_of_two().max(1024);
    let step = size - (taps - 1);
    let mut planner = RealFftPlanner::<f64>::new();
    let forward = planner.plan_fft_forward(size);
    let inverse = planner.plan_fft_inverse(size);
    let mut kernel = forward.make_output_vec();
    let mut padded = vec![0.0; size];
    padded[..taps].copy_from_slice(h);
    // The plan's input length equals its output length by construction: the call cannot fail.
    let _ = forward.process(&mut padded, &mut kernel);
    let scale = 1.0 / size as f64;
    kernel.iter_mut().for_each(|k| *k *= scale);
    let mut block = vec![0.0; size];
    let mut spectrum = forward.make_output_vec();
    let mut output = Vec::with_capacity(x.len());
    let mut start = 0;
    while start < x.len() {
        fill_block(&mut block, x, start, taps - 1, history);
        let _ = forward.process(&mut block, &mut spectrum);
        spectrum.iter_mut().zip(&kernel).for_each(|(s, k)| *s *= *k);
        clear_imaginary_edges(&mut spectrum);
        let _ = inverse.process(&mut spectrum, &mut block);
        let valid = step.min(x.len() - start);
        output.extend_from_slice(&block[taps - 1..taps - 1 + valid]);
        start += step;
    }
    output
}

/// Block k holds x[start − overlap .. start − overlap + size], with the history before x[0] and
/// zeros after the end.
fn fill_block(block: &mut [f64], x: &[f64], start: usize, overlap: usize, history: f64) {
    for (i, slot) in block.iter_mut().enumerate() {
        let index = start as isize - overlap as isize + i as isize;
        *slot = if index < 0 {
            history
        } else {
            x.get(index as usize).copied().unwrap_or(0.0)
        };
    }
}

/// The DC and Nyquist bins of a real signal's spectrum are real; rounding can leave a tiny
/// imaginary part there, which the inverse real FFT refuses.
fn clear_imaginary_edges(spectrum: &mut [Complex<f64>]) {
    if let Some(first) = spectrum.first_mut() {
        first.im = 0.0;
    }
    if let Some(last) = spectrum.last_mut() {
        last.im = 0.0;
    }
}

/// The convolution by whichever method is faster for this filter length.
pub fn convolve(x: &[f64], h: &[f64], history: f64) -> Vec<f64> {
    if h.len() < FFT_THRESHOLD_TAPS {
        convolve_direct(x, h, history)
    } else {
        convolve_fft(x, h, history)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::named_rng;
    use rand::RngExt;

    fn random(n: usize, name: &str) -> Vec<f64> {
        let mut rng = named_rng(11, name);
        (0..n).map(|_| rng.random_range(-1.0..1.0)).collect()
    }

    // Overlap-save against the direct sum: same quantity, two algorithms; each output is a sum
    // of N products of unit-scale numbers, so rounding is ~N ε ≈ 1e-13 for N = 700.
    #[test]
    fn fft_convolution_equals_the_direct_sum() {
        for (n, taps) in [(10_000, 701), (5, 64), (3000, 48), (20_000, 1500), (1, 100)] {
            let x = random(n, "x");
            let h = random(taps, "h");
            let direct = convolve_direct(&x, &h, 0.37);
            let fast = convolve_fft(&x, &h, 0.37);
            assert_eq!(direct.len(), fast.len());
            let worst = direct
                .iter()
                .zip(&fast)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-12, "n {n}, taps {taps}: {worst}");
        }
    }

    #[test]
    fn empty_input_gives_empty_output() {
        assert!(convolve_fft(&[], &[1.0, 2.0], 0.0).is_empty());
        assert!(convolve_direct(&[], &[1.0], 0.0).is_empty());
    }
}
