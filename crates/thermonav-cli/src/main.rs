//! The `thermonav` command: arguments are parsed once, resolved into validated settings, and
//! handed to one function per subcommand.

mod args;
mod bank_building;
mod bank_streaming;
mod bank_tables;
mod campaign;
mod commands;
mod failure;
mod figure_data;
mod fir_design;
mod html_report;
mod html_temperature;
mod inputs;
mod integration;
mod noise_units;
mod production_lot;
mod progress;
mod report;
mod settings;
mod thermal_calibration;
mod thermal_scenarios;
mod tournament_files;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    end_quietly_when_stdout_closes();
    let cli = match args::Cli::try_parse() {
        Ok(cli) => cli,
        Err(error) => return print_clap_error(&error),
    };
    progress::set_quiet(cli.quiet);
    match commands::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            eprintln!("error: {failure}");
            failure.exit_code()
        }
    }
}

/// Help and version go to stdout with success; real usage errors exit with 2.
fn print_clap_error(error: &clap::Error) -> ExitCode {
    // Printing can only fail when the stream is closed; nothing useful is left to do then.
    let _ = error.print();
    if error.use_stderr() {
        ExitCode::from(failure::USAGE_EXIT_CODE)
    } else {
        ExitCode::SUCCESS
    }
}

/// A reader that stops early (`thermonav inspect FILE | head -1`) closes stdout; the next
/// `println!` then fails with a broken pipe, which `std` turns into a panic. That is no error
/// of the command: like ripgrep, it ends quietly with success. Every output file is complete
/// by then (results are printed after they are written, and files are renamed into place).
fn end_quietly_when_stdout_closes() {
    let report_panic = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let payload = info.payload();
        let message = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or_default();
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(0);
        }
        report_panic(info);
    }));
}
