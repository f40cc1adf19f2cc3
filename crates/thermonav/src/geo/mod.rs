//! The Earth model: WGS84 ellipsoid, normal gravity, Earth and transport rates, radii of
//! curvature and the geodetic / ECEF / NED conversions.

pub mod gravity;
pub mod position;
pub mod wgs84;
