//! The thermal calibration of a model bank: its own records are the first power-on, a level
//! unit's az reads −g on top of its bias, and a calibration without any channel is none.

use super::{
    FitSettings, PowerOnRecord, RecordMean, ThermalCalibration, ThermalError, calibrate,
    merge_records, power_on_records, without_signal,
};
use crate::imu::Channel;
use crate::stoch::bank::ModelBank;
use std::collections::BTreeMap;

/// Latitude of the chamber site assumed unless given, degrees: 45°, at
/// [`DEFAULT_SITE_HEIGHT_M`]. Gravity there is within 0.5 mg of that at 38-52° and 0 to 1 km
/// would add 0.3 mg per 100 m: an error in the site moves only az's constant, which the
/// filter's bias state takes up.
pub const DEFAULT_SITE_LATITUDE_DEG: f64 = 45.0;

/// Height of the default chamber site above the ellipsoid, m (sea level).
pub const DEFAULT_SITE_HEIGHT_M: f64 = 0.0;

/// Per channel, the observations of the bank's own records, as power-on 1: the mean of each
/// entry's record (entries without one are left out).
pub fn bank_power_on(bank: &ModelBank) -> BTreeMap<Channel, Vec<PowerOnRecord>> {
    let means: Vec<RecordMean> = (bank.entries.iter())
        .filter_map(|e| e.record_mean.clone())
        .collect();
    power_on_records(1, &means)
}

/// The calibration of a level unit from the observations of its power-ons (`parts`, merged):
/// az's reading of −`gravity_m_s2` is taken off first and kept as the calibration's
/// `removed_signal`; `None` when no channel has observations.
///
/// # Errors
/// The first channel's [`ThermalError`] from [`calibrate`].
pub fn calibrate_level_unit(
    parts: Vec<BTreeMap<Channel, Vec<PowerOnRecord>>>,
    gravity_m_s2: f64,
) -> Result<Option<ThermalCalibration>, ThermalError> {
    let signal = BTreeMap::from([(Channel::Az, -gravity_m_s2)]);
    let observations = without_signal(merge_records(parts), &signal);
    let mut calibration = calibrate(&observations, FitSettings::default())?;
    if calibration.channels.is_empty() {
        return Ok(None);
    }
    calibration.removed_signal = signal;
    Ok(Some(calibration))
}
