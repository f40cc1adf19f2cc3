//! A bank's thermal calibration from its records, power-ons and sweeps.

pub mod calibration;
pub mod sweeps;
