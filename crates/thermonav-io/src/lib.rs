//! # thermonav-io
//!
//! File formats of thermonav. Readers take `impl BufRead` (plus a display name used in error
//! messages) and return library types; writers never leave a partial file behind.
