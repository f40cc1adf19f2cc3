//! `thermonav bank show`: the bank, or the model selected for an operating temperature.

use crate::args::{BankAction, BankArgs, BankShowArgs};
use crate::bank_tables::print_bank_table;
use crate::failure::{Classify, Failure};
use crate::inputs::read_bank;
use crate::report::print_json;
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use thermonav::imu::Channel;
use thermonav::stoch::bank::{GaussMarkovSource, SelectedModel, Selection};

/// Runs `bank`.
pub fn run(args: &BankArgs) -> Result<(), Failure> {
    match &args.action {
        BankAction::Show(show) => run_show(show),
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
    let (selection, source): (Selection, GaussMarkovSource) =
        (args.method.into(), args.model.into());
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
