//! `thermonav evaluate`: the temperature-model tournament on one data set (the paper's Steps
//! 2-3): every candidate model through the same filter, GNSS outages, errors against the
//! reference, the ranking, and its Monte Carlo significance over shifted outage starts.

use crate::args::EvaluateArgs;
use crate::failure::{Classify, Failure};
use crate::integration::load_noise;
use crate::report::print_json;
use crate::tournament_files::{
    RecordPlan, check_some_model_ran, print_tournament_table, run_and_write, scenario_from_files,
};
use anyhow::anyhow;
use std::path::Path;
use thermonav::evaluation::candidates::{ThermalOptions, datasheet_model as datasheet_model_of};
use thermonav::evaluation::experiment::{Replicates, Tournament, TournamentPlan};
use thermonav::evaluation::oracle::TrueModel;
use thermonav::nav::engine::EngineSettings;
use thermonav::nav::sensor_model::{ImuStochasticModel, ScaleFactorPrior};
use thermonav_io::profile::read_profile;
use thermonav_io::truth::read_truth_file;

/// Runs `evaluate`.
pub fn run(args: &EvaluateArgs) -> Result<(), Failure> {
    let s = crate::settings::navigation::evaluate(args)?;
    let noise = load_noise(&s.noise)?;
    let engine = EngineSettings {
        geometry: s.geometry,
        aiding: s.aiding,
        max_imu_gap_s: s.max_imu_gap_s,
        ..EngineSettings::default()
    };
    let scale = ScaleFactorPrior::default();
    let truth = read_truth(s.truth.as_deref(), &scale)?;
    let records = RecordPlan {
        oracle: truth.as_ref(),
        ..RecordPlan::calibrated(noise.thermal(), s.compensation)
    };
    let (main, operating_c) = scenario_from_files(
        &s.files,
        engine,
        &s.outages,
        s.operating_temperature_c,
        records,
    )?;
    let plan = TournamentPlan {
        noise: noise.source(),
        thermal: ThermalOptions::of_scenario(&main, s.scheduling, s.compensation),
        operating_temperature_c: operating_c,
        source: s.source,
        filters: s.filters.clone(),
        datasheet: Some(datasheet_model(s.datasheet.as_deref())?),
        scale,
        oracle: truth.as_ref(),
    };
    let tournament = Tournament::new(&plan).map_err(|e| anyhow!("{e}")).data()?;
    let replicates = Replicates::ShiftedOutages {
        extra: s.extra_replicates,
        seed: s.seed,
    };
    let file = run_and_write(
        &tournament,
        &main,
        &replicates,
        (&s.out, &s.files.imu_options),
    )?;
    if args.json {
        print_json(&file)?;
    } else {
        print_tournament_table(&file);
    }
    check_some_model_ran(&file)
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
