//! What a fit reports: the processes the record resolves, with the Gauss-Markov processes it
//! cannot tell from white noise or from a random walk merged into them.
//!
//! Two things made `gmwm`'s numbers mislead on a real record (issue 38, row 6):
//! - **processes the record does not resolve**: the optimiser works on the logarithms of the
//!   variances, so a process the data do not need drifts towards zero and was printed as
//!   `1.03e-84`; and the WIC (objective + 2 per parameter, like the AIC) takes a process that
//!   lowers the objective by a little more than 2, which a record without it does by chance
//!   (a white-noise and random-walk record got quantisation noise on one channel of six).
//!   [`resolve_selection`] leaves out, one at a time, every process (white noise apart) whose
//!   removal, the others refitted with the same weights, raises the objective by less than
//!   the χ² quantile at 1 − [`RESOLUTION_LEVEL`] (one degree of freedom per parameter), and
//!   refits without it; each is reported as absent with that test;
//! - **Gauss-Markov processes at the record's edges**: a sensor's internal low-pass makes the
//!   shortest scales fall below white noise, which the fit describes with a Gauss-Markov
//!   process at Tc ≈ one sample period (the fit keeps Tc above one sample); that process took
//!   a third of the ADIS16405's gyro white noise, whose density then read 1.50 deg/√h where
//!   the Allan curve gives 2.51. A process with Tc of at most [`WHITE_MERGE_SAMPLE_PERIODS`]
//!   is white at every averaging time beyond a few samples, and it is reported merged into the
//!   white noise: its spectrum at zero frequency, per sample σ²(1 + φ)/(1 − φ) ≈ 2σ²Tc, added
//!   to the white noise's variance (the density then agrees with the Allan curve's −½ line).
//!   At the other end a process whose Tc exceeds the record is seen only through σ²/Tc, as a
//!   random walk with increments σ²(1 − φ²) per sample: it is reported merged into the random
//!   walk (at the longest scale, at most half the record, its wavelet variance is within
//!   1 − 0.37 τ/Tc ≥ 82 % of that random walk's, where the estimate's own 95 % interval spans
//!   more than a factor of ten).
//!
//! Merging is a way of reporting the fitted composite, not another fit: the wavelet variance
//! the fit implies is the same, and the bootstrap's intervals of a merged parameter come from
//! the replicates merged the same way ([`merged_terms`]).

use serde::Serialize;
use statrs::distribution::{ChiSquared, ContinuousCDF};

use super::bootstrap::{GmwmEstimate, ModelSelection, estimate_gmwm};
use super::fit::{GmwmFit, objective_without};
use super::model::{ModelSpec, Term};
use super::{BootstrapSettings, GmwmError, fit_gmwm};
use crate::stoch::wavelet_variance::WaveletVariance;

/// The significance level below which a process is resolved: leaving it out must raise the
/// objective beyond the χ²(parameters) quantile at 1 − this. Measured on twenty simulated
/// white-noise and random-walk records (2^17 samples, 120 channels, `gmwm` with `auto`): the
/// report without the test had quantisation noise on 6 channels and a Gauss-Markov process
/// of at most 0.1 s on 5; with it, on none. Asked for `wn+qn+rw+2gm` on twenty such records
/// whose white noise partly passes a one-sample low-pass, quantisation noise was left out on
/// all 120 channels (p ≥ 0.61).
pub const RESOLUTION_LEVEL: f64 = 0.01;

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

/// A process the record does not resolve, left out.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AbsentProcess {
    /// The process (`qn`, `rw`, `dr`, `gm`).
    pub process: &'static str,
    /// The composite it was fitted in and left out of.
    pub fitted_in: ModelSpec,
    /// How much leaving it out raised the objective (the others refitted, same weights; zero
    /// when the refit without it went lower).
    pub objective_rise: f64,
    /// Its parameters: the χ² degrees of freedom of the test.
    pub degrees_of_freedom: usize,
    /// P(χ² > rise): at or above [`RESOLUTION_LEVEL`], the process is absent.
    pub p_value: f64,
}

/// The selected composite with the processes the record does not resolve left out, and what
/// was left out.
#[derive(Debug, Clone, PartialEq)]
pub struct ResolvedModel {
    /// The estimate of the composite reported (the selected one when nothing was left out).
    pub estimate: GmwmEstimate,
    /// The processes left out, in the order they were.
    pub absent: Vec<AbsentProcess>,
}

/// The first-ranked candidate of `selection` (fitted to `wv`) with every process the record
/// does not resolve left out, one at a time, the least resolved first (module docs). The
/// composite left is refitted and estimated with `settings` (a ranked candidate of the same
/// composite is taken as it is); when its bootstrap fails, it is given without intervals.
///
/// # Errors
/// Those of [`fit_gmwm`] and [`estimate_gmwm`] on the reduced composite.
pub fn resolve_selection(
    wv: &WaveletVariance,
    selection: &ModelSelection,
    settings: BootstrapSettings,
) -> Result<ResolvedModel, GmwmError> {
    let mut fit = selection.ranked[0].fit.clone();
    let mut absent = vec![];
    while let Some(left_out) = least_resolved(wv, &fit) {
        let k = left_out.0;
        absent.push(left_out.1);
        fit = fit_gmwm(wv, without(fit.model, &fit.terms[k]))?;
    }
    let estimate = match selection.ranked.iter().find(|e| e.fit.model == fit.model) {
        Some(e) => e.clone(),
        None => estimate_gmwm(wv, fit.model, settings).or_else(|_| {
            let without_bootstrap = BootstrapSettings {
                replicates: 0,
                ..settings
            };
            estimate_gmwm(wv, fit.model, without_bootstrap)
        })?,
    };
    Ok(ResolvedModel { estimate, absent })
}

/// The process of `fit` (white noise apart, one process always kept) whose removal is least
/// significant, when it is not significant at [`RESOLUTION_LEVEL`]: its index and record.
fn least_resolved(wv: &WaveletVariance, fit: &GmwmFit) -> Option<(usize, AbsentProcess)> {
    if fit.terms.len() < 2 {
        return None;
    }
    (fit.terms.iter().enumerate())
        .filter(|(_, t)| !matches!(t, Term::White { .. }))
        .map(|(k, t)| {
            let rise = (objective_without(wv, fit, k) - fit.objective).max(0.0);
            let degrees_of_freedom = t.n_coordinates();
            let p_value =
                ChiSquared::new(degrees_of_freedom as f64).map_or(0.0, |chi2| chi2.sf(rise));
            let record = AbsentProcess {
                process: process_name(t),
                fitted_in: fit.model,
                objective_rise: rise,
                degrees_of_freedom,
                p_value,
            };
            (k, record)
        })
        .max_by(|a, b| a.1.p_value.total_cmp(&b.1.p_value))
        .filter(|(_, record)| record.p_value >= RESOLUTION_LEVEL)
}

/// The short name of a process, as in a composite's name.
fn process_name(term: &Term) -> &'static str {
    match term {
        Term::White { .. } => "wn",
        Term::Quantisation { .. } => "qn",
        Term::RandomWalk { .. } => "rw",
        Term::Drift { .. } => "dr",
        Term::GaussMarkov { .. } => "gm",
    }
}

/// `spec` without one process of `term`'s kind.
fn without(mut spec: ModelSpec, term: &Term) -> ModelSpec {
    match term {
        Term::White { .. } => spec.white = false,
        Term::Quantisation { .. } => spec.quantisation = false,
        Term::RandomWalk { .. } => spec.random_walk = false,
        Term::Drift { .. } => spec.drift = false,
        Term::GaussMarkov { .. } => spec.gauss_markov -= 1,
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

    /// The selection of `candidates` on `n` samples of `truth` (stream `name`), resolved.
    fn resolved(truth: &[Term], n: usize, name: &str, candidates: &[&str]) -> ResolvedModel {
        use crate::stoch::gmwm::{select_model, simulate};
        use crate::stoch::wavelet_variance::haar_wavelet_variance;
        let y = simulate(truth, n, &mut crate::rng::named_rng(3, name));
        let wv = haar_wavelet_variance(&y, 1.0, None, 0.95).unwrap();
        let candidates: Vec<ModelSpec> = candidates.iter().map(|c| c.parse().unwrap()).collect();
        let settings = BootstrapSettings {
            replicates: 0,
            ..BootstrapSettings::default()
        };
        let selection = select_model(&wv, &candidates, settings).unwrap();
        resolve_selection(&wv, &selection, settings).unwrap()
    }

    // Quantisation noise asked for on a record without it is left out, with the test that
    // says so, and the composite without it is the one reported; on a record with strong
    // quantisation noise (it dominates the first scales) nothing is left out.
    #[test]
    fn a_process_the_record_does_not_have_is_absent_and_one_it_has_is_kept() {
        let truth = [
            Term::White { variance: 1.0 },
            Term::RandomWalk { variance: 1e-4 },
        ];
        let without = resolved(&truth, 1 << 16, "resolution/without", &["wn+qn+rw"]);
        assert_eq!(without.estimate.fit.model.to_string(), "wn+rw");
        assert_eq!(without.absent.len(), 1);
        let qn = &without.absent[0];
        assert_eq!((qn.process, qn.degrees_of_freedom), ("qn", 1));
        assert_eq!(qn.fitted_in.to_string(), "wn+qn+rw");
        assert!(qn.p_value >= RESOLUTION_LEVEL, "{qn:?}");
        let with_qn = [truth[0], Term::Quantisation { variance: 4.0 }, truth[1]];
        let kept = resolved(&with_qn, 1 << 16, "resolution/with", &["wn+qn+rw"]);
        assert!(kept.absent.is_empty(), "{:?}", kept.absent);
        assert_eq!(kept.estimate.reported_model.to_string(), "wn+qn+rw");
    }

    #[test]
    fn nothing_is_merged_in_a_composite_of_mid_range_processes() {
        let terms = [Term::White { variance: 1.0 }, gm(3.5, 1.0), gm(1000.0, 1.0)];
        let plan = merge_plan(&terms, 4096);
        assert!(plan.iter().all(Option::is_none));
        assert_eq!(merged_terms(&terms, &plan), terms.to_vec());
    }
}
