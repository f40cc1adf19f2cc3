//! Settings of the commands that read one file and write one (`filter`, `convert`): their
//! outputs checked against their inputs before anything is read.

use super::paths::Io;
use crate::args::{ConvertArgs, FilterArgs};
use crate::failure::Failure;
use std::path::{Path, PathBuf};

/// OUT.json: the record written beside an output file.
pub fn json_sidecar(out: &Path) -> PathBuf {
    let mut name = out.as_os_str().to_owned();
    name.push(".json");
    PathBuf::from(name)
}

/// `filter`: the output and its sidecar spare the input.
pub fn check_filter(args: &FilterArgs) -> Result<(), Failure> {
    Io::new()
        .input("the input", &args.input)
        .output("filtered output", &args.out)
        .output("filter record", &json_sidecar(&args.out))
        .check()
}

/// `convert`: the outputs (and a ULog's sidecar) spare the input and its tag file.
pub fn check_convert(args: &ConvertArgs, tag: &Path) -> Result<(), Failure> {
    let io = Io::new()
        .input("the input", &args.input)
        .input("--tag", tag)
        .output("converted output", &args.out)
        .output("conversion record", &json_sidecar(&args.out));
    match &args.gnss_out {
        Some(gnss) => io.output("GNSS output", gnss),
        None => io,
    }
    .check()
}
