//! Overlapping Allan deviation of rate data, its confidence intervals, and the IEEE Std 952
//! noise terms read off the curve.
//!
//! For a rate series y sampled at τ₀ with N samples, let S_i = Σ_{j<i} y_j (S₀ = 0, N + 1
//! values). The overlapping Allan variance at τ = m τ₀ (NIST SP 1065 eq. 14, written with the
//! phase x = τ₀ S) is
//!
//! σ²(τ) = Σ_{i=0}^{n−1} (S_{i+2m} − 2 S_{i+m} + S_i)² / (2 m² n),  n = N − 2m + 1 terms,
//!
//! which is allantools' `oadev(y, rate, data_type='freq')` and Stable32's "Overlapping Allan"
//! (the `#` column is n). The mean of y is removed first (the second difference cancels it
//! exactly; removing it keeps S small and the sums accurate). O(N) per τ, all τ in one blocked
//! sweep over S.
//!
//! The rest of the Allan family shares that phase and the τ grids ([`DeviationKind`],
//! [`deviation`]): the modified Allan deviation and the time deviation ([`modified_adev`],
//! [`time_deviation`]), the Hadamard deviations ([`hadamard_deviation`],
//! [`overlapping_hadamard_deviation`]) and the total deviation ([`total_deviation`]), each
//! equal to allantools 2024.6 with `data_type='freq'` (integration tests, 1e-9 relative).
//! Confidence limits and the IEEE 952 noise terms below are the overlapping Allan
//! deviation's only. The other kinds have none yet, on purpose: their limits need their own
//! equivalent degrees of freedom (Greenhall & Riley with d = 3 for the Hadamard variances, the
//! modified-variance case for mdev and tdev, NIST SP 1065 Table 7 for totdev; allantools has
//! all three) and a noise identification for their difference order, none of which is written
//! here; the Allan deviation's EDF in their place would give limits that are simply wrong.
//!
//! Confidence intervals follow Stable32 1.60: the noise type α at each τ by the lag-1
//! autocorrelation of the m-averages when at least 30 exist and by Barnes' B1 ratio (with R(n)
//! for phase noise) otherwise ([`identify_noise`]), Greenhall & Riley's equivalent degrees of
//! freedom ([`edf_overlapping_adev`]), and chi-square bounds, with either exact quantiles or
//! Stable32's own ([`ChiSquareQuantile`]).
//!
//! References: NIST SP 1065 (Riley 2008); Greenhall & Riley, "Uncertainty of stability
//! variances based on finite differences", PTTI 2003; Riley & Greenhall, "Power law noise
//! identification using the lag 1 autocorrelation", EFTF 2004.

mod confidence;
mod deviation;
mod edf;
mod family;
mod hadamard;
mod kind;
mod modified;
mod noise_id;
mod streaming;
mod total;

pub use confidence::{
    ChiSquareQuantile, CiSettings, DEFAULT_CONFIDENCE, ONE_SIGMA_CONFIDENCE, chi_square_quantile,
    confidence_intervals, confidence_intervals_with, interval_from_edf, intervals_for_noise,
};
pub use deviation::overlapping_adev;
pub use edf::edf_overlapping_adev;
pub use family::{channel_deviations, deviation};
pub use hadamard::{hadamard_deviation, overlapping_hadamard_deviation};
pub use kind::{DeviationCurve, DeviationKind, UnknownDeviationKind};
pub use modified::{modified_adev, time_deviation};
pub use noise_id::{
    NoiseIdMethod, NoiseIdentification, PowerLawNoise, identify_noise, identify_noise_at_factors,
};
pub use streaming::{StreamingAllan, StreamingAllanSettings};
pub use total::total_deviation;

use serde::Serialize;

/// Which averaging factors m to evaluate.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TauGrid {
    /// m = 1, 2, 4, … (allantools 'octave').
    Octave,
    /// m = 1, 2, 4, 10, 20, 40, … (allantools 'decade').
    Decade,
    /// About `per_decade` log-spaced m per decade (distinct integers).
    Dense {
        /// Points per decade.
        per_decade: usize,
    },
    /// These m.
    Explicit(Vec<usize>),
}

/// An Allan deviation curve.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AllanCurve {
    /// Averaging times τ = m τ₀, s.
    pub tau_s: Vec<f64>,
    /// Averaging factors m.
    pub averaging_factor: Vec<usize>,
    /// Overlapping Allan deviation, unit of the data.
    pub adev: Vec<f64>,
    /// Number of terms n = N − 2m + 1.
    pub n_terms: Vec<usize>,
    /// Samples N.
    pub n_samples: usize,
    /// Sampling interval τ₀, s.
    pub tau0_s: f64,
}

impl From<AllanCurve> for DeviationCurve {
    fn from(curve: AllanCurve) -> Self {
        Self {
            kind: DeviationKind::Adev,
            tau_s: curve.tau_s,
            averaging_factor: curve.averaging_factor,
            deviation: curve.adev,
            n_terms: curve.n_terms,
            n_samples: curve.n_samples,
            tau0_s: curve.tau0_s,
        }
    }
}

/// Why an Allan curve cannot be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AllanError {
    /// Too few samples.
    #[error("{samples} samples are too few for an Allan deviation (at least 3 are needed)")]
    TooShort {
        /// Samples given.
        samples: usize,
    },
    /// A NaN or infinity.
    #[error("sample {index} is not a finite number")]
    NonFinite {
        /// Its index.
        index: usize,
    },
    /// Bad sampling rate.
    #[error("sample rate {rate_hz} Hz must be finite and positive")]
    Rate {
        /// The value.
        rate_hz: f64,
    },
    /// No averaging factor fits the record.
    #[error("no averaging factor of the requested grid fits {samples} samples")]
    EmptyGrid {
        /// Samples given.
        samples: usize,
    },
    /// A confidence level (or quantile probability) outside (0, 1).
    #[error("confidence level must lie strictly between 0 and 1, got {0}")]
    InvalidConfidenceLevel(f64),
    /// Equivalent degrees of freedom that are not finite and positive.
    #[error("equivalent degrees of freedom must be finite and > 0, got {0}")]
    InvalidEdf(f64),
    /// A streaming pass needs a positive exact bound and stride.
    #[error(
        "streaming Allan settings need a positive exact bound and stride, got {exact_max_factor} and {stride}"
    )]
    StreamingSettings {
        /// The exact bound given.
        exact_max_factor: usize,
        /// The stride given.
        stride: usize,
    },
    /// A factor above a streaming pass's exact bound that its strided phase cannot serve.
    #[error(
        "averaging factor {factor} is above the streaming exact bound and not a multiple of the phase stride {stride} (use the octave or decade grid)"
    )]
    StreamingFactor {
        /// The factor.
        factor: usize,
        /// The stride.
        stride: usize,
    },
}

impl TauGrid {
    /// The averaging factors for N samples: those with at least one term (2m ≤ N), sorted,
    /// distinct.
    pub fn factors(&self, n: usize) -> Vec<usize> {
        self.factors_for(DeviationKind::Adev, n)
    }

    /// The averaging factors of this grid that `kind` can be evaluated at on N samples
    /// ([`DeviationKind::fits`]), sorted, distinct.
    pub fn factors_for(&self, kind: DeviationKind, n: usize) -> Vec<usize> {
        let mut m = self.candidates(n);
        m.retain(|&m| kind.fits(n, m));
        m.sort_unstable();
        m.dedup();
        m
    }

    /// The grid's factors before any is checked against the record length N.
    fn candidates(&self, n: usize) -> Vec<usize> {
        let phase_len = n + 1;
        match self {
            TauGrid::Octave => (0..=usize::BITS - phase_len.leading_zeros())
                .map(|k| 1usize << k)
                .collect(),
            TauGrid::Decade => {
                let decades = (phase_len as f64).log10().floor() as u32;
                (0..=decades)
                    .flat_map(|k| [1, 2, 4].map(|f| f * 10usize.pow(k)))
                    .collect()
            }
            TauGrid::Dense { per_decade } => {
                let per = (*per_decade).max(1) as f64;
                let top = (n as f64 / 2.0).log10();
                (0..=(top * per).ceil() as usize)
                    .map(|j| 10f64.powf(j as f64 / per).round() as usize)
                    .collect()
            }
            TauGrid::Explicit(list) => list.clone(),
        }
    }
}

/// Confidence limits of an Allan curve.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AllanIntervals {
    /// Confidence level p (e.g. 0.683).
    pub level: f64,
    /// Identified power-law noise exponent α per τ (2 white PM … −2 random-walk FM).
    pub alpha: Vec<i32>,
    /// Equivalent degrees of freedom per τ.
    pub edf: Vec<f64>,
    /// Lower limit of the deviation.
    pub low: Vec<f64>,
    /// Upper limit of the deviation.
    pub high: Vec<f64>,
}

/// Smallest number of m-averages for the lag-1 autocorrelation noise identification.
pub const MIN_AVERAGES_FOR_NOISE_ID: usize = 30;
