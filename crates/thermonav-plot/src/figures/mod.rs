//! The project's figures: each a function of typed data returning a standalone SVG string.
//!
//! Data come in SI (rad/s, m/s², s, m); [`DisplayUnits`] chooses how inertial quantities are
//! shown. Every panel has axis labels with units and a legend.

pub mod allan;
pub mod autocorrelation;
pub mod claims;
pub mod correlation;
pub mod navigation;
pub mod thermal;
pub mod thermal_check;

use crate::palette::{self, Color};
use thermonav::imu::{Channel, Sensor};
use thermonav::units::{m_per_s2_to_mg, rad_per_s_to_deg_per_h};

/// Units of gyro and accelerometer quantities on figures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DisplayUnits {
    /// rad/s and m/s².
    Si,
    /// deg/h and mg, as navigation engineers quote them.
    Navigation,
}

impl DisplayUnits {
    /// The unit of a rate of `sensor` (angular rate or specific force).
    pub fn rate_unit(self, sensor: Sensor) -> &'static str {
        match (self, sensor) {
            (DisplayUnits::Si, Sensor::Gyro) => "rad/s",
            (DisplayUnits::Si, Sensor::Accelerometer) => "m/s²",
            (DisplayUnits::Navigation, Sensor::Gyro) => "deg/h",
            (DisplayUnits::Navigation, Sensor::Accelerometer) => "mg",
        }
    }

    /// An SI rate of `sensor` (rad/s or m/s²) in the display unit.
    pub fn rate(self, sensor: Sensor, si: f64) -> f64 {
        match (self, sensor) {
            (DisplayUnits::Si, _) => si,
            (DisplayUnits::Navigation, Sensor::Gyro) => rad_per_s_to_deg_per_h(si),
            (DisplayUnits::Navigation, Sensor::Accelerometer) => m_per_s2_to_mg(si),
        }
    }
}

/// Panel title of a sensor's channels.
pub fn sensor_title(sensor: Sensor) -> &'static str {
    match sensor {
        Sensor::Gyro => "Gyroscopes",
        Sensor::Accelerometer => "Accelerometers",
    }
}

/// The colour of a channel: x, y and z of both sensors share the first three colours.
pub fn channel_color(channel: Channel) -> Color {
    palette::series_color(channel.index() % 3)
}
