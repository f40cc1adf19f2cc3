//! The canonical IMU CSV.
//!
//! ```text
//! t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c
//! 12.005000000,0.0012,-0.0003,0.0001,0.02,-0.01,-9.80665,21.5
//! ```
//! Columns are found by name, in any order. Rates may also be given as `g?_deg_s` or
//! `g?_deg_h` (gyros) and `a?_g` or `a?_mg` (accelerometers); increments as `dth?_rad` or
//! `dth?_deg` (angle) and `dv?_m_s` (velocity). Every value is converted to SI as it is read;
//! a file holds rates or increments, never both. `temp_c` is optional. The writer always uses
//! the SI names.
//!
//! [`ImuOptions`] take a file beyond its header: the IMU's mounting (every sample turned into
//! body axes as it is read), a sample rate for a file without `t_s`, and whether a subset of
//! the six channels is accepted ([`ChannelRule`]).

use crate::Strictness;
use crate::atomic::write_atomically;
use crate::error::{ReadError, ReadErrorKind, WriteError};
use crate::finite::write_finite;
use crate::layout::{ColumnSpec, Layout, Schema, Unit};
use crate::rows::{RowTimes, Rows};
use crate::text::write_time;
use std::fs::File;
use std::io::{BufRead, BufReader, Write};
use std::path::Path;
use thermonav::imu::{Channel, ImuSample, ImuSeries, SampleKind};
use thermonav::mounting::Mounting;
use thermonav::time::Timestamp;

/// First slot of the rate columns (gx..az), then of the increment columns (dthx..dvz).
const RATE_SLOT: usize = 0;
const INCREMENT_SLOT: usize = 6;
const TEMPERATURE_SLOT: usize = 12;

const fn spec(name: &'static str, slot: usize, unit: Unit) -> ColumnSpec {
    ColumnSpec { name, slot, unit }
}

/// Every accepted IMU column name.
pub(crate) const COLUMNS: [ColumnSpec; 28] = [
    spec("gx_rad_s", 0, Unit::Si),
    spec("gy_rad_s", 1, Unit::Si),
    spec("gz_rad_s", 2, Unit::Si),
    spec("gx_deg_s", 0, Unit::DegPerS),
    spec("gy_deg_s", 1, Unit::DegPerS),
    spec("gz_deg_s", 2, Unit::DegPerS),
    spec("gx_deg_h", 0, Unit::DegPerH),
    spec("gy_deg_h", 1, Unit::DegPerH),
    spec("gz_deg_h", 2, Unit::DegPerH),
    spec("ax_m_s2", 3, Unit::Si),
    spec("ay_m_s2", 4, Unit::Si),
    spec("az_m_s2", 5, Unit::Si),
    spec("ax_g", 3, Unit::G),
    spec("ay_g", 4, Unit::G),
    spec("az_g", 5, Unit::G),
    spec("ax_mg", 3, Unit::MilliG),
    spec("ay_mg", 4, Unit::MilliG),
    spec("az_mg", 5, Unit::MilliG),
    spec("dthx_rad", 6, Unit::Si),
    spec("dthy_rad", 7, Unit::Si),
    spec("dthz_rad", 8, Unit::Si),
    spec("dthx_deg", 6, Unit::Deg),
    spec("dthy_deg", 7, Unit::Deg),
    spec("dthz_deg", 8, Unit::Deg),
    spec("dvx_m_s", 9, Unit::Si),
    spec("dvy_m_s", 10, Unit::Si),
    spec("dvz_m_s", 11, Unit::Si),
    spec("temp_c", TEMPERATURE_SLOT, Unit::Si),
];

const SCHEMA: Schema = Schema {
    columns: &COLUMNS,
    expected: "t_s, g{x,y,z}_{rad_s,deg_s,deg_h}, a{x,y,z}_{m_s2,g,mg}, \
               dth{x,y,z}_{rad,deg}, dv{x,y,z}_m_s, temp_c",
    time_alternatives: " (or, for a file without times, a sample rate: --rate-hz)",
};

/// Canonical names of the six channels, with the other accepted names, per kind.
const RATE_NAMES: [(&str, &str); 6] = [
    ("gx_rad_s", " (or gx_deg_s, gx_deg_h)"),
    ("gy_rad_s", " (or gy_deg_s, gy_deg_h)"),
    ("gz_rad_s", " (or gz_deg_s, gz_deg_h)"),
    ("ax_m_s2", " (or ax_g, ax_mg)"),
    ("ay_m_s2", " (or ay_g, ay_mg)"),
    ("az_m_s2", " (or az_g, az_mg)"),
];
const INCREMENT_NAMES: [(&str, &str); 6] = [
    ("dthx_rad", " (or dthx_deg)"),
    ("dthy_rad", " (or dthy_deg)"),
    ("dthz_rad", " (or dthz_deg)"),
    ("dvx_m_s", ""),
    ("dvy_m_s", ""),
    ("dvz_m_s", ""),
];
const TEMPERATURE_NAME: &str = "temp_c";

/// How the canonical IMU reader takes a file beyond what its header says: the IMU's mounting
/// and where the times come from. The default reads the file as it stands (IMU axes are body
/// axes, times from `t_s`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ImuOptions {
    /// The IMU's mounting in the body: every sample's gyro and accelerometer vectors (rates or
    /// increments) are turned into body axes, v^b = C_s^b v^s, as they are read. `None`: the
    /// file's axes are the body axes.
    pub mounting: Option<Mounting>,
    /// The sample rate of a file without a `t_s` column, Hz: sample k (0-based) is at k / rate
    /// s. `None`: the file must have `t_s`; given, the file must not have it.
    pub rate_hz: Option<f64>,
    /// Which of the six channel columns the file must have.
    pub channels: ChannelRule,
    /// Whether a large file is parsed as two halves on two threads.
    pub split: FileSplit,
}

/// Whether [`read_imu_file_with`] parses a large file (8 MiB or more, uncompressed, timed by
/// `t_s`) as two halves on two threads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FileSplit {
    /// Two halves at once: the fastest read of one file when the cores are otherwise idle.
    #[default]
    TwoHalves,
    /// One pass on the calling thread: for files read side by side (a campaign's records on a
    /// thread pool), where the halves would only make the threads queue for the cores and
    /// fill memory twice (each half's columns, then the joined ones).
    OnePass,
}

/// Which of the six channel columns (gx..az, or their increments) an IMU file must have.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ChannelRule {
    /// All six, for navigation; the error names every absent one.
    #[default]
    AllSix,
    /// Any one or more (a single-gyro file), for the static analyses: the series' absent
    /// channels have empty columns ([`ImuSeries::present_channels`]).
    AnySubset,
}

impl ImuOptions {
    fn row_times(&self) -> RowTimes {
        match self.rate_hz {
            Some(rate_hz) => RowTimes::Rate { rate_hz },
            None => RowTimes::Column,
        }
    }
}

/// Streaming reader of the canonical IMU CSV: an iterator of SI samples.
///
/// Holds one line buffer whatever the file size. After an error the iterator ends.
///
/// # Example
/// ```
/// use thermonav_io::{ImuReader, Strictness};
/// let text = "t_s,gx_deg_s,gy_deg_s,gz_deg_s,ax_g,ay_g,az_g\n0.005,1,0,0,0,0,-1\n";
/// let mut reader = ImuReader::new(text.as_bytes(), "example", Strictness::Strict)?;
/// let sample = reader.next().unwrap()?;
/// assert_eq!(sample.gyro[0], std::f64::consts::PI / 180.0);
/// assert_eq!(sample.accel[2], -9.80665);
/// # Ok::<(), thermonav_io::ReadError>(())
/// ```
pub struct ImuReader<R> {
    rows: Rows<R>,
    kind: SampleKind,
    temperature: bool,
    mounting: Option<Mounting>,
    /// The channels present, in body axes (after the mounting).
    present: Vec<Channel>,
}

impl ImuReader<crate::FileReader> {
    /// Opens `path` (decompressing it when it is gzip, see [`crate::open_input`]) and reads
    /// its header.
    ///
    /// # Errors
    /// As [`ImuReader::new`], plus [`ReadErrorKind::Open`].
    pub fn open(path: impl AsRef<Path>, strictness: Strictness) -> Result<Self, ReadError> {
        Self::open_with(path, strictness, &ImuOptions::default())
    }

    /// [`ImuReader::open`] with `options`.
    ///
    /// # Errors
    /// As [`ImuReader::with_options`], plus [`ReadErrorKind::Open`].
    pub fn open_with(
        path: impl AsRef<Path>,
        strictness: Strictness,
        options: &ImuOptions,
    ) -> Result<Self, ReadError> {
        let (file, input) = crate::open_file(path.as_ref())?;
        Self::with_options(file, input, strictness, options)
    }
}

impl<R: BufRead> ImuReader<R> {
    /// Reads the header of `reader`; `input` names it in errors (usually the file path).
    ///
    /// # Errors
    /// [`ReadErrorKind::Empty`], an unknown, repeated or missing column, rate and increment
    /// columns together, or a read failure.
    pub fn new(
        reader: R,
        input: impl Into<String>,
        strictness: Strictness,
    ) -> Result<Self, ReadError> {
        Self::with_options(reader, input, strictness, &ImuOptions::default())
    }

    /// [`ImuReader::new`] with `options`: the mounting applied to every sample, the times
    /// from a rate for a file without `t_s`.
    ///
    /// # Errors
    /// As [`ImuReader::new`]; a `t_s` column together with a rate
    /// ([`ReadErrorKind::TimeColumnWithRate`]); no `t_s` column and no rate.
    pub fn with_options(
        reader: R,
        input: impl Into<String>,
        strictness: Strictness,
        options: &ImuOptions,
    ) -> Result<Self, ReadError> {
        let times = options.row_times();
        let rows = Rows::open_timed(reader, input.into(), &SCHEMA, strictness, times)?;
        let (kind, present) = sample_kind(rows.layout(), options.channels)
            .and_then(|(kind, present)| Ok((kind, body_channels(&present, options.mounting)?)))
            .map_err(|kind| rows.header_error(kind))?;
        let temperature = rows.layout().has(TEMPERATURE_SLOT);
        Ok(Self {
            rows,
            kind,
            temperature,
            mounting: options.mounting,
            present,
        })
    }

    /// Whether the file holds rates or increments.
    pub fn kind(&self) -> SampleKind {
        self.kind
    }

    /// Whether the file has a `temp_c` column.
    pub fn has_temperature(&self) -> bool {
        self.temperature
    }

    /// The channels the file holds, in body axes (after the mounting), in [`Channel::ALL`]
    /// order: all six unless read under [`ChannelRule::AnySubset`]. The samples carry 0 for
    /// the others.
    pub fn present_channels(&self) -> &[Channel] {
        &self.present
    }
}

impl<R: BufRead> Iterator for ImuReader<R> {
    type Item = Result<ImuSample, ReadError>;

    fn next(&mut self) -> Option<Self::Item> {
        let first = self.first_channel_slot();
        let (temperature, mounting) = (self.temperature, self.mounting);
        let sample = self.rows.next_row()?.map(|(time, values)| {
            let sample = ImuSample {
                time,
                gyro: [values[first], values[first + 1], values[first + 2]],
                accel: [values[first + 3], values[first + 4], values[first + 5]],
                temperature_c: temperature.then_some(values[TEMPERATURE_SLOT]),
            };
            mounting.map_or(sample, |m| m.sample_to_body(sample))
        });
        Some(match sample {
            Ok(ImuSample {
                temperature_c: Some(t),
                ..
            }) => match self.refused_temperature(t) {
                Some(error) => Err(error),
                None => sample,
            },
            other => other,
        })
    }
}

impl<R: BufRead> ImuReader<R> {
    /// The slot of the first of the six channels of the file's kind.
    fn first_channel_slot(&self) -> usize {
        match self.kind {
            SampleKind::Rates => RATE_SLOT,
            SampleKind::Increments => INCREMENT_SLOT,
        }
    }

    /// Appends every remaining row to `series` column by column: the samples [`Iterator::next`]
    /// gives, for a file read without a mounting, without building each one. `series` holds
    /// the first sample already (so its temperature column is there when the file has one).
    fn append_unrotated_rows(&mut self, series: &mut ImuSeries) -> Result<(), ReadError> {
        debug_assert!(self.mounting.is_none());
        let first = self.first_channel_slot();
        while let Some(row) = self.rows.next_row() {
            let (time, values) = row?;
            series.time.push(time);
            for (column, &value) in series.channels.iter_mut().zip(&values[first..first + 6]) {
                column.push(value);
            }
            let temperature_c = values[TEMPERATURE_SLOT];
            // The column is there exactly when the file has `temp_c` (the first sample made it).
            if let Some(column) = series.temperature_c.as_mut() {
                if let Some(error) = self.refused_temperature(temperature_c) {
                    return Err(error);
                }
                column.push(temperature_c);
            }
        }
        Ok(())
    }

    /// Under strict reading, the error for the current row's temperature when no sensor reads
    /// it (reading then ends); `None` otherwise.
    fn refused_temperature(&mut self, temperature_c: f64) -> Option<ReadError> {
        let strict = self.rows.strictness() == Strictness::Strict;
        (strict && !crate::is_sensor_temperature(temperature_c)).then(|| {
            let kind = crate::temperature_out_of_range(TEMPERATURE_NAME, temperature_c);
            self.rows.row_error(kind)
        })
    }
}

/// The kind of the header's channel columns, which must be of one kind and, under
/// [`ChannelRule::AllSix`], all six; and which of the six (in IMU axes) are there.
fn sample_kind(
    layout: &Layout,
    rule: ChannelRule,
) -> Result<(SampleKind, Vec<Channel>), ReadErrorKind> {
    let rate = (RATE_SLOT..RATE_SLOT + 6).find_map(|slot| layout.name_of(slot));
    let increment = (INCREMENT_SLOT..INCREMENT_SLOT + 6).find_map(|slot| layout.name_of(slot));
    let (kind, first, names) = match (rate, increment) {
        (Some(rate), Some(increment)) => {
            return Err(ReadErrorKind::MixedKinds {
                rate_column: rate.to_owned(),
                increment_column: increment.to_owned(),
            });
        }
        (None, Some(_)) => (SampleKind::Increments, INCREMENT_SLOT, INCREMENT_NAMES),
        _ => (SampleKind::Rates, RATE_SLOT, RATE_NAMES),
    };
    let present: Vec<Channel> = Channel::ALL
        .into_iter()
        .filter(|c| layout.has(first + c.index()))
        .collect();
    let missing: Vec<String> = Channel::ALL
        .into_iter()
        .filter(|c| !present.contains(c))
        .map(|c| format!("{}{}", names[c.index()].0, names[c.index()].1))
        .collect();
    match (rule, present.len()) {
        (_, 0) => {
            let (name, alternatives) = names[0];
            layout.require(first, name, alternatives)?;
        }
        (ChannelRule::AllSix, 6) | (ChannelRule::AnySubset, _) => {}
        (ChannelRule::AllSix, _) => return Err(ReadErrorKind::MissingChannels { missing }),
    }
    Ok((kind, present))
}

/// The channels present in body axes: those of `present` (IMU axes) moved by an axis
/// mapping; angles mix a sensor's three axes, so they need all three of each sensor that is
/// present.
fn body_channels(
    present: &[Channel],
    mounting: Option<Mounting>,
) -> Result<Vec<Channel>, ReadErrorKind> {
    let Some(mounting) = mounting else {
        return Ok(present.to_vec());
    };
    let mut body = Vec::new();
    for &channel in present {
        let (triad, axis) = (channel.index() / 3 * 3, channel.index() % 3);
        let Some(body_axis) = mounting.body_axis_of(axis) else {
            let partial = (triad..triad + 3).any(|i| !present.contains(&Channel::ALL[i]));
            if partial {
                return Err(ReadErrorKind::RotationOfPartialTriad {
                    channel: channel.name(),
                });
            }
            body.push(channel);
            continue;
        };
        body.push(Channel::ALL[triad + body_axis]);
    }
    body.sort();
    Ok(body)
}

/// Reads a whole IMU CSV from `reader` (named `input` in errors) into a series.
///
/// # Errors
/// Any [`ReadError`] of [`ImuReader`], and [`ReadErrorKind::HeaderOnly`] for a file without
/// data rows.
pub fn read_imu(
    reader: impl BufRead,
    input: impl Into<String>,
    strictness: Strictness,
) -> Result<ImuSeries, ReadError> {
    let input = input.into();
    let series = collect_series(
        ImuReader::new(reader, input.clone(), strictness)?,
        None,
        None,
    )?;
    check_gravity_magnitude(series, &input, strictness)
}

/// Reads a whole IMU CSV file into a series.
///
/// # Errors
/// As [`read_imu`], plus [`ReadErrorKind::Open`].
pub fn read_imu_file(
    path: impl AsRef<Path>,
    strictness: Strictness,
) -> Result<ImuSeries, ReadError> {
    read_imu_file_with(path, strictness, &ImuOptions::default())
}

/// [`read_imu_file`] with `options` (see [`ImuReader::with_options`]).
///
/// # Errors
/// As [`read_imu_file`] and [`ImuReader::with_options`].
pub fn read_imu_file_with(
    path: impl AsRef<Path>,
    strictness: Strictness,
    options: &ImuOptions,
) -> Result<ImuSeries, ReadError> {
    read_imu_file_into(path, strictness, options, None)
}

/// [`read_imu_file_with`] into the columns of `spare`, a series done with ([`ImuSeries::emptied`]),
/// when the file is read in one pass: the same series, with no new memory faulted in as far as
/// the spare's room goes. A reader of many records in turn passes each one's series on to the
/// next. The spare is dropped unused when the file is read in two halves, holds no rows, or
/// fails to read.
///
/// # Errors
/// As [`read_imu_file_with`].
pub fn read_imu_file_into(
    path: impl AsRef<Path>,
    strictness: Strictness,
    options: &ImuOptions,
    spare: Option<ImuSeries>,
) -> Result<ImuSeries, ReadError> {
    let path = path.as_ref();
    let file_bytes = std::fs::metadata(path).map(|m| m.len()).ok();
    // A compressed file cannot be entered in the middle, nor can rows timed by their index
    // be counted from it: those are read in one pass. The compression is looked at only for
    // a large file, never for a pipe (of length 0), whose first bytes a look would consume.
    let halves = file_bytes
        .filter(|&b| b >= PARALLEL_MIN_BYTES && options.split == FileSplit::TwoHalves)
        .filter(|_| options.rate_hz.is_none() && !crate::is_compressed(path))
        .and_then(|b| split_point(path, b))
        .and_then(|(header, boundary, bytes)| {
            read_halves(path, strictness, options, &header, (boundary, bytes))
        });
    let series = match halves {
        Some(series) => series,
        // Small files, and any file on which a half failed: one pass, which also gives the
        // exact error (line numbers counted from the top).
        None => {
            let reader = ImuReader::open_with(path, strictness, options)?;
            collect_series(reader, file_bytes, spare)?
        }
    };
    check_gravity_magnitude(series, &path.display().to_string(), strictness)
}

/// Mean |a| (m/s²) below which, down to [`G_UNITS_LOW_M_S2`], a record in m/s² is taken for
/// one in g: a static or driving record in g averages 1.00-1.05, one in m/s² 9.8-10.3, and only
/// free fall gives a mean magnitude near 1 m/s². The band stays narrow (±10 %) so that
/// synthetic records of unit-size values (|a| = √3 or 1.2) still read.
const G_UNITS_HIGH_M_S2: f64 = 1.1;
/// Lower end of the band of [`G_UNITS_HIGH_M_S2`].
const G_UNITS_LOW_M_S2: f64 = 0.9;

/// The series, or (strict reading) [`ReadErrorKind::AccelerationInG`] at the header line when
/// the mean specific-force magnitude is near 1: values in g under an m/s² column name.
fn check_gravity_magnitude(
    series: ImuSeries,
    input: &str,
    strictness: Strictness,
) -> Result<ImuSeries, ReadError> {
    let mut check = GravityCheck::default();
    check.add(&series);
    check.verdict(input, strictness)?;
    Ok(series)
}

/// The check that accelerations in g were not written under m/s² names, for a record read
/// whole or piece by piece: the running mean magnitude of the specific force, and the verdict
/// once the record has been read (values in g: a mean magnitude of 0.9 to 1.1).
#[derive(Debug, Clone, Default)]
pub struct GravityCheck {
    kind: Option<SampleKind>,
    norm_sum: f64,
    samples: usize,
    first: Option<Timestamp>,
    last: Option<Timestamp>,
}

impl GravityCheck {
    /// Adds the samples of the next piece of the record.
    pub fn add(&mut self, piece: &ImuSeries) {
        let [_, _, _, ax, ay, az] = &piece.channels;
        self.norm_sum += ax
            .iter()
            .zip(ay)
            .zip(az)
            // The plain root of the sum of squares, not nested `hypot` (a few per cent of the
            // whole read): the values are at most 1e15 under strict reading, so the squares
            // neither overflow nor underflow into a wrong verdict; a lenient read's huge or
            // non-finite values give a mean outside the band either way.
            .map(|((x, y), z)| (x * x + y * y + z * z).sqrt())
            .sum::<f64>();
        self.samples += piece.len();
        self.kind = self.kind.or(piece.kind);
        self.first = self.first.or(piece.time.first().copied());
        self.last = piece.time.last().copied().or(self.last);
    }

    /// Mean magnitude of the specific force so far, m/s² (increments divided by the record's
    /// mean interval); NaN for fewer than two samples of increments or none of rates.
    pub fn mean_m_s2(&self) -> f64 {
        let mean_norm = self.norm_sum / self.samples as f64;
        match self.kind {
            Some(SampleKind::Increments) => {
                let span_s = match (self.first, self.last) {
                    (Some(first), Some(last)) => last.since(first).as_seconds(),
                    _ => f64::NAN,
                };
                mean_norm * (self.samples as f64 - 1.0) / span_s
            }
            _ => mean_norm,
        }
    }

    /// Under strict reading, [`ReadErrorKind::AccelerationInG`] at the header line of `input`
    /// when the mean magnitude lies in the band of values in g.
    ///
    /// # Errors
    /// As above.
    pub fn verdict(&self, input: &str, strictness: Strictness) -> Result<(), ReadError> {
        let mean = self.mean_m_s2();
        let in_g = (G_UNITS_LOW_M_S2..=G_UNITS_HIGH_M_S2).contains(&mean);
        match strictness == Strictness::Strict && in_g {
            false => Ok(()),
            true => Err(ReadError::new(
                input,
                Some(1),
                ReadErrorKind::AccelerationInG {
                    samples: self.samples,
                    mean_m_s2: mean,
                },
            )),
        }
    }
}

/// Files at least this large are parsed as two halves on two threads.
const PARALLEL_MIN_BYTES: u64 = 8 << 20;

/// The header line and the byte after the first newline at or after the middle of the file.
fn split_point(path: &Path, bytes: u64) -> Option<(Vec<u8>, u64, u64)> {
    use std::io::{Read, Seek, SeekFrom};
    let mut reader = BufReader::new(File::open(path).ok()?);
    let mut header = Vec::new();
    // Bounded like every line: a file without newlines must not be read whole here.
    (&mut reader)
        .take(crate::lines::MAX_LINE_BYTES)
        .read_until(b'\n', &mut header)
        .ok()?;
    let mut file = reader.into_inner();
    file.seek(SeekFrom::Start(bytes / 2)).ok()?;
    let mut rest = Vec::new();
    let skipped = BufReader::new(file)
        .take(crate::lines::MAX_LINE_BYTES)
        .read_until(b'\n', &mut rest)
        .ok()? as u64;
    let boundary = bytes / 2 + skipped;
    let usable = rest.last() == Some(&b'\n') && boundary > header.len() as u64 && boundary < bytes;
    usable.then_some((header, boundary, bytes))
}

/// Both halves parsed in parallel (the second behind a copy of the header), or `None` when
/// either half fails or, under strict reading, time does not increase across the boundary.
fn read_halves(
    path: &Path,
    strictness: Strictness,
    options: &ImuOptions,
    header: &[u8],
    (boundary, bytes): (u64, u64),
) -> Option<ImuSeries> {
    use std::io::{Read, Seek, SeekFrom};
    let input = path.display().to_string();
    let (first, second) = std::thread::scope(|scope| {
        let first = scope.spawn(|| {
            let file = File::open(path).ok()?.take(boundary);
            let reader = ImuReader::with_options(
                BufReader::with_capacity(crate::FILE_BUFFER_BYTES, file),
                input.clone(),
                strictness,
                options,
            )
            .ok()?;
            // Room for the whole file's rows, so that the second half appends without a move.
            collect_series(reader, Some(bytes), None).ok()
        });
        let second = scope.spawn(|| {
            let mut file = File::open(path).ok()?;
            file.seek(SeekFrom::Start(boundary)).ok()?;
            let joined = std::io::Cursor::new(header.to_vec()).chain(file);
            let reader = ImuReader::with_options(
                BufReader::with_capacity(crate::FILE_BUFFER_BYTES, joined),
                input.clone(),
                strictness,
                options,
            )
            .ok()?;
            collect_series(reader, Some(bytes - boundary), None).ok()
        });
        (first.join().ok().flatten(), second.join().ok().flatten())
    });
    let (mut first, second) = (first?, second?);
    let ordered = match (first.time.last(), second.time.first()) {
        (Some(a), Some(b)) => strictness == Strictness::Lenient || a < b,
        _ => true,
    };
    (ordered && first.kind == second.kind).then(|| {
        append_series(&mut first, second);
        first
    })
}

fn append_series(first: &mut ImuSeries, second: ImuSeries) {
    first.time.extend(second.time);
    for (a, b) in first.channels.iter_mut().zip(second.channels) {
        a.extend(b);
    }
    first.temperature_c = match (first.temperature_c.take(), second.temperature_c) {
        (Some(mut a), Some(b)) => {
            a.extend(b);
            Some(a)
        }
        _ => None,
    };
}

/// Collects samples, into `spare`'s columns when given; with the input's size, reserves room
/// for all rows once the first is read.
fn collect_series<R: BufRead>(
    mut reader: ImuReader<R>,
    input_bytes: Option<u64>,
    spare: Option<ImuSeries>,
) -> Result<ImuSeries, ReadError> {
    let kind = reader.kind();
    let present = reader.present_channels().to_vec();
    let Some(first) = reader.next() else {
        return Ok(ImuSeries::new(kind));
    };
    let mut series = match spare {
        Some(spare) => spare.emptied(kind),
        None => ImuSeries::new(kind),
    };
    series.push(&first?);
    if let Some(bytes) = input_bytes {
        reserve_rows(&mut series, bytes / reader.rows.line_bytes().max(1));
    }
    match reader.mounting {
        Some(_) => {
            for sample in reader {
                series.push(&sample?);
            }
        }
        None => reader.append_unrotated_rows(&mut series)?,
    }
    series.keep_channels(&present);
    Ok(series)
}

/// Reserves room for about `rows` more samples (plus 3 % for rows longer than the first).
fn reserve_rows(series: &mut ImuSeries, rows: u64) {
    let additional = usize::try_from(rows + rows / 32).unwrap_or(0);
    series.time.reserve(additional);
    for column in series.channels.iter_mut().chain(&mut series.temperature_c) {
        column.reserve(additional);
    }
}

/// Whether an IMU file gets a `temp_c` column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TemperatureColumn {
    /// Write `temp_c`; every sample must carry a temperature.
    Written,
    /// No `temp_c` column; sample temperatures are ignored.
    Omitted,
}

/// Streaming writer of the canonical IMU CSV (SI column names).
///
/// Values are written in their shortest round-trip form and times as exact seconds with nine
/// decimals, so reading the file back gives the same bits.
pub struct ImuWriter<W: Write> {
    out: W,
    temperature: TemperatureColumn,
    rows: usize,
}

impl<W: Write> ImuWriter<W> {
    /// Writes the header for `kind` samples to `out`.
    ///
    /// # Errors
    /// [`WriteError::Io`] when `out` fails.
    pub fn new(
        mut out: W,
        kind: SampleKind,
        temperature: TemperatureColumn,
    ) -> Result<Self, WriteError> {
        out.write_all(header(kind, temperature).as_bytes())?;
        Ok(Self {
            out,
            temperature,
            rows: 0,
        })
    }

    /// Writes one sample as a line.
    ///
    /// # Errors
    /// [`WriteError::MissingTemperature`] when the file has `temp_c` and the sample has none;
    /// [`WriteError::Io`] when `out` fails.
    pub fn write_sample(&mut self, sample: &ImuSample) -> Result<(), WriteError> {
        let temperature = match (self.temperature, sample.temperature_c) {
            (TemperatureColumn::Written, None) => {
                return Err(WriteError::MissingTemperature { index: self.rows });
            }
            (TemperatureColumn::Written, Some(t)) => Some(t),
            (TemperatureColumn::Omitted, _) => None,
        };
        write_time(&mut self.out, sample.time)?;
        for &value in sample.gyro.iter().chain(&sample.accel).chain(&temperature) {
            self.out.write_all(b",")?;
            write_finite(&mut self.out, value)?;
        }
        self.out.write_all(b"\n")?;
        self.rows += 1;
        Ok(())
    }

    /// Flushes and returns the underlying writer.
    ///
    /// # Errors
    /// [`WriteError::Io`] when flushing fails.
    pub fn finish(mut self) -> Result<W, WriteError> {
        self.out.flush()?;
        Ok(self.out)
    }
}

/// The canonical names of the six channel columns of `kind`, in [`Channel::ALL`] order
/// (`gx_rad_s` .. `az_m_s2`, or `dthx_rad` .. `dvz_m_s`), as written.
///
/// [`Channel::ALL`]: thermonav::imu::Channel::ALL
pub fn channel_column_names(kind: SampleKind) -> [&'static str; 6] {
    let names = match kind {
        SampleKind::Rates => RATE_NAMES,
        SampleKind::Increments => INCREMENT_NAMES,
    };
    names.map(|(name, _)| name)
}

/// The header line for a kind, with `temp_c` when written.
fn header(kind: SampleKind, temperature: TemperatureColumn) -> String {
    let names = match kind {
        SampleKind::Rates => RATE_NAMES,
        SampleKind::Increments => INCREMENT_NAMES,
    };
    let mut line = String::from(crate::layout::TIME_COLUMN);
    for (name, _) in names {
        line.push(',');
        line.push_str(name);
    }
    if temperature == TemperatureColumn::Written {
        line.push(',');
        line.push_str(TEMPERATURE_NAME);
    }
    line.push('\n');
    line
}

/// Writes a whole series as a canonical IMU CSV, with `temp_c` when the series has temperatures.
///
/// # Errors
/// [`WriteError::Empty`], [`WriteError::UnknownKind`], [`WriteError::RaggedColumn`] for a
/// malformed series, and [`WriteError::Io`].
pub fn write_imu(out: impl Write, series: &ImuSeries) -> Result<(), WriteError> {
    let kind = check_series(series)?;
    let temperature = match series.temperature_c {
        Some(_) => TemperatureColumn::Written,
        None => TemperatureColumn::Omitted,
    };
    let mut writer = ImuWriter::new(out, kind, temperature)?;
    for index in 0..series.len() {
        writer.write_sample(&sample_at(series, index))?;
    }
    writer.finish()?;
    Ok(())
}

/// Writes a whole series to `path` atomically (see [`write_atomically`]).
///
/// # Errors
/// As [`write_imu`], wrapped with the path, plus the errors of [`write_atomically`].
pub fn write_imu_file(path: impl AsRef<Path>, series: &ImuSeries) -> Result<(), WriteError> {
    write_atomically(path, |file| write_imu(file, series))
}

/// The series' kind, after checking it has samples and columns of equal length.
fn check_series(series: &ImuSeries) -> Result<SampleKind, WriteError> {
    let expected = series.len();
    if expected == 0 {
        return Err(WriteError::Empty { what: "samples" });
    }
    let channels = Channel::ALL
        .iter()
        .map(|c| (c.name(), series.channel(*c).len()));
    let temperature = series
        .temperature_c
        .iter()
        .map(|t| (TEMPERATURE_NAME, t.len()));
    if let Some((column, len)) = channels
        .chain(temperature)
        .find(|&(_, len)| len != expected)
    {
        return Err(WriteError::RaggedColumn {
            column,
            len,
            expected,
        });
    }
    series.kind.ok_or(WriteError::UnknownKind)
}

/// Sample `index` of a checked series.
fn sample_at(series: &ImuSeries, index: usize) -> ImuSample {
    let value = |channel: Channel| series.channel(channel)[index];
    ImuSample {
        time: series.time[index],
        gyro: [value(Channel::Gx), value(Channel::Gy), value(Channel::Gz)],
        accel: [value(Channel::Ax), value(Channel::Ay), value(Channel::Az)],
        temperature_c: series.temperature_c.as_ref().map(|t| t[index]),
    }
}
