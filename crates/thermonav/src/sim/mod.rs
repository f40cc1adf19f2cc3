//! Seeded simulation of IMU errors and thermal-chamber campaigns.
//!
//! No public multi-temperature static IMU data exists, so the simulator is what lets every user
//! and every test run the whole method. The sensor simulated is described by a
//! [`crate::sensor::SensorProfile`]; every random draw comes from a generator named after what
//! it draws ([`crate::rng::named_rng`]), derived from one user seed: changing how one quantity
//! is drawn never changes the draws of another.
//!
//! Processes are discretised exactly with each sample's actual interval dt_k (method.md
//! equations 3-4): a Gauss-Markov bias steps with φ_k = exp(−dt_k/Tc) and driving variance
//! σ²(1 − φ_k²); white rate noise of density N averaged over dt_k has variance N²/dt_k; a bias
//! random walk of density K gains variance K² dt_k.

pub mod chamber;
pub mod clock;
pub mod errors;
pub mod ideal_imu;
pub mod motion;
pub mod rover;
pub mod temperature_program;
pub mod unit;
pub mod vessel;
