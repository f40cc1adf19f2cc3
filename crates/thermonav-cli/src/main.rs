//! The `thermonav` command: arguments are parsed once, resolved into validated settings, and
//! handed to one function per subcommand.

mod args;
mod banks;
mod campaign;
mod commands;
mod failure;
mod fir_design;
mod html;
mod inputs;
mod navigation;
mod progress;
mod report;
mod settings;
mod thermal;
mod thermal_scenarios;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    end_quietly_when_stdout_closes();
    remove_temporaries_on_interrupt();
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

/// SIGINT (Ctrl-C), SIGTERM and SIGHUP end the command at once, after deleting the temporary
/// file of every output not yet renamed into place, with the shell's exit code 128 + signal;
/// outputs already complete stay, inputs are never touched.
fn remove_temporaries_on_interrupt() {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            thermonav_io::remove_pending_temporaries();
            std::process::exit(128 + signal);
        }
    });
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
