//! Composite models: which processes are summed ([`ModelSpec`], parsed from `wn+rw+2gm`), the
//! processes with their per-sample parameters ([`Term`]) and their physical values.

use std::fmt;
use std::str::FromStr;

use serde::Serialize;

use super::theory;

/// Which processes a composite sums: white noise (WN), quantisation noise (QN), random walk
/// (RW), drift (DR) and k first-order Gauss-Markov processes (GM).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct ModelSpec {
    /// White noise.
    pub white: bool,
    /// Quantisation noise.
    pub quantisation: bool,
    /// Random walk.
    pub random_walk: bool,
    /// Drift (a linear trend).
    pub drift: bool,
    /// Number of Gauss-Markov processes.
    pub gauss_markov: usize,
}

/// A model specification that does not parse.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ModelSpecError {
    /// A part that names no process.
    #[error("'{0}' is not a process: use wn, qn, rw, dr, gm or kgm (e.g. wn+rw+2gm)")]
    Unknown(String),
    /// A process named twice.
    #[error("'{0}' appears twice: write 2gm for two Gauss-Markov processes")]
    Repeated(String),
    /// No process at all.
    #[error("the model is empty")]
    Empty,
}

impl FromStr for ModelSpec {
    type Err = ModelSpecError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let mut spec = ModelSpec::default();
        for part in text.split('+').map(|p| p.trim().to_ascii_lowercase()) {
            spec.add(&part)?;
        }
        if spec.n_terms() == 0 {
            return Err(ModelSpecError::Empty);
        }
        Ok(spec)
    }
}

impl ModelSpec {
    fn add(&mut self, part: &str) -> Result<(), ModelSpecError> {
        let flag = match part {
            "wn" => &mut self.white,
            "qn" => &mut self.quantisation,
            "rw" => &mut self.random_walk,
            "dr" => &mut self.drift,
            _ => return self.add_gauss_markov(part),
        };
        if *flag {
            return Err(ModelSpecError::Repeated(part.into()));
        }
        *flag = true;
        Ok(())
    }

    fn add_gauss_markov(&mut self, part: &str) -> Result<(), ModelSpecError> {
        let count = part
            .strip_suffix("gm")
            .map(|k| {
                if k.is_empty() {
                    Ok(1)
                } else {
                    k.parse::<usize>()
                }
            })
            .and_then(Result::ok)
            .filter(|&k| k > 0)
            .ok_or_else(|| ModelSpecError::Unknown(part.into()))?;
        if self.gauss_markov > 0 {
            return Err(ModelSpecError::Repeated(part.into()));
        }
        self.gauss_markov = count;
        Ok(())
    }

    /// Number of processes.
    pub fn n_terms(&self) -> usize {
        [self.white, self.quantisation, self.random_walk, self.drift]
            .iter()
            .filter(|&&b| b)
            .count()
            + self.gauss_markov
    }

    /// Number of free parameters (two per Gauss-Markov process, one for each other process).
    pub fn n_parameters(&self) -> usize {
        self.n_terms() + self.gauss_markov
    }
}

impl fmt::Display for ModelSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts: Vec<String> = [
            (self.white, "wn"),
            (self.quantisation, "qn"),
            (self.random_walk, "rw"),
            (self.drift, "dr"),
        ]
        .iter()
        .filter(|(on, _)| *on)
        .map(|(_, name)| name.to_string())
        .collect();
        match self.gauss_markov {
            0 => {}
            1 => parts.push("gm".into()),
            k => parts.push(format!("{k}gm")),
        }
        write!(f, "{}", parts.join("+"))
    }
}

/// One process with its parameters per sample (variances in the unit of the data squared).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "process", rename_all = "snake_case")]
pub enum Term {
    /// White noise of variance σ² per sample.
    White {
        /// σ², unit².
        variance: f64,
    },
    /// Quantisation noise x_t − x_{t−1}, var(x) = Q².
    Quantisation {
        /// Q², unit².
        variance: f64,
    },
    /// Random walk with increments of variance γ².
    RandomWalk {
        /// γ², unit².
        variance: f64,
    },
    /// Drift ω t (t in samples).
    Drift {
        /// ω, unit per sample.
        slope: f64,
    },
    /// First-order Gauss-Markov: AR(1) with φ = exp(−1/Tc), stationary variance s².
    GaussMarkov {
        /// Tc, samples.
        correlation_samples: f64,
        /// s², unit².
        variance: f64,
    },
}

impl Term {
    /// The theoretical Haar wavelet variance at scale `tau` samples.
    pub fn wavelet_variance(&self, tau: f64) -> f64 {
        match *self {
            Term::White { variance } => theory::white(variance, tau),
            Term::Quantisation { variance } => theory::quantisation(variance, tau),
            Term::RandomWalk { variance } => theory::random_walk(variance, tau),
            Term::Drift { slope } => theory::drift(slope, tau),
            Term::GaussMarkov {
                correlation_samples,
                variance,
            } => theory::gauss_markov(correlation_samples, variance, tau),
        }
    }

    /// The unconstrained coordinates the optimiser moves: logarithms of the variances (of ω²
    /// for the drift) and of Tc − 1 sample. A Gauss-Markov process whose Tc is below one
    /// sample interval is white noise at every scale the data have, so it would share the
    /// white noise with the composite's WN term (seen: Tc = 0.2 samples took 95 % of an
    /// accelerometer's white noise); Tc is kept above one sample.
    pub(super) fn coordinates(&self) -> Vec<f64> {
        match *self {
            Term::White { variance }
            | Term::Quantisation { variance }
            | Term::RandomWalk { variance } => vec![variance.ln()],
            Term::Drift { slope } => vec![(slope * slope).ln()],
            Term::GaussMarkov {
                correlation_samples,
                variance,
            } => vec![(correlation_samples - 1.0).max(1e-9).ln(), variance.ln()],
        }
    }

    /// The same process with the coordinates `c` (as many as [`Term::coordinates`] returns).
    pub(super) fn with_coordinates(&self, c: &[f64]) -> Term {
        match self {
            Term::White { .. } => Term::White {
                variance: c[0].exp(),
            },
            Term::Quantisation { .. } => Term::Quantisation {
                variance: c[0].exp(),
            },
            Term::RandomWalk { .. } => Term::RandomWalk {
                variance: c[0].exp(),
            },
            Term::Drift { .. } => Term::Drift {
                slope: (c[0] / 2.0).exp(),
            },
            Term::GaussMarkov { .. } => Term::GaussMarkov {
                correlation_samples: 1.0 + c[0].exp(),
                variance: c[1].exp(),
            },
        }
    }

    /// Number of coordinates.
    pub(super) fn n_coordinates(&self) -> usize {
        match self {
            Term::GaussMarkov { .. } => 2,
            _ => 1,
        }
    }

    /// The physical parameters of this process for sampling interval `dt_s`, in the order of
    /// its coordinates (Tc before σ); `gm_index` numbers the Gauss-Markov processes from 1.
    pub fn physical(&self, dt_s: f64, gm_index: usize) -> Vec<PhysicalParameter> {
        let p = |kind, value| PhysicalParameter { kind, value };
        match *self {
            Term::White { variance } => {
                vec![p(Parameter::WhiteNoiseDensity, (variance * dt_s).sqrt())]
            }
            Term::Quantisation { variance } => {
                vec![p(Parameter::Quantisation, variance.sqrt() * dt_s)]
            }
            Term::RandomWalk { variance } => {
                vec![p(Parameter::RandomWalk, (variance / dt_s).sqrt())]
            }
            Term::Drift { slope } => vec![p(Parameter::DriftRate, slope.abs() / dt_s)],
            Term::GaussMarkov {
                correlation_samples,
                variance,
            } => vec![
                p(
                    Parameter::CorrelationTime(gm_index),
                    correlation_samples * dt_s,
                ),
                p(Parameter::GaussMarkovSigma(gm_index), variance.sqrt()),
            ],
        }
    }
}

/// What a physical parameter is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Parameter {
    /// White-noise density N = σ √dt: unit·√s = unit/√Hz (ARW, VRW).
    WhiteNoiseDensity,
    /// Quantisation coefficient Q dt: unit·s (IEEE 952's Q, AVAR = 3Q²/τ²).
    Quantisation,
    /// Random-walk coefficient K = γ/√dt: unit/√s = unit·√Hz (IEEE 952's K, AVAR ≈ K² τ/3).
    RandomWalk,
    /// Drift rate |ω|/dt: unit/s.
    DriftRate,
    /// Correlation time of the k-th Gauss-Markov process (k from 1, shortest first), s.
    CorrelationTime(usize),
    /// Standard deviation of the k-th Gauss-Markov process, unit.
    GaussMarkovSigma(usize),
}

impl Parameter {
    /// A snake_case name with the unit as a suffix, the unit of the data written `unit`.
    pub fn name(&self) -> String {
        match self {
            Parameter::WhiteNoiseDensity => "white_noise_density_unit_sqrt_s".into(),
            Parameter::Quantisation => "quantisation_unit_s".into(),
            Parameter::RandomWalk => "random_walk_unit_per_sqrt_s".into(),
            Parameter::DriftRate => "drift_rate_unit_per_s".into(),
            Parameter::CorrelationTime(k) => format!("gm{k}_correlation_time_s"),
            Parameter::GaussMarkovSigma(k) => format!("gm{k}_sigma_unit"),
        }
    }
}

/// A physical parameter and its value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhysicalParameter {
    /// Which parameter.
    pub kind: Parameter,
    /// Its value in the unit the kind names.
    pub value: f64,
}

/// The sum of `terms`' wavelet variances at scale `tau` samples.
pub fn composite_wavelet_variance(terms: &[Term], tau: f64) -> f64 {
    terms.iter().map(|t| t.wavelet_variance(tau)).sum()
}

/// [`composite_wavelet_variance`] at every scale of `taus`, each term's scale-free factors
/// computed once (the same values, bit for bit: the same arithmetic, summed in the same order).
pub fn composite_wavelet_variances(terms: &[Term], taus: &[f64]) -> Vec<f64> {
    let each: Vec<Vec<f64>> = terms
        .iter()
        .map(|t| term_wavelet_variances(t, taus))
        .collect();
    sum_over_terms(&each, taus.len())
}

/// One term's wavelet variance at every scale of `taus`, its scale-free factors computed once:
/// the values [`Term::wavelet_variance`] gives.
pub fn term_wavelet_variances(term: &Term, taus: &[f64]) -> Vec<f64> {
    match *term {
        Term::GaussMarkov {
            correlation_samples,
            variance,
        } => (gauss_markov_factors(correlation_samples, taus).iter())
            .map(|f| f.at(variance))
            .collect(),
        _ => taus.iter().map(|&tau| term.wavelet_variance(tau)).collect(),
    }
}

/// The Gauss-Markov curve of correlation time `correlation_samples` at every scale of `taus`,
/// as the factors any variance takes ([`theory::ScaleFactors`]).
pub fn gauss_markov_factors(correlation_samples: f64, taus: &[f64]) -> Vec<theory::ScaleFactors> {
    let curve = theory::GaussMarkovCurve::new(correlation_samples);
    taus.iter().map(|&tau| curve.factors(tau)).collect()
}

/// Σ over terms of their wavelet variances (`each[term][scale]`), term by term in order at each
/// scale, as [`composite_wavelet_variance`] sums.
pub fn sum_over_terms(each: &[Vec<f64>], n_scales: usize) -> Vec<f64> {
    (0..n_scales)
        .map(|j| each.iter().map(|term| term[j]).sum())
        .collect()
}

/// The physical parameters of a composite, Gauss-Markov processes numbered from 1 in order.
pub fn physical_parameters(terms: &[Term], dt_s: f64) -> Vec<PhysicalParameter> {
    let mut gm = 0;
    terms
        .iter()
        .flat_map(|t| {
            if matches!(t, Term::GaussMarkov { .. }) {
                gm += 1;
            }
            t.physical(dt_s, gm)
        })
        .collect()
}

/// Composites from physical values: white-noise density (unit/√Hz) etc.; the inverse of
/// [`Term::physical`], for simulations and tests.
impl Term {
    /// White noise of density `density` (unit·√s) sampled every `dt_s`.
    pub fn white_from_density(density: f64, dt_s: f64) -> Term {
        Term::White {
            variance: density * density / dt_s,
        }
    }

    /// A random walk of coefficient `k` (unit/√s) sampled every `dt_s`.
    pub fn random_walk_from_k(k: f64, dt_s: f64) -> Term {
        Term::RandomWalk {
            variance: k * k * dt_s,
        }
    }

    /// Quantisation noise of coefficient `q` (unit·s) sampled every `dt_s`.
    pub fn quantisation_from_q(q: f64, dt_s: f64) -> Term {
        Term::Quantisation {
            variance: (q / dt_s).powi(2),
        }
    }

    /// A Gauss-Markov process of correlation time `tc_s` and standard deviation `sigma`.
    pub fn gauss_markov_from(tc_s: f64, sigma: f64, dt_s: f64) -> Term {
        Term::GaussMarkov {
            correlation_samples: tc_s / dt_s,
            variance: sigma * sigma,
        }
    }
}

impl Term {
    /// The theoretical overlapping Allan variance at averaging factor `m` (τ = m dt): twice the
    /// Haar wavelet variance at scale 2m, σ²_A(m) = 2 ν²(2m), unit².
    pub fn allan_variance(&self, m: f64) -> f64 {
        2.0 * self.wavelet_variance(2.0 * m)
    }

    /// A short label of the process (`WN`, `QN`, `RW`, `DR`, `GM`).
    pub fn label(&self) -> &'static str {
        match self {
            Term::White { .. } => "WN",
            Term::Quantisation { .. } => "QN",
            Term::RandomWalk { .. } => "RW",
            Term::Drift { .. } => "DR",
            Term::GaussMarkov { .. } => "GM",
        }
    }
}

/// The processes of a composite from its physical parameters by name ([`Parameter::name`],
/// as the bank stores them), sampled every `dt_s`: the inverse of [`physical_parameters`],
/// Gauss-Markov processes in the order of their index. `None` when a name is not a
/// parameter, or a Gauss-Markov process lacks its correlation time or its σ.
pub fn terms_from_parameters(
    parameters: &std::collections::BTreeMap<String, f64>,
    dt_s: f64,
) -> Option<Vec<Term>> {
    let mut terms = Vec::new();
    let mut gm: std::collections::BTreeMap<usize, (Option<f64>, Option<f64>)> = Default::default();
    for (name, &value) in parameters {
        match name.as_str() {
            "white_noise_density_unit_sqrt_s" => terms.push(Term::white_from_density(value, dt_s)),
            "quantisation_unit_s" => terms.push(Term::quantisation_from_q(value, dt_s)),
            "random_walk_unit_per_sqrt_s" => terms.push(Term::random_walk_from_k(value, dt_s)),
            "drift_rate_unit_per_s" => terms.push(Term::Drift {
                slope: value * dt_s,
            }),
            _ => {
                let (index, part) = gauss_markov_part(name)?;
                let slot = gm.entry(index).or_default();
                match part {
                    GmPart::CorrelationTime => slot.0 = Some(value),
                    GmPart::Sigma => slot.1 = Some(value),
                }
            }
        }
    }
    for (tc_s, sigma) in gm.values() {
        terms.push(Term::gauss_markov_from((*tc_s)?, (*sigma)?, dt_s));
    }
    Some(terms)
}

enum GmPart {
    CorrelationTime,
    Sigma,
}

/// (k, which) of `gm{k}_correlation_time_s` or `gm{k}_sigma_unit`.
fn gauss_markov_part(name: &str) -> Option<(usize, GmPart)> {
    let rest = name.strip_prefix("gm")?;
    let (index, part) = rest.split_once('_')?;
    let part = match part {
        "correlation_time_s" => GmPart::CorrelationTime,
        "sigma_unit" => GmPart::Sigma,
        _ => return None,
    };
    Some((index.parse().ok()?, part))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wavelet_variances_at_all_scales_are_the_per_scale_sums_bit_for_bit() {
        let terms = [
            Term::White { variance: 2.5e-5 },
            Term::GaussMarkov {
                correlation_samples: 0.6,
                variance: 1e-7,
            },
            Term::GaussMarkov {
                correlation_samples: 37_000.0,
                variance: 3e-9,
            },
            Term::Quantisation { variance: 1e-10 },
            Term::RandomWalk { variance: 1e-14 },
            Term::Drift { slope: 2e-9 },
        ];
        let taus: Vec<f64> = (1..=22).map(|j| f64::from(1_u32 << j)).collect();
        let all = composite_wavelet_variances(&terms, &taus);
        for (&tau, value) in taus.iter().zip(all) {
            assert_eq!(
                value.to_bits(),
                composite_wavelet_variance(&terms, tau).to_bits(),
                "tau {tau}"
            );
        }
    }

    // IEEE Std 952's closed forms: white noise σ²_A = N²/τ exactly; a random walk
    // σ²_A = K²τ/3 as τ grows (the discrete form is K²τ/3 · (1 + 1/(2m²))).
    #[test]
    fn allan_variance_follows_ieee_952() {
        let dt = 0.01;
        let white = Term::white_from_density(2e-3, dt);
        let walk = Term::random_walk_from_k(5e-5, dt);
        for m in [1.0, 8.0, 1024.0] {
            let tau = m * dt;
            assert!((white.allan_variance(m) / (4e-6 / tau) - 1.0).abs() < 1e-13);
            let continuous = 25e-10 * tau / 3.0;
            let discrete = continuous * (1.0 + 1.0 / (2.0 * m * m));
            assert!((walk.allan_variance(m) / discrete - 1.0).abs() < 1e-13);
        }
    }

    // The bank's parameters by name give back the processes they were written from.
    #[test]
    fn terms_from_parameters_inverts_physical_parameters() {
        let dt = 0.005;
        let terms = vec![
            Term::white_from_density(2e-3, dt),
            Term::quantisation_from_q(1e-6, dt),
            Term::random_walk_from_k(5e-5, dt),
            Term::Drift { slope: 3e-9 },
            Term::gauss_markov_from(0.02, 0.01, dt),
            Term::gauss_markov_from(150.0, 2e-4, dt),
        ];
        let named = physical_parameters(&terms, dt)
            .iter()
            .map(|p| (p.kind.name(), p.value))
            .collect();
        let back = terms_from_parameters(&named, dt).unwrap();
        assert_eq!(back.len(), terms.len());
        for tau in [2.0, 64.0, 65536.0] {
            let (a, b) = (
                composite_wavelet_variance(&terms, tau),
                composite_wavelet_variance(&back, tau),
            );
            assert!((a / b - 1.0).abs() < 1e-12, "scale {tau}");
        }
        let mut broken = named.clone();
        broken.remove("gm2_sigma_unit");
        assert_eq!(terms_from_parameters(&broken, dt), None);
        broken.insert("gm2_colour".into(), 1.0);
        assert_eq!(terms_from_parameters(&broken, dt), None);
    }
}
