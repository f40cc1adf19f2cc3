//! The overlapping Allan deviation itself: the centred phase (cumulative sum) and one blocked
//! sweep that accumulates the squared second differences of every averaging factor at once;
//! and what the rest of the family builds on: the factors a kind can use and a curve from a
//! variance of the phase ([`curve_from_variance`]).

use rayon::prelude::*;

use crate::stoch::acf::sum_of;

use super::{AllanCurve, AllanError, DeviationCurve, DeviationKind, TauGrid};

/// The overlapping Allan deviation of rate samples `y` at `sample_rate_hz` on `grid`.
///
/// Cost: one pass for the phase, then one sweep over it in which every factor's sum is
/// accumulated block by block; large inputs spread fixed-size slices of the sweep over the
/// rayon pool, with results independent of the number of threads.
///
/// # Errors
/// [`AllanError`] for fewer than 3 samples, non-finite values, a bad rate, or a grid with no
/// factor that fits.
///
/// # Example
/// ```
/// use thermonav::stoch::allan::{overlapping_adev, TauGrid};
/// let y = [1.0, -1.0, 1.0, -1.0, 1.0];
/// let curve = overlapping_adev(&y, 1.0, &TauGrid::Octave).unwrap();
/// assert_eq!(curve.averaging_factor, vec![1, 2]);
/// assert_eq!(curve.n_terms, vec![4, 2]);
/// assert!((curve.adev[0] - 2.0_f64.sqrt()).abs() < 1e-12);
/// ```
pub fn overlapping_adev(
    y: &[f64],
    sample_rate_hz: f64,
    grid: &TauGrid,
) -> Result<AllanCurve, AllanError> {
    let factors = checked_factors(y.len(), sample_rate_hz, grid)?;
    let sums = piece_sums(y);
    let total: f64 = sums.iter().sum();
    if !total.is_finite() {
        if let Some(index) = y.iter().position(|v| !v.is_finite()) {
            return Err(AllanError::NonFinite { index });
        }
    }
    let phase = centred_phase(y, total / y.len() as f64);
    let adev = sums_of_squared_second_differences(&phase, &factors)
        .iter()
        .zip(&factors)
        .map(|(sum, &m)| (sum / avar_denominator(phase.len(), m)).sqrt())
        .collect();
    Ok(curve_of(factors, adev, y.len(), sample_rate_hz))
}

/// The factors of `grid` for `n` samples at `sample_rate_hz`, refusing a bad rate, fewer than
/// 3 samples, or a grid with no factor that fits.
pub(super) fn checked_factors(
    n: usize,
    sample_rate_hz: f64,
    grid: &TauGrid,
) -> Result<Vec<usize>, AllanError> {
    checked_factors_for(DeviationKind::Adev, n, sample_rate_hz, grid)
}

/// [`checked_factors`] for the factors that `kind` can be evaluated at.
pub(super) fn checked_factors_for(
    kind: DeviationKind,
    n: usize,
    sample_rate_hz: f64,
    grid: &TauGrid,
) -> Result<Vec<usize>, AllanError> {
    if !(sample_rate_hz.is_finite() && sample_rate_hz > 0.0) {
        return Err(AllanError::Rate {
            rate_hz: sample_rate_hz,
        });
    }
    if n < 3 {
        return Err(AllanError::TooShort { samples: n });
    }
    let factors = grid.factors_for(kind, n);
    if factors.is_empty() {
        return Err(AllanError::EmptyGrid { samples: n });
    }
    Ok(factors)
}

/// The curve of deviations `adev` at `factors` for `n` samples at `sample_rate_hz`.
pub(super) fn curve_of(
    factors: Vec<usize>,
    adev: Vec<f64>,
    n: usize,
    sample_rate_hz: f64,
) -> AllanCurve {
    let tau0_s = 1.0 / sample_rate_hz;
    AllanCurve {
        tau_s: factors.iter().map(|&m| m as f64 * tau0_s).collect(),
        adev,
        n_terms: factors.iter().map(|&m| n - 2 * m + 1).collect(),
        averaging_factor: factors,
        n_samples: n,
        tau0_s,
    }
}

/// Samples per piece of the passes over the series. Fixed, so that every sum is added up in
/// the same order whether the pieces run on one thread or many.
const PIECE: usize = 1 << 16;

/// Samples below which the passes over the series stay on the calling thread.
const PARALLEL_SAMPLES: usize = 1 << 18;

/// Σ y over each piece of [`PIECE`] samples (the last one shorter). A non-finite sample makes
/// its piece's sum non-finite, so one pass serves both the mean and the finiteness check.
fn piece_sums(y: &[f64]) -> Vec<f64> {
    if y.len() < PARALLEL_SAMPLES {
        y.chunks(PIECE).map(sum_of).collect()
    } else {
        y.par_chunks(PIECE).map(sum_of).collect()
    }
}

/// The mean of y (see [`sum_of`]).
pub(crate) fn mean(y: &[f64]) -> f64 {
    sum_of(y) / y.len() as f64
}

/// S_i = Σ_{j<i} (y_j − ȳ), i = 0..=N: the phase in units of τ₀.
///
/// The mean is removed so the running sum stays small (a 0.4 °/s gyro bias over 10⁶ samples
/// would otherwise grow it to 4·10⁵ and cost six digits in the differences).
pub(crate) fn centred_cumulative_sum(y: &[f64]) -> Vec<f64> {
    centred_phase(y, piece_sums(y).iter().sum::<f64>() / y.len() as f64)
}

/// S_i = Σ_{j<i} (y_j − mean), i = 0..=N, in two passes over pieces of [`PIECE`] samples that
/// may run in parallel: each piece's own running sum from zero ([`running_sum_into`]), then each
/// piece shifted by the totals of the pieces before it.
fn centred_phase(y: &[f64], mean: f64) -> Vec<f64> {
    let mut phase = vec![0.0; y.len() + 1];
    let parallel = y.len() >= PARALLEL_SAMPLES;
    let totals: Vec<f64> = if parallel {
        phase[1..]
            .par_chunks_mut(PIECE)
            .zip(y.par_chunks(PIECE))
            .map(|(out, piece)| running_sum_into(piece, mean, out))
            .collect()
    } else {
        phase[1..]
            .chunks_mut(PIECE)
            .zip(y.chunks(PIECE))
            .map(|(out, piece)| running_sum_into(piece, mean, out))
            .collect()
    };
    let offsets: Vec<f64> = totals
        .iter()
        .scan(0.0, |before, total| {
            let offset = *before;
            *before += total;
            Some(offset)
        })
        .collect();
    let shift = |(out, offset): (&mut [f64], &f64)| out.iter_mut().for_each(|s| *s += offset);
    if parallel {
        phase[1..]
            .par_chunks_mut(PIECE)
            .zip(offsets.par_iter())
            .skip(1)
            .for_each(shift);
    } else {
        phase[1..]
            .chunks_mut(PIECE)
            .zip(&offsets)
            .skip(1)
            .for_each(shift);
    }
    phase
}

/// out_k = Σ_{j≤k} (y_j − mean); returns the total. A running sum is bound by the latency of one
/// addition, so it runs as four independent chains over the four quarters of the piece, and each
/// quarter is then shifted by the totals of those before it.
fn running_sum_into(y: &[f64], mean: f64, out: &mut [f64]) -> f64 {
    const CHAINS: usize = 4;
    let quarter = y.len() / CHAINS;
    let mut sums = [0.0_f64; CHAINS];
    for k in 0..quarter {
        for (c, sum) in sums.iter_mut().enumerate() {
            *sum += y[c * quarter + k] - mean;
            out[c * quarter + k] = *sum;
        }
    }
    for k in CHAINS * quarter..y.len() {
        sums[CHAINS - 1] += y[k] - mean;
        out[k] = sums[CHAINS - 1];
    }
    let mut offset = 0.0;
    for c in 1..CHAINS {
        offset += sums[c - 1];
        let end = if c + 1 == CHAINS {
            y.len()
        } else {
            (c + 1) * quarter
        };
        out[c * quarter..end].iter_mut().for_each(|p| *p += offset);
    }
    offset + sums[CHAINS - 1]
}

/// 2 m² n, n = phase points − 2m: the Allan-variance denominator in units of τ₀ (τ₀ cancels
/// because the phase is in rate × samples).
pub(super) fn avar_denominator(phase_len: usize, m: usize) -> f64 {
    2.0 * (m as f64).powi(2) * (phase_len - 2 * m) as f64
}

/// The overlapping Allan variance at factor m from the phase in units of τ₀.
pub(crate) fn overlapping_avar(phase: &[f64], m: usize) -> f64 {
    sums_of_squared_second_differences(phase, &[m])[0] / avar_denominator(phase.len(), m)
}

/// Phase points per slice of the sweep. Fixed, so that each factor's sum is added up in the
/// same order whether the slices run on one thread or many.
const SLICE: usize = 1 << 16;

/// Squared second differences (summed over all factors) below which one thread does the sweep.
const PARALLEL_WORK: usize = 1 << 22;

/// For each m of `factors` (ascending): Σ_i (s_{i+2m} − 2 s_{i+m} + s_i)² over all i with
/// i + 2m < s.len().
fn sums_of_squared_second_differences(s: &[f64], factors: &[usize]) -> Vec<f64> {
    let work: usize = factors.iter().map(|&m| s.len() - 2 * m).sum();
    swept_sums(s, factors, work >= PARALLEL_WORK)
}

/// The sums of [`sums_of_squared_second_differences`]: the index range is cut into fixed
/// slices, each one blocked sweep over all factors ([`slice_sums`], on the rayon pool when
/// `parallel`), and the slices' partial sums are added in slice order.
fn swept_sums(s: &[f64], factors: &[usize], parallel: bool) -> Vec<f64> {
    let longest = factors.iter().map(|&m| s.len() - 2 * m).max().unwrap_or(0);
    let starts: Vec<usize> = (0..longest).step_by(SLICE).collect();
    let slice = |&start: &usize| slice_sums(s, factors, start, (start + SLICE).min(longest));
    let partials: Vec<Vec<f64>> = if parallel {
        starts.par_iter().map(slice).collect()
    } else {
        starts.iter().map(slice).collect()
    };
    let mut total = vec![0.0; factors.len()];
    for partial in &partials {
        total.iter_mut().zip(partial).for_each(|(t, p)| *t += p);
    }
    total
}

/// Phase points per block of the sweep: the block of s_i (16 KiB) stays in L1 while every
/// factor uses it, and for octave grids the block at s_{i+2m} read for m is the one read at
/// s_{i+m'} for m' = 2m right after, still in cache.
const BLOCK: usize = 2048;

/// The sums of [`sums_of_squared_second_differences`] restricted to start ≤ i < end, compiled
/// for the widest vector instructions the processor has (pulp's run-time dispatch; fused
/// multiply-adds, so every path gives the same bits).
fn slice_sums(s: &[f64], factors: &[usize], start: usize, end: usize) -> Vec<f64> {
    pulp::Arch::new().dispatch(Slice {
        s,
        factors,
        start,
        end,
    })
}

/// One slice of the sweep as a [`pulp::WithSimd`] task.
struct Slice<'a> {
    s: &'a [f64],
    factors: &'a [usize],
    start: usize,
    end: usize,
}

impl pulp::WithSimd for Slice<'_> {
    type Output = Vec<f64>;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> Vec<f64> {
        blocked_slice_sums(self.s, self.factors, self.start, self.end)
    }
}

/// [`slice_sums`]' body: block by block, every factor's squared second differences.
#[inline(always)]
fn blocked_slice_sums(s: &[f64], factors: &[usize], start: usize, end: usize) -> Vec<f64> {
    let mut acc = vec![[0.0; LANES]; factors.len()];
    let mut block = start;
    while block < end {
        for (acc, &m) in acc.iter_mut().zip(factors) {
            let stop = (block + BLOCK).min(end).min(s.len() - 2 * m);
            if block < stop {
                add_second_differences(acc, s, block..stop, m);
            }
        }
        block += BLOCK;
    }
    acc.iter().map(total_of_lanes).collect()
}

/// Independent accumulators in [`add_second_differences`].
pub(super) const LANES: usize = 8;

/// A chunk from `chunks_exact(LANES)` as an array, so the compiler drops the bounds checks.
#[inline(always)]
fn as_lanes(chunk: &[f64]) -> &[f64; LANES] {
    chunk
        .try_into()
        .expect("chunks_exact yields LANES elements")
}

/// Adds ((s_i + s_{i+2m})/2 − s_{i+m})² for i in `range` to the lanes of `acc`: a quarter of
/// each squared second difference. The halving is exact and the square is accumulated by a
/// fused multiply-add (one rounding, the same on every processor); eight independent
/// accumulators let the compiler keep several vector registers busy instead of waiting on one
/// chain of additions. Inlined into a [`pulp`] dispatch ([`slice_sums`],
/// [`add_second_differences_dispatched`]): called elsewhere, the fused multiply-add would be a
/// library call.
#[inline(always)]
pub(super) fn add_second_differences(
    acc: &mut [f64; LANES],
    s: &[f64],
    range: std::ops::Range<usize>,
    m: usize,
) {
    let (start, end) = (range.start, range.end);
    let (a, b, c) = (
        &s[start..end],
        &s[start + m..end + m],
        &s[start + 2 * m..end + 2 * m],
    );
    let chunks = a
        .chunks_exact(LANES)
        .zip(b.chunks_exact(LANES))
        .zip(c.chunks_exact(LANES));
    for ((a, b), c) in chunks {
        let (a, b, c) = (as_lanes(a), as_lanes(b), as_lanes(c));
        for l in 0..LANES {
            let half = 0.5 * (a[l] + c[l]) - b[l];
            acc[l] = half.mul_add(half, acc[l]);
        }
    }
    let tail = a.len() - a.len() % LANES;
    for (l, i) in (tail..a.len()).enumerate() {
        let half = 0.5 * (a[i] + c[i]) - b[i];
        acc[l] = half.mul_add(half, acc[l]);
    }
}

/// [`add_second_differences`] called on its own (the streaming path adds a piece at a time),
/// through the same run-time instruction-set dispatch as the in-memory sweep.
pub(super) fn add_second_differences_dispatched(
    acc: &mut [f64; LANES],
    s: &[f64],
    range: std::ops::Range<usize>,
    m: usize,
) {
    pulp::Arch::new().dispatch(Piece { acc, s, range, m });
}

/// One call of [`add_second_differences`] as a [`pulp::WithSimd`] task.
struct Piece<'a> {
    acc: &'a mut [f64; LANES],
    s: &'a [f64],
    range: std::ops::Range<usize>,
    m: usize,
}

impl pulp::WithSimd for Piece<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        add_second_differences(self.acc, self.s, self.range, self.m);
    }
}

/// 4 Σ acc: the sum of squared second differences from the quarter-squares in the lanes.
pub(super) fn total_of_lanes(acc: &[f64; LANES]) -> f64 {
    4.0 * acc.iter().sum::<f64>()
}

/// The curve of `kind` whose variance at factor m is `variance(phase, m)`, with the phase
/// S_i = Σ_{j<i} (y_j − ȳ) (N + 1 points, in units of τ₀) and the variance in the unit of
/// `y` squared. The factors are evaluated in parallel; each one alone, so the result does not
/// depend on the number of threads.
///
/// # Errors
/// As [`deviation`](fn@super::deviation).
pub(super) fn curve_from_variance(
    kind: DeviationKind,
    y: &[f64],
    sample_rate_hz: f64,
    grid: &TauGrid,
    variance: impl Fn(&[f64], usize) -> f64 + Sync,
) -> Result<DeviationCurve, AllanError> {
    let factors = checked_factors_for(kind, y.len(), sample_rate_hz, grid)?;
    if let Some(index) = y.iter().position(|v| !v.is_finite()) {
        return Err(AllanError::NonFinite { index });
    }
    let phase = centred_cumulative_sum(y);
    let sigma = factors
        .par_iter()
        .map(|&m| variance(&phase, m).sqrt())
        .collect();
    Ok(DeviationCurve::new(
        kind,
        factors,
        sigma,
        y.len(),
        sample_rate_hz,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    // Closed form: y = 1, 2, 3 has mean 2, so S = 0, −1, −1, 0.
    #[test]
    fn phase_of_a_mean_removed_series() {
        assert_eq!(
            centred_cumulative_sum(&[1.0, 2.0, 3.0]),
            [0.0, -1.0, -1.0, 0.0]
        );
    }

    // Oracle: the plain running sum, one addition at a time, on one piece (serial path) and
    // on several pieces (parallel path). The samples are multiples of 1/8 below 2^8 whose second
    // half negates the first, so the mean is exactly 0 and every partial sum (below 2^27) is
    // exact in both orders of addition: the results must be equal.
    #[test]
    fn piecewise_phase_equals_the_plain_running_sum() {
        for half in [502, (5 * PIECE + 1003) / 2] {
            let first: Vec<f64> = (0..half).map(|k| ((k * k) % 1009) as f64 / 8.0).collect();
            let y: Vec<f64> = first.iter().chain(&first).copied().collect::<Vec<_>>();
            let y: Vec<f64> = y
                .iter()
                .enumerate()
                .map(|(k, v)| if k < half { *v } else { -v })
                .collect();
            let mut plain = vec![0.0];
            for v in &y {
                plain.push(plain.last().unwrap() + v);
            }
            assert_eq!(centred_cumulative_sum(&y), plain, "n {}", y.len());
        }
    }

    // Oracle: each factor summed alone, term by term, over a range that spans several slices
    // and blocks with ragged ends; the blocked sweep regroups the same additions (1e-12
    // relative is rounding).
    #[test]
    fn blocked_sweep_equals_one_factor_at_a_time() {
        let s: Vec<f64> = (0..3 * SLICE + 517)
            .map(|k| (k as f64 * 0.013).sin() * 50.0 + ((k * 7919) % 101) as f64 * 0.01)
            .collect();
        let factors = [1, 2, 3, 8, 100, 2047, 2048, 2049, 40_000, s.len() / 2 - 1];
        let blocked = sums_of_squared_second_differences(&s, &factors);
        for (&m, got) in factors.iter().zip(&blocked) {
            let plain: f64 = (0..s.len() - 2 * m)
                .map(|i| (s[i + 2 * m] - 2.0 * s[i + m] + s[i]).powi(2))
                .sum();
            assert!((got / plain - 1.0).abs() < 1e-12, "m {m}: {got} vs {plain}");
        }
    }

    // The thread count must not change a single bit: the slices are fixed and added in order.
    #[test]
    fn parallel_slices_give_the_serial_sums_exactly() {
        let s: Vec<f64> = (0..2 * SLICE + 77)
            .map(|k| ((k * 7919) % 1013) as f64 * 0.01)
            .collect();
        let factors = [1, 5, 64, 1000, 2048, 50_000];
        assert_eq!(
            swept_sums(&s, &factors, true),
            swept_sums(&s, &factors, false)
        );
    }
}
