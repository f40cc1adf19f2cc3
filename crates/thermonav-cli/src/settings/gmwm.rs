//! Settings of `gmwm`: the candidate models of `--model` and the bootstrap's replicates and
//! seed, checked (by the library's own checks) before the record is read.

use crate::args::GmwmArgs;
use crate::failure::Failure;
use anyhow::anyhow;
use thermonav::stoch::gmwm::{BootstrapSettings, ModelSpec};
use thermonav_io::gmwm::candidates_of;

/// What every channel of a `gmwm` run is fitted with.
#[derive(Debug, Clone)]
pub struct GmwmSettings {
    /// The candidates: the automatic list, or the one model given.
    pub candidates: Vec<ModelSpec>,
    /// The bootstrap of the parameters' intervals.
    pub bootstrap: BootstrapSettings,
}

/// `gmwm`'s options resolved, or a usage error naming the option.
pub fn resolve(args: &GmwmArgs) -> Result<GmwmSettings, Failure> {
    let candidates = candidates_of(&args.model)
        .map_err(|e| Failure::Usage(anyhow!("--model {}: {e}", args.model)))?;
    let mut bootstrap = BootstrapSettings::default();
    (bootstrap.replicates, bootstrap.seed) = (args.replicates, args.seed);
    bootstrap
        .validate()
        .map_err(|e| Failure::Usage(anyhow!("--{e}")))?;
    Ok(GmwmSettings {
        candidates,
        bootstrap,
    })
}
