//! The GMWM fit of one composite to one wavelet variance: automatic starting values, then
//! Levenberg-Marquardt on the weighted wavelet-moment residuals.

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use super::GmwmError;
use super::model::{
    ModelSpec, Term, composite_wavelet_variances, gauss_markov_factors, sum_over_terms,
    term_wavelet_variances,
};
use super::theory::ScaleFactors;
use crate::optimise::levenberg_marquardt::{
    LeastSquares, LmSettings, central_differences, minimise,
};
use crate::stoch::wavelet_variance::WaveletVariance;

/// The empirical moments a fit matches: scales τ_j (samples), ν̂²_j and their standard
/// deviations √(2/η_j) ν̂²_j; Ω = diag(1/sd²_j).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Moments {
    pub tau: Vec<f64>,
    pub nu: Vec<f64>,
    pub sd: Vec<f64>,
}

impl Moments {
    pub fn of(wv: &WaveletVariance) -> Result<Moments, GmwmError> {
        if let Some(j) = wv
            .variance
            .iter()
            .position(|v| v.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater))
        {
            return Err(GmwmError::ZeroWaveletVariance {
                scale_samples: wv.scale_samples[j],
            });
        }
        let sd = wv.estimate_variance().iter().map(|v| v.sqrt()).collect();
        Ok(Moments {
            tau: wv.scale_samples.iter().map(|&t| t as f64).collect(),
            nu: wv.variance.clone(),
            sd,
        })
    }

    /// The same moments with sd_j = √(2/η_j) ν²_j(θ): the weights of the second step.
    pub fn reweighted(&self, terms: &[Term]) -> Moments {
        let implied = composite_wavelet_variances(terms, &self.tau);
        let sd = (0..self.tau.len())
            .map(|j| self.sd[j] / self.nu[j] * implied[j])
            .collect();
        Moments { sd, ..self.clone() }
    }

    /// (ν̂²_j − ν²_j(θ)) / sd_j.
    pub fn residuals(&self, terms: &[Term]) -> Vec<f64> {
        self.residuals_of_implied(&composite_wavelet_variances(terms, &self.tau))
    }

    /// (ν̂²_j − `implied`_j) / sd_j.
    fn residuals_of_implied(&self, implied: &[f64]) -> Vec<f64> {
        (0..self.tau.len())
            .map(|j| (self.nu[j] - implied[j]) / self.sd[j])
            .collect()
    }

    /// The GMWM objective (ν̂ − ν(θ))ᵀ Ω (ν̂ − ν(θ)).
    pub fn objective(&self, terms: &[Term]) -> f64 {
        sum_of_squares(&self.residuals(terms))
    }

    /// [`Self::objective`] with the Gauss-Markov curves taken from `table` where it has them.
    fn objective_with(&self, terms: &[Term], table: &CurveTable) -> f64 {
        let each: Vec<Vec<f64>> = terms.iter().map(|t| table.wavelet_variances(t)).collect();
        let implied = sum_over_terms(&each, self.tau.len());
        sum_of_squares(&self.residuals_of_implied(&implied))
    }
}

/// Σ r².
fn sum_of_squares(r: &[f64]) -> f64 {
    r.iter().map(|r| r * r).sum()
}

/// A composite fitted by GMWM.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GmwmFit {
    /// The composite.
    pub model: ModelSpec,
    /// Its processes with per-sample parameters, Gauss-Markov processes by increasing Tc.
    pub terms: Vec<Term>,
    /// The minimised objective (ν̂ − ν(θ̂))ᵀ Ω (ν̂ − ν(θ̂)), dimensionless.
    pub objective: f64,
    /// Scales τ_j, samples.
    pub scale_samples: Vec<usize>,
    /// √var(ν̂²_j) of the weights Ω = diag(1/sd²_j), unit of the data squared.
    pub moment_sd: Vec<f64>,
    /// The model's wavelet variance ν²_j(θ̂), unit of the data squared.
    pub implied_variance: Vec<f64>,
    /// Sampling interval, s.
    pub dt_s: f64,
}

/// Fits `model` to the wavelet variance `wv` by GMWM with Ω = diag(1/var(ν̂²_j)), in two
/// steps: var(ν̂²_j) ≈ 2 ν̂⁴_j/η_j first, then 2 ν⁴_j(θ̂₁)/η_j.
///
/// Starting values: for every increasing tuple of Gauss-Markov correlation times taken from
/// the scales τ_j, the variances of all processes are linear in ν², so a weighted
/// non-negative least-squares fit gives them; the best few of these starts are refined by
/// Levenberg-Marquardt in log coordinates and the lowest objective is kept.
///
/// # Errors
/// [`GmwmError`] when the wavelet variance has no more scales than the model has parameters,
/// or a zero variance at some scale.
pub fn fit_gmwm(wv: &WaveletVariance, model: ModelSpec) -> Result<GmwmFit, GmwmError> {
    let moments = Moments::of(wv)?;
    if moments.tau.len() <= model.n_parameters() {
        return Err(GmwmError::TooFewScales {
            scales: moments.tau.len(),
            parameters: model.n_parameters(),
        });
    }
    let table = CurveTable::new(candidate_correlation_times(&moments.tau), &moments.tau);
    let mut starts: Vec<(f64, Vec<Term>)> = correlation_tuples(&moments.tau, model.gauss_markov)
        .iter()
        .map(|tcs| linear_start(&moments, model, tcs, &table))
        .map(|terms| (moments.objective_with(&terms, &table), terms))
        .collect();
    starts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let best = starts
        .iter()
        .take(STARTS)
        .map(|(_, terms)| refine(&moments, terms))
        .min_by(|a, b| moments.objective(a).total_cmp(&moments.objective(b)))
        .expect("at least one start");
    Ok(second_step(wv, model, &moments, &best))
}

/// The second GMWM step: Ω from the first step's model, var(ν̂²_j) ≈ 2 ν⁴_j(θ̂₁)/η_j, and a
/// refit from θ̂₁. Weights from ν̂² itself favour the scales where ν̂² happens to be low and
/// pull every variance down (by a few per cent on 10⁶ samples, as much as the intervals are
/// wide); weights from the model do not depend on the noise of each ν̂²_j.
fn second_step(
    wv: &WaveletVariance,
    model: ModelSpec,
    moments: &Moments,
    first: &[Term],
) -> GmwmFit {
    let moments = moments.reweighted(first);
    let terms = refine(&moments, first);
    fit_of(wv, model, &moments, terms)
}

fn fit_of(wv: &WaveletVariance, model: ModelSpec, moments: &Moments, terms: Vec<Term>) -> GmwmFit {
    GmwmFit {
        model,
        objective: moments.objective(&terms),
        moment_sd: moments.sd.clone(),
        scale_samples: wv.scale_samples.clone(),
        implied_variance: composite_wavelet_variances(&terms, &moments.tau),
        terms,
        dt_s: wv.dt_s,
    }
}

/// The objective of `fit`'s composite without its `k`-th process, the others refitted by
/// Levenberg-Marquardt from their values in `fit` and with `fit`'s weights, so that its rise
/// over `fit.objective` is what leaving the process out costs. `wv` is the wavelet variance
/// `fit` was fitted to.
pub(super) fn objective_without(wv: &WaveletVariance, fit: &GmwmFit, k: usize) -> f64 {
    let moments = Moments {
        tau: wv.scale_samples.iter().map(|&t| t as f64).collect(),
        nu: wv.variance.clone(),
        sd: fit.moment_sd.clone(),
    };
    let start: Vec<Term> = (fit.terms.iter().enumerate())
        .filter(|(i, _)| *i != k)
        .map(|(_, t)| *t)
        .collect();
    moments.objective(&refine(&moments, &start))
}

/// Starts refined by Levenberg-Marquardt.
const STARTS: usize = 4;

/// Coordinates of all terms, concatenated.
pub(super) fn coordinates(terms: &[Term]) -> Vec<f64> {
    terms.iter().flat_map(Term::coordinates).collect()
}

/// `template`'s processes with the coordinates `x`.
pub(super) fn with_coordinates(template: &[Term], x: &[f64]) -> Vec<Term> {
    (template.iter().zip(coordinate_spans(template)))
        .map(|(t, span)| t.with_coordinates(&x[span]))
        .collect()
}

/// Where each term's coordinates sit in the coordinate vector of a composite shaped like
/// `template`.
fn coordinate_spans(template: &[Term]) -> Vec<std::ops::Range<usize>> {
    let mut offset = 0;
    (template.iter())
        .map(|t| {
            offset += t.n_coordinates();
            offset - t.n_coordinates()..offset
        })
        .collect()
}

/// Levenberg-Marquardt from `start`, then the Gauss-Markov processes sorted by Tc.
fn refine(moments: &Moments, start: &[Term]) -> Vec<Term> {
    let problem = MomentProblem {
        moments,
        template: start,
    };
    let result = minimise(&problem, &coordinates(start), LmSettings::default());
    sorted(with_coordinates(start, &result.x))
}

/// The residuals of `moments` as a function of the coordinates of a composite shaped like
/// `template`.
struct MomentProblem<'a> {
    moments: &'a Moments,
    template: &'a [Term],
}

impl LeastSquares for MomentProblem<'_> {
    fn residuals(&self, x: &[f64]) -> Vec<f64> {
        self.moments.residuals(&with_coordinates(self.template, x))
    }

    /// A coordinate moves one term: the other terms' wavelet variances are computed once at x
    /// and only the moved term's again at x ± h (from the curve at x when the coordinate is a
    /// Gauss-Markov variance), then summed over the terms in the same order as at a whole
    /// evaluation, so the values are those of the generic Jacobian, bit for bit, for a fraction
    /// of its curve evaluations.
    fn jacobian(&self, x: &[f64], n_residuals: usize, step: f64) -> DMatrix<f64> {
        let tau = &self.moments.tau;
        let terms = with_coordinates(self.template, x);
        let table = CurveTable::new(terms.iter().filter_map(correlation_samples), tau);
        let mut each: Vec<Vec<f64>> = terms.iter().map(|t| table.wavelet_variances(t)).collect();
        let spans = coordinate_spans(self.template);
        let mut probe = x.to_vec();
        central_differences(x, n_residuals, step, |k, h| {
            let i = spans.iter().take_while(|span| span.end <= k).count();
            probe[k] = x[k] + h;
            let moved = self.template[i].with_coordinates(&probe[spans[i].clone()]);
            probe[k] = x[k];
            let kept = std::mem::replace(&mut each[i], table.wavelet_variances(&moved));
            let residuals = self
                .moments
                .residuals_of_implied(&sum_over_terms(&each, tau.len()));
            each[i] = kept;
            residuals
        })
    }
}

/// Gauss-Markov curves at the scales `tau` for some correlation times, computed once for all the
/// evaluations that use them (the starts' tuples draw from a few correlation times; a
/// Jacobian's variance coordinates keep theirs).
struct CurveTable<'a> {
    tau: &'a [f64],
    curves: Vec<(f64, Vec<ScaleFactors>)>,
}

impl<'a> CurveTable<'a> {
    fn new(correlation_samples: impl Iterator<Item = f64>, tau: &'a [f64]) -> Self {
        let curves = correlation_samples
            .map(|tc| (tc, gauss_markov_factors(tc, tau)))
            .collect();
        Self { tau, curves }
    }

    /// `term`'s wavelet variance at every scale, the values [`term_wavelet_variances`] gives:
    /// from the table's curve when it has the term's correlation time.
    fn wavelet_variances(&self, term: &Term) -> Vec<f64> {
        let curve = correlation_samples(term).and_then(|tc| {
            self.curves
                .iter()
                .find(|(known, _)| known.to_bits() == tc.to_bits())
        });
        match (term, curve) {
            (Term::GaussMarkov { variance, .. }, Some((_, factors))) => {
                factors.iter().map(|f| f.at(*variance)).collect()
            }
            _ => term_wavelet_variances(term, self.tau),
        }
    }
}

/// A Gauss-Markov term's correlation time, samples.
fn correlation_samples(term: &Term) -> Option<f64> {
    match *term {
        Term::GaussMarkov {
            correlation_samples,
            ..
        } => Some(correlation_samples),
        _ => None,
    }
}

/// The Gauss-Markov processes by increasing correlation time (their labels are otherwise
/// interchangeable, and the intervals need one labelling).
pub(super) fn sorted(mut terms: Vec<Term>) -> Vec<Term> {
    let tc = |t: &Term| correlation_samples(t).unwrap_or(0.0);
    let first_gm = terms
        .iter()
        .position(|t| matches!(t, Term::GaussMarkov { .. }))
        .unwrap_or(terms.len());
    terms[first_gm..].sort_by(|a, b| tc(a).total_cmp(&tc(b)));
    terms
}

/// The correlation times (samples) the starts draw from: the scales τ_j/2.
fn candidate_correlation_times(tau: &[f64]) -> impl Iterator<Item = f64> + '_ {
    tau.iter().map(|t| t / 2.0)
}

/// Increasing k-tuples of candidate correlation times (samples): the scales τ_j/2, every
/// second one when there are too many tuples.
fn correlation_tuples(tau: &[f64], k: usize) -> Vec<Vec<f64>> {
    let mut candidates: Vec<f64> = candidate_correlation_times(tau).collect();
    while k > 1 && n_choose(candidates.len(), k) > 3000 {
        candidates = candidates.iter().step_by(2).copied().collect();
    }
    let mut tuples = vec![];
    let mut current = vec![];
    extend_tuples(&candidates, k, &mut current, &mut tuples);
    tuples
}

fn n_choose(n: usize, k: usize) -> usize {
    (0..k).fold(1, |acc, i| acc * (n - i) / (i + 1))
}

fn extend_tuples(pool: &[f64], k: usize, current: &mut Vec<f64>, out: &mut Vec<Vec<f64>>) {
    if current.len() == k {
        out.push(current.clone());
        return;
    }
    for (i, &tc) in pool.iter().enumerate() {
        current.push(tc);
        extend_tuples(&pool[i + 1..], k, current, out);
        current.pop();
    }
}

/// The model's processes with unit variance (unit slope for the drift) and the given Tc's.
fn unit_terms(model: ModelSpec, tcs: &[f64]) -> Vec<Term> {
    let unit = 1.0;
    let mut terms = vec![];
    let flags = [
        (model.white, Term::White { variance: unit }),
        (model.quantisation, Term::Quantisation { variance: unit }),
        (model.random_walk, Term::RandomWalk { variance: unit }),
        (model.drift, Term::Drift { slope: unit }),
    ];
    terms.extend(flags.iter().filter(|(on, _)| *on).map(|(_, t)| *t));
    terms.extend(tcs.iter().map(|&tc| Term::GaussMarkov {
        correlation_samples: tc,
        variance: unit,
    }));
    terms
}

/// Variances by weighted non-negative least squares with the Tc's fixed (every ν²_j is linear
/// in them; ω² for the drift), a variance at zero raised to 1 % of the largest value that
/// process could have alone.
fn linear_start(moments: &Moments, model: ModelSpec, tcs: &[f64], table: &CurveTable) -> Vec<Term> {
    let basis = unit_terms(model, tcs);
    let columns: Vec<Vec<f64>> = basis.iter().map(|t| table.wavelet_variances(t)).collect();
    let design = DMatrix::from_fn(moments.tau.len(), basis.len(), |j, i| {
        columns[i][j] / moments.sd[j]
    });
    let target = DVector::from_fn(moments.tau.len(), |j, _| moments.nu[j] / moments.sd[j]);
    let coefficients = non_negative_least_squares(&design, &target);
    basis
        .iter()
        .zip(coefficients)
        .enumerate()
        .map(|(i, (term, c))| {
            let ceiling = (0..moments.tau.len())
                .map(|j| target[j] / design[(j, i)])
                .fold(f64::INFINITY, f64::min);
            scaled(term, c.max(1e-2 * ceiling))
        })
        .collect()
}

/// `term` (with unit variance) scaled to variance `c` (ω² = c for the drift).
fn scaled(term: &Term, c: f64) -> Term {
    match *term {
        Term::White { .. } => Term::White { variance: c },
        Term::Quantisation { .. } => Term::Quantisation { variance: c },
        Term::RandomWalk { .. } => Term::RandomWalk { variance: c },
        Term::Drift { .. } => Term::Drift { slope: c.sqrt() },
        Term::GaussMarkov {
            correlation_samples,
            ..
        } => Term::GaussMarkov {
            correlation_samples,
            variance: c,
        },
    }
}

/// min ‖A c − b‖ over c ≥ 0 by a plain active set: solve on the free columns, fix the most
/// negative coefficient at zero, repeat (enough for starting values).
fn non_negative_least_squares(a: &DMatrix<f64>, b: &DVector<f64>) -> Vec<f64> {
    let mut free: Vec<usize> = (0..a.ncols()).collect();
    loop {
        let sub = a.select_columns(&free);
        let solved = sub.svd(true, true).solve(b, 1e-14).ok();
        let mut c = vec![0.0; a.ncols()];
        let Some(solved) = solved else { return c };
        free.iter().zip(solved.iter()).for_each(|(&i, &v)| c[i] = v);
        let most_negative = free
            .iter()
            .copied()
            .filter(|&i| c[i] < 0.0)
            .min_by(|&x, &y| c[x].total_cmp(&c[y]));
        match most_negative {
            Some(i) => free.retain(|&f| f != i),
            None => return c,
        }
        if free.is_empty() {
            return vec![0.0; a.ncols()];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // The starts' table against the terms' own curves: for composites whose Gauss-Markov
    // terms take the table's correlation times, every term's wavelet variances, the objective
    // and the linear start equal those computed without the table, bit for bit.
    #[test]
    fn the_curve_table_gives_the_terms_own_curves() {
        let tau: Vec<f64> = (0..14).map(|j| f64::from(1 << j)).collect();
        let nu: Vec<f64> = (tau.iter()).map(|t| 1e-3 / t + 1e-6 * t).collect();
        let moments = Moments {
            sd: nu.iter().map(|v| 0.2 * v).collect(),
            tau: tau.clone(),
            nu,
        };
        let table = CurveTable::new(candidate_correlation_times(&tau), &tau);
        let untabled = CurveTable::new(std::iter::empty(), &tau);
        let model: ModelSpec = "WN+2GM+RW".parse().unwrap();
        for tcs in [[0.5, 8.0], [4.0, 4096.0], [16.0, 1024.0]] {
            let start = linear_start(&moments, model, &tcs, &table);
            assert_eq!(
                start,
                linear_start(&moments, model, &tcs, &untabled),
                "{tcs:?}"
            );
            for term in &start {
                let tabled = table.wavelet_variances(term);
                assert_eq!(tabled, term_wavelet_variances(term, &tau), "{term:?}");
                let one_by_one: Vec<f64> = tau.iter().map(|&t| term.wavelet_variance(t)).collect();
                assert_eq!(tabled, one_by_one, "{term:?}");
            }
            assert_eq!(
                moments.objective_with(&start, &table).to_bits(),
                moments.objective(&start).to_bits()
            );
        }
    }

    // The term-wise Jacobian against the generic one (every term evaluated at x ± h): equal
    // bit for bit at several points of a four-term composite, Gauss-Markov curves on both
    // sides of their series/closed-form switch.
    #[test]
    fn the_term_wise_jacobian_is_the_generic_jacobian() {
        let tau: Vec<f64> = (0..16).map(|j| f64::from(1 << j)).collect();
        let template = [
            Term::White { variance: 2.0 },
            Term::GaussMarkov {
                correlation_samples: 5.0,
                variance: 0.3,
            },
            Term::GaussMarkov {
                correlation_samples: 900.0,
                variance: 0.05,
            },
            Term::RandomWalk { variance: 1e-7 },
        ];
        let nu = composite_wavelet_variances(&template, &tau)
            .iter()
            .enumerate()
            .map(|(j, v)| v * (1.0 + 0.05 * (j as f64).sin()))
            .collect::<Vec<_>>();
        let moments = Moments {
            sd: nu.iter().map(|v| 0.1 * v).collect(),
            tau,
            nu,
        };
        let problem = MomentProblem {
            moments: &moments,
            template: &template,
        };
        let generic = |x: &[f64]| problem.residuals(x);
        let start = coordinates(&template);
        for shift in [0.0, 0.7, -1.3, 2.9] {
            let x: Vec<f64> = (start.iter().enumerate())
                .map(|(k, c)| c + shift * (k as f64 * 1.7).cos())
                .collect();
            let n = moments.tau.len();
            let fast = problem.jacobian(&x, n, 1e-5);
            let slow = LeastSquares::jacobian(&generic, &x, n, 1e-5);
            assert_eq!(fast.shape(), (n, x.len()));
            for (f, s) in fast.iter().zip(slow.iter()) {
                assert_eq!(f.to_bits(), s.to_bits(), "shift {shift}");
            }
        }
    }
}
