//! One navigation run on an IMU record read as it goes, in memory bounded whatever the
//! record's length: what [`super::run`] does with a whole record, with the record read twice.
//!
//! 1. A first pass ([`RecordSurvey`]) gives what needs the whole record before the run: its
//!    extent (the outages are laid over it, the progress is counted against it, a smoothed run
//!    is checked against it), the mean of its temp_c column (the model's temperature) and its
//!    temperature track (the scheduled models; it holds only the changes of temperature).
//! 2. [`prepare_stream`] reads the second pass's increments only as far as the start needs
//!    (the alignment levels on the IMU just after its fix: the head is read in doubling spans
//!    until it covers that, so it is the alignment of the whole record).
//! 3. [`PreparedStream::run`] feeds the head and then the rest of the stream to the filter
//!    ([`run_streaming`]), whose every epoch and innovation goes to the caller's sink and to a
//!    [`SolutionSummary`] for the report. Only the smoother's forward history (when asked)
//!    grows with the record.
//!
//! A bank's thermal compensation of the samples is the one step not streamed:
//! [`is_streamable`] says when a run needs it, and the caller then reads the record whole.

use super::alignment::AlignmentError;
use super::alignment::{InitialBiasSource, InitialUncertainty};
use super::engine::{EngineSettings, Filtering, StreamError};
use super::navigate::run_streaming;
use super::run::{
    LEVELLING_S, NO_TEMPERATURE_NOTE, NoiseModel, RunError, RunModels, RunOutcome, RunSettings,
    Start, StartFound, initial_estimate, initial_uncertainty, with_outages_over,
};
use super::schedule::{
    Compensation, CompensationOutcome, ScheduleError, Scheduling, TemperatureTrack,
    compensate_record,
};
use super::solution::{Solution, SolutionSink, SolutionSummary};
use crate::gnss::GnssFix;
use crate::imu::{ImuSample, ImuSeries, SampleKind};
use crate::ins::state::Increment;
use crate::time::Timestamp;
use std::time::Instant;

/// What a pass over the IMU record gives before the run, sample by sample.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordSurvey {
    kind: SampleKind,
    samples: usize,
    /// Times of the first two samples (the second is the first increment's) and the last.
    first: Option<Timestamp>,
    second: Option<Timestamp>,
    last: Option<Timestamp>,
    temperature_sum_c: f64,
    temperature_samples: usize,
    /// The temperature track's changes: a sample's time and temperature when it differs from
    /// the last kept one (what [`TemperatureTrack`] keeps of a series).
    change_times: Vec<Timestamp>,
    change_c: Vec<f64>,
}

impl RecordSurvey {
    /// An empty survey of a record of `kind`.
    pub fn new(kind: SampleKind) -> Self {
        Self {
            kind,
            samples: 0,
            first: None,
            second: None,
            last: None,
            temperature_sum_c: 0.0,
            temperature_samples: 0,
            change_times: Vec::new(),
            change_c: Vec::new(),
        }
    }

    /// Adds the next sample.
    pub fn add(&mut self, sample: &ImuSample) {
        match self.samples {
            0 => self.first = Some(sample.time),
            1 => self.second = Some(sample.time),
            _ => {}
        }
        self.samples += 1;
        self.last = Some(sample.time);
        let Some(t) = sample.temperature_c else {
            return;
        };
        self.temperature_sum_c += t;
        self.temperature_samples += 1;
        if self.change_c.last() != Some(&t) {
            self.change_times.push(sample.time);
            self.change_c.push(t);
        }
    }

    /// Samples seen.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// Whether the record had temperatures.
    pub fn has_temperature(&self) -> bool {
        self.temperature_samples > 0
    }

    /// Mean of the temp_c column, °C (as [`ImuSeries::mean_temperature_c`]).
    pub fn mean_temperature_c(&self) -> Option<f64> {
        (self.temperature_samples > 0)
            .then(|| self.temperature_sum_c / self.temperature_samples as f64)
    }

    /// The temperature track (as [`TemperatureTrack::of_series`]).
    ///
    /// # Errors
    /// As [`TemperatureTrack::new`].
    pub fn track(&self) -> Result<Option<TemperatureTrack>, ScheduleError> {
        match self.change_c.is_empty() {
            true => Ok(None),
            false => TemperatureTrack::new(&self.change_times, &self.change_c).map(Some),
        }
    }

    /// Time of the first increment (the second sample).
    pub fn first_increment_time(&self) -> Option<Timestamp> {
        self.second
    }

    /// Times of the first and the last increment.
    pub fn increment_span(&self) -> Option<(Timestamp, Timestamp)> {
        Some((self.second?, self.last?))
    }
}

/// Whether a run can be streamed: not when the bank's thermal calibration would be
/// subtracted from the record's samples (a bank with one, compensation on, temperatures in
/// the record), which [`super::run::prepare`] does on the whole record.
pub fn is_streamable(noise: NoiseModel, settings: &RunSettings, survey: &RecordSurvey) -> bool {
    let compensates = noise.thermal().is_some()
        && settings.compensation == Compensation::WhenCalibrated
        && survey.has_temperature();
    !compensates
}

/// Why a streamed run failed: the run (with the input it is about), or the stream.
#[derive(Debug, Clone, PartialEq)]
pub enum StreamRunError<E> {
    /// As [`super::run::prepare`] and [`super::run::PreparedRun::run`].
    Run(RunError),
    /// The increments could not be read.
    Input(E),
}

impl<E> From<RunError> for StreamRunError<E> {
    fn from(error: RunError) -> Self {
        StreamRunError::Run(error)
    }
}

/// A streamed run ready to go: models chosen, outages laid, start found, the head of the
/// increments read to find it.
#[derive(Debug)]
pub struct PreparedStream {
    models: RunModels,
    compensation: CompensationOutcome,
    head: Vec<Increment>,
    gnss: Vec<GnssFix>,
    engine: EngineSettings,
    start: StartFound,
    uncertainty: InitialUncertainty,
    bias_source: InitialBiasSource,
    increments: usize,
    last_time: Timestamp,
    /// What the caller may want to tell the user (as [`super::run::PreparedRun::notes`]).
    pub notes: Vec<String>,
}

/// [`super::run::prepare`] of a record surveyed by `survey` whose increments are read from
/// `increments` (only as far as the start needs; [`PreparedStream::run`] takes the rest).
/// Not for a run [`is_streamable`] refuses: its compensation would be skipped.
///
/// # Errors
/// [`StreamRunError::Run`] as [`super::run::prepare`]; [`StreamRunError::Input`] for an
/// increment that fails to read.
pub fn prepare_stream<E>(
    survey: &RecordSurvey,
    increments: &mut impl Iterator<Item = Result<Increment, E>>,
    gnss: Vec<GnssFix>,
    noise: NoiseModel,
    start: Start,
    settings: &RunSettings,
) -> Result<PreparedStream, StreamRunError<E>> {
    let models = RunModels::of_record(settings, noise, survey.mean_temperature_c(), || {
        survey.track()
    })?;
    let mut notes = Vec::new();
    if settings.scheduling != Scheduling::Fixed && models.scheduled.is_none() {
        notes.push(NO_TEMPERATURE_NOTE.to_string());
    }
    // Streamed only when nothing is subtracted: the outcome is that of a record without
    // temperatures (compensation off, no calibration, or none to apply it by).
    let mut no_samples = ImuSeries::new(survey.kind);
    let compensation = compensate_record(&mut no_samples, noise.thermal(), settings.compensation);
    let (prior, bias_source) = initial_uncertainty(noise, &compensation, &models.model);
    let span = survey.increment_span().ok_or(RunError::TooShort)?;
    let engine = with_outages_over(&settings.engine, &settings.outages, span)?;
    let (head, start) = head_and_start(start, increments, &gnss, &engine)?;
    let uncertainty = start.uncertainty(prior);
    Ok(PreparedStream {
        models,
        compensation,
        head,
        gnss,
        engine,
        start,
        uncertainty,
        bias_source,
        increments: survey.samples() - 1,
        last_time: span.1,
        notes,
    })
}

/// The first increments, read until the start found from them is the whole record's, and
/// that start.
fn head_and_start<E>(
    start: Start,
    increments: &mut impl Iterator<Item = Result<Increment, E>>,
    gnss: &[GnssFix],
    engine: &EngineSettings,
) -> Result<(Vec<Increment>, StartFound), StreamRunError<E>> {
    let mut head = Vec::new();
    let mut horizon_s = 60.0;
    loop {
        let exhausted = fill(&mut head, increments, horizon_s)?;
        let found = initial_estimate(start, &head, gnss, engine);
        let levelled = |f: &StartFound| match start {
            Start::Reference(_) => true,
            Start::Align => (head.last()).is_some_and(|l| {
                l.time > f.initial.nav.time
                    && l.time.since(f.initial.nav.time).as_seconds() > LEVELLING_S
            }),
        };
        match found {
            Ok(f) if exhausted || levelled(&f) => return Ok((head, f)),
            Ok(_) | Err(RunError::Alignment(AlignmentError::NoImu(_))) if !exhausted => {}
            other => return Ok((head, other?)),
        }
        horizon_s *= 2.0;
    }
}

/// Reads increments into `head` until it spans `horizon_s`; true when the stream ended first.
fn fill<E>(
    head: &mut Vec<Increment>,
    increments: &mut impl Iterator<Item = Result<Increment, E>>,
    horizon_s: f64,
) -> Result<bool, StreamRunError<E>> {
    loop {
        if let (Some(a), Some(b)) = (head.first(), head.last()) {
            if b.time.since(a.time).as_seconds() >= horizon_s {
                return Ok(false);
            }
        }
        match increments.next() {
            None => return Ok(true),
            Some(inc) => head.push(inc.map_err(StreamRunError::Input)?),
        }
    }
}

/// What a streamed run gave: the outcome (its solution holds no epochs and no innovations:
/// they went to the sink) and the summary its report is made of
/// ([`super::report::RunReport::of_summary`]).
#[derive(Debug)]
pub struct StreamOutcome {
    /// The run's outcome.
    pub outcome: RunOutcome,
    /// What the report needs of the records.
    pub summary: SolutionSummary,
}

impl PreparedStream {
    /// IMU increments in the record (for a progress bar's length).
    pub fn imu_samples(&self) -> usize {
        self.increments
    }

    /// The filter's settings, outages laid.
    pub fn engine(&self) -> &EngineSettings {
        &self.engine
    }

    /// Runs the filter over the head and then `rest`, every record to `sink`; `progress` is
    /// told the increments processed.
    ///
    /// # Errors
    /// [`StreamRunError::Run`] with [`RunError::Nav`]; [`StreamRunError::Input`].
    pub fn run<E>(
        self,
        rest: impl Iterator<Item = Result<Increment, E>>,
        sink: &mut dyn SolutionSink,
        progress: &mut dyn FnMut(usize),
    ) -> Result<StreamOutcome, StreamRunError<E>> {
        let started = Instant::now();
        let filtering = Filtering {
            initial: self.start.initial,
            p0: self.uncertainty.covariance(),
            schedule: self.models.schedule(),
            settings: &self.engine,
        };
        let mut summary = SolutionSummary::default();
        let records = self.head.into_iter().map(Ok).chain(rest);
        let mut both = (&mut summary, sink);
        let tail = run_streaming(
            filtering,
            records,
            &self.gnss,
            Some(self.last_time),
            &mut both,
            progress,
        )
        .map_err(|e| match e {
            StreamError::Nav(e) => StreamRunError::Run(RunError::Nav(e)),
            StreamError::Input(e) => StreamRunError::Input(e),
        })?;
        let solution = Solution {
            epochs: Vec::new(),
            innovations: Vec::new(),
            imu_samples: tail.imu_samples,
            smoothed: tail.smoothed,
        };
        let gnss_sd = crate::gnss::GnssSdUse::of(&self.gnss, self.engine.default_position_sd_m);
        let outcome = RunOutcome {
            gnss_sd,
            processing_s: started.elapsed().as_secs_f64(),
            models: self.models,
            compensation: self.compensation,
            engine: self.engine,
            solution,
            initial: self.start.source,
            course_baseline: self.start.course_baseline,
            still_start: self.start.still_start,
            still_decision: self.start.still_decision,
            uncertainty: self.uncertainty,
            bias_source: self.bias_source,
        };
        Ok(StreamOutcome { outcome, summary })
    }
}
