//! Step 3 of the story: does the temperature model matter once GNSS drops out?
//!
//! A harbour survey at 17 °C (simulated: the same sensor as the chamber campaign, 1 Hz GNSS
//! position and dual-antenna heading) is navigated with every model that could be chosen:
//! each bank entry's, the bank interpolated at 17 °C, a temperature-blind pooled model and
//! the data sheet's. Every model runs through the same filter on the same data with the same
//! GNSS outages; the errors inside the outages rank them. The survey is simulated again under
//! other seeds (new IMU errors and GNSS noise) to tell a real ranking from luck: the paired
//! t-test of the winner against the runner-up.
//!
//! `cargo run --release -p thermonav --example outage_tournament`

mod common;

use std::time::Instant;
use thermonav::evaluation::candidates::{DatasheetValues, tournament_candidates};
use thermonav::evaluation::metrics::Metric;
use thermonav::evaluation::scenario::Scenario;
use thermonav::evaluation::tournament::{ModelResult, run_tournament, summarize_replicates};
use thermonav::nav::alignment::{align_from_gnss, uncorrected};
use thermonav::nav::engine::{EngineSettings, FilterKind, increments_from_series};
use thermonav::nav::measurement::AntennaGeometry;
use thermonav::nav::outage::Outages;
use thermonav::nav::sensor_model::ScaleFactorPrior;
use thermonav::sim::clock::SampleClock;
use thermonav::sim::vessel::{GnssSettings, VesselRun, harbour_survey, simulate_vessel};
use thermonav::stoch::bank::GaussMarkovSource;
use thermonav::trajectory::TrajectoryPoint;

/// Survey temperature, °C.
const SURVEY_C: f64 = 17.0;
/// Survey length, s.
const SURVEY_S: f64 = 600.0;
/// IMU rate on the vessel, Hz.
const IMU_HZ: f64 = 25.0;
/// GNSS outages spread over the survey: how many, and how long each, s.
const OUTAGES: (usize, f64) = (4, 60.0);
/// Simulation seeds of the survey replicates (the first is the chamber campaign's).
const SEEDS: [u64; 4] = [common::SEED, 8, 9, 10];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let started = Instant::now();
    let profile = common::sensor();
    let bank = common::bank(&profile)?;
    let scale = ScaleFactorPrior::default();
    let (candidates, excluded) = tournament_candidates(
        &bank,
        SURVEY_C,
        GaussMarkovSource::IRREGULAR_ML,
        &scale,
        Some(&DatasheetValues::adis16364().model(&scale)),
    );
    for e in &excluded {
        println!("left out: {}: {}", e.label, e.reason);
    }
    println!(
        "Survey: {SURVEY_S} s of harbour survey at {SURVEY_C} °C, IMU {IMU_HZ} Hz, GNSS 1 Hz; {} outages of {} s spread over it",
        OUTAGES.0, OUTAGES.1
    );
    println!(
        "Models: {}; the EKF; {} simulation seeds",
        candidates
            .iter()
            .map(|c| c.label.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        SEEDS.len()
    );
    let mut replicates = Vec::new();
    let mut first = None;
    for seed in SEEDS {
        let scenario = survey(&profile, seed)?;
        replicates.push(run_tournament(
            &scenario,
            &candidates,
            &[FilterKind::Ekf],
            &|| {},
        ));
        first.get_or_insert(scenario);
    }
    // The UKF on the first seed with the interpolated model, to set beside the EKF.
    let interpolated: Vec<_> = candidates
        .iter()
        .filter(|c| c.label.starts_with("interpolated"))
        .cloned()
        .collect();
    let first = first.ok_or("no seed")?;
    let ukf = run_tournament(&first, &interpolated, &[FilterKind::Ukf], &|| {});
    first_seed_detail(replicates[0].iter().chain(&ukf));

    let (summaries, tests) = summarize_replicates(&replicates);
    println!(
        "\nOver the {} seeds: mean and 95 % interval of each model's figure (paper: mean of the per-outage RMS;",
        SEEDS.len()
    );
    println!("KF-GINS: RMS of the per-outage maximum):");
    println!(
        "  {:<22}  {:>4}  {:>26}  {:>26}  {:>22}",
        "model", "", "RMS horizontal, m", "max horizontal, m", "RMS heading, deg"
    );
    for s in &summaries {
        let cell = |metric: Metric| {
            s.ci95
                .iter()
                .find(|(m, _)| *m == metric)
                .map_or("-".into(), |(_, ci)| {
                    format!("{:.1} ({:.1}-{:.1})", ci.mean, ci.low, ci.high)
                })
        };
        println!(
            "  {:<22}  {:>4}  {:>26}  {:>26}  {:>22}{}",
            s.label,
            s.filter.name(),
            cell(Metric::RmsHorizontal),
            cell(Metric::MaxDriftHorizontal),
            cell(Metric::RmsHeading),
            if s.failures > 0 {
                format!("  ({} runs failed)", s.failures)
            } else {
                String::new()
            }
        );
    }
    println!("\nWinner against runner-up, paired over the seeds:");
    for t in tests.iter().filter(|t| t.metric == Metric::RmsHorizontal) {
        let p = t
            .test
            .map_or("-".into(), |test| format!("{:.3}", test.p_value));
        let verdict = if t.significant {
            "a real difference"
        } else {
            "within the noise of the replicates"
        };
        println!(
            "  {}: {} beats {} on RMS horizontal error, p = {p}: {verdict}",
            t.filter.name(),
            t.winner,
            t.runner_up
        );
    }
    println!("Done in {:.1} s.", started.elapsed().as_secs_f64());
    Ok(())
}

/// The survey simulated under `seed`, aligned from GNSS, with the outages and filter settings.
fn survey(
    profile: &common::SensorProfile,
    seed: u64,
) -> Result<Scenario, Box<dyn std::error::Error>> {
    let gnss = GnssSettings::default();
    let run = VesselRun {
        motion: harbour_survey(SURVEY_S),
        temperature: thermonav::sim::vessel::SurveyTemperature::Constant {
            temperature_c: SURVEY_C,
        },
        unit: thermonav::sim::unit::SimulatedUnit::default(),
        clock: SampleClock::new(IMU_HZ, 0.0, 0.0)?,
        gnss,
        seed,
    };
    let record = simulate_vessel(profile, &run)?;
    let increments = increments_from_series(&record.imu);
    let geometry = AntennaGeometry {
        lever_arm_body_m: gnss.lever_arm_body_m,
        baseline_body: gnss.baseline_body_m,
    };
    let start = align_from_gnss(&increments, &record.gnss, &geometry, 1.0)?;
    let (first, last) = match (record.gnss.first(), record.gnss.last()) {
        (Some(a), Some(b)) => (a.time, b.time),
        _ => return Err("the survey has no GNSS fix".into()),
    };
    let settings = EngineSettings {
        geometry,
        outages: Outages::spread(first, last, OUTAGES.0, OUTAGES.1)?,
        ..EngineSettings::default()
    };
    Ok(Scenario {
        increments,
        compensated_increments: None,
        oracle_increments: None,
        temperature: None,
        gnss: record.gnss,
        reference: record
            .reference
            .states
            .iter()
            .map(TrajectoryPoint::from_nav_state)
            .collect(),
        reference_content: Default::default(),
        initial: uncorrected(start.nav),
        still_start: None,
        settings,
    })
}

/// Per-outage errors of the first seed, for the interpolated model and the data sheet's.
fn first_seed_detail<'a>(results: impl Iterator<Item = &'a ModelResult>) {
    println!("\nFirst seed, outage by outage (RMS / maximum horizontal error, m):");
    for r in results {
        let shown = r.label.starts_with("interpolated") || r.label == "data sheet";
        match &r.outcome {
            Ok(e) if shown => {
                let cells: Vec<String> = e
                    .metrics
                    .per_outage
                    .iter()
                    .map(|o| {
                        format!(
                            "{:.0}-{:.0} s: {:.1} / {:.1}",
                            o.start_s, o.end_s, o.rms_horizontal_m, o.max_horizontal_m
                        )
                    })
                    .collect();
                println!(
                    "  {:<22} {:>4}  {}",
                    r.label,
                    r.filter.name(),
                    cells.join(";  ")
                );
                for s in &e.innovations {
                    println!(
                        "  {:<22} {:>4}  {:?} updates: mean NIS {:.2} for {} dimensions, {} of {} rejected by the gate",
                        "", "", s.kind, s.mean_nis, s.dimension, s.rejected, s.offered
                    );
                }
            }
            Err(why) => println!("  {} {}: the run failed: {why}", r.label, r.filter.name()),
            Ok(_) => {}
        }
    }
}
