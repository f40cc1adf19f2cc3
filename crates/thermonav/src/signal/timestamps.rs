//! Timestamp checks: nominal rate, jitter, gaps, duplicates and reversals.
