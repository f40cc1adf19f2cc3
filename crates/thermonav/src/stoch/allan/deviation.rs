//! Overlapping Allan deviation of a rate (frequency-type) series, with its tau grids.

use super::AllanError;

/// Fewest samples for which an overlapping Allan deviation exists (m = 1 needs two terms).
pub const MIN_SAMPLES: usize = 3;

/// Which averaging factors m (tau = m * tau0) to evaluate.
///
/// Every grid keeps only the m that leave at least two terms in the estimator,
/// `n_terms = N - 2m + 1 >= 2`, i.e. `m <= (N - 1) / 2` for N samples. This is allantools'
/// rule (`tau_generator` followed by `remove_small_ns`, which drops results with one term).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TauGrid {
    /// m = 1, 2, 4, 8, ... (allantools `taus='octave'`).
    Octave,
    /// m = 1, 2, 4, 10, 20, 40, 100, ... (allantools `taus='decade'`, Stable32's decade spacing).
    Decade,
    /// About `points_per_decade` log-spaced factors per decade: m = round(10^(j / points_per_decade)),
    /// j = 0, 1, 2, ..., duplicates removed (so fewer points in the first decade).
    Dense {
        /// Points per decade of tau, at least 1.
        points_per_decade: usize,
    },
    /// These averaging factors (sorted and de-duplicated); each must be usable, else an error.
    Explicit(Vec<usize>),
}

/// Something about the input worth telling the caller although the curve was computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AllanWarning {
    /// Every sample has the same value: the deviation is exactly zero at every tau.
    ConstantInput,
}

/// An overlapping Allan deviation curve, in the units of the input series.
#[derive(Debug, Clone, PartialEq)]
pub struct AllanCurve {
    /// Averaging time tau = m / sample rate, s.
    pub tau_s: Vec<f64>,
    /// Overlapping Allan deviation at each tau, in the units of the input.
    pub adev: Vec<f64>,
    /// Number of second-difference terms in the estimator: N - 2m + 1.
    pub n_terms: Vec<usize>,
    /// Averaging factor m (tau = m * tau0).
    pub averaging_factor: Vec<usize>,
    /// Sample rate of the input series, Hz.
    pub sample_rate_hz: f64,
    /// Number of input samples N.
    pub n_samples: usize,
    /// Remarks on the input (e.g. a constant series).
    pub warnings: Vec<AllanWarning>,
}

/// Largest averaging factor with at least two estimator terms for `n_samples` samples.
pub fn max_averaging_factor(n_samples: usize) -> usize {
    n_samples.saturating_sub(1) / 2
}

/// The averaging factors that `grid` selects for a series of `n_samples` samples.
///
/// # Errors
/// A dense grid with zero points per decade, an explicit factor of zero, or an explicit
/// factor above [`max_averaging_factor`].
pub fn averaging_factors(grid: &TauGrid, n_samples: usize) -> Result<Vec<usize>, AllanError> {
    let max_m = max_averaging_factor(n_samples);
    match grid {
        TauGrid::Octave => Ok(octave_factors(max_m)),
        TauGrid::Decade => Ok(decade_factors(max_m)),
        TauGrid::Dense { points_per_decade } => dense_factors(*points_per_decade, max_m),
        TauGrid::Explicit(ms) => explicit_factors(ms, max_m, n_samples),
    }
}

fn octave_factors(max_m: usize) -> Vec<usize> {
    std::iter::successors(Some(1_usize), |m| m.checked_mul(2))
        .take_while(|&m| m <= max_m)
        .collect()
}

fn decade_factors(max_m: usize) -> Vec<usize> {
    std::iter::successors(Some(1_usize), |p| p.checked_mul(10))
        .flat_map(|p| [p, 2 * p, 4 * p])
        .take_while(|&m| m <= max_m)
        .collect()
}

fn dense_factors(points_per_decade: usize, max_m: usize) -> Result<Vec<usize>, AllanError> {
    if points_per_decade == 0 {
        return Err(AllanError::ZeroPointsPerDecade);
    }
    let mut ms: Vec<usize> = Vec::new();
    for j in 0.. {
        let m = 10_f64.powf(j as f64 / points_per_decade as f64).round() as usize;
        if m > max_m {
            break;
        }
        if ms.last() != Some(&m) {
            ms.push(m);
        }
    }
    Ok(ms)
}

fn explicit_factors(ms: &[usize], max_m: usize, n: usize) -> Result<Vec<usize>, AllanError> {
    let mut sorted = ms.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    if sorted.first() == Some(&0) {
        return Err(AllanError::ZeroAveragingFactor);
    }
    match sorted.last() {
        Some(&m) if m > max_m => Err(AllanError::AveragingFactorTooLarge {
            m,
            max: max_m,
            n_samples: n,
        }),
        _ => Ok(sorted),
    }
}

/// Overlapping Allan deviation of a rate series `y` sampled at `sample_rate_hz`.
///
/// With tau0 = 1/rate, the series is integrated to phase x_k = tau0 * sum_{i<k} (y_i - mean(y)),
/// k = 0..N (N + 1 values; the mean is removed first only to keep the running sum small, it
/// cancels in the second difference), and for each averaging factor m (NIST SP 1065 eq. 11,
/// IEEE Std 952 Annex C):
///
/// sigma^2(m tau0) = 1 / (2 (m tau0)^2 (N - 2m + 1)) * sum_{i=0}^{N-2m} (x_{i+2m} - 2 x_{i+m} + x_i)^2
///
/// Each m costs O(N); all m share one blocked sweep over the cumulative sum, and large
/// problems (N times the number of taus above 2^23) spread the taus over the available cores
/// with scoped threads (results identical to a single thread). Assumes equally spaced samples without
/// gaps or dead time. This is allantools `oadev(y, rate, data_type='freq')` and Stable32's
/// "Overlapping Allan" on frequency data, including its term count `#` = N - 2m + 1.
///
/// # Errors
/// Fewer than [`MIN_SAMPLES`] samples, a non-finite sample, a sample rate that is not finite
/// and positive, or an invalid grid (see [`averaging_factors`]).
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
    let ms = averaging_factors(grid, y.len())?;
    let phase = cumulative_phase(y);
    let adev = second_difference_sums_of_squares(&phase, &ms)
        .iter()
        .zip(&ms)
        .map(|(sum_sq, &m)| (sum_sq / avar_denominator(phase.len(), m)).sqrt())
        .collect();
    Ok(AllanCurve {
        tau_s: ms.iter().map(|&m| m as f64 / sample_rate_hz).collect(),
        adev,
        n_terms: ms.iter().map(|&m| y.len() + 1 - 2 * m).collect(),
        averaging_factor: ms,
        sample_rate_hz,
        n_samples: y.len(),
        warnings: input_warnings(y),
    })
}

/// Checks length, finiteness and sample rate of a rate series.
pub(crate) fn validate_series(y: &[f64], sample_rate_hz: f64) -> Result<(), AllanError> {
    if !(sample_rate_hz.is_finite() && sample_rate_hz > 0.0) {
        return Err(AllanError::InvalidSampleRate(sample_rate_hz));
    }
    if y.len() < MIN_SAMPLES {
        return Err(AllanError::TooFewSamples {
            got: y.len(),
            min: MIN_SAMPLES,
        });
    }
    match y.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(AllanError::NonFiniteSample {
            index,
            value: y[index],
        }),
        None => Ok(()),
    }
}

fn input_warnings(y: &[f64]) -> Vec<AllanWarning> {
    if y.iter().all(|&v| v == y[0]) {
        vec![AllanWarning::ConstantInput]
    } else {
        Vec::new()
    }
}

/// Mean by eight interleaved partial sums (pairwise-like accuracy, vectorisable).
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

/// Phase in units of tau0: s_0 = 0, s_{k+1} = s_k + (y_k - mean(y)).
///
/// The mean is removed first so the running sum stays near zero (a 0.4 deg/s gyro bias over
/// 10^6 samples would otherwise grow it to 4e5 and cost ~6 digits in the differences).
/// The sum runs as four independent chains over the four quarters of the series (a running
/// sum is latency-bound; four chains overlap), then each quarter is shifted by the totals of
/// the quarters before it.
pub(crate) fn cumulative_phase(y: &[f64]) -> Vec<f64> {
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

/// 2 m^2 (number of terms): the Allan-variance denominator in units of tau0.
fn avar_denominator(phase_len: usize, m: usize) -> f64 {
    2.0 * (m as f64).powi(2) * (phase_len - 2 * m) as f64
}

/// Overlapping Allan variance at factor m from phase in units of tau0 (the tau0 factors cancel).
pub(crate) fn overlapping_avar(phase: &[f64], m: usize) -> f64 {
    second_difference_sums_of_squares(phase, &[m])[0] / avar_denominator(phase.len(), m)
}

/// For each m in `ms`: sum_i (s_{i+2m} - 2 s_{i+m} + s_i)^2 over all i with i + 2m < s.len().
///
/// Large problems (more than [`PARALLEL_WORK`] element-terms) split the factors over the
/// available cores with scoped threads; each factor's sum is still computed by one thread in
/// one fixed order, so the result does not depend on the number of threads.
fn second_difference_sums_of_squares(s: &[f64], ms: &[usize]) -> Vec<f64> {
    let threads = worker_count(s.len().saturating_mul(ms.len()), ms.len());
    if threads <= 1 {
        return blocked_sums_of_squares(s, ms);
    }
    let groups: Vec<Vec<usize>> = (0..threads)
        .map(|t| ms.iter().skip(t).step_by(threads).copied().collect())
        .collect();
    let results: Vec<Vec<f64>> = std::thread::scope(|scope| {
        let handles: Vec<_> = groups
            .iter()
            .map(|group| scope.spawn(|| blocked_sums_of_squares(s, group)))
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("a summing thread does not panic"))
            .collect()
    });
    (0..ms.len())
        .map(|i| results[i % threads][i / threads])
        .collect()
}

/// Element-terms above which the sums are spread over several threads.
const PARALLEL_WORK: usize = 1 << 23;

fn worker_count(work: usize, n_factors: usize) -> usize {
    if work < PARALLEL_WORK {
        return 1;
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    cores.min(n_factors)
}

/// One sweep over i in blocks for all m together: the block's s_i is shared by every m and,
/// for small m, s_{i+m} and s_{i+2m} fall in the same cache lines, so the series is read
/// from memory a few times in all instead of up to three times per m.
fn blocked_sums_of_squares(s: &[f64], ms: &[usize]) -> Vec<f64> {
    const BLOCK: usize = 2048;
    let mut sums = vec![0.0; ms.len()];
    let longest = ms.iter().map(|&m| s.len() - 2 * m).max().unwrap_or(0);
    for start in (0..longest).step_by(BLOCK) {
        for (sum, &m) in sums.iter_mut().zip(ms) {
            let end = (start + BLOCK).min(s.len() - 2 * m);
            if start < end {
                let (a, b) = (&s[start..end], &s[start + m..end + m]);
                *sum += block_sum_of_squares(a, b, &s[start + 2 * m..end + 2 * m]);
            }
        }
    }
    sums
}

/// A chunk from `chunks_exact(8)` as an array, so the compiler drops the bounds checks.
fn as_lanes(chunk: &[f64]) -> &[f64; 8] {
    chunk.try_into().expect("chunks_exact(8) yields 8 elements")
}

/// sum_i (c_i - 2 b_i + a_i)^2 over equal-length slices.
///
/// Eight independent accumulators let the compiler keep several vector lanes busy.
fn block_sum_of_squares(a: &[f64], b: &[f64], c: &[f64]) -> f64 {
    const LANES: usize = 8;
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

    // Closed forms: the grids are short enough to write out by hand.
    #[test]
    fn octave_grid_stops_at_half_the_samples() {
        // N = 9: m <= 4 (n_terms = 10 - 2m >= 2).
        assert_eq!(averaging_factors(&TauGrid::Octave, 9).unwrap(), [1, 2, 4]);
        assert_eq!(averaging_factors(&TauGrid::Octave, 8).unwrap(), [1, 2]);
    }

    #[test]
    fn decade_grid_is_one_two_four() {
        let ms = averaging_factors(&TauGrid::Decade, 1000).unwrap();
        assert_eq!(ms, [1, 2, 4, 10, 20, 40, 100, 200, 400]);
    }

    #[test]
    fn dense_grid_is_unique_and_log_spaced() {
        let ms = averaging_factors(
            &TauGrid::Dense {
                points_per_decade: 5,
            },
            250,
        )
        .unwrap();
        // 10^(j/5) rounded: 1, 2(1.58), 3(2.51), 4(3.98), 6(6.31), 10, 16, 25, 40, 63, 100
        assert_eq!(ms, [1, 2, 3, 4, 6, 10, 16, 25, 40, 63, 100]);
    }

    #[test]
    fn explicit_grid_rejects_zero_and_too_large() {
        let err = averaging_factors(&TauGrid::Explicit(vec![0, 1]), 10).unwrap_err();
        assert_eq!(err, AllanError::ZeroAveragingFactor);
        let err = averaging_factors(&TauGrid::Explicit(vec![5]), 10).unwrap_err();
        assert_eq!(
            err,
            AllanError::AveragingFactorTooLarge {
                m: 5,
                max: 4,
                n_samples: 10
            }
        );
    }

    #[test]
    fn cumulative_phase_of_mean_removed_series() {
        let s = cumulative_phase(&[1.0, 2.0, 3.0]);
        assert_eq!(s, [0.0, -1.0, -1.0, 0.0]);
    }
}
