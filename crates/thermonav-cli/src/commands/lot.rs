//! `thermonav lot summarize`: the lot summary from the banks that separate unit jobs wrote.

use crate::args::{LotAction, LotArgs};
use crate::failure::Failure;

/// Runs `lot`.
pub fn run(args: &LotArgs) -> Result<(), Failure> {
    match &args.action {
        LotAction::Summarize(summarize) => crate::banks::production_lot::run_summarize(summarize),
    }
}
