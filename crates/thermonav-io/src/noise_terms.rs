//! IEEE 952 noise terms as JSON documents give them: each term in SI and in the units
//! navigation engineers quote (`allan --json`, the Python package's `noise_terms`).

use serde::Serialize;
use std::collections::BTreeMap;
use thermonav::imu::Sensor;
use thermonav::stoch::noise_terms::{Bound, NoiseTerms, TermReading};
use thermonav::units::{SECONDS_PER_HOUR, m_per_s2_to_mg, rad_per_s_to_deg_per_h, rad_to_deg};

/// A term with its SI value, its edge-unit value, the τ range it was read over and its
/// confidence interval (both units; `null` when the limits gave none).
#[derive(Debug, Serialize)]
pub struct TermJson {
    /// SI value.
    pub value_si: f64,
    /// SI unit.
    pub unit_si: &'static str,
    /// Value in the edge unit.
    pub value: f64,
    /// Edge unit.
    pub unit: &'static str,
    /// τ range used, s.
    pub tau_min_s: f64,
    /// τ range used, s.
    pub tau_max_s: f64,
    /// Points of the curve used.
    pub points: usize,
    /// `estimate`, or `at_most` for an upper bound.
    pub bound: Bound,
    /// Lower confidence limit, SI.
    pub ci_low_si: Option<f64>,
    /// Upper confidence limit, SI.
    pub ci_high_si: Option<f64>,
    /// Lower confidence limit, edge unit.
    pub ci_low: Option<f64>,
    /// Upper confidence limit, edge unit.
    pub ci_high: Option<f64>,
}

/// The five terms; absent ones are `null`, with their reason in `absent`.
#[derive(Debug, Serialize)]
pub struct TermsJson {
    /// Quantisation noise Q.
    pub quantization: Option<TermJson>,
    /// Angle or velocity random walk N.
    pub random_walk: Option<TermJson>,
    /// Bias instability B.
    pub bias_instability: Option<TermJson>,
    /// Rate random walk K.
    pub rate_random_walk: Option<TermJson>,
    /// Rate ramp R.
    pub rate_ramp: Option<TermJson>,
    /// Term key → why the curve does not support it.
    pub absent: BTreeMap<&'static str, String>,
}

/// A term's units: SI, edge, and the conversion between them.
pub type Units = (&'static str, &'static str, fn(f64) -> f64);

/// The units of Q, N, B, K and R of a sensor's channel, in that order (SI, edge, conversion):
/// deg, deg/sqrt(h), deg/h, deg/h/sqrt(h), deg/h^2 for a gyro; m/s, m/s/sqrt(h), mg,
/// m/s^2/sqrt(h), m/s^2/h for an accelerometer.
pub fn term_units(sensor: Sensor) -> [Units; 5] {
    match sensor {
        Sensor::Gyro => gyro_units(),
        Sensor::Accelerometer => accelerometer_units(),
    }
}

fn term(t: &TermReading, (unit_si, unit, to_edge): Units) -> Option<TermJson> {
    t.as_ref().ok().map(|t| TermJson {
        value_si: t.value,
        unit_si,
        value: to_edge(t.value),
        unit,
        tau_min_s: t.tau_min_s,
        tau_max_s: t.tau_max_s,
        points: t.points,
        bound: t.bound,
        ci_low_si: t.ci.map(|c| c.low),
        ci_high_si: t.ci.map(|c| c.high),
        ci_low: t.ci.map(|c| to_edge(c.low)),
        ci_high: t.ci.map(|c| to_edge(c.high)),
    })
}

/// Units of Q, N, B, K and R of a gyro.
fn gyro_units() -> [Units; 5] {
    [
        ("rad", "deg", rad_to_deg),
        ("rad/sqrt(s)", "deg/sqrt(h)", |v| {
            rad_to_deg(v) * SECONDS_PER_HOUR.sqrt()
        }),
        ("rad/s", "deg/h", rad_per_s_to_deg_per_h),
        ("rad/s/sqrt(s)", "deg/h/sqrt(h)", |v| {
            rad_per_s_to_deg_per_h(v) * SECONDS_PER_HOUR.sqrt()
        }),
        ("rad/s^2", "deg/h^2", |v| {
            rad_per_s_to_deg_per_h(v) * SECONDS_PER_HOUR
        }),
    ]
}

/// Units of Q, N, B, K and R of an accelerometer.
fn accelerometer_units() -> [Units; 5] {
    [
        ("m/s", "m/s", |v| v),
        ("m/s/sqrt(s)", "m/s/sqrt(h)", |v| {
            v * SECONDS_PER_HOUR.sqrt()
        }),
        ("m/s^2", "mg", m_per_s2_to_mg),
        ("m/s^2/sqrt(s)", "m/s^2/sqrt(h)", |v| {
            v * SECONDS_PER_HOUR.sqrt()
        }),
        ("m/s^3", "m/s^2/h", |v| v * SECONDS_PER_HOUR),
    ]
}

/// Converts terms of a gyro or accelerometer channel.
pub fn terms_json(terms: &NoiseTerms, sensor: Sensor) -> TermsJson {
    let [q, n, b, k, r] = term_units(sensor);
    TermsJson {
        quantization: term(&terms.quantization, q),
        random_walk: term(&terms.random_walk, n),
        bias_instability: term(&terms.bias_instability, b),
        rate_random_walk: term(&terms.rate_random_walk, k),
        rate_ramp: term(&terms.rate_ramp, r),
        absent: absent_reasons(terms),
    }
}

/// Term key → why the curve does not support it.
fn absent_reasons(terms: &NoiseTerms) -> BTreeMap<&'static str, String> {
    let named = [
        ("quantization", &terms.quantization),
        ("random_walk", &terms.random_walk),
        ("bias_instability", &terms.bias_instability),
        ("rate_random_walk", &terms.rate_random_walk),
        ("rate_ramp", &terms.rate_ramp),
    ];
    let reason = |(name, t): (&'static str, &TermReading)| {
        t.as_ref().err().map(|a| (name, a.reason.clone()))
    };
    named.into_iter().filter_map(reason).collect()
}
