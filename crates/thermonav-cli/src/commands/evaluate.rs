//! `thermonav evaluate`: the temperature-model tournament on one data set (the paper's Steps
//! 2-3): every candidate model through the same filter, GNSS outages, errors against the
//! reference, the ranking, and its Monte Carlo significance. `demo` calls the same code.

use super::bank::{read_bank, source_of};
use super::integrate::{antenna_geometry, increments_with_span, operating_temperature, outages_in};
use crate::args::{EvaluateArgs, FiltersArg};
use crate::failure::{Classify, Failure};
use crate::report::print_json;
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use thermonav::evaluation::candidates::{
    Candidate, CandidateKind, DatasheetValues, Excluded, tournament_candidates,
};
use thermonav::evaluation::metrics::{EpochError, Metric, OutageMetrics};
use thermonav::evaluation::significance::MeanInterval;
use thermonav::evaluation::tournament::{
    ModelResult, Scenario, Significance, run_tournament, summarize_replicates,
};
use thermonav::nav::alignment::{InitialUncertainty, uncorrected};
use thermonav::nav::engine::{EngineSettings, FilterKind};
use thermonav::nav::measurement::AntennaGeometry;
use thermonav::nav::outage::Outages;
use thermonav::nav::sensor_model::ScaleFactorPrior;
use thermonav::nav::solution::InnovationStatistics;
use thermonav::rng::named_rng;
use thermonav::stoch::bank::{GaussMarkovSource, ModelBank};
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::{
    Strictness, WriteError, read_gnss_file, read_imu_file, read_trajectory_file, write_atomically,
    write_json_atomically,
};

/// Runs `evaluate`.
pub fn run(args: &EvaluateArgs) -> Result<(), Failure> {
    if args.monte_carlo == 0 {
        return Err(Failure::Usage(anyhow!("--monte-carlo must be at least 1")));
    }
    let geometry = antenna_geometry(&args.lever_arm_m, &args.baseline)?;
    let bank = read_bank(&args.bank)?;
    let (main, operating_c) = scenario_from_files(
        &ScenarioFiles {
            imu: &args.imu,
            gnss: &args.gnss,
            reference: &args.reference,
        },
        geometry,
        &args.outages,
        args.operating_temperature_c,
    )?;
    let outages = main.settings.outages.clone();
    let replicates = shifted_outage_replicates(&main, &outages, args.monte_carlo, args.seed)?;
    let plan = TournamentPlan {
        bank: &bank,
        operating_temperature_c: operating_c,
        source: source_of(args.model),
        filters: filters_of(args.filter),
        replicate_kind: "shifted outage start times (one common random shift per replicate)",
        out: &args.out,
    };
    let report = run_plan(&plan, &main, &replicates)?;
    if args.json {
        return print_json(&report);
    }
    print_tournament_table(&report);
    Ok(())
}

/// The three input files of a tournament.
pub struct ScenarioFiles<'a> {
    /// IMU CSV.
    pub imu: &'a Path,
    /// GNSS CSV.
    pub gnss: &'a Path,
    /// Reference trajectory CSV.
    pub reference: &'a Path,
}

/// The scenario of the files (start from the reference at the first fix, default initial
/// covariance and filter settings, the outages of `outage_spec`) and the operating
/// temperature (given, or the IMU's mean temp_c).
pub fn scenario_from_files(
    files: &ScenarioFiles,
    geometry: AntennaGeometry,
    outage_spec: &str,
    operating_temperature_c: Option<f64>,
) -> Result<(Scenario, f64), Failure> {
    let series = read_imu_file(files.imu, Strictness::Strict).data()?;
    let gnss = read_gnss_file(files.gnss, Strictness::Strict).data()?;
    let reference = read_trajectory_file(files.reference, Strictness::Strict).data()?;
    let operating_c = operating_temperature(operating_temperature_c, &series, files.imu)?;
    let (increments, first, last) = increments_with_span(&series, files.imu)?;
    let outages = outages_in(outage_spec, first, last)?;
    check_reference_covers(&reference, &outages, files.reference)?;
    let settings = EngineSettings {
        geometry,
        outages,
        ..EngineSettings::default()
    };
    let scenario = scenario_of(increments, gnss, reference, settings, files.reference)?;
    Ok((scenario, operating_c))
}

/// Every outage must lie within the reference trajectory.
fn check_reference_covers(
    reference: &[TrajectoryPoint],
    outages: &Outages,
    path: &Path,
) -> Result<(), Failure> {
    let (Some(first), Some(last)) = (reference.first(), reference.last()) else {
        return Err(Failure::Data(anyhow!(
            "{}: no trajectory point",
            path.display()
        )));
    };
    match outages
        .windows()
        .iter()
        .find(|w| w.start < first.time || w.end > last.time)
    {
        Some(w) => Err(Failure::Data(anyhow!(
            "{}: the reference ({:.3}-{:.3} s) does not cover the outage {:.3}-{:.3} s",
            path.display(),
            first.time.as_seconds(),
            last.time.as_seconds(),
            w.start.as_seconds(),
            w.end.as_seconds()
        ))),
        None => Ok(()),
    }
}

/// A scenario from in-memory data, started from the reference at the first fix.
pub fn scenario_of(
    increments: Vec<thermonav::ins::state::Increment>,
    gnss: Vec<thermonav::gnss::GnssFix>,
    reference: Vec<TrajectoryPoint>,
    settings: EngineSettings,
    reference_name: &Path,
) -> Result<Scenario, Failure> {
    let initial = initial_from_reference(&reference, &gnss, reference_name)?;
    Ok(Scenario {
        increments,
        gnss,
        reference,
        initial: uncorrected(initial.nav_state()),
        initial_covariance: InitialUncertainty::default().covariance(),
        settings,
    })
}

/// The filters of a `--filter` choice, UKF first (the paper's filter).
pub fn filters_of(choice: FiltersArg) -> Vec<FilterKind> {
    match choice {
        FiltersArg::Ekf => vec![FilterKind::Ekf],
        FiltersArg::Ukf => vec![FilterKind::Ukf],
        FiltersArg::Both => vec![FilterKind::Ukf, FilterKind::Ekf],
    }
}

/// The reference point at (or last before) the first GNSS fix: the common starting state.
fn initial_from_reference(
    reference: &[TrajectoryPoint],
    gnss: &[thermonav::gnss::GnssFix],
    path: &Path,
) -> Result<TrajectoryPoint, Failure> {
    let start = gnss
        .first()
        .map(|f| f.time)
        .ok_or_else(|| Failure::Data(anyhow!("the GNSS file has no fix")))?;
    reference
        .iter()
        .rev()
        .find(|p| p.time <= start)
        .copied()
        .ok_or_else(|| {
            Failure::Data(anyhow!(
                "{}: the reference starts after the first GNSS fix ({:.3} s)",
                path.display(),
                start.as_seconds()
            ))
        })
}

/// Extra replicates with every outage moved by one seeded shift, uniform within ± half the
/// smallest margin (between outages and to the data's ends), so windows never overlap or
/// leave the data.
fn shifted_outage_replicates(
    main: &Scenario,
    outages: &Outages,
    count: usize,
    seed: u64,
) -> Result<Vec<Scenario>, Failure> {
    use rand::RngExt;
    let windows = outages.windows();
    let (Some(first), Some(last)) = (main.increments.first(), main.increments.last()) else {
        return Ok(Vec::new());
    };
    let mut margins: Vec<f64> = windows
        .windows(2)
        .map(|p| p[1].start.since(p[0].end).as_seconds())
        .collect();
    if let (Some(a), Some(b)) = (windows.first(), windows.last()) {
        margins.push(2.0 * a.start.since(first.time).as_seconds());
        margins.push(2.0 * last.time.since(b.end).as_seconds());
    }
    let half = margins.iter().copied().fold(f64::INFINITY, f64::min) / 2.0;
    let mut rng = named_rng(seed, "evaluate/outage-shift");
    (1..count)
        .map(|_| {
            let shift = if half.is_finite() && half > 0.0 {
                rng.random_range(-half..half)
            } else {
                0.0
            };
            let shifted = outages.shifted(shift).map_err(|e| anyhow!("{e}")).data()?;
            let mut scenario = main.clone();
            scenario.settings.outages = shifted;
            Ok(scenario)
        })
        .collect()
}

/// What a tournament compares and where it writes.
pub struct TournamentPlan<'a> {
    /// The bank.
    pub bank: &'a ModelBank,
    /// Operating temperature, °C.
    pub operating_temperature_c: f64,
    /// Gauss-Markov family.
    pub source: GaussMarkovSource,
    /// Filters, reported in this order.
    pub filters: Vec<FilterKind>,
    /// How replicates differ, in words.
    pub replicate_kind: &'static str,
    /// Output folder.
    pub out: &'a Path,
}

/// One model's line in the report.
#[derive(Debug, Serialize)]
pub struct ModelJson {
    label: String,
    #[serde(flatten)]
    candidate: CandidateKind,
    temperature_c: Option<f64>,
    filter: FilterKind,
    failure: Option<String>,
    rms_north_m: Option<f64>,
    rms_east_m: Option<f64>,
    rms_horizontal_m: Option<f64>,
    rms_heading_deg: Option<f64>,
    max_drift_horizontal_m: Option<f64>,
    rms_of_max_north_m: Option<f64>,
    rms_of_max_east_m: Option<f64>,
    rms_of_max_heading_deg: Option<f64>,
    per_outage: Vec<OutageMetrics>,
    ci95: BTreeMap<&'static str, MeanInterval>,
    innovations: Vec<InnovationStatistics>,
    errors_csv: Option<PathBuf>,
}

/// The significance section.
#[derive(Debug, Serialize)]
pub struct SignificanceJson {
    replicates: usize,
    replicates_differ_by: &'static str,
    tests: Vec<Significance>,
}

/// The whole report (the `evaluation.json` contract).
#[derive(Debug, Serialize)]
pub struct EvaluationJson {
    operating_temperature_c: f64,
    gauss_markov_source: GaussMarkovSource,
    filters: Vec<FilterKind>,
    outages: Vec<OutageSpanJson>,
    models: Vec<ModelJson>,
    excluded: Vec<Excluded>,
    best: BTreeMap<&'static str, String>,
    best_by_filter: BTreeMap<&'static str, BTreeMap<&'static str, String>>,
    significance: SignificanceJson,
    report_file: PathBuf,
}

#[derive(Debug, Serialize)]
struct OutageSpanJson {
    start_s: f64,
    end_s: f64,
}

/// Runs the tournament on `main` (and the replicates), writes `evaluation.json` and the
/// per-model error CSVs under the plan's folder, and returns the report.
pub fn run_plan(
    plan: &TournamentPlan,
    main: &Scenario,
    replicates: &[Scenario],
) -> Result<EvaluationJson, Failure> {
    let (candidates, excluded) = tournament_candidates(
        plan.bank,
        plan.operating_temperature_c,
        plan.source,
        &ScaleFactorPrior::default(),
        Some(&DatasheetValues::adis16364()),
    );
    let from_bank = |c: &Candidate| {
        matches!(
            c.kind,
            CandidateKind::Entry { .. } | CandidateKind::Interpolated { .. }
        )
    };
    if !candidates.iter().any(from_bank) {
        let reasons: Vec<String> = excluded
            .iter()
            .map(|e| format!("{}: {}", e.label, e.reason))
            .collect();
        return Err(Failure::Data(anyhow!(
            "no model of the bank can be used:\n  {}",
            reasons.join("\n  ")
        )));
    }
    let runs = candidates.len() * plan.filters.len() * (1 + replicates.len());
    let bar = crate::progress::bar(runs, "tournament runs");
    let tick = || bar.inc(1);
    let results = run_tournament(main, &candidates, &plan.filters, &tick);
    let mut all = vec![results.clone()];
    for scenario in replicates {
        let mut r = run_tournament(scenario, &candidates, &plan.filters, &tick);
        for m in &mut r {
            if let Ok(e) = &mut m.outcome {
                e.errors.clear();
            }
        }
        all.push(r);
    }
    bar.finish_and_clear();
    let (summaries, tests) = summarize_replicates(&all);
    let errors_dir = plan.out.join("errors");
    let mut models = Vec::new();
    for (result, summary) in results.iter().zip(&summaries) {
        let candidate = candidates
            .iter()
            .find(|c| c.label == result.label)
            .ok_or_else(|| Failure::Data(anyhow!("internal: lost candidate {}", result.label)))?;
        let csv = write_errors(&errors_dir, result)?;
        models.push(model_json(candidate, result, &summary.ci95, csv));
    }
    let ranking = if all.len() > 1 {
        mean_values(&models)
    } else {
        single_run_values(&results)
    };
    let best_by_filter = plan
        .filters
        .iter()
        .map(|f| (f.name(), best_labels(&ranking, *f)))
        .collect::<BTreeMap<_, _>>();
    let report_file = plan.out.join("evaluation.json");
    let report = EvaluationJson {
        operating_temperature_c: plan.operating_temperature_c,
        gauss_markov_source: plan.source,
        filters: plan.filters.clone(),
        outages: main
            .settings
            .outages
            .windows()
            .iter()
            .map(|w| OutageSpanJson {
                start_s: w.start.as_seconds(),
                end_s: w.end.as_seconds(),
            })
            .collect(),
        models,
        excluded,
        best: best_labels(&ranking, plan.filters[0]),
        best_by_filter,
        significance: SignificanceJson {
            replicates: all.len(),
            replicates_differ_by: plan.replicate_kind,
            tests,
        },
        report_file: report_file.clone(),
    };
    write_json_atomically(&report_file, &report).data()?;
    Ok(report)
}

/// A model's label, filter and the values it is ranked by (in [`Metric::ALL`] order).
type Ranked = (String, FilterKind, [Option<f64>; 5]);

/// The values of a single run.
fn single_run_values(results: &[ModelResult]) -> Vec<Ranked> {
    results
        .iter()
        .map(|r| (r.label.clone(), r.filter, Metric::ALL.map(|m| r.value(m))))
        .collect()
}

/// The Monte Carlo means.
fn mean_values(models: &[ModelJson]) -> Vec<Ranked> {
    models
        .iter()
        .map(|m| {
            let mean = |metric: Metric| m.ci95.get(metric.key()).map(|c| c.mean);
            (m.label.clone(), m.filter, Metric::ALL.map(mean))
        })
        .collect()
}

/// The label with the lowest value of each metric among `filter`'s models.
fn best_labels(values: &[Ranked], filter: FilterKind) -> BTreeMap<&'static str, String> {
    Metric::ALL
        .iter()
        .enumerate()
        .filter_map(|(k, metric)| {
            values
                .iter()
                .filter(|(_, f, _)| *f == filter)
                .filter_map(|(label, _, v)| v[k].map(|x| (label, x)))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(label, _)| (metric.key(), label.clone()))
        })
        .collect()
}

fn model_json(
    candidate: &Candidate,
    result: &ModelResult,
    ci95: &[(Metric, MeanInterval)],
    errors_csv: Option<PathBuf>,
) -> ModelJson {
    let ok = result.outcome.as_ref().ok().map(|e| &e.metrics);
    let pick = |f: fn(&thermonav::evaluation::metrics::RunMetrics) -> f64| ok.map(f);
    ModelJson {
        label: result.label.clone(),
        candidate: result.candidate,
        temperature_c: candidate.temperature_c(),
        filter: result.filter,
        failure: result.outcome.as_ref().err().cloned(),
        rms_north_m: pick(|m| m.rms_north_m),
        rms_east_m: pick(|m| m.rms_east_m),
        rms_horizontal_m: pick(|m| m.rms_horizontal_m),
        rms_heading_deg: pick(|m| m.rms_heading_deg),
        max_drift_horizontal_m: pick(|m| m.max_drift_horizontal_m),
        rms_of_max_north_m: pick(|m| m.rms_of_max_north_m),
        rms_of_max_east_m: pick(|m| m.rms_of_max_east_m),
        rms_of_max_heading_deg: pick(|m| m.rms_of_max_heading_deg),
        per_outage: ok.map(|m| m.per_outage.clone()).unwrap_or_default(),
        ci95: ci95.iter().map(|(m, ci)| (m.key(), *ci)).collect(),
        innovations: result
            .outcome
            .as_ref()
            .map(|e| e.innovations.clone())
            .unwrap_or_default(),
        errors_csv,
    }
}

/// A file-name-safe form of a label.
fn slug(label: &str) -> String {
    let mut out = String::new();
    for c in label.chars() {
        match c {
            'a'..='z' | 'A'..='Z' | '0'..='9' => out.push(c.to_ascii_lowercase()),
            '-' | '.' => out.push(c),
            _ if !out.ends_with('_') => out.push('_'),
            _ => {}
        }
    }
    out.trim_matches('_').replace("_c", "c")
}

/// The per-epoch errors inside each outage of one run, as CSV.
fn write_errors(dir: &Path, result: &ModelResult) -> Result<Option<PathBuf>, Failure> {
    let Ok(evaluated) = &result.outcome else {
        return Ok(None);
    };
    std::fs::create_dir_all(dir)
        .map_err(|e| anyhow!("{}: cannot create: {e}", dir.display()))
        .data()?;
    let path = dir.join(format!(
        "{}_{}.csv",
        result.filter.name(),
        slug(&result.label)
    ));
    write_atomically(&path, |file| write_error_rows(file, &evaluated.errors)).data()?;
    Ok(Some(path))
}

fn write_error_rows(
    out: &mut impl std::io::Write,
    errors: &[Vec<EpochError>],
) -> Result<(), WriteError> {
    writeln!(
        out,
        "outage,t_s,since_outage_start_s,north_m,east_m,horizontal_m,heading_deg"
    )?;
    for (k, outage) in errors.iter().enumerate() {
        for e in outage {
            writeln!(
                out,
                "{},{:.9},{:.9},{},{},{},{}",
                k + 1,
                e.time_s,
                e.since_outage_start_s,
                e.north_m,
                e.east_m,
                e.horizontal_m,
                e.heading_deg
            )?;
        }
    }
    Ok(())
}

/// The table of the paper's Figures 13-15, per filter, best marked with '*'.
pub fn print_tournament_table(r: &EvaluationJson) {
    println!(
        "\nINS-only errors in {} GNSS outages at {:.1} °C ({:?} models; mean of per-outage RMS; max drift = RMS of per-outage maxima)",
        r.outages.len(),
        r.operating_temperature_c,
        r.gauss_markov_source
    );
    for filter in &r.filters {
        let best = &r.best_by_filter[filter.name()];
        println!(
            "\n{:<22} {:>15} {:>15} {:>15} {:>13} {:>16}",
            format!("{} model", filter.name().to_uppercase()),
            "north m",
            "east m",
            "horizontal m",
            "heading deg",
            "max drift m"
        );
        for m in r.models.iter().filter(|m| m.filter == *filter) {
            let cell = |key: &str, v: Option<f64>| {
                let mark = if best.get(key) == Some(&m.label) {
                    "*"
                } else {
                    " "
                };
                match (m.ci95.get(key), v) {
                    (Some(c), _) => format!("{:.2} ±{:.2}{mark}", c.mean, (c.high - c.low) / 2.0),
                    (None, Some(x)) => format!("{x:.2}{mark}"),
                    (None, None) => "diverged ".into(),
                }
            };
            println!(
                "{:<22} {:>15} {:>15} {:>15} {:>13} {:>16}",
                m.label,
                cell("rms_north_m", m.rms_north_m),
                cell("rms_east_m", m.rms_east_m),
                cell("rms_horizontal_m", m.rms_horizontal_m),
                cell("rms_heading_deg", m.rms_heading_deg),
                cell("max_drift_horizontal_m", m.max_drift_horizontal_m)
            );
        }
    }
    if r.significance.replicates > 1 {
        println!(
            "\nValues are means over {} replicates ({}) ± the half-width of the 95 % interval of the mean; '*' marks the lowest mean.",
            r.significance.replicates, r.significance.replicates_differ_by
        );
        for t in &r.significance.tests {
            if let Some(test) = &t.test {
                println!(
                    "{} {}: {} beats {} by {:.2} (95 % [{:.2}, {:.2}]), paired t p = {:.3}: {}",
                    t.filter.name(),
                    t.metric.key(),
                    t.winner,
                    t.runner_up,
                    -test.mean_difference,
                    -test.ci95_difference[1],
                    -test.ci95_difference[0],
                    test.p_value,
                    if t.significant {
                        "significant"
                    } else {
                        "not significant (could be noise)"
                    }
                );
            }
        }
    }
    for e in &r.excluded {
        println!("excluded {}: {}", e.label, e.reason);
    }
    println!("\nwritten: {}", r.report_file.display());
}
