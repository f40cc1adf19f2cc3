//! Named unit conversions, used only at the edges (readers, writers, reports).
//!
//! Inside the crate every quantity is SI: rad, rad/s, m/s², s. Noise terms follow IEEE Std 952
//! names: angle random walk (ARW), velocity random walk (VRW), bias instability (BI), rate random
//! walk (RRW). Each conversion is a plain multiplication by a named factor, so a reader can check
//! it by eye.

use std::f64::consts::PI;

/// Standard gravity, m/s² per g (CGPM 1901, exact by definition).
pub const STANDARD_GRAVITY_M_S2: f64 = 9.80665;
/// Seconds per hour.
pub const SECONDS_PER_HOUR: f64 = 3600.0;
/// Radians per degree.
pub const RAD_PER_DEG: f64 = PI / 180.0;

/// Degrees to radians.
pub fn deg_to_rad(deg: f64) -> f64 {
    deg * RAD_PER_DEG
}

/// Radians to degrees.
pub fn rad_to_deg(rad: f64) -> f64 {
    rad / RAD_PER_DEG
}

/// Angular rate in deg/h to rad/s.
pub fn deg_per_h_to_rad_per_s(deg_per_h: f64) -> f64 {
    deg_to_rad(deg_per_h) / SECONDS_PER_HOUR
}

/// Angular rate in rad/s to deg/h.
pub fn rad_per_s_to_deg_per_h(rad_per_s: f64) -> f64 {
    rad_to_deg(rad_per_s) * SECONDS_PER_HOUR
}

/// Acceleration in g to m/s².
pub fn g_to_m_per_s2(g: f64) -> f64 {
    g * STANDARD_GRAVITY_M_S2
}

/// Acceleration in milli-g to m/s².
pub fn mg_to_m_per_s2(mg: f64) -> f64 {
    g_to_m_per_s2(mg / 1000.0)
}

/// Acceleration in m/s² to milli-g.
pub fn m_per_s2_to_mg(m_per_s2: f64) -> f64 {
    m_per_s2 / STANDARD_GRAVITY_M_S2 * 1000.0
}

/// Angle random walk in deg/√h to rad/√s (equivalently rad/s/√Hz).
///
/// 1 deg/√h = (π/180) rad / √(3600 s) = (π/180)/60 rad/√s.
pub fn arw_deg_per_sqrt_h_to_rad_per_sqrt_s(deg_per_sqrt_h: f64) -> f64 {
    deg_to_rad(deg_per_sqrt_h) / SECONDS_PER_HOUR.sqrt()
}

/// Angle random walk in rad/√s to deg/√h.
pub fn arw_rad_per_sqrt_s_to_deg_per_sqrt_h(rad_per_sqrt_s: f64) -> f64 {
    rad_to_deg(rad_per_sqrt_s) * SECONDS_PER_HOUR.sqrt()
}

/// Velocity random walk in m/s/√h to m/s/√s (equivalently m/s²/√Hz).
pub fn vrw_m_per_s_per_sqrt_h_to_m_per_s_per_sqrt_s(m_per_s_per_sqrt_h: f64) -> f64 {
    m_per_s_per_sqrt_h / SECONDS_PER_HOUR.sqrt()
}

/// Velocity random walk in m/s/√s to m/s/√h.
pub fn vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h(m_per_s_per_sqrt_s: f64) -> f64 {
    m_per_s_per_sqrt_s * SECONDS_PER_HOUR.sqrt()
}

/// An angle wrapped to (−π, π], rad.
pub fn wrap_pi(angle_rad: f64) -> f64 {
    let wrapped = angle_rad.rem_euclid(std::f64::consts::TAU);
    if wrapped > std::f64::consts::PI {
        wrapped - std::f64::consts::TAU
    } else {
        wrapped
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Closed forms: each factor written out by hand from its definition.
    #[test]
    fn arw_one_deg_per_sqrt_h_is_pi_over_10800_rad_per_sqrt_s() {
        let expected = PI / 180.0 / 60.0;
        assert!((arw_deg_per_sqrt_h_to_rad_per_sqrt_s(1.0) - expected).abs() < 1e-18);
        assert!((arw_rad_per_sqrt_s_to_deg_per_sqrt_h(expected) - 1.0).abs() < 1e-14);
    }

    #[test]
    fn one_deg_per_h_is_4_85e_6_rad_per_s() {
        assert!((deg_per_h_to_rad_per_s(1.0) - 4.848_136_811_095_36e-6).abs() < 1e-18);
        assert!((rad_per_s_to_deg_per_h(deg_per_h_to_rad_per_s(7.5)) - 7.5).abs() < 1e-12);
    }

    #[test]
    fn milli_g_round_trip() {
        assert!((mg_to_m_per_s2(1000.0) - 9.80665).abs() < 1e-15);
        assert!((m_per_s2_to_mg(mg_to_m_per_s2(0.1)) - 0.1).abs() < 1e-15);
    }

    #[test]
    fn vrw_one_m_per_s_per_sqrt_h_is_one_sixtieth() {
        assert!((vrw_m_per_s_per_sqrt_h_to_m_per_s_per_sqrt_s(0.12) - 0.002).abs() < 1e-17);
        assert!((vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h(0.002) - 0.12).abs() < 1e-15);
    }
}
