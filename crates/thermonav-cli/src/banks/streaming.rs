//! `characterize --reading streaming`: one record read in pieces and characterised in memory
//! independent of its length (see `thermonav::stoch::streaming`). A reader thread parses the
//! next piece of a CSV while the six channels of the previous one are processed in parallel; an
//! MCAP or ROS 1 bag is read record by record in the same thread, its pieces pushed as they come.

use crate::args::ReadingArg;
use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use std::path::Path;
use std::sync::mpsc::sync_channel;
use thermonav::imu::{ImuSeries, SampleKind};
use thermonav::stoch::bank::TemperatureEntry;
use thermonav::stoch::characterize::CharacterizeSettings;
use thermonav::stoch::streaming::{StreamingCharacterizer, StreamingSettings};
use thermonav_io::ros::extract::{StreamOptions, TopicNames, stream_imu_series};
use thermonav_io::{GravityCheck, ImuOptions, ImuReader, ReadError, ReadErrorKind, Strictness};

/// Files at least this large are streamed under `--reading auto` (1 GiB: about 12 M rows of
/// a full-precision 6-channel CSV, whose in-memory characterisation peaks near 2 GB).
pub const AUTO_STREAMING_BYTES: u64 = 1 << 30;

/// Rows per piece handed from the reader thread to the characterisation.
const PIECE_ROWS: usize = 1 << 16;

/// Whether `path` is streamed under `reading`.
pub fn streams(path: &Path, reading: ReadingArg) -> bool {
    match reading {
        ReadingArg::InMemory => false,
        ReadingArg::Streaming => true,
        ReadingArg::Auto => std::fs::metadata(path).is_ok_and(|m| m.len() >= AUTO_STREAMING_BYTES),
    }
}

/// Characterises the record in `path`, read as `imu` says (a bag's topics as `topics` choose),
/// in pieces; `name` is its source label.
pub fn characterize_streaming(
    path: &Path,
    given: Option<f64>,
    settings: &CharacterizeSettings,
    (name, imu, topics): (&str, &ImuOptions, &TopicNames),
) -> Result<TemperatureEntry, Failure> {
    let mut stream = StreamingCharacterizer::new(settings.clone(), StreamingSettings::default());
    let mut gravity = GravityCheck::default();
    match crate::inputs::is_streamed_bag(path) {
        true => feed_bag(path, (imu, topics), &mut stream, &mut gravity)?,
        false => {
            let reader = ImuReader::open_with(path, Strictness::Strict, imu).data()?;
            check_all_six(&reader, path)?;
            feed(path, reader, &mut stream, &mut gravity)?;
        }
    }
    check_has_rows(&stream, path)?;
    gravity
        .verdict(&path.display().to_string(), Strictness::Strict)
        .data()?;
    let temperature_c = temperature_of(given, stream.mean_temperature_c(), path)?;
    let (entry, _) = stream
        .finish(temperature_c, name)
        .map_err(|e| anyhow!("{}: {e}", path.display()))
        .data()?;
    Ok(entry)
}

/// Pushes every piece the reader thread parses into the characterisation and the gravity check.
fn feed(
    path: &Path,
    reader: ImuReader<thermonav_io::FileReader>,
    stream: &mut StreamingCharacterizer,
    gravity: &mut GravityCheck,
) -> Result<(), Failure> {
    let kind = reader.kind();
    std::thread::scope(|scope| {
        let (send, receive) = sync_channel::<Result<ImuSeries, ReadError>>(2);
        scope.spawn(move || read_pieces(reader, kind, |piece| send.send(piece).is_ok()));
        for piece in receive {
            let piece = piece.data()?;
            gravity.add(&piece);
            stream
                .push(&piece)
                .map_err(|e| anyhow!("{}: {e}", path.display()))
                .data()?;
        }
        Ok(())
    })
}

/// Pushes the IMU of the MCAP or ROS 1 bag at `path` (its `sensor_msgs/Imu` topic and `temp_c`
/// from its temperature topic, chosen by `topics` as when a bag is read in memory) into the
/// characterisation and the gravity check in pieces as the bag is read record by record:
/// memory is a piece and the temperature messages, whatever the bag's length.
fn feed_bag(
    path: &Path,
    (imu, topics): (&ImuOptions, &TopicNames),
    stream: &mut StreamingCharacterizer,
    gravity: &mut GravityCheck,
) -> Result<(), Failure> {
    if imu.mounting.is_some() || imu.rate_hz.is_some() {
        return Err(Failure::Data(anyhow!(
            "{}: a ROS bag has its own times and is read in FRD from ROS body axes: \
             --imu-rotation and --rate-hz apply to CSV input (thermonav convert BAG --out \
             imu.csv, then give the options with imu.csv)",
            path.display()
        )));
    }
    let mut refused = None;
    let pieces = StreamOptions {
        piece_len: PIECE_ROWS,
        stamp_lags: false,
        gnss: false,
    };
    let read = stream_imu_series(path, topics.choice(), pieces, &mut |piece| {
        gravity.add(&piece);
        stream.push(&piece).map_err(|e| {
            let text = format!("{}: {e}", path.display());
            refused = Some(anyhow!("{text}"));
            ReadError::new(
                path.display().to_string(),
                None,
                ReadErrorKind::Unusable(text),
            )
        })
    });
    if let Some(refusal) = refused {
        return Err(refusal).data();
    }
    read.map(|_| ()).map_err(crate::inputs::bag_failure)
}

/// The refusal of a record of a subset of the channels: streaming characterises all six.
fn check_all_six(reader: &ImuReader<thermonav_io::FileReader>, path: &Path) -> Result<(), Failure> {
    match reader.present_channels().len() {
        6 => Ok(()),
        n => Err(Failure::Usage(anyhow!(
            "{}: {n} of the six channels: --reading streaming characterises all six; read a subset in memory (--reading in-memory)",
            path.display()
        ))),
    }
}

/// The error for a file with a header and no data rows.
fn check_has_rows(stream: &StreamingCharacterizer, path: &Path) -> Result<(), Failure> {
    if stream.samples() == 0 {
        return Err(anyhow!(
            "{}: the file has a header but no data rows",
            path.display()
        ))
        .data();
    }
    Ok(())
}

/// The record's temperature: `--temperature-c`, else the mean of its `temp_c` column (a record
/// read whole or streamed).
pub(crate) fn temperature_of(
    given: Option<f64>,
    mean: Option<f64>,
    path: &Path,
) -> Result<f64, Failure> {
    match (given, mean) {
        (Some(t), _) => Ok(t),
        (None, Some(mean)) => crate::inputs::recorded_temperature(path, mean),
        (None, None) => Err(Failure::Usage(anyhow!(
            "{}: no temp_c column; give the temperature with --temperature-c",
            path.display()
        ))),
    }
}

/// Parses the file into pieces of [`PIECE_ROWS`] samples and hands each to `deliver`
/// (stopping when it returns false); a read error is delivered as the last item.
fn read_pieces(
    reader: ImuReader<thermonav_io::FileReader>,
    kind: SampleKind,
    mut deliver: impl FnMut(Result<ImuSeries, ReadError>) -> bool,
) {
    let mut piece = ImuSeries::new(kind);
    for sample in reader {
        match sample {
            Ok(sample) => piece.push(&sample),
            Err(e) => {
                deliver(Err(e));
                return;
            }
        }
        if piece.len() == PIECE_ROWS
            && !deliver(Ok(std::mem::replace(&mut piece, ImuSeries::new(kind))))
        {
            return;
        }
    }
    if !piece.is_empty() {
        deliver(Ok(piece));
    }
}
