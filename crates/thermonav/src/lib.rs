//! # thermonav
//!
//! Temperature-dependent stochastic modelling of MEMS inertial sensor errors, after
//! El-Diasty & Pagiatakis (2009), and the GNSS/INS filters that use those models.
//!
//! This crate is the numerical core: it reads no files, draws no plots and holds no global
//! state. File formats live in `thermonav-io`; the command line in `thermonav-cli`.
//!
//! ## Primer: from chamber records to errors in a GNSS outage
//!
//! The method in one run, on simulated data (no public multi-temperature static IMU data
//! exists; the simulator stands in for the chamber and the survey, and every draw follows from
//! the seed):
//!
//! 1. **Records**: a static IMU in a thermal chamber at 0 °C and at 40 °C
//!    ([`sim::chamber::simulate_chamber_run`]).
//! 2. **Characterise** each record into a bank entry: Allan deviation and noise terms, the AR
//!    model, three Gauss-Markov models ([`stoch::characterize::characterize`]), gathered in a
//!    [`stoch::bank::ModelBank`].
//! 3. **Select** the model for the operating temperature, 17 °C: Tc and σ interpolated
//!    between the two entries ([`nav::sensor_model::ImuStochasticModel::from_bank`]).
//! 4. **Filter** a harbour survey at 17 °C ([`sim::vessel::simulate_vessel`]) with that model:
//!    aligned from GNSS alone ([`nav::alignment::align_from_gnss`]), the 21-state EKF
//!    ([`nav::navigate::run`]), GNSS withheld for 60 s ([`nav::outage::Outages`]).
//! 5. **Measure** the errors against the reference trajectory inside the outage
//!    ([`evaluation::metrics::evaluate_solution`]), and inside an aided window of the same
//!    length for comparison.
//!
//! The records are 30 min at 10 Hz. Their length is what counts: at the sensor's datasheet
//! noise (ARW 2 °/√h) a gyro's Gauss-Markov bias is not yet significant against its white noise
//! after ten minutes, at any rate (DESIGN.md, "Why does the bank carry a third Gauss-Markov
//! model"); the rate only has to allow the AR conditioning (0.4 Hz low-pass, 1 Hz modelling
//! rate). The whole test takes about a second in release mode (about ten in a debug build).
//!
//! ```
//! use thermonav::evaluation::metrics::{Reference, evaluate_solution};
//! use thermonav::imu::Channel;
//! use thermonav::nav::alignment::{InitialUncertainty, align_from_gnss, uncorrected};
//! use thermonav::nav::engine::{EngineSettings, increments_from_series};
//! use thermonav::nav::measurement::AntennaGeometry;
//! use thermonav::nav::navigate::run;
//! use thermonav::nav::outage::Outages;
//! use thermonav::nav::sensor_model::{BankChoice, ImuStochasticModel, ScaleFactorPrior};
//! use thermonav::sim::chamber::{ChamberRun, ChamberWander, calgary, simulate_chamber_run};
//! use thermonav::sim::clock::SampleClock;
//! use thermonav::sensor::adis16364_like;
//! use thermonav::sim::vessel::{GnssSettings, VesselRun, harbour_survey, simulate_vessel};
//! use thermonav::stoch::bank::{GaussMarkovSource, ModelBank, Placement, Selection};
//! use thermonav::stoch::characterize::{CharacterizeSettings, characterize};
//! use thermonav::trajectory::TrajectoryPoint;
//! use thermonav::units::arw_rad_per_sqrt_s_to_deg_per_sqrt_h;
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let profile = adis16364_like(); // the simulated sensor: ADIS16364 datasheet noise
//! let seed = 7;
//!
//! // 1-2. One static record per chamber temperature, each characterised into a bank entry.
//! let mut entries = Vec::new();
//! for set_point_c in [0.0, 40.0] {
//!     let chamber = ChamberRun {
//!         temperature: thermonav::sim::chamber::ChamberTemperature::SetPoint { temperature_c: set_point_c },
//!         unit: thermonav::sim::unit::SimulatedUnit::default(),
//!         power_on: 1,
//!         duration_s: 1800.0,
//!         clock: SampleClock::new(10.0, 50e-6, 0.0)?, // 10 Hz, 50 µs timing jitter
//!         site: calgary(),
//!         wander: ChamberWander { sigma_c: 0.05, correlation_time_s: 600.0 },
//!         seed,
//!     };
//!     let record = simulate_chamber_run(&profile, &chamber)?;
//!     let settings = CharacterizeSettings::default();
//!     let (entry, _details) = characterize(&record.series, set_point_c, "simulated", &settings)?;
//!     entries.push(entry);
//! }
//! let bank = ModelBank::new(entries)?;
//!
//! // 3. The model at 17 °C, interpolated between the 0 °C and 40 °C entries.
//! let choice = BankChoice {
//!     temperature_c: 17.0,
//!     selection: Selection::Linear,
//!     source: GaussMarkovSource::IRREGULAR_ML, // exact likelihood of Gauss-Markov + white noise
//! };
//! let model = ImuStochasticModel::from_bank(&bank, &choice, &ScaleFactorPrior::default())?;
//! let gx = bank.select(17.0, Channel::Gx, choice.source, choice.selection)?;
//! assert!(matches!(gx.placement, Placement::Between { lower_c: 0.0, upper_c: 40.0, weight }
//!     if (weight - 17.0 / 40.0).abs() < 1e-12));
//! for axis in model.gyro.iter().chain(&model.accel) {
//!     // Recovered from the records: finite and positive on all six axes.
//!     assert!(axis.bias.correlation_time_s.is_finite() && axis.bias.correlation_time_s > 0.0);
//!     assert!(axis.bias.sigma.is_finite() && axis.bias.sigma > 0.0);
//! }
//! // The gyros' white noise is the datasheet's 2 °/√h, to within the Allan fit's spread.
//! let arw = arw_rad_per_sqrt_s_to_deg_per_sqrt_h(model.gyro[0].white_noise_density);
//! assert!((arw - 2.0).abs() < 0.2, "ARW {arw} °/√h");
//!
//! // 4. Five minutes of survey at 17 °C: IMU at 20 Hz, GNSS position and heading at 1 Hz.
//! let gnss = GnssSettings::default();
//! let survey = VesselRun {
//!     motion: harbour_survey(300.0),
//!     temperature: thermonav::sim::vessel::SurveyTemperature::Constant { temperature_c: 17.0 },
//!     unit: thermonav::sim::unit::SimulatedUnit::default(),
//!     clock: SampleClock::new(20.0, 0.0, 0.0)?,
//!     gnss,
//!     seed,
//! };
//! let field = simulate_vessel(&profile, &survey)?;
//! let increments = increments_from_series(&field.imu);
//! let geometry = AntennaGeometry {
//!     lever_arm_body_m: gnss.lever_arm_body_m,
//!     baseline_body: gnss.baseline_body_m,
//! };
//! let start = align_from_gnss(&increments, &field.gnss, &geometry, 1.0)?;
//! let settings = EngineSettings {
//!     geometry,
//!     outages: Outages::from_start_duration(&[(210.0, 60.0)])?, // no GNSS from 210 s to 270 s
//!     ..EngineSettings::default() // the EKF; `filter: FilterKind::Ukf` for the UKF
//! };
//! let p0 = InitialUncertainty::default().covariance();
//! let initial = uncorrected(start.nav);
//! let solution = run(&increments, &field.gnss, initial, p0, &model, &settings, &mut |_| {})?;
//!
//! // 5. Errors against the truth inside the outage, and over an aided minute (120-180 s).
//! let reference: Vec<TrajectoryPoint> =
//!     field.reference.states.iter().map(TrajectoryPoint::from_nav_state).collect();
//! let outages = settings.outages.windows();
//! let (outage, errors) = evaluate_solution(Reference::full(&reference), &solution.epochs, outages)?;
//! let aided_minute = Outages::from_start_duration(&[(120.0, 60.0)])?;
//! let (aided, _) = evaluate_solution(Reference::full(&reference), &solution.epochs, aided_minute.windows())?;
//! assert!(aided.max_drift_horizontal_m < 3.0, "aided: {} m", aided.max_drift_horizontal_m);
//! assert!(outage.max_drift_horizontal_m.is_finite());
//! assert!(outage.max_drift_horizontal_m > 10.0 * aided.max_drift_horizontal_m);
//! // INS-only, the error grows through the outage, and the filter knows it: its north
//! // position sigma at the outage's end is many times the aided one.
//! let through = &errors[0];
//! assert!(through.last().unwrap().horizontal_m > 10.0 * through[0].horizontal_m.max(0.1));
//! let sd_north_m = |t_s: f64| {
//!     let e = solution.epochs.iter().find(|e| e.estimate.nav.time.as_seconds() >= t_s).unwrap();
//!     e.sd[0]
//! };
//! assert!(sd_north_m(269.9) > 10.0 * sd_north_m(150.0));
//! # Ok(())
//! # }
//! ```
//!
//! The examples in `crates/thermonav/examples/` tell the same story at more length and print
//! what they find: `characterize_a_chamber`, `choose_a_model_for_temperature` and
//! `outage_tournament` (every bank model, the interpolated, pooled and data-sheet models
//! through the same outages, [`evaluation::tournament::run_tournament`]). Run one with
//! `cargo run --release -p thermonav --example NAME`.
//!
//! ## Principles
//! - Time is integer nanoseconds ([`time::Timestamp`]); seconds as `f64` only for arithmetic.
//! - Every quantity is SI inside the crate (rad/s, m/s², s); other units appear only at the
//!   edges, through the named conversions in [`units`].
//! - Choices are types (enums), never strings or booleans.
//! - Frames and times are types: a body vector does not add to a NED one, rotations compose
//!   only when their frames meet, a span is not an epoch. [`frames`] and [`time`] show each
//!   refused mix-up as a doctest that must not compile, beside the code that does.
//! - Estimators state their equation, assumptions and reference in their docs, and each is
//!   tested against an independent oracle (SciPy, statsmodels, allantools, Stable32, R, MATLAB).
//!
//! ## Modules
//! - [`time`]: exact timestamps and durations.
//! - [`units`]: named unit conversions (deg/h, mg, deg/√h, …).
//! - [`statistics`]: order statistics of plain numbers (median, median absolute deviation).
//! - [`evaluation`]: outage metrics, the temperature-model tournament and its significance.
//! - [`filter`]: generic UKF and EKF steps, sigma points, chi-square gating.
//! - [`frames`]: vectors and rotations typed by frame (body FRD, NED, ECEF).
//! - [`geo`]: WGS84, normal gravity, Earth rate.
//! - [`imu`]: IMU samples and series (rates or increments), channel names.
//! - [`ins`]: strapdown mechanization in NED.
//! - [`nav`]: the 21-state GNSS/INS filters (EKF, UKF) driven by the model bank.
//! - [`gnss`]: GNSS fixes: position, optional velocity, precision and dual-antenna heading.
//! - [`trajectory`]: reference trajectory points: position, velocity, attitude.
//! - [`mounting`]: the IMU's mounting in the body (an axis mapping or roll, pitch, yaw).
//! - [`optimise`]: general optimisers (Nelder-Mead, Newton, Brent, golden section,
//!   Levenberg-Marquardt), knowing nothing of what they optimise.
//! - [`signal`]: Kaiser FIR design, zero-phase filtering, decimation, timestamp checks.
//! - [`stoch`]: autocorrelation, AR estimators, Gauss-Markov models, Allan variance, the
//!   temperature model bank.
//! - [`rng`]: named, seeded random streams (simulation, Monte Carlo evaluation, tests).
//! - [`sensor`]: sensor profiles (noise figures, temperature dependence, the data-sheet
//!   ADIS16364-like profile) and the stochastic model they imply.
//! - [`setting`]: one setting checked against its range (positive, finite), refused with an
//!   error naming it: the checks the CLI and the Python package share.
//! - [`sim`]: seeded simulation of IMU errors and thermal-chamber campaigns.

pub mod evaluation;
pub mod filter;
pub mod frames;
pub mod geo;
pub mod gnss;
pub mod imu;
pub mod ins;
pub mod mounting;
pub mod nav;
pub mod optimise;
pub mod rng;
pub mod sensor;
pub mod setting;
pub mod signal;
pub mod sim;
pub mod statistics;
pub mod stoch;
pub mod time;
pub mod trajectory;
pub mod units;
