//! The navigation state and the IMU increments that drive it.

use crate::frames::{Body, Ned, Rotation, Vector};
use crate::geo::position::Geodetic;
use crate::time::{Duration, Timestamp};

/// Position, velocity and attitude at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NavState {
    /// Time of validity.
    pub time: Timestamp,
    /// Geodetic position.
    pub position: Geodetic,
    /// Velocity relative to the Earth, resolved in NED, m/s.
    pub velocity: Vector<Ned>,
    /// Attitude C_b^n.
    pub attitude: Rotation<Body, Ned>,
}

/// One IMU sample as increments over the interval ending at `time`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Increment {
    /// End of the interval.
    pub time: Timestamp,
    /// Interval length, exact (positive).
    pub dt: Duration,
    /// Angle increment Δθ, rad, body axes.
    pub delta_angle: Vector<Body>,
    /// Velocity increment Δv (integrated specific force), m/s, body axes.
    pub delta_velocity: Vector<Body>,
}

impl Increment {
    /// Increments from rates held constant over the interval: Δθ = ω dt, Δv = f dt.
    pub fn from_rates(
        time: Timestamp,
        dt: Duration,
        rate: [f64; 3],
        specific_force: [f64; 3],
    ) -> Self {
        let dt_s = dt.as_seconds();
        Self {
            time,
            dt,
            delta_angle: Vector::from_array(rate).scale(dt_s),
            delta_velocity: Vector::from_array(specific_force).scale(dt_s),
        }
    }

    /// Interval length in seconds, for formulas.
    pub fn dt_s(&self) -> f64 {
        self.dt.as_seconds()
    }

    /// Start of the interval (`time − dt`).
    pub fn start(&self) -> Timestamp {
        self.time - self.dt
    }
}
