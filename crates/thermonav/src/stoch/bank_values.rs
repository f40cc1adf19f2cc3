//! The values of a bank entry checked against what they can be: a bank is read from a file
//! that a person may have edited, and a negative σ or a zero sampling interval would reach the
//! filter as a wrong model (or a NaN) rather than as an error naming the value.

use super::bank::{
    AllanSummary, ArSummary, BankError, ChannelModel, GaussMarkovEstimate, GaussMarkovSource,
    Preprocessing, TemperatureEntry,
};
use crate::imu::Channel;

/// What a bank value must be.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ValueRule {
    /// Finite and strictly positive.
    Positive,
    /// Finite and not negative.
    NonNegative,
    /// Finite.
    Finite,
}

impl ValueRule {
    /// True when `value` obeys the rule.
    pub fn admits(self, value: f64) -> bool {
        match self {
            Self::Positive => value.is_finite() && value > 0.0,
            Self::NonNegative => value.is_finite() && value >= 0.0,
            Self::Finite => value.is_finite(),
        }
    }

    /// The rule in words.
    pub fn words(self) -> &'static str {
        match self {
            Self::Positive => "a finite number > 0",
            Self::NonNegative => "a finite number >= 0",
            Self::Finite => "a finite number",
        }
    }
}

/// Where in an entry a value is: the entry's temperature and, for a channel's value, the
/// channel.
#[derive(Debug, Clone, Copy)]
struct Place {
    temperature_c: f64,
    channel: Option<Channel>,
}

impl Place {
    /// `value` of `field` checked against `rule`.
    fn check(self, field: &str, value: f64, rule: ValueRule) -> Result<(), BankError> {
        match rule.admits(value) {
            true => Ok(()),
            false => Err(self.error(field, value, rule.words())),
        }
    }

    fn error(self, field: &str, value: f64, expected: &'static str) -> BankError {
        BankError::Value {
            temperature_c: self.temperature_c,
            channel: self.channel.map_or("-", Channel::name),
            field: field.to_string(),
            value,
            expected,
        }
    }

    /// Every value of `values` checked against `rule`.
    fn check_all(self, field: &str, values: &[f64], rule: ValueRule) -> Result<(), BankError> {
        values.iter().try_for_each(|&v| self.check(field, v, rule))
    }
}

impl TemperatureEntry {
    /// Checks every value of the entry: rates, intervals, variances, σ and correlation times
    /// positive; noise terms not negative; coefficients finite; the Allan curve's two columns
    /// of one length.
    ///
    /// # Errors
    /// [`BankError::Value`] naming the first value that is not what it must be.
    pub fn check_values(&self) -> Result<(), BankError> {
        let entry = Place {
            temperature_c: self.temperature_c,
            channel: None,
        };
        check_preprocessing(entry, &self.preprocessing)?;
        self.channels.iter().try_for_each(|(&channel, model)| {
            let place = Place {
                channel: Some(channel),
                ..entry
            };
            check_channel(place, model)
        })
    }
}

fn check_preprocessing(place: Place, p: &Preprocessing) -> Result<(), BankError> {
    place.check(
        "preprocessing.input_rate_hz",
        p.input_rate_hz,
        ValueRule::Positive,
    )?;
    place.check(
        "preprocessing.modelling_rate_hz",
        p.modelling_rate_hz,
        ValueRule::Positive,
    )?;
    place.check(
        "preprocessing.decimation_factor",
        p.decimation_factor as f64,
        ValueRule::Positive,
    )
}

fn check_channel(place: Place, model: &ChannelModel) -> Result<(), BankError> {
    check_allan(place, &model.allan)?;
    check_ar(place, &model.ar)?;
    // Every family the entry holds: the three every bank has and the optional ones (gmwm),
    // whose values reach a run as surely (`--model gmwm`).
    GaussMarkovSource::all()
        .filter_map(|s| Some((s, model.gauss_markov.estimate(s)?)))
        .try_for_each(|(s, estimate)| {
            let field = format!("gauss_markov.{}", s.name());
            let sigma = match s.sigma_may_be_zero() {
                true => ValueRule::NonNegative,
                false => ValueRule::Positive,
            };
            check_gauss_markov(place, &field, estimate, sigma)
        })
}

fn check_allan(place: Place, allan: &AllanSummary) -> Result<(), BankError> {
    place.check_all("allan.tau_s", &allan.tau_s, ValueRule::Positive)?;
    place.check_all("allan.adev", &allan.adev, ValueRule::NonNegative)?;
    if allan.adev.len() != allan.tau_s.len() {
        let length = allan.adev.len() as f64;
        return Err(place.error(
            "allan.adev (its length)",
            length,
            "as many values as allan.tau_s",
        ));
    }
    let terms = [
        ("allan.white_noise_density", allan.white_noise_density),
        ("allan.bias_instability", allan.bias_instability),
        ("allan.rate_random_walk", allan.rate_random_walk),
        (
            "allan.bias_instability_at_most",
            allan.bias_instability_at_most,
        ),
    ];
    terms
        .into_iter()
        .filter_map(|(field, value)| value.map(|v| (field, v)))
        .try_for_each(|(field, v)| place.check(field, v, ValueRule::NonNegative))?;
    let range = allan.white_noise_tau_range_s.unwrap_or([1.0, 1.0]);
    place.check_all("allan.white_noise_tau_range_s", &range, ValueRule::Positive)
}

fn check_ar(place: Place, ar: &ArSummary) -> Result<(), BankError> {
    place.check_all("ar.coefficients", &ar.coefficients, ValueRule::Finite)?;
    place.check("ar.noise_variance", ar.noise_variance, ValueRule::Positive)?;
    place.check("ar.dt_s", ar.dt_s, ValueRule::Positive)
}

fn check_gauss_markov(
    place: Place,
    field: &str,
    estimate: &GaussMarkovEstimate,
    sigma_rule: ValueRule,
) -> Result<(), BankError> {
    let GaussMarkovEstimate::Model {
        correlation_time_s,
        sigma,
        ci95_correlation_time_s,
    } = estimate
    else {
        return Ok(());
    };
    let tc = format!("{field}.correlation_time_s");
    place.check(&tc, *correlation_time_s, ValueRule::Positive)?;
    place.check(&format!("{field}.sigma"), *sigma, sigma_rule)?;
    let bounds: Vec<f64> = ci95_correlation_time_s.iter().flatten().copied().collect();
    place.check_all(
        &format!("{field}.ci95_correlation_time_s"),
        &bounds,
        ValueRule::Positive,
    )
}
