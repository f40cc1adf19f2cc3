//! GNSS fixes: geodetic position with optional precision, NED velocity and dual-antenna heading.
//!
//! Values are SI inside: latitude and longitude in radians, height in metres above the WGS84
//! ellipsoid, velocity in m/s along north-east-down, heading in radians. Degrees appear only in
//! files, converted at the edge by `thermonav-io` through [`crate::units`].

use crate::time::Timestamp;

/// A heading measured by a dual-antenna GNSS receiver, with its standard deviation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadingObservation {
    /// True heading of the antenna baseline (body x), clockwise from north about down, rad.
    pub heading_rad: f64,
    /// One-sigma uncertainty of the heading, rad.
    pub sd_rad: f64,
}

/// One GNSS solution epoch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GnssFix {
    /// Time of validity of the solution.
    pub time: Timestamp,
    /// Geodetic latitude, rad.
    pub latitude_rad: f64,
    /// Geodetic longitude, rad.
    pub longitude_rad: f64,
    /// Height above the WGS84 ellipsoid, m.
    pub height_m: f64,
    /// One-sigma position uncertainty along north, east and down, m, when the receiver gives it
    /// (files give it along up, which is the same standard deviation).
    pub position_sd_ned_m: Option<[f64; 3]>,
    /// Velocity along north, east and down, m/s, when the receiver gives it.
    pub velocity_ned_m_s: Option<[f64; 3]>,
    /// Dual-antenna heading, when available.
    pub heading: Option<HeadingObservation>,
}
