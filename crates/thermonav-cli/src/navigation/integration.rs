//! One `integrate` run from its settings: the 21-state GNSS/INS filter on an IMU and a GNSS
//! file with the bank's (or a profile's) noise model at the chosen temperature; writes the
//! solution trajectory, its state and innovation files, and returns the summary. Shared by
//! `integrate` and `demo`; the run itself is the library's [`thermonav::nav::run`].

use crate::banks::loaded_noise::{LoadedNoise, load_noise};
use crate::failure::{Classify, Failure};
use crate::navigation::outcome::{ImuReading, Summary, run_failure, summarize, write_epochs};
use crate::navigation::reference_input::record_span;
use crate::settings::navigation::{IntegrateSettings, SolutionFiles};
use thermonav::nav::report::RunReport;
use thermonav::nav::run::{PreparedRun, RunError, RunOutcome, Start, prepare};
use thermonav::nav::solution::Solution;
use thermonav::nav::stream::is_streamable;
use thermonav::nav::time_offset::{estimate_time_offset, shifted};
use thermonav_io::solution::write_innovations_file;
use thermonav_io::{Strictness, read_gnss_file, read_imu_file_with};

/// Runs the filter on the files of `settings`, writes the outputs and returns the summary.
pub fn integrate(settings: &IntegrateSettings) -> Result<Summary, Failure> {
    let noise = load_noise(&settings.noise, settings.thermal_from.as_deref())?;
    let notes = noise.notes_on_record(&settings.imu, &settings.imu_options);
    for note in &notes {
        eprintln!("note: {} {}", settings.imu.display(), note.note);
    }
    // The offset search runs the filter many times on the record read once.
    let survey = match settings.in_memory || settings.time_offset_search.is_some() {
        true => None,
        false => Some(crate::navigation::stream::survey(settings)?),
    };
    let mut summary = match survey.filter(|s| is_streamable(noise.model(), &settings.run, s)) {
        Some(survey) => crate::navigation::stream::integrate(settings, &noise, &survey),
        None => integrate_in_memory(settings, &noise),
    }?;
    summary.record_notes = notes;
    Ok(summary)
}

/// [`integrate`] with the record read whole and the solution kept until it is written.
fn integrate_in_memory(
    settings: &IntegrateSettings,
    noise: &LoadedNoise,
) -> Result<Summary, Failure> {
    let series =
        read_imu_file_with(&settings.imu, Strictness::Strict, &settings.imu_options).data()?;
    let gnss = read_gnss_file(&settings.gnss, Strictness::Strict).data()?;
    let reference = match &settings.initial_from {
        Some(path) => {
            let run = (record_span(&series), settings.imu.as_path());
            Some(crate::navigation::reference_input::read_start_reference(
                path, run,
            )?)
        }
        None => None,
    };
    let start = reference.as_deref().map_or(Start::Align, Start::Reference);
    let time_offset = match &settings.time_offset_search {
        Some(search) => Some(
            estimate_time_offset(&series, &gnss, noise.model(), start, &settings.run, search)
                .map_err(|e| run_failure(e, settings))?,
        ),
        None => None,
    };
    let series = match &time_offset {
        Some(estimate) => shifted(&series, estimate.applied_offset_s),
        None => series,
    };
    let prepared = prepare(series, gnss, noise.model(), start, &settings.run)
        .map_err(|e| run_failure(e, settings))?;
    for note in &prepared.notes {
        eprintln!("note: {} {note}", settings.imu.display());
    }
    let outcome = run_with_progress(prepared).map_err(|e| run_failure(e, settings))?;
    write_outputs(&settings.outputs, &outcome.solution)?;
    let mut summary = summarize(settings, ImuReading::Whole, RunReport::of(&outcome));
    summary.time_offset = time_offset;
    Ok(summary)
}

fn run_with_progress(prepared: PreparedRun) -> Result<RunOutcome, RunError> {
    let label = format!("integrating ({})", prepared.engine().filter.name());
    let bar = crate::progress::bar(prepared.imu_samples(), &label);
    let outcome = prepared.run(&mut |n| bar.set_position(n as u64))?;
    bar.finish_and_clear();
    Ok(outcome)
}

fn write_outputs(files: &SolutionFiles, solution: &Solution) -> Result<(), Failure> {
    write_epochs(&files.solution, &files.states, &solution.epochs)?;
    if let Some([trajectory, states]) = &files.smoothed {
        write_epochs(trajectory, states, &solution.smoothed)?;
    }
    write_innovations_file(&files.innovations, &solution.innovations).data()
}
