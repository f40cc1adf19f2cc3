//! GNSS fixes: geodetic position with optional precision, NED velocity and dual-antenna heading.
//!
//! Values are SI inside: latitude and longitude in radians, height in metres above the WGS84
//! ellipsoid, velocity in m/s along north-east-down, heading in radians. Degrees appear only in
//! files, converted at the edge by `thermonav-io` through [`crate::units`].

use crate::time::Timestamp;
use serde::Serialize;

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

/// Where a run's GNSS position standard deviations came from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GnssSdUse {
    /// `file` (every fix has its sds), `default` (none has: the default was used for all), or
    /// `file_and_default` (some have).
    pub source: GnssSdSource,
    /// Fixes in the record.
    pub fixes: usize,
    /// Fixes without sds, given the default.
    pub fixes_with_default_sd: usize,
    /// The default, north/east/down, m (the engine's `default_position_sd_m`).
    pub default_position_sd_ned_m: [f64; 3],
}

/// Which sds a run's fixes carried.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GnssSdSource {
    /// Every fix's own.
    File,
    /// The default for every fix.
    Default,
    /// Some fixes' own, the default for the others.
    FileAndDefault,
}

impl GnssSdUse {
    /// The sds of `fixes` with `default_position_sd_ned_m` for those without.
    pub fn of(fixes: &[GnssFix], default_position_sd_ned_m: [f64; 3]) -> Self {
        let without = fixes
            .iter()
            .filter(|f| f.position_sd_ned_m.is_none())
            .count();
        let source = match without {
            0 => GnssSdSource::File,
            n if n == fixes.len() => GnssSdSource::Default,
            _ => GnssSdSource::FileAndDefault,
        };
        Self {
            source,
            fixes: fixes.len(),
            fixes_with_default_sd: without,
            default_position_sd_ned_m,
        }
    }

    /// In words, with the default's values when it was used.
    pub fn words(&self) -> String {
        let [n, e, d] = self.default_position_sd_ned_m;
        match self.source {
            GnssSdSource::File => format!("the file's, on all {} fixes", self.fixes),
            _ => format!(
                "default {n} m north, {e} m east, {d} m down on {} of {} fixes (no sd_n_m, sd_e_m, sd_u_m in the file)",
                self.fixes_with_default_sd, self.fixes
            ),
        }
    }
}
