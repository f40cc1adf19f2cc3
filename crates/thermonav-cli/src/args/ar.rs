//! Arguments of `thermonav ar`.

use clap::{Args, ValueEnum};
use std::path::PathBuf;

/// AR estimators.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ArMethodArg {
    /// Yule-Walker (Levinson-Durbin on the biased autocovariance).
    YuleWalker,
    /// Burg.
    Burg,
    /// Covariance method (forward least squares).
    Covariance,
    /// Modified covariance (forward-backward least squares).
    ModifiedCovariance,
}

/// Arguments of `ar`.
#[derive(Debug, Args)]
pub struct ArArgs {
    /// The IMU CSV (rates); filter and decimate it first with `thermonav filter` as the paper does.
    pub file: PathBuf,
    /// Estimator.
    #[arg(long, value_enum, default_value_t = ArMethodArg::Burg)]
    pub method: ArMethodArg,
    /// Order: a number, or `auto` (BIC over 1..=--max-order).
    #[arg(long, default_value = "1")]
    pub order: String,
    /// Largest order tried by `--order auto`.
    #[arg(long, default_value_t = 10)]
    pub max_order: usize,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

impl From<ArMethodArg> for thermonav::stoch::ar::ArMethod {
    fn from(m: ArMethodArg) -> Self {
        match m {
            ArMethodArg::YuleWalker => Self::YuleWalker,
            ArMethodArg::Burg => Self::Burg,
            ArMethodArg::Covariance => Self::Covariance,
            ArMethodArg::ModifiedCovariance => Self::ModifiedCovariance,
        }
    }
}
