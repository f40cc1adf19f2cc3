//! Geodetic position on WGS84: radii of curvature, ECEF conversion, the NED frame's
//! orientation, and the navigation-frame rates (Groves 2013, §2.4 and §5.4).

use super::wgs84::{EARTH_RATE_RAD_S, ECCENTRICITY_SQ, SEMI_MAJOR_AXIS_M, SEMI_MINOR_AXIS_M};
use crate::frames::{Ecef, Ned, Rotation, Vector};
use nalgebra::{Matrix3, Rotation3, UnitQuaternion};

/// A geodetic position: latitude and longitude in radians, ellipsoidal height in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geodetic {
    /// Geodetic latitude φ, rad.
    pub latitude_rad: f64,
    /// Longitude λ, rad.
    pub longitude_rad: f64,
    /// Height above the ellipsoid h, m.
    pub height_m: f64,
}

/// The largest |latitude| thermonav navigates at, °: the local-level (NED) mechanisation
/// divides by cos φ (longitude rate, transport rate tan φ), which vanishes at the poles. At 89°
/// a metre east is already 57 times the longitude change it is at the equator; closer in, the
/// north and east axes turn faster than a filter step can follow. Motion definitions, GNSS
/// fixes and the filter's own solution are refused beyond it.
pub const NAVIGATION_LATITUDE_LIMIT_DEG: f64 = 89.0;

/// True when `latitude_rad` is within [`NAVIGATION_LATITUDE_LIMIT_DEG`] of the equator.
pub fn within_navigation_latitudes(latitude_rad: f64) -> bool {
    latitude_rad.to_degrees().abs() <= NAVIGATION_LATITUDE_LIMIT_DEG
}

/// Meridian radius of curvature R_N(φ) = a (1 − e²) / (1 − e² sin²φ)^{3/2}, m.
pub fn meridian_radius_m(latitude_rad: f64) -> f64 {
    let s2 = latitude_rad.sin().powi(2);
    let d = 1.0 - ECCENTRICITY_SQ * s2;
    SEMI_MAJOR_AXIS_M * (1.0 - ECCENTRICITY_SQ) / (d * d.sqrt())
}

/// Transverse (prime-vertical) radius of curvature R_E(φ) = a / √(1 − e² sin²φ), m.
pub fn transverse_radius_m(latitude_rad: f64) -> f64 {
    SEMI_MAJOR_AXIS_M / (1.0 - ECCENTRICITY_SQ * latitude_rad.sin().powi(2)).sqrt()
}

impl Geodetic {
    /// A position from degrees and metres (the edge units).
    pub fn from_degrees(latitude_deg: f64, longitude_deg: f64, height_m: f64) -> Self {
        Self {
            latitude_rad: latitude_deg.to_radians(),
            longitude_rad: longitude_deg.to_radians(),
            height_m,
        }
    }

    /// ECEF coordinates, m (Groves eq. 2.112).
    pub fn to_ecef(&self) -> Vector<Ecef> {
        let (sl, cl) = self.latitude_rad.sin_cos();
        let (so, co) = self.longitude_rad.sin_cos();
        let re = transverse_radius_m(self.latitude_rad);
        let h = self.height_m;
        Vector::new(
            (re + h) * cl * co,
            (re + h) * cl * so,
            ((1.0 - ECCENTRICITY_SQ) * re + h) * sl,
        )
    }

    /// The geodetic position of an ECEF point, by Bowring's initial guess and Newton-free
    /// fixed-point iterations on the latitude (converges to < 1e-12 rad in three iterations for
    /// |h| < 1000 km; four are done).
    pub fn from_ecef(r: &Vector<Ecef>) -> Self {
        let (x, y, z) = (r.x(), r.y(), r.z());
        let p = x.hypot(y);
        let longitude_rad = y.atan2(x);
        let e2 = ECCENTRICITY_SQ;
        let ep2 = e2 / (1.0 - e2);
        let theta = (z * SEMI_MAJOR_AXIS_M).atan2(p * SEMI_MINOR_AXIS_M);
        let (st, ct) = theta.sin_cos();
        let mut lat = (z + ep2 * SEMI_MINOR_AXIS_M * st.powi(3))
            .atan2(p - e2 * SEMI_MAJOR_AXIS_M * ct.powi(3));
        for _ in 0..4 {
            let re = transverse_radius_m(lat);
            let h = if lat.cos().abs() > 1e-10 {
                p / lat.cos() - re
            } else {
                z.abs() - SEMI_MINOR_AXIS_M
            };
            lat = z.atan2(p * (1.0 - e2 * re / (re + h)));
        }
        let re = transverse_radius_m(lat);
        let height_m = if lat.cos().abs() > 1e-10 {
            p / lat.cos() - re
        } else {
            z.abs() - SEMI_MINOR_AXIS_M
        };
        Self {
            latitude_rad: lat,
            longitude_rad,
            height_m,
        }
    }

    /// C_n^e: NED axes at this position resolved in ECEF (Groves eq. 2.150, transposed).
    pub fn ned_to_ecef(&self) -> Rotation<Ned, Ecef> {
        let (sl, cl) = self.latitude_rad.sin_cos();
        let (so, co) = self.longitude_rad.sin_cos();
        let m = Matrix3::new(
            -sl * co,
            -so,
            -cl * co,
            -sl * so,
            co,
            -cl * so,
            cl,
            0.0,
            -sl,
        );
        Rotation::from_unit_quaternion(UnitQuaternion::from_rotation_matrix(
            &Rotation3::from_matrix_unchecked(m),
        ))
    }

    /// Earth rate in NED, ω_ie^n = ω_ie (cos φ, 0, −sin φ), rad/s.
    pub fn earth_rate_ned(&self) -> Vector<Ned> {
        Vector::from_array(super::wgs84::earth_rate_ned(self.latitude_rad))
    }

    /// Transport rate ω_en^n for velocity v^n (Groves eq. 5.44), rad/s:
    /// (v_E/(R_E + h), −v_N/(R_N + h), −v_E tan φ/(R_E + h)).
    pub fn transport_rate_ned(&self, velocity_ned_m_s: &Vector<Ned>) -> Vector<Ned> {
        let rn = meridian_radius_m(self.latitude_rad) + self.height_m;
        let re = transverse_radius_m(self.latitude_rad) + self.height_m;
        let (vn, ve) = (velocity_ned_m_s.x(), velocity_ned_m_s.y());
        Vector::new(ve / re, -vn / rn, -ve * self.latitude_rad.tan() / re)
    }

    /// Position rates from NED velocity (Groves eq. 5.56): dφ/dt, dλ/dt (rad/s), dh/dt (m/s).
    pub fn rates(&self, velocity_ned_m_s: &Vector<Ned>) -> [f64; 3] {
        let rn = meridian_radius_m(self.latitude_rad) + self.height_m;
        let re = transverse_radius_m(self.latitude_rad) + self.height_m;
        [
            velocity_ned_m_s.x() / rn,
            velocity_ned_m_s.y() / (re * self.latitude_rad.cos()),
            -velocity_ned_m_s.z(),
        ]
    }

    /// The position `offset` (NED, m) away, with the radii at `self` (first order: the
    /// neglected curvature terms are ~|offset|²/R, below 1 µm for offsets of metres and below
    /// 1 mm for a 200 Hz step at 1 km/s). Also the first-order step `v dt` along a velocity.
    pub fn displaced(&self, offset: &Vector<Ned>) -> Geodetic {
        let rn = meridian_radius_m(self.latitude_rad) + self.height_m;
        let re = transverse_radius_m(self.latitude_rad) + self.height_m;
        Geodetic {
            latitude_rad: self.latitude_rad + offset.x() / rn,
            longitude_rad: self.longitude_rad + offset.y() / (re * self.latitude_rad.cos()),
            height_m: self.height_m - offset.z(),
        }
    }

    /// The curvilinear NED offset from `origin` to `self` with the radii at `origin`: the exact
    /// inverse of [`Geodetic::displaced`] (`origin.displaced(&self.offset_from(origin))`
    /// returns `self` to rounding). Unlike [`Geodetic::ned_from`] it has no tangent-plane
    /// curvature term, so error states round-trip through it without a bias in down.
    pub fn offset_from(&self, origin: &Geodetic) -> Vector<Ned> {
        let rn = meridian_radius_m(origin.latitude_rad) + origin.height_m;
        let re = transverse_radius_m(origin.latitude_rad) + origin.height_m;
        Vector::new(
            (self.latitude_rad - origin.latitude_rad) * rn,
            (self.longitude_rad - origin.longitude_rad) * re * origin.latitude_rad.cos(),
            origin.height_m - self.height_m,
        )
    }

    /// The coordinate-wise mean of two positions (the mid-interval position of a step).
    pub fn midpoint(&self, other: &Geodetic) -> Geodetic {
        Geodetic {
            latitude_rad: 0.5 * (self.latitude_rad + other.latitude_rad),
            longitude_rad: 0.5 * (self.longitude_rad + other.longitude_rad),
            height_m: 0.5 * (self.height_m + other.height_m),
        }
    }

    /// The NED displacement from `origin` to `self` on the local tangent plane, m
    /// (ECEF difference rotated into the origin's NED axes).
    pub fn ned_from(&self, origin: &Geodetic) -> Vector<Ned> {
        origin.ned_to_ecef().inverse() * (self.to_ecef() - origin.to_ecef())
    }
}

/// Earth rotation rate about the ECEF z axis, rad/s.
pub fn earth_rate_ecef() -> Vector<Ecef> {
    Vector::new(0.0, 0.0, EARTH_RATE_RAD_S)
}
