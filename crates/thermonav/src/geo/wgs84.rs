//! WGS84 defining and derived constants (NIMA TR8350.2, 3rd ed., tables 3.1 and 3.3).

/// Semi-major axis a, m.
pub const SEMI_MAJOR_AXIS_M: f64 = 6_378_137.0;
/// Flattening f = 1 / 298.257223563.
pub const FLATTENING: f64 = 1.0 / 298.257_223_563;
/// Earth rotation rate ω_ie, rad/s.
pub const EARTH_RATE_RAD_S: f64 = 7.292_115e-5;
/// Geocentric gravitational constant GM, m³/s².
pub const GM_M3_S2: f64 = 3.986_004_418e14;
/// Semi-minor axis b = a (1 − f), m.
pub const SEMI_MINOR_AXIS_M: f64 = SEMI_MAJOR_AXIS_M * (1.0 - FLATTENING);
/// First eccentricity squared e² = f (2 − f).
pub const ECCENTRICITY_SQ: f64 = FLATTENING * (2.0 - FLATTENING);
/// Normal gravity at the equator γ_e, m/s².
pub const GRAVITY_EQUATOR_M_S2: f64 = 9.780_325_335_9;
/// Normal gravity at the poles γ_p, m/s².
pub const GRAVITY_POLE_M_S2: f64 = 9.832_184_937_8;

/// Earth rotation rate resolved in the local NED frame at geodetic latitude `latitude_rad`:
/// ω_ie^n = ω_ie (cos φ, 0, −sin φ), rad/s.
pub fn earth_rate_ned(latitude_rad: f64) -> [f64; 3] {
    let (sin, cos) = latitude_rad.sin_cos();
    [EARTH_RATE_RAD_S * cos, 0.0, -EARTH_RATE_RAD_S * sin]
}
