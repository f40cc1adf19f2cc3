//! `thermonav evaluate`: the temperature-model tournament on one data set (the paper's Steps
//! 2-3): every candidate model through the same filter, GNSS outages, errors against the
//! reference, the ranking, and its Monte Carlo significance over shifted outage starts. Outside
//! solutions (`--solution`: KF-GINS, RTKLIB, any trajectory CSV) are scored beside the
//! candidates with the same metrics, or alone when no IMU is given.

use crate::args::{EvaluateAction, EvaluateArgs};
use crate::banks::loaded_noise::load_noise;
use crate::failure::{Classify, Failure};
use crate::navigation::reference_input::{read_reference, span_of};
use crate::navigation::tournament_files::{
    Echo, EvaluationFile, FileScenario, RecordPlan, StartPlan, check_some_model_ran,
    print_tournament_table, run_and_write, scenario_from_files_with, write_outside_only,
};
use crate::navigation::tournament_shards;
use crate::report::print_json;
use crate::settings::navigation::{EvaluateSettings, FilterRun, OutsideInput};
use anyhow::anyhow;
use std::path::Path;
use thermonav::evaluation::candidates::{ThermalOptions, datasheet_model as datasheet_model_of};
use thermonav::evaluation::experiment::{Replicates, Tournament, TournamentPlan};
use thermonav::evaluation::metrics::Reference;
use thermonav::evaluation::oracle::TrueModel;
use thermonav::evaluation::outside::{OutsideResult, score_outside};
use thermonav::evaluation::scenario::Scenario;
use thermonav::evaluation::shard::Shard;
use thermonav::gnss::{GnssSdSource, GnssSdUse};
use thermonav::nav::engine::EngineSettings;
use thermonav::nav::outage::Outage;
use thermonav::nav::sensor_model::{ImuStochasticModel, ScaleFactorPrior};
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::Strictness;
use thermonav_io::outside_solution::read_solution_file;
use thermonav_io::profile::read_profile;
use thermonav_io::truth::read_truth_file;

/// An outside solution read: its input and its trajectory.
type Solution = (OutsideInput, Vec<TrajectoryPoint>);

/// Runs `evaluate`.
pub fn run(args: &EvaluateArgs) -> Result<(), Failure> {
    if let Some(EvaluateAction::Merge(merge)) = &args.action {
        return print_evaluation(&tournament_shards::merge(merge)?, merge.json);
    }
    let s = crate::settings::navigation::evaluate(args)?;
    let solutions = read_solutions(&s.solutions)?;
    let file = match (&s.run, s.shard) {
        (Some(run), Some(shard)) => return run_shard(&s, run, shard, args.json),
        (Some(run), None) => run_filters(&s, run, &solutions)?,
        (None, _) => score_alone(&s, &solutions)?,
    };
    print_evaluation(&file, args.json)
}

/// Prints what was written (the table, or the JSON document) and fails when no model ran.
fn print_evaluation(file: &EvaluationFile, json: bool) -> Result<(), Failure> {
    if json {
        print_json(file)?;
    } else {
        print_tournament_table(file);
    }
    check_some_model_ran(file)
}

/// One shard of the tournament (`--shard`), written for `evaluate merge`.
fn run_shard(
    s: &EvaluateSettings,
    run: &FilterRun,
    shard: Shard,
    json: bool,
) -> Result<(), Failure> {
    let (tournament, FileScenario { scenario: main, .. }) = prepare(s, run)?;
    let replicates = replicates_of(s);
    let parts = (&tournament, &main, &replicates);
    let written = tournament_shards::run_and_write_shard(parts, shard, (s, run))?;
    if json {
        return print_json(&written);
    }
    println!(
        "shard {}/{}: {} of {} runs\nwritten: {}",
        written.shard_index,
        written.shard_count,
        written.runs,
        written.total_runs,
        written.shard_file.display()
    );
    Ok(())
}

/// The Monte Carlo of `s`: shifted outage starts.
fn replicates_of(s: &EvaluateSettings) -> Replicates<'static> {
    Replicates::ShiftedOutages {
        extra: s.extra_replicates,
        seed: s.seed,
    }
}

/// Our tournament on the files, the outside solutions scored beside it.
fn run_filters(
    s: &EvaluateSettings,
    run: &FilterRun,
    solutions: &[Solution],
) -> Result<EvaluationFile, Failure> {
    let (tournament, made) = prepare(s, run)?;
    if let Some(warning) = made.time_offset.as_ref().and_then(|t| t.warning.as_deref()) {
        eprintln!("warning: {warning}");
    }
    let main = &made.scenario;
    let gnss_sd = GnssSdUse::of(&main.gnss, main.settings.default_position_sd_m);
    if gnss_sd.source != GnssSdSource::File {
        eprintln!("note: GNSS position sd: {}", gnss_sd.words());
    }
    let outside = score_all(solutions, main.reference(), windows(main))?;
    run_and_write(
        &tournament,
        main,
        &replicates_of(s),
        &outside,
        (&s.out, &echo(s, run, &made)),
    )
}

/// The tournament of `s` and its main scenario, from the files.
fn prepare(s: &EvaluateSettings, run: &FilterRun) -> Result<(Tournament, FileScenario), Failure> {
    let noise = load_noise(&run.noise, run.thermal_from.as_deref())?;
    let scale = ScaleFactorPrior::default();
    let truth = read_truth(s.truth.as_deref(), &scale)?;
    let records = RecordPlan {
        oracle: truth.as_ref(),
        ..RecordPlan::calibrated(noise.thermal(), s.compensation)
    };
    let engine = s.options.engine(EngineSettings::default());
    let integrate_run = s.integrate_run();
    let start = StartPlan {
        initial_from: run.initial_from.as_deref(),
        time_offset: (s.time_offset_search.as_ref()).map(|t| (t, &integrate_run, noise.model())),
    };
    let settings = (engine, &s.outages, s.temperature.given_c());
    let made = scenario_from_files_with(&run.files, settings, records, start)?;
    let (main, operating_c) = (&made.scenario, made.operating_temperature_c);
    let plan = TournamentPlan {
        noise: noise.source(),
        thermal: ThermalOptions::of_scenario(main, s.scheduling, s.compensation),
        operating_temperature_c: operating_c,
        source: s.options.gauss_markov,
        filters: s.filters.clone(),
        datasheet: Some(datasheet_model(s.datasheet.as_deref())?),
        scale,
        oracle: truth.as_ref(),
    };
    let tournament = Tournament::new(&plan).map_err(|e| anyhow!("{e}")).data()?;
    let scaled = tournament.with_process_noise_scale(s.options.process_noise_scale);
    Ok((scaled, made))
}

/// What evaluation.json repeats of the command line: the IMU's rotation, the run options and
/// the time offset the record was shifted by.
fn echo(s: &EvaluateSettings, run: &FilterRun, made: &FileScenario) -> Echo {
    Echo {
        imu_options: run.files.imu_options,
        run_options: Some(s.options.clone()),
        time_offset: made.time_offset.clone(),
    }
}

/// The main scenario's outage windows.
fn windows(main: &Scenario) -> &[Outage] {
    main.settings.outages.windows()
}

/// Only the outside solutions, against the reference, with the outages laid over its span.
fn score_alone(s: &EvaluateSettings, solutions: &[Solution]) -> Result<EvaluationFile, Failure> {
    let reference = read_reference(&s.reference)?;
    let Some(span) = span_of(&reference.points) else {
        return Err(anyhow!("{}: no point", s.reference.display())).data();
    };
    let outages = s
        .outages
        .resolve(span)
        .map_err(|e| {
            anyhow!(
                "--outages over the reference {}: {e}",
                s.reference.display()
            )
        })
        .usage()?;
    let scored = Reference {
        points: &reference.points,
        content: reference.content(),
    };
    let outside = score_all(solutions, scored, outages.windows())?;
    write_outside_only((outages.windows(), scored.content), &outside, &s.out)
}

/// Every --solution read (all before any is scored, so a bad file fails early).
fn read_solutions(inputs: &[OutsideInput]) -> Result<Vec<Solution>, Failure> {
    let read = |input: &OutsideInput| {
        let points = read_solution_file(&input.path, input.format, Strictness::Strict).data()?;
        Ok((input.clone(), points))
    };
    inputs.iter().map(read).collect()
}

/// Every solution scored against `reference` in `outages`, errors naming its file.
fn score_all(
    solutions: &[Solution],
    reference: Reference,
    outages: &[Outage],
) -> Result<Vec<OutsideResult>, Failure> {
    let score = |(input, points): &Solution| {
        score_outside(&input.label, points, reference, outages)
            .map_err(|e| anyhow!("{} ({}): {e}", input.path.display(), input.format.name()))
            .data()
    };
    solutions.iter().map(score).collect()
}

/// The survey truth of `--truth`, when given.
fn read_truth(path: Option<&Path>, scale: &ScaleFactorPrior) -> Result<Option<TrueModel>, Failure> {
    path.map(|p| read_truth_file(p, scale)).transpose().data()
}

/// The data-sheet candidate: a profile's model at its reference temperature, or the ADIS16364
/// data sheet.
fn datasheet_model(profile: Option<&Path>) -> Result<ImuStochasticModel, Failure> {
    let read = profile.map(read_profile).transpose().data()?;
    let model = datasheet_model_of(read.as_ref(), &ScaleFactorPrior::default());
    let named = |e| anyhow!("{}: {e}", profile.unwrap_or(Path::new("")).display());
    model.map_err(named).data()
}
