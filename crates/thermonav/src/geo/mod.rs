//! The Earth model: WGS84 ellipsoid, normal gravity and Earth rate.
//!
//! Radii of curvature, transport rate and the geodetic/ECEF/NED conversions join this module
//! with the strapdown navigation.

pub mod gravity;
pub mod wgs84;
