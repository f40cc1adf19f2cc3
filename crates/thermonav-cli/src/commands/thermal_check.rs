//! `thermonav bank check`: a bank's thermal calibration against a record, block by block.

use crate::args::BankCheckArgs;
use crate::failure::{Classify, Failure};
use crate::inputs::read_thermal_calibration;
use crate::report::print_json;
use crate::settings::paths::Io;
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use thermonav::imu::Channel;
use thermonav::setting::positive;
use thermonav::stoch::thermal::check::{ChannelCheck, check_record};
use thermonav_io::ImuOptions;
use thermonav_plot::figures::DisplayUnits;

/// The JSON document of `bank check --json`.
#[derive(Debug, Serialize)]
struct CheckDocument {
    bank: String,
    record: String,
    block_s: f64,
    channels: BTreeMap<&'static str, ChannelCheck>,
}

/// Runs `bank check`.
pub fn run(args: &BankCheckArgs) -> Result<(), Failure> {
    positive("block_s", args.block_s)?;
    Io::new()
        .input("BANK", &args.bank)
        .input("RECORD", &args.record)
        .check()?;
    let calibration = read_thermal_calibration(&args.bank)?;
    let record = crate::thermal::calibration::sweep_series(
        &args.record,
        args.instance,
        (
            &ImuOptions::default(),
            &crate::settings::imu::topics(&args.topics),
        ),
    )?;
    let checks = check_record(&calibration, &record.series, args.block_s, args.power_on)
        .map_err(|e| anyhow!("{}: {e}", args.record.display()))
        .data()?;
    let document = CheckDocument {
        bank: args.bank.display().to_string(),
        record: args.record.display().to_string(),
        block_s: args.block_s,
        channels: checks.into_iter().map(|(c, k)| (c.name(), k)).collect(),
    };
    if args.json {
        return print_json(&document);
    }
    print_table(&document);
    Ok(())
}

/// The table: per channel, in deg/h and mg.
fn print_table(document: &CheckDocument) {
    println!(
        "{} against {} ({} s blocks; residual = observed − predicted)",
        document.bank, document.record, document.block_s
    );
    println!(
        "{:<3} {:>6} {:>6} {:>12} {:>12} {:>17} {:>16} {:>9} {:>17} {:>8}",
        "ch",
        "unit",
        "blocks",
        "rms before",
        "rms after",
        "rms before, shape",
        "rms after, shape",
        "coverage",
        "coverage, shape",
        "clamped"
    );
    for (&name, check) in &document.channels {
        let Some(channel) = Channel::from_name(name) else {
            continue;
        };
        let sensor = channel.sensor();
        let show = |si: f64| DisplayUnits::Navigation.rate(sensor, si);
        println!(
            "{:<3} {:>6} {:>6} {:>12.3} {:>12.3} {:>17.3} {:>16.3} {:>8.0}% {:>16.0}% {:>8}",
            name,
            DisplayUnits::Navigation.rate_unit(sensor),
            check.blocks.len(),
            show(check.rms_before),
            show(check.rms_after),
            show(check.rms_before_offset_removed),
            show(check.rms_after_offset_removed),
            100.0 * check.coverage,
            100.0 * check.coverage_offset_removed,
            check.blocks.iter().filter(|b| b.clamped).count()
        );
    }
    println!(
        "shape: the record's own mean residual taken off (and the band without its offset part); --json for every block"
    );
    print_unhelpful(document);
}

/// A line per channel whose compensated shape is worse than the record's own.
fn print_unhelpful(document: &CheckDocument) {
    for (&name, check) in &document.channels {
        let Some(channel) = Channel::from_name(name) else {
            continue;
        };
        if check.makes_worse() {
            let sensor = channel.sensor();
            let show = |si: f64| DisplayUnits::Navigation.rate(sensor, si);
            println!(
                "{name}: compensation makes this record worse (shape rms {:.3} {unit} after against {:.3} {unit} uncompensated): the calibration does not predict it",
                show(check.rms_after_offset_removed),
                show(check.rms_before_offset_removed),
                unit = DisplayUnits::Navigation.rate_unit(sensor)
            );
        }
    }
}
