//! The discrete wavelet transform, one level ([`dwt`], [`idwt`]) and multilevel ([`wavedec`],
//! [`waverec`]), equal to PyWavelets' functions of the same names for the two extension modes
//! of [`ExtensionMode`].
//!
//! With F taps and a signal x of n samples:
//! - `symmetric`: x is extended by half-sample reflection (… x₁ x₀ | x₀ x₁ … x_{n−1} | x_{n−1}
//!   x_{n−2} …, repeated as often as a long filter needs), and a_k = Σ_j lo_j x_{2k+1−j} for
//!   k < ⌊(n + F − 1)/2⌋ (likewise d with the high pass). The inverse keeps the part of the
//!   up-sampled convolutions that needs no extension: 2m − F + 2 samples from m coefficients.
//! - `periodization`: an odd x gets its last sample repeated, the result is treated as periodic
//!   of period p, and a_k = Σ_j lo_j x_{(F/2 + 2k − j) mod p} for k < p/2. The transform is
//!   then orthogonal and the inverse is its transpose.
//!
//! As in PyWavelets, the reconstruction of an odd-length signal is one sample longer (the
//! extra sample is an artefact of the extension); [`Decomposition::signal_len`] says how many
//! to keep.

use super::daubechies::FilterBank;
use crate::signal::SignalError;

/// How the signal is extended beyond its ends (PyWavelets' mode names).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum ExtensionMode {
    /// Half-sample symmetric reflection, PyWavelets' default: no jump at the ends.
    #[default]
    Symmetric,
    /// Periodic, with exactly ⌈n/2⌉ coefficients per level: an orthogonal transform, but the
    /// ends of the record meet (a jump when they differ).
    Periodization,
}

impl ExtensionMode {
    /// PyWavelets' name of the mode.
    pub fn name(self) -> &'static str {
        match self {
            ExtensionMode::Symmetric => "symmetric",
            ExtensionMode::Periodization => "periodization",
        }
    }
}

/// The deepest level at which a coefficient still sees one whole filter, as PyWavelets'
/// `dwt_max_level`: ⌊log₂(n / (F − 1))⌋, 0 when n < F − 1 (and for filters shorter than 2).
pub fn max_level(samples: usize, filter_len: usize) -> usize {
    if filter_len < 2 || samples < filter_len - 1 {
        return 0;
    }
    let ratio = samples / (filter_len - 1);
    (usize::BITS - 1 - ratio.leading_zeros()) as usize
}

/// Coefficients per band of one level from `samples` inputs (PyWavelets' `dwt_coeff_len`).
pub fn coefficient_len(samples: usize, filter_len: usize, mode: ExtensionMode) -> usize {
    match mode {
        ExtensionMode::Symmetric => (samples + filter_len - 1) / 2,
        ExtensionMode::Periodization => samples.div_ceil(2),
    }
}

/// One level: the approximation and detail coefficients of `x` (empty for an empty `x`).
pub fn dwt(x: &[f64], bank: &FilterBank, mode: ExtensionMode) -> (Vec<f64>, Vec<f64>) {
    if x.is_empty() {
        return (Vec::new(), Vec::new());
    }
    match mode {
        ExtensionMode::Symmetric => (
            analyse_symmetric(x, &bank.dec_lo),
            analyse_symmetric(x, &bank.dec_hi),
        ),
        ExtensionMode::Periodization => {
            let padded = padded_to_even(x);
            (
                analyse_periodic(&padded, &bank.dec_lo),
                analyse_periodic(&padded, &bank.dec_hi),
            )
        }
    }
}

/// One level back: the signal from approximation `a` and detail `d` of equal length.
///
/// # Errors
/// [`SignalError::Spec`] when the lengths differ.
pub fn idwt(
    a: &[f64],
    d: &[f64],
    bank: &FilterBank,
    mode: ExtensionMode,
) -> Result<Vec<f64>, SignalError> {
    if a.len() != d.len() {
        return Err(SignalError::Spec {
            message: format!(
                "approximation ({}) and detail ({}) coefficients differ in length",
                a.len(),
                d.len()
            ),
        });
    }
    Ok(match mode {
        ExtensionMode::Symmetric => synthesise_valid(a, d, bank),
        ExtensionMode::Periodization => synthesise_periodic(a, d, bank),
    })
}

/// A multilevel decomposition: the approximation at the deepest level and the details of
/// every level, coarsest first (PyWavelets' list `[cA_L, cD_L, …, cD_1]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Decomposition {
    approximation: Vec<f64>,
    details: Vec<Vec<f64>>,
    mode: ExtensionMode,
    signal_len: usize,
}

impl Decomposition {
    /// A decomposition from its parts (details coarsest first), checked level by level as
    /// [`waverec`] will use them: an approximation as long as the next detail band, or one
    /// longer (PyWavelets then drops its last coefficient).
    ///
    /// # Errors
    /// [`SignalError::Spec`] for no detail band or inconsistent lengths.
    pub fn from_parts(
        approximation: Vec<f64>,
        details: Vec<Vec<f64>>,
        bank: &FilterBank,
        mode: ExtensionMode,
        signal_len: usize,
    ) -> Result<Self, SignalError> {
        let bad = |message: String| Err(SignalError::Spec { message });
        if details.is_empty() {
            return bad("a decomposition needs at least one detail band".into());
        }
        let mut a_len = approximation.len();
        for (i, d) in details.iter().enumerate() {
            if a_len != d.len() && a_len != d.len() + 1 {
                return bad(format!(
                    "detail band {i} has {} coefficients, the approximation {a_len}",
                    d.len()
                ));
            }
            a_len = reconstructed_len(d.len(), bank.filter_len(), mode);
        }
        Ok(Self {
            approximation,
            details,
            mode,
            signal_len,
        })
    }

    /// The approximation coefficients at the deepest level.
    pub fn approximation(&self) -> &[f64] {
        &self.approximation
    }

    /// The detail coefficients, coarsest level first.
    pub fn details(&self) -> &[Vec<f64>] {
        &self.details
    }

    /// The detail coefficients for changing in place, coarsest level first.
    pub fn details_mut(&mut self) -> impl Iterator<Item = &mut [f64]> {
        self.details.iter_mut().map(Vec::as_mut_slice)
    }

    /// The finest detail band (level 1).
    pub fn finest_details(&self) -> &[f64] {
        self.details.last().map_or(&[], Vec::as_slice)
    }

    /// Number of levels.
    pub fn levels(&self) -> usize {
        self.details.len()
    }

    /// The extension mode of the transform.
    pub fn mode(&self) -> ExtensionMode {
        self.mode
    }

    /// Length of the decomposed signal.
    pub fn signal_len(&self) -> usize {
        self.signal_len
    }
}

/// `level` levels of the transform of `x` (PyWavelets' `wavedec(x, wavelet, mode, level)`).
///
/// # Errors
/// [`SignalError::NonFinite`] for a NaN or infinite sample; [`SignalError::WaveletLevel`] for
/// a level of 0 or above [`max_level`] for this length and filter,
/// [`SignalError::WaveletTooShort`] when the length allows none.
pub fn wavedec(
    x: &[f64],
    bank: &FilterBank,
    mode: ExtensionMode,
    level: usize,
) -> Result<Decomposition, SignalError> {
    check_finite(x)?;
    check_level(level, x.len(), bank.filter_len())?;
    let mut approximation = x.to_vec();
    let mut details = Vec::with_capacity(level);
    for _ in 0..level {
        let (a, d) = dwt(&approximation, bank, mode);
        approximation = a;
        details.push(d);
    }
    details.reverse();
    Ok(Decomposition {
        approximation,
        details,
        mode,
        signal_len: x.len(),
    })
}

/// The signal back from its decomposition (PyWavelets' `waverec`): one sample longer than
/// [`Decomposition::signal_len`] for an odd length.
pub fn waverec(decomposition: &Decomposition, bank: &FilterBank) -> Vec<f64> {
    let mut a = decomposition.approximation.clone();
    for d in &decomposition.details {
        a.truncate(d.len());
        a = match decomposition.mode {
            ExtensionMode::Symmetric => synthesise_valid(&a, d, bank),
            ExtensionMode::Periodization => synthesise_periodic(&a, d, bank),
        };
    }
    a
}

/// [`SignalError::WaveletTooShort`] when no level is possible, else
/// [`SignalError::WaveletLevel`] unless 1 ≤ `level` ≤ [`max_level`].
pub fn check_level(level: usize, samples: usize, filter_len: usize) -> Result<(), SignalError> {
    let max = max_level(samples, filter_len);
    if (1..=max).contains(&level) {
        return Ok(());
    }
    if max == 0 {
        return Err(SignalError::WaveletTooShort {
            samples,
            needed: filter_len.saturating_sub(1).max(1),
            filter_len,
        });
    }
    Err(SignalError::WaveletLevel {
        level,
        max_level: max,
        samples,
        filter_len,
    })
}

/// [`SignalError::NonFinite`] at the first NaN or infinite sample.
fn check_finite(x: &[f64]) -> Result<(), SignalError> {
    match x.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(SignalError::NonFinite { index }),
        None => Ok(()),
    }
}

/// Samples one inverse level gives from `m` coefficients per band.
fn reconstructed_len(m: usize, filter_len: usize, mode: ExtensionMode) -> usize {
    match mode {
        ExtensionMode::Symmetric => (2 * m + 2).saturating_sub(filter_len),
        ExtensionMode::Periodization => 2 * m,
    }
}

/// Index into x of the half-sample symmetric extension, repeated with period 2n.
fn symmetric_index(i: isize, n: usize) -> usize {
    let m = i.rem_euclid(2 * n as isize) as usize;
    if m < n { m } else { 2 * n - 1 - m }
}

/// a_k = Σ_j f_j x_{2k+1−j}, x extended symmetrically.
fn analyse_symmetric(x: &[f64], filter: &[f64]) -> Vec<f64> {
    let (n, taps) = (x.len(), filter.len());
    (0..coefficient_len(n, taps, ExtensionMode::Symmetric))
        .map(|k| {
            let centre = (2 * k + 1) as isize;
            filter
                .iter()
                .enumerate()
                .map(|(j, f)| f * x[symmetric_index(centre - j as isize, n)])
                .sum()
        })
        .collect()
}

/// x with its last sample repeated when its length is odd.
fn padded_to_even(x: &[f64]) -> Vec<f64> {
    let mut padded = x.to_vec();
    if let Some(&last) = x.last().filter(|_| x.len() % 2 == 1) {
        padded.push(last);
    }
    padded
}

/// a_k = Σ_j f_j x_{(F/2 + 2k − j) mod p}, x of even length p.
fn analyse_periodic(x: &[f64], filter: &[f64]) -> Vec<f64> {
    let (p, half) = (x.len(), filter.len() / 2);
    (0..p / 2)
        .map(|k| {
            filter
                .iter()
                .enumerate()
                .map(|(j, f)| f * x[periodic_index(half + 2 * k, j, p)])
                .sum()
        })
        .collect()
}

/// (centre − j) mod p.
fn periodic_index(centre: usize, j: usize, p: usize) -> usize {
    (centre as isize - j as isize).rem_euclid(p as isize) as usize
}

/// The valid part of Σ_k a_k lo_{t−2k} + d_k hi_{t−2k}: t = o + F − 2 for o < 2m − F + 2.
fn synthesise_valid(a: &[f64], d: &[f64], bank: &FilterBank) -> Vec<f64> {
    let taps = bank.filter_len();
    (0..reconstructed_len(a.len(), taps, ExtensionMode::Symmetric))
        .map(|o| {
            let t = o + taps - 2;
            let first = (t + 1).saturating_sub(taps).div_ceil(2);
            (first..a.len().min(t / 2 + 1))
                .map(|k| a[k] * bank.rec_lo[t - 2 * k] + d[k] * bank.rec_hi[t - 2 * k])
                .sum()
        })
        .collect()
}

/// The transpose of the periodic analysis: each coefficient spread back over its taps.
fn synthesise_periodic(a: &[f64], d: &[f64], bank: &FilterBank) -> Vec<f64> {
    let (p, half) = (2 * a.len(), bank.filter_len() / 2);
    let mut out = vec![0.0; p];
    for (k, (ak, dk)) in a.iter().zip(d).enumerate() {
        for (j, (lo, hi)) in bank.dec_lo.iter().zip(&bank.dec_hi).enumerate() {
            out[periodic_index(half + 2 * k, j, p)] += lo * ak + hi * dk;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::signal::wavelet::daubechies::Daubechies;

    #[test]
    fn max_level_is_pywavelets_dwt_max_level() {
        // pywt.dwt_max_level(1000, 8) = 7, (7, 8) = 0, (6, 8) = 0, (14, 8) = 1, (1, 2) = 0.
        assert_eq!(max_level(1000, 8), 7);
        assert_eq!(max_level(7, 8), 0);
        assert_eq!(max_level(6, 8), 0);
        assert_eq!(max_level(14, 8), 1);
        assert_eq!(max_level(1, 2), 0);
        assert_eq!(max_level(0, 2), 0);
    }

    #[test]
    fn both_modes_reconstruct_the_signal() {
        let x: Vec<f64> = (0..37).map(|i| ((i * i) % 11) as f64 - 3.0).collect();
        for order in [1, 3, 6] {
            let bank = Daubechies::new(order).unwrap().filter_bank();
            for mode in [ExtensionMode::Symmetric, ExtensionMode::Periodization] {
                let level = max_level(x.len(), bank.filter_len());
                let back = waverec(&wavedec(&x, &bank, mode, level).unwrap(), &bank);
                assert_eq!(back.len(), x.len() + 1);
                for (a, b) in x.iter().zip(&back) {
                    assert!((a - b).abs() < 1e-12, "db{order} {mode:?}: {a} vs {b}");
                }
            }
        }
    }

    #[test]
    fn levels_beyond_the_maximum_and_bad_samples_are_refused() {
        let bank = Daubechies::new(4).unwrap().filter_bank();
        let x = vec![1.0; 20];
        assert!(matches!(
            wavedec(&x, &bank, ExtensionMode::Symmetric, 2),
            Err(SignalError::WaveletLevel { max_level: 1, .. })
        ));
        assert!(wavedec(&x, &bank, ExtensionMode::Symmetric, 0).is_err());
        assert!(matches!(
            wavedec(&[1.0; 6], &bank, ExtensionMode::Symmetric, 1),
            Err(SignalError::WaveletTooShort { needed: 7, .. })
        ));
        assert!(wavedec(&[], &bank, ExtensionMode::Symmetric, 1).is_err());
        let mut y = x.clone();
        y[3] = f64::NAN;
        assert_eq!(
            wavedec(&y, &bank, ExtensionMode::Symmetric, 1),
            Err(SignalError::NonFinite { index: 3 })
        );
    }
}
