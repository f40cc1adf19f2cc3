//! Gauss-Markov processes a record cannot tell from white noise or from a random walk,
//! reported merged into them (issue 38, row 6).
//!
//! A sensor's internal low-pass makes the shortest scales fall below white noise, which the
//! fit describes with a Gauss-Markov process at Tc ≈ one sample period (the fit keeps Tc above
//! one sample); that process took a third of the ADIS16405's gyro white noise, whose density
//! then read 1.50 deg/√h where the Allan curve gives 2.51. A process with Tc of at most
//! [`WHITE_MERGE_SAMPLE_PERIODS`] is white at every averaging time beyond a few samples, and it
//! is reported merged into the white noise: its spectrum at zero frequency, per sample
//! σ²(1 + φ)/(1 − φ) ≈ 2σ²Tc, added to the white noise's variance (the density then agrees
//! with the Allan curve's −½ line). At the other end a process whose Tc exceeds the record is
//! seen only through σ²/Tc, as a random walk with increments σ²(1 − φ²) per sample: it is
//! reported merged into the random walk (at the longest scale, at most half the record, its
//! wavelet variance is within 1 − 0.37 τ/Tc ≥ 82 % of that random walk's, where the estimate's
//! own 95 % interval spans more than a factor of ten).
//!
//! Merging is a way of reporting the fitted composite, not another fit: the wavelet variance
//! the fit implies is the same, and the bootstrap's intervals of a merged parameter come from
//! the replicates merged the same way ([`merged_terms`]).

use serde::Serialize;

use super::model::{ModelSpec, Term};

/// Gauss-Markov processes with Tc of at most this many sample periods are reported merged into
/// the white noise. Three sample periods covers a first-order low-pass whose cut-off is above
/// f_s/(6π) ≈ f_s/19 (Tc = 1/(2π f_c)); MEMS IMUs set their digital low-pass between about
/// f_s/10 and f_s/2 (Tc 0.3 to 1.6 samples), and at 64 samples a process of Tc = 3 samples
/// has 86 % of its white equivalent's wavelet variance, 93 % at 128.
pub const WHITE_MERGE_SAMPLE_PERIODS: f64 = 3.0;

/// What a Gauss-Markov process was merged into.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MergedInto {
    /// The white noise (Tc of a few sample periods).
    WhiteNoise,
    /// The random walk (Tc beyond the record).
    RandomWalk,
}

/// A Gauss-Markov process of the fit reported merged into another process.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MergedProcess {
    /// Which of the fitted composite's Gauss-Markov processes (from 1, by increasing Tc).
    pub gm_index: usize,
    /// Its correlation time, s.
    pub correlation_time_s: f64,
    /// Its correlation time in sample periods.
    pub correlation_samples: f64,
    /// Its standard deviation, unit of the data.
    pub sigma: f64,
    /// Where it went.
    pub into: MergedInto,
    /// What it amounts to alone: a white-noise density (unit·√s) or a random-walk coefficient
    /// (unit/√s); the merged parameter is the root of the sum of the squares.
    pub equivalent: f64,
    /// The record's length, s.
    pub record_s: f64,
}

/// Where each process of `terms` goes when reported: `None` kept, else merged.
pub(super) fn merge_plan(terms: &[Term], n_samples: usize) -> Vec<Option<MergedInto>> {
    terms
        .iter()
        .map(|t| match *t {
            Term::GaussMarkov {
                correlation_samples,
                ..
            } if correlation_samples <= WHITE_MERGE_SAMPLE_PERIODS => Some(MergedInto::WhiteNoise),
            Term::GaussMarkov {
                correlation_samples,
                ..
            } if correlation_samples > n_samples as f64 => Some(MergedInto::RandomWalk),
            _ => None,
        })
        .collect()
}

/// `terms` as reported under `plan` (from [`merge_plan`] of a composite shaped like `terms`):
/// the merged Gauss-Markov processes added to the white noise or the random walk (either
/// created when the composite has none), in the composite's order (wn, qn, rw, dr, gm...).
pub(super) fn merged_terms(terms: &[Term], plan: &[Option<MergedInto>]) -> Vec<Term> {
    let added = |into| -> f64 {
        (terms.iter().zip(plan))
            .filter(|(_, p)| **p == Some(into))
            .map(|(t, _)| per_sample_equivalent(t, into))
            .sum()
    };
    let (white, walk) = (added(MergedInto::WhiteNoise), added(MergedInto::RandomWalk));
    let mut kept: Vec<Term> = (terms.iter().zip(plan))
        .filter(|(_, p)| p.is_none())
        .map(|(t, _)| *t)
        .collect();
    add_variance(&mut kept, white, Term::White { variance: 0.0 });
    add_variance(&mut kept, walk, Term::RandomWalk { variance: 0.0 });
    kept
}

/// Adds `extra` to the variance of `kept`'s process of `like`'s kind, inserting one in the
/// composite's order when there is none (nothing when `extra` is zero).
fn add_variance(kept: &mut Vec<Term>, extra: f64, like: Term) {
    if extra == 0.0 {
        return;
    }
    let rank = |t: &Term| match t {
        Term::White { .. } => 0,
        Term::Quantisation { .. } => 1,
        Term::RandomWalk { .. } => 2,
        Term::Drift { .. } => 3,
        Term::GaussMarkov { .. } => 4,
    };
    match kept.iter_mut().find(|t| rank(t) == rank(&like)) {
        Some(Term::White { variance } | Term::RandomWalk { variance }) => *variance += extra,
        _ => {
            let at = kept.iter().take_while(|t| rank(t) < rank(&like)).count();
            let inserted = match like {
                Term::White { .. } => Term::White { variance: extra },
                _ => Term::RandomWalk { variance: extra },
            };
            kept.insert(at, inserted);
        }
    }
}

/// What a Gauss-Markov process adds per sample: to the white noise's variance the sum of its
/// autocovariances σ²(1 + φ)/(1 − φ) = σ² coth(1/(2 Tc)); to the random walk's increment
/// variance σ²(1 − φ²).
fn per_sample_equivalent(term: &Term, into: MergedInto) -> f64 {
    let Term::GaussMarkov {
        correlation_samples,
        variance,
    } = *term
    else {
        return 0.0;
    };
    match into {
        MergedInto::WhiteNoise => variance / (0.5 / correlation_samples).tanh(),
        MergedInto::RandomWalk => variance * -(-2.0 / correlation_samples).exp_m1(),
    }
}

/// The merged processes of `terms` (sampled every `dt_s`, `n_samples` of them) under `plan`.
pub(super) fn merged_processes(
    terms: &[Term],
    plan: &[Option<MergedInto>],
    dt_s: f64,
    n_samples: usize,
) -> Vec<MergedProcess> {
    let mut gm_index = 0;
    let mut merged = vec![];
    for (term, into) in terms.iter().zip(plan) {
        let Term::GaussMarkov {
            correlation_samples,
            variance,
        } = *term
        else {
            continue;
        };
        gm_index += 1;
        let Some(into) = *into else { continue };
        let per_sample = per_sample_equivalent(term, into);
        merged.push(MergedProcess {
            gm_index,
            correlation_time_s: correlation_samples * dt_s,
            correlation_samples,
            sigma: variance.sqrt(),
            into,
            equivalent: match into {
                MergedInto::WhiteNoise => (per_sample * dt_s).sqrt(),
                MergedInto::RandomWalk => (per_sample / dt_s).sqrt(),
            },
            record_s: n_samples as f64 * dt_s,
        });
    }
    merged
}

/// The composite of `terms` by kind.
pub(super) fn spec_of(terms: &[Term]) -> ModelSpec {
    let mut spec = ModelSpec::default();
    for term in terms {
        match term {
            Term::White { .. } => spec.white = true,
            Term::Quantisation { .. } => spec.quantisation = true,
            Term::RandomWalk { .. } => spec.random_walk = true,
            Term::Drift { .. } => spec.drift = true,
            Term::GaussMarkov { .. } => spec.gauss_markov += 1,
        }
    }
    spec
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stoch::gmwm::model::composite_wavelet_variance;

    fn gm(tc: f64, variance: f64) -> Term {
        Term::GaussMarkov {
            correlation_samples: tc,
            variance,
        }
    }

    // A process of one sample period goes into the white noise, one beyond the record into the
    // random walk (created here: the composite has none), the others stay in order; at scales
    // long beside the short process and short beside the long one, the reported composite's
    // wavelet variance is the fitted one's.
    #[test]
    fn short_and_long_processes_are_merged_into_white_noise_and_random_walk() {
        let n = 1 << 16;
        let terms = [
            Term::White { variance: 2.0 },
            Term::Quantisation { variance: 0.1 },
            gm(1.0, 3.0),
            gm(500.0, 0.01),
            gm(1e9, 50.0),
        ];
        let plan = merge_plan(&terms, n);
        use MergedInto::*;
        assert_eq!(
            plan,
            vec![None, None, Some(WhiteNoise), None, Some(RandomWalk)]
        );
        let reported = merged_terms(&terms, &plan);
        assert_eq!(spec_of(&reported).to_string(), "wn+qn+rw+gm");
        let Term::White { variance } = reported[0] else {
            panic!("{reported:?}")
        };
        let coth = 1.0 / 0.5f64.tanh();
        assert!((variance - (2.0 + 3.0 * coth)).abs() < 1e-12);
        for tau in [512.0, 2048.0] {
            let ratio = composite_wavelet_variance(&reported, tau)
                / composite_wavelet_variance(&terms, tau);
            assert!((ratio - 1.0).abs() < 0.01, "scale {tau}: {ratio}");
        }
        let merged = merged_processes(&terms, &plan, 0.01, n);
        assert_eq!(merged.len(), 2);
        assert_eq!((merged[0].gm_index, merged[1].gm_index), (1, 3));
        assert!((merged[0].equivalent - (3.0 * coth * 0.01f64).sqrt()).abs() < 1e-12);
        assert_eq!(merged[1].into, RandomWalk);
    }

    #[test]
    fn nothing_is_merged_in_a_composite_of_mid_range_processes() {
        let terms = [Term::White { variance: 1.0 }, gm(3.5, 1.0), gm(1000.0, 1.0)];
        let plan = merge_plan(&terms, 4096);
        assert!(plan.iter().all(Option::is_none));
        assert_eq!(merged_terms(&terms, &plan), terms.to_vec());
    }
}
