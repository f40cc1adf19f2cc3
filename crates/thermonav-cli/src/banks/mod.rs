//! Banks: built from static records (whole or streamed), read back as a run's noise model,
//! printed as tables, and production lots.

pub mod building;
pub mod loaded_noise;
pub mod noise_units;
pub mod production_lot;
pub mod streaming;
pub mod tables;
