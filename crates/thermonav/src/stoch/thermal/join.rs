//! One bank's thermal calibration joined to the noise models of another bank or of a sensor
//! profile (`--thermal-from`): a calibration from sweeps alone has no noise models, and a
//! run needs both. They join only when they speak of the same channels in the same units.

use super::ThermalCalibration;
use crate::imu::Channel;
use std::collections::BTreeMap;

/// Why a thermal calibration cannot join a noise model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ThermalJoinError {
    /// The thermal bank has no calibration.
    #[error("has no thermal calibration")]
    NoCalibration,
    /// The two cover different channels.
    #[error("its thermal calibration covers {thermal} but the noise model covers {noise}")]
    Channels {
        /// The calibration's channels.
        thermal: String,
        /// The noise model's channels.
        noise: String,
    },
    /// A channel is in different units.
    #[error("{channel}: its thermal calibration is in {thermal} but the noise model in {noise}")]
    Unit {
        /// The channel.
        channel: &'static str,
        /// The calibration's unit.
        thermal: String,
        /// The noise model's unit.
        noise: String,
    },
}

/// The unit of each channel of a calibration: that of its bias curve's constant term.
fn calibration_units(thermal: &ThermalCalibration) -> BTreeMap<Channel, String> {
    thermal
        .channels
        .iter()
        .map(|(&c, cal)| {
            let unit = cal.bias.coefficient_units.first().cloned();
            (
                c,
                unit.unwrap_or_else(|| c.si_unit(crate::imu::SampleKind::Rates).into()),
            )
        })
        .collect()
}

fn channel_names<V>(channels: &BTreeMap<Channel, V>) -> String {
    let names: Vec<&str> = channels.keys().map(|c| c.name()).collect();
    names.join(",")
}

/// Checks that `thermal` speaks of the channels of `noise` (channel → unit) in their units.
///
/// # Errors
/// [`ThermalJoinError::Channels`] or [`ThermalJoinError::Unit`].
pub fn check_join(
    noise: &BTreeMap<Channel, String>,
    thermal: &ThermalCalibration,
) -> Result<(), ThermalJoinError> {
    let units = calibration_units(thermal);
    if units.keys().ne(noise.keys()) {
        return Err(ThermalJoinError::Channels {
            thermal: channel_names(&units),
            noise: channel_names(noise),
        });
    }
    for (c, unit) in &units {
        if noise[c] != *unit {
            return Err(ThermalJoinError::Unit {
                channel: c.name(),
                thermal: unit.clone(),
                noise: noise[c].clone(),
            });
        }
    }
    Ok(())
}
