//! The identity of a simulated unit: what stays the same every time it is switched on.
//!
//! A unit's bias is b(T) = b_unit + c₁ (T − T_ref) + c₂ (T − T_ref)² + b_power-on: its fixed
//! bias b_unit (drawn once per unit, with the profile's `turn_on_bias_sigma`: the data sheet's
//! initial bias, mostly unit to unit) plus its deterministic temperature curve make the
//! *repeatable* curve, the same in every chamber run and every survey of the unit; each
//! power-on adds a smaller offset (`power_on_offset_sigma`), fixed while the unit runs. The
//! fixed bias comes from a generator named after the unit's serial number alone, so a chamber
//! campaign and a survey of the same serial see the same unit whatever their own seeds; each
//! power-on's offset comes from the run's seed and the power-on's name.

use super::errors::standard_normal;
use crate::imu::Channel;
use crate::rng::named_rng;
use crate::sensor::SensorProfile;
use serde::Serialize;
use std::collections::BTreeMap;

/// The serial number of the unit the simulators use unless told otherwise.
pub const DEFAULT_SERIAL: u64 = 1;

/// A simulated unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct SimulatedUnit {
    /// Its serial number (the seed of its fixed bias).
    pub serial: u64,
}

impl Default for SimulatedUnit {
    fn default() -> Self {
        Self {
            serial: DEFAULT_SERIAL,
        }
    }
}

/// The repeatable bias curve of one channel: Σ_k coefficients\[k\] (T − T_ref)^k.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RepeatableCurve {
    /// Unit of the curve (`rad/s` or `m/s^2`).
    pub unit: &'static str,
    /// T_ref, °C.
    pub reference_temperature_c: f64,
    /// b_unit, c₁ (per °C), c₂ (per °C²).
    pub coefficients: [f64; 3],
}

impl RepeatableCurve {
    /// The curve's value at `temperature_c`, channel unit.
    pub fn value_at(&self, temperature_c: f64) -> f64 {
        let d = temperature_c - self.reference_temperature_c;
        let [b, c1, c2] = self.coefficients;
        b + (c1 + c2 * d) * d
    }
}

impl SimulatedUnit {
    /// The unit's fixed bias of `channel`, channel unit (0 for a channel the profile lacks).
    pub fn fixed_bias(&self, profile: &SensorProfile, channel: Channel) -> f64 {
        let sigma = profile
            .channel(channel)
            .map_or(0.0, |p| p.turn_on_bias_sigma);
        let name = format!("unit/{}/fixed-bias", channel.name());
        sigma * standard_normal(&mut named_rng(self.serial, &name))
    }

    /// The offset that power-on `power_on` (a name unique within the run of `seed`) adds to
    /// `channel`, channel unit.
    pub fn power_on_offset(
        &self,
        profile: &SensorProfile,
        channel: Channel,
        seed: u64,
        power_on: &str,
    ) -> f64 {
        let sigma = profile
            .channel(channel)
            .map_or(0.0, |p| p.power_on_offset_sigma);
        let name = format!(
            "unit/{}/power-on/{power_on}/{}",
            self.serial,
            channel.name()
        );
        sigma * standard_normal(&mut named_rng(seed, &name))
    }

    /// The repeatable curve of every channel.
    pub fn repeatable_curves(&self, profile: &SensorProfile) -> BTreeMap<Channel, RepeatableCurve> {
        Channel::ALL
            .iter()
            .filter_map(|&channel| {
                let p = profile.channel(channel)?;
                let curve = RepeatableCurve {
                    unit: channel.si_unit(crate::imu::SampleKind::Rates),
                    reference_temperature_c: profile.reference_temperature_c,
                    coefficients: [
                        self.fixed_bias(profile, channel),
                        p.bias_temperature_coefficient_per_c,
                        p.bias_temperature_quadratic_per_c2,
                    ],
                };
                Some((channel, curve))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensor::adis16364_like;

    #[test]
    fn a_unit_keeps_its_fixed_bias_and_power_ons_differ() {
        let profile = adis16364_like();
        let unit = SimulatedUnit { serial: 7 };
        assert_eq!(
            unit.fixed_bias(&profile, Channel::Gx),
            SimulatedUnit { serial: 7 }.fixed_bias(&profile, Channel::Gx)
        );
        assert_ne!(
            unit.fixed_bias(&profile, Channel::Gx),
            SimulatedUnit { serial: 8 }.fixed_bias(&profile, Channel::Gx)
        );
        let a = unit.power_on_offset(&profile, Channel::Ax, 3, "1");
        let b = unit.power_on_offset(&profile, Channel::Ax, 3, "2");
        assert_ne!(a, b);
        assert_eq!(a, unit.power_on_offset(&profile, Channel::Ax, 3, "1"));
    }

    #[test]
    fn the_curve_is_the_fixed_bias_plus_the_profile_polynomial() {
        // Closed form: b_unit + c₁ d + c₂ d² at d = T − T_ref.
        let profile = adis16364_like();
        let unit = SimulatedUnit::default();
        let curves = unit.repeatable_curves(&profile);
        let p = profile.channel(Channel::Gy).unwrap();
        let d = 60.0 - profile.reference_temperature_c;
        let expected = unit.fixed_bias(&profile, Channel::Gy)
            + p.bias_temperature_coefficient_per_c * d
            + p.bias_temperature_quadratic_per_c2 * d * d;
        let got = curves[&Channel::Gy].value_at(60.0);
        assert!((got - expected).abs() < 1e-15, "{got} vs {expected}");
    }
}
