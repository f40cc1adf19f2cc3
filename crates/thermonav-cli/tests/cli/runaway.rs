//! Issue 37: options that multiply work are bounded and checked before any file is read.

use crate::{outcome, thermonav};

#[test]
fn gmwm_replicates_out_of_range_are_a_usage_error_before_reading_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("never-read.csv");
    let missing = missing.to_str().unwrap();
    for replicates in ["5", "1001", "1000000000"] {
        let (status, stdout, stderr) =
            outcome(&thermonav(&["gmwm", missing, "--replicates", replicates]));
        assert_eq!(status, 2, "{replicates}: {stderr}");
        assert!(stdout.is_empty(), "{stdout}");
        assert!(
            stderr.contains(&format!(
                "--replicates: 0 (no bootstrap) or 10 to 1000 bootstrap replicates, got {replicates}"
            )),
            "{stderr}"
        );
    }
}
