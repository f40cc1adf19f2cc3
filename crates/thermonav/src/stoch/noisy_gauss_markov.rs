//! Gauss-Markov bias seen through white noise: exact maximum likelihood on irregular timestamps.
//!
//! A static MEMS channel is a first-order Gauss-Markov bias b plus white noise of density N:
//! y_k = b(t_k) + n_k, var(n_k) = N²/d_k, where d_k is the interval sample k averages over.
//! Fitting an AR(1) to y (the paper's route) mistakes the white noise for decorrelation and
//! shortens Tc badly when N²/σ² is comparable to Tc (it is for datasheet ADIS16364 figures: the
//! white noise dominates every sample). This estimator models both: the likelihood of y is
//! computed exactly by a scalar Kalman filter that steps the bias with each sample's own dt_k
//! (method.md equations 3-4),
//!
//! b_k = φ_k b_{k−1} + w_k, φ_k = exp(−dt_k/Tc), var(w_k) = σ²(1 − φ_k²), b_0 ~ N(0, σ²).
//!
//! The overall scale σ² is concentrated out in closed form, leaving a two-dimensional search
//! over ln Tc and ln ρ, ρ = N²/σ² (seconds): a coarse grid, then Nelder-Mead. The 95 % interval
//! of Tc is the likelihood-ratio interval of the profile log-likelihood of ln Tc (maximised
//! over ln ρ), so it stays positive and is as asymmetric as the likelihood.
//!
//! Every likelihood is one Kalman pass over the record, bound by the latency of its per-step
//! division; passes for several (Tc, ρ) run as lanes of one pass at about the cost of one. So
//! each search asks for several points at once: the grid nine ρ a column, Nelder-Mead its four
//! candidates an iteration, the profile three ρ a Newton step.
//!
//! The data are demeaned first (turn-on bias and deterministic offsets are not part of the
//! stochastic model). Reference: Harvey (1989), *Forecasting, structural time series models and
//! the Kalman filter*, §3.4 (prediction-error decomposition, concentrated likelihood).

use serde::Serialize;

use crate::optimise::brent::brent_maximum;
use crate::optimise::nelder_mead::{Objective, nelder_mead};
use crate::optimise::newton::newton_maximum;

/// Why the estimator cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NoisyGaussMarkovError {
    /// Too few samples.
    #[error("need at least {needed} samples for a Gauss-Markov + white-noise fit, got {got}")]
    TooShort {
        /// Minimum.
        needed: usize,
        /// Given.
        got: usize,
    },
    /// Times and values of different lengths.
    #[error("{times} times but {values} values")]
    Length {
        /// Number of times.
        times: usize,
        /// Number of values.
        values: usize,
    },
    /// A non-finite value.
    #[error("sample {index} is not a finite number")]
    NonFinite {
        /// Index of the sample.
        index: usize,
    },
    /// Times not strictly increasing.
    #[error("time {index} does not increase ({previous_s} s then {time_s} s)")]
    Order {
        /// Index of the sample.
        index: usize,
        /// Previous time.
        previous_s: f64,
        /// This time.
        time_s: f64,
    },
    /// Zero variance.
    #[error("the series is constant: no noise to model")]
    Constant,
}

/// A fitted model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NoisyGaussMarkovFit {
    /// Correlation time Tc, s.
    pub correlation_time_s: f64,
    /// Gauss-Markov standard deviation σ, unit of the data.
    pub sigma: f64,
    /// White-noise density N, unit of the data × √s.
    pub white_noise_density: f64,
    /// 95 % interval of Tc, s; the upper side is `None` when the likelihood does not bound it.
    pub ci95_correlation_time_s: [Option<f64>; 2],
    /// Maximised log-likelihood.
    pub log_likelihood: f64,
    /// Samples used.
    pub n_samples: usize,
}

/// The outcome: a model, or why the data admit none.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum NoisyGaussMarkovOutcome {
    /// A Gauss-Markov model with an interior maximum.
    Model(NoisyGaussMarkovFit),
    /// The maximum sits at a bound of the search: no Gauss-Markov equivalent.
    NoEquivalent {
        /// Why, in words.
        reason: String,
    },
}

/// Samples: times (s) and values, with the averaging interval d_k of each.
struct Record {
    dt_s: Vec<f64>,
    average_s: Vec<f64>,
    /// 1/d_k, 1/s.
    inverse_average_per_s: Vec<f64>,
    /// The smallest and largest 1/d_k.
    min_inverse_average_per_s: f64,
    max_inverse_average_per_s: f64,
    /// The first interval: the one most of a sampled record's intervals are close to, about
    /// which the transitions are expanded ([`Transitions`]).
    nominal_dt_s: f64,
    /// dt_k − dt₀, s (exactly the difference [`Transitions::at`] takes), and its largest size.
    offset_s: Vec<f64>,
    max_abs_offset_s: f64,
    values: Vec<f64>,
}

/// Fits the Gauss-Markov + white-noise model by exact maximum likelihood.
///
/// `times_s` are the sample times (strictly increasing); each sample is taken to average over
/// the interval since the previous one (the first over the next interval).
///
/// # Errors
/// [`NoisyGaussMarkovError`] for fewer than 20 samples, mismatched lengths, non-finite values,
/// non-increasing times or a constant series.
pub fn fit_noisy_gauss_markov(
    times_s: &[f64],
    values: &[f64],
) -> Result<NoisyGaussMarkovOutcome, NoisyGaussMarkovError> {
    let record = prepare(times_s, values)?;
    let span_s = times_s[times_s.len() - 1] - times_s[0];
    let min_dt = record.dt_s.iter().copied().fold(f64::INFINITY, f64::min);
    let bounds = Bounds {
        ln_tc: [(0.5 * min_dt).ln(), (2.0 * span_s).ln()],
        ln_rho: [(1e-6 * min_dt).ln(), (1e6 * span_s).ln()],
    };
    let start = grid_start(&record, &bounds);
    let best = nelder_mead(&Likelihood(&record, &bounds), start, [0.5, 0.5], 400);
    Ok(outcome(&record, &bounds, best))
}

fn prepare(times_s: &[f64], values: &[f64]) -> Result<Record, NoisyGaussMarkovError> {
    const MIN_SAMPLES: usize = 20;
    if times_s.len() != values.len() {
        return Err(NoisyGaussMarkovError::Length {
            times: times_s.len(),
            values: values.len(),
        });
    }
    if values.len() < MIN_SAMPLES {
        return Err(NoisyGaussMarkovError::TooShort {
            needed: MIN_SAMPLES,
            got: values.len(),
        });
    }
    if let Some(index) = values.iter().chain(times_s).position(|v| !v.is_finite()) {
        return Err(NoisyGaussMarkovError::NonFinite {
            index: index % values.len(),
        });
    }
    if let Some(k) = (1..times_s.len()).find(|&k| times_s[k] <= times_s[k - 1]) {
        return Err(NoisyGaussMarkovError::Order {
            index: k,
            previous_s: times_s[k - 1],
            time_s: times_s[k],
        });
    }
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let centred: Vec<f64> = values.iter().map(|v| v - mean).collect();
    if centred.iter().all(|&v| v == 0.0) {
        return Err(NoisyGaussMarkovError::Constant);
    }
    let mut dt_s: Vec<f64> = times_s.windows(2).map(|w| w[1] - w[0]).collect();
    dt_s.insert(0, dt_s[0]);
    let inverse_average_per_s: Vec<f64> = dt_s.iter().map(|d| 1.0 / d).collect();
    let offset_s: Vec<f64> = dt_s.iter().map(|d| d - dt_s[0]).collect();
    Ok(Record {
        min_inverse_average_per_s: inverse_average_per_s
            .iter()
            .copied()
            .fold(f64::MAX, f64::min),
        max_inverse_average_per_s: inverse_average_per_s.iter().copied().fold(0.0, f64::max),
        inverse_average_per_s,
        average_s: dt_s.clone(),
        nominal_dt_s: dt_s[0],
        max_abs_offset_s: offset_s.iter().fold(0.0, |m, o| o.abs().max(m)),
        offset_s,
        dt_s,
        values: centred,
    })
}

/// Search box in (ln Tc, ln ρ).
struct Bounds {
    ln_tc: [f64; 2],
    ln_rho: [f64; 2],
}

impl Bounds {
    fn contains(&self, p: [f64; 2]) -> bool {
        (self.ln_tc[0]..=self.ln_tc[1]).contains(&p[0])
            && (self.ln_rho[0]..=self.ln_rho[1]).contains(&p[1])
    }

    fn at_edge(&self, p: [f64; 2]) -> Option<&'static str> {
        if near_bound(p[0], self.ln_tc[1]) {
            Some(
                "the likelihood keeps rising as Tc grows past twice the record length: the bias behaves as a random walk or drift over this record",
            )
        } else if near_bound(p[0], self.ln_tc[0]) {
            Some(
                "the likelihood peaks at Tc below the sampling interval: no correlation is visible, the channel looks white",
            )
        } else if near_bound(p[1], self.ln_rho[1]) {
            Some(
                "the white-noise share is at the top of its search range: the Gauss-Markov part cannot be separated from it",
            )
        } else {
            None
        }
    }
}

fn near_bound(value: f64, bound: f64) -> bool {
    (value - bound).abs() < 0.05
}

/// Unit-scale Kalman pass: Σ v²/S and Σ ln S for Tc = `tc_s`, ρ = `rho_s`.
fn innovations(record: &Record, tc_s: f64, rho_s: f64) -> (f64, f64) {
    let [out] = passes_at(record, [[tc_s, rho_s]]);
    out
}

/// [`innovations`] at `N` points (Tc, ρ) in one multi-lane pass, bit for bit: with the
/// near-nominal transitions when every lane takes them (the sampled records' case), otherwise
/// with [`Transitions::at`] in every lane (which gives the near-nominal value wherever that
/// applies).
fn passes_at<const N: usize>(record: &Record, points: [[f64; 2]; N]) -> [(f64, f64); N] {
    let transitions = points.map(|[tc_s, _]| Transitions::new(record.nominal_dt_s, tc_s));
    let rho_s = points.map(|[_, rho_s]| rho_s);
    let n = record.values.len();
    if transitions.iter().all(|t| t.all_near_nominal(record)) {
        let offsets = &record.offset_s[..n];
        kalman_pass(record, rho_s, |k| {
            std::array::from_fn(|j| transitions[j].near_nominal(offsets[k]))
        })
    } else {
        let dt_s = &record.dt_s[..n];
        kalman_pass(record, rho_s, |k| {
            std::array::from_fn(|j| transitions[j].at(dt_s[k]))
        })
    }
}

/// φ_k = exp(−dt_k/Tc) of every step of a record at one Tc ([`Transitions::at`], so the same
/// values), for the passes that share a Tc: a column of the grid, the search of a profile.
/// Element 0 (the first sample, no transition) is unused.
fn transition_table(record: &Record, tc_s: f64) -> Vec<f64> {
    let transitions = Transitions::new(record.nominal_dt_s, tc_s);
    if transitions.all_near_nominal(record) {
        (record.offset_s.iter())
            .map(|&offset| transitions.near_nominal(offset))
            .collect()
    } else {
        record.dt_s.iter().map(|&dt| transitions.at(dt)).collect()
    }
}

/// The Kalman pass of [`innovations`] for `N` filters at once (lanes with their own ρ and their
/// own transitions `phi_at(k)[j]`, k ≥ 1, sharing the loads of the record), each lane doing
/// exactly the arithmetic of the one-lane pass, so the results are those of `N` separate
/// passes. The pass is bound by the latency of each step's division, not by arithmetic: four
/// lanes cost about what one does (measured: 0.21 ms for one lane or four over 21 578 steps).
///
/// Σ ln S is the [`LogProduct`] of the factors, renormalised every 8 steps; when every factor
/// is known beforehand to lie in the product's range (S = p + ρ/d_k with 0 ≤ p ≤ 1, so
/// ρ min(1/d) ≥ 1e-30 and 2 + ρ max(1/d) ≤ 1e30 suffice) the range test leaves the loop, and
/// the loop runs in blocks of 8 steps with the renormalisation between blocks: the same
/// products in the same order as [`LogProduct::multiply`]. Otherwise each lane runs with
/// [`LogProduct::multiply`] itself.
#[inline(always)]
fn kalman_pass<const N: usize>(
    record: &Record,
    rho_s: [f64; N],
    phi_at: impl Fn(usize) -> [f64; N],
) -> [(f64, f64); N] {
    let n = record.values.len();
    let values = &record.values[..n];
    let inverse_d = &record.inverse_average_per_s[..n];
    let in_range = rho_s.iter().all(|&rho| {
        rho * record.min_inverse_average_per_s >= LogProduct::MIN_FACTOR
            && 2.0 + rho * record.max_inverse_average_per_s <= LogProduct::MAX_FACTOR
    });
    if !in_range {
        return std::array::from_fn(|j| {
            let rho = rho_s[j];
            let mut lanes = Lanes::new();
            let mut log_det = LogProduct::default();
            for k in 0..n {
                if k > 0 {
                    lanes.predict([phi_at(k)[j]]);
                }
                let s = lanes.update(&[rho], inverse_d[k], values[k]);
                log_det.multiply(s[0]);
            }
            (lanes.weighted[0], log_det.ln())
        });
    }
    let mut lanes = Lanes::<N>::new();
    let mut product = [1.0_f64; N];
    let mut exponent = [0_i64; N];
    let multiply = |product: &mut [f64; N], s: [f64; N]| {
        for (m, s) in product.iter_mut().zip(s) {
            *m *= s;
        }
    };
    let block = LogProduct::RENORMALISE_EVERY;
    multiply(&mut product, lanes.update(&rho_s, inverse_d[0], values[0]));
    let mut start = 1;
    while start < n {
        let end = (start / block + 1) * block;
        if end <= n {
            for k in start..end {
                lanes.predict(phi_at(k));
                multiply(&mut product, lanes.update(&rho_s, inverse_d[k], values[k]));
            }
            for (m, e) in product.iter_mut().zip(&mut exponent) {
                *e += split_exponent(m);
            }
        } else {
            for k in start..n {
                lanes.predict(phi_at(k));
                multiply(&mut product, lanes.update(&rho_s, inverse_d[k], values[k]));
            }
        }
        start = end;
    }
    std::array::from_fn(|j| {
        (
            lanes.weighted[j],
            product[j].ln() + exponent[j] as f64 * std::f64::consts::LN_2,
        )
    })
}

/// The state of `N` unit-scale Kalman filters over one record: bias estimate x, its variance p,
/// and Σ v²/S so far.
struct Lanes<const N: usize> {
    x: [f64; N],
    p: [f64; N],
    weighted: [f64; N],
}

impl<const N: usize> Lanes<N> {
    fn new() -> Self {
        Self {
            x: [0.0; N],
            p: [1.0; N],
            weighted: [0.0; N],
        }
    }

    /// b_k = φ b_{k−1} + w_k, var(w_k) = 1 − φ², each lane with its own φ.
    #[inline(always)]
    fn predict(&mut self, phi: [f64; N]) {
        for ((x, p), phi) in self.x.iter_mut().zip(&mut self.p).zip(phi) {
            *x *= phi;
            *p = phi * phi * *p + (1.0 - phi * phi);
        }
    }

    /// The measurement y with variance ρ/d: returns the innovation variances S.
    #[inline(always)]
    fn update(&mut self, rho_s: &[f64; N], inverse_d: f64, y: f64) -> [f64; N] {
        let mut out = [0.0; N];
        for j in 0..N {
            let (x, p) = (&mut self.x[j], &mut self.p[j]);
            let s = *p + rho_s[j] * inverse_d;
            let inverse_s = 1.0 / s;
            let v = y - *x;
            self.weighted[j] += v * v * inverse_s;
            let gain = *p * inverse_s;
            *x += gain * v;
            *p -= gain * *p;
            out[j] = s;
        }
        out
    }
}

/// exp(−dt/Tc) for the intervals of a record: one `exp` per likelihood for the nominal
/// interval, and for an interval within 0.1 % of Tc of it the nominal value times the Taylor
/// polynomial of exp(−u), u = (dt − dt₀)/Tc, to the fourth power (the next term is u⁵/120 <
/// 1e-17, below rounding); other intervals (a dropped sample, Tc below the jitter) by `exp`.
/// A sampled record's intervals are the nominal one give or take the clock's jitter, so the
/// polynomial serves nearly every step at a fraction of the cost of `exp`.
struct Transitions {
    nominal_dt_s: f64,
    nominal: f64,
    inverse_tc_per_s: f64,
}

impl Transitions {
    fn new(nominal_dt_s: f64, tc_s: f64) -> Self {
        Self {
            nominal_dt_s,
            nominal: (-nominal_dt_s / tc_s).exp(),
            inverse_tc_per_s: 1.0 / tc_s,
        }
    }

    #[inline(always)]
    fn at(&self, dt_s: f64) -> f64 {
        let u = (dt_s - self.nominal_dt_s) * self.inverse_tc_per_s;
        if u.abs() < Self::NEAR {
            self.nominal * Self::polynomial(u)
        } else {
            (-dt_s * self.inverse_tc_per_s).exp()
        }
    }

    /// |u| below which the polynomial serves.
    const NEAR: f64 = 1e-3;

    /// exp(−u) to rounding for |u| < [`Self::NEAR`].
    #[inline(always)]
    fn polynomial(u: f64) -> f64 {
        1.0 - u * (1.0 - u * (0.5 - u * (1.0 / 6.0 - u / 24.0)))
    }

    /// Whether every interval of `record` takes the polynomial in [`Self::at`]: the largest
    /// |dt − dt₀| over Tc below [`Self::NEAR`] (rounding is monotone, so then every |u| is).
    fn all_near_nominal(&self, record: &Record) -> bool {
        record.max_abs_offset_s * self.inverse_tc_per_s < Self::NEAR
    }

    /// [`Self::at`] for an interval dt₀ + `offset_s` known to take the polynomial
    /// ([`Self::all_near_nominal`]): the same value without the test.
    #[inline(always)]
    fn near_nominal(&self, offset_s: f64) -> f64 {
        self.nominal * Self::polynomial(offset_s * self.inverse_tc_per_s)
    }
}

/// Σ ln sₖ of positive factors, kept as a product whose binary exponent is moved into an integer
/// every [`LogProduct::RENORMALISE_EVERY`] factors: one `ln` per likelihood instead of one per
/// sample. Eight factors each within 1e±30 stay far inside f64's range; the product's rounding
/// adds about √n × 1e-16 to the sum, less than summing n logarithms does.
#[derive(Debug)]
struct LogProduct {
    mantissa: f64,
    exponent: i64,
    pending: usize,
    /// Σ ln sₖ directly, once a factor left the range the product can hold.
    fallback: Option<f64>,
}

impl Default for LogProduct {
    fn default() -> Self {
        Self {
            mantissa: 1.0,
            exponent: 0,
            pending: 0,
            fallback: None,
        }
    }
}

impl LogProduct {
    const RENORMALISE_EVERY: usize = 8;
    const MIN_FACTOR: f64 = 1e-30;
    const MAX_FACTOR: f64 = 1e30;

    fn multiply(&mut self, factor: f64) {
        if let Some(sum) = &mut self.fallback {
            *sum += factor.ln();
            return;
        }
        if !(Self::MIN_FACTOR..=Self::MAX_FACTOR).contains(&factor) {
            self.fallback = Some(self.ln() + factor.ln());
            return;
        }
        self.mantissa *= factor;
        self.pending += 1;
        if self.pending == Self::RENORMALISE_EVERY {
            self.renormalise();
        }
    }

    /// Moves the mantissa's binary exponent into `exponent`, leaving it in [1, 2).
    fn renormalise(&mut self) {
        self.exponent += split_exponent(&mut self.mantissa);
        self.pending = 0;
    }

    fn ln(&self) -> f64 {
        match self.fallback {
            Some(sum) => sum,
            None => self.mantissa.ln() + self.exponent as f64 * std::f64::consts::LN_2,
        }
    }
}

/// Sets a positive normal `mantissa`'s binary exponent to 0 (the value to [1, 2)) and returns
/// the exponent it had.
#[inline(always)]
fn split_exponent(mantissa: &mut f64) -> i64 {
    const EXPONENT_BITS: u64 = 0x7ff << 52;
    let bits = mantissa.to_bits();
    *mantissa = f64::from_bits((bits & !EXPONENT_BITS) | (1023 << 52));
    ((bits & EXPONENT_BITS) >> 52) as i64 - 1023
}

/// Concentrated log-likelihood; −∞ outside the search box.
fn concentrated(record: &Record, bounds: &Bounds, p: [f64; 2]) -> f64 {
    if !bounds.contains(p) {
        return f64::NEG_INFINITY;
    }
    concentrated_value(record, innovations(record, p[0].exp(), p[1].exp()))
}

/// [`concentrated`] at `N` points, bit for bit, in one multi-lane pass ([`passes_at`]). Lanes
/// of points outside the box run a point inside it, their results dropped, so that the pass
/// keeps its fast path.
fn concentrated_at<const N: usize>(
    record: &Record,
    bounds: &Bounds,
    points: [[f64; 2]; N],
) -> [f64; N] {
    let Some(&stand_in) = points.iter().find(|&&p| bounds.contains(p)) else {
        return [f64::NEG_INFINITY; N];
    };
    let lanes = points.map(|p| if bounds.contains(p) { p } else { stand_in });
    let passes = passes_at(record, lanes.map(|p| p.map(f64::exp)));
    std::array::from_fn(|j| match bounds.contains(points[j]) {
        true => concentrated_value(record, passes[j]),
        false => f64::NEG_INFINITY,
    })
}

/// The negative concentrated log-likelihood of a record over a search box, as Nelder-Mead's
/// objective: its candidate points of an iteration in one multi-lane pass.
struct Likelihood<'a>(&'a Record, &'a Bounds);

impl Objective for Likelihood<'_> {
    fn values<const N: usize>(&self, points: [[f64; 2]; N]) -> [f64; N] {
        concentrated_at(self.0, self.1, points).map(|v| -v)
    }
}

/// The concentrated log-likelihood from a pass's Σ v²/S and Σ ln S.
fn concentrated_value(record: &Record, (weighted, log_det): (f64, f64)) -> f64 {
    let n = record.values.len() as f64;
    let scale = weighted / n;
    -0.5 * n * ((2.0 * std::f64::consts::PI).ln() + 1.0 + scale.ln()) - 0.5 * log_det
}

/// Best point of a 13 × 9 grid over the search box (cell centres, all inside it). Each column
/// of 9 ρ shares one Tc: one [`AtTc`] for its multi-lane passes.
fn grid_start(record: &Record, bounds: &Bounds) -> [f64; 2] {
    let lerp = |b: [f64; 2], k: usize, n: usize| b[0] + (b[1] - b[0]) * (k as f64 + 0.5) / n as f64;
    let ln_rho: [f64; 9] = std::array::from_fn(|j| lerp(bounds.ln_rho, j, 9));
    let mut best = ([0.0, 0.0], f64::NEG_INFINITY);
    for i in 0..13 {
        let column = AtTc::new(record, bounds, lerp(bounds.ln_tc, i, 13));
        // 4 + 4 + 1 lanes: nine at once spill the filters' state out of the 16 SSE registers
        // (callgrind: 4 + 4 + 1 take 6 % fewer instructions than 9, and 3 × 3 or 2 × 4 + 1 more).
        let mut values = [0.0; 9];
        for c in 0..2 {
            let lanes: [f64; 4] = std::array::from_fn(|j| ln_rho[4 * c + j]);
            values[4 * c..4 * c + 4].copy_from_slice(&column.at(lanes));
        }
        [values[8]] = column.at([ln_rho[8]]);
        for (&r, value) in ln_rho.iter().zip(values) {
            if value > best.1 {
                best = ([column.ln_tc, r], value);
            }
        }
    }
    best.0
}

/// Likelihood-ratio threshold for keeping the Gauss-Markov part: the 0.99 quantile of χ² with
/// 2 degrees of freedom (Tc and σ added to white noise). Conservative for this boundary
/// problem (σ = 0 lies on the edge of the parameter space, where the true null distribution is
/// a mixture with fewer degrees of freedom).
pub const SIGNIFICANCE_LR: f64 = 9.210_340_371_976_18;

/// Log-likelihood of white noise alone, var(y_k) = N²/d_k, with N² at its maximum
/// (1/n) Σ y_k² d_k.
fn white_only_log_likelihood(record: &Record) -> f64 {
    let n = record.values.len() as f64;
    let density_sq = record
        .values
        .iter()
        .zip(&record.average_s)
        .map(|(y, d)| y * y * d)
        .sum::<f64>()
        / n;
    let log_d: f64 = record.average_s.iter().map(|d| d.ln()).sum();
    -0.5 * n * ((2.0 * std::f64::consts::PI).ln() + 1.0 + density_sq.ln()) + 0.5 * log_d
}

fn outcome(record: &Record, bounds: &Bounds, best: [f64; 2]) -> NoisyGaussMarkovOutcome {
    if let Some(reason) = bounds.at_edge(best) {
        return NoisyGaussMarkovOutcome::NoEquivalent {
            reason: reason.to_string(),
        };
    }
    let (weighted, log_det) = innovations(record, best[0].exp(), best[1].exp());
    let log_likelihood = if bounds.contains(best) {
        concentrated_value(record, (weighted, log_det))
    } else {
        f64::NEG_INFINITY
    };
    let ratio = 2.0 * (log_likelihood - white_only_log_likelihood(record));
    if ratio < SIGNIFICANCE_LR {
        let reason = format!(
            "the Gauss-Markov part is not significant: likelihood ratio {ratio:.2} against white noise alone is below {SIGNIFICANCE_LR:.2} (chi-square, 2 dof, 0.99)"
        );
        return NoisyGaussMarkovOutcome::NoEquivalent { reason };
    }
    let scale = weighted / record.values.len() as f64;
    let tc = best[0].exp();
    NoisyGaussMarkovOutcome::Model(NoisyGaussMarkovFit {
        correlation_time_s: tc,
        sigma: scale.sqrt(),
        white_noise_density: (best[1].exp() * scale).sqrt(),
        ci95_correlation_time_s: likelihood_ratio_interval(record, bounds, best),
        log_likelihood,
        n_samples: record.values.len(),
    })
}

/// Half the 0.95 quantile of χ² with one degree of freedom: the drop of the profile
/// log-likelihood that bounds a 95 % likelihood-ratio interval.
pub const LR_DROP_95: f64 = 1.920_729_410_347_062;

/// The profile log-likelihood of ln Tc (maximised over ln ρ on ±3 around `rho_hint`, the
/// optimum at a neighbouring Tc) and the maximising ln ρ: by [`newton_maximum`], three ρ a
/// pass, to [`PROFILE_TOLERANCE`] of the maximum, or where its steps are not trusted by
/// [`brent_maximum`] to 1e-4 in ln ρ.
fn profile(record: &Record, bounds: &Bounds, ln_tc: f64, rho_hint: f64) -> (f64, f64) {
    let at_tc = AtTc::new(record, bounds, ln_tc);
    at_tc
        .newton_profile(rho_hint)
        .unwrap_or_else(|| at_tc.brent_profile(rho_hint))
}

/// The concentrated log-likelihood at one Tc as a function of ln ρ, its transitions tabled once.
struct AtTc<'a> {
    record: &'a Record,
    bounds: &'a Bounds,
    ln_tc: f64,
    table: Vec<f64>,
}

impl<'a> AtTc<'a> {
    fn new(record: &'a Record, bounds: &'a Bounds, ln_tc: f64) -> Self {
        Self {
            record,
            bounds,
            ln_tc,
            table: transition_table(record, ln_tc.exp()),
        }
    }

    /// The ln ρ searched: ±3 around the hint, inside the box.
    fn bracket(&self, rho_hint: f64) -> [f64; 2] {
        [
            (rho_hint - 3.0).max(self.bounds.ln_rho[0]),
            (rho_hint + 3.0).min(self.bounds.ln_rho[1]),
        ]
    }

    /// The likelihood at ln ρ = `r` for the `N` values of `r`, one pass; −∞ for all when one
    /// lies outside the box.
    fn at<const N: usize>(&self, r: [f64; N]) -> [f64; N] {
        if !r.iter().all(|&r| self.bounds.contains([self.ln_tc, r])) {
            return [f64::NEG_INFINITY; N];
        }
        kalman_pass(self.record, r.map(f64::exp), |k| [self.table[k]; N])
            .map(|pass| concentrated_value(self.record, pass))
    }

    /// The profile (value, ln ρ) by [`newton_maximum`], three ρ a pass, to
    /// [`PROFILE_TOLERANCE`]; `None` where its steps are not trusted.
    fn newton_profile(&self, rho_hint: f64) -> Option<(f64, f64)> {
        let bracket = self.bracket(rho_hint);
        newton_maximum(|r| self.at(r), bracket, rho_hint, PROFILE_TOLERANCE)
            .map(|(r, value)| (value, r))
    }

    /// The profile (value, ln ρ) by [`brent_maximum`] to 1e-4 in ln ρ.
    fn brent_profile(&self, rho_hint: f64) -> (f64, f64) {
        let (r, value) = brent_maximum(|r| self.at([r])[0], self.bracket(rho_hint), 1e-4);
        (value, r)
    }
}

/// How far below the maximum a profile log-likelihood may be left: 1e-5, 200 times below the
/// level tolerance of the interval's search ([`bisect`]).
const PROFILE_TOLERANCE: f64 = 1e-5;

/// 95 % likelihood-ratio interval of Tc: where the profile log-likelihood of ln Tc falls
/// [`LR_DROP_95`] below its maximum (Venzon & Moolgavkar 1988), found by stepping out from the
/// estimate and then by false position. Asymmetric where the likelihood is, which the Wald
/// interval is not (short records, Tc comparable to the record). An upper side that never falls
/// within the search box is `None` (unbounded); a lower side that never falls is the smallest
/// Tc searched.
///
/// The step-out extrapolates the signed root √(2·drop), which is close to linear in ln Tc
/// (exactly so for a quadratic profile, and much closer to it than the drop on a skewed one):
/// the next distance from the estimate is 1.2 times the one where the root through the last
/// profile reaches √(2·1.92), at least 1.5 and at most 8 times the last distance, and at most
/// the edge of the box (which is itself profiled before a side is declared unbounded).
fn likelihood_ratio_interval(record: &Record, bounds: &Bounds, best: [f64; 2]) -> [Option<f64>; 2] {
    let maximum = concentrated(record, bounds, best);
    let side = |direction: f64| -> Option<f64> {
        let edge = if direction > 0.0 {
            bounds.ln_tc[1]
        } else {
            bounds.ln_tc[0]
        };
        let mut inside = [best[0], maximum];
        let (mut rho, mut distance) = (best[1], 0.3);
        loop {
            let candidate = best[0] + direction * distance;
            let candidate = if (candidate - edge) * direction > 0.0 {
                edge
            } else {
                candidate
            };
            if candidate == inside[0] {
                return None;
            }
            let (value, r) = profile(record, bounds, candidate, rho);
            let outside = [candidate, value];
            if value < maximum - LR_DROP_95 {
                return Some(bisect(record, bounds, inside, outside, r, maximum).exp());
            }
            let drop = maximum - value;
            let growth = if drop > 0.0 {
                1.2 * (LR_DROP_95 / drop).sqrt()
            } else {
                f64::INFINITY
            };
            distance *= growth.clamp(1.5, 8.0);
            (inside, rho) = (outside, r);
        }
    };
    [side(-1.0).or(Some(bounds.ln_tc[0].exp())), side(1.0)]
}

/// The ln Tc between `inside` (profile above `maximum` − [`LR_DROP_95`]) and `outside` (below),
/// each given as [ln Tc, profile value] (the values the step-out already has), where the profile
/// crosses that level, starting the profiles' searches at `rho` (the ln ρ of the last one):
/// false position on √1.92 − √drop (the signed root, nearly linear, see
/// [`likelihood_ratio_interval`]) with the Illinois modification (the end that stays has its
/// value halved, so both ends move), stopped when the bracket is below 2e-3 in ln Tc (0.2 % of
/// Tc) or the profile is within 0.002 of the level (0.1 % of the 1.92 drop). On the flat upper
/// sides of hour-long records a level tolerance of 0.005 left the ends up to 0.4 % from the
/// crossing (the profile falls by ~1 per unit of ln Tc there); 0.002 leaves under 0.05 %.
fn bisect(
    record: &Record,
    bounds: &Bounds,
    inside: [f64; 2],
    outside: [f64; 2],
    mut rho: f64,
    maximum: f64,
) -> f64 {
    let target = maximum - LR_DROP_95;
    // > 0 inside, < 0 outside, 0 at the level.
    let root = |value: f64| LR_DROP_95.sqrt() - (maximum - value).max(0.0).sqrt();
    let (mut a, mut ra) = (inside[0], root(inside[1]));
    let (mut b, mut rb) = (outside[0], root(outside[1]));
    let mut kept_side = 0i8;
    for _ in 0..60 {
        if (b - a).abs() <= 2e-3 {
            break;
        }
        let c = (a * rb - b * ra) / (rb - ra);
        let c = if c.is_finite() && (c - a) * (c - b) < 0.0 {
            c
        } else {
            0.5 * (a + b)
        };
        let (value, r) = profile(record, bounds, c, rho);
        rho = r;
        if (value - target).abs() < 0.002 {
            return c;
        }
        let rc = root(value);
        if value >= target {
            (a, ra) = (c, rc);
            if kept_side == 1 {
                rb *= 0.5;
            }
            kept_side = 1;
        } else {
            (b, rb) = (c, rc);
            if kept_side == -1 {
                ra *= 0.5;
            }
            kept_side = -1;
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimise::nelder_mead::nelder_mead_reference;
    use crate::rng::named_rng;
    use nalgebra::{DMatrix, DVector};
    use rand::RngExt;
    use rand_distr::{Distribution, StandardNormal};

    /// Irregular times (dt uniform in [0.05, 0.15] s) and GM + white values.
    fn simulate(n: usize, tc_s: f64, sigma: f64, density: f64, seed: u64) -> (Vec<f64>, Vec<f64>) {
        let mut rng = named_rng(seed, "noisy-gm-test");
        let normal = |rng: &mut crate::rng::SimRng| -> f64 { StandardNormal.sample(rng) };
        let (mut t, mut b) = (0.0, sigma * normal(&mut rng));
        let (mut times, mut values) = (Vec::with_capacity(n), Vec::with_capacity(n));
        for k in 0..n {
            let dt: f64 = rng.random_range(0.05..0.15);
            if k > 0 {
                let phi = (-dt / tc_s).exp();
                b = phi * b + sigma * (1.0 - phi * phi).sqrt() * normal(&mut rng);
            }
            t += dt;
            times.push(t);
            values.push(b + density / dt.sqrt() * normal(&mut rng));
        }
        (times, values)
    }

    /// Times 0.1 s apart with a clock's jitter of up to 12 µs: every Tc searched takes the
    /// near-nominal transitions, and so the multi-lane passes.
    fn jittered_times(n: usize) -> Vec<f64> {
        (0..n)
            .map(|k| 0.1 * k as f64 + 1e-6 * ((k * 7919) % 13) as f64)
            .collect()
    }

    /// The dense Gaussian log-likelihood of the demeaned record with covariance s²Σ,
    /// Σ_ij = exp(−|t_i − t_j|/Tc) + δ_ij ρ/d_i, concentrated in s²: the slow, obviously
    /// correct O(n³) oracle for the Kalman recursion.
    fn dense_concentrated(times: &[f64], values: &[f64], tc: f64, rho: f64) -> f64 {
        let n = values.len();
        let mean = values.iter().sum::<f64>() / n as f64;
        let y = DVector::from_iterator(n, values.iter().map(|v| v - mean));
        let mut d: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
        d.insert(0, d[0]);
        let sigma = DMatrix::from_fn(n, n, |i, j| {
            (-(times[i] - times[j]).abs() / tc).exp() + if i == j { rho / d[i] } else { 0.0 }
        });
        let chol = sigma.cholesky().unwrap();
        let quad = y.dot(&chol.solve(&y));
        let log_det: f64 = 2.0 * chol.l().diagonal().iter().map(|v| v.ln()).sum::<f64>();
        let s2 = quad / n as f64;
        -0.5 * n as f64 * ((2.0 * std::f64::consts::PI).ln() + 1.0 + s2.ln()) - 0.5 * log_det
    }

    /// The Kalman pass as first written: one filter, one step at a time, Σ ln S through
    /// [`LogProduct::multiply`] with its range test at every factor. The reference for
    /// [`kalman_pass`].
    fn innovations_reference(record: &Record, tc_s: f64, rho_s: f64) -> (f64, f64) {
        let transitions = Transitions::new(record.nominal_dt_s, tc_s);
        let (mut x, mut p) = (0.0_f64, 1.0_f64);
        let mut weighted = 0.0_f64;
        let mut log_det = LogProduct::default();
        for (k, ((&dt, &inverse_d), &y)) in record
            .dt_s
            .iter()
            .zip(&record.inverse_average_per_s)
            .zip(&record.values)
            .enumerate()
        {
            if k > 0 {
                let phi = transitions.at(dt);
                x *= phi;
                p = phi * phi * p + (1.0 - phi * phi);
            }
            let s = p + rho_s * inverse_d;
            let inverse_s = 1.0 / s;
            let v = y - x;
            weighted += v * v * inverse_s;
            log_det.multiply(s);
            let gain = p * inverse_s;
            x += gain * v;
            p -= gain * p;
        }
        (weighted, log_det.ln())
    }

    // The blocked, multi-lane pass does the reference's arithmetic in the reference's order, so
    // the results are equal bit for bit: one lane with transitions computed on the fly (with and
    // without the per-step test of the interval: Tc 400 s is far above the intervals' spread,
    // 30 ms below it), nine and four lanes from a table, lengths that are and are not multiples
    // of the 8-step block, and ρ so large (1e32) that the factors leave the log product's range
    // (the per-factor path).
    #[test]
    fn the_kalman_pass_is_the_reference_pass_bit_for_bit() {
        for n in [20, 64, 1003] {
            let (times, values) = simulate(n, 2.0, 1.0, 0.3, 3);
            let record = prepare(&times, &values).unwrap();
            let rho = [1e-9, 1e-5, 1e-3, 0.01, 0.1, 1.0, 10.0, 1e3, 1e8];
            for tc in [0.03, 0.7, 5.0, 400.0] {
                let near = Transitions::new(record.nominal_dt_s, tc).all_near_nominal(&record);
                assert_eq!(near, tc > 100.0, "Tc {tc}");
                let table = transition_table(&record, tc);
                let lanes = kalman_pass(&record, rho, |k| [table[k]; 9]);
                let four =
                    kalman_pass(&record, [rho[1], rho[3], rho[5], rho[7]], |k| [table[k]; 4]);
                for (&r, lane) in rho.iter().zip(lanes) {
                    let reference = innovations_reference(&record, tc, r);
                    assert_eq!(lane, reference, "n {n} Tc {tc} rho {r}");
                    assert_eq!(
                        innovations(&record, tc, r),
                        reference,
                        "n {n} Tc {tc} rho {r}"
                    );
                }
                for (j, lane) in four.into_iter().enumerate() {
                    let reference = innovations_reference(&record, tc, rho[2 * j + 1]);
                    assert_eq!(lane, reference, "n {n} Tc {tc} four lanes");
                }
                let reference = innovations_reference(&record, tc, 1e32);
                assert_eq!(innovations(&record, tc, 1e32), reference, "n {n} Tc {tc}");
                let [with_table] = kalman_pass(&record, [1e32], |k| [table[k]]);
                assert_eq!(with_table, reference, "n {n} Tc {tc}");
            }
        }
    }

    // Lanes with their own Tc (each lane's transitions its own) give each point's one-lane
    // likelihood bit for bit, on a jittered record (every Tc near-nominal, the multi-lane pass)
    // and on one whose intervals spread over 0.05-0.15 s (point by point), with points outside
    // the search box among them.
    #[test]
    fn likelihoods_at_several_points_are_each_points_own() {
        let (times, values) = simulate(500, 2.0, 1.0, 0.3, 8);
        let jittered = jittered_times(500);
        let bounds = Bounds {
            ln_tc: [-6.0, 8.0],
            ln_rho: [-15.0, 12.0],
        };
        let points = [
            [1.0, -2.0],
            [3.0, 0.5],
            [9.0, 0.0],
            [-0.5, -7.0],
            [2.0, 13.0],
            [6.0, 4.0],
        ];
        for times in [&times, &jittered] {
            let record = prepare(times, &values).unwrap();
            let at_once = concentrated_at(&record, &bounds, points);
            for (p, value) in points.into_iter().zip(at_once) {
                let alone = concentrated(&record, &bounds, p);
                assert_eq!(value.to_bits(), alone.to_bits(), "{p:?}");
            }
            let outside = concentrated_at(&record, &bounds, [[9.0, 0.0], [0.0, 20.0]]);
            assert_eq!(outside, [f64::NEG_INFINITY; 2]);
        }
    }

    // The batched method takes the reference's path (`optimise::nelder_mead`, one evaluation at
    // a time) on the likelihood of a jittered record through multi-lane passes: the same
    // minimum, bit for bit, with expansions, reflections and both contractions along the way
    // (the smooth likelihood asks for no shrink; `optimise::nelder_mead`'s kinked test does).
    #[test]
    fn nelder_mead_in_batches_is_the_standard_method_on_the_likelihood() {
        let mut steps = [0; 5];
        let (_, values) = simulate(2000, 3.0, 1.0, 0.2, 21);
        let times = jittered_times(2000);
        let record = prepare(&times, &values).unwrap();
        assert!(Transitions::new(record.nominal_dt_s, 0.05).all_near_nominal(&record));
        let (batched, reference) = likelihood_minima(&record, &mut steps);
        assert_eq!(batched, reference);
        assert!(steps[..4].iter().all(|&n| n > 0), "steps taken {steps:?}");
    }

    /// The minima of the negative likelihood of `record` from its grid start by the batched
    /// method and by the reference (counting its steps into `steps`).
    fn likelihood_minima(record: &Record, steps: &mut [usize; 5]) -> ([f64; 2], [f64; 2]) {
        let bounds = Bounds {
            ln_tc: [-4.0, 7.0],
            ln_rho: [-15.0, 12.0],
        };
        let start = grid_start(record, &bounds);
        let batched = nelder_mead(&Likelihood(record, &bounds), start, [0.5, 0.5], 400);
        let likelihood = |p| -concentrated(record, &bounds, p);
        (
            batched,
            nelder_mead_reference(likelihood, start, [0.5, 0.5], steps),
        )
    }

    // On a record whose intervals spread over 0.05-0.15 s (transitions by `exp` in every lane)
    // the batched method also takes the reference's path.
    #[test]
    fn nelder_mead_in_batches_is_the_standard_method_on_irregular_times() {
        let (times, values) = simulate(1500, 3.0, 1.0, 0.2, 22);
        let record = prepare(&times, &values).unwrap();
        assert!(!Transitions::new(record.nominal_dt_s, 50.0).all_near_nominal(&record));
        let (batched, reference) = likelihood_minima(&record, &mut [0; 5]);
        assert_eq!(batched, reference);
    }

    #[test]
    fn kalman_likelihood_equals_the_dense_gaussian_likelihood() {
        // Same quantity by two algorithms; agreement to 1e-9 relative is rounding in the
        // 60 × 60 Cholesky.
        let (times, values) = simulate(60, 0.7, 1.0, 0.1, 1);
        let record = prepare(&times, &values).unwrap();
        let bounds = Bounds {
            ln_tc: [-10.0, 10.0],
            ln_rho: [-20.0, 20.0],
        };
        for (tc, rho) in [(0.7, 0.01), (3.0, 0.2), (0.1, 1e-4)] {
            let fast = concentrated(&record, &bounds, [f64::ln(tc), f64::ln(rho)]);
            let slow = dense_concentrated(&times, &values, tc, rho);
            assert!(
                ((fast - slow) / slow).abs() < 1e-9,
                "Tc {tc}, rho {rho}: {fast} vs {slow}"
            );
        }
    }

    #[test]
    fn white_only_likelihood_is_the_dense_limit_of_vanishing_gauss_markov_share() {
        // With ρ = 1e9 s the Gauss-Markov part is 1e-9 of the covariance (times d ≈ 0.1 s), so
        // the dense likelihood equals the white-only closed form to ~1e-7 relative.
        let (times, values) = simulate(60, 0.7, 1.0, 0.1, 2);
        let record = prepare(&times, &values).unwrap();
        let slow = dense_concentrated(&times, &values, 0.7, 1e9);
        let closed = white_only_log_likelihood(&record);
        assert!(((closed - slow) / slow).abs() < 1e-7, "{closed} vs {slow}");
    }

    #[test]
    fn recovers_tc_through_dominant_white_noise_on_jittered_times() {
        // Tc 20 s, σ 1, N² = 5 σ² s: at 10 Hz each sample's white variance is 50 σ², the regime
        // where AR(1) fails. 30 000 samples (~3000 s, 150 Tc). Over 10 seeds the 95 % interval
        // must cover the truth at least 8 times (binomial: P(≤7 | 0.95) ≈ 1 %), and the
        // geometric mean estimate must be within 15 % (se of ln Tc here is ~0.15/√10 ≈ 0.05).
        let (tc, sigma, density) = (20.0, 1.0, 5f64.sqrt());
        let mut covered = 0;
        let mut ln_sum = 0.0;
        for seed in 0..10 {
            let (times, values) = simulate(30_000, tc, sigma, density, 100 + seed);
            let NoisyGaussMarkovOutcome::Model(fit) =
                fit_noisy_gauss_markov(&times, &values).unwrap()
            else {
                panic!("seed {seed}: no model");
            };
            let [lo, hi] = fit.ci95_correlation_time_s;
            covered += usize::from(lo.unwrap() <= tc && hi.is_none_or(|h| tc <= h));
            ln_sum += fit.correlation_time_s.ln();
            assert!(
                (fit.white_noise_density / density - 1.0).abs() < 0.05,
                "N {}",
                fit.white_noise_density
            );
        }
        let geometric_mean = (ln_sum / 10.0).exp();
        assert!(covered >= 8, "covered {covered}/10");
        assert!(
            (geometric_mean / tc - 1.0).abs() < 0.15,
            "mean Tc {geometric_mean}"
        );
    }

    #[test]
    fn white_noise_alone_has_no_gauss_markov_equivalent() {
        let mut rng = named_rng(5, "white");
        let times: Vec<f64> = (0..5000).map(|k| k as f64 * 0.1).collect();
        let values: Vec<f64> = (0..5000).map(|_| StandardNormal.sample(&mut rng)).collect();
        let outcome = fit_noisy_gauss_markov(&times, &values).unwrap();
        assert!(
            matches!(outcome, NoisyGaussMarkovOutcome::NoEquivalent { .. }),
            "{outcome:?}"
        );
    }

    #[test]
    fn bad_input_is_refused() {
        let t: Vec<f64> = (0..30).map(f64::from).collect();
        assert_eq!(
            fit_noisy_gauss_markov(&t, &[1.0; 30]),
            Err(NoisyGaussMarkovError::Constant)
        );
        assert!(matches!(
            fit_noisy_gauss_markov(&t[..10], &[1.0; 10]),
            Err(NoisyGaussMarkovError::TooShort { .. })
        ));
        let mut v: Vec<f64> = t.iter().map(|x| x.sin()).collect();
        v[3] = f64::NAN;
        assert_eq!(
            fit_noisy_gauss_markov(&t, &v),
            Err(NoisyGaussMarkovError::NonFinite { index: 3 })
        );
        let mut back = t.clone();
        back[7] = 2.0;
        assert!(matches!(
            fit_noisy_gauss_markov(&back, &t),
            Err(NoisyGaussMarkovError::Order { index: 7, .. })
        ));
    }

    // Against `exp` itself: on both branches (|u| below and above 1e-3) and for Tc from 10 ms
    // to 3 h, within 4e-16 relative (two roundings of the product and the polynomial).
    #[test]
    fn transitions_are_exp_to_rounding() {
        let nominal = 0.005;
        for tc in [0.01, 0.7, 100.0, 1e4] {
            let transitions = Transitions::new(nominal, tc);
            for k in -400..=400 {
                let dt = nominal + f64::from(k) * 5e-3 * tc / 400.0 * 0.5;
                if dt <= 0.0 {
                    continue;
                }
                let exact = (-dt / tc).exp();
                let fast = transitions.at(dt);
                assert!(
                    ((fast - exact) / exact).abs() < 4e-16,
                    "Tc {tc} dt {dt}: {fast} vs {exact}"
                );
            }
        }
    }

    // Against Σ ln sₖ summed directly: 200 000 seeded factors log-uniform over 1e±20 (the
    // running sum reaches 1e6), within 1e-12 relative of the sum, which is itself rounded at
    // about n × 1e-16; a factor outside 1e±30 switches to the direct sum with the same result.
    #[test]
    fn the_log_product_is_the_sum_of_the_logs() {
        let mut rng = named_rng(7, "log-product-test");
        let factors: Vec<f64> = (0..200_000)
            .map(|_| 10f64.powf(rng.random_range(-20.0..20.0)))
            .collect();
        let mut product = LogProduct::default();
        for &f in &factors {
            product.multiply(f);
        }
        let direct: f64 = factors.iter().map(|f| f.ln()).sum();
        assert!(((product.ln() - direct) / direct.abs().max(1.0)).abs() < 1e-12);
        let mut wide = LogProduct::default();
        let extreme = [3.0, 1e-40, 2.0, 1e45, 0.5];
        for &f in &extreme {
            wide.multiply(f);
        }
        let direct: f64 = extreme.iter().map(|f| f.ln()).sum();
        assert!(
            (wide.ln() - direct).abs() < 1e-12,
            "{} vs {direct}",
            wide.ln()
        );
    }

    /// The profile log-likelihood of ln Tc by brute force: the concentrated likelihood on 1201
    /// points of ln ρ over ±3 around `centre`, the best kept (0.005 apart: the value within
    /// f''/2 · 0.0025² ≈ f''·3e-6 of the true maximum).
    fn slow_profile(record: &Record, bounds: &Bounds, ln_tc: f64, centre: f64) -> f64 {
        (0..=1200)
            .map(|k| centre - 3.0 + 0.005 * f64::from(k))
            .map(|r| concentrated(record, bounds, [ln_tc, r]))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    // The profile at Tc from a tenth to ten times the estimate, started 0.8 off in ln ρ, against
    // the brute-force profile (1201 points 0.005 apart: at most f''·3e-6 below the maximum):
    // never more than the tolerance below it, and never above the maximum, which lies within
    // f''·3e-6 of it.
    #[test]
    fn the_profile_is_the_brute_force_profile() {
        let (_, values) = simulate(5000, 20.0, 1.0, 1.0, 31);
        let times = jittered_times(5000);
        let record = prepare(&times, &values).unwrap();
        let bounds = Bounds {
            ln_tc: [-4.0, 8.0],
            ln_rho: [-15.0, 12.0],
        };
        let best = nelder_mead(
            &Likelihood(&record, &bounds),
            grid_start(&record, &bounds),
            [0.5, 0.5],
            400,
        );
        for factor in [0.1, 0.5, 0.9, 1.0, 2.0, 10.0] {
            let ln_tc = best[0] + f64::ln(factor);
            let (value, r) = profile(&record, &bounds, ln_tc, best[1] + 0.8);
            let at_tc = AtTc::new(&record, &bounds, ln_tc);
            // Newton's steps served (Brent, the fallback, is tested on its own).
            assert_eq!(
                at_tc.newton_profile(best[1] + 0.8),
                Some((value, r)),
                "Tc x{factor}"
            );
            let slow = slow_profile(&record, &bounds, ln_tc, r);
            let curvature = -(concentrated(&record, &bounds, [ln_tc, r + 0.01]) - 2.0 * value
                + concentrated(&record, &bounds, [ln_tc, r - 0.01]))
                / 1e-4;
            assert!(
                value >= slow - PROFILE_TOLERANCE,
                "Tc x{factor}: {value} vs {slow}"
            );
            // A bad evaluation would show here: the value is one the likelihood took.
            assert!(
                value <= slow + curvature.abs() * 3.2e-6,
                "Tc x{factor}: {value} vs {slow}"
            );
        }
    }

    // The 95 % likelihood-ratio interval against a brute-force profile: at 0.4 % of Tc inside
    // each end the slow profile is above max − 1.92, at 0.4 % outside below it (the search
    // stops within 0.2 % in ln Tc or 0.002 of the level). A 200 Hz-like record with clock
    // jitter, so that both branches of the transitions are used.
    #[test]
    fn the_likelihood_ratio_interval_ends_where_the_profile_drops_by_the_chi_square_level() {
        let mut rng = named_rng(11, "lr-interval-test");
        let normal = |rng: &mut crate::rng::SimRng| -> f64 { StandardNormal.sample(rng) };
        let (tc, sigma, density, n): (f64, f64, f64, usize) = (30.0, 1.0, 1.5, 20_000);
        let (mut t, mut b) = (0.0, sigma * normal(&mut rng));
        let (mut times, mut values) = (Vec::new(), Vec::new());
        for k in 0..n {
            let dt = if k % 997 == 0 {
                0.2
            } else {
                0.1 + rng.random_range(-5e-5..5e-5)
            };
            let phi = (-dt / tc).exp();
            b = phi * b + sigma * (1.0 - phi * phi).sqrt() * normal(&mut rng);
            t += dt;
            times.push(t);
            values.push(b + density / dt.sqrt() * normal(&mut rng));
        }
        let record = prepare(&times, &values).unwrap();
        let span = times[n - 1] - times[0];
        let min_dt = record.dt_s.iter().copied().fold(f64::INFINITY, f64::min);
        let bounds = Bounds {
            ln_tc: [(0.5 * min_dt).ln(), (2.0 * span).ln()],
            ln_rho: [(1e-6 * min_dt).ln(), (1e6 * span).ln()],
        };
        let best = nelder_mead(
            &Likelihood(&record, &bounds),
            grid_start(&record, &bounds),
            [0.5, 0.5],
            400,
        );
        let target = concentrated(&record, &bounds, best) - LR_DROP_95;
        let [lo, hi] = likelihood_ratio_interval(&record, &bounds, best);
        let (lo, hi) = (lo.unwrap().ln(), hi.unwrap().ln());
        assert!(lo < best[0] && best[0] < hi, "{lo} {} {hi}", best[0]);
        for (end, inward) in [(lo, 1.0), (hi, -1.0)] {
            let inside = slow_profile(&record, &bounds, end + inward * 0.004, best[1]);
            let outside = slow_profile(&record, &bounds, end - inward * 0.004, best[1]);
            assert!(
                inside > target && outside < target,
                "end {end}: {inside} / {outside} vs {target}"
            );
        }
    }
}
