//! `thermonav characterize`: the temperature model bank from static records.

use crate::args::CharacterizeArgs;
use crate::bank_building::build_job_bank;
use crate::bank_tables::print_bank_table;
use crate::failure::Failure;
use crate::production_lot::characterize_lot;
use crate::report::print_json;
use crate::settings::characterization::{CharacterizeJob, characterize};
use serde::Serialize;
use std::path::Path;
use thermonav::stoch::bank::{GaussMarkovEstimate, ModelBank};

#[derive(Debug, Serialize)]
struct Summary<'a> {
    bank: String,
    temperatures_c: Vec<f64>,
    entries: Vec<EntrySummary<'a>>,
}

#[derive(Debug, Serialize)]
struct EntrySummary<'a> {
    temperature_c: f64,
    source: &'a str,
    channels: Vec<ChannelSummary<'a>>,
}

#[derive(Debug, Serialize)]
struct ChannelSummary<'a> {
    channel: &'static str,
    unit: &'a str,
    irregular_ml: &'a GaussMarkovEstimate,
    ar_based: &'a GaussMarkovEstimate,
    acf_fit: &'a GaussMarkovEstimate,
    white_noise_density: Option<f64>,
}

/// Runs `characterize`.
pub fn run(args: &CharacterizeArgs) -> Result<(), Failure> {
    let job = match characterize(args)? {
        CharacterizeJob::Lot(lot) => return characterize_lot(&lot, args.json),
        CharacterizeJob::Bank(job) => job,
    };
    let bank = build_job_bank(&job)?;
    if args.json {
        return print_json(&summarize(&bank, &job.out));
    }
    print_bank_table(&bank);
    println!("\nbank written to {}", job.out.display());
    Ok(())
}

fn summarize<'a>(bank: &'a ModelBank, out: &Path) -> Summary<'a> {
    Summary {
        bank: out.display().to_string(),
        temperatures_c: bank.temperatures_c(),
        entries: bank
            .entries
            .iter()
            .map(|e| EntrySummary {
                temperature_c: e.temperature_c,
                source: &e.source,
                channels: e
                    .channels
                    .iter()
                    .map(|(c, m)| ChannelSummary {
                        channel: c.name(),
                        unit: &m.unit,
                        irregular_ml: &m.gauss_markov.irregular_ml,
                        ar_based: &m.gauss_markov.ar_based,
                        acf_fit: &m.gauss_markov.acf_fit,
                        white_noise_density: m.allan.white_noise_density,
                    })
                    .collect(),
            })
            .collect(),
    }
}
