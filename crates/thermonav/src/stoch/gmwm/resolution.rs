//! What a fit reports: the processes the record resolves (the Gauss-Markov processes it
//! cannot tell from white noise or a random walk are merged into them by [`super::merging`]).
//!
//! Processes the record does not resolve made `gmwm`'s numbers mislead on a real record
//! (issue 38, row 6): the optimiser works on the logarithms of the variances, so a process the
//! data do not need drifts towards zero and was printed as `1.03e-84`; and the WIC (the
//! objective plus 2 per parameter, like the AIC) takes a process that lowers the objective by a little more
//! than 2, which a record without it does by chance (a white-noise and random-walk record got
//! quantisation noise on one channel of six). [`resolve_selection`] leaves out, one at a time,
//! every process (white noise apart) whose removal, the others refitted with the same weights,
//! raises the objective by less than the χ² quantile at 1 − [`RESOLUTION_LEVEL`] (one degree
//! of freedom per parameter), and refits without it; each is reported as absent with that
//! test.

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
}
