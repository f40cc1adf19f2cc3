//! Progress bars for long work: drawn on stderr when it is a terminal, silent when stderr is
//! piped or redirected, and hidden entirely with `--quiet`.

use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

static QUIET: AtomicBool = AtomicBool::new(false);

/// The stack every new bar joins while [`stacked`] runs.
static STACK: Mutex<Option<MultiProgress>> = Mutex::new(None);

/// stderr, or nothing under `--quiet`.
fn draw_target() -> ProgressDrawTarget {
    if QUIET.load(Ordering::Relaxed) {
        ProgressDrawTarget::hidden()
    } else {
        ProgressDrawTarget::stderr()
    }
}

/// Runs `work` with every bar made meanwhile drawn in one stack, one line each: work that runs
/// side by side (two tournaments at once) would otherwise draw its bars over each other.
pub fn stacked<R>(work: impl FnOnce() -> R) -> R {
    let set = |stack: Option<MultiProgress>| {
        *STACK
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner()) = stack;
    };
    set(Some(MultiProgress::with_draw_target(draw_target())));
    let result = work();
    set(None);
    result
}

/// Hides every bar for the rest of the run (the `--quiet` flag).
pub fn set_quiet(quiet: bool) {
    QUIET.store(quiet, Ordering::Relaxed);
}

/// True under `--quiet`.
pub fn is_quiet() -> bool {
    QUIET.load(Ordering::Relaxed)
}

/// A bar of `len` steps labelled `message`. indicatif's stderr target draws nothing when stderr
/// is not a terminal, so piped runs stay clean.
pub fn bar(len: usize, message: &str) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(len as u64), draw_target());
    let style = ProgressStyle::with_template("{msg:<34} [{bar:30}] {pos}/{len} ({elapsed})")
        .map(|s| s.progress_chars("=> "));
    if let Ok(style) = style {
        bar.set_style(style);
    }
    bar.set_message(message.to_string());
    match STACK.lock().unwrap_or_else(|p| p.into_inner()).as_ref() {
        Some(stack) => stack.add(bar),
        None => bar,
    }
}
