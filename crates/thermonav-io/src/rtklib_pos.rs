//! RTKLIB solution files (`.pos`, the text output of `rnx2rtkp`, RTKPOST and RTKNAVI).
//!
//! ```text
//! %  GPST          latitude(deg) longitude(deg) height(m) Q  ns  sdn(m) sde(m) sdu(m) sdne(m) sdeu(m) sdun(m) age(s) ratio vn(m/s) ve(m/s) vu(m/s) sdvn …
//! 2025/07/08 19:34:18.499 40.0966268 -105.1474483 1601.4740000 1.0000000 21.0000000 0.0098995 …
//! ```
//! Lines starting with `%` are comments; the last one naming the position columns is the column
//! header, and data columns are found by those names (unknown names are ignored). Supported:
//! - position as `latitude(deg) longitude(deg) height(m)` (ellipsoidal), or as
//!   `x-ecef(m) y-ecef(m) z-ecef(m)` converted to geodetic WGS84;
//! - `Q` (1 fix, 2 float, 3 SBAS, 4 DGPS, 5 single, 6 PPP), `ns`;
//! - standard deviations `sdn sde sdu` (kept as north, east, down: the same values), or
//!   `sdx sdy sdz sdxy sdyz sdzx` rotated from ECEF into NED (RTKLIB writes each covariance
//!   as sign(c)·√|c|);
//! - velocities `vn ve vu` (up negated into down) or `vx vy vz` (ECEF, rotated into NED);
//!   velocity standard deviations are not kept ([`GnssFix`] has none).
//!
//! Not supported (clear errors): times in UTC or JST (the header says which), latitude and
//! longitude in degrees-minutes-seconds, and ENU baselines. A file without a column header is
//! read as the default latitude/longitude layout when its lines have 15 or 24 fields.
//!
//! Times are `yyyy/mm/dd hh:mm:ss.sss` or `week seconds-of-week`, both GPST, put on the GPST
//! scale of [`crate::gpst`] (seconds since 1970 counted in GPST, no leap seconds: the
//! convention of RTKLIB's `.tag` files).

use crate::Strictness;
use crate::error::{ReadError, ReadErrorKind};
use crate::fixed::{number, read_records, seconds, shown, split_blanks, whole_number};
use crate::gpst;
use std::io::BufRead;
use std::path::Path;
use thermonav::frames::Vector;
use thermonav::geo::position::Geodetic;
use thermonav::gnss::GnssFix;
use thermonav::time::{NANOS_PER_SECOND, Timestamp};
use thermonav::units::deg_to_rad;

/// One solution epoch: the fix and RTKLIB's quality flag and satellite count.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PosSolution {
    /// Position (and standard deviations and velocity when the file has them).
    pub fix: GnssFix,
    /// RTKLIB's `Q`: 1 fix, 2 float, 3 SBAS, 4 DGPS, 5 single, 6 PPP.
    pub quality: u8,
    /// Number of satellites (`ns`), when the file has the column.
    pub satellites: Option<u32>,
}

/// A set of quality flags `Q` (0–7) to keep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct QualitySet(u8);

impl QualitySet {
    /// Every solution.
    pub const ALL: QualitySet = QualitySet(u8::MAX);

    /// Only the flags listed (values above 7 are ignored).
    pub fn of(qualities: &[u8]) -> Self {
        Self(
            qualities
                .iter()
                .filter(|&&q| q < 8)
                .fold(0, |set, &q| set | (1 << q)),
        )
    }

    /// Whether solutions of quality `q` are kept.
    pub fn contains(self, q: u8) -> bool {
        q < 8 && self.0 & (1 << q) != 0
    }
}

/// How a `.pos` file is read.
#[derive(Debug, Clone, Copy)]
pub struct PosSettings {
    /// What happens to suspect values (NaN, latitude beyond ±90°, negative STD, time order).
    pub strictness: Strictness,
    /// Which solutions to keep; [`QualitySet::of`]`(&[1])` keeps fixed solutions only.
    pub qualities: QualitySet,
}

impl Default for PosSettings {
    fn default() -> Self {
        Self {
            strictness: Strictness::Strict,
            qualities: QualitySet::ALL,
        }
    }
}

/// Reads an RTKLIB `.pos` file from `reader` (named `input` in errors).
///
/// # Errors
/// [`ReadErrorKind::NoData`], an unsupported header (time system, DMS, ENU), a line with a
/// field count other than the header's, a bad date, time or number, NaN (strict), times that do
/// not increase (strict), each with its line.
pub fn read_rtklib_pos(
    reader: impl BufRead,
    input: impl Into<String>,
    settings: PosSettings,
) -> Result<Vec<PosSolution>, ReadError> {
    let mut columns: Option<Columns> = None;
    read_records(
        reader,
        input.into(),
        settings.strictness,
        EXPECTED,
        |line| {
            if let Some(comment) = line.strip_prefix(b"%") {
                if let Some(found) = Columns::from_header(comment)? {
                    columns = Some(found);
                }
                return Ok(None);
            }
            let fields = split_blanks(line);
            let layout = match &columns {
                Some(layout) => layout,
                None => columns.insert(Columns::default_for(fields.len())?),
            };
            let solution = layout.solution(&fields, settings.strictness)?;
            if settings.strictness == Strictness::Strict {
                crate::gnss::check_ranges(&solution.fix)?;
            }
            let keep = settings.qualities.contains(solution.quality);
            Ok(keep.then_some((solution.fix.time, solution)))
        },
    )
}

/// Reads an RTKLIB `.pos` file from `path`.
///
/// # Errors
/// As [`read_rtklib_pos`], plus [`ReadErrorKind::Open`].
pub fn read_rtklib_pos_file(
    path: impl AsRef<Path>,
    settings: PosSettings,
) -> Result<Vec<PosSolution>, ReadError> {
    let (file, input) = crate::open_file(path.as_ref())?;
    read_rtklib_pos(file, input, settings)
}

const EXPECTED: &str = "RTKLIB solution lines: date time position Q ns …";

/// Column names of RTKLIB's default latitude/longitude output, in its order.
const DEFAULT_NAMES: [&str; 22] = [
    "latitude(deg)",
    "longitude(deg)",
    "height(m)",
    "Q",
    "ns",
    "sdn(m)",
    "sde(m)",
    "sdu(m)",
    "sdne(m)",
    "sdeu(m)",
    "sdun(m)",
    "age(s)",
    "ratio",
    "vn(m/s)",
    "ve(m/s)",
    "vu(m/s)",
    "sdvn",
    "sdve",
    "sdvu",
    "sdvne",
    "sdveu",
    "sdvun",
];

/// Where the position is given.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Form {
    /// Latitude, longitude (degrees), ellipsoidal height.
    Geodetic,
    /// ECEF x, y, z.
    Ecef,
}

/// Field indices (0-based, the two time fields included) of the columns used.
#[derive(Debug, Clone)]
struct Columns {
    form: Form,
    count: usize,
    position: [usize; 3],
    quality: usize,
    satellites: Option<usize>,
    sd: Option<[usize; 3]>,
    /// ECEF cross terms sdxy, sdyz, sdzx.
    cross: Option<[usize; 3]>,
    velocity: Option<[usize; 3]>,
}

/// Fields before the first named column: date and time, or week and seconds.
const TIME_FIELDS: usize = 2;

impl Columns {
    /// The columns of a comment line when it is a column header, `None` for other comments.
    fn from_header(comment: &[u8]) -> Result<Option<Self>, ReadErrorKind> {
        let tokens = split_blanks(comment);
        let has = |name: &str| tokens.contains(&name.as_bytes());
        if has("latitude(d'\")") || has("e-baseline(m)") {
            return Err(ReadErrorKind::Unsupported {
                found: "a position in degrees-minutes-seconds or as an ENU baseline".into(),
                expected: "latitude(deg) or x-ecef(m) columns",
            });
        }
        if !(has("latitude(deg)") || has("x-ecef(m)")) {
            return Ok(None);
        }
        let Some((&system, names)) = tokens.split_first() else {
            return Ok(None);
        };
        if system != b"GPST" {
            return Err(ReadErrorKind::Unsupported {
                found: format!("time system \"{}\"", shown(system)),
                expected: "GPST (set RTKLIB's time system to GPST)",
            });
        }
        let names: Vec<&str> = names
            .iter()
            .map(|n| std::str::from_utf8(n).unwrap_or(""))
            .collect();
        Self::from_names(&names).map(Some)
    }

    /// RTKLIB's default latitude/longitude layout for a file without column header.
    fn default_for(fields: usize) -> Result<Self, ReadErrorKind> {
        match fields.checked_sub(TIME_FIELDS) {
            Some(named @ (13 | 22)) => Self::from_names(&DEFAULT_NAMES[..named]),
            _ => Err(ReadErrorKind::FieldCount {
                expected: TIME_FIELDS + 13,
                header: "no RTKLIB column header (% GPST latitude(deg) …) before the first \
                         solution, so 15 or 24 fields of the default layout"
                    .into(),
                found: fields,
            }),
        }
    }

    fn from_names(names: &[&str]) -> Result<Self, ReadErrorKind> {
        let find = |name: &str| {
            names
                .iter()
                .position(|n| *n == name)
                .map(|i| i + TIME_FIELDS)
        };
        let triple = |a: &str, b: &str, c: &str| Some([find(a)?, find(b)?, find(c)?]);
        let missing = |name: &'static str| ReadErrorKind::MissingColumn {
            name,
            alternatives: "",
        };
        let (form, position) = match triple("latitude(deg)", "longitude(deg)", "height(m)") {
            Some(position) => (Form::Geodetic, position),
            None => (
                Form::Ecef,
                triple("x-ecef(m)", "y-ecef(m)", "z-ecef(m)")
                    .ok_or_else(|| missing("latitude(deg) longitude(deg) height(m)"))?,
            ),
        };
        let (sd, cross, velocity) = match form {
            Form::Geodetic => (
                triple("sdn(m)", "sde(m)", "sdu(m)"),
                None,
                triple("vn(m/s)", "ve(m/s)", "vu(m/s)"),
            ),
            Form::Ecef => (
                triple("sdx(m)", "sdy(m)", "sdz(m)"),
                triple("sdxy(m)", "sdyz(m)", "sdzx(m)"),
                triple("vx(m/s)", "vy(m/s)", "vz(m/s)"),
            ),
        };
        Ok(Self {
            form,
            count: names.len() + TIME_FIELDS,
            position,
            quality: find("Q").ok_or_else(|| missing("Q"))?,
            satellites: find("ns"),
            sd,
            cross,
            velocity,
        })
    }

    /// Decodes one data line.
    fn solution(
        &self,
        fields: &[&[u8]],
        strictness: Strictness,
    ) -> Result<PosSolution, ReadErrorKind> {
        crate::fixed::expect_fields(
            fields,
            self.count,
            "the column header's names after the time",
        )?;
        let time = solution_time(fields)?;
        let value = |index: usize| number(fields, index, POS_COLUMN, strictness);
        let triple = |indices: [usize; 3]| -> Result<[f64; 3], ReadErrorKind> {
            Ok([value(indices[0])?, value(indices[1])?, value(indices[2])?])
        };
        let position = triple(self.position)?;
        let sd = self.sd.map(triple).transpose()?;
        let velocity = self.velocity.map(triple).transpose()?;
        let quality =
            whole_number(fields, self.quality, "Q", 7, "a quality flag from 0 to 7")? as u8;
        let satellites = match self.satellites {
            Some(index) => {
                Some(whole_number(fields, index, "ns", 999, "a number of satellites")? as u32)
            }
            None => None,
        };
        let fix = match self.form {
            Form::Geodetic => GnssFix {
                time,
                latitude_rad: deg_to_rad(position[0]),
                longitude_rad: deg_to_rad(position[1]),
                height_m: position[2],
                position_sd_ned_m: sd,
                velocity_ned_m_s: velocity.map(|[vn, ve, vu]| [vn, ve, -vu]),
                heading: None,
            },
            Form::Ecef => {
                let cross = self.cross.map(triple).transpose()?;
                ecef_fix(time, position, sd, cross, velocity)
            }
        };
        Ok(PosSolution {
            fix,
            quality,
            satellites,
        })
    }
}

/// Name given to value columns in messages (with the field number).
const POS_COLUMN: &str = "solution value";

/// The time of a solution line: `yyyy/mm/dd hh:mm:ss.sss` or `week seconds`, GPST.
fn solution_time(fields: &[&[u8]]) -> Result<Timestamp, ReadErrorKind> {
    if fields[0].contains(&b'/') {
        let days = calendar_days(fields[0])?;
        let nanos = nanos_of_day(fields[1])?;
        gpst::from_day_and_nanos(days, nanos).ok_or_else(|| bad_date(fields[0]))
    } else {
        let week = whole_number(fields, 0, "GPS week", 9_999, "a GPS week number")?;
        let seconds_of_week = seconds(fields, 1, "GPS seconds of week")?;
        gpst::from_week_and_nanos(week as i64, seconds_of_week.as_nanos())
            .ok_or_else(|| bad_date(fields[1]))
    }
}

/// Days since 1970-01-01 of `yyyy/mm/dd`.
fn calendar_days(field: &[u8]) -> Result<i64, ReadErrorKind> {
    let parts: Vec<Option<u32>> = field.split(|&b| b == b'/').map(small_integer).collect();
    match parts[..] {
        [Some(year), Some(month @ 1..=12), Some(day @ 1..=31)] if (1900..=2200).contains(&year) => {
            Ok(gpst::days_from_civil(i64::from(year), month, day))
        }
        _ => Err(bad_date(field)),
    }
}

/// Nanoseconds into the day of `hh:mm:ss.sss`.
fn nanos_of_day(field: &[u8]) -> Result<i64, ReadErrorKind> {
    let bad = || ReadErrorKind::BadField {
        index: 2,
        column: "time",
        expected: "hh:mm:ss.sss",
        found: shown(field),
    };
    let mut parts = field.splitn(3, |&b| b == b':');
    let (Some(hours), Some(minutes), Some(second_text)) =
        (parts.next(), parts.next(), parts.next())
    else {
        return Err(bad());
    };
    let (Some(hours @ 0..=23), Some(minutes @ 0..=59)) =
        (small_integer(hours), small_integer(minutes))
    else {
        return Err(bad());
    };
    let second = seconds(&[second_text], 0, "seconds").map_err(|_| bad())?;
    if !(0..61 * NANOS_PER_SECOND).contains(&second.as_nanos()) {
        return Err(bad());
    }
    Ok(i64::from(hours * 3600 + minutes * 60) * NANOS_PER_SECOND + second.as_nanos())
}

/// A field of 1 to 4 decimal digits.
fn small_integer(text: &[u8]) -> Option<u32> {
    let digits = !text.is_empty() && text.len() <= 4 && text.iter().all(u8::is_ascii_digit);
    digits.then(|| text.iter().fold(0, |n, &d| n * 10 + u32::from(d - b'0')))
}

fn bad_date(field: &[u8]) -> ReadErrorKind {
    ReadErrorKind::BadField {
        index: 1,
        column: "date",
        expected: "yyyy/mm/dd (or a GPS week)",
        found: shown(field),
    }
}

/// A fix from ECEF position, standard deviations (with cross terms) and velocity.
fn ecef_fix(
    time: Timestamp,
    position: [f64; 3],
    sd: Option<[f64; 3]>,
    cross: Option<[f64; 3]>,
    velocity: Option<[f64; 3]>,
) -> GnssFix {
    let geodetic = Geodetic::from_ecef(&Vector::from_array(position));
    // C_e^n is the transpose of C_n^e.
    let ned_to_ecef = geodetic.ned_to_ecef().matrix();
    let to_ned = |v: [f64; 3]| -> [f64; 3] {
        std::array::from_fn(|r| (0..3).map(|k| ned_to_ecef[k][r] * v[k]).sum())
    };
    let position_sd_ned_m = sd.map(|sd| {
        let covariance = ecef_covariance(sd, cross.unwrap_or_default());
        // Diagonal of C_e^n P C_n^e: element r is Σ_k Σ_l C_n^e[k][r] P[k][l] C_n^e[l][r].
        std::array::from_fn(|r| {
            let variance: f64 = (0..3)
                .flat_map(|k| (0..3).map(move |l| (k, l)))
                .map(|(k, l)| ned_to_ecef[k][r] * covariance[k][l] * ned_to_ecef[l][r])
                .sum();
            variance.max(0.0).sqrt()
        })
    });
    GnssFix {
        time,
        latitude_rad: geodetic.latitude_rad,
        longitude_rad: geodetic.longitude_rad,
        height_m: geodetic.height_m,
        position_sd_ned_m,
        velocity_ned_m_s: velocity.map(to_ned),
        heading: None,
    }
}

/// The ECEF covariance from RTKLIB's sdx, sdy, sdz and signed roots sdxy, sdyz, sdzx.
fn ecef_covariance(sd: [f64; 3], cross: [f64; 3]) -> [[f64; 3]; 3] {
    let variance = |s: f64| s * s.abs();
    let [xy, yz, zx] = cross.map(variance);
    [
        [sd[0] * sd[0], xy, zx],
        [xy, sd[1] * sd[1], yz],
        [zx, yz, sd[2] * sd[2]],
    ]
}
