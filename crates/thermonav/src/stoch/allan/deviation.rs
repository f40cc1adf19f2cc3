//! The overlapping Allan deviation itself: the centred phase (cumulative sum) and one blocked
//! sweep that accumulates the squared second differences of every averaging factor at once.

use rayon::prelude::*;

use super::{AllanCurve, AllanError, TauGrid};

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
    validate_series(y, sample_rate_hz)?;
    let factors = grid.factors(y.len());
    if factors.is_empty() {
        return Err(AllanError::EmptyGrid { samples: y.len() });
    }
    let phase = centred_cumulative_sum(y);
    let tau0_s = 1.0 / sample_rate_hz;
    let n = y.len();
    let adev = sums_of_squared_second_differences(&phase, &factors)
        .iter()
        .zip(&factors)
        .map(|(sum, &m)| (sum / avar_denominator(phase.len(), m)).sqrt())
        .collect();
    Ok(AllanCurve {
        tau_s: factors.iter().map(|&m| m as f64 * tau0_s).collect(),
        adev,
        n_terms: factors.iter().map(|&m| n - 2 * m + 1).collect(),
        averaging_factor: factors,
        n_samples: n,
        tau0_s,
    })
}

/// Checks the rate, the length (at least 3) and that every sample is finite.
pub(crate) fn validate_series(y: &[f64], sample_rate_hz: f64) -> Result<(), AllanError> {
    if !(sample_rate_hz.is_finite() && sample_rate_hz > 0.0) {
        return Err(AllanError::Rate {
            rate_hz: sample_rate_hz,
        });
    }
    if y.len() < 3 {
        return Err(AllanError::TooShort { samples: y.len() });
    }
    match y.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(AllanError::NonFinite { index }),
        None => Ok(()),
    }
}

/// Mean by eight interleaved partial sums (vectorisable, and more accurate than one chain).
pub(crate) fn mean(y: &[f64]) -> f64 {
    let mut partial = [0.0_f64; 8];
    let chunks = y.chunks_exact(8);
    let rest: f64 = chunks.remainder().iter().sum();
    for chunk in chunks {
        for (p, v) in partial.iter_mut().zip(chunk) {
            *p += v;
        }
    }
    (partial.iter().sum::<f64>() + rest) / y.len() as f64
}

/// S_i = Σ_{j<i} (y_j − ȳ), i = 0..=N: the phase in units of τ₀.
///
/// The mean is removed so the running sum stays small (a 0.4 °/s gyro bias over 10⁶ samples
/// would otherwise grow it to 4·10⁵ and cost six digits in the differences). A running sum is
/// bound by the latency of one addition, so it runs as four independent chains over the four
/// quarters of the series, and each quarter is then shifted by the totals of those before it.
pub(crate) fn centred_cumulative_sum(y: &[f64]) -> Vec<f64> {
    const CHAINS: usize = 4;
    let mean = mean(y);
    let quarter = y.len() / CHAINS;
    let mut phase = vec![0.0; y.len() + 1];
    let mut sums = [0.0_f64; CHAINS];
    for k in 0..quarter {
        for (c, sum) in sums.iter_mut().enumerate() {
            *sum += y[c * quarter + k] - mean;
            phase[c * quarter + k + 1] = *sum;
        }
    }
    for k in CHAINS * quarter..y.len() {
        sums[CHAINS - 1] += y[k] - mean;
        phase[k + 1] = sums[CHAINS - 1];
    }
    let mut offset = 0.0;
    for c in 1..CHAINS {
        offset += sums[c - 1];
        let end = if c + 1 == CHAINS {
            y.len()
        } else {
            (c + 1) * quarter
        };
        phase[c * quarter + 1..=end]
            .iter_mut()
            .for_each(|p| *p += offset);
    }
    phase
}

/// 2 m² n, n = phase points − 2m: the Allan-variance denominator in units of τ₀ (τ₀ cancels
/// because the phase is in rate × samples).
fn avar_denominator(phase_len: usize, m: usize) -> f64 {
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
///
/// The index range is cut into fixed slices; each slice is one blocked sweep over all factors
/// ([`slice_sums`]) and the slices' partial sums are added in slice order.
fn sums_of_squared_second_differences(s: &[f64], factors: &[usize]) -> Vec<f64> {
    let longest = factors.iter().map(|&m| s.len() - 2 * m).max().unwrap_or(0);
    let starts: Vec<usize> = (0..longest).step_by(SLICE).collect();
    let slice = |&start: &usize| slice_sums(s, factors, start, (start + SLICE).min(longest));
    let work: usize = factors.iter().map(|&m| s.len() - 2 * m).sum();
    let partials: Vec<Vec<f64>> = if work < PARALLEL_WORK {
        starts.iter().map(slice).collect()
    } else {
        starts.par_iter().map(slice).collect()
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

/// The sums of [`sums_of_squared_second_differences`] restricted to start ≤ i < end.
fn slice_sums(s: &[f64], factors: &[usize], start: usize, end: usize) -> Vec<f64> {
    let mut sums = vec![0.0; factors.len()];
    for block in (start..end).step_by(BLOCK) {
        for (sum, &m) in sums.iter_mut().zip(factors) {
            let stop = (block + BLOCK).min(end).min(s.len() - 2 * m);
            if block < stop {
                *sum += block_sum_of_squares(
                    &s[block..stop],
                    &s[block + m..stop + m],
                    &s[block + 2 * m..stop + 2 * m],
                );
            }
        }
    }
    sums
}

/// Independent accumulators in [`block_sum_of_squares`].
const LANES: usize = 8;

/// A chunk from `chunks_exact(LANES)` as an array, so the compiler drops the bounds checks.
fn as_lanes(chunk: &[f64]) -> &[f64; LANES] {
    chunk
        .try_into()
        .expect("chunks_exact yields LANES elements")
}

/// Σ_i (c_i − 2 b_i + a_i)² over equal-length slices. Eight independent accumulators let the
/// compiler keep several vector registers busy instead of waiting on one chain of additions.
fn block_sum_of_squares(a: &[f64], b: &[f64], c: &[f64]) -> f64 {
    let mut acc = [0.0_f64; LANES];
    let chunks = a
        .chunks_exact(LANES)
        .zip(b.chunks_exact(LANES))
        .zip(c.chunks_exact(LANES));
    for ((a, b), c) in chunks {
        let (a, b, c) = (as_lanes(a), as_lanes(b), as_lanes(c));
        for l in 0..LANES {
            let d = c[l] - 2.0 * b[l] + a[l];
            acc[l] += d * d;
        }
    }
    let tail = a.len() - a.len() % LANES;
    let rest: f64 = (tail..a.len())
        .map(|i| c[i] - 2.0 * b[i] + a[i])
        .map(|d| d * d)
        .sum();
    acc.iter().sum::<f64>() + rest
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

    // Oracle: the plain running sum, one addition at a time (the four-chain version adds the
    // same numbers in another order: 1e-12 of the largest |S| is rounding).
    #[test]
    fn four_chain_phase_equals_the_plain_running_sum() {
        let y: Vec<f64> = (0..1003)
            .map(|k| ((k * k) as f64 * 0.37).sin() + 0.2)
            .collect();
        let m = y.iter().sum::<f64>() / y.len() as f64;
        let mut plain = vec![0.0];
        for v in &y {
            plain.push(plain.last().unwrap() + (v - m));
        }
        let fast = centred_cumulative_sum(&y);
        let scale = plain.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        for (f, p) in fast.iter().zip(&plain) {
            assert!((f - p).abs() <= 1e-12 * scale, "{f} vs {p}");
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
}
