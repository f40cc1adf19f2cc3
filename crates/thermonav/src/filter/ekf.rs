//! Extended Kalman filter steps: covariance propagation and the Joseph-form update
//! P⁺ = (I − KH) P (I − KH)ᵀ + K R Kᵀ, which keeps P symmetric positive semi-definite for any
//! gain (Bucy & Joseph 1968; Groves 2013 §3.2.2).

use super::ukf::{Innovation, check_finite};
use super::{FilterError, symmetrize};
use nalgebra::{SMatrix, SVector};

/// P ← F P Fᵀ + Q.
pub fn propagate_covariance<const N: usize>(
    p: &SMatrix<f64, N, N>,
    f: &SMatrix<f64, N, N>,
    q: &SMatrix<f64, N, N>,
) -> SMatrix<f64, N, N> {
    symmetrize(&(f * p * f.transpose() + q))
}

/// The linearised update of (x, P) with residual `residual` = z − h(x), Jacobian `h`, noise `r`.
///
/// # Errors
/// [`FilterError`] when S = H P Hᵀ + R is singular or the result not finite.
pub fn joseph_update<const N: usize, const M: usize>(
    x: &mut SVector<f64, N>,
    p: &mut SMatrix<f64, N, N>,
    residual: &SVector<f64, M>,
    h: &SMatrix<f64, M, N>,
    r: &SMatrix<f64, M, M>,
) -> Result<Innovation<M>, FilterError> {
    let s = symmetrize(&(h * *p * h.transpose() + r));
    let s_inv = s.try_inverse().ok_or(FilterError::SingularInnovation)?;
    let gain = *p * h.transpose() * s_inv;
    let i_kh = SMatrix::<f64, N, N>::identity() - gain * h;
    let new_x = *x + gain * residual;
    let new_p = symmetrize(&(i_kh * *p * i_kh.transpose() + gain * r * gain.transpose()));
    check_finite(&new_x, &new_p)?;
    (*x, *p) = (new_x, new_p);
    let nis = (residual.transpose() * s_inv * residual)[(0, 0)];
    Ok(Innovation {
        residual: *residual,
        covariance: s,
        nis,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::sigma_points::SigmaPointScheme;
    use crate::filter::ukf::Ukf;
    use nalgebra::{Matrix2, Matrix2x3, Matrix3, Vector2, Vector3};

    // For a linear model the unscented transform is exact, so the UKF and the Joseph-form EKF
    // must agree to rounding (1e-12), and with the optimal gain Joseph equals (I − KH)P.
    #[test]
    fn joseph_update_equals_the_ukf_on_a_linear_model() {
        let x0 = Vector3::new(1.0, -2.0, 0.5);
        let p0 = Matrix3::new(2.0, 0.3, 0.1, 0.3, 1.0, -0.2, 0.1, -0.2, 0.5);
        let f = Matrix3::new(1.0, 0.1, 0.0, 0.0, 1.0, 0.1, 0.0, 0.0, 1.0);
        let q = Matrix3::from_diagonal(&Vector3::new(0.01, 0.02, 0.03));
        let h = Matrix2x3::new(1.0, 0.0, 0.5, 0.0, 1.0, -1.0);
        let r = Matrix2::new(0.2, 0.05, 0.05, 0.3);
        let z = Vector2::new(0.7, -1.1);

        let (mut x, mut p) = (f * x0, propagate_covariance(&p0, &f, &q));
        let residual = z - h * x;
        let innovation = joseph_update(&mut x, &mut p, &residual, &h, &r).unwrap();

        let scheme = SigmaPointScheme::MerweScaled {
            alpha: 0.5,
            beta: 2.0,
            kappa: 0.0,
        };
        let mut ukf = Ukf::new(x0, p0, scheme);
        ukf.predict(|s| f * s, &q).unwrap();
        let ukf_innovation = ukf.update(&z, |s| h * s, &r).unwrap();

        assert!((x - ukf.x).amax() < 1e-12 && (p - ukf.p).amax() < 1e-12);
        assert!((innovation.nis - ukf_innovation.nis).abs() < 1e-12);
        let p_pred = propagate_covariance(&p0, &f, &q);
        let k = p_pred * h.transpose() * innovation.covariance.try_inverse().unwrap();
        let simple = (Matrix3::identity() - k * h) * p_pred;
        assert!((p - simple).amax() < 1e-12);
    }
}
