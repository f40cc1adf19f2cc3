//! Settings of the commands that read one file and write one (`filter`, `convert`): their
//! outputs checked against their inputs before anything is read.

use super::paths::Io;
use crate::args::{
    ConvertArgs, DEFAULT_FILTER_MODE, DEFAULT_RIPPLE_DB, DEFAULT_TRANSITION_HZ, DenoiseArg,
    FilterArgs, FilterKaiserArgs, KaiserArgs, ModeArg, WaveletArgs,
};
use crate::failure::Failure;
use anyhow::anyhow;
use std::path::{Path, PathBuf};
use thermonav::signal::decimate::check_anti_alias;
use thermonav::signal::wavelet::denoise::{DecompositionLevel, WaveletDenoise};

/// What `filter` runs, resolved from its options.
#[derive(Debug, Clone, Copy)]
pub enum FilterPlan {
    /// The Kaiser low-pass.
    Kaiser(KaiserPlan),
    /// Wavelet shrinkage.
    Wavelet(WaveletDenoise),
}

/// The Kaiser path of `filter`: the design, the zero-phase mode and the optional decimation.
#[derive(Debug, Clone, Copy)]
pub struct KaiserPlan {
    /// The low-pass specification.
    pub kaiser: KaiserArgs,
    /// Zero-phase mode.
    pub mode: ModeArg,
    /// Decimated rate, Hz.
    pub decimate_to_hz: Option<f64>,
    /// Design rate, Hz (default: the file's nominal rate).
    pub fs_hz: Option<f64>,
}

/// OUT.json: the record written beside an output file.
pub fn json_sidecar(out: &Path) -> PathBuf {
    let mut name = out.as_os_str().to_owned();
    name.push(".json");
    PathBuf::from(name)
}

/// `filter`: the output and its sidecar spare the input and any file that is not a record;
/// the options are those of the method, with their defaults.
pub fn resolve_filter(args: &FilterArgs) -> Result<FilterPlan, Failure> {
    check_filter_paths(args)?;
    match args.method {
        DenoiseArg::Kaiser => kaiser_plan(args).map(FilterPlan::Kaiser),
        DenoiseArg::Wavelet => wavelet_plan(args).map(FilterPlan::Wavelet),
    }
}

/// The output and its sidecar spare the input and any file that is not a record of ours.
fn check_filter_paths(args: &FilterArgs) -> Result<(), Failure> {
    Io::new()
        .input("the input", &args.input)
        .output("filtered output", &args.out)
        .output("filter record", &json_sidecar(&args.out))
        .check()?;
    check_sidecar_free(&args.out)
}

/// The Kaiser options with their defaults; wavelet options are refused.
fn kaiser_plan(args: &FilterArgs) -> Result<KaiserPlan, Failure> {
    refuse_options(
        "--method kaiser",
        "wavelet",
        &wavelet_options(&args.wavelet),
    )?;
    let plan = kaiser_settings(&args.kaiser)?;
    check_anti_alias_of(&plan)?;
    Ok(plan)
}

fn kaiser_settings(k: &FilterKaiserArgs) -> Result<KaiserPlan, Failure> {
    Ok(KaiserPlan {
        kaiser: kaiser_spec(k)?,
        mode: k.mode.unwrap_or(DEFAULT_FILTER_MODE),
        decimate_to_hz: k.decimate_to_hz,
        fs_hz: k.fs_hz,
    })
}

/// The low-pass specification: --cutoff-hz is required.
fn kaiser_spec(k: &FilterKaiserArgs) -> Result<KaiserArgs, Failure> {
    let cutoff_hz = k.cutoff_hz.ok_or_else(|| {
        Failure::Usage(anyhow!("--method kaiser (the default) needs --cutoff-hz"))
    })?;
    Ok(KaiserArgs {
        cutoff_hz,
        transition_hz: k.transition_hz.unwrap_or(DEFAULT_TRANSITION_HZ),
        ripple_db: k.ripple_db.unwrap_or(DEFAULT_RIPPLE_DB),
    })
}

/// The wavelet options over the library's defaults; Kaiser options are refused.
fn wavelet_plan(args: &FilterArgs) -> Result<WaveletDenoise, Failure> {
    refuse_options("--method wavelet", "Kaiser", &kaiser_options(&args.kaiser))?;
    wavelet_settings(&args.wavelet)
}

fn wavelet_settings(w: &WaveletArgs) -> Result<WaveletDenoise, Failure> {
    let d = WaveletDenoise::default();
    Ok(WaveletDenoise {
        wavelet: w.wavelet.unwrap_or(d.wavelet),
        level: decomposition_level(w.level)?,
        mode: w.extension.map_or(d.mode, Into::into),
        rule: w.threshold.map_or(d.rule, Into::into),
        thresholding: w.thresholding.map_or(d.thresholding, Into::into),
    })
}

/// `--level L` (1 or more; its maximum depends on the record) or the deepest level.
fn decomposition_level(level: Option<usize>) -> Result<DecompositionLevel, Failure> {
    match level {
        None => Ok(DecompositionLevel::Max),
        Some(0) => Err(Failure::Usage(anyhow!(
            "--level 0 decomposes nothing: give 1 or more (or leave it out for the deepest level)"
        ))),
        Some(level) => Ok(DecompositionLevel::Fixed(level)),
    }
}

/// The wavelet options given.
fn wavelet_options(w: &WaveletArgs) -> Vec<&'static str> {
    given(&[
        ("--wavelet", w.wavelet.is_some()),
        ("--level", w.level.is_some()),
        ("--threshold", w.threshold.is_some()),
        ("--thresholding", w.thresholding.is_some()),
        ("--extension", w.extension.is_some()),
    ])
}

/// The Kaiser options given.
fn kaiser_options(k: &FilterKaiserArgs) -> Vec<&'static str> {
    given(&[
        ("--cutoff-hz", k.cutoff_hz.is_some()),
        ("--transition-hz", k.transition_hz.is_some()),
        ("--ripple-db", k.ripple_db.is_some()),
        ("--mode", k.mode.is_some()),
        ("--decimate-to-hz", k.decimate_to_hz.is_some()),
        ("--fs-hz", k.fs_hz.is_some()),
    ])
}

fn given(options: &[(&'static str, bool)]) -> Vec<&'static str> {
    options.iter().filter(|o| o.1).map(|o| o.0).collect()
}

/// A usage error naming the options of the other method.
fn refuse_options(method: &str, kind: &str, options: &[&str]) -> Result<(), Failure> {
    if options.is_empty() {
        return Ok(());
    }
    let joined = options.join(", ");
    Err(Failure::Usage(anyhow!(
        "{joined}: {kind} option(s), which {method} does not use: leave out or choose the other --method"
    )))
}

/// With `--decimate-to-hz`, the filter's stop band must start at or below the new Nyquist
/// frequency (the library's rule: cut-off + transition/2 <= rate/2).
fn check_anti_alias_of(plan: &KaiserPlan) -> Result<(), Failure> {
    let Some(target_hz) = plan.decimate_to_hz else {
        return Ok(());
    };
    let k = &plan.kaiser;
    check_anti_alias(k.cutoff_hz, k.transition_hz, target_hz)
        .map_err(|e| Failure::Usage(anyhow!("--decimate-to-hz {target_hz}: {e}")))
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
