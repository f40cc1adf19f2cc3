//! The canonical GNSS CSV.
//!
//! ```text
//! t_s,lat_deg,lon_deg,h_m[,sd_n_m,sd_e_m,sd_u_m][,vn_m_s,ve_m_s,vd_m_s][,heading_deg,sd_heading_deg]
//! ```
//! Columns are found by name, in any order. Each optional group is all-or-nothing. Angles are
//! degrees in the file and radians in [`GnssFix`]. Under [`Strictness::Strict`] latitudes must
//! lie within ±90° and standard deviations must not be negative.

use crate::Strictness;
use crate::atomic::write_atomically;
use crate::error::{ReadError, ReadErrorKind, WriteError};
use crate::finite::write_finite;
use crate::layout::{ColumnSpec, Layout, Presence, Schema, TIME_COLUMN, Unit};
use crate::rows::Rows;
use crate::text::{degrees_reading_back_exactly, write_time};
use std::io::{BufRead, Write};
use std::path::Path;
use thermonav::gnss::{GnssFix, HeadingObservation};

const LAT: usize = 0;
const LON: usize = 1;
const HEIGHT: usize = 2;
const SD_N: usize = 3;
const VN: usize = 6;
const HEADING: usize = 9;
const SD_HEADING: usize = 10;

const fn spec(name: &'static str, slot: usize, unit: Unit) -> ColumnSpec {
    ColumnSpec { name, slot, unit }
}

/// Every GNSS column (besides `t_s`), in canonical order.
const COLUMNS: [ColumnSpec; 11] = [
    spec("lat_deg", LAT, Unit::Deg),
    spec("lon_deg", LON, Unit::Deg),
    spec("h_m", HEIGHT, Unit::Si),
    spec("sd_n_m", SD_N, Unit::Si),
    spec("sd_e_m", SD_N + 1, Unit::Si),
    spec("sd_u_m", SD_N + 2, Unit::Si),
    spec("vn_m_s", VN, Unit::Si),
    spec("ve_m_s", VN + 1, Unit::Si),
    spec("vd_m_s", VN + 2, Unit::Si),
    spec("heading_deg", HEADING, Unit::Deg),
    spec("sd_heading_deg", SD_HEADING, Unit::Deg),
];

const SCHEMA: Schema = Schema {
    columns: &COLUMNS,
    expected: "t_s, lat_deg, lon_deg, h_m, sd_n_m, sd_e_m, sd_u_m, vn_m_s, ve_m_s, vd_m_s, \
               heading_deg, sd_heading_deg",
    time_alternatives: "",
};

/// The optional groups: name as told to the user, and member columns.
const SD_GROUP: &str = "sd_n_m,sd_e_m,sd_u_m";
const VELOCITY_GROUP: &str = "vn_m_s,ve_m_s,vd_m_s";
const HEADING_GROUP: &str = "heading_deg,sd_heading_deg";

fn members(first: usize, count: usize) -> Vec<(usize, &'static str)> {
    COLUMNS[first..first + count]
        .iter()
        .map(|c| (c.slot, c.name))
        .collect()
}

/// Which optional groups a GNSS file has.
#[derive(Debug, Clone, Copy)]
struct Groups {
    position_sd: Presence,
    velocity: Presence,
    heading: Presence,
}

/// Streaming reader of the canonical GNSS CSV: an iterator of fixes (SI, radians).
///
/// Holds one line buffer whatever the file size. After an error the iterator ends.
pub struct GnssReader<R> {
    rows: Rows<R>,
    groups: Groups,
}

impl GnssReader<crate::FileReader> {
    /// Opens `path` and reads its header.
    ///
    /// # Errors
    /// As [`GnssReader::new`], plus [`ReadErrorKind::Open`].
    pub fn open(path: impl AsRef<Path>, strictness: Strictness) -> Result<Self, ReadError> {
        let (file, input) = crate::open_file(path.as_ref())?;
        Self::new(file, input, strictness)
    }
}

impl<R: BufRead> GnssReader<R> {
    /// Reads the header of `reader`; `input` names it in errors (usually the file path).
    ///
    /// # Errors
    /// [`ReadErrorKind::Empty`], an unknown, repeated or missing column, a partial optional
    /// group, or a read failure.
    pub fn new(
        reader: R,
        input: impl Into<String>,
        strictness: Strictness,
    ) -> Result<Self, ReadError> {
        let rows = Rows::open(reader, input.into(), &SCHEMA, strictness)?;
        let groups = groups_of(rows.layout()).map_err(|kind| rows.header_error(kind))?;
        Ok(Self { rows, groups })
    }
}

fn groups_of(layout: &Layout) -> Result<Groups, ReadErrorKind> {
    layout.require(LAT, "lat_deg", "")?;
    layout.require(LON, "lon_deg", "")?;
    layout.require(HEIGHT, "h_m", "")?;
    Ok(Groups {
        position_sd: layout.group_presence(SD_GROUP, &members(SD_N, 3))?,
        velocity: layout.group_presence(VELOCITY_GROUP, &members(VN, 3))?,
        heading: layout.group_presence(HEADING_GROUP, &members(HEADING, 2))?,
    })
}

impl<R: BufRead> Iterator for GnssReader<R> {
    type Item = Result<GnssFix, ReadError>;

    fn next(&mut self) -> Option<Self::Item> {
        let groups = self.groups;
        let fix = match self.rows.next_row()? {
            Ok((time, v)) => fix_from_row(time, v, groups),
            Err(error) => return Some(Err(error)),
        };
        if self.rows.strictness() == Strictness::Strict {
            if let Err(kind) = check_ranges(&fix) {
                return Some(Err(self.rows.row_error(kind)));
            }
        }
        Some(Ok(fix))
    }
}

fn fix_from_row(time: thermonav::time::Timestamp, v: &[f64], groups: Groups) -> GnssFix {
    let triple = |first: usize| [v[first], v[first + 1], v[first + 2]];
    GnssFix {
        time,
        latitude_rad: v[LAT],
        longitude_rad: v[LON],
        height_m: v[HEIGHT],
        position_sd_ned_m: (groups.position_sd == Presence::Present).then(|| triple(SD_N)),
        velocity_ned_m_s: (groups.velocity == Presence::Present).then(|| triple(VN)),
        heading: (groups.heading == Presence::Present).then_some(HeadingObservation {
            heading_rad: v[HEADING],
            sd_rad: v[SD_HEADING],
        }),
    }
}

/// Strict checks: latitude within ±90°, height within the navigable range, standard
/// deviations positive.
pub(crate) fn check_ranges(fix: &GnssFix) -> Result<(), ReadErrorKind> {
    crate::check_latitude(fix.latitude_rad)?;
    check_height(fix.height_m)?;
    let sd_names = ["sd_n_m", "sd_e_m", "sd_u_m"];
    if let Some(sds) = fix.position_sd_ned_m {
        if let Some((&found, column)) = sds.iter().zip(sd_names).find(|(sd, _)| **sd <= 0.0) {
            return Err(negative_sd(column, found));
        }
    }
    match fix.heading {
        Some(h) if h.sd_rad <= 0.0 => Err(negative_sd(
            "sd_heading_deg",
            degrees_reading_back_exactly(h.sd_rad),
        )),
        _ => Ok(()),
    }
}

/// Heights a GNSS/INS navigates at: the deepest ocean to 100 km (the edge of space); a normal
/// gravity and the Earth's radii hold there, and a typo such as 1e300 never reaches the filter.
fn check_height(height_m: f64) -> Result<(), ReadErrorKind> {
    match (-12_000.0..=100_000.0).contains(&height_m) {
        true => Ok(()),
        false => Err(ReadErrorKind::OutOfRange {
            column: "h_m",
            found: height_m,
            expected: "-12000 to 100000 m",
        }),
    }
}

fn negative_sd(column: &'static str, found: f64) -> ReadErrorKind {
    ReadErrorKind::OutOfRange {
        column,
        found,
        expected: "a standard deviation > 0 (a fix of zero spread would be trusted without limit)",
    }
}

/// Reads a whole GNSS CSV from `reader` (named `input` in errors).
///
/// # Errors
/// Any [`ReadError`] of [`GnssReader`], and [`ReadErrorKind::HeaderOnly`] for a file without
/// data rows.
pub fn read_gnss(
    reader: impl BufRead,
    input: impl Into<String>,
    strictness: Strictness,
) -> Result<Vec<GnssFix>, ReadError> {
    GnssReader::new(reader, input, strictness)?.collect()
}

/// Reads a whole GNSS CSV file.
///
/// # Errors
/// As [`read_gnss`], plus [`ReadErrorKind::Open`].
pub fn read_gnss_file(
    path: impl AsRef<Path>,
    strictness: Strictness,
) -> Result<Vec<GnssFix>, ReadError> {
    GnssReader::open(path, strictness)?.collect()
}

/// Writes fixes as a canonical GNSS CSV. An optional group is written when the first fix has
/// it; every fix must then have the same groups. Angles are written in the degree value that
/// reads back to the same radians.
///
/// # Errors
/// [`WriteError::Empty`] for no fix, [`WriteError::InconsistentGroup`], [`WriteError::Io`].
pub fn write_gnss(mut out: impl Write, fixes: &[GnssFix]) -> Result<(), WriteError> {
    let first = fixes.first().ok_or(WriteError::Empty { what: "fixes" })?;
    let shape = Groups::of(first);
    out.write_all(shape.header().as_bytes())?;
    for (index, fix) in fixes.iter().enumerate() {
        shape.check(fix, index)?;
        write_fix(&mut out, fix)?;
    }
    out.flush()?;
    Ok(())
}

/// Drops from every fix the optional groups that some fix lacks, so that the fixes can be
/// written as one file (foreign formats give velocity or heading only at some epochs); returns
/// the names of the dropped groups.
pub fn keep_common_groups(fixes: &mut [GnssFix]) -> Vec<&'static str> {
    let every = |has: fn(&GnssFix) -> bool| fixes.iter().all(has);
    let keep_sd = every(|f| f.position_sd_ned_m.is_some());
    let keep_velocity = every(|f| f.velocity_ned_m_s.is_some());
    let keep_heading = every(|f| f.heading.is_some());
    let some = |has: fn(&GnssFix) -> bool| fixes.iter().any(has);
    let dropped: Vec<&'static str> = [
        (
            keep_sd || !some(|f| f.position_sd_ned_m.is_some()),
            SD_GROUP,
        ),
        (
            keep_velocity || !some(|f| f.velocity_ned_m_s.is_some()),
            VELOCITY_GROUP,
        ),
        (
            keep_heading || !some(|f| f.heading.is_some()),
            HEADING_GROUP,
        ),
    ]
    .into_iter()
    .filter_map(|(fine, group)| (!fine).then_some(group))
    .collect();
    for fix in fixes.iter_mut() {
        fix.position_sd_ned_m = fix.position_sd_ned_m.filter(|_| keep_sd);
        fix.velocity_ned_m_s = fix.velocity_ned_m_s.filter(|_| keep_velocity);
        fix.heading = fix.heading.filter(|_| keep_heading);
    }
    dropped
}

/// Writes fixes to `path` atomically (see [`write_atomically`]).
///
/// # Errors
/// As [`write_gnss`], wrapped with the path, plus the errors of [`write_atomically`].
pub fn write_gnss_file(path: impl AsRef<Path>, fixes: &[GnssFix]) -> Result<(), WriteError> {
    write_atomically(path, |file| write_gnss(file, fixes))
}

impl Groups {
    fn of(fix: &GnssFix) -> Self {
        let presence = |present: bool| match present {
            true => Presence::Present,
            false => Presence::Absent,
        };
        Self {
            position_sd: presence(fix.position_sd_ned_m.is_some()),
            velocity: presence(fix.velocity_ned_m_s.is_some()),
            heading: presence(fix.heading.is_some()),
        }
    }

    /// Each group's presence and column names.
    fn listed(self) -> [(Presence, &'static str); 3] {
        [
            (self.position_sd, SD_GROUP),
            (self.velocity, VELOCITY_GROUP),
            (self.heading, HEADING_GROUP),
        ]
    }

    fn header(self) -> String {
        let mut header = format!("{TIME_COLUMN},lat_deg,lon_deg,h_m");
        for (_, group) in self
            .listed()
            .into_iter()
            .filter(|(p, _)| *p == Presence::Present)
        {
            header.push(',');
            header.push_str(group);
        }
        header.push('\n');
        header
    }

    /// Fails when `fix` carries other groups than these.
    fn check(self, fix: &GnssFix, index: usize) -> Result<(), WriteError> {
        let differing = self
            .listed()
            .into_iter()
            .zip(Groups::of(fix).listed())
            .find(|((expected, _), (found, _))| expected != found);
        match differing {
            None => Ok(()),
            Some((_, (found, group))) => Err(WriteError::InconsistentGroup {
                group,
                index,
                presence: match found {
                    Presence::Present => "has",
                    Presence::Absent => "lacks",
                },
            }),
        }
    }
}

fn write_fix(out: &mut impl Write, fix: &GnssFix) -> Result<(), WriteError> {
    write_time(out, fix.time)?;
    let position = [
        degrees_reading_back_exactly(fix.latitude_rad),
        degrees_reading_back_exactly(fix.longitude_rad),
        fix.height_m,
    ];
    let heading = fix.heading.map(|h| {
        [
            degrees_reading_back_exactly(h.heading_rad),
            degrees_reading_back_exactly(h.sd_rad),
        ]
    });
    let optional = fix.position_sd_ned_m.iter().flatten();
    let optional = optional.chain(fix.velocity_ned_m_s.iter().flatten());
    for &value in position
        .iter()
        .chain(optional)
        .chain(heading.iter().flatten())
    {
        out.write_all(b",")?;
        write_finite(out, value)?;
    }
    out.write_all(b"\n")?;
    Ok(())
}
