//! Strapdown inertial navigation in the local-level NED frame.
//!
//! - [`state`]: the navigation state (position, velocity, attitude) and IMU increments.
//! - [`error_model`]: the 21-state error model (system matrix F) of the psi-angle form.
//! - [`transition`]: its discrete transition and process noise by blocks, and the covariance
//!   propagation that uses them.
//! - [`mechanization`]: one strapdown step from a pair of increments, with coning, sculling and
//!   rotation compensation.

pub mod error_model;
pub mod mechanization;
pub mod state;
pub mod transition;
