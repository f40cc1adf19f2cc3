//! Replays the fuzzers' saved inputs (`fuzz/corpus/<target>/`, and `fuzz/regressions/<target>/`
//! for the inputs that once crashed) through the same entry points as the fuzz targets, so that
//! stable CI holds every parser to what the fuzzers established: any bytes give `Ok` or `Err`,
//! never a panic.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use thermonav_io::parsers::Parser;

/// The `fuzz/` folder at the top of the repository.
fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz")
}

/// Every file in `dir` (none when it does not exist).
fn files_in(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut files: Vec<PathBuf> = entries
        .map(|e| e.expect("readable entry").path())
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    files
}

/// Feeds `file` to `parser`: `Some(accepted)`, or `None` when the parser panicked.
fn replay(parser: Parser, file: &Path) -> Option<bool> {
    let bytes = std::fs::read(file).expect("readable corpus file");
    let name = file.display().to_string();
    catch_unwind(AssertUnwindSafe(|| {
        parser.record_count(&bytes, &name).is_ok()
    }))
    .ok()
}

#[test]
fn every_saved_fuzz_input_returns_without_panicking() {
    let mut panicked = Vec::new();
    for parser in Parser::ALL {
        let target = parser.target_name();
        let corpus = files_in(&fuzz_dir().join("corpus").join(target));
        let regressions = files_in(&fuzz_dir().join("regressions").join(target));
        assert!(
            !corpus.is_empty(),
            "{target}: no corpus under fuzz/corpus/{target}"
        );
        let mut accepted = 0;
        for file in corpus.iter().chain(&regressions) {
            match replay(parser, file) {
                Some(ok) => accepted += usize::from(ok),
                None => panicked.push(file.display().to_string()),
            }
        }
        // The corpus reaches past the error paths: some inputs are whole, valid files.
        assert!(accepted > 0, "{target}: no corpus input parses");
    }
    assert!(panicked.is_empty(), "parsers panicked on {panicked:#?}");
}
