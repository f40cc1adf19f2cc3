//! Which member of the Allan family a curve holds, the factors each one can be evaluated at, its
//! number of terms, and the curve type they share.

use serde::{Deserialize, Serialize};

/// A member of the Allan family of two-sample-like deviations, all computed from the phase
/// x = τ₀ Σ (y − ȳ) of rate samples y (allantools' `data_type='freq'`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DeviationKind {
    /// Overlapping Allan deviation (allantools `oadev`), unit of the data; the default.
    #[default]
    Adev,
    /// Modified Allan deviation (allantools `mdev`), unit of the data.
    Mdev,
    /// Hadamard deviation, non-overlapping (allantools `hdev`), unit of the data.
    Hdev,
    /// Overlapping Hadamard deviation (allantools `ohdev`), unit of the data.
    Ohdev,
    /// Time deviation τ·mdev/√3 (allantools `tdev`), unit of the data times seconds.
    Tdev,
    /// Total deviation, phase reflected at both ends (allantools `totdev`), unit of the data.
    Totdev,
}

impl DeviationKind {
    /// Every kind, in the order of `allan --kind`'s help.
    pub const ALL: [DeviationKind; 6] = [
        DeviationKind::Adev,
        DeviationKind::Mdev,
        DeviationKind::Hdev,
        DeviationKind::Ohdev,
        DeviationKind::Tdev,
        DeviationKind::Totdev,
    ];

    /// The short name (allantools' function name for every kind but `adev`, which is its
    /// `oadev`).
    pub fn name(self) -> &'static str {
        match self {
            DeviationKind::Adev => "adev",
            DeviationKind::Mdev => "mdev",
            DeviationKind::Hdev => "hdev",
            DeviationKind::Ohdev => "ohdev",
            DeviationKind::Tdev => "tdev",
            DeviationKind::Totdev => "totdev",
        }
    }

    /// The name in words, e.g. "modified Allan deviation".
    pub fn title(self) -> &'static str {
        match self {
            DeviationKind::Adev => "overlapping Allan deviation",
            DeviationKind::Mdev => "modified Allan deviation",
            DeviationKind::Hdev => "Hadamard deviation",
            DeviationKind::Ohdev => "overlapping Hadamard deviation",
            DeviationKind::Tdev => "time deviation",
            DeviationKind::Totdev => "total deviation",
        }
    }

    /// True when the deviation is in the data's unit times seconds (tdev), false when it is in
    /// the data's unit.
    pub fn is_time_scaled(self) -> bool {
        self == DeviationKind::Tdev
    }

    /// The number of terms averaged at factor m for n rate samples (n + 1 phase points), as
    /// allantools counts them: n − 2m + 1 (adev), n − 3m + 2 (mdev, tdev), n + 1 − 3m (ohdev),
    /// ⌈(n + 1 − 3m)/m⌉ (hdev, stride m), n − 1 (totdev). Saturates at 0.
    pub fn n_terms(self, n: usize, m: usize) -> usize {
        let phase_len = n + 1;
        match self {
            DeviationKind::Adev => phase_len.saturating_sub(2 * m),
            DeviationKind::Mdev | DeviationKind::Tdev => (phase_len + 1).saturating_sub(3 * m),
            DeviationKind::Ohdev => phase_len.saturating_sub(3 * m),
            DeviationKind::Hdev => phase_len.saturating_sub(3 * m).div_ceil(m.max(1)),
            DeviationKind::Totdev => n.saturating_sub(1),
        }
    }

    /// Whether factor m ≥ 1 can be evaluated on n rate samples: at least one term for adev
    /// (2m ≤ n, as before this family existed), at least two for the others (allantools drops
    /// single-term points): 3m ≤ n (mdev, tdev), 3m + 1 ≤ n (ohdev), 4m ≤ n (hdev), m ≤ n
    /// (totdev, whose reflected phase serves every m below the record length).
    pub fn fits(self, n: usize, m: usize) -> bool {
        let least = if self == DeviationKind::Adev { 1 } else { 2 };
        m >= 1 && m <= n && self.n_terms(n, m) >= least
    }
}

/// A name that is not a deviation kind.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown deviation kind `{0}` (expected adev, mdev, hdev, ohdev, tdev or totdev)")]
pub struct UnknownDeviationKind(pub String);

impl std::str::FromStr for DeviationKind {
    type Err = UnknownDeviationKind;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        DeviationKind::ALL
            .into_iter()
            .find(|kind| kind.name() == s)
            .ok_or_else(|| UnknownDeviationKind(s.to_string()))
    }
}

impl std::fmt::Display for DeviationKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A curve of one deviation kind.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DeviationCurve {
    /// Which deviation.
    pub kind: DeviationKind,
    /// Averaging times τ = m τ₀, s.
    pub tau_s: Vec<f64>,
    /// Averaging factors m.
    pub averaging_factor: Vec<usize>,
    /// The deviation: unit of the data, or unit of the data times seconds for tdev.
    pub deviation: Vec<f64>,
    /// Number of terms averaged ([`DeviationKind::n_terms`]).
    pub n_terms: Vec<usize>,
    /// Samples N.
    pub n_samples: usize,
    /// Sampling interval τ₀, s.
    pub tau0_s: f64,
}

impl DeviationCurve {
    /// The curve of `kind` with `deviation` at `factors` for `n` samples at `sample_rate_hz`.
    pub(super) fn new(
        kind: DeviationKind,
        factors: Vec<usize>,
        deviation: Vec<f64>,
        n: usize,
        sample_rate_hz: f64,
    ) -> Self {
        let tau0_s = 1.0 / sample_rate_hz;
        Self {
            kind,
            tau_s: factors.iter().map(|&m| m as f64 * tau0_s).collect(),
            n_terms: factors.iter().map(|&m| kind.n_terms(n, m)).collect(),
            averaging_factor: factors,
            deviation,
            n_samples: n,
            tau0_s,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_parse_back_to_their_kind() {
        for kind in DeviationKind::ALL {
            assert_eq!(kind.name().parse::<DeviationKind>(), Ok(kind));
        }
        assert!("oadev".parse::<DeviationKind>().is_err());
    }

    // Closed forms for n = 10 rate samples (11 phase points) at m = 3: 5 (adev), 3 (mdev),
    // ⌈2/3⌉ = 1 (hdev), 2 (ohdev), 3 (tdev), 9 (totdev).
    #[test]
    fn term_counts_at_n_10_m_3() {
        let counts: Vec<usize> = DeviationKind::ALL
            .iter()
            .map(|k| k.n_terms(10, 3))
            .collect();
        assert_eq!(counts, [5, 3, 1, 2, 3, 9]);
        assert!(!DeviationKind::Hdev.fits(10, 3) && DeviationKind::Ohdev.fits(10, 3));
        assert!(DeviationKind::Totdev.fits(10, 10) && !DeviationKind::Totdev.fits(10, 11));
    }
}
