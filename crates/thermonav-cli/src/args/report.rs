//! Arguments of `thermonav report`.

use clap::Args;
use std::path::PathBuf;

/// Arguments of `report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// The folder demo (or characterize + evaluate) wrote: DIR/bank.json (required:
    /// characterize --out DIR/bank.json); optional: DIR/demo.json,
    /// DIR/evaluation/evaluation.json with its errors/ (evaluate --out DIR/evaluation),
    /// DIR/vessel/reference.csv (the survey figure), DIR/solution/solution.innovations.csv
    /// (integrate --out DIR/solution/solution.csv; the innovations figure). Or a folder
    /// evaluate wrote (evaluate --out DIR: DIR/evaluation.json with its errors/): the
    /// tournament alone, without the bank's sections.
    pub dir: PathBuf,
}
