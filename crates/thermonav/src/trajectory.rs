//! Reference trajectories: position, velocity and attitude over time, for evaluating a
//! navigation solution.
//!
//! Values are SI inside: radians, metres, m/s. Attitude is the body (FRD) frame relative to the
//! local NED frame as Z-Y-X Euler angles: yaw about down, then pitch about the new y, then roll
//! about the new x.

use crate::frames::{Rotation, Vector};
use crate::geo::position::Geodetic;
use crate::ins::state::NavState;
use crate::time::Timestamp;

/// What a reference trajectory holds, and so what can be scored against it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ReferenceContent {
    /// Position, velocity and attitude (a trajectory CSV, a KF-GINS `.nav`): position and
    /// heading errors are scored, and a run can start from it.
    #[default]
    Full,
    /// Positions only (GNSS fixes, an RTK solution): position errors are scored; heading and
    /// attitude are not, and a run cannot take its attitude from it.
    PositionOnly,
}

impl ReferenceContent {
    /// Whether heading errors are scored against such a reference.
    pub fn scores_heading(self) -> bool {
        self == Self::Full
    }
}

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

impl TrajectoryPoint {
    /// The point of a navigation state (attitude as Z-Y-X Euler angles).
    pub fn from_nav_state(s: &NavState) -> Self {
        let (roll_rad, pitch_rad, yaw_rad) = s.attitude.euler_zyx();
        Self {
            time: s.time,
            latitude_rad: s.position.latitude_rad,
            longitude_rad: s.position.longitude_rad,
            height_m: s.position.height_m,
            velocity_ned_m_s: s.velocity.to_array(),
            roll_rad,
            pitch_rad,
            yaw_rad,
        }
    }

    /// The navigation state of the point.
    pub fn nav_state(&self) -> NavState {
        NavState {
            time: self.time,
            position: Geodetic {
                latitude_rad: self.latitude_rad,
                longitude_rad: self.longitude_rad,
                height_m: self.height_m,
            },
            velocity: Vector::from_array(self.velocity_ned_m_s),
            attitude: Rotation::from_euler_zyx(self.roll_rad, self.pitch_rad, self.yaw_rad),
        }
    }
}
