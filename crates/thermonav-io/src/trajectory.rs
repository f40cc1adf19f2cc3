//! The canonical reference-trajectory CSV.
//!
//! ```text
//! t_s,lat_deg,lon_deg,h_m,vn_m_s,ve_m_s,vd_m_s,roll_deg,pitch_deg,yaw_deg
//! ```
//! Columns are found by name, in any order; all are required. Angles are degrees in the file
//! and radians in [`TrajectoryPoint`]. Under [`Strictness::Strict`] latitudes must lie within
//! ±90°.

use crate::Strictness;
use crate::atomic::write_atomically;
use crate::error::{ReadError, ReadErrorKind, WriteError};
use crate::finite::write_finite;
use crate::layout::{ColumnSpec, Layout, Schema, TIME_COLUMN, Unit};
use crate::rows::Rows;
use crate::text::{degrees_reading_back_exactly, write_time};
use std::io::{BufRead, Write};
use std::path::Path;
use thermonav::time::Timestamp;
use thermonav::trajectory::TrajectoryPoint;

const fn spec(name: &'static str, slot: usize, unit: Unit) -> ColumnSpec {
    ColumnSpec { name, slot, unit }
}

/// Every trajectory column (besides `t_s`), in canonical order; slot = position here.
const COLUMNS: [ColumnSpec; 9] = [
    spec("lat_deg", 0, Unit::Deg),
    spec("lon_deg", 1, Unit::Deg),
    spec("h_m", 2, Unit::Si),
    spec("vn_m_s", 3, Unit::Si),
    spec("ve_m_s", 4, Unit::Si),
    spec("vd_m_s", 5, Unit::Si),
    spec("roll_deg", 6, Unit::Deg),
    spec("pitch_deg", 7, Unit::Deg),
    spec("yaw_deg", 8, Unit::Deg),
];

const SCHEMA: Schema = Schema {
    columns: &COLUMNS,
    expected: "t_s, lat_deg, lon_deg, h_m, vn_m_s, ve_m_s, vd_m_s, roll_deg, pitch_deg, yaw_deg",
    time_alternatives: "",
};

/// Streaming reader of the canonical trajectory CSV: an iterator of points (SI, radians).
///
/// Holds one line buffer whatever the file size. After an error the iterator ends.
pub struct TrajectoryReader<R> {
    rows: Rows<R>,
}

impl TrajectoryReader<crate::FileReader> {
    /// Opens `path` and reads its header.
    ///
    /// # Errors
    /// As [`TrajectoryReader::new`], plus [`ReadErrorKind::Open`].
    pub fn open(path: impl AsRef<Path>, strictness: Strictness) -> Result<Self, ReadError> {
        let (file, input) = crate::open_file(path.as_ref())?;
        Self::new(file, input, strictness)
    }
}

impl<R: BufRead> TrajectoryReader<R> {
    /// Reads the header of `reader`; `input` names it in errors (usually the file path).
    ///
    /// # Errors
    /// [`ReadErrorKind::Empty`], an unknown, repeated or missing column, or a read failure.
    pub fn new(
        reader: R,
        input: impl Into<String>,
        strictness: Strictness,
    ) -> Result<Self, ReadError> {
        let rows = Rows::open(reader, input.into(), &SCHEMA, strictness)?;
        require_all(rows.layout()).map_err(|kind| rows.header_error(kind))?;
        Ok(Self { rows })
    }
}

fn require_all(layout: &Layout) -> Result<(), ReadErrorKind> {
    COLUMNS
        .iter()
        .try_for_each(|column| layout.require(column.slot, column.name, ""))
}

impl<R: BufRead> Iterator for TrajectoryReader<R> {
    type Item = Result<TrajectoryPoint, ReadError>;

    fn next(&mut self) -> Option<Self::Item> {
        let point = match self.rows.next_row()? {
            Ok((time, values)) => point_from_row(time, values),
            Err(error) => return Some(Err(error)),
        };
        if self.rows.strictness() == Strictness::Strict {
            if let Err(kind) = crate::check_latitude(point.latitude_rad) {
                return Some(Err(self.rows.row_error(kind)));
            }
        }
        Some(Ok(point))
    }
}

fn point_from_row(time: Timestamp, v: &[f64]) -> TrajectoryPoint {
    TrajectoryPoint {
        time,
        latitude_rad: v[0],
        longitude_rad: v[1],
        height_m: v[2],
        velocity_ned_m_s: [v[3], v[4], v[5]],
        roll_rad: v[6],
        pitch_rad: v[7],
        yaw_rad: v[8],
    }
}

/// Reads a whole trajectory CSV from `reader` (named `input` in errors).
///
/// # Errors
/// Any [`ReadError`] of [`TrajectoryReader`], and [`ReadErrorKind::HeaderOnly`] for a file
/// without data rows.
pub fn read_trajectory(
    reader: impl BufRead,
    input: impl Into<String>,
    strictness: Strictness,
) -> Result<Vec<TrajectoryPoint>, ReadError> {
    TrajectoryReader::new(reader, input, strictness)?.collect()
}

/// Reads a whole trajectory CSV file.
///
/// # Errors
/// As [`read_trajectory`], plus [`ReadErrorKind::Open`].
pub fn read_trajectory_file(
    path: impl AsRef<Path>,
    strictness: Strictness,
) -> Result<Vec<TrajectoryPoint>, ReadError> {
    TrajectoryReader::open(path, strictness)?.collect()
}

/// Writes points as a canonical trajectory CSV. Angles are written in the degree value that
/// reads back to the same radians.
///
/// # Errors
/// [`WriteError::Empty`] for no point, [`WriteError::Io`].
pub fn write_trajectory(mut out: impl Write, points: &[TrajectoryPoint]) -> Result<(), WriteError> {
    if points.is_empty() {
        return Err(WriteError::Empty { what: "points" });
    }
    write_trajectory_header(&mut out)?;
    for point in points {
        write_trajectory_point(&mut out, point)?;
    }
    out.flush()?;
    Ok(())
}

/// The header line of [`write_trajectory`].
///
/// # Errors
/// [`WriteError::Io`].
pub fn write_trajectory_header(out: &mut impl Write) -> Result<(), WriteError> {
    out.write_all(TIME_COLUMN.as_bytes())?;
    for column in &COLUMNS {
        out.write_all(b",")?;
        out.write_all(column.name.as_bytes())?;
    }
    out.write_all(b"\n")?;
    Ok(())
}

/// Writes points to `path` atomically (see [`write_atomically`]).
///
/// # Errors
/// As [`write_trajectory`], wrapped with the path, plus the errors of [`write_atomically`].
pub fn write_trajectory_file(
    path: impl AsRef<Path>,
    points: &[TrajectoryPoint],
) -> Result<(), WriteError> {
    write_atomically(path, |file| write_trajectory(file, points))
}

/// One point's line of [`write_trajectory`].
///
/// # Errors
/// [`WriteError::Io`].
pub fn write_trajectory_point(out: &mut impl Write, p: &TrajectoryPoint) -> Result<(), WriteError> {
    write_time(out, p.time)?;
    for value in trajectory_values(p) {
        out.write_all(b",")?;
        write_finite(out, value)?;
    }
    out.write_all(b"\n")?;
    Ok(())
}

/// The names of the columns after `t_s`, in file order (`lat_deg` .. `yaw_deg`).
pub fn trajectory_column_names() -> [&'static str; 9] {
    COLUMNS.map(|c| c.name)
}

/// A point's values in the columns of [`trajectory_column_names`] and their units, as
/// written (angles in the degrees that read back to the same radians).
pub fn trajectory_values(p: &TrajectoryPoint) -> [f64; 9] {
    [
        degrees_reading_back_exactly(p.latitude_rad),
        degrees_reading_back_exactly(p.longitude_rad),
        p.height_m,
        p.velocity_ned_m_s[0],
        p.velocity_ned_m_s[1],
        p.velocity_ned_m_s[2],
        degrees_reading_back_exactly(p.roll_rad),
        degrees_reading_back_exactly(p.pitch_rad),
        degrees_reading_back_exactly(p.yaw_rad),
    ]
}
