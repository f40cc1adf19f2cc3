//! `thermonav bank show`: the bank, or the model selected for an operating temperature.

use super::characterize::print_bank_table;
use crate::args::{BankAction, BankArgs, BankShowArgs, GmSourceArg, SelectArg};
use crate::failure::{Classify, Failure};
use crate::report::print_json;
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;
use thermonav::imu::Channel;
use thermonav::stoch::bank::{GaussMarkovSource, ModelBank, SelectedModel, Selection};

/// Runs `bank`.
pub fn run(args: &BankArgs) -> Result<(), Failure> {
    match &args.action {
        BankAction::Show(show) => run_show(show),
    }
}

/// Reads and validates a bank file.
pub fn read_bank(path: &Path) -> Result<ModelBank, Failure> {
    thermonav_io::bank::read_bank_file(path).data()
}

/// The library source of a `--model` choice.
pub fn source_of(m: GmSourceArg) -> GaussMarkovSource {
    match m {
        GmSourceArg::IrregularMl => GaussMarkovSource::IrregularMl,
        GmSourceArg::ArBased => GaussMarkovSource::ArBased,
        GmSourceArg::AcfFit => GaussMarkovSource::AcfFit,
    }
}

/// The library rule of a `--method` choice.
pub fn selection_of(m: SelectArg) -> Selection {
    match m {
        SelectArg::Nearest => Selection::Nearest,
        SelectArg::Linear => Selection::Linear,
    }
}

#[derive(Debug, Serialize)]
struct SelectionJson {
    operating_temperature_c: f64,
    selection: Selection,
    model: GaussMarkovSource,
    channels: BTreeMap<&'static str, SelectedModel>,
}

fn run_show(args: &BankShowArgs) -> Result<(), Failure> {
    let bank = read_bank(&args.bank)?;
    let Some(t) = args.at_temperature_c else {
        if args.json {
            return print_json(&bank);
        }
        print_bank_table(&bank);
        return Ok(());
    };
    let (selection, source) = (selection_of(args.method), source_of(args.model));
    let mut channels = BTreeMap::new();
    for channel in Channel::ALL {
        let model = bank
            .select(t, channel, source, selection)
            .map_err(|e| anyhow!("{}: {e}", args.bank.display()))
            .data()?;
        channels.insert(channel.name(), model);
    }
    let doc = SelectionJson {
        operating_temperature_c: t,
        selection,
        model: source,
        channels,
    };
    if args.json {
        return print_json(&doc);
    }
    println!("model for {t} °C ({selection:?}, {source:?}):");
    for (name, m) in &doc.channels {
        println!(
            "{name:<4} Tc {:>10.2} s  sigma {:>12.4e}  from {:?}",
            m.correlation_time_s, m.sigma, m.placement
        );
    }
    Ok(())
}
