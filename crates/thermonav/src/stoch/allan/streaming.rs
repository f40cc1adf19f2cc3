//! The overlapping Allan deviation and its confidence intervals from a record read piece by
//! piece, in memory that does not grow with the record except for one phase value every
//! `stride` samples.
//!
//! - Averaging factors m ≤ `exact_max_factor`: exact. The last 2 `exact_max_factor` phase
//!   values are kept; every squared second difference (S_{i+2m} − 2 S_{i+m} + S_i)² is added
//!   once its last point arrives, so the sum is the in-memory one regrouped (rounding only).
//! - Larger m (which must be multiples of `stride` D): the decimated-overlap estimator, the
//!   same second differences averaged over the starting points i that are multiples of D,
//!   from the phase kept at every D-th point: σ²_D(τ) = Σ_{k=0}^{K} (P_{k+2q} − 2 P_{k+q} +
//!   P_k)² / (2 m² (K + 1)), P_k = S_{kD}, q = m/D, K = ⌊(N − 2m)/D⌋. It is unbiased like the
//!   full estimator and keeps one term in D; neighbouring terms overlap in all but D of their
//!   2m samples, so for m ≥ 2 `exact_max_factor` ≫ D it loses almost nothing: the tests bound
//!   the difference from the full estimator by a small fraction of the confidence interval.
//!   `n_terms` still reports N − 2m + 1, the count of the estimator it approximates (on which
//!   the EDF is computed).
//! - Noise identification for the confidence intervals (Stable32's rule, see
//!   [`identify_noise`](super::identify_noise)): the lag-1 autocorrelation needs only running
//!   sums of the m-averages and of their first and second differences, kept per factor; the
//!   m-averages of the large factors come exactly from the strided phase. The B1 ratio (fewer
//!   than 30 averages) uses the stored averages; when B1 says "phase noise", the R(n) test
//!   needs the modified Allan variance of the whole phase, which is not kept: flicker phase is
//!   assumed, as [`NoiseIdMethod::B1RatioRnUnavailable`](super::NoiseIdMethod) documents.
//!
//! The phase is centred on a provisional mean given at the start (the mean of a first
//! piece), not on the record's mean, which a single pass does not know; the second
//! differences cancel any mean exactly, so only rounding differs from the in-memory curve.
//!
//! Memory per channel: 2 `exact_max_factor` + N/D + a few per factor f64 values (N/D =
//! 5.4 M values, 43 MB, for 24 h at 1 kHz and D = 16).

use super::deviation::{
    LANES, add_second_differences_dispatched, avar_denominator, checked_factors, curve_of,
    total_of_lanes,
};
use super::noise_id::{MAX_DIFFERENCES, lag1_decision, noise_of_block_means};
use super::{
    AllanCurve, AllanError, AllanIntervals, CiSettings, MIN_AVERAGES_FOR_NOISE_ID, NoiseIdMethod,
    NoiseIdentification, PowerLawNoise, TauGrid, intervals_for_noise,
};

/// Where the streaming Allan deviation stops being exact, and the stride of the phase it keeps
/// beyond.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StreamingAllanSettings {
    /// Largest averaging factor computed exactly (from a window of 2 × this many phase values).
    pub exact_max_factor: usize,
    /// Stride D of the phase kept for the larger factors (which must be multiples of it).
    pub stride: usize,
}

impl Default for StreamingAllanSettings {
    /// Exact up to m = 8192 (8.2 s at 1 kHz), stride 16 beyond: the first approximate octave
    /// factor, 16384, averages 1024 starting points per period of m.
    fn default() -> Self {
        Self {
            exact_max_factor: 8192,
            stride: 16,
        }
    }
}

/// Running sums for the lag-1 autocorrelation of a series seen one value at a time, shifted
/// by its first value so the sums of squares do not cancel.
#[derive(Debug, Clone, Copy, Default)]
struct Lag1Sums {
    count: usize,
    shift: f64,
    sum: f64,
    sum_squares: f64,
    sum_lagged: f64,
    first: f64,
    last: f64,
}

impl Lag1Sums {
    fn push(&mut self, value: f64) {
        if self.count == 0 {
            self.shift = value;
        }
        let u = value - self.shift;
        if self.count == 0 {
            self.first = u;
        } else {
            self.sum_lagged += self.last * u;
        }
        self.sum += u;
        self.sum_squares += u * u;
        self.last = u;
        self.count += 1;
    }

    /// r1 = Σ (u_t − ū)(u_{t+1} − ū) / Σ (u_t − ū)², expanded in the running sums; `None` for a
    /// constant series.
    fn r1(&self) -> Option<f64> {
        let n = self.count as f64;
        let mean = self.sum / n;
        let denominator = self.sum_squares - self.sum * mean;
        let numerator = self.sum_lagged - mean * (2.0 * self.sum - self.first - self.last)
            + (n - 1.0) * mean * mean;
        (self.count >= 2 && denominator > 0.0).then(|| numerator / denominator)
    }
}

/// The lag-1 sums of the m-averages and of their differences, and the first averages (all of
/// them when there are fewer than [`MIN_AVERAGES_FOR_NOISE_ID`], for the B1 ratio).
#[derive(Debug, Clone, Default)]
struct AveragesNoise {
    levels: [Lag1Sums; MAX_DIFFERENCES + 1],
    previous: Option<f64>,
    previous_difference: Option<f64>,
    first_averages: Vec<f64>,
}

impl AveragesNoise {
    fn push(&mut self, average: f64) {
        self.levels[0].push(average);
        if let Some(previous) = self.previous {
            let difference = average - previous;
            self.levels[1].push(difference);
            if let Some(before) = self.previous_difference {
                self.levels[2].push(difference - before);
            }
            self.previous_difference = Some(difference);
        }
        self.previous = Some(average);
        if self.first_averages.len() < MIN_AVERAGES_FOR_NOISE_ID {
            self.first_averages.push(average);
        }
    }

    fn identify(&self, n_samples: usize) -> Option<NoiseIdentification> {
        let n_averages = self.levels[0].count;
        if n_averages < MIN_AVERAGES_FOR_NOISE_ID {
            return noise_of_block_means(
                self.first_averages.clone(),
                n_samples,
                phase_noise_unknown,
            );
        }
        Some(NoiseIdentification {
            noise: lag1_decision(|d| self.levels[d].r1())?,
            method: NoiseIdMethod::Lag1Autocorrelation,
            n_averages,
        })
    }
}

/// What a streaming pass assumes when B1 says "phase noise" (R(n) needs the whole phase).
fn phase_noise_unknown() -> (PowerLawNoise, NoiseIdMethod) {
    (
        PowerLawNoise::FlickerPhase,
        NoiseIdMethod::B1RatioRnUnavailable,
    )
}

/// One exactly computed averaging factor: the lanes of its sum of squared second differences,
/// the start of its next m-average, and the noise statistics of the averages.
#[derive(Debug, Clone)]
struct ExactFactor {
    m: usize,
    lanes: [f64; LANES],
    next_average_start: usize,
    noise: AveragesNoise,
}

/// The overlapping Allan deviation of rate data fed piece by piece (see the module docs).
#[derive(Debug, Clone)]
pub struct StreamingAllan {
    grid: TauGrid,
    settings: StreamingAllanSettings,
    offset: f64,
    samples: usize,
    recent: Vec<f64>,
    recent_start: usize,
    exact: Vec<ExactFactor>,
    strided: Vec<f64>,
}

impl StreamingAllan {
    /// A pass on `grid` whose phase is centred on `offset` (a provisional mean of the data).
    ///
    /// # Errors
    /// [`AllanError::StreamingSettings`] for a zero stride or exact bound.
    pub fn new(
        grid: TauGrid,
        offset: f64,
        settings: StreamingAllanSettings,
    ) -> Result<Self, AllanError> {
        if settings.stride == 0 || settings.exact_max_factor == 0 {
            return Err(AllanError::StreamingSettings {
                exact_max_factor: settings.exact_max_factor,
                stride: settings.stride,
            });
        }
        let exact = grid
            .factors(2 * settings.exact_max_factor)
            .into_iter()
            .map(|m| ExactFactor {
                m,
                lanes: [0.0; LANES],
                next_average_start: 0,
                noise: AveragesNoise::default(),
            })
            .collect();
        Ok(Self {
            grid,
            settings,
            offset,
            samples: 0,
            recent: vec![0.0],
            recent_start: 0,
            exact,
            strided: vec![0.0],
        })
    }

    /// Samples seen so far.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// Adds the next samples of the record.
    ///
    /// # Errors
    /// [`AllanError::NonFinite`] (index counted from the first sample of the record).
    pub fn push(&mut self, y: &[f64]) -> Result<(), AllanError> {
        if let Some(k) = y.iter().position(|v| !v.is_finite()) {
            return Err(AllanError::NonFinite {
                index: self.samples + k,
            });
        }
        let old_end = self.samples;
        self.extend_phase(y);
        let new_end = self.samples;
        for factor in &mut self.exact {
            add_new_terms(factor, &self.recent, self.recent_start, old_end, new_end);
        }
        self.forget_old_phase();
        Ok(())
    }

    /// Appends S_{t+1} = S_t + (y_t − offset) to the window, and to the strided store at
    /// multiples of the stride.
    fn extend_phase(&mut self, y: &[f64]) {
        let stride = self.settings.stride;
        let mut s = *self
            .recent
            .last()
            .expect("the window holds S_0 from the start");
        for &v in y {
            s += v - self.offset;
            self.samples += 1;
            self.recent.push(s);
            if self.samples % stride == 0 {
                self.strided.push(s);
            }
        }
    }

    /// Drops phase values no exact factor will read again (keeps the last 2 × the bound),
    /// in batches so that the copy is amortised.
    fn forget_old_phase(&mut self) {
        let keep = 2 * self.settings.exact_max_factor + 1;
        if self.recent.len() > 2 * keep + (1 << 16) {
            let drop = self.recent.len() - keep;
            self.recent.drain(..drop);
            self.recent_start += drop;
        }
    }

    /// The curve on the grid and its confidence limits at `ci`, for data at `sample_rate_hz`.
    ///
    /// # Errors
    /// As [`overlapping_adev`](super::overlapping_adev), plus
    /// [`AllanError::StreamingFactor`] for a factor above the exact bound that is not a
    /// multiple of the stride.
    pub fn finish(
        &self,
        sample_rate_hz: f64,
        ci: &CiSettings,
    ) -> Result<(AllanCurve, AllanIntervals), AllanError> {
        let n = self.samples;
        let factors = checked_factors(n, sample_rate_hz, &self.grid)?;
        let mut adev = Vec::with_capacity(factors.len());
        let mut alpha = Vec::with_capacity(factors.len());
        for &m in &factors {
            let (avar, noise) = match self.exact.iter().find(|f| f.m == m) {
                Some(f) => (
                    total_of_lanes(&f.lanes) / avar_denominator(n + 1, m),
                    f.noise.identify(n),
                ),
                None => self.strided_point(m)?,
            };
            adev.push(avar.sqrt());
            alpha.push(noise.map_or(0, |id| id.noise.alpha()));
        }
        let curve = curve_of(factors, adev, n, sample_rate_hz);
        let intervals = intervals_for_noise(&curve, alpha, ci);
        Ok((curve, intervals))
    }

    /// The decimated-overlap variance at m and the noise type of its m-averages, both from the
    /// strided phase.
    fn strided_point(&self, m: usize) -> Result<(f64, Option<NoiseIdentification>), AllanError> {
        let stride = self.settings.stride;
        if m % stride != 0 {
            return Err(AllanError::StreamingFactor { factor: m, stride });
        }
        let (n, q, p) = (self.samples, m / stride, &self.strided);
        let starts = (n - 2 * m) / stride + 1;
        let sum: f64 = (0..starts)
            .map(|k| (p[k + 2 * q] - 2.0 * p[k + q] + p[k]).powi(2))
            .sum();
        let avar = sum / (2.0 * (m as f64).powi(2) * starts as f64);
        let averages: Vec<f64> = (0..n / m)
            .map(|k| (p[(k + 1) * q] - p[k * q]) / m as f64)
            .collect();
        Ok((avar, noise_of_block_means(averages, n, phase_noise_unknown)))
    }
}

/// Adds to `factor` the second differences and m-averages whose last phase point is in
/// (old_end, new_end]; `recent` holds the phase from global index `start`.
fn add_new_terms(
    factor: &mut ExactFactor,
    recent: &[f64],
    start: usize,
    old_end: usize,
    new_end: usize,
) {
    let m = factor.m;
    if new_end >= 2 * m {
        let first = (old_end + 1).saturating_sub(2 * m);
        let last = new_end - 2 * m;
        if first <= last {
            add_second_differences_dispatched(
                &mut factor.lanes,
                recent,
                first - start..last + 1 - start,
                m,
            );
        }
    }
    while factor.next_average_start + m <= new_end {
        let b = factor.next_average_start - start;
        factor.noise.push((recent[b + m] - recent[b]) / m as f64);
        factor.next_average_start += m;
    }
}
