//! Other tools' navigation solutions read as trajectories, for scoring beside ours
//! (`thermonav evaluate --solution`).
//!
//! | format | reader | time | attitude |
//! |---|---|---|---|
//! | `csv` | our trajectory CSV ([`crate::trajectory`]) | `t_s` as it is | roll, pitch, yaw |
//! | `kf-gins-nav` | KF-GINS `.nav` ([`crate::kf_gins`]) | week + seconds of week on the GPST scale of [`crate::gpst`] (week 0: seconds of week) | roll, pitch, yaw 0..360° (the errors are wrapped) |
//! | `rtklib-pos` | RTKLIB `.pos` ([`crate::rtklib_pos`]) | GPST on the same scale | none: yaw is the course over ground from `vn`, `ve` (required), roll and pitch 0 |
//!
//! NaveGo is not among them: its solution is a MATLAB struct, and NaveGo documents no file
//! export; write it as our trajectory CSV (the columns of [`crate::trajectory`]) and read it as
//! `csv`.

use crate::Strictness;
use crate::error::{ReadError, ReadErrorKind};
use crate::kf_gins::{read_kf_gins_nav, read_kf_gins_nav_file};
use crate::rtklib_pos::{PosSettings, PosSolution, read_rtklib_pos, read_rtklib_pos_file};
use crate::trajectory::{read_trajectory, read_trajectory_file};
use std::io::BufRead;
use std::path::Path;
use thermonav::trajectory::TrajectoryPoint;

/// The formats of outside solutions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SolutionFormat {
    /// Our trajectory CSV.
    Csv,
    /// KF-GINS navigation result.
    KfGinsNav,
    /// RTKLIB solution.
    RtklibPos,
}

impl SolutionFormat {
    /// The format told by a file's extension (`.csv`, `.nav`, `.pos`), if any.
    pub fn of_path(path: &Path) -> Option<Self> {
        match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
            "csv" => Some(Self::Csv),
            "nav" => Some(Self::KfGinsNav),
            "pos" => Some(Self::RtklibPos),
            _ => None,
        }
    }

    /// Name as on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Csv => "csv",
            Self::KfGinsNav => "kf-gins-nav",
            Self::RtklibPos => "rtklib-pos",
        }
    }
}

/// Reads the solution at `path` in `format` as a trajectory.
///
/// # Errors
/// The format's reader's errors; for `rtklib-pos`, [`ReadErrorKind::MissingColumn`] when a
/// solution has no velocity (there is no heading to score without one).
pub fn read_solution_file(
    path: &Path,
    format: SolutionFormat,
    strictness: Strictness,
) -> Result<Vec<TrajectoryPoint>, ReadError> {
    match format {
        SolutionFormat::Csv => read_trajectory_file(path, strictness),
        SolutionFormat::KfGinsNav => read_kf_gins_nav_file(path, strictness),
        SolutionFormat::RtklibPos => {
            let settings = PosSettings {
                strictness,
                ..PosSettings::default()
            };
            let solutions = read_rtklib_pos_file(path, settings)?;
            let input = path.display().to_string();
            solutions.iter().map(|s| point_of_pos(s, &input)).collect()
        }
    }
}

/// Reads a solution in `format` from `reader` (named `input` in errors) as a trajectory, as
/// [`read_solution_file`] does from a file (the entry point of the `outside_solution` fuzz
/// target).
///
/// # Errors
/// As [`read_solution_file`].
pub fn read_solution(
    reader: impl BufRead,
    input: &str,
    format: SolutionFormat,
    strictness: Strictness,
) -> Result<Vec<TrajectoryPoint>, ReadError> {
    match format {
        SolutionFormat::Csv => read_trajectory(reader, input, strictness),
        SolutionFormat::KfGinsNav => read_kf_gins_nav(reader, input, strictness),
        SolutionFormat::RtklibPos => {
            let settings = PosSettings {
                strictness,
                ..PosSettings::default()
            };
            let solutions = read_rtklib_pos(reader, input, settings)?;
            solutions.iter().map(|s| point_of_pos(s, input)).collect()
        }
    }
}

/// A `.pos` epoch as a trajectory point: yaw from the course over ground.
fn point_of_pos(s: &PosSolution, input: &str) -> Result<TrajectoryPoint, ReadError> {
    let fix = &s.fix;
    let [vn, ve, vd] = fix.velocity_ned_m_s.ok_or_else(|| {
        let kind = ReadErrorKind::MissingColumn {
            name: "vn(m/s) ve(m/s) vu(m/s)",
            alternatives: " (or vx vy vz: the heading of an RTKLIB solution is its course over ground)",
        };
        ReadError::new(input, None, kind)
    })?;
    Ok(TrajectoryPoint {
        time: fix.time,
        latitude_rad: fix.latitude_rad,
        longitude_rad: fix.longitude_rad,
        height_m: fix.height_m,
        velocity_ned_m_s: [vn, ve, vd],
        roll_rad: 0.0,
        pitch_rad: 0.0,
        yaw_rad: ve.atan2(vn),
    })
}
