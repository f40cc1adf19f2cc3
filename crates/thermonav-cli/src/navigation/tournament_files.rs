//! The tournament's file side (the tournament itself is `thermonav::evaluation::experiment`):
//! the scenario read from its files, the run with a progress bar, the per-model error CSVs and
//! `evaluation.json` written, and the table of the paper's Figures 13-15 printed. Shared by
//! `evaluate` and `demo`.

use crate::failure::{Classify, Failure};
use crate::inputs::operating_temperature;
use crate::navigation::reference_input::{
    check_overlap, read_reference, read_start_reference, record_span,
};
use crate::settings::navigation::ScenarioFiles;
use anyhow::anyhow;
use serde::Serialize;
use std::path::{Path, PathBuf};
use thermonav::evaluation::experiment::{Replicates, Tournament};
use thermonav::evaluation::metrics::{EpochError, Metric};
use thermonav::evaluation::outside::OutsideResult;
use thermonav::evaluation::report::{ModelReport, TournamentReport};
pub use thermonav::evaluation::scenario::RecordPlan;
use thermonav::evaluation::scenario::{
    Scenario, ScenarioError, ScenarioImu, scenario_imu as library_scenario_imu,
    scenario_of as library_scenario_of, scenario_of_records,
};
use thermonav::evaluation::tournament::ModelResult;
use thermonav::gnss::GnssFix;
use thermonav::imu::ImuSeries;
use thermonav::nav::engine::{EngineSettings, FilterKind};
use thermonav::nav::outage::{Outage, OutageSpec};
use thermonav::nav::run::{NoiseModel, RunInput, RunSettings, Start};
use thermonav::nav::run_options::RunOptions;
use thermonav::nav::time_offset::{
    TimeOffsetEstimate, TimeOffsetSearch, estimate_time_offset, shifted,
};
use thermonav::trajectory::{ReferenceContent, TrajectoryPoint};
use thermonav_io::{
    ImuOptions, Strictness, WriteError, read_gnss_file, read_imu_file_with, write_atomically,
    write_json_atomically,
};

/// `evaluation.json`: the report and where it was written.
#[derive(Debug, Serialize)]
pub struct EvaluationFile {
    /// The report.
    #[serde(flatten)]
    pub report: TournamentReport,
    /// The `--imu-rotation` the IMU record was turned by, when given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub imu_rotation: Option<String>,
    /// How every candidate's run went (`evaluate`'s run options, as `integrate --json`
    /// reports its own; absent when no filter ran, and from the demo's tournaments, which set
    /// their runs themselves).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub run_options: Option<RunOptions>,
    /// The IMU-GNSS time offset every candidate ran at (`--estimate-time-offset`, as
    /// `integrate --json` reports its own).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time_offset: Option<TimeOffsetEstimate>,
    /// This file.
    pub report_file: PathBuf,
}

/// What evaluation.json repeats of the command line beside the report.
#[derive(Debug, Clone, Default)]
pub struct Echo {
    /// How the IMU record was read (its `--imu-rotation`).
    pub imu_options: ImuOptions,
    /// The run options of every candidate's run.
    pub run_options: Option<RunOptions>,
    /// The time offset every candidate ran at, when estimated.
    pub time_offset: Option<TimeOffsetEstimate>,
}

/// The echo as evaluation.json writes it: the rotation's text, the run options and the time
/// offset.
#[derive(Debug, Clone, Default)]
pub struct EchoText {
    /// The `--imu-rotation`, as text.
    pub imu_rotation: Option<String>,
    /// The run options of every candidate's run.
    pub run_options: Option<RunOptions>,
    /// The time offset every candidate ran at, when estimated.
    pub time_offset: Option<TimeOffsetEstimate>,
}

/// How the runs of a tournament from files start and on which record, beside the reference:
/// the trajectory they start from (`--initial-from`) and the IMU-GNSS time-offset search
/// (`--estimate-time-offset`) with the run it is made with. The default: from the reference
/// (aligned when it holds positions only), on the record as read.
#[derive(Debug, Clone, Copy, Default)]
pub struct StartPlan<'a> {
    /// The trajectory every run starts from instead of the reference.
    pub initial_from: Option<&'a Path>,
    /// The search, the run it searches with and that run's noise model.
    pub time_offset: Option<(&'a TimeOffsetSearch, &'a RunSettings, NoiseModel<'a>)>,
}

/// A tournament's scenario from files: the scenario, the operating temperature and the time
/// offset its record was shifted by, when estimated.
#[derive(Debug)]
pub struct FileScenario {
    /// The scenario.
    pub scenario: Scenario,
    /// The operating temperature, °C (given, or the IMU's mean temp_c).
    pub operating_temperature_c: f64,
    /// The estimated IMU-GNSS time offset (the record shifted by its applied offset).
    pub time_offset: Option<TimeOffsetEstimate>,
}

/// The scenario of the files (start from the reference at the first fix, default initial
/// covariance, `engine`'s settings with the outages of `outages`, the record compensated
/// under `records` beside the raw one, and with the truth's bias subtracted for the oracle)
/// and the operating temperature (given, or the IMU's mean temp_c). The reference may be any
/// kind [`crate::navigation::reference_input`] reads; one of positions only is checked to overlap the
/// IMU record, and the runs then start aligned from GNSS and score no heading.
pub fn scenario_from_files(
    files: &ScenarioFiles,
    engine: EngineSettings,
    outages: &OutageSpec,
    operating_temperature_c: Option<f64>,
    records: RecordPlan,
) -> Result<(Scenario, f64), Failure> {
    let settings = (engine, outages, operating_temperature_c);
    let made = scenario_from_files_with(files, settings, records, StartPlan::default())?;
    Ok((made.scenario, made.operating_temperature_c))
}

/// [`scenario_from_files`] with the runs started and the record shifted as `plan` says: from
/// `--initial-from`'s trajectory (refused without attitude, as integrate refuses it), and on
/// the record shifted by the time offset estimated with the plan's run, started as every
/// candidate starts.
pub fn scenario_from_files_with(
    files: &ScenarioFiles,
    (engine, outages, operating_temperature_c): (EngineSettings, &OutageSpec, Option<f64>),
    records: RecordPlan,
    plan: StartPlan,
) -> Result<FileScenario, Failure> {
    let series = read_imu_file_with(&files.imu, Strictness::Strict, &files.imu_options).data()?;
    let gnss = read_gnss_file(&files.gnss, Strictness::Strict).data()?;
    let reference = read_reference(&files.reference)?;
    let run = (record_span(&series), files.imu.as_path());
    check_overlap((&reference, &files.reference), run)?;
    let operating_c = operating_temperature(operating_temperature_c, &series, &files.imu)?;
    let initial = (plan.initial_from.map(|p| read_start_reference(p, run))).transpose()?;
    let content = reference.content();
    let start = match (&initial, content) {
        (Some(points), _) => Some(Start::Reference(points)),
        (None, ReferenceContent::PositionOnly) => Some(Start::Align),
        (None, ReferenceContent::Full) => None,
    };
    let searched = start.unwrap_or(Start::Reference(&reference.points));
    let time_offset = (plan.time_offset)
        .map(|search| offset_of((&series, &gnss), searched, search, files))
        .transpose()?;
    let series = match &time_offset {
        Some(estimate) => shifted(&series, estimate.applied_offset_s),
        None => series,
    };
    let scenario =
        scenario_of_records(&series, gnss, reference.points, (&engine, outages), records)
            .and_then(|s| started(s, content, start))
            .map_err(|e| scenario_failure(e, files))?;
    Ok(FileScenario {
        scenario,
        operating_temperature_c: operating_c,
        time_offset,
    })
}

/// The scenario scored as the reference's `content` allows, its runs started by `start`
/// (`None`: from the reference).
fn started(
    scenario: Scenario,
    content: ReferenceContent,
    start: Option<Start>,
) -> Result<Scenario, ScenarioError> {
    let scenario = match content {
        ReferenceContent::Full => scenario,
        ReferenceContent::PositionOnly => scenario.scoring_positions_only(),
    };
    match start {
        Some(start) => scenario.started(start),
        None => Ok(scenario),
    }
}

/// The IMU-GNSS time offset of the record, searched with the plan's run from `start` (as
/// `integrate --estimate-time-offset` searches), errors naming the file they are about.
fn offset_of(
    (series, gnss): (&ImuSeries, &[GnssFix]),
    start: Start,
    (search, run, noise): (&TimeOffsetSearch, &RunSettings, NoiseModel),
    files: &ScenarioFiles,
) -> Result<TimeOffsetEstimate, Failure> {
    estimate_time_offset(series, gnss, noise, start, run, search)
        .map_err(|e| scenario_failure(ScenarioError::Run(e), files))
}

/// A refused scenario, naming the file (or the option) it is about.
pub fn scenario_failure(error: ScenarioError, files: &ScenarioFiles) -> Failure {
    let file = match error.input() {
        RunInput::Settings => return Failure::Usage(anyhow!("--outages: {error}")),
        RunInput::Imu => Some(&files.imu),
        RunInput::Gnss => Some(&files.gnss),
        RunInput::Reference => Some(&files.reference),
        RunInput::Noise | RunInput::Filter => None,
    };
    let named = file.map(|f| format!("{}: ", f.display()));
    Failure::Data(anyhow!("{}{error}", named.unwrap_or_default()))
}

/// The IMU side of a scenario from its record (see the library's
/// [`thermonav::evaluation::scenario::scenario_imu`]), errors naming `path`.
pub fn scenario_imu(
    series: &ImuSeries,
    plan: RecordPlan,
    path: &Path,
) -> Result<ScenarioImu, Failure> {
    library_scenario_imu(series, plan)
        .map_err(|e| anyhow!("{}: {e}", path.display()))
        .data()
}

/// A scenario from in-memory data, started from the reference at the first fix (see the
/// library's [`thermonav::evaluation::scenario::scenario_of`]), errors naming the reference.
pub fn scenario_of(
    imu: ScenarioImu,
    gnss: Vec<GnssFix>,
    reference: Vec<TrajectoryPoint>,
    settings: EngineSettings,
    reference_name: &Path,
) -> Result<Scenario, Failure> {
    library_scenario_of(imu, gnss, reference, settings).map_err(|e| match e {
        ScenarioError::NoFix => Failure::Data(anyhow!("{e}")),
        _ => Failure::Data(anyhow!("{}: {e}", reference_name.display())),
    })
}

/// Runs the tournament (with a progress bar), adds the `outside` solutions' rows, writes the
/// per-model error CSVs under `out/errors` and `out/evaluation.json`, and returns what was
/// written.
pub fn run_and_write(
    tournament: &Tournament,
    main: &Scenario,
    replicates: &Replicates,
    outside: &[OutsideResult],
    (out, echo): (&Path, &Echo),
) -> Result<EvaluationFile, Failure> {
    let bar = crate::progress::bar(tournament.runs(replicates), "tournament runs");
    let outcome = tournament
        .run(main, replicates, &|| bar.inc(1))
        .map_err(|e| anyhow!("{e}"))
        .data()?;
    bar.finish_and_clear();
    let text = EchoText {
        imu_rotation: crate::settings::imu::rotation_text(&echo.imu_options),
        run_options: echo.run_options.clone(),
        time_offset: echo.time_offset.clone(),
    };
    write_outcome((outcome.report, &outcome.main), outside, (out, text))
}

/// Adds the `outside` solutions' rows to `report`, writes the per-model error CSVs of the
/// main run `main` under `out/errors` and `out/evaluation.json` (with the `--imu-rotation`
/// text and the run options, when given), and returns what was written (also the end of
/// `evaluate merge`).
pub fn write_outcome(
    (mut report, main): (TournamentReport, &[ModelResult]),
    outside: &[OutsideResult],
    (out, echo): (&Path, EchoText),
) -> Result<EvaluationFile, Failure> {
    report.add_outside(outside);
    let ours = main.iter().map(|r| {
        let errors = r.outcome.as_ref().ok().map(|e| e.errors.as_slice());
        (format!("{}_{}", r.filter.name(), slug(&r.label)), errors)
    });
    let errors: Vec<_> = ours.chain(outside_errors(outside)).collect();
    write_evaluation(report, &errors, (out, echo))
}

/// Scores only outside solutions (no filter runs) and writes their error CSVs and
/// `out/evaluation.json`.
pub fn write_outside_only(
    (outages, content): (&[Outage], ReferenceContent),
    outside: &[OutsideResult],
    out: &Path,
) -> Result<EvaluationFile, Failure> {
    let report = TournamentReport::outside_only(outages, outside, content);
    let errors: Vec<_> = outside_errors(outside).collect();
    write_evaluation(report, &errors, (out, EchoText::default()))
}

/// The error-CSV names and errors of outside solutions.
fn outside_errors(
    outside: &[OutsideResult],
) -> impl Iterator<Item = (String, Option<&[Vec<EpochError>]>)> {
    outside.iter().map(|o| {
        let errors = Some(o.evaluated.errors.as_slice());
        (format!("outside_{}", slug(&o.label)), errors)
    })
}

/// Writes each model's errors (`errors` in the report's model order: file stem and errors, none
/// for a failed run) under `out/errors`, stores their paths relative to evaluation.json, and
/// writes `out/evaluation.json`.
fn write_evaluation(
    mut report: TournamentReport,
    errors: &[(String, Option<&[Vec<EpochError>]>)],
    (out, echo): (&Path, EchoText),
) -> Result<EvaluationFile, Failure> {
    // Every number is checked before the first file is written: a report that cannot be
    // written leaves no error table behind.
    thermonav_io::check_finite(&report).data()?;
    for (stem, errors) in errors {
        thermonav_io::check_finite(errors)
            .map_err(|e| anyhow!("errors of {stem}: {e}"))
            .data()?;
    }
    for (model, (stem, errors)) in report.models.iter_mut().zip(errors) {
        model.errors_csv = match errors {
            Some(e) => Some(write_errors(out, stem, e)?),
            None => None,
        };
    }
    let file = EvaluationFile {
        report,
        imu_rotation: echo.imu_rotation,
        run_options: echo.run_options,
        time_offset: echo.time_offset,
        report_file: out.join("evaluation.json"),
    };
    // The folder exists already when an error CSV was written, not when every run failed.
    crate::campaign::create_folder(out)?;
    write_json_atomically(&file.report_file, &file).data()?;
    Ok(file)
}

/// A data failure when no model's main run succeeded (the report, written and printed, says
/// why each failed).
pub fn check_some_model_ran(file: &EvaluationFile) -> Result<(), Failure> {
    let models = &file.report.models;
    if models.iter().any(|m| m.failure.is_none()) {
        return Ok(());
    }
    let first = models.first().and_then(|m| m.failure.as_deref());
    Err(Failure::Data(anyhow!(
        "every model's filter failed on this data (first: {}); see {}",
        first.unwrap_or("no candidate"),
        file.report_file.display()
    )))
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

/// The per-epoch errors inside each outage of one run, as `out/errors/STEM.csv`; returns its
/// path relative to `out` (where evaluation.json is).
fn write_errors(out: &Path, stem: &str, errors: &[Vec<EpochError>]) -> Result<PathBuf, Failure> {
    let dir = out.join("errors");
    std::fs::create_dir_all(&dir)
        .map_err(|e| anyhow!("{}: cannot create: {e}", dir.display()))
        .data()?;
    let relative = Path::new("errors").join(format!("{stem}.csv"));
    write_atomically(out.join(&relative), |file| write_error_rows(file, errors)).data()?;
    Ok(relative)
}

/// The error table: a `heading_deg` column only when the errors have one (none against a
/// position-only reference).
fn write_error_rows(
    out: &mut impl std::io::Write,
    errors: &[Vec<EpochError>],
) -> Result<(), WriteError> {
    let first = errors.iter().flatten().next();
    let content = match first.is_some_and(|e| e.heading_deg.is_none()) {
        true => ReferenceContent::PositionOnly,
        false => ReferenceContent::Full,
    };
    writeln!(out, "outage,{}", EpochError::columns(content).join(","))?;
    for (k, outage) in errors.iter().enumerate() {
        for e in outage {
            write!(out, "{}", k + 1)?;
            error_values(out, e)?;
        }
    }
    Ok(())
}

/// One epoch's values after its outage number, each through the finite gate.
fn error_values(out: &mut impl std::io::Write, e: &EpochError) -> std::io::Result<()> {
    for value in e.values() {
        out.write_all(b",")?;
        thermonav_io::write_finite(out, value)?;
    }
    out.write_all(b"\n")
}

/// The table of the paper's Figures 13-15, per filter, best marked with '*', the outside
/// solutions in every table (or in their own when no filter ran).
pub fn print_tournament_table(file: &EvaluationFile) {
    let r = &file.report;
    println!(
        "\nINS-only errors in {} GNSS outages{} (mean of per-outage RMS; max drift = RMS of per-outage maxima)",
        r.outages.len(),
        conditions(r)
    );
    for filter in &r.filters {
        print_filter_table(r, Some(*filter));
    }
    if r.filters.is_empty() {
        print_filter_table(r, None);
    }
    if let Some(not_scored) = r.reference.not_scored {
        println!("\nnot scored: {not_scored}");
    }
    if let Some(t) = &file.time_offset {
        println!(
            "\nevery run on the IMU record shifted by {:+.1} ms, the time offset estimated ({}) in {} runs over ±{:.0} ms",
            1e3 * t.applied_offset_s,
            match t.applied {
                true => "applied",
                false => "not determined, not applied",
            },
            t.runs,
            1e3 * t.bracket_s[1]
        );
    }
    if r.models.iter().any(|m| m.filter.is_none()) {
        println!(
            "\noutside: scored assuming their solver withheld GNSS in these same outages; not ranked"
        );
    }
    if r.significance.replicates > 1 {
        print_significance(r);
    }
    print_oracle_gaps(r);
    for e in &r.excluded {
        println!("excluded {}: {}", e.label, e.reason);
    }
    println!("\nwritten: {}", file.report_file.display());
}

/// " at T °C (SOURCE models)" when our filters ran.
fn conditions(r: &TournamentReport) -> String {
    match (r.operating_temperature_c, r.gauss_markov_source) {
        (Some(t), Some(source)) => format!(" at {t:.1} °C ({} models)", source.cli_name()),
        _ => String::new(),
    }
}

/// Every model's horizontal error above the oracle's, when there is one.
fn print_oracle_gaps(r: &TournamentReport) {
    if let Some(first) = r.oracle_gaps.first() {
        println!(
            "\nAbove the oracle ({}, the simulator's true model; horizontal):",
            first.oracle
        );
    }
    for g in &r.oracle_gaps {
        let filter = g.filter.name().to_uppercase();
        println!(
            "  {filter} {:<30} {:>+9.2} m ({:.2}x)",
            g.label, g.excess_m, g.ratio
        );
    }
}

/// One filter's table (its models, then the outside solutions), or the outside solutions'
/// alone for `None`.
fn print_filter_table(r: &TournamentReport, filter: Option<FilterKind>) {
    let title = filter.map_or("outside", FilterKind::name);
    println!(
        "\n{:<28} {:>15} {:>15} {:>15} {:>13} {:>16}",
        format!("{} model", title.to_uppercase()),
        "north m",
        "east m",
        "horizontal m",
        "heading deg",
        "max drift m"
    );
    let best = filter.and_then(|f| r.best_by_filter.get(f.name()));
    let shown = r.models.iter().filter(|m| m.filter == filter);
    for m in shown.chain(
        r.models
            .iter()
            .filter(|m| filter.is_some() && m.filter.is_none()),
    ) {
        let cells = Metric::ALL.map(|metric| {
            let best_here = best.and_then(|b| b.get(metric.key())) == Some(&m.label);
            table_cell(m, metric, if best_here { "*" } else { " " })
        });
        println!(
            "{:<28} {:>15} {:>15} {:>15} {:>13} {:>16}",
            row_label(m),
            cells[0],
            cells[1],
            cells[2],
            cells[3],
            cells[4]
        );
    }
}

/// A model's label in the tables, an outside solution's marked as such.
fn row_label(m: &ModelReport) -> String {
    match m.filter {
        Some(_) => m.label.clone(),
        None => format!("{} (outside)", m.label),
    }
}

/// The mean ± half-width over replicates, or the single run's value, or "diverged" (or
/// "not scored" for the heading against a position-only reference).
fn table_cell(m: &ModelReport, metric: Metric, mark: &str) -> String {
    match (m.ci95.get(metric.key()), m.value(metric)) {
        (Some(c), _) => format!("{:.2} ±{:.2}{mark}", c.mean, (c.high - c.low) / 2.0),
        (None, Some(x)) => format!("{x:.2}{mark}"),
        (None, None) if m.failure.is_none() => "not scored ".into(),
        (None, None) => "diverged ".into(),
    }
}

fn print_significance(r: &TournamentReport) {
    println!(
        "\nValues are means over {} replicates ({}) ± the half-width of the 95 % interval of the mean; '*' marks the lowest mean.",
        r.significance.replicates, r.significance.replicates_differ_by
    );
    for t in &r.significance.tests {
        let Some(test) = &t.test else { continue };
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

#[cfg(test)]
mod tests {
    use super::*;

    fn epoch(heading_deg: f64) -> EpochError {
        let heading_deg = Some(heading_deg);
        EpochError {
            time_s: 12.5,
            since_outage_start_s: 2.5,
            north_m: 1.0,
            east_m: -2.0,
            horizontal_m: 5f64.sqrt(),
            heading_deg,
        }
    }

    // Issue 20: the per-epoch error CSV is a writer like the others: a NaN is refused, not
    // printed.
    #[test]
    fn the_error_rows_are_written_exactly_and_refuse_a_nan() {
        let mut out = Vec::new();
        write_error_rows(&mut out, &[vec![epoch(0.25)]]).unwrap();
        let text = String::from_utf8(out).unwrap();
        let row = text.lines().nth(1).unwrap();
        assert_eq!(row, format!("1,12.5,2.5,1,-2,{},0.25", 5f64.sqrt()));
        let error = write_error_rows(&mut Vec::new(), &[vec![epoch(f64::NAN)]]).unwrap_err();
        assert!(error.to_string().contains("NaN"), "{error}");
    }

    // Issue 38 row 3: against a position-only reference the table has no heading column.
    #[test]
    fn errors_without_heading_have_no_heading_column() {
        let mut out = Vec::new();
        let position_only = EpochError {
            heading_deg: None,
            ..epoch(0.0)
        };
        write_error_rows(&mut out, &[vec![position_only]]).unwrap();
        let text = String::from_utf8(out).unwrap();
        let mut lines = text.lines();
        let header = "outage,t_s,since_outage_start_s,north_m,east_m,horizontal_m";
        assert_eq!(lines.next(), Some(header));
        assert_eq!(lines.next().unwrap().split(',').count(), 6);
    }
}
