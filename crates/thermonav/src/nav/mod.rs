//! GNSS/INS integration: the 21-state error-state filters (EKF and UKF) that carry the
//! temperature model bank's noise models into navigation.
//!
//! - [`sensor_model`]: per-axis white noise and Gauss-Markov bias / scale-factor models, taken
//!   from the bank at a chosen temperature, and their exact discretisation; [`profile_model`]:
//!   the same model taken from a sensor profile or a data sheet's figures.
//! - [`error_state`]: the nominal estimate (navigation state plus sensor corrections) and the
//!   21-element error vector that moves between it and the truth (⊕ and ⊖).
//! - [`measurement`]: GNSS position and velocity at a lever arm, dual-antenna heading.
//! - [`alignment`]: coarse levelling, heading from GNSS, the initial covariance.
//! - [`schedule`]: the model at the IMU's temperature at every covariance step (a track of
//!   the temperature and models precomputed on a grid), and the thermal compensation of a
//!   record.
//! - [`outage`]: windows in which GNSS updates are withheld.
//! - [`engine`]: the run loop: mechanization at the IMU rate, covariance propagation at a
//!   chosen rate, updates at GNSS epochs, closed-loop feedback.
//! - [`navigate`]: the entry points ([`navigate::run`], [`navigate::run_scheduled`],
//!   [`navigate::run_streaming`]): the checks, then one filter or the Gaussian sum.
//! - [`process_model`]: one covariance step's linearisation (Φ, Q) and nonlinear propagation;
//!   [`error_filter`]: the EKF and the UKF behind one interface (predict and update by value).
//! - [`gaussian_sum`]: the z-gyro bias prior split into filters run in lockstep, for runs in
//!   which nothing observes the heading directly.
//! - [`solution`]: what a run returns: solution epochs, innovations and their statistics.
//! - [`run`]: one run on records already read (model chosen, record compensated, outages
//!   laid, start aligned, filter run), and [`report`]: what it reports; [`stream`]: the same
//!   run on a record read as it goes, its records streamed to a sink, in bounded memory.
//! - [`time_offset`]: the IMU-GNSS time offset that maximises the innovations' likelihood.
//!
//! Error conventions (as in [`crate::ins::error_model`]): δr = r̂ − r (NED, m), δv = v̂ − v,
//! Ĉ_b^n = (I − [φ×]) C_b^n, and the sensor states are the error left in the corrected
//! measurements (true bias minus estimated bias), which the closed-loop feedback adds to the
//! estimated corrections.

pub mod alignment;
pub mod engine;
pub mod error_filter;
pub mod error_state;
pub mod gaussian_sum;
pub mod measurement;
pub mod navigate;
pub mod outage;
pub mod process_model;
pub mod profile_model;
pub mod report;
pub mod run;
pub mod run_options;
pub mod schedule;
pub mod sensor_model;
pub mod smoother;
pub mod solution;
pub mod static_alignment;
pub mod stream;
pub mod time_offset;
