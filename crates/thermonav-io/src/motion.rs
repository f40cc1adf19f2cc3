//! Motion definitions as TOML (units in the key names), like the peers' motion files.
//!
//! ```toml
//! initial_speed_m_s = 0.0
//! initial_heading_deg = 90.0
//! pitch = "follows_path"        # or "level" (a vessel)
//!
//! [start]
//! lat_deg = 51.08
//! lon_deg = -114.13
//! h_m = 1100.0
//!
//! [[segment]]                  # accelerate to 15 m/s
//! duration_s = 10.0
//! acceleration_m_s2 = 1.5
//!
//! [[segment]]                  # a 90° right turn while climbing
//! duration_s = 9.0
//! turn_rate_deg_s = 10.0
//! climb_rate_m_s = 0.5
//!
//! [[waves.roll]]               # optional harmonic motion (roll, pitch in deg; heave in m)
//! amplitude_deg = 3.0
//! period_s = 6.0
//! ```
//! Omitted segment values are zero. The file converts once to the library's SI
//! [`MotionDefinition`].

use serde::Deserialize;
use std::path::Path;
use thermonav::sim::motion::{
    Harmonic, MotionDefinition, MotionSegment, PitchModel, StartPoint, WaveMotion,
};

/// Why a motion file cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum MotionFileError {
    /// Unreadable file.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// File.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// Not valid TOML for the schema (the parser's message carries line and column).
    #[error("{path}: {message}")]
    Parse {
        /// File.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// Values out of range (the validation error is the message, not a chained source, so
    /// it is printed once).
    #[error("{path}: {problem}")]
    Invalid {
        /// File.
        path: String,
        /// The validation error.
        problem: thermonav::sim::motion::MotionError,
    },
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MotionFile {
    start: StartPoint,
    #[serde(default)]
    initial_speed_m_s: f64,
    #[serde(default)]
    initial_heading_deg: f64,
    #[serde(default = "default_pitch")]
    pitch: PitchModel,
    segment: Vec<SegmentFile>,
    #[serde(default)]
    waves: WavesFile,
}

fn default_pitch() -> PitchModel {
    PitchModel::FollowsPath
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SegmentFile {
    duration_s: f64,
    #[serde(default)]
    acceleration_m_s2: f64,
    #[serde(default)]
    turn_rate_deg_s: f64,
    #[serde(default)]
    climb_rate_m_s: f64,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct WavesFile {
    #[serde(default)]
    roll: Vec<AngleHarmonic>,
    #[serde(default)]
    pitch: Vec<AngleHarmonic>,
    #[serde(default)]
    heave: Vec<HeaveHarmonic>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct AngleHarmonic {
    amplitude_deg: f64,
    period_s: f64,
    #[serde(default)]
    phase_deg: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct HeaveHarmonic {
    amplitude_m: f64,
    period_s: f64,
    #[serde(default)]
    phase_deg: f64,
}

fn angle(h: &AngleHarmonic) -> Harmonic {
    Harmonic {
        amplitude: h.amplitude_deg.to_radians(),
        period_s: h.period_s,
        phase_rad: h.phase_deg.to_radians(),
    }
}

/// Parses a motion definition; `path` names the source in errors.
///
/// # Errors
/// [`MotionFileError`] for invalid TOML, unknown keys, or values out of range.
pub fn parse_motion(text: &str, path: &str) -> Result<MotionDefinition, MotionFileError> {
    let file: MotionFile = toml::from_str(text).map_err(|e| MotionFileError::Parse {
        path: path.to_string(),
        message: e.to_string(),
    })?;
    let motion = MotionDefinition {
        start: file.start,
        initial_speed_m_s: file.initial_speed_m_s,
        initial_heading_rad: file.initial_heading_deg.to_radians(),
        segments: file
            .segment
            .iter()
            .map(|s| MotionSegment {
                duration_s: s.duration_s,
                acceleration_m_s2: s.acceleration_m_s2,
                turn_rate_rad_s: s.turn_rate_deg_s.to_radians(),
                climb_rate_m_s: s.climb_rate_m_s,
            })
            .collect(),
        waves: WaveMotion {
            roll: file.waves.roll.iter().map(angle).collect(),
            pitch: file.waves.pitch.iter().map(angle).collect(),
            heave: file
                .waves
                .heave
                .iter()
                .map(|h| Harmonic {
                    amplitude: h.amplitude_m,
                    period_s: h.period_s,
                    phase_rad: h.phase_deg.to_radians(),
                })
                .collect(),
        },
        pitch: file.pitch,
    };
    motion
        .validate()
        .map_err(|problem| MotionFileError::Invalid {
            path: path.to_string(),
            problem,
        })?;
    Ok(motion)
}

/// Reads a motion file.
///
/// # Errors
/// As [`parse_motion`], plus an unreadable file.
pub fn read_motion(path: &Path) -> Result<MotionDefinition, MotionFileError> {
    let name = path.display().to_string();
    let text = crate::read_document_text(path).map_err(|source| MotionFileError::Read {
        path: name.clone(),
        source,
    })?;
    parse_motion(&text, &name)
}

#[cfg(test)]
mod tests {
    use super::*;

    const CAR: &str = "
initial_heading_deg = 90.0
[start]
lat_deg = 51.08
lon_deg = -114.13
h_m = 1100.0
[[segment]]
duration_s = 10.0
acceleration_m_s2 = 1.5
[[segment]]
duration_s = 9.0
turn_rate_deg_s = 10.0
climb_rate_m_s = 0.5
";

    #[test]
    fn a_car_file_converts_to_si() {
        let m = parse_motion(CAR, "car.toml").unwrap();
        assert_eq!(m.segments.len(), 2);
        assert_eq!(m.duration_s(), 19.0);
        assert!((m.initial_heading_rad - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert!((m.segments[1].turn_rate_rad_s - 10f64.to_radians()).abs() < 1e-15);
        assert_eq!(m.pitch, PitchModel::FollowsPath);
    }

    #[test]
    fn mistakes_name_the_file() {
        let typo = CAR.replace("turn_rate_deg_s", "turn_rate_degs");
        let e = parse_motion(&typo, "car.toml").unwrap_err().to_string();
        assert!(
            e.starts_with("car.toml") && e.contains("turn_rate_degs"),
            "{e}"
        );
        let backwards = CAR.replace("acceleration_m_s2 = 1.5", "acceleration_m_s2 = -1.5");
        let e = parse_motion(&backwards, "car.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("speed"), "{e}");
    }
}
