//! What the story examples share: the simulated thermal-chamber campaign, its model bank, and
//! the data-sheet units the figures are printed in. Each example uses part of it.
#![allow(dead_code)]

use thermonav::imu::{Channel, Sensor};
pub use thermonav::sensor::SensorProfile;
use thermonav::sensor::adis16364_like;
use thermonav::sim::chamber::{
    ChamberError, ChamberRecord, ChamberRun, ChamberWander, calgary, simulate_chamber_run,
};
use thermonav::sim::clock::SampleClock;
use thermonav::stoch::bank::ModelBank;
use thermonav::stoch::characterize::{CharacterizeSettings, characterize};
use thermonav::units::{
    arw_rad_per_sqrt_s_to_deg_per_sqrt_h, m_per_s2_to_mg, rad_per_s_to_deg_per_h,
    vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h,
};

/// Chamber set points, °C (the paper's six).
pub const TEMPERATURES_C: [f64; 6] = [-40.0, -20.0, 0.0, 20.0, 40.0, 60.0];
/// Length of each static record, s.
pub const RECORD_S: f64 = 3600.0;
/// Sampling rate of the records, Hz.
pub const RATE_HZ: f64 = 10.0;
/// Standard deviation of the logger's timing jitter, s.
pub const JITTER_S: f64 = 50e-6;
/// Probability that a sample is dropped.
pub const DROP_PROBABILITY: f64 = 0.001;
/// The one seed every simulated draw follows from.
pub const SEED: u64 = 7;

/// The simulated sensor: the built-in ADIS16364-like profile (data-sheet noise, bias
/// correlation times that change with temperature).
pub fn sensor() -> SensorProfile {
    adis16364_like()
}

/// One static record per set point, level, x north, at the paper's Calgary site.
pub fn campaign(profile: &SensorProfile) -> Result<Vec<ChamberRecord>, ChamberError> {
    let clock = SampleClock::new(RATE_HZ, JITTER_S, DROP_PROBABILITY)?;
    TEMPERATURES_C
        .iter()
        .map(|&set_point_c| {
            let run = ChamberRun {
                temperature: thermonav::sim::chamber::ChamberTemperature::SetPoint {
                    temperature_c: set_point_c,
                },
                unit: thermonav::sim::unit::SimulatedUnit::default(),
                power_on: 1,
                duration_s: RECORD_S,
                clock,
                site: calgary(),
                wander: ChamberWander {
                    sigma_c: 0.05,
                    correlation_time_s: 600.0,
                },
                seed: SEED,
            };
            simulate_chamber_run(profile, &run)
        })
        .collect()
}

/// The campaign characterised with the default settings into a bank.
pub fn bank(profile: &SensorProfile) -> Result<ModelBank, Box<dyn std::error::Error>> {
    let settings = CharacterizeSettings::default();
    let mut entries = Vec::new();
    for record in campaign(profile)? {
        let t = record.truth.temperature_c;
        let (entry, _) = characterize(&record.series, t, &format!("chamber {t} °C"), &settings)?;
        entries.push(entry);
    }
    Ok(ModelBank::new(entries)?)
}

/// A bias or a bias-like value (σ, bias instability) of `channel` in data-sheet units: deg/h
/// for gyros, mg for accelerometers.
pub fn bias(channel: Channel, si: f64) -> f64 {
    match channel.sensor() {
        Sensor::Gyro => rad_per_s_to_deg_per_h(si),
        Sensor::Accelerometer => m_per_s2_to_mg(si),
    }
}

/// The unit of [`bias`].
pub fn bias_unit(channel: Channel) -> &'static str {
    match channel.sensor() {
        Sensor::Gyro => "deg/h",
        Sensor::Accelerometer => "mg",
    }
}

/// A white-noise density of `channel` in data-sheet units: angle random walk in deg/√h,
/// velocity random walk in m/s/√h.
pub fn density(channel: Channel, si: f64) -> f64 {
    match channel.sensor() {
        Sensor::Gyro => arw_rad_per_sqrt_s_to_deg_per_sqrt_h(si),
        Sensor::Accelerometer => vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h(si),
    }
}

/// The unit of [`density`].
pub fn density_unit(channel: Channel) -> &'static str {
    match channel.sensor() {
        Sensor::Gyro => "deg/√h",
        Sensor::Accelerometer => "m/s/√h",
    }
}
