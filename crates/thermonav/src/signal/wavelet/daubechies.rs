//! Daubechies' extremal-phase wavelets dbN (N vanishing moments, 2N taps), computed from their
//! definition.
//!
//! Daubechies (1988), "Orthonormal bases of compactly supported wavelets", Comm. Pure Appl.
//! Math. 41(7), 909-996; *Ten Lectures on Wavelets* (1992), §6.1: the scaling filter is
//! H(z) = √2 ((1 + z⁻¹)/2)^N Q(z⁻¹) with |Q(e^{iω})|² = P(sin²(ω/2)),
//! P(y) = Σ_{k<N} C(N−1+k, k) y^k. Each root y_i of P gives through y = (2 − z − z⁻¹)/4 a pair
//! z_i, 1/z_i; the extremal-phase choice (the one tabulated by Daubechies and used by
//! PyWavelets and MATLAB as dbN) keeps the root inside the unit circle, so
//! Q(z⁻¹) ∝ Π_i (1 − z_i z⁻¹), and the coefficients are scaled to Σ h = √2.
//!
//! In `f64` the factorisation keeps 14-15 digits up to db10 (checked against PyWavelets'
//! tables to 1e-14 in the tests); it loses them beyond (db13: 1.5e-14, db20: 6e-13, measured),
//! which is why the family stops at [`Daubechies::MAX_ORDER`].

use crate::signal::SignalError;
use nalgebra::Complex;
use std::fmt;
use std::str::FromStr;

/// A Daubechies wavelet dbN: N vanishing moments, 2N taps; db1 is the Haar wavelet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Daubechies {
    order: usize,
}

/// The four filters of an orthogonal wavelet, in PyWavelets' order and orientation
/// (`Wavelet.filter_bank`): analysis low and high pass, synthesis low and high pass.
#[derive(Debug, Clone, PartialEq)]
pub struct FilterBank {
    /// Analysis (decomposition) low pass: the scaling filter reversed.
    pub dec_lo: Vec<f64>,
    /// Analysis high pass: dec_hi_k = (−1)^{k+1} h_k.
    pub dec_hi: Vec<f64>,
    /// Synthesis (reconstruction) low pass: the scaling filter h, Σ h = √2.
    pub rec_lo: Vec<f64>,
    /// Synthesis high pass: rec_hi_k = (−1)^k h_{2N−1−k}.
    pub rec_hi: Vec<f64>,
}

impl Daubechies {
    /// The highest order offered (see the module documentation).
    pub const MAX_ORDER: usize = 10;

    /// db4, 8 taps.
    pub const DB4: Self = Self { order: 4 };

    /// dbN for N in 1..=[`Self::MAX_ORDER`].
    ///
    /// # Errors
    /// [`SignalError::Spec`] for another order.
    pub fn new(order: usize) -> Result<Self, SignalError> {
        if (1..=Self::MAX_ORDER).contains(&order) {
            Ok(Self { order })
        } else {
            Err(SignalError::Spec {
                message: format!(
                    "Daubechies order {order}: expected 1..={} (db1..db{})",
                    Self::MAX_ORDER,
                    Self::MAX_ORDER
                ),
            })
        }
    }

    /// N, the number of vanishing moments.
    pub fn order(self) -> usize {
        self.order
    }

    /// Number of taps, 2N.
    pub fn filter_len(self) -> usize {
        2 * self.order
    }

    /// The filters of this wavelet.
    pub fn filter_bank(self) -> FilterBank {
        FilterBank::from_scaling_filter(scaling_filter(self.order))
    }
}

impl FilterBank {
    /// The quadrature-mirror bank of an orthogonal scaling filter `h` (even length).
    pub fn from_scaling_filter(h: Vec<f64>) -> Self {
        let f = h.len();
        let sign = |k: usize| if k % 2 == 0 { 1.0 } else { -1.0 };
        Self {
            dec_lo: h.iter().rev().copied().collect(),
            dec_hi: (0..f).map(|k| -sign(k) * h[k]).collect(),
            rec_hi: (0..f).map(|k| sign(k) * h[f - 1 - k]).collect(),
            rec_lo: h,
        }
    }

    /// Number of taps of each filter.
    pub fn filter_len(&self) -> usize {
        self.rec_lo.len()
    }
}

impl fmt::Display for Daubechies {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "db{}", self.order)
    }
}

impl FromStr for Daubechies {
    type Err = SignalError;

    /// Parses `dbN` (as PyWavelets names them; `haar` is db1).
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let lower = text.trim().to_ascii_lowercase();
        if lower == "haar" {
            return Self::new(1);
        }
        let order = lower.strip_prefix("db").and_then(|n| n.parse().ok());
        order.map_or_else(
            || {
                Err(SignalError::Spec {
                    message: format!(
                        "wavelet {text:?}: expected a Daubechies wavelet db1..db{}",
                        Self::MAX_ORDER
                    ),
                })
            },
            Self::new,
        )
    }
}

/// The scaling filter h of dbN (Σ h = √2), ascending powers of z⁻¹.
fn scaling_filter(order: usize) -> Vec<f64> {
    let mut polynomial = vec![Complex::new(1.0, 0.0)];
    for _ in 0..order {
        polynomial = multiply_by_linear(&polynomial, Complex::new(1.0, 0.0));
    }
    for y in polynomial_roots(&daubechies_polynomial(order)) {
        polynomial = multiply_by_linear(&polynomial, -inner_root(y));
    }
    let h: Vec<f64> = polynomial.iter().map(|c| c.re).collect();
    let scale = std::f64::consts::SQRT_2 / h.iter().sum::<f64>();
    h.iter().map(|v| v * scale).collect()
}

/// P(y) = Σ_{k<N} C(N−1+k, k) y^k, ascending powers.
fn daubechies_polynomial(order: usize) -> Vec<f64> {
    (0..order).map(|k| binomial(order - 1 + k, k)).collect()
}

/// C(n, k) as a float (exact for the small n here).
fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
}

/// The root inside the unit circle of z + 1/z = 2 − 4y (the other is its inverse).
fn inner_root(y: Complex<f64>) -> Complex<f64> {
    let b = Complex::new(2.0, 0.0) - y * 4.0;
    let s = (b * b - 4.0).sqrt();
    let outer = if (b + s).norm() >= (b - s).norm() {
        (b + s) / 2.0
    } else {
        (b - s) / 2.0
    };
    outer.inv()
}

/// p(z) (z − c)·, coefficients ascending in the variable that multiplies: (1 + c w) p(w) for
/// w = z⁻¹, i.e. p convolved with [1, c].
fn multiply_by_linear(p: &[Complex<f64>], c: Complex<f64>) -> Vec<Complex<f64>> {
    let mut out = vec![Complex::new(0.0, 0.0); p.len() + 1];
    for (i, &v) in p.iter().enumerate() {
        out[i] += v;
        out[i + 1] += v * c;
    }
    out
}

/// The roots of a real polynomial (ascending coefficients, non-zero leading one) by the
/// Durand-Kerner iteration, each then polished by Newton's method on the polynomial itself.
fn polynomial_roots(coefficients: &[f64]) -> Vec<Complex<f64>> {
    let degree = coefficients.len().saturating_sub(1);
    let lead = coefficients[degree];
    let monic: Vec<f64> = coefficients.iter().map(|c| c / lead).collect();
    let seed = Complex::new(0.4, 0.9);
    let mut roots: Vec<Complex<f64>> = (0..degree).map(|k| seed.powu(k as u32)).collect();
    for _ in 0..500 {
        let change = durand_kerner_sweep(&monic, &mut roots);
        if change < 1e-15 {
            break;
        }
    }
    roots.iter().map(|&r| newton_polish(&monic, r)).collect()
}

/// One Durand-Kerner update of every root; returns the largest change.
fn durand_kerner_sweep(monic: &[f64], roots: &mut [Complex<f64>]) -> f64 {
    let mut change: f64 = 0.0;
    for i in 0..roots.len() {
        let others = (0..roots.len())
            .filter(|&j| j != i)
            .fold(Complex::new(1.0, 0.0), |p, j| p * (roots[i] - roots[j]));
        let step = evaluate(monic, roots[i]).0 / others;
        roots[i] -= step;
        change = change.max(step.norm() / roots[i].norm().max(1.0));
    }
    change
}

/// Three Newton steps from `root`.
fn newton_polish(p: &[f64], mut root: Complex<f64>) -> Complex<f64> {
    for _ in 0..3 {
        let (value, slope) = evaluate(p, root);
        if slope.norm() > 0.0 {
            root -= value / slope;
        }
    }
    root
}

/// p(z) and p'(z) by Horner's rule (ascending coefficients).
fn evaluate(p: &[f64], z: Complex<f64>) -> (Complex<f64>, Complex<f64>) {
    let zero = Complex::new(0.0, 0.0);
    p.iter().rev().fold((zero, zero), |(value, slope), &c| {
        (value * z + c, slope * z + value)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn db2_has_the_closed_form_coefficients() {
        // Daubechies (1988): h = (1 + √3, 3 + √3, 3 − √3, 1 − √3) / (4√2).
        let s3 = 3f64.sqrt();
        let expected = [1.0 + s3, 3.0 + s3, 3.0 - s3, 1.0 - s3].map(|v| v / (4.0 * 2f64.sqrt()));
        let h = Daubechies::new(2).unwrap().filter_bank().rec_lo;
        for (a, b) in h.iter().zip(expected) {
            assert!((a - b).abs() < 1e-15, "{a} vs {b}");
        }
    }

    #[test]
    fn every_order_is_orthonormal_with_n_vanishing_moments() {
        for n in 1..=Daubechies::MAX_ORDER {
            let h = Daubechies::new(n).unwrap().filter_bank().rec_lo;
            for m in 0..n {
                let s: f64 = (0..h.len() - 2 * m).map(|i| h[i] * h[i + 2 * m]).sum();
                let want = if m == 0 { 1.0 } else { 0.0 };
                assert!((s - want).abs() < 1e-14, "db{n} shift {m}: {s}");
            }
            for p in 0..n as i32 {
                let moment: f64 = h
                    .iter()
                    .enumerate()
                    .map(|(k, v)| if k % 2 == 0 { 1.0 } else { -1.0 } * (k as f64).powi(p) * v)
                    .sum();
                assert!(
                    moment.abs() < 1e-9 * (h.len() as f64).powi(p),
                    "db{n} moment {p}"
                );
            }
        }
    }

    #[test]
    fn names_parse_and_bad_orders_are_refused() {
        assert_eq!("db4".parse::<Daubechies>().unwrap().order(), 4);
        assert_eq!("haar".parse::<Daubechies>().unwrap().order(), 1);
        assert_eq!(Daubechies::new(7).unwrap().to_string(), "db7");
        for bad in ["db0", "db11", "sym4", "", "db"] {
            assert!(bad.parse::<Daubechies>().is_err(), "{bad}");
        }
    }
}
