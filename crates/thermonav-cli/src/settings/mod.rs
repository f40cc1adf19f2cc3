//! Settings: the command line resolved once into validated, typed values before any file is
//! read. A command's `resolve` refuses bad usage (exit 2) up front, and refuses an output that
//! would overwrite one of the command's inputs; what is left for the command is to load, run,
//! write and print. A value out of its range is refused by the library's check
//! ([`thermonav::setting`]), whose error becomes a usage error naming the option. Defaults are the library's (`Default` impls and constants), which clap
//! shows in `--help`.

pub mod analysis;
pub mod bank;
pub mod characterization;
pub mod gmwm;
pub mod imu;
pub mod navigation;
pub mod paths;
pub mod plot;
pub mod simulation;

use crate::failure::Failure;
use anyhow::anyhow;
use thermonav::nav::measurement::AntennaGeometry;

/// Three finite numbers, else a usage error naming the option.
pub fn triple(name: &str, values: &[f64]) -> Result<[f64; 3], Failure> {
    match values {
        [x, y, z] if values.iter().all(|c| c.is_finite()) => Ok([*x, *y, *z]),
        _ => Err(Failure::Usage(anyhow!(
            "{name} takes three finite numbers (x,y,z)"
        ))),
    }
}

/// The antenna set-up from `--lever-arm-m` and `--baseline`.
pub fn antenna_geometry(lever_arm_m: &[f64], baseline: &[f64]) -> Result<AntennaGeometry, Failure> {
    let baseline = triple("--baseline", baseline)?;
    if baseline[0].hypot(baseline[1]) == 0.0 {
        return Err(Failure::Usage(anyhow!(
            "--baseline must have a horizontal component to define a heading"
        )));
    }
    Ok(AntennaGeometry {
        lever_arm_body_m: triple("--lever-arm-m", lever_arm_m)?,
        baseline_body: baseline,
    })
}
