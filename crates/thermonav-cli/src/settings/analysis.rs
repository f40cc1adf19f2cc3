//! Settings of the commands that read one file and write one (`filter`, `convert`): their
//! outputs checked against their inputs before anything is read.

use super::paths::Io;
use crate::args::{ConvertArgs, FilterArgs};
use crate::failure::Failure;
use std::path::{Path, PathBuf};
use thermonav::signal::decimate::check_anti_alias;

/// OUT.json: the record written beside an output file.
pub fn json_sidecar(out: &Path) -> PathBuf {
    let mut name = out.as_os_str().to_owned();
    name.push(".json");
    PathBuf::from(name)
}

/// `filter`: the output and its sidecar spare the input and any file that is not a record.
pub fn check_filter(args: &FilterArgs) -> Result<(), Failure> {
    Io::new()
        .input("the input", &args.input)
        .output("filtered output", &args.out)
        .output("filter record", &json_sidecar(&args.out))
        .check()?;
    check_anti_alias_of(args)?;
    check_sidecar_free(&args.out)
}

/// With `--decimate-to-hz`, the filter's stop band must start at or below the new Nyquist
/// frequency (the library's rule: cut-off + transition/2 <= rate/2).
fn check_anti_alias_of(args: &FilterArgs) -> Result<(), Failure> {
    let Some(target_hz) = args.decimate_to_hz else {
        return Ok(());
    };
    let k = &args.kaiser;
    check_anti_alias(k.cutoff_hz, k.transition_hz, target_hz)
        .map_err(|e| Failure::Usage(anyhow::anyhow!("--decimate-to-hz {target_hz}: {e}")))
}

/// Refuses an `OUT.json` that exists and is not a record of ours (a JSON object naming its
/// `input`, as every record does): `--out D/bank` would otherwise overwrite `D/bank.json`.
fn check_sidecar_free(out: &Path) -> Result<(), Failure> {
    let sidecar = json_sidecar(out);
    if !sidecar.exists() || is_a_record(&sidecar) {
        return Ok(());
    }
    Err(Failure::Usage(anyhow::anyhow!(
        "{} exists and is not a thermonav record (a JSON object with an \"input\" key): --out {} would overwrite it with this run's record; choose another --out or move the file",
        sidecar.display(),
        out.display()
    )))
}

fn is_a_record(path: &Path) -> bool {
    thermonav_io::read_document(path)
        .ok()
        .and_then(|bytes| serde_json::from_slice::<serde_json::Value>(&bytes).ok())
        .is_some_and(|v| v.get("input").is_some())
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
