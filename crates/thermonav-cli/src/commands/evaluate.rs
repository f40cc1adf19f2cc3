//! `thermonav evaluate`: the temperature-model tournament on one data set (the paper's Steps
//! 2-3): every candidate model through the same filter, GNSS outages, errors against the
//! reference, the ranking, and its Monte Carlo significance over shifted outage starts.

use crate::args::EvaluateArgs;
use crate::failure::{Classify, Failure};
use crate::inputs::read_bank;
use crate::report::print_json;
use crate::tournament_files::{print_tournament_table, run_and_write, scenario_from_files};
use anyhow::anyhow;
use thermonav::evaluation::candidates::DatasheetValues;
use thermonav::evaluation::experiment::{Replicates, Tournament, TournamentPlan};
use thermonav::nav::engine::EngineSettings;
use thermonav::nav::sensor_model::ScaleFactorPrior;

/// Runs `evaluate`.
pub fn run(args: &EvaluateArgs) -> Result<(), Failure> {
    let s = crate::settings::navigation::evaluate(args)?;
    let bank = read_bank(&s.bank)?;
    let engine = EngineSettings {
        geometry: s.geometry,
        ..EngineSettings::default()
    };
    let (main, operating_c) =
        scenario_from_files(&s.files, engine, &s.outages, s.operating_temperature_c)?;
    let plan = TournamentPlan {
        bank: &bank,
        operating_temperature_c: operating_c,
        source: s.source,
        filters: s.filters.clone(),
        datasheet: Some(DatasheetValues::adis16364()),
        scale: ScaleFactorPrior::default(),
    };
    let tournament = Tournament::new(&plan).map_err(|e| anyhow!("{e}")).data()?;
    let replicates = Replicates::ShiftedOutages {
        extra: s.extra_replicates,
        seed: s.seed,
    };
    let file = run_and_write(&tournament, &main, &replicates, &s.out)?;
    if args.json {
        return print_json(&file);
    }
    print_tournament_table(&file);
    Ok(())
}
