//! Normal gravity of the WGS84 ellipsoid.
//!
//! On the ellipsoid, Somigliana's closed formula (NIMA TR8350.2 eq. 4-1):
//! γ(φ) = γ_e (1 + k sin²φ) / √(1 − e² sin²φ), k = (b γ_p)/(a γ_e) − 1.
//! Above it, the second-order free-air expansion (TR8350.2 eq. 4-3):
//! γ(φ, h) = γ(φ) [1 − 2/a (1 + f + m − 2 f sin²φ) h + 3 h²/a²], m = ω² a² b / GM.
//! Valid to ~1 µm/s² below 20 km; the deflection of the vertical is ignored (normal gravity
//! points along the ellipsoidal normal, down in NED).

use super::wgs84::{
    EARTH_RATE_RAD_S, ECCENTRICITY_SQ, FLATTENING, GM_M3_S2, GRAVITY_EQUATOR_M_S2,
    GRAVITY_POLE_M_S2, SEMI_MAJOR_AXIS_M, SEMI_MINOR_AXIS_M,
};

/// Magnitude of normal gravity on the ellipsoid at geodetic latitude φ, m/s² (Somigliana).
pub fn somigliana_m_s2(latitude_rad: f64) -> f64 {
    let k =
        SEMI_MINOR_AXIS_M * GRAVITY_POLE_M_S2 / (SEMI_MAJOR_AXIS_M * GRAVITY_EQUATOR_M_S2) - 1.0;
    let sin_sq = latitude_rad.sin().powi(2);
    GRAVITY_EQUATOR_M_S2 * (1.0 + k * sin_sq) / (1.0 - ECCENTRICITY_SQ * sin_sq).sqrt()
}

/// Magnitude of normal gravity at geodetic latitude φ and ellipsoidal height h, m/s².
pub fn normal_gravity_m_s2(latitude_rad: f64, height_m: f64) -> f64 {
    let a = SEMI_MAJOR_AXIS_M;
    let m = EARTH_RATE_RAD_S.powi(2) * a * a * SEMI_MINOR_AXIS_M / GM_M3_S2;
    let sin_sq = latitude_rad.sin().powi(2);
    let linear = 2.0 / a * (1.0 + FLATTENING + m - 2.0 * FLATTENING * sin_sq) * height_m;
    let quadratic = 3.0 * height_m * height_m / (a * a);
    somigliana_m_s2(latitude_rad) * (1.0 - linear + quadratic)
}

/// Normal gravity vector in NED, m/s²: (0, 0, γ(φ, h)).
pub fn gravity_ned(latitude_rad: f64, height_m: f64) -> [f64; 3] {
    [0.0, 0.0, normal_gravity_m_s2(latitude_rad, height_m)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::deg_to_rad;

    // Oracle: the defining values of the WGS84 normal gravity field at the equator and the pole,
    // and at 45° the closed formula written with the constants as TR8350.2 publishes them
    // (k = 0.00193185265241, e² = 0.00669437999013), not derived as in the code.
    // The code derives k from γ_e and γ_p, which are published to 1e-10 m/s²; that rounding
    // moves k by ~6e-12 and γ(45°) by ~3e-11 m/s², hence the 1e-10 tolerance.
    #[test]
    fn somigliana_reproduces_the_defining_values() {
        assert!((somigliana_m_s2(0.0) - 9.780_325_335_9).abs() < 1e-9);
        assert!((somigliana_m_s2(deg_to_rad(90.0)) - 9.832_184_937_8).abs() < 1e-9);
        let s2 = deg_to_rad(45.0).sin().powi(2);
        let published = 9.780_325_335_9 * (1.0 + 0.001_931_852_652_41 * s2)
            / (1.0 - 0.006_694_379_990_13 * s2).sqrt();
        assert!((somigliana_m_s2(deg_to_rad(45.0)) - published).abs() < 1e-10);
    }

    // Oracle: the free-air gradient of normal gravity is ≈ −3.086e-6 s⁻² near the surface
    // (the textbook 0.3086 mGal/m), so 1000 m costs ≈ 3.086e-3 m/s². 2e-6 covers the latitude
    // dependence of the gradient (±0.2 %) and the quadratic term.
    #[test]
    fn free_air_gradient_is_0_3086_mgal_per_metre() {
        let lat = deg_to_rad(45.0);
        let drop = normal_gravity_m_s2(lat, 0.0) - normal_gravity_m_s2(lat, 1000.0);
        assert!((drop - 3.086e-3).abs() < 2e-6, "drop {drop}");
    }
}
