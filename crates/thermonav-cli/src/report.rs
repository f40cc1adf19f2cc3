//! Printing results: one JSON document on stdout with `--json`, aligned text otherwise.

use crate::failure::{Classify, Failure};
use serde::Serialize;

/// Prints `value` as one pretty JSON document on stdout (none when it holds a number that is
/// not finite: the error names it).
pub fn print_json(value: &impl Serialize) -> Result<(), Failure> {
    let text = thermonav_io::finite_json_pretty(value).data()?;
    println!("{text}");
    Ok(())
}

/// Prints `label  value` rows with the labels padded to a common width.
pub fn print_rows(rows: &[(&str, String)]) {
    let width = rows.iter().map(|(label, _)| label.len()).max().unwrap_or(0);
    for (label, value) in rows {
        println!("{label:<width$}  {value}");
    }
}
