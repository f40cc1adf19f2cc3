//! Arguments of `thermonav ar`.

use clap::{Args, ValueEnum};
use std::path::PathBuf;
use thermonav::stoch::ar::ArMethod;
use thermonav::stoch::ar::order::DEFAULT_AUTO_MAX_ORDER;

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
    #[arg(long, value_enum, default_value_t = ArMethod::default().into())]
    pub method: ArMethodArg,
    /// Order: a number, or `auto` (BIC over 1..=--max-order).
    #[arg(long, default_value = "1")]
    pub order: String,
    /// Largest order tried by `--order auto`.
    #[arg(long, default_value_t = DEFAULT_AUTO_MAX_ORDER)]
    pub max_order: usize,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

impl From<ArMethodArg> for ArMethod {
    fn from(m: ArMethodArg) -> Self {
        match m {
            ArMethodArg::YuleWalker => Self::YuleWalker,
            ArMethodArg::Burg => Self::Burg,
            ArMethodArg::Covariance => Self::Covariance,
            ArMethodArg::ModifiedCovariance => Self::ModifiedCovariance,
        }
    }
}

impl From<ArMethod> for ArMethodArg {
    fn from(m: ArMethod) -> Self {
        match m {
            ArMethod::YuleWalker => Self::YuleWalker,
            ArMethod::Burg => Self::Burg,
            ArMethod::Covariance => Self::Covariance,
            ArMethod::ModifiedCovariance => Self::ModifiedCovariance,
        }
    }
}
