//! Reference trajectories: position, velocity and attitude over time, for evaluating a
//! navigation solution.
//!
//! Values are SI inside: radians, metres, m/s. Attitude is the body (FRD) frame relative to the
//! local NED frame as Z-Y-X Euler angles: yaw about down, then pitch about the new y, then roll
//! about the new x.

use crate::time::Timestamp;

/// One epoch of a reference trajectory.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrajectoryPoint {
    /// Time of the epoch.
    pub time: Timestamp,
    /// Geodetic latitude, rad.
    pub latitude_rad: f64,
    /// Geodetic longitude, rad.
    pub longitude_rad: f64,
    /// Height above the WGS84 ellipsoid, m.
    pub height_m: f64,
    /// Velocity along north, east and down, m/s.
    pub velocity_ned_m_s: [f64; 3],
    /// Roll (rotation about body x), rad.
    pub roll_rad: f64,
    /// Pitch (rotation about body y), rad.
    pub pitch_rad: f64,
    /// Yaw (heading, rotation about down), rad.
    pub yaw_rad: f64,
}
