//! Arguments of `thermonav lot`.

use clap::{Args, Subcommand};
use std::path::PathBuf;

/// Arguments of `lot`.
#[derive(Debug, Args)]
pub struct LotArgs {
    /// What to do with the lot.
    #[command(subcommand)]
    pub action: LotAction,
}

/// Lot actions.
#[derive(Debug, Subcommand)]
pub enum LotAction {
    /// Build DIR/lot-summary.json from DIR/SERIAL/bank.json of every unit of the manifest
    /// (written by separate `characterize --manifest --unit-index N` jobs).
    Summarize(LotSummarizeArgs),
}

/// Arguments of `lot summarize`.
#[derive(Debug, Args)]
pub struct LotSummarizeArgs {
    /// The folder the unit jobs wrote (their --out).
    pub dir: PathBuf,
    /// The lot manifest (TOML).
    #[arg(long)]
    pub manifest: PathBuf,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}
