//! Integration tests of the thermonav library against independent oracles.

mod acf;
mod ar;
