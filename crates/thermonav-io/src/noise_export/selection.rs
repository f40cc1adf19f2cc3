//! The bank's noise quantities at one operating temperature, SI, per channel: what every
//! export reads.
//!
//! [`Selection::Nearest`] takes the entry nearest the temperature (ties to the colder one, as
//! [`ModelBank::select`]); [`Selection::Linear`] interpolates each quantity linearly in
//! temperature between the two bracketing entries (a quantity absent from either is absent).
//! Unlike `bank show`, a temperature outside the bank's range is refused for both: a filter
//! configuration written for 80 °C from a bank that ends at 40 °C would carry the 40 °C values
//! under the 80 °C name.

use super::NoiseExportError;
use std::collections::BTreeMap;
use thermonav::imu::{Channel, Sensor};
use thermonav::nav::sensor_model::GaussMarkovParameters;
use thermonav::stoch::bank::{
    BankError, GaussMarkovSource, ModelBank, Placement, Selection, TemperatureEntry,
    check_operating_temperature,
};
use thermonav::stoch::noise_terms::BIAS_INSTABILITY_FACTOR;

/// A noise quantity of a channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Term {
    /// White-noise density N (ARW rad/√s, VRW m/s/√s) from the Allan curve.
    WhiteNoiseDensity,
    /// Bias instability B (rad/s, m/s²) from the Allan curve.
    BiasInstability,
    /// Rate random walk K (rad/s/√s, m/s²/√s) from the Allan curve.
    RateRandomWalk,
    /// The largest K the Allan curve allows: the K whose σ(τ) = K √(τ/3) meets the curve's
    /// last point.
    RateRandomWalkAtMost,
    /// The first-order Gauss-Markov bias model (σ and Tc) of the chosen family.
    GaussMarkov,
}

impl Term {
    /// Its key in the bank (`absent_terms`, `gauss_markov`).
    pub fn key(self) -> &'static str {
        match self {
            Term::WhiteNoiseDensity => "white_noise_density",
            Term::BiasInstability => "bias_instability",
            Term::RateRandomWalk => "rate_random_walk",
            Term::RateRandomWalkAtMost => "rate_random_walk_at_most",
            Term::GaussMarkov => "gauss_markov",
        }
    }

    /// Its name in words.
    pub fn words(self) -> &'static str {
        match self {
            Term::WhiteNoiseDensity => "white-noise density N (ARW/VRW)",
            Term::BiasInstability => "bias instability B",
            Term::RateRandomWalk => "rate random walk K",
            Term::RateRandomWalkAtMost => "upper bound on the rate random walk K",
            Term::GaussMarkov => "Gauss-Markov bias model (sigma, Tc)",
        }
    }
}

/// One channel's quantities at the operating temperature, SI; absent ones with the reason.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ChannelNoise {
    /// N, rad/√s or m/s/√s.
    pub white_noise_density: Option<f64>,
    /// B, rad/s or m/s².
    pub bias_instability: Option<f64>,
    /// K, rad/s/√s or m/s²/√s.
    pub rate_random_walk: Option<f64>,
    /// The largest K the curve allows ([`Term::RateRandomWalkAtMost`]), same unit.
    pub rate_random_walk_at_most: Option<f64>,
    /// The Gauss-Markov model of the chosen family.
    pub gauss_markov: Option<GaussMarkovParameters>,
    /// The first-order Gauss-Markov model that reproduces the Allan minimum, for the formats
    /// that need a Gauss-Markov bias when the bank has none ([`AllanStandIn`]).
    pub allan_stand_in: Option<AllanStandIn>,
    /// Why a quantity is absent.
    pub absent: BTreeMap<Term, String>,
}

/// A first-order Gauss-Markov bias standing in for one the bank does not have (its part was
/// not significant): σ = B = the minimum Allan deviation / 0.664 and Tc = the τ of that
/// minimum; where the curve has no minimum inside it (it falls to its end), σ = the bound on B
/// at its longest τ (σ(τ)/0.664) and Tc = that τ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AllanStandIn {
    /// The stand-in (σ in the channel's SI unit).
    pub model: GaussMarkovParameters,
    /// Whether it is read at a minimum inside the curve (else at its longest τ).
    pub at_minimum: bool,
}

impl AllanStandIn {
    /// The stand-in of an Allan curve, `None` for a curve that is zero or empty.
    pub fn of_curve(tau_s: &[f64], adev: &[f64]) -> Option<Self> {
        let positive = adev.iter().enumerate().filter(|(_, sigma)| **sigma > 0.0);
        let (i, _) = positive.min_by(|a, b| a.1.total_cmp(b.1))?;
        let last = adev.len().min(tau_s.len()).checked_sub(1)?;
        let at_minimum = i > 0 && i < last;
        let k = if at_minimum { i } else { last };
        let model = GaussMarkovParameters {
            correlation_time_s: tau_s[k],
            sigma: adev[k] / BIAS_INSTABILITY_FACTOR,
        };
        Some(Self { model, at_minimum })
    }

    /// Interpolated with `weight` on `upper`.
    fn between(lower: Option<Self>, upper: Option<Self>, weight: f64) -> Option<Self> {
        let (a, b) = (lower?, upper?);
        let lerp = |x: f64, y: f64| x + (y - x) * weight;
        let model = GaussMarkovParameters {
            correlation_time_s: lerp(a.model.correlation_time_s, b.model.correlation_time_s),
            sigma: lerp(a.model.sigma, b.model.sigma),
        };
        let at_minimum = a.at_minimum && b.at_minimum;
        Some(Self { model, at_minimum })
    }
}

/// The bank's noise at one temperature: the six channels and the record's rate.
#[derive(Debug, Clone, PartialEq)]
pub struct ImuNoise {
    /// The operating temperature asked for, °C.
    pub temperature_c: f64,
    /// Which entries the values come from.
    pub placement: Placement,
    /// The Gauss-Markov family used.
    pub source: GaussMarkovSource,
    /// Nominal sampling rate of the raw record (of the entry nearest the temperature), Hz.
    pub sample_rate_hz: f64,
    /// Per channel.
    pub channels: BTreeMap<Channel, ChannelNoise>,
}

impl ImuNoise {
    /// The bank's noise at `temperature_c` (or at its only entry when `None`).
    ///
    /// # Errors
    /// [`NoiseExportError`] when the temperature is missing (several entries), not finite or
    /// outside the bank's range, or the bank's layout is invalid.
    pub fn at_temperature(
        bank: &ModelBank,
        temperature_c: Option<f64>,
        selection: Selection,
        source: GaussMarkovSource,
    ) -> Result<Self, NoiseExportError> {
        bank.check_layout()?;
        let temperature_c = operating_temperature_c(bank, temperature_c, selection)?;
        let placement = bank.placement(temperature_c, selection);
        let nearest = &bank.entries[bank.nearest_index(temperature_c)];
        let channels = Channel::ALL
            .iter()
            .map(|&c| {
                Ok((
                    c,
                    channel_noise(bank, (temperature_c, selection), c, source)?,
                ))
            })
            .collect::<Result<_, NoiseExportError>>()?;
        Ok(Self {
            temperature_c,
            placement,
            source,
            sample_rate_hz: nearest.preprocessing.input_rate_hz,
            channels,
        })
    }

    /// The value of `term` for `channel` (σ for [`Term::GaussMarkov`]), or an error naming
    /// what is missing and why.
    ///
    /// # Errors
    /// [`NoiseExportError::MissingTerm`].
    pub fn require(&self, channel: Channel, term: Term) -> Result<f64, NoiseExportError> {
        let noise = &self.channels[&channel];
        let value = match term {
            Term::WhiteNoiseDensity => noise.white_noise_density,
            Term::BiasInstability => noise.bias_instability,
            Term::RateRandomWalk => noise.rate_random_walk,
            Term::RateRandomWalkAtMost => noise.rate_random_walk_at_most,
            Term::GaussMarkov => noise.gauss_markov.map(|gm| gm.sigma),
        };
        value.ok_or_else(|| self.missing(channel, term))
    }

    /// The Gauss-Markov model of `channel`.
    ///
    /// # Errors
    /// [`NoiseExportError::MissingTerm`].
    pub fn gauss_markov(
        &self,
        channel: Channel,
    ) -> Result<GaussMarkovParameters, NoiseExportError> {
        self.channels[&channel]
            .gauss_markov
            .ok_or_else(|| self.missing(channel, Term::GaussMarkov))
    }

    /// The Gauss-Markov model of `channel`, or where the bank has none its Allan stand-in
    /// ([`AllanStandIn`], returned beside it).
    ///
    /// # Errors
    /// [`NoiseExportError::MissingTerm`] when there is neither.
    pub fn bias_model(
        &self,
        channel: Channel,
    ) -> Result<(GaussMarkovParameters, Option<AllanStandIn>), NoiseExportError> {
        let noise = &self.channels[&channel];
        match (noise.gauss_markov, noise.allan_stand_in) {
            (Some(model), _) => Ok((model, None)),
            (None, Some(stand_in)) => Ok((stand_in.model, Some(stand_in))),
            (None, None) => Err(self.missing(channel, Term::GaussMarkov)),
        }
    }

    /// [`ImuNoise::bias_model`] of the three axes of `sensor`, without the stand-in flags.
    ///
    /// # Errors
    /// As [`ImuNoise::bias_model`].
    pub fn bias_model_axes(
        &self,
        sensor: Sensor,
    ) -> Result<[GaussMarkovParameters; 3], NoiseExportError> {
        let [x, y, z] = sensor_channels(sensor);
        Ok([
            self.bias_model(x)?.0,
            self.bias_model(y)?.0,
            self.bias_model(z)?.0,
        ])
    }

    /// `term` of the three axes x, y, z of `sensor`.
    ///
    /// # Errors
    /// As [`ImuNoise::require`].
    pub fn axes(&self, sensor: Sensor, term: Term) -> Result<[f64; 3], NoiseExportError> {
        let [x, y, z] = sensor_channels(sensor);
        Ok([
            self.require(x, term)?,
            self.require(y, term)?,
            self.require(z, term)?,
        ])
    }

    /// The Gauss-Markov models of the three axes of `sensor`.
    ///
    /// # Errors
    /// As [`ImuNoise::gauss_markov`].
    pub fn gauss_markov_axes(
        &self,
        sensor: Sensor,
    ) -> Result<[GaussMarkovParameters; 3], NoiseExportError> {
        let [x, y, z] = sensor_channels(sensor);
        Ok([
            self.gauss_markov(x)?,
            self.gauss_markov(y)?,
            self.gauss_markov(z)?,
        ])
    }

    pub(super) fn missing(&self, channel: Channel, term: Term) -> NoiseExportError {
        let reason = self.channels[&channel].absent.get(&term).cloned();
        NoiseExportError::MissingTerm {
            format: "",
            channel: channel.name(),
            term: term.words(),
            temperature_c: self.temperature_c,
            reason: reason.unwrap_or_else(|| "not in the bank".to_string()),
        }
    }
}

/// gx, gy, gz or ax, ay, az.
pub fn sensor_channels(sensor: Sensor) -> [Channel; 3] {
    match sensor {
        Sensor::Gyro => [Channel::Gx, Channel::Gy, Channel::Gz],
        Sensor::Accelerometer => [Channel::Ax, Channel::Ay, Channel::Az],
    }
}

/// The temperature to export at: the one given, inside the bank's range, or the only entry's.
fn operating_temperature_c(
    bank: &ModelBank,
    temperature_c: Option<f64>,
    selection: Selection,
) -> Result<f64, NoiseExportError> {
    let temps = bank.temperatures_c();
    let (low_c, high_c) = (temps[0], temps[temps.len() - 1]);
    let Some(t) = temperature_c else {
        return match temps.len() {
            1 => Ok(low_c),
            entries => Err(NoiseExportError::NoTemperature {
                entries,
                low_c,
                high_c,
            }),
        };
    };
    check_operating_temperature(t)?;
    if t < low_c || t > high_c {
        let nearest_c = temps[bank.nearest_index(t)];
        return Err(NoiseExportError::OutsideRange {
            temperature_c: t,
            low_c,
            high_c,
            selection,
            nearest_c,
        });
    }
    Ok(t)
}

/// A channel's quantities at a temperature inside the bank's range.
fn channel_noise(
    bank: &ModelBank,
    (temperature_c, selection): (f64, Selection),
    channel: Channel,
    source: GaussMarkovSource,
) -> Result<ChannelNoise, NoiseExportError> {
    let mut noise = match bank.placement(temperature_c, selection) {
        Placement::Entry { temperature_c } | Placement::Clamped { temperature_c } => {
            entry_noise(entry_at(bank, temperature_c), channel, source)?
        }
        Placement::Between {
            lower_c,
            upper_c,
            weight,
        } => {
            let lower = entry_noise(entry_at(bank, lower_c), channel, source)?;
            let upper = entry_noise(entry_at(bank, upper_c), channel, source)?;
            interpolated(&lower, &upper, weight, [lower_c, upper_c])
        }
    };
    match bank.select(temperature_c, channel, source, selection) {
        Ok(m) => {
            noise.gauss_markov = Some(GaussMarkovParameters {
                correlation_time_s: m.correlation_time_s,
                sigma: m.sigma,
            });
        }
        Err(BankError::NoModel { reason, .. }) => {
            noise.absent.insert(Term::GaussMarkov, reason);
        }
        Err(e) => return Err(e.into()),
    }
    Ok(noise)
}

fn entry_at(bank: &ModelBank, temperature_c: f64) -> &TemperatureEntry {
    let k = bank.nearest_index(temperature_c);
    &bank.entries[k]
}

/// The Allan terms of one entry's channel (the Gauss-Markov model is added by the caller);
/// with the GMWM family, the white-noise density is the composite's mapped one, as the filter
/// takes it.
fn entry_noise(
    entry: &TemperatureEntry,
    channel: Channel,
    source: GaussMarkovSource,
) -> Result<ChannelNoise, BankError> {
    let model = entry
        .channels
        .get(&channel)
        .ok_or(BankError::MissingChannel {
            temperature_c: entry.temperature_c,
            channel: channel.name(),
        })?;
    let allan = &model.allan;
    let mut absent = BTreeMap::new();
    for term in [
        Term::WhiteNoiseDensity,
        Term::BiasInstability,
        Term::RateRandomWalk,
    ] {
        let reason = allan.absent_terms.get(term.key());
        let reason = reason.map_or("not identified on the Allan curve", String::as_str);
        absent.insert(
            term,
            format!("{reason} (entry at {} °C)", entry.temperature_c),
        );
    }
    let at_most = largest_rate_random_walk(&allan.tau_s, &allan.adev);
    if at_most.is_none() {
        let reason = format!(
            "the Allan curve is empty (entry at {} °C)",
            entry.temperature_c
        );
        absent.insert(Term::RateRandomWalkAtMost, reason);
    }
    let white_noise_density = model
        .white_noise_density(source)
        .or(allan.white_noise_density);
    let noise = ChannelNoise {
        white_noise_density,
        bias_instability: allan.bias_instability,
        rate_random_walk: allan.rate_random_walk,
        rate_random_walk_at_most: at_most,
        gauss_markov: None,
        allan_stand_in: AllanStandIn::of_curve(&allan.tau_s, &allan.adev),
        absent,
    };
    Ok(without_reasons_of_present(noise))
}

/// K √(τ/3) = σ(τ) at the curve's longest τ: a rate random walk above this would lift the
/// curve above its last point (IEEE Std 952, σ_K(τ) = K √(τ/3)).
fn largest_rate_random_walk(tau_s: &[f64], adev: &[f64]) -> Option<f64> {
    let (&tau, &sigma) = tau_s.last().zip(adev.last())?;
    Some(sigma * (3.0 / tau).sqrt())
}

/// Keeps the reasons of the absent quantities only.
fn without_reasons_of_present(mut noise: ChannelNoise) -> ChannelNoise {
    let present = [
        (Term::WhiteNoiseDensity, noise.white_noise_density.is_some()),
        (Term::BiasInstability, noise.bias_instability.is_some()),
        (Term::RateRandomWalk, noise.rate_random_walk.is_some()),
    ];
    for (term, is_present) in present {
        if is_present {
            noise.absent.remove(&term);
        }
    }
    noise
}

/// Each Allan term interpolated with `weight` on `upper`, absent when either lacks it.
fn interpolated(
    lower: &ChannelNoise,
    upper: &ChannelNoise,
    weight: f64,
    [lower_c, upper_c]: [f64; 2],
) -> ChannelNoise {
    let lerp = |a: Option<f64>, b: Option<f64>| Some(a? + (b? - a?) * weight);
    let mut absent = lower.absent.clone();
    absent.extend(upper.absent.clone());
    for reason in absent.values_mut() {
        *reason =
            format!("{reason}: linear interpolation between {lower_c} and {upper_c} °C needs both");
    }
    ChannelNoise {
        white_noise_density: lerp(lower.white_noise_density, upper.white_noise_density),
        bias_instability: lerp(lower.bias_instability, upper.bias_instability),
        rate_random_walk: lerp(lower.rate_random_walk, upper.rate_random_walk),
        rate_random_walk_at_most: lerp(
            lower.rate_random_walk_at_most,
            upper.rate_random_walk_at_most,
        ),
        gauss_markov: None,
        allan_stand_in: AllanStandIn::between(lower.allan_stand_in, upper.allan_stand_in, weight),
        absent,
    }
}
