//! `thermonav evaluate`: the temperature-model tournament on one data set (the paper's Steps
//! 2-3): every candidate model through the same filter, GNSS outages, errors against the
//! reference, the ranking, and its Monte Carlo significance over shifted outage starts.

use crate::args::EvaluateArgs;
use crate::failure::{Classify, Failure};
use crate::integration::load_noise;
use crate::report::print_json;
use crate::settings::navigation::EvaluateSettings;
use crate::tournament_files::{
    RecordPlan, check_some_model_ran, print_tournament_table, run_and_write, scenario_from_files,
};
use anyhow::anyhow;
use std::path::Path;
use thermonav::evaluation::candidates::DatasheetValues;
use thermonav::evaluation::candidates::ThermalOptions;
use thermonav::evaluation::experiment::{Replicates, Tournament, TournamentPlan};
use thermonav::evaluation::oracle::TrueModel;
use thermonav::evaluation::tournament::Scenario;
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
        thermal: thermal_options(&s, &main),
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
    let file = run_and_write(&tournament, &main, &replicates, &s.out)?;
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

/// The record's temperature range and the settings' switches.
fn thermal_options(s: &EvaluateSettings, main: &Scenario) -> ThermalOptions {
    ThermalOptions {
        imu_temperature_range_c: main.temperature.as_ref().map(|t| t.range_c()),
        scheduling: s.scheduling,
        compensation: s.compensation,
    }
}

/// The data-sheet candidate: a profile's model at its reference temperature, or the ADIS16364
/// data sheet.
fn datasheet_model(profile: Option<&Path>) -> Result<ImuStochasticModel, Failure> {
    let scale = ScaleFactorPrior::default();
    let Some(path) = profile else {
        return Ok(DatasheetValues::adis16364().model(&scale));
    };
    let profile = read_profile(path).data()?;
    profile
        .stochastic_model(profile.reference_temperature_c, &scale)
        .map_err(|e| anyhow!("{}: {e}", path.display()))
        .data()
}
