//! Runs and tournaments from files: `integrate`'s run (whole or streamed) and what it
//! reports, `evaluate`'s scenario, runs, shards and references.

pub mod integration;
pub mod outcome;
pub mod reference_input;
pub mod stream;
pub mod tournament_files;
pub mod tournament_shards;
