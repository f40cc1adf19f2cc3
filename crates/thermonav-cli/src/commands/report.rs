//! `thermonav report DIR`: DIR/report.html from what `demo` (or `characterize` + `evaluate`)
//! wrote there.

use crate::args::ReportArgs;
use crate::failure::Failure;

/// Runs `report`.
pub fn run(args: &ReportArgs) -> Result<(), Failure> {
    let path = crate::html::report::write_report(&args.dir)?;
    println!("report written: {}", path.display());
    Ok(())
}
