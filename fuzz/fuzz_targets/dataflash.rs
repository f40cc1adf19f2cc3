//! Fuzzes `Parser::DataFlash`: any bytes must give `Ok` or `Err`, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use thermonav_io::parsers::Parser;

fuzz_target!(|data: &[u8]| {
    let _ = Parser::DataFlash.record_count(data, "fuzz");
});
