//! Strapdown inertial navigation in the local-level NED frame.
//!
//! - [`state`]: the navigation state (position, velocity, attitude) and IMU increments.
//! - [`mechanization`]: one strapdown step from a pair of increments, with coning, sculling and
//!   rotation compensation.

pub mod mechanization;
pub mod state;
