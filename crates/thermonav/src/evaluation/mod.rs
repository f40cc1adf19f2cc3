//! The paper's Steps 2-3: INS-only errors inside GNSS outages, per model, and the tournament
//! that ranks the temperature models by them.
//!
//! - [`metrics`]: errors of a solution against a reference inside each outage; per-outage RMS
//!   and maximum; overall figures as the paper reports them (mean of the per-outage RMS) and as
//!   KF-GINS does (RMS of the per-outage maxima).
//! - [`candidates`]: the models that compete: every bank entry, the bank interpolated at the
//!   operating temperature, the temperature-blind mean of the bank, and data-sheet values.
//! - [`oracle`]: the simulator's true model as a candidate, the best any model could do.
//! - [`scenario`]: a tournament's scenario from records already read.
//! - [`tournament`]: every candidate through the same filter on the same data, in parallel,
//!   and the ranking.
//! - [`experiment`]: a tournament with its replicates (shifted outages, or scenarios the
//!   caller makes), bounded in memory, giving the [`report`].
//! - [`outside`]: trajectories of other tools (KF-GINS, RTKLIB, ...) scored with the same
//!   outage metrics, as unranked rows of the report.
//! - [`report`]: the report's types, which are the `evaluation.json` contract, and the
//!   ranking.
//! - [`shard`]: a tournament's runs cut into shards (one batch job each) and the merge that
//!   gives the report of one whole run.
//! - [`significance`]: Monte Carlo summaries (mean and 95 % interval per metric) and the
//!   paired test of the winner against the runner-up.

pub mod candidates;
pub mod experiment;
pub mod metrics;
pub mod oracle;
pub mod outside;
pub mod report;
pub mod scenario;
pub mod shard;
pub mod significance;
pub mod tournament;
