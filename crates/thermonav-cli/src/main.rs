//! The `thermonav` command.

use std::process::ExitCode;

fn main() -> ExitCode {
    println!("thermonav");
    ExitCode::SUCCESS
}
