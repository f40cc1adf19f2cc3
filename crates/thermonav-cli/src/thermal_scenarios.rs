//! The demo's scenarios in which temperature matters, on the built-in temperature-sensitive
//! profile (`thermonav::sensor::temperature_sensitive`) with every channel's MEMS structure
//! lagging its temperature sensor by [`DEMO_THERMAL_LAG_S`]: one chamber campaign of one unit
//! (set points at repeated power-ons for the noise models, a chamber program whose sweep gives
//! the thermal calibration with its lag, and a sweep of another power-on that checks it,
//! [`HeldOutCheck`]), its bank, and two surveys of the same unit, each with its tournament and
//! the claim it tests (the oracle reads the true bias at the structure's lagged temperature):
//!
//! - (b) a survey at 17 °C: the bank model nearest the survey's temperature has the lowest
//!   mean horizontal error among the fixed bank temperatures and beats every model 40 °C or
//!   more away, paired p < 0.01;
//! - (c) a cold start warming up: scheduled plus compensated beats the best fixed model plus
//!   compensation and every fixed model without it, paired p < 0.01.
//!
//! (b)'s replicates are independent simulations of the survey (new noise and a new power-on
//! offset of the same unit, seeds `seed + k`), so its p-values say how surely the nearest model
//! wins on another survey of this unit, not only wherever the outages of one survey fall; each
//! comparison states the replicates its measured effect needs for p < 0.01 at 80 % power
//! ([`thermonav::evaluation::significance::pairs_for_power`]). (c) and the matrix shift the
//! outages along one simulated survey (as `evaluate --monte-carlo` does).
use crate::banks::building::{BankInputs, build_bank_reading};
use crate::campaign::{ChamberTruth, run_chamber, true_model, with_thermal_lag};
use crate::failure::{Classify, Failure};
use crate::inputs::{TEMPERATURE_SENSITIVE_PROFILE, load_profile};
use crate::navigation::tournament_files::{
    EvaluationFile, RecordPlan, run_and_write, scenario_imu, scenario_of,
};
use crate::settings::simulation::{ChamberSettings, chamber_settings};
use crate::thermal::calibration::ThermalInputs;
use crate::thermal::sweeps::calibrate_sweeps_alone;
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use thermonav::evaluation::candidates::{CandidateKind, ThermalOptions};
use thermonav::evaluation::experiment::{CandidateSource, Replicates, Tournament, TournamentPlan};
use thermonav::evaluation::oracle::TrueModel;
use thermonav::evaluation::report::ModelReport;
use thermonav::evaluation::scenario::Scenario;
use thermonav::evaluation::significance::pairs_for_power;
use thermonav::evaluation::tournament::Contrast;
use thermonav::imu::Channel;
use thermonav::nav::engine::{EngineSettings, FilterKind};
use thermonav::nav::measurement::AntennaGeometry;
use thermonav::nav::outage::OutageSpec;
use thermonav::nav::schedule::{Compensation, Scheduling};
use thermonav::nav::sensor_model::ScaleFactorPrior;
use thermonav::sensor::SensorProfile;
use thermonav::sim::chamber::{CampaignSettings, ChamberTemperature, Ramp, calgary};
use thermonav::sim::clock::SampleClock;
use thermonav::sim::temperature_program::TemperatureProgram;
use thermonav::sim::unit::SimulatedUnit;
use thermonav::sim::vessel::{
    GnssSettings, SurveyTemperature, VesselRun, harbour_survey, simulate_vessel,
};
use thermonav::stoch::bank::{GaussMarkovSource, ModelBank};
use thermonav::stoch::characterize::CharacterizeSettings;
use thermonav::stoch::thermal::check::{ChannelCheck, check_record};
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::{write_atomically, write_json_atomically};
use thermonav_plot::figures::DisplayUnits;
use thermonav_plot::figures::thermal_check::thermal_check_figure;

/// The time constant by which the demo unit's MEMS structure lags its temperature sensor, s
/// (every channel): during the warming survey's first minutes the structure is then several
/// °C behind the sensor, which a calibration in T alone mistakes for bias.
pub const DEMO_THERMAL_LAG_S: f64 = 120.0;

/// The chamber program the unit's lag is calibrated from, in a power-on of its own: 20 →
/// −30 → 50 → 20 °C at 3 °C/min with 10-minute dwells at the turns (4400 s).
fn lag_program() -> TemperatureProgram {
    TemperatureProgram {
        t_s: vec![0.0, 1000.0, 1600.0, 3200.0, 3800.0, 4400.0],
        temperature_c: vec![20.0, -30.0, -30.0, 50.0, 50.0, 20.0],
    }
}

/// The sweep the calibration is checked on, never fitted to: another power-on, −30 → 50 °C
/// at 2 °C/min.
const HELD_OUT_RAMP: Ramp = Ramp {
    start_c: -30.0,
    end_c: 50.0,
    rate_c_per_min: 2.0,
};

/// Where the held-out check's figure is written, under the scenarios' folder.
pub const HELD_OUT_CHECK_SVG: &str = "held_out_check.svg";

/// The p-value a claim's comparisons must stay below.
pub const CLAIM_P_VALUE: f64 = 0.01;

/// Distance from the survey temperature beyond which a bank model is "far", °C.
pub const FAR_C: f64 = 40.0;

/// Sizes of the scenarios.
#[derive(Debug, Clone)]
pub struct ScenarioPlan {
    /// Chamber record length of the first power-on, s.
    pub chamber_duration_s: f64,
    /// Chamber rate, Hz.
    pub chamber_rate_hz: f64,
    /// Power-ons of the campaign.
    pub power_ons: u32,
    /// Record length of the further power-ons, s.
    pub repeat_duration_s: f64,
    /// Survey length, s.
    pub survey_s: f64,
    /// Survey IMU rate, Hz.
    pub survey_rate_hz: f64,
    /// Outages of each survey.
    pub outages: OutageSpec,
    /// Replicates of scenario (b), the main run included.
    pub replicates: u64,
    /// Replicates of scenario (c).
    pub warming_replicates: u64,
    /// Survey temperatures of the matrix of the paper's Figures 13-15 (empty: no matrix).
    pub matrix_survey_temperatures_c: Vec<f64>,
    /// Replicates of each matrix survey.
    pub matrix_replicates: u64,
    /// Start temperature of the warming survey, °C.
    pub cold_start_c: f64,
    /// Its settled temperature, °C.
    pub settled_c: f64,
    /// Its warm-up time constant, s.
    pub warm_up_time_constant_s: f64,
    /// Seed of the campaign and the surveys.
    pub seed: u64,
}

impl ScenarioPlan {
    /// The warming survey's temperature.
    fn warming(&self) -> SurveyTemperature {
        SurveyTemperature::WarmUp {
            start_c: self.cold_start_c,
            settled_c: self.settled_c,
            time_constant_s: self.warm_up_time_constant_s,
        }
    }
}

/// One comparison a claim rests on.
#[derive(Debug, Clone, Serialize)]
pub struct ClaimComparison {
    /// The model the claim says is better.
    pub better: String,
    /// The model it must beat.
    pub worse: String,
    /// Mean of worse − better over the replicates, m (negative: the claim's model is worse).
    pub mean_difference_m: f64,
    /// Paired t-test p-value.
    pub p_value: Option<f64>,
    /// 95 % interval of the mean of worse − better, m (`None` without a test).
    pub ci95_difference_m: Option<[f64; 2]>,
    /// The claim's model is better with p below [`CLAIM_P_VALUE`].
    pub holds: bool,
    /// Replicates the measured effect (mean over sd of the paired differences) needs for
    /// p < [`CLAIM_P_VALUE`] with [`CLAIM_POWER`] power; `None` without a test, or beyond
    /// [`MAX_POWER_REPLICATES`].
    pub replicates_needed: Option<usize>,
}

/// The power a claim's comparison is sized for.
pub const CLAIM_POWER: f64 = 0.8;

/// The most replicates a power statement looks at (`evaluate --monte-carlo`'s limit).
pub const MAX_POWER_REPLICATES: usize = 1000;

/// How a scenario's replicates differ from its main run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ReplicateKind {
    /// The outages shifted along the one simulated survey.
    ShiftedOutages,
    /// The survey simulated anew (seeds `seed + k`).
    NewSimulations,
}

/// A scenario's claim and whether the tournament bears it out.
#[derive(Debug, Clone, Serialize)]
pub struct Claim {
    /// The claim, in words.
    pub statement: String,
    /// Whether every part of it holds.
    pub holds: bool,
    /// The comparisons.
    pub comparisons: Vec<ClaimComparison>,
    /// With an oracle: the simulator's true models scheduled ((b): on the raw record; (c): on
    /// the record compensated with the bank's calibration, as the claimed candidate runs)
    /// against the same rival as the claim's hardest comparison; when even it does not win,
    /// the claim is beyond what any noise model can show on these data.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub oracle_bound: Option<ClaimComparison>,
}

/// One scenario's outcome.
#[derive(Debug, Serialize)]
pub struct ScenarioOutcome {
    /// Its name.
    pub name: &'static str,
    /// How the survey's temperature behaves.
    pub survey_temperature: SurveyTemperature,
    /// The claim tested.
    pub claim: Claim,
    /// The tournament.
    pub tournament: EvaluationFile,
}

/// Both scenarios and what they were run on.
#[derive(Debug, Serialize)]
pub struct ThermalScenarios {
    /// The sensor profile.
    pub profile: String,
    /// The campaign's power-ons.
    pub power_ons: u32,
    /// The bank (with its thermal calibration).
    pub bank: PathBuf,
    /// (b): temperature matters at a constant 17 °C.
    pub temperature_matters: ScenarioOutcome,
    /// (c): a survey that warms up.
    pub warming_survey: ScenarioOutcome,
    /// Survey temperature × model temperature (the paper's Figures 13-15 as a full matrix),
    /// when the plan asks for it.
    pub matrix: Option<TemperatureMatrix>,
    /// The thermal calibration (with its lag, from the chamber program) checked on a sweep
    /// of another power-on.
    pub held_out_check: HeldOutCheck,
}

/// The bank's thermal calibration against a sweep it was not fitted to.
#[derive(Debug, Serialize)]
pub struct HeldOutCheck {
    /// The simulated unit's lag, s (every channel).
    pub true_lag_s: f64,
    /// The record checked.
    pub record: PathBuf,
    /// The figure (observed, predicted and band against time and temperature), its file
    /// name beside the bank.
    pub figure: String,
    /// Per channel: the lag chosen (s; 0 without one), and the shape RMS of the record's
    /// 30 s block means before and after compensation, rate unit.
    pub channels: BTreeMap<Channel, HeldOutChannel>,
}

/// One channel of [`HeldOutCheck`].
#[derive(Debug, Serialize)]
pub struct HeldOutChannel {
    /// SI unit of the RMS values.
    pub unit: &'static str,
    /// The chosen model's lag τ, s (negative: the structure lags; 0: no lag term).
    pub tau_s: f64,
    /// Shape RMS uncompensated.
    pub rms_before_offset_removed: f64,
    /// Shape RMS after compensation.
    pub rms_after_offset_removed: f64,
    /// Fraction of blocks within the band.
    pub coverage_offset_removed: f64,
}

/// Mean horizontal error of every fixed bank model on surveys at several temperatures.
#[derive(Debug, Serialize)]
pub struct TemperatureMatrix {
    /// Survey temperatures, °C (rows).
    pub survey_temperatures_c: Vec<f64>,
    /// Bank model temperatures, °C (columns).
    pub model_temperatures_c: Vec<f64>,
    /// Mean over the replicates of the per-outage RMS horizontal error, m, `[row][column]`
    /// (null where the model is missing or failed).
    pub mean_horizontal_m: Vec<Vec<Option<f64>>>,
    /// Per row, the model temperature with the lowest error, °C.
    pub best_model_c: Vec<Option<f64>>,
    /// Per row, the lowest error over the error of the model nearest the survey temperature
    /// (1: the nearest model is the best).
    pub nearest_over_best: Vec<Option<f64>>,
    /// Replicates per survey (shifted outages).
    pub replicates: u64,
}

/// Runs the campaign, the bank and both scenarios under `out`.
///
/// # Errors
/// A simulation, characterisation or tournament that fails.
pub fn run_thermal_scenarios(plan: &ScenarioPlan, out: &Path) -> Result<ThermalScenarios, Failure> {
    let profile = demo_unit_profile()?;
    let bank_path = out.join("bank.json");
    let (bank, held_out_record) = campaign_bank(plan, out, &bank_path)?;
    let held_out_check = held_out_check(&bank, &held_out_record, out)?;
    let constant = SurveyTemperature::Constant {
        temperature_c: 17.0,
    };
    let warming = plan.warming();
    let survey = Survey {
        profile: &profile,
        bank: &bank,
        plan,
    };
    let (b, c) = survey.claims_b_and_c((&constant, &warming), out)?;
    let matrix = survey.matrix(&out.join("matrix"))?;
    Ok(ThermalScenarios {
        profile: profile.name.clone(),
        power_ons: plan.power_ons,
        bank: bank_path,
        temperature_matters: ScenarioOutcome {
            name: "temperature matters (b)",
            claim: nearest_claim(
                &b.report.models,
                &b.report.significance.horizontal_contrasts,
                17.0,
            ),
            survey_temperature: constant,
            tournament: b,
        },
        warming_survey: ScenarioOutcome {
            name: "a survey that warms up (c)",
            claim: scheduled_claim(
                &c.report.models,
                &c.report.significance.horizontal_contrasts,
            ),
            survey_temperature: warming,
            tournament: c,
        },
        matrix,
        held_out_check,
    })
}

/// The built-in temperature-sensitive profile with every channel's structure lagging by
/// [`DEMO_THERMAL_LAG_S`].
fn demo_unit_profile() -> Result<SensorProfile, Failure> {
    with_thermal_lag(
        load_profile(Some(Path::new(TEMPERATURE_SENSITIVE_PROFILE)))?,
        Some(DEMO_THERMAL_LAG_S),
    )
}

/// The chamber campaign of the lagging unit, its bank (noise models from the set points, the
/// thermal calibration with its lag from the chamber program), and the held-out sweep's file.
fn campaign_bank(
    plan: &ScenarioPlan,
    out: &Path,
    bank: &Path,
) -> Result<(ModelBank, PathBuf), Failure> {
    let campaign = CampaignSettings {
        duration_s: plan.chamber_duration_s,
        rate_hz: plan.chamber_rate_hz,
        power_ons: plan.power_ons,
        repeat_duration_s: Some(plan.repeat_duration_s),
        ramp: Some(HELD_OUT_RAMP),
        program: Some(lag_program()),
        ..CampaignSettings::default()
    };
    let profile = Some(PathBuf::from(TEMPERATURE_SENSITIVE_PROFILE));
    let mut chamber = chamber_settings(out.join("chamber"), campaign, profile, plan.seed)?;
    chamber.thermal_lag_s = Some(DEMO_THERMAL_LAG_S);
    let truth = run_chamber(&chamber)?;
    let sweep = |wanted: fn(&ChamberTemperature) -> bool| {
        (truth.further_records.iter())
            .find(|r| wanted(&r.truth.chamber))
            .map(|r| r.file.clone())
            .ok_or_else(|| Failure::Data(anyhow!("the campaign wrote no sweep record")))
    };
    let program = sweep(|t| matches!(t, ChamberTemperature::Program(_)))?;
    let ramp = sweep(|t| matches!(t, ChamberTemperature::Ramp(_)))?;
    // The set points' bank and the program's calibration are independent: side by side.
    let sweeps = ThermalInputs {
        sweeps: vec![vec![program]],
        site: calgary(),
        ..ThermalInputs::default()
    };
    let (static_bank, lag) = rayon::join(
        || set_point_bank(&chamber, &truth, bank),
        || calibrate_sweeps_alone(&sweeps),
    );
    let (static_bank, lag) = (static_bank?, lag?);
    let joined = static_bank
        .with_thermal_from(lag)
        .map_err(|e| anyhow!("the chamber program's calibration: {e}"))
        .data()?;
    write_json_atomically(bank, &joined).data()?;
    Ok((joined, ramp))
}

/// The bank of the set points (noise models, and their static thermal calibration).
fn set_point_bank(
    chamber: &ChamberSettings,
    truth: &ChamberTruth,
    bank: &Path,
) -> Result<ModelBank, Failure> {
    let files: Vec<&Path> = truth.files.iter().map(PathBuf::as_path).collect();
    let thermal = ThermalInputs {
        power_ons: further_power_ons(truth),
        site: calgary(),
        ..ThermalInputs::default()
    };
    let inputs = BankInputs {
        files: &files,
        temperatures: &chamber.campaign.temperatures_c,
        thermal: &thermal,
    };
    build_bank_reading(
        &inputs,
        &CharacterizeSettings::default(),
        crate::args::ReadingArg::Auto,
        bank,
    )
}

/// The set-point records of the power-ons after the first, grouped by power-on (the sweeps
/// have power-ons of their own).
fn further_power_ons(truth: &ChamberTruth) -> Vec<Vec<PathBuf>> {
    let mut groups: BTreeMap<u32, Vec<PathBuf>> = BTreeMap::new();
    let set_points = (truth.further_records.iter())
        .filter(|r| matches!(r.truth.chamber, ChamberTemperature::SetPoint { .. }));
    for record in set_points {
        groups
            .entry(record.truth.power_on)
            .or_default()
            .push(record.file.clone());
    }
    groups.into_values().collect()
}

/// The bank's thermal calibration checked on the held-out sweep (30 s blocks), with its
/// figure written beside the bank.
fn held_out_check(bank: &ModelBank, record: &Path, out: &Path) -> Result<HeldOutCheck, Failure> {
    let calibration = bank
        .thermal
        .as_ref()
        .ok_or_else(|| Failure::Data(anyhow!("the demo's bank has no thermal calibration")))?;
    let read = (&Default::default(), &Default::default());
    let series = crate::thermal::calibration::sweep_series(record, 0, read)?.series;
    let checks = check_record(calibration, &series, HELD_OUT_BLOCK_S, None)
        .map_err(|e| anyhow!("{}: {e}", record.display()))
        .data()?;
    let chosen: Vec<(Channel, &ChannelCheck)> = checks.iter().map(|(&c, k)| (c, k)).collect();
    let svg = thermal_check_figure(
        "the demo unit's thermal calibration (with its lag) on a sweep it was not fitted to",
        &chosen,
        DisplayUnits::Navigation,
    );
    write_atomically(out.join(HELD_OUT_CHECK_SVG), |file| {
        Ok(std::io::Write::write_all(file, svg.as_bytes())?)
    })
    .data()?;
    let channels = checks
        .iter()
        .map(|(c, k)| {
            let tau_s = calibration.channels.get(c).map_or(0.0, |cal| cal.lag_s());
            let row = HeldOutChannel {
                unit: k.unit,
                tau_s,
                rms_before_offset_removed: k.rms_before_offset_removed,
                rms_after_offset_removed: k.rms_after_offset_removed,
                coverage_offset_removed: k.coverage_offset_removed,
            };
            (*c, row)
        })
        .collect();
    Ok(HeldOutCheck {
        true_lag_s: DEMO_THERMAL_LAG_S,
        record: record.to_path_buf(),
        figure: HELD_OUT_CHECK_SVG.into(),
        channels,
    })
}

/// Block length of the held-out check, s.
const HELD_OUT_BLOCK_S: f64 = 30.0;

/// What the surveys share.
struct Survey<'a> {
    profile: &'a SensorProfile,
    bank: &'a ModelBank,
    plan: &'a ScenarioPlan,
}

impl Survey<'_> {
    /// The tournament of the bank's candidates on a survey at `temperature`, replicated as
    /// `kind` says.
    fn tournament(
        &self,
        temperature: SurveyTemperature,
        (scheduling, compensation, replicates, kind): (
            Scheduling,
            Compensation,
            u64,
            ReplicateKind,
        ),
        out: &Path,
    ) -> Result<EvaluationFile, Failure> {
        let operating_c = mean_temperature_c(&temperature, self.plan.survey_s);
        let run = self.run(temperature)?;
        let (main, truth) = self
            .scenario(&run, compensation)
            .map_err(|e| anyhow!("{e}"))
            .data()?;
        let thermal = ThermalOptions {
            imu_temperature_range_c: main.temperature.as_ref().map(|t| t.range_c()),
            scheduling,
            compensation,
        };
        let plan = self.tournament_plan(Some(&truth), thermal, operating_c);
        let tournament = Tournament::new(&plan).map_err(|e| anyhow!("{e}")).data()?;
        let extra = replicates.saturating_sub(1) as usize;
        let resimulated = |k: usize| {
            let run = VesselRun {
                seed: run.seed.wrapping_add(k as u64),
                ..run.clone()
            };
            self.scenario(&run, compensation).map(|(s, _)| s)
        };
        let replicates = match kind {
            ReplicateKind::ShiftedOutages => Replicates::ShiftedOutages {
                extra,
                seed: self.plan.seed,
            },
            ReplicateKind::NewSimulations => Replicates::Made {
                extra,
                differ_by: "simulation seeds (new IMU errors, power-on offset and GNSS noise per replicate)",
                make: &resimulated,
            },
        };
        run_and_write(
            &tournament,
            &main,
            &replicates,
            &[],
            (out, &Default::default()),
        )
    }

    /// The tournaments of claims (b), on a survey at `constant`, and (c), on one at `warming`.
    /// They are independent (their own seeds, folders and records), so they run side by side
    /// and one fills the cores the other's last replicates leave idle. Their two progress bars
    /// would draw over each other, so both are hidden meanwhile (the step line says what runs).
    fn claims_b_and_c(
        &self,
        (constant, warming): (&SurveyTemperature, &SurveyTemperature),
        out: &Path,
    ) -> Result<(EvaluationFile, EvaluationFile), Failure> {
        // At one temperature the scheduled and compensated candidates add nothing to (b)'s
        // claim.
        let fixed = (
            Scheduling::Fixed,
            Compensation::Off,
            self.plan.replicates,
            ReplicateKind::NewSimulations,
        );
        let thermal = (
            Scheduling::ByTemperature,
            Compensation::WhenCalibrated,
            self.plan.warming_replicates,
            ReplicateKind::ShiftedOutages,
        );
        let (b, c) = crate::progress::stacked(|| {
            rayon::join(
                || self.tournament(constant.clone(), fixed, &out.join("temperature_matters")),
                || self.tournament(warming.clone(), thermal, &out.join("warming_survey")),
            )
        });
        Ok((b?, c?))
    }

    /// The plan of a scenario's tournament: the bank's candidates (and the oracle's), EKF.
    fn tournament_plan<'t>(
        &'t self,
        oracle: Option<&'t TrueModel>,
        thermal: ThermalOptions,
        operating_temperature_c: f64,
    ) -> TournamentPlan<'t> {
        TournamentPlan {
            oracle,
            noise: CandidateSource::Bank(self.bank),
            thermal,
            operating_temperature_c,
            source: GaussMarkovSource::default(),
            filters: vec![FilterKind::Ekf],
            datasheet: None,
            scale: ScaleFactorPrior::default(),
        }
    }

    /// The fixed bank models on a survey at each of the plan's matrix temperatures.
    fn matrix(&self, out: &Path) -> Result<Option<TemperatureMatrix>, Failure> {
        let temperatures = &self.plan.matrix_survey_temperatures_c;
        if temperatures.is_empty() {
            return Ok(None);
        }
        let fixed = (
            Scheduling::Fixed,
            Compensation::Off,
            self.plan.matrix_replicates,
            ReplicateKind::ShiftedOutages,
        );
        let mut rows = Vec::new();
        for &t in temperatures {
            let survey = SurveyTemperature::Constant { temperature_c: t };
            let file = self.tournament(survey, fixed, &out.join(format!("survey_{t}C")))?;
            rows.push(entry_errors(&file.report.models));
        }
        Ok(Some(matrix_of(
            temperatures,
            &rows,
            self.plan.matrix_replicates,
        )))
    }

    fn run(&self, temperature: SurveyTemperature) -> Result<VesselRun, Failure> {
        Ok(VesselRun {
            motion: harbour_survey(self.plan.survey_s),
            temperature,
            unit: SimulatedUnit::default(),
            clock: SampleClock::new(self.plan.survey_rate_hz, 50e-6, 0.0).usage()?,
            gnss: GnssSettings::default(),
            seed: self.plan.seed,
        })
    }

    /// The survey as a scenario (raw and compensated records) and its truth, which every
    /// scenario carries so that each claim says whether the true model itself could show it.
    /// The compensated records (ours and the oracle's) are made only when `compensation` lets
    /// compensated candidates in.
    fn scenario(
        &self,
        run: &VesselRun,
        compensation: Compensation,
    ) -> Result<(Scenario, TrueModel), String> {
        let record = simulate_vessel(self.profile, run).map_err(|e| e.to_string())?;
        let name = Path::new("simulated survey");
        let truth = true_model(self.profile, run, &record.imu).map_err(|e| e.to_string())?;
        let records = RecordPlan {
            oracle: Some(&truth).filter(|_| compensation != Compensation::Off),
            ..RecordPlan::calibrated(self.bank.thermal.as_ref(), compensation)
        };
        let imu = scenario_imu(&record.imu, records, name).map_err(|e| e.to_string())?;
        let reference: Vec<TrajectoryPoint> = record
            .reference
            .states
            .iter()
            .map(TrajectoryPoint::from_nav_state)
            .collect();
        let span = match (imu.increments.first(), imu.increments.last()) {
            (Some(a), Some(b)) => (a.time, b.time),
            _ => return Err("the survey has no IMU interval".into()),
        };
        let settings = EngineSettings {
            geometry: AntennaGeometry {
                lever_arm_body_m: run.gnss.lever_arm_body_m,
                baseline_body: run.gnss.baseline_body_m,
            },
            outages: self.plan.outages.resolve(span).map_err(|e| e.to_string())?,
            ..EngineSettings::default()
        };
        let scenario = scenario_of(imu, record.gnss, reference, settings, name);
        Ok((scenario.map_err(|e| e.to_string())?, truth))
    }
}

/// The mean of a survey's temperature over its first `duration_s`, °C (1 s steps).
fn mean_temperature_c(temperature: &SurveyTemperature, duration_s: f64) -> f64 {
    let steps = duration_s.max(1.0).ceil() as usize;
    (0..steps).map(|k| temperature.at(k as f64)).sum::<f64>() / steps as f64
}

/// The comparison of `better` against `worse` in the tournament's contrasts.
fn comparison(contrasts: &[Contrast], better: &str, worse: &str) -> ClaimComparison {
    let found = contrasts.iter().find(|c| {
        (c.better == better && c.worse == worse) || (c.better == worse && c.worse == better)
    });
    let (mean_difference_m, p_value, ci95_difference_m) = match found {
        Some(c) if c.better == better => (
            c.mean_difference_m,
            c.test.map(|t| t.p_value),
            c.test.map(|t| t.ci95_difference),
        ),
        Some(c) => (
            -c.mean_difference_m,
            c.test.map(|t| t.p_value),
            c.test
                .map(|t| [-t.ci95_difference[1], -t.ci95_difference[0]]),
        ),
        None => (f64::NAN, None, None),
    };
    let replicates_needed = found.and_then(|c| c.test).and_then(|t| {
        pairs_for_power(
            t.effect_size(),
            CLAIM_P_VALUE,
            CLAIM_POWER,
            MAX_POWER_REPLICATES,
        )
    });
    ClaimComparison {
        better: better.to_string(),
        worse: worse.to_string(),
        holds: mean_difference_m > 0.0 && p_value.is_some_and(|p| p < CLAIM_P_VALUE),
        replicates_needed: replicates_needed.filter(|_| mean_difference_m > 0.0),
        mean_difference_m: if mean_difference_m.is_finite() {
            mean_difference_m
        } else {
            0.0
        },
        p_value,
        ci95_difference_m,
    }
}

/// The mean horizontal error over the replicates (the main run's without replicates), m.
fn mean_horizontal_m(model: &ModelReport) -> Option<f64> {
    model
        .ci95
        .get("rms_horizontal_m")
        .map(|c| c.mean)
        .or(model.rms_horizontal_m)
}

/// The fixed bank models (entries) with their temperatures.
fn entries(models: &[ModelReport]) -> Vec<(&ModelReport, f64)> {
    models
        .iter()
        .filter_map(|m| match m.candidate {
            CandidateKind::Entry { temperature_c } => Some((m, temperature_c)),
            _ => None,
        })
        .collect()
}

/// (model temperature, mean horizontal error) of every fixed bank model.
fn entry_errors(models: &[ModelReport]) -> Vec<(f64, Option<f64>)> {
    entries(models)
        .into_iter()
        .map(|(m, t)| (t, mean_horizontal_m(m)))
        .collect()
}

/// The matrix of the rows' errors, on the union of their model temperatures.
fn matrix_of(
    survey_temperatures_c: &[f64],
    rows: &[Vec<(f64, Option<f64>)>],
    replicates: u64,
) -> TemperatureMatrix {
    let mut model_temperatures_c: Vec<f64> = rows.iter().flatten().map(|(t, _)| *t).collect();
    model_temperatures_c.sort_by(f64::total_cmp);
    model_temperatures_c.dedup();
    let mean_horizontal_m: Vec<Vec<Option<f64>>> = rows
        .iter()
        .map(|row| {
            let at = |t: f64| row.iter().find(|(m, _)| *m == t).and_then(|(_, e)| *e);
            model_temperatures_c.iter().map(|&t| at(t)).collect()
        })
        .collect();
    let (best_model_c, nearest_over_best) = survey_temperatures_c
        .iter()
        .zip(&mean_horizontal_m)
        .map(|(&survey_c, errors)| row_verdict(survey_c, &model_temperatures_c, errors))
        .unzip();
    TemperatureMatrix {
        survey_temperatures_c: survey_temperatures_c.to_vec(),
        model_temperatures_c,
        mean_horizontal_m,
        best_model_c,
        nearest_over_best,
        replicates,
    }
}

/// The best model's temperature and best / nearest error ratio of one row.
fn row_verdict(
    survey_c: f64,
    model_c: &[f64],
    errors: &[Option<f64>],
) -> (Option<f64>, Option<f64>) {
    let known: Vec<(f64, f64)> = model_c
        .iter()
        .zip(errors)
        .filter_map(|(&t, e)| e.map(|e| (t, e)))
        .collect();
    let best = known.iter().min_by(|a, b| a.1.total_cmp(&b.1)).copied();
    let nearest = known
        .iter()
        .min_by(|a, b| (a.0 - survey_c).abs().total_cmp(&(b.0 - survey_c).abs()))
        .copied();
    match (best, nearest) {
        (Some(b), Some(n)) => (Some(b.0), Some(b.1 / n.1)),
        _ => (None, None),
    }
}

/// The matrix as text: one row per survey temperature.
fn print_matrix(m: &TemperatureMatrix) {
    println!(
        "\nSurvey temperature x model temperature (the paper's Figures 13-15 as a matrix): mean horizontal error, m, over {} shifted-outage replicates; '*' marks each row's best",
        m.replicates
    );
    let header: Vec<String> = m
        .model_temperatures_c
        .iter()
        .map(|t| format!("{:>9}", format!("{t} °C")))
        .collect();
    println!("{:>10} {}", "survey", header.join(""));
    for (k, row) in m.mean_horizontal_m.iter().enumerate() {
        let cells: Vec<String> = row
            .iter()
            .zip(&m.model_temperatures_c)
            .map(|(e, &t)| matrix_cell(*e, m.best_model_c[k] == Some(t)))
            .collect();
        println!(
            "{:>10} {}",
            format!("{} °C", m.survey_temperatures_c[k]),
            cells.join("")
        );
    }
}

fn matrix_cell(error: Option<f64>, best: bool) -> String {
    match error {
        Some(e) => format!("{:>8.1}{}", e, if best { "*" } else { " " }),
        None => format!("{:>9}", "-"),
    }
}

/// Claim (b): the entry nearest `survey_c` is the best entry and beats the far ones.
fn nearest_claim(models: &[ModelReport], contrasts: &[Contrast], survey_c: f64) -> Claim {
    let fixed = entries(models);
    let distance = |t: f64| (t - survey_c).abs();
    let Some(&(nearest, nearest_c)) = fixed
        .iter()
        .min_by(|a, b| distance(a.1).total_cmp(&distance(b.1)))
    else {
        return unavailable("the bank has no fixed model");
    };
    let best_entry = fixed
        .iter()
        .filter_map(|(m, _)| mean_horizontal_m(m).map(|v| (m, v)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(m, _)| m.label.clone());
    let comparisons: Vec<ClaimComparison> = fixed
        .iter()
        .filter(|(_, t)| distance(*t) >= FAR_C)
        .map(|(m, _)| comparison(contrasts, &nearest.label, &m.label))
        .collect();
    let lowest = best_entry.as_deref() == Some(nearest.label.as_str());
    // The oracle (the true model, scheduled on the raw record) against the far rival the
    // nearest model does worst against: when even it does not win, no model can show (b).
    let hardest = comparisons
        .iter()
        .min_by(|a, b| a.mean_difference_m.total_cmp(&b.mean_difference_m))
        .map(|c| c.worse.clone());
    let oracle = models
        .iter()
        .find(|m| m.candidate == CandidateKind::Oracle)
        .map(|m| m.label.clone());
    Claim {
        statement: format!(
            "the bank model nearest {survey_c} °C ({nearest_c} °C) has the lowest mean horizontal error among the fixed bank temperatures{} and beats every model {FAR_C} °C or more away with paired p < {CLAIM_P_VALUE}",
            if lowest {
                ""
            } else {
                " (it does not: the lowest is another)"
            }
        ),
        holds: lowest && !comparisons.is_empty() && comparisons.iter().all(|c| c.holds),
        comparisons,
        oracle_bound: oracle
            .zip(hardest)
            .map(|(oracle, rival)| comparison(contrasts, &oracle, &rival)),
    }
}

/// Claim (c): scheduled plus compensated beats the compensated fixed model and every
/// uncompensated fixed model.
fn scheduled_claim(models: &[ModelReport], contrasts: &[Contrast]) -> Claim {
    let label_of = |wanted: fn(&CandidateKind) -> bool| {
        models
            .iter()
            .find(|m| wanted(&m.candidate))
            .map(|m| m.label.clone())
    };
    let Some(best) = label_of(|k| matches!(k, CandidateKind::ScheduledCompensated { .. })) else {
        return unavailable(
            "no scheduled and compensated candidate (no thermal calibration or no temp_c)",
        );
    };
    let mut rivals: Vec<String> = entries(models)
        .iter()
        .map(|(m, _)| m.label.clone())
        .collect();
    let fixed_compensated = label_of(|k| matches!(k, CandidateKind::CompensatedEntry { .. }));
    rivals.extend(fixed_compensated.clone());
    let comparisons: Vec<ClaimComparison> = rivals
        .iter()
        .map(|rival| comparison(contrasts, &best, rival))
        .collect();
    // The bound of the claim's hardest part, scheduling on the compensated record: the true
    // noise models scheduled on the same record (our calibration's compensation), so that the
    // bound asks what the claim asks. The truth's exact compensation would also credit the
    // oracle with a better compensation than any model here can have.
    let oracle = label_of(|k| matches!(k, CandidateKind::OracleOnCalibrated));
    Claim {
        statement: format!(
            "scheduled plus compensated beats the fixed model plus compensation and every fixed model without it, with paired p < {CLAIM_P_VALUE}"
        ),
        holds: comparisons.iter().all(|c| c.holds),
        comparisons,
        oracle_bound: oracle
            .zip(fixed_compensated)
            .map(|(oracle, rival)| comparison(contrasts, &oracle, &rival)),
    }
}

fn unavailable(why: &str) -> Claim {
    Claim {
        statement: format!("not testable: {why}"),
        holds: false,
        comparisons: Vec::new(),
        oracle_bound: None,
    }
}

/// What a comparison's power statement says, in words.
fn replicates_needed_text(needed: Option<usize>) -> String {
    match needed {
        Some(n) => format!(
            "{n} replicates give p < {CLAIM_P_VALUE} with {:.0} % power at this effect",
            CLAIM_POWER * 100.0
        ),
        None => format!("no number of replicates up to {MAX_POWER_REPLICATES} shows this effect"),
    }
}

/// The oracle against the claim's hardest rival, and what it means.
fn print_oracle_bound(o: &ClaimComparison) {
    let p = o.p_value.map_or("n/a".to_string(), |p| format!("{p:.2e}"));
    let meaning = match (o.holds, o.mean_difference_m > 0.0) {
        (true, _) => "the true model shows it, so a better model could".to_string(),
        (false, true) => format!(
            "the true model leads but these replicates do not show it ({})",
            replicates_needed_text(o.replicates_needed)
        ),
        (false, false) => "not even the true model leads: no model can on these data".into(),
    };
    let lead = o.mean_difference_m;
    println!(
        "oracle: {} beats {} by {lead:.2} m (paired p = {p}): {meaning}",
        o.better, o.worse
    );
}

/// The scenarios' text: each claim with its comparisons.
pub fn print_thermal_scenarios(s: &ThermalScenarios) {
    for scenario in [&s.temperature_matters, &s.warming_survey] {
        println!(
            "\n{} on the {} ({} power-ons in the chamber):",
            scenario.name, s.profile, s.power_ons
        );
        crate::navigation::tournament_files::print_tournament_table(&scenario.tournament);
        let verdict = if scenario.claim.holds {
            "HOLDS"
        } else {
            "does NOT hold"
        };
        println!("claim ({verdict}): {}", scenario.claim.statement);
        for c in &scenario.claim.comparisons {
            let p = c.p_value.map_or("n/a".to_string(), |p| format!("{p:.2e}"));
            println!(
                "  {} beats {} by {:.2} m (paired p = {p}; {}){}",
                c.better,
                c.worse,
                c.mean_difference_m,
                replicates_needed_text(c.replicates_needed),
                if c.holds { "" } else { "  <- not shown" }
            );
        }
        if let Some(bound) = &scenario.claim.oracle_bound {
            print_oracle_bound(bound);
        }
    }
    print_held_out_check(&s.held_out_check);
    if let Some(m) = &s.matrix {
        print_matrix(m);
    }
}

/// The calibration on the held-out sweep: per channel the lag chosen and the shape RMS before
/// and after compensation (deg/h, mg), with the band's coverage.
fn print_held_out_check(check: &HeldOutCheck) {
    println!(
        "\nthe unit's thermal calibration (structure lagging by {} s; lag from a chamber program) on a sweep of another power-on it was not fitted to ({}):",
        check.true_lag_s,
        check.record.display()
    );
    for (channel, c) in &check.channels {
        let name = channel.name();
        let units = DisplayUnits::Navigation;
        let show = |si: f64| units.rate(channel.sensor(), si);
        println!(
            "  {name}: lag chosen {:.0} s; shape rms {:.2} -> {:.2} {}; band covers {:.0} % of the 30 s blocks",
            c.tau_s,
            show(c.rms_before_offset_removed),
            show(c.rms_after_offset_removed),
            units.rate_unit(channel.sensor()),
            100.0 * c.coverage_offset_removed
        );
    }
}
