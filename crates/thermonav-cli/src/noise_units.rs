//! IEEE 952 noise terms in the units navigation engineers quote, next to SI.

use serde::Serialize;
use thermonav::imu::Sensor;
use thermonav::stoch::noise_terms::{NoiseTerms, Term};
use thermonav::units::{SECONDS_PER_HOUR, m_per_s2_to_mg, rad_per_s_to_deg_per_h, rad_to_deg};

/// A term with its SI value, its edge-unit value and the τ range it was read over.
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
}

/// The five terms; absent ones are `null`.
#[derive(Debug, Serialize)]
pub struct TermsJson {
    quantization: Option<TermJson>,
    random_walk: Option<TermJson>,
    bias_instability: Option<TermJson>,
    rate_random_walk: Option<TermJson>,
    rate_ramp: Option<TermJson>,
}

fn term(
    t: Option<Term>,
    unit_si: &'static str,
    unit: &'static str,
    to_edge: impl Fn(f64) -> f64,
) -> Option<TermJson> {
    t.map(|t| TermJson {
        value_si: t.value,
        unit_si,
        value: to_edge(t.value),
        unit,
        tau_min_s: t.tau_min_s,
        tau_max_s: t.tau_max_s,
    })
}

/// Converts terms of a gyro or accelerometer channel.
pub fn terms_json(terms: &NoiseTerms, sensor: Sensor) -> TermsJson {
    let sqrt_h = SECONDS_PER_HOUR.sqrt();
    match sensor {
        Sensor::Gyro => TermsJson {
            quantization: term(terms.quantization, "rad", "deg", rad_to_deg),
            random_walk: term(terms.random_walk, "rad/sqrt(s)", "deg/sqrt(h)", |v| {
                rad_to_deg(v) * sqrt_h
            }),
            bias_instability: term(
                terms.bias_instability,
                "rad/s",
                "deg/h",
                rad_per_s_to_deg_per_h,
            ),
            rate_random_walk: term(
                terms.rate_random_walk,
                "rad/s/sqrt(s)",
                "deg/h/sqrt(h)",
                |v| rad_per_s_to_deg_per_h(v) * sqrt_h,
            ),
            rate_ramp: term(terms.rate_ramp, "rad/s^2", "deg/h^2", |v| {
                rad_per_s_to_deg_per_h(v) * SECONDS_PER_HOUR
            }),
        },
        Sensor::Accelerometer => TermsJson {
            quantization: term(terms.quantization, "m/s", "m/s", |v| v),
            random_walk: term(terms.random_walk, "m/s/sqrt(s)", "m/s/sqrt(h)", |v| {
                v * sqrt_h
            }),
            bias_instability: term(terms.bias_instability, "m/s^2", "mg", m_per_s2_to_mg),
            rate_random_walk: term(
                terms.rate_random_walk,
                "m/s^2/sqrt(s)",
                "m/s^2/sqrt(h)",
                |v| v * sqrt_h,
            ),
            rate_ramp: term(terms.rate_ramp, "m/s^3", "m/s^2/h", |v| {
                v * SECONDS_PER_HOUR
            }),
        },
    }
}

/// One line summary: "ARW 2.01 deg/sqrt(h), BI 24.3 deg/h, RRW n/a".
pub fn terms_line(t: &TermsJson) -> String {
    let show = |name: &str, t: &Option<TermJson>| {
        t.as_ref().map_or(format!("{name} n/a"), |t| {
            format!("{name} {:.4} {}", t.value, t.unit)
        })
    };
    [
        show("N", &t.random_walk),
        show("B", &t.bias_instability),
        show("K", &t.rate_random_walk),
        show("Q", &t.quantization),
    ]
    .join(", ")
}
