//! # thermonav-io
//!
//! File formats of thermonav. Readers take `impl BufRead` (plus a display name used in error
//! messages) and return library types; writers never leave a partial file behind.
//!
//! ## Canonical CSVs
//! One header line of unit-suffixed names, then one comma-separated line per record. Columns
//! are found by name, in any order; unknown names are errors. Values are converted to SI once,
//! as they are read, through [`thermonav::units`]; writers use the SI (or degree) names below
//! and print every number so that it reads back to the same bits.
//! - IMU ([`imu`]): `t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2[,temp_c]`, or the
//!   increments `dthx_rad,…,dvz_m_s`; other units accepted on reading.
//! - GNSS ([`gnss`]): `t_s,lat_deg,lon_deg,h_m` plus optional groups
//!   `sd_n_m,sd_e_m,sd_u_m`, `vn_m_s,ve_m_s,vd_m_s`, `heading_deg,sd_heading_deg`.
//! - Reference trajectory ([`trajectory`]):
//!   `t_s,lat_deg,lon_deg,h_m,vn_m_s,ve_m_s,vd_m_s,roll_deg,pitch_deg,yaw_deg`.
//!
//! Lines may end in `\n` or `\r\n`. Blank lines are skipped wherever they are, but counted, so
//! the line numbers in errors are those an editor shows. Times in `t_s` are read digit by digit
//! into integer nanoseconds and written back with nine decimals: no time is ever rounded
//! through an `f64` (except one written in scientific notation, which is rare for times).
//!
//! ## Foreign formats
//! Readers of other tools' files, returning the same library types (the `thermonav convert`
//! command writes them out as canonical CSVs):
//! - [`rtklib_pos`]: RTKLIB solutions (`.pos`), latitude/longitude or ECEF form, `Q` filter;
//! - [`nmea`]: NMEA 0183 GGA, RMC, VTG, HDT, THS with checksums, combined per epoch;
//! - [`kf_gins`]: KF-GINS IMU increments, GNSS positions and `.nav` trajectories (and their
//!   writers, [`kf_gins_write`]);
//! - [`outside_solution`]: KF-GINS, RTKLIB and our own solutions read as trajectories, to score
//!   other tools beside ours;
//! - [`reference`](mod@reference): a reference trajectory from our trajectory or GNSS CSV, an RTKLIB `.pos`
//!   or a KF-GINS `.nav`, the kind told by the content;
//! - [`raw_imu`]: raw IMU CSV timed by its RTKLIB time-tag file (`.tag`);
//! - [`ulog`]: PX4 ULog (`.ulg`): any topic by field name, and the IMU (with temperature) and
//!   GNSS of a flight log ([`ulog::px4`]);
//! - [`ros`]: ROS 2 bags (MCAP and SQLite `.db3`) and ROS 1 bags (v2.0): `sensor_msgs/Imu`
//!   (ROS body axes turned into FRD), `Temperature` and `NavSatFix`, timed at header stamps;
//! - [`dataflash`]: ArduPilot DataFlash logs (`.bin`): any message by column name, and the IMU
//!   (with its temperature) and GPS of a flight log ([`dataflash::ardupilot`]).
//!
//! They share one absolute time scale, [`gpst`]: seconds since 1970 counted in GPST without
//! leap seconds (the `.tag` convention), so that IMU and GNSS files from these sources line
//! up. Lines of these formats are numbered like the canonical CSVs' in errors.
//!
//! ## Model banks and sensor profiles
//! [`bank`]: the model bank JSON written by `thermonav characterize`, validated on reading.
//! [`profile`]: sensor profiles ([`thermonav::sensor`]) as TOML with the unit in every key.
//!
//! ## Autopilot thermal parameters
//! [`thermal_parameters`]: a bank's thermal calibration as PX4 `TC_*` (QGroundControl
//! `.params`) or ArduPilot `INS_TCAL1_*` (`.param`) parameters.
//!
//! ## Noise configurations of other tools
//! [`noise_export`]: a bank's noise model at a temperature as Kalibr `imu.yaml`, KF-GINS
//! `imunoise:`, OB_GINS `imumodel:`, gnss-ins-sim `imu_err`, PX4 EKF2 and ArduPilot EKF3
//! parameters, a MATLAB `imuSensor` script or ROS `sensor_msgs/Imu` covariances.
//!
//! ## Production lots
//! [`lot`]: lot manifests (TOML): the units of a production lot and their chamber records.
//!
//! ## Fuzzing
//! [`parsers::Parser`] names every reader above and parses from bytes: the entry point of the
//! fuzz targets in `fuzz/` and of the test that replays their corpus.
//!
//! ## Streaming
//! [`ImuReader`], [`GnssReader`] and [`TrajectoryReader`] are iterators over any `BufRead`,
//! holding a single line buffer; `read_*` functions collect whole files.
//!
//! ## Compressed input
//! Every reader that takes a path opens it through [`open_input`]: a file whose name ends in
//! `.gz` or that starts with the gzip magic bytes is decompressed as it is read (pure Rust,
//! `flate2` on `miniz_oxide`), so errors name the file and the line as for a plain file.
//!
//! ## Atomic output
//! [`write_atomically`], [`AtomicFile`] and [`write_json_atomically`] write through a temporary
//! file renamed into place on success.

pub mod atomic;
pub mod bank;
pub mod dataflash;
mod decimal_value;
pub mod error;
mod fast_row;
pub mod finite;
mod fixed;
pub mod gmwm;
pub mod gnss;
pub mod gpst;
pub mod imu;
pub mod kf_gins;
pub mod kf_gins_write;
mod layout;
mod lines;
pub mod lot;
pub mod motion;
pub mod nmea;
pub mod noise_export;
pub mod noise_terms;
pub mod outside_solution;
pub mod parsers;
pub mod profile;
pub mod raw_imu;
pub mod reference;
pub mod ros;
mod rows;
pub mod rtklib_pos;
pub mod sample_checks;
mod short_decimal;
pub mod solution;
pub mod temperature_table;
mod text;
pub mod thermal_parameters;
pub mod trajectory;
pub mod truth;
pub mod ulog;

pub use atomic::{AtomicFile, remove_pending_temporaries, write_atomically, write_json_atomically};
pub use error::{ReadError, ReadErrorKind, WriteError};
pub use finite::{NonFinite, check_finite, finite_json_pretty, write_finite};
pub use gnss::{
    GnssReader, keep_common_groups, read_gnss, read_gnss_file, write_gnss, write_gnss_file,
};
pub use imu::{
    ChannelRule, FileSplit, GravityCheck, ImuOptions, ImuReader, ImuWriter, TemperatureColumn,
    read_imu, read_imu_file, read_imu_file_into, read_imu_file_with, write_imu, write_imu_file,
};
pub use trajectory::{
    TrajectoryReader, read_trajectory, read_trajectory_file, trajectory_column_names,
    trajectory_values, write_trajectory, write_trajectory_file,
};

use std::fs::File;
use std::io::BufReader;
use std::path::Path;

/// How readers treat values that parse but are suspect.
///
/// Text that is not a number, a wrong number of fields and header problems are errors under
/// both policies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Strictness {
    /// Reject NaN and infinite values, times that do not increase strictly, and values out of
    /// their physical range (latitude beyond ±90°, negative standard deviation); the error
    /// names the line (and, for times, both times).
    Strict,
    /// Keep such values as they are, for tools that count and report them (`inspect`).
    Lenient,
}

/// Read buffer of file readers, bytes.
const FILE_BUFFER_BYTES: usize = 1 << 18;

/// A file reader's input: the file's bytes, decompressed when it is gzip (see [`open_input`]).
pub type FileReader = BufReader<InputFile>;

/// Opens `path` for reading, with the path as the input's name.
fn open_file(path: &Path) -> Result<(FileReader, String), ReadError> {
    let input = path.display().to_string();
    match open_input(path) {
        Ok(file) => Ok((BufReader::with_capacity(FILE_BUFFER_BYTES, file), input)),
        Err(error) => Err(ReadError::new(input, None, ReadErrorKind::Open(error))),
    }
}

/// The two bytes every gzip member starts with (RFC 1952).
pub const GZIP_MAGIC: [u8; 2] = [0x1f, 0x8b];

/// The bytes of an input file: as stored, or through a gzip decompressor.
///
/// A decompression failure (a truncated or corrupt stream) is a read error of kind
/// `InvalidInput` or `InvalidData`, which readers report with the file's name like any other.
pub struct InputFile(Source);

enum Source {
    Plain(BufReader<File>),
    Gzip(Box<flate2::bufread::MultiGzDecoder<BufReader<File>>>),
}

impl InputFile {
    /// Whether the file is read through the decompressor.
    pub fn is_compressed(&self) -> bool {
        matches!(self.0, Source::Gzip(_))
    }
}

impl std::io::Read for InputFile {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        match &mut self.0 {
            Source::Plain(file) => file.read(buf),
            Source::Gzip(decoder) => decoder.read(buf),
        }
    }
}

/// Opens `path`, through a gzip decompressor when its name ends in `.gz` or its first bytes
/// are [`GZIP_MAGIC`]: the one open point of every reader that takes a path, so that
/// `imu.csv.gz`, `run.ulg.gz` or `bank.json.gz` read like the plain files. Concatenated gzip
/// members read as one stream (as `zcat` does).
///
/// # Errors
/// The error of opening the file.
pub fn open_input(path: &Path) -> std::io::Result<InputFile> {
    use std::io::BufRead;
    let mut file = BufReader::new(File::open(path)?);
    let named_gz = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gz"));
    // A failure to read the first bytes (a directory) is left to the first read, which
    // reports it as a read error of the file.
    let magic = file
        .fill_buf()
        .is_ok_and(|head| head.starts_with(&GZIP_MAGIC));
    let compressed = named_gz || magic;
    Ok(InputFile(match compressed {
        true => Source::Gzip(Box::new(flate2::bufread::MultiGzDecoder::new(file))),
        false => Source::Plain(file),
    }))
}

/// Whether [`open_input`] reads `path` through the decompressor (false when it cannot be
/// opened). It opens the file and reads its first bytes: not for a pipe, which would lose them.
pub fn is_compressed(path: &Path) -> bool {
    open_input(path).is_ok_and(|f| f.is_compressed())
}

/// The largest document read whole (a bank, a sensor profile, a motion file, a lot manifest):
/// 64 MiB, a thousand times the largest bank a campaign writes. A larger input, or an endless
/// one such as `/dev/zero`, is refused after reading that much instead of exhausting memory.
pub const DOCUMENT_LIMIT_BYTES: u64 = 64 << 20;

/// The bytes of the document at `path`, at most [`DOCUMENT_LIMIT_BYTES`] of them (after
/// decompression, see [`open_input`]: a gzip bomb is cut off like an endless input).
///
/// # Errors
/// The error of opening or reading the file, or one of kind `InvalidData` saying that it is
/// larger than the limit.
pub fn read_document(path: &Path) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    open_input(path)?
        .take(DOCUMENT_LIMIT_BYTES + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > DOCUMENT_LIMIT_BYTES {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "larger than {} MiB, more than any document of this kind can be (expected a bank, profile, motion or manifest file)",
                DOCUMENT_LIMIT_BYTES >> 20
            ),
        ));
    }
    Ok(bytes)
}

/// [`read_document`] with the path as the input's name; a missing file is
/// [`ReadErrorKind::Open`], any other failure [`ReadErrorKind::Read`].
pub(crate) fn read_named_document(path: &Path) -> Result<(Vec<u8>, String), ReadError> {
    let input = path.display().to_string();
    match read_document(path) {
        Ok(bytes) => Ok((bytes, input)),
        Err(e) => {
            let kind = match e.kind() {
                std::io::ErrorKind::NotFound => ReadErrorKind::Open(e),
                _ => ReadErrorKind::Read(e),
            };
            Err(ReadError::new(input, None, kind))
        }
    }
}

/// [`read_document`] as UTF-8 text.
///
/// # Errors
/// As [`read_document`], and `InvalidData` for bytes that are not UTF-8.
pub fn read_document_text(path: &Path) -> std::io::Result<String> {
    String::from_utf8(read_document(path)?).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("not UTF-8 text ({e})"),
        )
    })
}

/// How many times its compressed size a gzip log may expand to, beyond
/// [`DOCUMENT_LIMIT_BYTES`]: binary inertial logs compress two to ten times, so a file that
/// expands further is a decompression bomb, refused before it exhausts memory.
pub const MAX_GZIP_EXPANSION: u64 = 32;

/// The most bytes a file of `stored_bytes` may decompress to when read whole.
fn whole_file_limit(stored_bytes: u64) -> u64 {
    DOCUMENT_LIMIT_BYTES.saturating_add(stored_bytes.saturating_mul(MAX_GZIP_EXPANSION))
}

/// The bytes of `file` (compressed when `file.is_compressed()`), at most
/// [`whole_file_limit`] of `stored_bytes` for a compressed one.
fn read_bounded(mut file: InputFile, stored_bytes: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    if !file.is_compressed() {
        file.read_to_end(&mut bytes)?;
        return Ok(bytes);
    }
    let limit = whole_file_limit(stored_bytes);
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    match bytes.len() as u64 > limit {
        true => Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "the gzip stream of {stored_bytes} bytes expands beyond {} MiB ({}x its size plus {} MiB, more than any log compresses): refused as a decompression bomb (decompress it with gunzip first if it is genuine)",
                limit >> 20,
                MAX_GZIP_EXPANSION,
                DOCUMENT_LIMIT_BYTES >> 20
            ),
        )),
        false => Ok(bytes),
    }
}

/// The bytes of the file at `path` (decompressed, see [`open_input`], at most
/// [`MAX_GZIP_EXPANSION`] times the stored size plus [`DOCUMENT_LIMIT_BYTES`]), with the path
/// as the input's name; a missing or forbidden file is [`ReadErrorKind::Open`], a failure
/// part-way [`ReadErrorKind::Read`].
fn read_whole_file(path: &Path) -> Result<(Vec<u8>, String), ReadError> {
    let input = path.display().to_string();
    let stored_bytes = std::fs::metadata(path).map_or(0, |m| m.len());
    let read = open_input(path).and_then(|file| read_bounded(file, stored_bytes));
    match read {
        Ok(bytes) => Ok((bytes, input)),
        Err(e) => {
            let kind = match e.kind() {
                std::io::ErrorKind::NotFound | std::io::ErrorKind::PermissionDenied => {
                    ReadErrorKind::Open(e)
                }
                _ => ReadErrorKind::Read(e),
            };
            Err(ReadError::new(input, None, kind))
        }
    }
}

/// Coldest and warmest temperature a sensor record may carry, °C: beyond the −55..+125 °C
/// that MEMS inertial sensors are specified for, with a margin; outside, the value is a
/// unit mistake (kelvin, tenths of a degree) or corrupt.
pub const SENSOR_TEMPERATURE_RANGE_C: [f64; 2] = [-80.0, 150.0];

/// `t` when it lies in [`SENSOR_TEMPERATURE_RANGE_C`], else the message naming where it came
/// from (`source`): what `characterize` and the Python package say of a record's temperature.
pub fn check_characterization_temperature(source: &str, t: f64) -> Result<f64, String> {
    let [lo, hi] = SENSOR_TEMPERATURE_RANGE_C;
    if (lo..=hi).contains(&t) {
        Ok(t)
    } else {
        Err(format!(
            "{source}: {t} °C is outside {lo}..{hi} °C, the range a MEMS sensor is characterised in"
        ))
    }
}

/// True for a temperature inside [`SENSOR_TEMPERATURE_RANGE_C`].
pub(crate) fn is_sensor_temperature(temperature_c: f64) -> bool {
    let [low, high] = SENSOR_TEMPERATURE_RANGE_C;
    (low..=high).contains(&temperature_c)
}

/// The error of a temperature outside [`SENSOR_TEMPERATURE_RANGE_C`] in `column`.
pub(crate) fn temperature_out_of_range(column: &'static str, found: f64) -> ReadErrorKind {
    ReadErrorKind::OutOfRange {
        column,
        found,
        expected: "-80 to 150 °C, the range of a sensor's temperature",
    }
}

/// Strict check that a latitude lies within ±90°.
fn check_latitude(latitude_rad: f64) -> Result<(), ReadErrorKind> {
    let limit_rad = thermonav::units::deg_to_rad(90.0);
    match latitude_rad.abs() <= limit_rad {
        true => Ok(()),
        false => Err(ReadErrorKind::OutOfRange {
            column: "lat_deg",
            found: text::degrees_reading_back_exactly(latitude_rad),
            expected: "-90 to 90",
        }),
    }
}
