//! Settings of the analysis commands: those that read one file and write one (`filter`,
//! `convert`), their outputs checked against their inputs before anything is read, and those
//! that read one record and print (`allan`, `ar`), their options checked by the library's
//! types.

use super::paths::Io;
use crate::args::{
    AllanArgs, ArArgs, ConvertArgs, DenoiseArg, FilterArgs, FilterKaiserArgs, KaiserArgs,
    WaveletArgs,
};
use crate::failure::Failure;
use crate::fir_design::design;
use anyhow::anyhow;
use std::path::{Path, PathBuf};
use thermonav::signal::decimate::{check_anti_alias, decimation_factor};
use thermonav::signal::kaiser::{DEFAULT_RIPPLE_DB, DEFAULT_TRANSITION_HZ, FirFilter, KaiserSpec};
use thermonav::signal::wavelet::denoise::{DecompositionLevel, WaveletDenoise};
use thermonav::signal::zero_phase::{ZeroPhaseMode, filter_for_mode};
use thermonav::stoch::allan::{CiSettings, DeviationKind, TauGrid};
use thermonav::stoch::ar::ArMethod;
use thermonav::stoch::ar::order::{Criterion, Order};
use thermonav_io::ImuOptions;
use thermonav_io::ros::extract::TopicNames;

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
    pub mode: ZeroPhaseMode,
    /// Decimated rate, Hz.
    pub decimate_to_hz: Option<f64>,
    /// Design rate, Hz (default: the file's nominal rate).
    pub fs_hz: Option<f64>,
}

impl KaiserPlan {
    /// The filter designed at `--fs-hz`, else at `file_rate_hz`, for the zero-phase mode,
    /// and the decimation factor (1 without `--decimate-to-hz`). A design or a decimation the
    /// rate does not allow is a usage error: [`resolve_filter`] finds it before reading when
    /// `--fs-hz` is given, the command after reading the file's rate otherwise.
    pub fn design_at(&self, file_rate_hz: f64) -> Result<(FirFilter, usize), Failure> {
        let (spec, designed) = design(self.fs_hz.unwrap_or(file_rate_hz), &self.kaiser)?;
        let filter = filter_for_mode(designed, &spec, self.mode);
        let factor = match self.decimate_to_hz {
            None => 1,
            Some(target_hz) => decimation_factor(filter.sample_rate_hz(), target_hz)
                .map_err(|e| Failure::Usage(anyhow!("--decimate-to-hz {target_hz}: {e}")))?,
        };
        Ok((filter, factor))
    }
}

/// The level of `w` for a record of `rows` samples read from `input`: a `--level` the
/// record's length does not allow is a usage error (the one check of `filter` that needs the
/// record), a record too short for one level a data error.
pub fn wavelet_level(w: &WaveletDenoise, rows: usize, input: &Path) -> Result<usize, Failure> {
    let level = (w.level_for(rows)).map_err(|e| anyhow!("{}: {rows} rows: {e}", input.display()));
    match w.level {
        DecompositionLevel::Fixed(l) => {
            level.map_err(|e| Failure::Usage(e.context(format!("--level {l}"))))
        }
        DecompositionLevel::Max => level.map_err(Failure::Data),
    }
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
    let k = &plan.kaiser;
    KaiserSpec::check_band(k.cutoff_hz, k.transition_hz, k.ripple_db)
        .map_err(|e| Failure::Usage(e.into()))?;
    check_anti_alias_of(&plan)?;
    if let Some(fs_hz) = plan.fs_hz {
        plan.design_at(fs_hz)?;
    }
    Ok(plan)
}

fn kaiser_settings(k: &FilterKaiserArgs) -> Result<KaiserPlan, Failure> {
    Ok(KaiserPlan {
        kaiser: kaiser_spec(k)?,
        mode: k.mode.map_or_else(ZeroPhaseMode::default, Into::into),
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

/// What `allan` runs, resolved from its options.
#[derive(Debug, Clone)]
pub struct AllanSettings {
    /// How the record is read: its mounting and rate.
    pub options: ImuOptions,
    /// Which topics of a bag.
    pub topics: TopicNames,
    /// The τ grid.
    pub grid: TauGrid,
    /// The confidence limits' settings (level checked by the library).
    pub ci: CiSettings,
    /// Which member of the Allan family.
    pub kind: DeviationKind,
}

/// `allan`: the confidence level (the library's rule: strictly between 0 and 1) and the
/// record's reading options.
pub fn resolve_allan(args: &AllanArgs) -> Result<AllanSettings, Failure> {
    let ci = CiSettings {
        level: args.confidence,
        ..CiSettings::default()
    };
    ci.validate()
        .map_err(|e| Failure::Usage(anyhow!("--confidence {}: {e}", args.confidence)))?;
    Ok(AllanSettings {
        options: super::imu::options(&args.rotation, &args.rate)?,
        topics: super::imu::topics(&args.topics),
        grid: args.taus.into(),
        ci,
        kind: args.kind,
    })
}

/// What `ar` fits, resolved from its options.
#[derive(Debug, Clone, Copy)]
pub struct ArSettings {
    /// The order, checked by the library.
    pub order: Order,
    /// The estimator.
    pub method: ArMethod,
}

/// `ar`: `--order` (a number, or `auto`: BIC up to `--max-order`) checked by the library.
pub fn resolve_ar(args: &ArArgs) -> Result<ArSettings, Failure> {
    let order = ar_order(&args.order, args.max_order)?;
    order.validate().map_err(|e| match order {
        Order::Fixed(_) => Failure::Usage(anyhow!("--order {}: {e}", args.order)),
        Order::Auto { .. } => Failure::Usage(anyhow!("--max-order {}: {e}", args.max_order)),
    })?;
    Ok(ArSettings {
        order,
        method: args.method.into(),
    })
}

/// The `--order` text as an order: `auto` (BIC over 1..=max_order) or an integer.
fn ar_order(text: &str, max_order: usize) -> Result<Order, Failure> {
    if text == "auto" {
        return Ok(Order::Auto {
            criterion: Criterion::Bic,
            max_order,
        });
    }
    text.parse().map(Order::Fixed).map_err(|_| {
        Failure::Usage(anyhow!(
            "--order {text:?}: expected an integer from 1 to {} (the fit costs samples × order²) or `auto`",
            thermonav::stoch::ar::MAX_AR_ORDER
        ))
    })
}
