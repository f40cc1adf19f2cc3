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
/// Each m costs O(N) (one pass over the cumulative sum). Assumes equally spaced samples without
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
    let adev = ms
        .iter()
        .map(|&m| overlapping_avar(&phase, m).sqrt())
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

/// Mean by Neumaier-compensated summation.
pub(crate) fn compensated_mean(y: &[f64]) -> f64 {
    let (mut sum, mut compensation) = (0.0_f64, 0.0_f64);
    for &v in y {
        let t = sum + v;
        compensation += if sum.abs() >= v.abs() {
            (sum - t) + v
        } else {
            (v - t) + sum
        };
        sum = t;
    }
    (sum + compensation) / y.len() as f64
}

/// Phase in units of tau0: s_0 = 0, s_{k+1} = s_k + (y_k - mean(y)), Kahan-compensated.
pub(crate) fn cumulative_phase(y: &[f64]) -> Vec<f64> {
    let mean = compensated_mean(y);
    let mut phase = Vec::with_capacity(y.len() + 1);
    let (mut sum, mut compensation) = (0.0_f64, 0.0_f64);
    phase.push(0.0);
    for &v in y {
        let term = (v - mean) - compensation;
        let t = sum + term;
        compensation = (t - sum) - term;
        sum = t;
        phase.push(sum);
    }
    phase
}

/// Overlapping Allan variance at factor m from phase in units of tau0 (the tau0 factors cancel).
pub(crate) fn overlapping_avar(phase: &[f64], m: usize) -> f64 {
    let n_terms = phase.len() - 2 * m;
    second_difference_sum_of_squares(phase, m) / (2.0 * (m * m) as f64 * n_terms as f64)
}

/// sum_i (s_{i+2m} - 2 s_{i+m} + s_i)^2 over all i with i + 2m < s.len().
///
/// Eight independent accumulators let the compiler keep several vector lanes busy.
fn second_difference_sum_of_squares(s: &[f64], m: usize) -> f64 {
    const LANES: usize = 8;
    let n = s.len() - 2 * m;
    let (x0, x1, x2) = (&s[..n], &s[m..m + n], &s[2 * m..2 * m + n]);
    let mut acc = [0.0_f64; LANES];
    let chunks = x0
        .chunks_exact(LANES)
        .zip(x1.chunks_exact(LANES))
        .zip(x2.chunks_exact(LANES));
    for ((a, b), c) in chunks {
        for l in 0..LANES {
            let d = c[l] - 2.0 * b[l] + a[l];
            acc[l] += d * d;
        }
    }
    let tail = n - n % LANES;
    let rest: f64 = (tail..n)
        .map(|i| x2[i] - 2.0 * x1[i] + x0[i])
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
