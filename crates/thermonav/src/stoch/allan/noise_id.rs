//! Power-law noise identification at one averaging factor (for confidence intervals).
//!
//! Stable32's procedure, reconstructed and checked against its output (see
//! [`identify_noise`]): the lag-1 autocorrelation method when at least
//! [`MIN_AVERAGES_FOR_NOISE_ID`] averaged values exist, otherwise the B1 bias ratio, with R(n) to split
//! the two phase-noise types.

use std::f64::consts::{LN_2, PI};

use super::MIN_AVERAGES_FOR_NOISE_ID;
use super::deviation::{centred_cumulative_sum, mean, overlapping_avar};

/// Power-law noise S_y(f) ∝ f^alpha of the fractional-frequency (rate) series, restricted to
/// the types the Allan variance can tell apart (alpha = 2 ... -2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PowerLawNoise {
    /// alpha = +2: white phase (for a gyro: white angle noise, e.g. angle quantisation).
    WhitePhase,
    /// alpha = +1: flicker phase.
    FlickerPhase,
    /// alpha = 0: white frequency (for a gyro: angle random walk).
    WhiteFrequency,
    /// alpha = -1: flicker frequency (bias instability).
    FlickerFrequency,
    /// alpha = -2: random-walk frequency (rate random walk).
    RandomWalkFrequency,
}

impl PowerLawNoise {
    /// The exponent alpha of S_y(f) ∝ f^alpha.
    pub fn alpha(self) -> i32 {
        match self {
            Self::WhitePhase => 2,
            Self::FlickerPhase => 1,
            Self::WhiteFrequency => 0,
            Self::FlickerFrequency => -1,
            Self::RandomWalkFrequency => -2,
        }
    }

    /// The type with exponent `alpha`, clamped to 2 ... -2 (steeper noise than random-walk
    /// frequency is reported as random-walk frequency, the Allan variance's limit).
    pub fn from_alpha_clamped(alpha: i32) -> Self {
        match alpha {
            i32::MIN..=-2 => Self::RandomWalkFrequency,
            -1 => Self::FlickerFrequency,
            0 => Self::WhiteFrequency,
            1 => Self::FlickerPhase,
            _ => Self::WhitePhase,
        }
    }
}

/// Which test decided the noise type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoiseIdMethod {
    /// Lag-1 autocorrelation of the averaged (and differenced) series.
    Lag1Autocorrelation,
    /// B1 bias ratio (standard variance / Allan variance) of the averaged series.
    B1Ratio,
    /// B1 said "phase noise"; R(n) = MVAR/AVAR chose white or flicker phase (or white FM).
    B1RatioAndRn,
    /// B1 said "phase noise" but R(n) needs 3m <= N + 1: flicker phase assumed (the type
    /// with the smaller, more cautious EDF of the two).
    B1RatioRnUnavailable,
}

/// The noise type found at one averaging factor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoiseIdentification {
    /// Dominant noise type.
    pub noise: PowerLawNoise,
    /// How it was decided.
    pub method: NoiseIdMethod,
    /// Number of non-overlapping averages the decision used (floor(N / m)).
    pub n_averages: usize,
}

/// Identifies the dominant power-law noise of rate series `y` at averaging factor `m`.
///
/// 1. Average `y` in non-overlapping blocks of m samples (n = floor(N/m) values z).
/// 2. If n >= [`MIN_AVERAGES_FOR_NOISE_ID`]: lag-1 autocorrelation method (Riley & Greenhall 2004;
///    NIST SP 1065 §5.5.6). r1 = sum (z_t - zbar)(z_{t+1} - zbar) / sum (z_t - zbar)^2,
///    delta = r1 / (1 + r1); while delta >= 0.25 and d < 2, difference z and retry;
///    alpha = -round(2 delta) - 2d. No polynomial detrending (only the mean is removed):
///    that is what reproduces Stable32 on the Cs 5071A decade run.
/// 3. Otherwise the B1 ratio (Barnes 1969; Howe 2000): B1 = s^2 / sigma_A^2, the sample
///    variance (n - 1 divisor) of the n averages over their non-overlapping Allan variance,
///    compared with B1(N, mu) = N (1 - N^mu) / (2 (N - 1) (1 - 2^mu)) (mu = 0:
///    N ln N / (2 (N - 1) ln 2)) for mu = 2 ... -2, the nearest on a log scale winning
///    (boundaries at geometric means). N here is the full series length: that, not n, is
///    what reproduces Stable32. mu = -1, 0, 1 give alpha = -mu - 1; mu = -2 (phase noise) is
///    split with R(n) = Mod AVAR / AVAR against 1/m (white PM), the flicker-PM ratio
///    [3 ln(256/27) / (8 pi^2)] / [(1.038 + 3 ln(pi m)) / (4 pi^2)] (f_h = 1/(2 tau0)) and
///    1/2 (white FM), nearest on a log scale.
///
/// Checked against all 79 octave/decade rows of six Stable32 1.60 OADEV runs: 78 agree; the
/// miss (Keysight TIC, m = 8192, six averages) is a B1 decision on very few points.
///
/// `None` when m = 0, 2m > N (no term), or the averaged series is constant (no noise type).
pub fn identify_noise(y: &[f64], m: usize) -> Option<NoiseIdentification> {
    if m == 0 || 2 * m > y.len() {
        return None;
    }
    noise_of_block_means(block_means(y, m), y.len(), || phase_noise_by_rn(y, m))
}

/// The decision of [`identify_noise`] from the block means `z` of a series of `n_samples`,
/// with `phase_noise` deciding between the phase-noise types when B1 says phase noise (it
/// needs the whole series).
pub(super) fn noise_of_block_means(
    z: Vec<f64>,
    n_samples: usize,
    phase_noise: impl FnOnce() -> (PowerLawNoise, NoiseIdMethod),
) -> Option<NoiseIdentification> {
    let n_averages = z.len();
    let (noise, method) = if n_averages >= MIN_AVERAGES_FOR_NOISE_ID {
        (lag1_noise_type(z)?, NoiseIdMethod::Lag1Autocorrelation)
    } else {
        b1_noise_type(&z, n_samples, phase_noise)?
    };
    Some(NoiseIdentification {
        noise,
        method,
        n_averages,
    })
}

/// [`identify_noise`] at each of `factors`, with the block sums of a factor built from those of
/// the largest earlier factor that divides it (an octave's from the previous octave's pairs), so
/// that the whole set costs about one pass over `y` instead of one per factor. The sums are
/// added in another order than one block at a time, so a decision can differ from
/// [`identify_noise`]'s only where a statistic sits within rounding of a threshold.
pub fn identify_noise_at_factors(y: &[f64], factors: &[usize]) -> Vec<Option<NoiseIdentification>> {
    let mut known: Vec<(usize, Vec<f64>)> = Vec::new();
    factors
        .iter()
        .map(|&m| {
            if m == 0 || 2 * m > y.len() {
                return None;
            }
            let sums = block_sums_from(y, m, &known);
            let means = sums.iter().map(|s| s / m as f64).collect();
            known.push((m, sums));
            noise_of_block_means(means, y.len(), || phase_noise_by_rn(y, m))
        })
        .collect()
}

/// Sums of the blocks of `m` samples of `y`, from the block sums of the largest factor in
/// `known` that divides `m` (or from `y` itself).
fn block_sums_from(y: &[f64], m: usize, known: &[(usize, Vec<f64>)]) -> Vec<f64> {
    let divisor = known
        .iter()
        .filter(|(k, _)| m % k == 0)
        .max_by_key(|(k, _)| *k);
    match divisor {
        Some((k, sums)) => sums
            .chunks_exact(m / k)
            .take(y.len() / m)
            .map(|c| c.iter().sum())
            .collect(),
        None => y.chunks_exact(m).map(|block| block.iter().sum()).collect(),
    }
}

fn block_means(y: &[f64], m: usize) -> Vec<f64> {
    y.chunks_exact(m)
        .map(|block| block.iter().sum::<f64>() / m as f64)
        .collect()
}

/// Lag-1 autocorrelation with the mean removed; `None` for a constant series.
fn lag1_autocorrelation(z: &[f64]) -> Option<f64> {
    let zbar = mean(z);
    // Both sums in one pass: each is added in the order it would be alone (the same bits as
    // two `sum`s, which start from -0.0), and the two chains of additions overlap in time.
    let (mut denominator, mut numerator) = (-0.0_f64, -0.0_f64);
    for w in z.windows(2) {
        denominator += (w[0] - zbar).powi(2);
        numerator += (w[0] - zbar) * (w[1] - zbar);
    }
    if let Some(last) = z.last() {
        denominator += (last - zbar).powi(2);
    }
    (denominator > 0.0).then_some(numerator / denominator)
}

/// Differences of the averaged series the lag-1 method may take (d = 0, 1, 2).
pub(super) const MAX_DIFFERENCES: usize = 2;

fn lag1_noise_type(z: Vec<f64>) -> Option<PowerLawNoise> {
    let mut level = z;
    lag1_decision(|d| {
        if d > 0 {
            level = level.windows(2).map(|w| w[1] - w[0]).collect();
        }
        lag1_autocorrelation(&level)
    })
}

/// The lag-1 rule given r1 of the averaged series differenced d times (`r1_of(d)`, asked for
/// d = 0, 1, 2 in order): delta = r1 / (1 + r1); difference again while delta >= 0.25;
/// alpha = -round(2 delta) - 2d. `None` when an r1 is undefined (a constant series).
pub(super) fn lag1_decision(mut r1_of: impl FnMut(usize) -> Option<f64>) -> Option<PowerLawNoise> {
    for d in 0..=MAX_DIFFERENCES {
        let r1 = r1_of(d)?;
        if 1.0 + r1 <= 0.0 {
            // r1 = -1: perfectly alternating, delta -> -inf: the bluest type.
            return Some(PowerLawNoise::WhitePhase);
        }
        let delta = r1 / (1.0 + r1);
        if delta < 0.25 || d == MAX_DIFFERENCES {
            let alpha = -(2.0 * delta).round() as i32 - 2 * d as i32;
            return Some(PowerLawNoise::from_alpha_clamped(alpha));
        }
    }
    unreachable!("the loop returns at d == MAX_DIFFERENCES")
}

fn sample_variance(z: &[f64]) -> f64 {
    let zbar = mean(z);
    z.iter().map(|v| (v - zbar).powi(2)).sum::<f64>() / (z.len() - 1) as f64
}

fn non_overlapping_avar(z: &[f64]) -> f64 {
    let sum_sq: f64 = z.windows(2).map(|w| (w[1] - w[0]).powi(2)).sum();
    sum_sq / (2.0 * (z.len() - 1) as f64)
}

/// Barnes' B1(N, r = 1, mu): expected N-sample variance over the Allan variance.
fn b1_theory(n: f64, mu: i32) -> f64 {
    if mu == 0 {
        n * n.ln() / (2.0 * (n - 1.0) * LN_2)
    } else {
        let mu = f64::from(mu);
        n * (1.0 - n.powf(mu)) / (2.0 * (n - 1.0) * (1.0 - 2_f64.powf(mu)))
    }
}

/// The candidate whose theoretical value is nearest to `measured` on a log scale.
fn nearest_on_log_scale<T: Copy>(measured: f64, candidates: &[(T, f64)]) -> T {
    let distance = |theory: f64| (measured.ln() - theory.ln()).abs();
    candidates
        .iter()
        .min_by(|a, b| distance(a.1).total_cmp(&distance(b.1)))
        .map(|c| c.0)
        .expect("candidate lists are non-empty")
}

fn b1_noise_type(
    z: &[f64],
    n_samples: usize,
    phase_noise: impl FnOnce() -> (PowerLawNoise, NoiseIdMethod),
) -> Option<(PowerLawNoise, NoiseIdMethod)> {
    let avar = non_overlapping_avar(z);
    if z.len() < 2 || avar <= 0.0 {
        return None;
    }
    let b1 = sample_variance(z) / avar;
    let n = n_samples as f64;
    let candidates: Vec<(i32, f64)> = (-2..=2).map(|mu| (mu, b1_theory(n, mu))).collect();
    let mu = nearest_on_log_scale(b1, &candidates);
    if mu > -2 {
        let noise = PowerLawNoise::from_alpha_clamped(-mu - 1);
        return Some((noise, NoiseIdMethod::B1Ratio));
    }
    Some(phase_noise())
}

/// R(n) = Mod AVAR / AVAR of the phase noises and white FM (NIST SP 1065 Table 4 formulas).
fn rn_theory(m: usize) -> [(PowerLawNoise, f64); 3] {
    let m = m as f64;
    let mvar_flicker_pm = 3.0 * (256.0_f64 / 27.0).ln() / (8.0 * PI * PI);
    let avar_flicker_pm = (1.038 + 3.0 * (PI * m).ln()) / (4.0 * PI * PI);
    [
        (PowerLawNoise::WhitePhase, 1.0 / m),
        (
            PowerLawNoise::FlickerPhase,
            mvar_flicker_pm / avar_flicker_pm,
        ),
        (PowerLawNoise::WhiteFrequency, 0.5),
    ]
}

fn phase_noise_by_rn(y: &[f64], m: usize) -> (PowerLawNoise, NoiseIdMethod) {
    let phase = centred_cumulative_sum(y);
    match modified_avar(&phase, m) {
        Some(mvar) if mvar > 0.0 => {
            let rn = mvar / overlapping_avar(&phase, m);
            let noise = nearest_on_log_scale(rn, &rn_theory(m));
            (noise, NoiseIdMethod::B1RatioAndRn)
        }
        _ => (
            PowerLawNoise::FlickerPhase,
            NoiseIdMethod::B1RatioRnUnavailable,
        ),
    }
}

/// Modified Allan variance at factor m from phase in units of tau0 (NIST SP 1065 eq. 14);
/// `None` when 3m > N + 1 leaves no term.
fn modified_avar(phase: &[f64], m: usize) -> Option<f64> {
    let n_second = phase.len().checked_sub(2 * m)?;
    let n_terms = n_second.checked_sub(m - 1).filter(|&t| t > 0)?;
    let mut window: f64 = (0..m).map(|i| second_difference(phase, i, m)).sum();
    let mut sum_sq = window * window;
    for j in 1..n_terms {
        window += second_difference(phase, j + m - 1, m) - second_difference(phase, j - 1, m);
        sum_sq += window * window;
    }
    let m4 = (m as f64).powi(4);
    Some(sum_sq / (2.0 * m4 * n_terms as f64))
}

fn second_difference(s: &[f64], i: usize, m: usize) -> f64 {
    s[i + 2 * m] - 2.0 * s[i + m] + s[i]
}

#[cfg(test)]
mod factor_tests {
    use super::*;
    use crate::rng::named_rng;
    use rand_distr::{Distribution, StandardNormal};

    // Against identify_noise at each factor (one block at a time, the obviously correct
    // route): the same type, method and number of averages on white, random-walk and mixed
    // series, for octave and decade factor sets and one with factors that divide nothing
    // before them.
    #[test]
    fn the_noise_types_at_all_factors_are_those_of_one_factor_at_a_time() {
        let mut rng = named_rng(5, "noise-id-factors");
        let n = 100_000;
        let white: Vec<f64> = (0..n).map(|_| StandardNormal.sample(&mut rng)).collect();
        let mut walk = 0.0;
        let random_walk: Vec<f64> = white
            .iter()
            .map(|w| {
                walk += 0.01 * w;
                walk + w
            })
            .collect();
        let octaves: Vec<usize> = (0..16).map(|k| 1 << k).collect();
        let decades = [
            1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10_000, 20_000,
        ];
        let odd = [3, 7, 9, 21, 63, 100, 1000];
        for y in [&white, &random_walk] {
            for factors in [&octaves[..], &decades[..], &odd[..]] {
                let all = identify_noise_at_factors(y, factors);
                for (&m, got) in factors.iter().zip(&all) {
                    assert_eq!(*got, identify_noise(y, m), "m {m}");
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lag1_autocorrelation_in_one_pass_is_the_two_sums_bit_for_bit() {
        use rand::{RngExt, SeedableRng};
        let two_sums = |z: &[f64]| {
            let zbar = mean(z);
            let denominator: f64 = z.iter().map(|v| (v - zbar).powi(2)).sum();
            let numerator: f64 = z.windows(2).map(|w| (w[0] - zbar) * (w[1] - zbar)).sum();
            (denominator > 0.0).then_some(numerator / denominator)
        };
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        for n in [1, 2, 3, 17, 1000, 4097] {
            let z: Vec<f64> = (0..n).map(|_| rng.random::<f64>() - 0.5).collect();
            let bits = |r: Option<f64>| r.map(f64::to_bits);
            assert_eq!(bits(lag1_autocorrelation(&z)), bits(two_sums(&z)), "n {n}");
        }
        assert_eq!(lag1_autocorrelation(&[2.0, 2.0, 2.0]), None);
    }

    // Closed forms of Barnes' B1 (NIST SP 1065 / Howe 2000 table): mu = -1 gives 1,
    // mu = 1 gives N/2, mu = 2 gives N(N+1)/6, mu = -2 gives (N+1)/(1.5 N).
    #[test]
    fn b1_theory_special_cases() {
        let n = 17.0;
        assert!((b1_theory(n, -1) - 1.0).abs() < 1e-14);
        assert!((b1_theory(n, 1) - n / 2.0).abs() < 1e-12);
        assert!((b1_theory(n, 2) - n * (n + 1.0) / 6.0).abs() < 1e-10);
        assert!((b1_theory(n, -2) - (n + 1.0) / (1.5 * n)).abs() < 1e-14);
    }

    // Slow obviously-correct MVAR: the definition with an explicit inner sum.
    #[test]
    fn modified_avar_matches_its_definition() {
        let phase: Vec<f64> = (0..40).map(|k| ((k * k) as f64 * 0.37).sin()).collect();
        let m = 4;
        let n_terms = phase.len() - 3 * m + 1;
        let slow: f64 = (0..n_terms)
            .map(|j| {
                (j..j + m)
                    .map(|i| second_difference(&phase, i, m))
                    .sum::<f64>()
            })
            .map(|v| v * v)
            .sum::<f64>()
            / (2.0 * (m as f64).powi(4) * n_terms as f64);
        let fast = modified_avar(&phase, m).unwrap();
        assert!((fast - slow).abs() <= 1e-13 * slow);
        assert_eq!(modified_avar(&phase[..3 * m - 2], m), None);
    }

    #[test]
    fn alternating_series_is_white_phase_not_nan() {
        let y: Vec<f64> = (0..64)
            .map(|k| if k % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        let id = identify_noise(&y, 1).unwrap();
        assert_eq!(id.noise, PowerLawNoise::WhitePhase);
    }

    #[test]
    fn constant_series_has_no_noise_type() {
        let y = vec![3.0; 100];
        assert_eq!(identify_noise(&y, 2), None);
        assert_eq!(identify_noise(&y, 40), None);
    }
}
