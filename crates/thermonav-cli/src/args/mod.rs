//! The command line: clap's argument types, one file per command and `shared.rs` for the
//! types several commands share (every type re-exported here, so `crate::args::X` names it);
//! a command's settings are resolved from them in `crate::settings`.

mod allan;
mod ar;
mod bank;
mod characterize;
mod compensate;
mod convert;
mod demo;
mod evaluate;
mod filter;
mod fir;
mod gmwm;
mod inspect;
mod integrate;
mod lot;
mod plot;
mod report;
mod shared;
mod simulate;

pub use allan::*;
pub use ar::*;
pub use bank::*;
pub use characterize::*;
pub use compensate::*;
pub use convert::*;
pub use demo::*;
pub use evaluate::*;
pub use filter::*;
pub use fir::*;
pub use gmwm::*;
pub use inspect::*;
pub use integrate::*;
pub use lot::*;
pub use plot::*;
pub use report::*;
pub use shared::*;
pub use simulate::*;

use clap::{Parser, Subcommand};

/// Temperature-dependent stochastic modelling of MEMS IMU errors and GNSS/INS filtering.
#[derive(Debug, Parser)]
#[command(name = "thermonav", version, about, long_about = None)]
pub struct Cli {
    /// No progress bars or step messages on stderr (results and errors are still printed).
    #[arg(long, global = true)]
    pub quiet: bool,
    /// The subcommand to run.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run the main job on built-in simulated data and write everything under --out.
    Demo(DemoArgs),
    /// Sanity-check an IMU, GNSS or reference CSV (chosen by its header): rate, jitter, gaps, ordering, NaN/inf, channel statistics.
    Inspect(InspectArgs),
    /// Design a Kaiser-window FIR low-pass filter (SciPy kaiserord + firwin).
    Fir(FirArgs),
    /// Low-pass filter (and optionally decimate) every channel of an IMU CSV.
    Filter(FilterArgs),
    /// Overlapping Allan deviation per channel, confidence limits and IEEE 952 noise terms.
    Allan(AllanArgs),
    /// AR model per channel and its Gauss-Markov equivalent.
    Ar(ArArgs),
    /// Composite noise model per channel fitted to the Haar wavelet variance (GMWM).
    Gmwm(GmwmArgs),
    /// Build the temperature model bank from static records (one per temperature).
    Characterize(CharacterizeArgs),
    /// Read a model bank.
    Bank(BankArgs),
    /// Production lots: summarise the banks that `characterize --manifest` wrote.
    Lot(LotArgs),
    /// Simulate thermal-chamber records, a vessel survey, or write the built-in sensor profile.
    Simulate(SimulateArgs),
    /// GNSS/INS integration (21-state EKF or UKF) with the bank's noise model at a temperature.
    Integrate(IntegrateArgs),
    /// The temperature-model tournament: every bank model through the filter, GNSS outages,
    /// errors against a reference, ranking and its Monte Carlo significance.
    Evaluate(Box<EvaluateArgs>),
    /// Convert a foreign file (RTKLIB .pos, NMEA, KF-GINS, raw IMU + .tag, PX4 ULog, ROS bags,
    /// ArduPilot DataFlash) to a canonical CSV.
    Convert(ConvertArgs),
    /// Build DIR/report.html (one self-contained page) from what demo or evaluate wrote there.
    Report(ReportArgs),
    /// Draw a figure as SVG (or PNG, by the --out extension) from a file thermonav wrote.
    Plot(PlotArgs),
    /// Take a bank's thermal calibration (the bias at each sample's temperature, through the
    /// channel's thermal lag where it has one, and the power-on offset) off every sample of a
    /// record, gravity kept; writes the canonical IMU CSV and OUT.csv.json.
    Compensate(CompensateArgs),
}
