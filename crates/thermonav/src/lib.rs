//! # thermonav
//!
//! Temperature-dependent stochastic modelling of MEMS inertial sensor errors, after
//! El-Diasty & Pagiatakis (2009), and the GNSS/INS filters that use those models.
//!
//! This crate is the numerical core: it reads no files, draws no plots and holds no global
//! state. File formats live in `thermonav-io`; the command line in `thermonav-cli`.
//!
//! ## Primer
//! - Time is integer nanoseconds ([`time::Timestamp`]); seconds as `f64` only for arithmetic.
//! - Every quantity is SI inside the crate (rad/s, m/s², s); other units appear only at the
//!   edges, through the named conversions in [`units`].
//! - Choices are types (enums), never strings or booleans.
//! - Estimators state their equation, assumptions and reference in their docs, and each is
//!   tested against an independent oracle (SciPy, statsmodels, allantools, Stable32, R, MATLAB).
//!
//! ## Modules
//! - [`time`]: exact timestamps and durations.
//! - [`units`]: named unit conversions (deg/h, mg, deg/√h, …).
//! - [`evaluation`]: outage metrics, the temperature-model tournament and its significance.
//! - [`filter`]: generic UKF and EKF steps, sigma points, chi-square gating.
//! - [`frames`]: vectors and rotations typed by frame (body FRD, NED, ECEF).
//! - [`geo`]: WGS84, normal gravity, Earth rate.
//! - [`imu`]: IMU samples and series (rates or increments), channel names.
//! - [`ins`]: strapdown mechanization in NED.
//! - [`nav`]: the 21-state GNSS/INS filters (EKF, UKF) driven by the model bank.
//! - [`gnss`]: GNSS fixes: position, optional velocity, precision and dual-antenna heading.
//! - [`trajectory`]: reference trajectory points: position, velocity, attitude.
//! - [`signal`]: Kaiser FIR design, zero-phase filtering, decimation, timestamp checks.
//! - [`stoch`]: autocorrelation, AR estimators, Gauss-Markov models, Allan variance, the
//!   temperature model bank.
//! - [`rng`]: named, seeded random streams (simulation, Monte Carlo evaluation, tests).
//! - [`sensor`]: sensor profiles (noise figures, temperature dependence, the data-sheet
//!   ADIS16364-like profile) and the stochastic model they imply.
//! - [`sim`]: seeded simulation of IMU errors and thermal-chamber campaigns.

pub mod evaluation;
pub mod filter;
pub mod frames;
pub mod geo;
pub mod gnss;
pub mod imu;
pub mod ins;
pub mod nav;
pub mod rng;
pub mod sensor;
pub mod signal;
pub mod sim;
pub mod stoch;
pub mod time;
pub mod trajectory;
pub mod units;
