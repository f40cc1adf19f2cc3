//! One function per subcommand.

mod allan;
mod ar;
mod bank;
mod characterize;
mod compensate;
mod convert;
mod demo;
mod evaluate;
mod filter;
mod fir;
mod gmwm;
mod inspect;
mod integrate;
mod lot;
mod plot;
mod report;
mod simulate;
mod thermal_check;

use crate::args::{BankAction, Cli, Command};
use crate::failure::Failure;

/// Runs the chosen subcommand.
pub fn run(cli: Cli) -> Result<(), Failure> {
    match cli.command {
        Command::Demo(args) => demo::run(&args),
        Command::Inspect(args) => inspect::run(&args),
        Command::Fir(args) => fir::run(&args),
        Command::Filter(args) => filter::run(&args),
        Command::Allan(args) => allan::run(&args),
        Command::Ar(args) => ar::run(&args),
        Command::Gmwm(args) => gmwm::run(&args),
        Command::Characterize(args) => characterize::run(&args),
        Command::Bank(args) => match &args.action {
            BankAction::Show(show) => bank::run_show(show),
            BankAction::Export(export) => bank::run_export(export),
            BankAction::Check(check) => thermal_check::run(check),
        },
        Command::Lot(args) => lot::run(&args),
        Command::Simulate(args) => simulate::run(&args),
        Command::Integrate(args) => integrate::run(&args),
        Command::Evaluate(args) => evaluate::run(&args),
        Command::Convert(args) => convert::run(&args),
        Command::Plot(args) => plot::run(&args),
        Command::Report(args) => report::run(&args),
        Command::Compensate(args) => compensate::run(&args),
    }
}
