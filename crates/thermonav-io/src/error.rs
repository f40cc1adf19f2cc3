//! Errors of the readers and writers.

use crate::text::SecondsText;
use std::io;
use thermonav::time::Timestamp;

/// A file (or stream) that could not be read, with where and why.
///
/// Displays as `input:line: what`, e.g.
/// `data/imu.csv:17: expected 8 fields (t_s,gx_rad_s,…,temp_c), found 6`, or as `input: what`
/// when the problem is not tied to one line (`data/imu.csv: header only, no data rows`).
/// Line numbers are 1-based and count every physical line: header, data and blank lines.
#[derive(Debug, thiserror::Error)]
#[error("{input}{}: {kind}", LineSuffix(*.line))]
pub struct ReadError {
    /// Name of the input, as given to the reader (usually the file path).
    pub input: String,
    /// 1-based line number, when the problem is on one line.
    pub line: Option<u64>,
    /// What went wrong.
    pub kind: ReadErrorKind,
}

impl ReadError {
    /// A new error about `input`, at `line` when known.
    pub fn new(input: impl Into<String>, line: Option<u64>, kind: ReadErrorKind) -> Self {
        Self {
            input: input.into(),
            line,
            kind,
        }
    }
}

/// Prints `:17` for a line number and nothing otherwise.
struct LineSuffix(Option<u64>);

impl std::fmt::Display for LineSuffix {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.0 {
            Some(line) => write!(f, ":{line}"),
            None => Ok(()),
        }
    }
}

/// Why an input could not be read.
#[derive(Debug, thiserror::Error)]
pub enum ReadErrorKind {
    /// The file could not be opened.
    #[error("cannot open: {0}")]
    Open(io::Error),
    /// Reading failed part-way.
    #[error("read failed: {0}")]
    Read(io::Error),
    /// No line at all (or only blank lines).
    #[error("file is empty (expected a header line)")]
    Empty,
    /// A header line and nothing else.
    #[error("header only, no data rows")]
    HeaderOnly,
    /// The header line is not UTF-8 text.
    #[error(
        "header line is not valid UTF-8 text (expected comma-separated column names such as t_s)"
    )]
    HeaderNotUtf8,
    /// A line has no end within the limit (not a text file, or a broken one).
    #[error("line longer than {limit_bytes} bytes")]
    LineTooLong {
        /// The longest line accepted, bytes.
        limit_bytes: u64,
    },
    /// A header name that the format does not know.
    #[error("unknown column \"{name}\" (expected one of {expected}){hint}")]
    UnknownColumn {
        /// The name found in the header.
        name: String,
        /// The names the format accepts.
        expected: &'static str,
        /// When the header is another of our CSVs (IMU, GNSS, trajectory): ": this looks like
        /// a GNSS CSV: was it meant for --gnss?"; else empty.
        hint: String,
    },
    /// Two header names give the same quantity (`gx_rad_s` and `gx_deg_s`, or `t_s` twice).
    #[error("columns {first} and {second} give the same quantity")]
    DuplicateColumn {
        /// The first of the two names.
        first: String,
        /// The second of the two names.
        second: String,
    },
    /// A required column is absent from the header.
    #[error("missing column {name}{alternatives}")]
    MissingColumn {
        /// Canonical name of the column.
        name: &'static str,
        /// Other accepted names, as ` (or …)`, or empty.
        alternatives: &'static str,
    },
    /// A sample rate was given for a file that has a time column.
    #[error(
        "the file has a t_s column and a sample rate of {rate_hz} Hz was given: times come from one source (the column, or the rate for a file without times)"
    )]
    TimeColumnWithRate {
        /// The rate given, Hz.
        rate_hz: f64,
    },
    /// Some of the six IMU channels are absent where all six are needed.
    #[error("missing column{} {}: all six channels gx..az are needed here (only the static analyses, characterize and allan, take a subset)", if missing.len() == 1 { "" } else { "s" }, missing.join(", "))]
    MissingChannels {
        /// Canonical names of the absent channel columns, each with its other accepted names.
        missing: Vec<String>,
    },
    /// Roll, pitch and yaw asked of a sensor with only some of its three axes.
    #[error(
        "channel {channel}: an rpy rotation mixes a sensor's three axes, and the file has only some of them: give an axis mapping (such as -y,x,z), or all three axes"
    )]
    RotationOfPartialTriad {
        /// A channel of the incomplete sensor.
        channel: &'static str,
    },
    /// An IMU header mixes rate and increment columns.
    #[error(
        "column {rate_column} is a rate but {increment_column} is an increment (one file holds one kind)"
    )]
    MixedKinds {
        /// A rate column of the header.
        rate_column: String,
        /// An increment column of the header.
        increment_column: String,
    },
    /// An optional group of columns is only partly present.
    #[error("incomplete column group {group}: has {present} but not {missing}")]
    PartialGroup {
        /// The group's columns.
        group: &'static str,
        /// One column of the group that is present.
        present: String,
        /// One column of the group that is absent.
        missing: &'static str,
    },
    /// A data line has more or fewer fields than the header.
    #[error("expected {expected} fields ({header}), found {found}")]
    FieldCount {
        /// Number of header columns.
        expected: usize,
        /// The header line.
        header: String,
        /// Number of fields on the line.
        found: usize,
    },
    /// A field is not a number.
    #[error("column {column}: expected a number, found \"{found}\"")]
    NotANumber {
        /// Header name of the column.
        column: String,
        /// The field's text.
        found: String,
    },
    /// A time field is not a finite number of seconds within ±9.2e9 s.
    #[error(
        "column {column}: expected a finite time in seconds within ±9.2e9 s, found \"{found}\""
    )]
    BadTime {
        /// Header name of the column.
        column: String,
        /// The field's text.
        found: String,
    },
    /// A NaN or infinite value, rejected under [`crate::Strictness::Strict`].
    #[error("column {column}: value \"{found}\" is not finite (strict reading)")]
    NonFinite {
        /// Header name of the column.
        column: String,
        /// The field's text.
        found: String,
    },
    /// A finite value too large for any reading, rejected under [`crate::Strictness::Strict`].
    #[error(
        "column {column}: value \"{found}\" is too large (expected a magnitude of at most 1e15; strict reading)"
    )]
    TooLarge {
        /// Header name of the column.
        column: String,
        /// The field's text.
        found: String,
    },
    /// A value outside its physical range, rejected under [`crate::Strictness::Strict`].
    #[error("column {column}: value {found} is out of range (expected {expected}; strict reading)")]
    OutOfRange {
        /// Header name of the column.
        column: &'static str,
        /// The value, in the file's unit.
        found: f64,
        /// The accepted range.
        expected: &'static str,
    },
    /// A time not after the previous one, rejected under [`crate::Strictness::Strict`].
    #[error(
        "time {} s does not increase after {} s on line {previous_line} (strict reading)",
        SecondsText(*.current), SecondsText(*.previous)
    )]
    NonIncreasingTime {
        /// Time on the previous data line.
        previous: Timestamp,
        /// Line number of the previous data line.
        previous_line: u64,
        /// Time on this line.
        current: Timestamp,
    },
    /// A headerless format with no data line at all.
    #[error("no data (expected {expected})")]
    NoData {
        /// What the format's lines hold.
        expected: &'static str,
    },
    /// A field of a fixed-layout line that is not what the format expects there.
    #[error("field {index} ({column}): expected {expected}, found \"{found}\"")]
    BadField {
        /// 1-based position of the field on the line.
        index: usize,
        /// The format's name for the field.
        column: &'static str,
        /// What the field should hold.
        expected: &'static str,
        /// The field's text (cut to 40 characters).
        found: String,
    },
    /// A variant of a format that this reader does not implement.
    #[error("{found} is not supported (expected {expected})")]
    Unsupported {
        /// What was found.
        found: String,
        /// What the reader accepts.
        expected: &'static str,
    },
    /// An NMEA sentence whose checksum does not match its characters, or that has none.
    #[error(
        "NMEA checksum: the sentence ends in \"{given}\" but its characters give *{computed:02X}"
    )]
    Checksum {
        /// The text after `*` (empty when the sentence has no checksum).
        given: String,
        /// XOR of the characters between `$` and `*`.
        computed: u8,
    },
    /// A binary file whose bytes are not what the format expects at some offset.
    #[error("at byte {offset}: expected {expected}")]
    BadBinary {
        /// Offset of the problem from the start of the file, bytes.
        offset: u64,
        /// What the format has there.
        expected: &'static str,
    },
    /// Accelerations whose mean magnitude is near 1 where the header declares m/s² (or m/s
    /// increments): values in g under an SI column name, rejected under strict reading.
    #[error(
        "mean |a| over the {samples} samples is {mean_m_s2:.3} m/s^2, near 1: the accelerations \
         look like they are in g (expected m/s^2, about 9.81 at rest; name the columns \
         ax_g,ay_g,az_g for values in g)"
    )]
    AccelerationInG {
        /// Samples averaged.
        samples: usize,
        /// Mean magnitude of the specific force, in the unit the header declares.
        mean_m_s2: f64,
    },
    /// The input, taken as a whole, cannot be used; the text says why and what is needed.
    #[error("{0}")]
    Unusable(String),
}

/// Why a file or stream could not be written.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// The temporary file beside the target could not be created.
    #[error("{path}: cannot create a temporary file beside it: {source}")]
    CreateTemporary {
        /// The target path.
        path: String,
        /// The system's reason.
        source: io::Error,
    },
    /// The finished temporary file could not be flushed, synced or renamed onto the target.
    #[error("{path}: cannot move the finished temporary file into place: {source}")]
    Commit {
        /// The target path.
        path: String,
        /// The system's reason.
        source: io::Error,
    },
    /// Writing a given file failed; the target was left untouched.
    #[error("{path}: {source}")]
    InFile {
        /// The target path.
        path: String,
        /// What went wrong.
        source: Box<WriteError>,
    },
    /// The underlying writer failed.
    #[error("write failed: {0}")]
    Io(#[from] io::Error),
    /// JSON encoding failed.
    #[error("JSON encoding failed: {0}")]
    Json(#[from] serde_json::Error),
    /// Nothing to write: a file with a header and no rows could not be read back.
    #[error("nothing to write: no {what}")]
    Empty {
        /// What there is none of (`samples`, `fixes`, `points`).
        what: &'static str,
    },
    /// An IMU series whose kind (rates or increments) is not set.
    #[error("IMU series has no sample kind (rates or increments)")]
    UnknownKind,
    /// A column of a series whose length differs from the time axis.
    #[error("column {column} has {len} values but the time axis has {expected}")]
    RaggedColumn {
        /// Name of the column.
        column: &'static str,
        /// Its length.
        len: usize,
        /// Length of the time axis.
        expected: usize,
    },
    /// A sample without temperature written to a file with a `temp_c` column.
    #[error("sample {index} has no temperature but the file has a temp_c column")]
    MissingTemperature {
        /// 0-based index of the sample.
        index: usize,
    },
    /// A time that cannot be written as the format's seconds of week.
    #[error("record {index} at {time_s} s: expected {expected}")]
    WeekTime {
        /// 0-based index of the record.
        index: usize,
        /// Its time, s.
        time_s: f64,
        /// What the format expects.
        expected: &'static str,
    },
    /// A fix without the position standard deviation the format needs.
    #[error(
        "fix {index} has no position standard deviation (KF-GINS's GNSS file needs sdn sde sdd: give the GNSS CSV sd_n_m,sd_e_m,sd_u_m)"
    )]
    MissingPositionSd {
        /// 0-based index of the fix.
        index: usize,
    },
    /// GNSS fixes that do not all carry the same optional groups.
    #[error("fix {index} {presence} the {group} group, unlike fix 0")]
    InconsistentGroup {
        /// The group's columns.
        group: &'static str,
        /// 0-based index of the first fix that differs.
        index: usize,
        /// `has` or `lacks`.
        presence: &'static str,
    },
}
