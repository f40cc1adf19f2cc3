//! Signal conditioning: timestamp checks, Kaiser-window FIR design, zero-phase filtering and
//! decimation (paper step 2: de-noising before stochastic modelling).
//!
//! Wavelet de-noising, the paper's named alternative, belongs here as a sibling module when it
//! comes; it would take the same `&[f64]` in and give the same length out.

pub mod timestamps;
