//! A composite noise model mapped onto the filter's three noise parameters per axis.
//!
//! The 21-state filter carries, per sensor axis, white measurement noise of density N (in the
//! process noise of the velocity or attitude error) and one first-order Gauss-Markov bias
//! state (Tc, σ). A composite of white noise, quantisation noise, random walk, drift and k
//! Gauss-Markov processes is folded onto those three numbers as follows; each rule keeps what
//! the process does to the integrated error over the averaging times of an outage band
//! [τ_lo, τ_hi]:
//! - **white noise** σ²_wn per sample: N² = σ²_wn dt;
//! - **the bias state** is the Gauss-Markov process, among those with τ_lo ≤ Tc ≤ the record,
//!   that contributes the largest share of the composite's wavelet variance at some scale of
//!   the band (the process the Allan curve shows as the bias-instability bump there);
//! - **a Gauss-Markov process shorter than the bias state's** (or shorter than τ_lo when there is
//!   none) is white at the scales beyond its Tc: its spectrum at zero frequency is 2σ²Tc, so
//!   N² += 2σ²Tc. This is how a sensor's internal low-pass (white noise seen through a short
//!   AR(1)) ends up in N (per sample, exactly σ²(1 + φ)/(1 − φ), the sum of its
//!   autocovariances);
//! - **a Gauss-Markov process longer than the bias state's** is a random walk at the scales
//!   below its Tc, K² = 2σ²/Tc; so is every Gauss-Markov process whose Tc exceeds the record
//!   (its Tc is not identified, only σ²/Tc is);
//! - **a random walk** K² (and the folded ones) is added to the bias state's driving noise
//!   q = 2σ_b²/Tc_b, at the bias state's Tc: σ_b² += K² Tc_b/2 (per sample, exactly
//!   σ_b² += γ²/(1 − φ_b²)), which is the same random walk
//!   at every τ ≪ Tc_b. Without any Gauss-Markov process the bias state is a random walk held
//!   by a Tc of the record's length: σ_b² = K² T/2;
//! - **quantisation noise** is dropped: it is the difference of a white sequence, so its
//!   integral does not grow (AVAR 3Q²/τ² falls faster than white noise's);
//! - **drift** is dropped from the noise: a constant trend is what the bias state estimates.
//!
//! The mapped model is an approximation; [`MappedNoise::band_ratio`] says by how much its
//! wavelet variance departs from the composite's at the scales of the band.

use serde::{Deserialize, Serialize};

use super::model::{Term, composite_wavelet_variance};

/// The outage band of averaging times the mapping is made for, s.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TauBand {
    /// Shortest averaging time, s.
    pub shortest_s: f64,
    /// Longest averaging time, s.
    pub longest_s: f64,
}

impl Default for TauBand {
    /// One second to one minute: the outage lengths the tournament imposes (60 s) and the
    /// GNSS interval below them.
    fn default() -> Self {
        TauBand {
            shortest_s: 1.0,
            longest_s: 60.0,
        }
    }
}

/// What became of one process of the composite.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Fold {
    /// Into the white-noise density.
    White,
    /// It is the bias state.
    BiasState,
    /// Into the bias state's driving noise, as a random walk.
    RandomWalk,
    /// Dropped (quantisation noise, drift).
    Dropped,
}

/// The filter's noise parameters of one axis, from a composite.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MappedNoise {
    /// White-noise density N, unit·√s.
    pub white_noise_density: f64,
    /// Bias-state correlation time Tc, s.
    pub bias_correlation_time_s: f64,
    /// Bias-state standard deviation σ, unit.
    pub bias_sigma: f64,
    /// What became of each process, in the composite's order.
    pub folds: Vec<Fold>,
}

/// Maps `terms` (sampled every `dt_s`, a record of `record_s` seconds) onto the filter's white
/// noise and Gauss-Markov bias state for averaging times in `band`.
pub fn map_to_filter_states(
    terms: &[Term],
    dt_s: f64,
    record_s: f64,
    band: TauBand,
) -> MappedNoise {
    let record_samples = record_s / dt_s;
    let bias = bias_state_index(terms, dt_s, record_samples, band);
    let (tc_samples, bias_variance) = bias
        .and_then(|i| gauss_markov_parts(&terms[i]))
        .unwrap_or((record_samples, 0.0));
    let boundary = if bias.is_some() {
        tc_samples
    } else {
        band.shortest_s / dt_s
    };
    let folds: Vec<Fold> = terms
        .iter()
        .enumerate()
        .map(|(i, t)| fold_of(t, Some(i) == bias, boundary, record_samples))
        .collect();
    let white_per_sample: f64 = terms
        .iter()
        .zip(&folds)
        .filter(|(_, f)| **f == Fold::White)
        .map(|(t, _)| white_equivalent(t))
        .sum();
    let walk_per_sample: f64 = terms
        .iter()
        .zip(&folds)
        .filter(|(_, f)| **f == Fold::RandomWalk)
        .map(|(t, _)| walk_equivalent(t))
        .sum();
    let bias_walk_factor = -(-2.0 / tc_samples).exp_m1();
    MappedNoise {
        white_noise_density: (white_per_sample * dt_s).sqrt(),
        bias_correlation_time_s: tc_samples * dt_s,
        bias_sigma: (bias_variance + walk_per_sample / bias_walk_factor).sqrt(),
        folds,
    }
}

impl MappedNoise {
    /// The mapped model as a composite (white noise plus one Gauss-Markov process), sampled
    /// every `dt_s`.
    pub fn as_terms(&self, dt_s: f64) -> Vec<Term> {
        vec![
            Term::white_from_density(self.white_noise_density, dt_s),
            Term::gauss_markov_from(self.bias_correlation_time_s, self.bias_sigma, dt_s),
        ]
    }

    /// The ratios ν²_mapped(τ_j)/ν²_composite(τ_j) at the dyadic scales τ_j = 2^j dt inside
    /// `band`, with the scales in s.
    pub fn band_ratio(&self, terms: &[Term], dt_s: f64, band: TauBand) -> Vec<(f64, f64)> {
        let mapped = self.as_terms(dt_s);
        band_scales(dt_s, band)
            .map(|tau| {
                let ratio = composite_wavelet_variance(&mapped, tau)
                    / composite_wavelet_variance(terms, tau);
                (tau * dt_s, ratio)
            })
            .collect()
    }
}

/// The dyadic scales 2^j (samples) whose τ_j = 2^j dt lies in `band`.
pub fn band_scales(dt_s: f64, band: TauBand) -> impl Iterator<Item = f64> {
    (1..63)
        .map(|j| f64::powi(2.0, j))
        .filter(move |tau| tau * dt_s >= band.shortest_s && tau * dt_s <= band.longest_s)
}

/// The Gauss-Markov process with τ_lo ≤ Tc ≤ the record and the largest share of the
/// composite's wavelet variance at some scale of the band.
fn bias_state_index(
    terms: &[Term],
    dt_s: f64,
    record_samples: f64,
    band: TauBand,
) -> Option<usize> {
    let shortest = band.shortest_s / dt_s;
    let share = |t: &Term| {
        band_scales(dt_s, band)
            .map(|tau| t.wavelet_variance(tau) / composite_wavelet_variance(terms, tau))
            .fold(0.0, f64::max)
    };
    terms
        .iter()
        .enumerate()
        .filter(|(_, t)| {
            matches!(t, Term::GaussMarkov { correlation_samples, .. }
                if *correlation_samples >= shortest && *correlation_samples <= record_samples)
        })
        .max_by(|a, b| share(a.1).total_cmp(&share(b.1)))
        .map(|(i, _)| i)
}

/// Where one process goes, `boundary` the bias state's Tc (samples).
fn fold_of(term: &Term, is_bias: bool, boundary: f64, record_samples: f64) -> Fold {
    match *term {
        _ if is_bias => Fold::BiasState,
        Term::White { .. } => Fold::White,
        Term::RandomWalk { .. } => Fold::RandomWalk,
        Term::Quantisation { .. } | Term::Drift { .. } => Fold::Dropped,
        Term::GaussMarkov {
            correlation_samples,
            ..
        } if correlation_samples < boundary && correlation_samples <= record_samples => Fold::White,
        Term::GaussMarkov { .. } => Fold::RandomWalk,
    }
}

/// The white-noise variance per sample that `term` amounts to at scales beyond its memory:
/// σ² for white noise; for a Gauss-Markov process the sum of its autocovariances over all
/// lags, σ²(1 + φ)/(1 − φ) = σ² coth(1/(2Tc)) ≈ 2σ²Tc (Tc in samples).
fn white_equivalent(term: &Term) -> f64 {
    match *term {
        Term::White { variance } => variance,
        Term::GaussMarkov {
            correlation_samples,
            variance,
        } => variance / (0.5 / correlation_samples).tanh(),
        _ => 0.0,
    }
}

/// The random-walk increment variance per sample that `term` amounts to at scales within its
/// memory: γ² for a random walk; for a Gauss-Markov process its innovation variance
/// σ²(1 − φ²) ≈ 2σ²/Tc (Tc in samples).
fn walk_equivalent(term: &Term) -> f64 {
    match *term {
        Term::RandomWalk { variance } => variance,
        Term::GaussMarkov {
            correlation_samples,
            variance,
        } => -variance * (-2.0 / correlation_samples).exp_m1(),
        _ => 0.0,
    }
}

/// (Tc in samples, σ²) of a Gauss-Markov process.
fn gauss_markov_parts(term: &Term) -> Option<(f64, f64)> {
    match *term {
        Term::GaussMarkov {
            correlation_samples,
            variance,
        } => Some((correlation_samples, variance)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stoch::allan::{ChiSquareQuantile, chi_square_quantile};
    use crate::stoch::wavelet_variance::max_level;

    const DT_S: f64 = 0.01;

    fn gm(tc_s: f64, sigma: f64) -> Term {
        Term::gauss_markov_from(tc_s, sigma, DT_S)
    }

    // The white and random-walk equivalents are limits of the closed-form wavelet variance
    // (an independent formula, checked against its slow definition in `theory`): ν²(τ)·τ of a
    // Gauss-Markov process tends to its white equivalent as τ/Tc → ∞, and ν²(τ)·12/τ to its
    // random-walk equivalent as τ/Tc → 0 (ν² of a random walk is γ²(τ² + 2)/(12τ)).
    #[test]
    fn equivalents_are_the_limits_of_the_wavelet_variance() {
        for tc in [0.7, 3.0, 40.0] {
            let term = Term::GaussMarkov {
                correlation_samples: tc,
                variance: 2.5,
            };
            let tau_long = 2f64.powi(40);
            let white = term.wavelet_variance(tau_long) * tau_long;
            assert!(
                (white / white_equivalent(&term) - 1.0).abs() < 1e-9,
                "Tc {tc}"
            );
        }
        let slow = Term::GaussMarkov {
            correlation_samples: 1e9,
            variance: 2.5,
        };
        let tau = 64.0;
        let walk = slow.wavelet_variance(tau) * 12.0 * tau / (tau * tau + 2.0);
        // The first neglected term is of order τ/Tc = 6e-8.
        assert!((walk / walk_equivalent(&slow) - 1.0).abs() < 1e-6);
    }

    // Pure white noise maps onto itself, with no bias state beyond a zero random walk.
    #[test]
    fn white_noise_alone_maps_onto_itself() {
        let terms = [Term::white_from_density(3e-3, DT_S)];
        let mapped = map_to_filter_states(&terms, DT_S, 3600.0, TauBand::default());
        assert!((mapped.white_noise_density / 3e-3 - 1.0).abs() < 1e-14);
        assert_eq!(mapped.bias_sigma, 0.0);
        assert_eq!(mapped.bias_correlation_time_s, 3600.0);
        assert_eq!(mapped.folds, vec![Fold::White]);
    }

    // A sensor-like composite: white noise, a 0.05 s Gauss-Markov process (an internal
    // low-pass), the 80 s bias process the band sees, a random walk and a Gauss-Markov process
    // whose Tc (1e9 s) no record identifies. Each goes where the rules say.
    #[test]
    fn each_process_goes_where_the_rules_say() {
        let terms = [
            Term::white_from_density(2e-3, DT_S),
            gm(0.05, 0.02),
            gm(80.0, 4e-4),
            Term::random_walk_from_k(2e-6, DT_S),
            gm(1e9, 0.5),
            Term::Quantisation { variance: 1e-8 },
        ];
        let mapped = map_to_filter_states(&terms, DT_S, 20_000.0, TauBand::default());
        use Fold::*;
        assert_eq!(
            mapped.folds,
            vec![White, White, BiasState, RandomWalk, RandomWalk, Dropped]
        );
        assert_eq!(mapped.bias_correlation_time_s, 80.0);
        // Continuous-time forms: N² = N_wn² + 2σ²Tc, σ_b² = σ² + (K² + 2σ_slow²/Tc_slow)·Tc_b/2;
        // the discrete forms agree with them to O(dt/Tc).
        let n2 = 2e-3f64.powi(2) + 2.0 * 0.02f64.powi(2) * 0.05;
        assert!((mapped.white_noise_density.powi(2) / n2 - 1.0).abs() < 0.02);
        let k2 = 2e-6f64.powi(2) + 2.0 * 0.25 / 1e9;
        let s2 = 4e-4f64.powi(2) + k2 * 80.0 / 2.0;
        assert!((mapped.bias_sigma.powi(2) / s2 - 1.0).abs() < 1e-3);
    }

    /// The chi-square 95 % range of ν̂²_j/ν²_j for a record of `n` samples at scale `tau`.
    fn sampling_range(n: usize, tau: f64) -> (f64, f64) {
        let eta = ((n as f64 - tau + 1.0) / tau).max(1.0);
        let q = |p| chi_square_quantile(p, eta, ChiSquareQuantile::Exact).unwrap() / eta;
        (q(0.025), q(0.975))
    }

    // The test: the mapped model's wavelet variance (Allan variance / 2) stays inside
    // the composite's 95 % sampling band at every dyadic scale of the outage band (1-60 s),
    // for WN + RW + 2 GM and WN + QN + GM composites of ADIS16405-like magnitudes recorded for
    // 3 h at 100 Hz (the band a record of that length draws around the composite's curve).
    #[test]
    fn mapped_model_stays_inside_the_composites_band_over_an_outage() {
        let n = 3 * 3600 * 100;
        let composites = [
            vec![
                Term::white_from_density(7e-4, DT_S),
                Term::random_walk_from_k(3e-7, DT_S),
                gm(0.01, 0.02),
                gm(300.0, 1.5e-4),
            ],
            vec![
                Term::white_from_density(5e-3, DT_S),
                Term::Quantisation { variance: 1e-7 },
                gm(120.0, 8e-4),
            ],
        ];
        assert!(
            max_level(n) >= 12,
            "the band's 1-60 s scales exist in the record"
        );
        for terms in composites {
            let band = TauBand::default();
            let mapped = map_to_filter_states(&terms, DT_S, n as f64 * DT_S, band);
            let ratios = mapped.band_ratio(&terms, DT_S, band);
            assert_eq!(ratios.len(), 6, "scales 1.28 s .. 40.96 s");
            for (tau_s, ratio) in ratios {
                let (low, high) = sampling_range(n, tau_s / DT_S);
                assert!(
                    ratio > low && ratio < high,
                    "{terms:?}: at {tau_s} s the mapped/composite ratio {ratio} is outside \
                     the sampling band [{low}, {high}]"
                );
            }
        }
    }
}
