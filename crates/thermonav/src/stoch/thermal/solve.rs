//! The numerical kernel shared by both thermal fits: a QR least-squares solve of a scaled
//! design matrix, its hat-matrix diagonal, the PRESS statistic and the change of polynomial
//! basis from the scaled variable z = (T − c)/s to d = T − T_ref.

use nalgebra::{DMatrix, DVector};

/// A column whose R diagonal is below this fraction of the largest one makes the design rank
/// deficient (the columns are scaled to |z| ≤ 1, so the diagonals are comparable).
const RANK_TOLERANCE: f64 = 1e-10;

/// An observation whose leverage h_ii is within this of 1 alone determines a parameter:
/// leaving it out makes the fit unidentifiable and its PRESS residual undefined.
const LEVERAGE_TOLERANCE: f64 = 1e-9;

/// The affine map from temperature to the scaled variable z = (T − c)/s ∈ [−1, 1] over the
/// data: c the middle of the range, s its half-width (1 °C when every temperature is equal).
#[derive(Debug, Clone, Copy)]
pub(super) struct Scaling {
    pub centre_c: f64,
    pub half_range_c: f64,
}

impl Scaling {
    /// The scaling of a non-empty set of finite temperatures.
    pub fn of(temperatures_c: impl Iterator<Item = f64>) -> Self {
        let (lo, hi) = range(temperatures_c);
        let half = (hi - lo) / 2.0;
        Scaling {
            centre_c: lo + half,
            half_range_c: if half > 0.0 { half } else { 1.0 },
        }
    }

    /// z for a temperature.
    pub fn z(&self, temperature_c: f64) -> f64 {
        (temperature_c - self.centre_c) / self.half_range_c
    }
}

/// Smallest and largest value.
pub(super) fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

/// Number of distinct values (exact equality).
pub(super) fn distinct(values: impl Iterator<Item = f64>) -> usize {
    let mut sorted: Vec<f64> = values.collect();
    sorted.sort_by(f64::total_cmp);
    sorted.dedup();
    sorted.len()
}

/// An ordinary least-squares solution in the design's own basis.
#[derive(Debug, Clone)]
pub(super) struct LeastSquares {
    /// θ̂ = R⁻¹ Qᵀ y.
    pub coefficients: DVector<f64>,
    /// (XᵀX)⁻¹ = R⁻¹ R⁻ᵀ.
    pub inverse_gram: DMatrix<f64>,
    /// h_ii = ‖row i of Q‖².
    pub hat_diagonal: Vec<f64>,
    /// e = y − X θ̂.
    pub residuals: Vec<f64>,
}

impl LeastSquares {
    /// Residual sum of squares.
    pub fn rss(&self) -> f64 {
        self.residuals.iter().map(|e| e * e).sum()
    }

    /// PRESS = Σ (e_i / (1 − h_ii))² over the observations `include` accepts; `None` when one
    /// of them has leverage 1 (its deletion residual is undefined).
    pub fn press(&self, include: impl Fn(usize) -> bool) -> Option<f64> {
        let mut sum = 0.0;
        for (i, (e, h)) in self.residuals.iter().zip(&self.hat_diagonal).enumerate() {
            if !include(i) {
                continue;
            }
            if 1.0 - h <= LEVERAGE_TOLERANCE {
                return None;
            }
            sum += (e / (1.0 - h)).powi(2);
        }
        Some(sum)
    }
}

/// Solves min ‖y − Xθ‖ by Householder QR; `None` when X has fewer rows than columns or is
/// numerically rank deficient.
pub(super) fn least_squares(x: &DMatrix<f64>, y: &DVector<f64>) -> Option<LeastSquares> {
    let (n, p) = x.shape();
    if n < p || p == 0 {
        return None;
    }
    let qr = x.clone().qr();
    let (q, r) = (qr.q(), qr.r());
    let largest = r.diagonal().amax();
    if largest == 0.0
        || r.diagonal()
            .iter()
            .any(|d| d.abs() <= RANK_TOLERANCE * largest)
    {
        return None;
    }
    let coefficients = r.solve_upper_triangular(&(q.transpose() * y))?;
    let r_inverse = r.solve_upper_triangular(&DMatrix::identity(p, p))?;
    let inverse_gram = &r_inverse * r_inverse.transpose();
    let hat_diagonal = (0..n).map(|i| q.row(i).norm_squared()).collect();
    let residuals = (y - x * &coefficients).iter().copied().collect();
    Some(LeastSquares {
        coefficients,
        inverse_gram,
        hat_diagonal,
        residuals,
    })
}

/// The matrix M with b = M a, where Σ a_k z^k = Σ b_m (T − T_ref)^m for z = (T − c)/s:
/// z^k = s^(−k) Σ_m C(k, m) d^m δ^(k−m) with d = T − T_ref and δ = T_ref − c, so
/// M[m][k] = C(k, m) δ^(k−m) s^(−k) for k ≥ m and 0 otherwise.
pub(super) fn to_reference_basis(scaling: Scaling, reference_c: f64, terms: usize) -> DMatrix<f64> {
    let delta = reference_c - scaling.centre_c;
    DMatrix::from_fn(terms, terms, |m, k| {
        if k < m {
            0.0
        } else {
            binomial(k, m) * delta.powi((k - m) as i32) / scaling.half_range_c.powi(k as i32)
        }
    })
}

/// Binomial coefficient C(k, m) for the small k of a cubic.
fn binomial(k: usize, m: usize) -> f64 {
    (0..m).fold(1.0, |c, i| c * (k - i) as f64 / (i + 1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_change_reproduces_the_polynomial() {
        let scaling = Scaling {
            centre_c: 20.0,
            half_range_c: 60.0,
        };
        let a = DVector::from_vec(vec![0.3, -1.2, 0.7, 2.5]);
        let b = to_reference_basis(scaling, 25.0, 4) * &a;
        for t in [-40.0, 0.0, 25.0, 80.0] {
            let z = scaling.z(t);
            let scaled: f64 = (0..4).map(|k| a[k] * z.powi(k as i32)).sum();
            let d: f64 = t - 25.0;
            let reference: f64 = (0..4).map(|m| b[m] * d.powi(m as i32)).sum();
            assert!(
                (scaled - reference).abs() < 1e-12,
                "{scaled} vs {reference}"
            );
        }
    }

    #[test]
    fn rank_deficient_design_is_refused() {
        let x = DMatrix::from_row_slice(3, 2, &[1.0, 2.0, 1.0, 2.0, 1.0, 2.0]);
        let y = DVector::from_vec(vec![1.0, 2.0, 3.0]);
        assert!(least_squares(&x, &y).is_none());
    }

    #[test]
    fn hat_diagonal_sums_to_the_number_of_parameters() {
        let x = DMatrix::from_fn(5, 2, |i, k| (i as f64 / 4.0 * 2.0 - 1.0).powi(k as i32));
        let y = DVector::from_vec(vec![0.1, 0.4, 0.2, 0.9, 1.1]);
        let ls = least_squares(&x, &y).unwrap();
        assert!((ls.hat_diagonal.iter().sum::<f64>() - 2.0).abs() < 1e-12);
    }
}
