//! Delay-compensated FIR filtering and decimation of a record fed piece by piece.
//!
//! The output is y_j = Σ_i h_i x_{j+D−i}, D = (taps − 1)/2, for the kept
//! j ∈ [`valid_decimated_indices`]: the multiples of F with D ≤ j ≤ n − 1 − D, whose whole
//! filter window lies inside the record (NumPy's `convolve(x, h, 'valid')`, delay removed,
//! every F-th sample on the record's own grid j = 0, F, 2F, …). Those samples equal
//! `decimate(&filter_zero_phase(filter, x, ZeroPhaseMode::DelayCompensated)?, factor)`
//! (see [`super::zero_phase`]) at the same j; the outputs nearer the ends than D, which there
//! come from the odd reflection of the record about its end (the first one is the raw first
//! sample: for a symmetric filter of unit gain Σ h_k (2 x_0 − x_k) over the reflected half
//! plus the other half gives x_0 back), are not produced. Only the kept outputs are computed,
//! each by a direct sum (taps/F multiplications per input sample), and only a window of about
//! taps + F recent samples is held: memory is independent of the record length, apart from
//! the decimated output itself.
//!
//! The in-memory path convolves by FFT; the sums agree to rounding (~taps × ε relative).

use super::SignalError;
use super::decimate::valid_decimated_indices;
use super::kaiser::FirFilter;

/// Independent partial sums of the dot product (lets the compiler vectorise it).
const LANES: usize = 8;

/// A delay-compensated low-pass filter and decimator fed with successive pieces of a record.
#[derive(Debug, Clone)]
pub struct StreamingDecimator {
    reversed_taps: Vec<f64>,
    delay: usize,
    factor: usize,
    window: Vec<f64>,
    window_start: usize,
    samples: usize,
    next_output: usize,
    output: Vec<f64>,
}

impl StreamingDecimator {
    /// A decimator keeping every `factor`-th output of `filter` (odd number of taps).
    ///
    /// # Errors
    /// [`SignalError::EvenTaps`] for an even number of taps.
    pub fn new(filter: &FirFilter, factor: usize) -> Result<Self, SignalError> {
        let taps = filter.taps();
        if taps.len() % 2 == 0 {
            return Err(SignalError::EvenTaps { taps: taps.len() });
        }
        let (delay, factor) = ((taps.len() - 1) / 2, factor.max(1));
        Ok(Self {
            reversed_taps: taps.iter().rev().copied().collect(),
            delay,
            factor,
            window: Vec::new(),
            window_start: 0,
            samples: 0,
            next_output: delay.div_ceil(factor) * factor,
            output: Vec::new(),
        })
    }

    /// Adds the next samples and computes every output whose inputs have all arrived.
    ///
    /// # Errors
    /// [`SignalError::NonFinite`] (index counted from the first sample of the record).
    pub fn push(&mut self, x: &[f64]) -> Result<(), SignalError> {
        if let Some(k) = x.iter().position(|v| !v.is_finite()) {
            return Err(SignalError::NonFinite {
                index: self.samples + k,
            });
        }
        self.window.extend_from_slice(x);
        self.samples += x.len();
        pulp::Arch::new().dispatch(ReadyOutputs(self));
        self.forget_used_samples();
        Ok(())
    }

    /// Every output whose inputs have all arrived. Run through [`pulp::Arch::dispatch`], so
    /// the dot products are compiled for the widest vector instructions the processor has
    /// (found at run time); the result does not depend on which, because the sums are fused
    /// multiply-adds in a fixed order on every path.
    #[inline(always)]
    fn compute_ready_outputs(&mut self) {
        while self.next_output + self.delay < self.samples {
            let y = self.output_at(self.next_output);
            self.output.push(y);
            self.next_output += self.factor;
        }
    }

    /// Drops the samples no future output reads (before next output − delay), in batches.
    fn forget_used_samples(&mut self) {
        let needed_from = self.next_output.saturating_sub(self.delay);
        let unused = needed_from.saturating_sub(self.window_start);
        if unused > self.window.len() / 2 && unused > 0 {
            self.window.drain(..unused);
            self.window_start += unused;
        }
    }

    /// Output j (D ≤ j, all its inputs arrived).
    #[inline(always)]
    fn output_at(&self, j: usize) -> f64 {
        let from = j - self.delay - self.window_start;
        dot(
            &self.reversed_taps,
            &self.window[from..from + self.reversed_taps.len()],
        )
    }

    /// The decimated, filtered record: the outputs at [`valid_decimated_indices`] (every
    /// output whose inputs have all arrived is already computed).
    ///
    /// # Errors
    /// [`SignalError::TooShort`] when the record is not longer than 3 × taps (the in-memory
    /// filter's edge extension).
    pub fn finish(self) -> Result<Vec<f64>, SignalError> {
        let taps = self.reversed_taps.len();
        let n = self.samples;
        if n <= 3 * taps {
            return Err(SignalError::TooShort {
                samples: n,
                needed: 3 * taps + 1,
                taps,
            });
        }
        Ok(self.output)
    }
}

/// The delay-compensated low-pass output of `filter` on the whole record `x` at the kept
/// indices [`valid_decimated_indices`] (every `factor`-th sample whose filter window lies inside
/// the record): the output of [`StreamingDecimator`] fed `x` in one piece, bit for bit (same
/// products in the same order), read from `x` in place instead of a copied window. Equal to
/// `decimate(&filter_zero_phase(filter, x, DelayCompensated)?, factor)` at those indices to
/// rounding, at taps/factor multiplications per input sample instead of a full FFT convolution.
///
/// # Errors
/// [`SignalError::EvenTaps`], [`SignalError::TooShort`] (not longer than 3 × taps, as the
/// in-memory filter), [`SignalError::NonFinite`].
pub fn filter_and_decimate(
    filter: &FirFilter,
    x: &[f64],
    factor: usize,
) -> Result<Vec<f64>, SignalError> {
    let taps = filter.taps();
    if taps.len() % 2 == 0 {
        return Err(SignalError::EvenTaps { taps: taps.len() });
    }
    if x.len() <= 3 * taps.len() {
        return Err(SignalError::TooShort {
            samples: x.len(),
            needed: 3 * taps.len() + 1,
            taps: taps.len(),
        });
    }
    let record = WholeRecord {
        reversed_taps: taps.iter().rev().copied().collect(),
        x,
        factor: factor.max(1),
    };
    let output = pulp::Arch::new().dispatch(&record);
    // Every output window is taps long and they are `factor` apart: when they overlap, a NaN
    // or infinity between the first and the last window reaches some output (0 × NaN is NaN),
    // so one check of the short output and of the few samples outside every window stands
    // for the scan of the whole record.
    let delay = record.delay();
    let kept = valid_decimated_indices(x.len(), delay, record.factor);
    let head = &x[..kept.start.saturating_sub(delay).min(x.len())];
    let tail_start = (output.len() * record.factor + kept.start).saturating_sub(record.factor);
    let tail = &x[(tail_start + delay + 1).min(x.len())..];
    let outside_finite = head.iter().chain(tail).all(|v| v.is_finite());
    let covered = record.factor <= delay + 1 && !output.is_empty() && outside_finite;
    if !covered || output.iter().any(|v| !v.is_finite()) {
        if let Some(index) = x.iter().position(|v| !v.is_finite()) {
            return Err(SignalError::NonFinite { index });
        }
    }
    Ok(output)
}

/// The kept outputs of a whole record, as a [`pulp::WithSimd`] task.
struct WholeRecord<'a> {
    reversed_taps: Vec<f64>,
    x: &'a [f64],
    factor: usize,
}

impl WholeRecord<'_> {
    fn delay(&self) -> usize {
        (self.reversed_taps.len() - 1) / 2
    }

    /// Output j (D ≤ j < n − D): a dot product inside the record.
    #[inline(always)]
    fn output_at(&self, j: usize) -> f64 {
        let from = j - self.delay();
        dot(
            &self.reversed_taps,
            &self.x[from..from + self.reversed_taps.len()],
        )
    }
}

impl pulp::WithSimd for &WholeRecord<'_> {
    type Output = Vec<f64>;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> Vec<f64> {
        // A plain loop, not an iterator adaptor: a closure would be compiled outside this
        // instruction-set context, and its fused multiply-adds would become library calls.
        let kept = valid_decimated_indices(self.x.len(), self.delay(), self.factor);
        let mut output = Vec::with_capacity(kept.len());
        let mut j = kept.start;
        while j < kept.end {
            output.push(self.output_at(j));
            j += self.factor;
        }
        output
    }
}

/// [`StreamingDecimator::compute_ready_outputs`] as a [`pulp::WithSimd`] task: compiled once per
/// instruction set, the best one chosen at run time.
struct ReadyOutputs<'a>(&'a mut StreamingDecimator);

impl pulp::WithSimd for ReadyOutputs<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        self.0.compute_ready_outputs();
    }
}

/// Σ a_k b_k over equal lengths, in [`LANES`] partial sums of fused multiply-adds (one
/// rounding per term on every processor, so every dispatch path gives the same bits).
#[inline(always)]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut lanes = [0.0_f64; LANES];
    let chunks = a.chunks_exact(LANES).zip(b.chunks_exact(LANES));
    for (x, y) in chunks {
        for l in 0..LANES {
            lanes[l] = x[l].mul_add(y[l], lanes[l]);
        }
    }
    let tail = a.len() - a.len() % LANES;
    let rest: f64 = a[tail..].iter().zip(&b[tail..]).map(|(x, y)| x * y).sum();
    lanes.iter().sum::<f64>() + rest
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::named_rng;
    use crate::signal::decimate::decimate_valid;
    use crate::signal::kaiser::{KaiserSpec, design_kaiser_lowpass};
    use crate::signal::zero_phase::{ZeroPhaseMode, filter_zero_phase};
    use rand::RngExt;

    // Oracle: the in-memory path (odd extension, FFT convolution, delay removal, decimation) at
    // the kept indices, fed in pieces of awkward sizes; the two differ by the rounding of sums of
    // ~taps unit-scale products (1e-12 absolute on values of order 1 is far above it and far
    // below any signal).
    #[test]
    fn pieces_give_the_in_memory_filter_and_decimation() {
        let spec = KaiserSpec::new(100.0, 2.0, 1.0, 60.0).unwrap();
        let filter = design_kaiser_lowpass(&spec).unwrap().with_odd_taps(&spec);
        let mut rng = named_rng(5, "streaming decimator");
        let x: Vec<f64> = (0..20_000)
            .map(|k| (k as f64 * 0.01).sin() + rng.random_range(-1.0..1.0))
            .collect();
        for (factor, piece) in [(10, 777), (7, 1), (1, 4096), (25, 20_000)] {
            let expected = decimate_valid(
                &filter_zero_phase(&filter, &x, ZeroPhaseMode::DelayCompensated).unwrap(),
                (filter.num_taps() - 1) / 2,
                factor,
            );
            let mut stream = StreamingDecimator::new(&filter, factor).unwrap();
            for chunk in x.chunks(piece) {
                stream.push(chunk).unwrap();
            }
            let got = stream.finish().unwrap();
            assert_eq!(got.len(), expected.len(), "factor {factor}");
            let worst = got
                .iter()
                .zip(&expected)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-12, "factor {factor}, piece {piece}: {worst}");
        }
    }

    // Oracle: a ramp x_k = k through a symmetric filter of unit DC gain is the ramp itself
    // wherever the window lies inside the record (Σ h_i (j + D − i) = j), so the outputs must be
    // exactly the kept indices j0, j0 + F, … with j0 the first multiple of F at or above the
    // delay D and the last at most n − 1 − D (rounding: 1e-9 on values up to 1e4). Before, the
    // first output was the edge value x_0 itself (odd reflection) and the last x_{n-1}.
    #[test]
    fn outputs_come_only_from_inside_the_record() {
        let spec = KaiserSpec::new(100.0, 2.0, 1.0, 60.0).unwrap();
        let filter = design_kaiser_lowpass(&spec).unwrap().with_odd_taps(&spec);
        let delay = (filter.num_taps() - 1) / 2;
        let n = 10_000;
        let x: Vec<f64> = (0..n).map(|k| k as f64).collect();
        for factor in [1, 7, 100, 333] {
            let first = delay.div_ceil(factor) * factor;
            let expected: Vec<usize> = (first..n - delay).step_by(factor).collect();
            let mut stream = StreamingDecimator::new(&filter, factor).unwrap();
            stream.push(&x).unwrap();
            for got in [
                filter_and_decimate(&filter, &x, factor).unwrap(),
                stream.finish().unwrap(),
            ] {
                assert_eq!(got.len(), expected.len(), "factor {factor}");
                for (y, j) in got.iter().zip(&expected) {
                    assert!((y - *j as f64).abs() < 1e-9, "factor {factor}: {y} at {j}");
                }
            }
        }
    }

    #[test]
    fn too_short_and_non_finite_records_are_refused() {
        let spec = KaiserSpec::new(100.0, 2.0, 1.0, 60.0).unwrap();
        let filter = design_kaiser_lowpass(&spec).unwrap().with_odd_taps(&spec);
        let mut stream = StreamingDecimator::new(&filter, 10).unwrap();
        stream.push(&[1.0; 10]).unwrap();
        assert!(matches!(stream.finish(), Err(SignalError::TooShort { .. })));
        let mut stream = StreamingDecimator::new(&filter, 10).unwrap();
        stream.push(&[1.0; 10]).unwrap();
        assert_eq!(
            stream.push(&[1.0, f64::NAN]),
            Err(SignalError::NonFinite { index: 11 })
        );
    }

    // The whole-record form against the streaming decimator fed in pieces (the same products
    // in the same order, so equal bit for bit) and against the in-memory FFT path (rounding of
    // sums of ~taps unit-scale products: 1e-12).
    #[test]
    fn whole_record_equals_the_pieces_bit_for_bit() {
        let spec = KaiserSpec::new(100.0, 2.0, 1.0, 60.0).unwrap();
        let filter = design_kaiser_lowpass(&spec).unwrap().with_odd_taps(&spec);
        let mut rng = named_rng(6, "whole-record decimator");
        let x: Vec<f64> = (0..20_000)
            .map(|k| (k as f64 * 0.013).cos() + rng.random_range(-1.0..1.0))
            .collect();
        for (factor, piece) in [(10, 333), (7, 1), (1, 5000), (400, 20_000)] {
            let mut stream = StreamingDecimator::new(&filter, factor).unwrap();
            for chunk in x.chunks(piece) {
                stream.push(chunk).unwrap();
            }
            let whole = filter_and_decimate(&filter, &x, factor).unwrap();
            assert_eq!(whole, stream.finish().unwrap(), "factor {factor}");
            let expected = decimate_valid(
                &filter_zero_phase(&filter, &x, ZeroPhaseMode::DelayCompensated).unwrap(),
                (filter.num_taps() - 1) / 2,
                factor,
            );
            assert_eq!(whole.len(), expected.len(), "factor {factor}");
            let worst = whole
                .iter()
                .zip(&expected)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-12, "factor {factor}: {worst}");
        }
    }

    // A NaN or infinity is found and located whether the output windows cover the whole
    // record (factor 10 <= delay + 1: found through the outputs) or leave gaps (factor 400,
    // more than the taps: found by the scan), at the start, inside and at the end.
    #[test]
    fn whole_record_refuses_non_finite_samples_wherever_they_are() {
        let spec = KaiserSpec::new(100.0, 2.0, 1.0, 60.0).unwrap();
        let filter = design_kaiser_lowpass(&spec).unwrap().with_odd_taps(&spec);
        for factor in [10, 400] {
            for index in [0, 777, 9_999] {
                for bad in [f64::NAN, f64::INFINITY] {
                    let mut x = vec![0.5; 10_000];
                    x[index] = bad;
                    assert_eq!(
                        filter_and_decimate(&filter, &x, factor),
                        Err(SignalError::NonFinite { index }),
                        "factor {factor}, index {index}"
                    );
                }
            }
        }
        assert!(matches!(
            filter_and_decimate(&filter, &[1.0; 10], 10),
            Err(SignalError::TooShort { .. })
        ));
    }
}
