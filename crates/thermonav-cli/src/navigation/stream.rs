//! `integrate` in bounded memory: the IMU file read twice as a stream (once to survey it, once
//! to run), the reference trajectory read for its one starting point, and the solution, state
//! and innovation files written as the filter goes ([`SolutionFilesWriter`], temporary files
//! renamed at the end; a failed run leaves none). The run is the library's
//! [`thermonav::nav::stream`]; [`crate::navigation::integration`] chooses it when the run allows.

use crate::banks::loaded_noise::LoadedNoise;
use crate::failure::{Classify, Failure};
use crate::navigation::outcome::{ImuReading, Summary, run_failure, summarize, write_epochs};
use crate::settings::navigation::IntegrateSettings;
use thermonav::gnss::GnssFix;
use thermonav::imu::ImuSeries;
use thermonav::ins::state::Increment;
use thermonav::nav::engine::increments_of_samples;
use thermonav::nav::report::RunReport;
use thermonav::nav::run::Start;
use thermonav::nav::solution::with_sink_on_own_thread;
use thermonav::nav::stream::{PreparedStream, RecordSurvey, StreamRunError, prepare_stream};
use thermonav::time::Timestamp;
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::imu::GravityCheck;
use thermonav_io::reference::ReferenceKind;
use thermonav_io::solution::SolutionFilesWriter;
use thermonav_io::trajectory::TrajectoryReader;
use thermonav_io::{ImuReader, ReadError, Strictness, read_gnss_file};

/// Samples per piece of the gravity-magnitude check of the survey.
const PIECE_SAMPLES: usize = 8192;

/// The first pass over the IMU file: every row read and checked as the whole-record reader
/// does (file:line errors, the g-for-m/s² check), the survey the run needs kept.
pub fn survey(settings: &IntegrateSettings) -> Result<RecordSurvey, Failure> {
    let reader = open_imu(settings)?;
    let kind = reader.kind();
    let mut survey = RecordSurvey::new(kind);
    let mut gravity = GravityCheck::default();
    let mut piece = ImuSeries::new(kind);
    for sample in reader {
        let sample = sample.data()?;
        survey.add(&sample);
        piece.push(&sample);
        if piece.len() == PIECE_SAMPLES {
            gravity.add(&piece);
            piece = ImuSeries::new(kind);
        }
    }
    gravity.add(&piece);
    let input = settings.imu.display().to_string();
    gravity.verdict(&input, Strictness::Strict).data()?;
    Ok(survey)
}

fn open_imu(settings: &IntegrateSettings) -> Result<ImuReader<thermonav_io::FileReader>, Failure> {
    ImuReader::open_with(&settings.imu, Strictness::Strict, &settings.imu_options).data()
}

/// The IMU file's increments, read as they are asked for.
fn increments(
    settings: &IntegrateSettings,
) -> Result<impl Iterator<Item = Result<Increment, ReadError>>, Failure> {
    let reader = open_imu(settings)?;
    Ok(increments_of_samples(reader.kind(), reader))
}

/// Runs `integrate` streamed on a surveyed record.
pub fn integrate(
    settings: &IntegrateSettings,
    noise: &LoadedNoise,
    survey: &RecordSurvey,
) -> Result<Summary, Failure> {
    let gnss = read_gnss_file(&settings.gnss, Strictness::Strict).data()?;
    let reference = starting_point(settings, survey, &gnss)?;
    let start = reference.as_deref().map_or(Start::Align, Start::Reference);
    let mut stream = increments(settings)?;
    let prepared = prepare_stream(
        survey,
        &mut stream,
        gnss,
        noise.model(),
        start,
        &settings.run,
    )
    .map_err(|e| stream_failure(e, settings))?;
    for note in &prepared.notes {
        eprintln!("note: {} {note}", settings.imu.display());
    }
    let files = &settings.outputs;
    let mut writer =
        SolutionFilesWriter::create(&files.solution, &files.states, &files.innovations).data()?;
    let outcome = run_with_progress(prepared, stream, &mut writer)
        .map_err(|e| stream_failure(e, settings))?;
    let report = RunReport::of_summary(&outcome.outcome, &outcome.summary);
    if let Some([trajectory, states]) = &files.smoothed {
        write_epochs(trajectory, states, &outcome.outcome.solution.smoothed)?;
    }
    writer.finish().data()?;
    Ok(summarize(settings, ImuReading::Streamed, report))
}

fn run_with_progress(
    prepared: PreparedStream,
    rest: impl Iterator<Item = Result<Increment, ReadError>>,
    writer: &mut SolutionFilesWriter,
) -> Result<thermonav::nav::stream::StreamOutcome, StreamRunError<ReadError>> {
    let label = format!("integrating ({})", prepared.engine().filter.name());
    let bar = crate::progress::bar(prepared.imu_samples(), &label);
    // The files are formatted and written on a thread of their own while the filter runs.
    let outcome = with_sink_on_own_thread(writer, |sink| {
        prepared.run(rest, sink, &mut |n| bar.set_position(n as u64))
    })?;
    bar.finish_and_clear();
    Ok(outcome)
}

fn stream_failure(error: StreamRunError<ReadError>, settings: &IntegrateSettings) -> Failure {
    match error {
        StreamRunError::Run(e) => run_failure(e, settings),
        StreamRunError::Input(e) => Failure::Data(e.into()),
    }
}

/// Whether the reference at `path` is our trajectory CSV (read row by row below).
fn is_trajectory_csv(path: &std::path::Path) -> Result<bool, Failure> {
    let kind = crate::navigation::reference_input::reference_kind(path)?;
    Ok(kind == ReferenceKind::TrajectoryCsv)
}

/// The one reference point a run starts from (`--initial-from`): the last in the file at or
/// before the first fix (the first increment without fixes), or the first; every row read and
/// checked as the whole-file reader does. `None` without `--initial-from`; an empty `Vec` for
/// a file without points (the run then says so).
fn starting_point(
    settings: &IntegrateSettings,
    survey: &RecordSurvey,
    gnss: &[GnssFix],
) -> Result<Option<Vec<TrajectoryPoint>>, Failure> {
    let Some(path) = &settings.initial_from else {
        return Ok(None);
    };
    if !is_trajectory_csv(path)? {
        // A .nav is read whole (the run picks its point); a position-only kind is refused.
        let run = (survey.increment_span(), settings.imu.as_path());
        return crate::navigation::reference_input::read_start_reference(path, run).map(Some);
    }
    let at: Option<Timestamp> = gnss
        .first()
        .map(|f| f.time)
        .or(survey.first_increment_time());
    let (mut first, mut last, mut chosen) = (None, None, None);
    for point in TrajectoryReader::open(path, Strictness::Strict).data()? {
        let point = point.data()?;
        first = first.or(Some(point));
        last = Some(point.time);
        if at.is_some_and(|t| point.time <= t) {
            chosen = Some(point);
        }
    }
    if let Some(span) = first.map(|p| p.time).zip(last) {
        let reference = (span, ReferenceKind::TrajectoryCsv, path.as_path());
        let run = (survey.increment_span(), settings.imu.as_path());
        crate::navigation::reference_input::check_span_overlap(reference, run)?;
    }
    Ok(Some(chosen.or(first).into_iter().collect()))
}
