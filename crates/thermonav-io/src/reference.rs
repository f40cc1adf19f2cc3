//! A reference trajectory in any of the forms users have one: the kind is told by the file's
//! content, and each kind is read by its own reader.
//!
//! | kind | told by | reader | holds |
//! |---|---|---|---|
//! | `trajectory-csv` | a comma-separated header with `roll_deg` (or `yaw_deg`…) | [`crate::trajectory`] | position, velocity, attitude |
//! | `gnss-csv` | a comma-separated header with `lat_deg` and no attitude | [`crate::gnss`] | position (velocity when the file has it) |
//! | `rtklib-pos` | a `%` comment line or a `yyyy/mm/dd` date first | [`crate::rtklib_pos`] | position (velocity when the file has it) |
//! | `kf-gins-nav` | 11 blank-separated numbers a line | [`crate::kf_gins`] | position, velocity, attitude |
//!
//! Times are the readers' own: `t_s` as it is for our CSVs; GPST on the scale of
//! [`crate::gpst`] for a `.pos` (calendar or week/seconds) and a `.nav` with a week (a week of
//! 0 leaves seconds of week), the scale `thermonav convert` puts the same files on, so a
//! reference lines up with an IMU record converted from the same receiver's log.
//!
//! A position-only reference ([`ReferenceContent::PositionOnly`]) has its points' attitude
//! at zero: the caller scores position alone and takes no attitude from it.

use crate::Strictness;
use crate::error::{ReadError, ReadErrorKind};
use crate::gnss::read_gnss;
use crate::kf_gins::read_kf_gins_nav;
use crate::rtklib_pos::{PosSettings, read_rtklib_pos};
use crate::trajectory::read_trajectory;
use std::io::{BufRead, Read};
use std::path::Path;
use thermonav::gnss::GnssFix;
use thermonav::trajectory::{ReferenceContent, TrajectoryPoint};

/// The forms of a reference trajectory.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ReferenceKind {
    /// Our trajectory CSV.
    TrajectoryCsv,
    /// Our GNSS CSV (what `--gnss` reads).
    GnssCsv,
    /// An RTKLIB solution (`.pos`).
    RtklibPos,
    /// A KF-GINS navigation result or ground truth (`.nav`).
    KfGinsNav,
}

impl ReferenceKind {
    /// Name as the user sees it.
    pub fn name(self) -> &'static str {
        match self {
            Self::TrajectoryCsv => "trajectory CSV",
            Self::GnssCsv => "GNSS CSV",
            Self::RtklibPos => "RTKLIB .pos",
            Self::KfGinsNav => "KF-GINS .nav",
        }
    }

    /// What a reference of this kind holds.
    pub fn content(self) -> ReferenceContent {
        match self {
            Self::TrajectoryCsv | Self::KfGinsNav => ReferenceContent::Full,
            Self::GnssCsv | Self::RtklibPos => ReferenceContent::PositionOnly,
        }
    }

    /// The kind told by the first bytes of a file, or why none fits.
    ///
    /// # Errors
    /// [`ReadErrorKind::Empty`] for no line; [`ReadErrorKind::Unsupported`] for a first line
    /// that fits no kind.
    pub fn of_head(head: &[u8]) -> Result<Self, ReadErrorKind> {
        let text = String::from_utf8_lossy(head);
        let first = (text.lines().map(str::trim))
            .find(|l| !l.is_empty())
            .ok_or(ReadErrorKind::Empty)?;
        if first.starts_with('%') || is_slashed_date(first) {
            return Ok(Self::RtklibPos);
        }
        if first.contains(',') {
            return csv_kind(first);
        }
        match first.split_whitespace().count() {
            11 => Ok(Self::KfGinsNav),
            15 | 24 => Ok(Self::RtklibPos),
            _ => Err(unknown_kind(first)),
        }
    }
}

/// The kinds a reference may be, for errors.
const KINDS: &str = "a trajectory CSV (t_s,lat_deg,…,yaw_deg), a GNSS CSV (t_s,lat_deg,lon_deg,h_m,…), an RTKLIB .pos or a KF-GINS .nav";

/// The 1-based number of the first line with text in `head` (the line a kind is told by).
fn first_line_number(head: &[u8]) -> Option<u64> {
    let text = String::from_utf8_lossy(head);
    let index = text.lines().position(|l| !l.trim().is_empty())?;
    Some(index as u64 + 1)
}

/// The first line as an error shows it: 60 characters at most, control characters and
/// undecodable bytes escaped (a binary file's first bytes are no text to print).
fn shown_line(first: &str) -> String {
    first
        .chars()
        .take(60)
        .flat_map(
            |c| match c.is_control() || c == char::REPLACEMENT_CHARACTER {
                true => c.escape_unicode().collect::<Vec<char>>(),
                false => vec![c],
            },
        )
        .collect()
}

fn unknown_kind(first: &str) -> ReadErrorKind {
    let shown = shown_line(first);
    ReadErrorKind::Unsupported {
        found: format!("a file whose first line is \"{shown}\""),
        expected: KINDS,
    }
}

/// A first field such as `2025/07/08` (RTKLIB's calendar time, in a file without header).
fn is_slashed_date(line: &str) -> bool {
    let token = line.split_whitespace().next().unwrap_or("");
    let parts: Vec<&str> = token.split('/').collect();
    parts.len() == 3
        && parts
            .iter()
            .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()))
}

/// Our trajectory CSV when the header names an attitude column, our GNSS CSV when it names
/// `lat_deg` without one.
fn csv_kind(header: &str) -> Result<ReferenceKind, ReadErrorKind> {
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let has = |name: &str| names.contains(&name);
    if ["roll_deg", "pitch_deg", "yaw_deg", "roll_rad", "yaw_rad"]
        .iter()
        .any(|n| has(n))
    {
        return Ok(ReferenceKind::TrajectoryCsv);
    }
    match has("lat_deg") || has("lat_rad") {
        true => Ok(ReferenceKind::GnssCsv),
        // The trajectory reader names what is wrong with the header.
        false => Ok(ReferenceKind::TrajectoryCsv),
    }
}

/// A reference trajectory read: its kind, what it holds and its points.
#[derive(Debug, Clone)]
pub struct Reference {
    /// The form it was read from.
    pub kind: ReferenceKind,
    /// Its points; attitude zero when [`ReferenceKind::content`] is position-only.
    pub points: Vec<TrajectoryPoint>,
}

impl Reference {
    /// What it holds.
    pub fn content(&self) -> ReferenceContent {
        self.kind.content()
    }
}

/// Bytes read from the start of a file to tell its kind.
const HEAD_BYTES: u64 = 4096;

/// Reads the reference at `path`, its kind told by its content (gzip read through).
///
/// # Errors
/// [`ReadErrorKind::Open`], a content of no known kind ([`ReferenceKind::of_head`]), and the
/// errors of the kind's reader, each naming the file.
pub fn read_reference_file(path: &Path, strictness: Strictness) -> Result<Reference, ReadError> {
    let kind = reference_kind_of_file(path)?;
    let (file, input) = crate::open_file(path)?;
    read_reference_kind(file, &input, kind, strictness)
}

/// The kind of the reference at `path`, told by its first bytes.
///
/// # Errors
/// [`ReadErrorKind::Open`] and those of [`ReferenceKind::of_head`], naming the file.
pub fn reference_kind_of_file(path: &Path) -> Result<ReferenceKind, ReadError> {
    let input = path.display().to_string();
    let mut head = Vec::new();
    crate::open_input(path)
        .and_then(|file| file.take(HEAD_BYTES).read_to_end(&mut head))
        .map_err(|e| ReadError::new(input.as_str(), None, ReadErrorKind::Open(e)))?;
    ReferenceKind::of_head(&head).map_err(|k| ReadError::new(input, first_line_number(&head), k))
}

/// Reads a reference of `kind` from `reader` (named `input` in errors).
///
/// # Errors
/// The errors of the kind's reader.
pub fn read_reference_kind(
    reader: impl BufRead,
    input: &str,
    kind: ReferenceKind,
    strictness: Strictness,
) -> Result<Reference, ReadError> {
    let points = match kind {
        ReferenceKind::TrajectoryCsv => read_trajectory(reader, input, strictness)?,
        ReferenceKind::KfGinsNav => read_kf_gins_nav(reader, input, strictness)?,
        ReferenceKind::GnssCsv => points_of_fixes(read_gnss(reader, input, strictness)?),
        ReferenceKind::RtklibPos => {
            let settings = PosSettings {
                strictness,
                ..PosSettings::default()
            };
            let solutions = read_rtklib_pos(reader, input, settings)?;
            points_of_fixes(solutions.into_iter().map(|s| s.fix).collect())
        }
    };
    Ok(Reference { kind, points })
}

/// Fixes as position-only reference points: velocity when the fix has one (else zero),
/// attitude zero.
fn points_of_fixes(fixes: Vec<GnssFix>) -> Vec<TrajectoryPoint> {
    fixes.iter().map(point_of_fix).collect()
}

fn point_of_fix(fix: &GnssFix) -> TrajectoryPoint {
    TrajectoryPoint {
        time: fix.time,
        latitude_rad: fix.latitude_rad,
        longitude_rad: fix.longitude_rad,
        height_m: fix.height_m,
        velocity_ned_m_s: fix.velocity_ned_m_s.unwrap_or([0.0; 3]),
        roll_rad: 0.0,
        pitch_rad: 0.0,
        yaw_rad: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // A binary file's first bytes are shown escaped: the error prints no control character
    // and no undecodable byte, and the line it names is the first with text.
    #[test]
    fn a_binary_head_is_refused_with_its_bytes_escaped() {
        let head = b"\n\x89PNG\r\n\x1a\n\x00\x00";
        let Err(kind) = ReferenceKind::of_head(head) else {
            panic!("a PNG is no reference")
        };
        let text = kind.to_string();
        assert!(!text.chars().any(|c| c.is_control()), "{text:?}");
        assert!(!text.contains(char::REPLACEMENT_CHARACTER), "{text:?}");
        assert!(text.contains("\\u{fffd}PNG"), "{text}");
        assert_eq!(first_line_number(head), Some(2));
    }
}
