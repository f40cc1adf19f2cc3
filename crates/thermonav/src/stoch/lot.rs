//! Production lots: how the models of many units of one sensor type spread, and which units
//! stand apart.
//!
//! Each unit has its own [`ModelBank`]. The entries of all units are matched by temperature
//! into lot temperature points: sorted by temperature, an entry joins the current point when
//! it lies within [`POINT_TOLERANCE_C`] of the previous entry, and starts a new point otherwise
//! (chamber set points are several degrees apart, a unit's record wanders by a fraction of a
//! degree). Per point, channel and quantity (each Gauss-Markov family's correlation time and
//! σ, the Allan white-noise density, bias instability and rate random walk) the summary gives
//! the median, minimum, maximum and median absolute deviation (MAD) across the units that have
//! a value.
//!
//! Outlier rule: a unit's value is an outlier when it lies more than [`OUTLIER_SCALED_MADS`]
//! scaled MADs from the median, the scaled MAD being [`MAD_TO_SIGMA`] × MAD (a consistent
//! estimate of the standard deviation for normal data; Rousseeuw & Croux 1993). When the MAD
//! is zero (fewer than three distinct values) no unit is flagged.

use crate::imu::{Channel, Sensor};
use crate::statistics::{median_absolute_deviation, median_of_sorted};
use crate::stoch::bank::{ChannelModel, GaussMarkovEstimate, GaussMarkovSource, ModelBank};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Largest gap between the temperatures of entries matched into one lot point, °C.
pub const POINT_TOLERANCE_C: f64 = 2.0;

/// Distance from the median, in scaled MADs, beyond which a unit is an outlier.
pub const OUTLIER_SCALED_MADS: f64 = 3.0;

/// MAD to standard deviation for normal data: 1 / Φ⁻¹(3/4).
pub const MAD_TO_SIGMA: f64 = 1.482_602_218_505_602;

/// Why a lot cannot be summarised.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LotError {
    /// No unit at all.
    #[error("the lot has no units")]
    NoUnits,
    /// Two units with the same serial.
    #[error("serial \"{0}\" appears twice")]
    DuplicateSerial(String),
    /// One unit has two entries that match the same lot temperature point.
    #[error(
        "unit {serial} has entries at {first_c} °C and {second_c} °C, closer than the {POINT_TOLERANCE_C} °C that separates lot temperature points"
    )]
    AmbiguousTemperature {
        /// The unit.
        serial: String,
        /// The colder entry, °C.
        first_c: f64,
        /// The warmer entry, °C.
        second_c: f64,
    },
}

/// One unit of a lot: its serial and its bank.
#[derive(Debug, Clone, Copy)]
pub struct UnitBank<'a> {
    /// The unit's serial number.
    pub serial: &'a str,
    /// The unit's bank.
    pub bank: &'a ModelBank,
}

/// The spread of a lot, per temperature point and channel, and its outliers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LotSummary {
    /// Name of the lot.
    pub lot: String,
    /// Serials of the units, in the order given.
    pub units: Vec<String>,
    /// The outlier rule, in words.
    pub outlier_rule: String,
    /// Temperature points, increasing.
    pub points: Vec<LotPoint>,
    /// Every outlying value, by point, channel and quantity.
    pub outliers: Vec<Outlier>,
}

/// One lot temperature point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LotPoint {
    /// Median of the units' entry temperatures, °C.
    pub temperature_c: f64,
    /// Each unit's entry temperature at this point, °C.
    pub unit_temperatures_c: BTreeMap<String, f64>,
    /// Per channel, per quantity (its key carries the unit), the spread across units.
    pub channels: BTreeMap<Channel, BTreeMap<String, Spread>>,
}

/// Order statistics of one quantity across units; values in the unit of the quantity's key.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Spread {
    /// Number of units with a value.
    pub units_with_value: usize,
    /// Median.
    pub median: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Median absolute deviation from the median (unscaled).
    pub mad: f64,
    /// Units whose value is an outlier, with the value and its distance.
    pub outliers: Vec<OutlyingValue>,
    /// Units at this point without a value (no Gauss-Markov equivalent, term not identified).
    pub without_value: Vec<String>,
}

/// A unit's value beyond the outlier rule, within its [`Spread`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OutlyingValue {
    /// The unit.
    pub serial: String,
    /// The unit's value, in the quantity's unit.
    pub value: f64,
    /// Distance from the median in scaled MADs.
    pub scaled_mads_from_median: f64,
}

/// A unit's value that lies beyond the outlier rule, with where it was found.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outlier {
    /// The unit.
    pub serial: String,
    /// The lot point, °C.
    pub temperature_c: f64,
    /// The channel.
    pub channel: Channel,
    /// The quantity's key (with its unit).
    pub quantity: String,
    /// The unit's value, in the quantity's unit.
    pub value: f64,
    /// The lot median, in the quantity's unit.
    pub median: f64,
    /// Distance from the median in scaled MADs.
    pub scaled_mads_from_median: f64,
}

/// A quantity summarised across a lot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Correlation time of a Gauss-Markov family, s.
    CorrelationTime(GaussMarkovSource),
    /// σ of a Gauss-Markov family, channel unit.
    Sigma(GaussMarkovSource),
    /// Allan white-noise density (ARW or VRW).
    WhiteNoiseDensity,
    /// Allan bias instability.
    BiasInstability,
    /// Allan rate random walk.
    RateRandomWalk,
}

const FAMILIES: [GaussMarkovSource; 3] = [
    GaussMarkovSource::IrregularMl,
    GaussMarkovSource::ArBased,
    GaussMarkovSource::AcfFit,
];

impl Quantity {
    /// Every quantity, Gauss-Markov families first.
    pub fn all() -> Vec<Quantity> {
        let mut all: Vec<Quantity> = FAMILIES
            .iter()
            .flat_map(|&f| [Quantity::CorrelationTime(f), Quantity::Sigma(f)])
            .collect();
        all.extend([
            Quantity::WhiteNoiseDensity,
            Quantity::BiasInstability,
            Quantity::RateRandomWalk,
        ]);
        all
    }

    /// The JSON key of the quantity for a sensor, with its SI unit
    /// (`irregular_ml_sigma_rad_s`, `white_noise_density_m_s_per_sqrt_s`).
    pub fn key(self, sensor: Sensor) -> String {
        let (rate, density, walk) = match sensor {
            Sensor::Gyro => ("rad_s", "rad_per_sqrt_s", "rad_s_per_sqrt_s"),
            Sensor::Accelerometer => ("m_s2", "m_s_per_sqrt_s", "m_s2_per_sqrt_s"),
        };
        match self {
            Quantity::CorrelationTime(f) => format!("{}_correlation_time_s", f.name()),
            Quantity::Sigma(f) => format!("{}_sigma_{rate}", f.name()),
            Quantity::WhiteNoiseDensity => format!("white_noise_density_{density}"),
            Quantity::BiasInstability => format!("bias_instability_{rate}"),
            Quantity::RateRandomWalk => format!("rate_random_walk_{walk}"),
        }
    }

    /// The value of the quantity in a channel's models, when there is one.
    pub fn value(self, model: &ChannelModel) -> Option<f64> {
        let gauss_markov = |f| match model.gauss_markov.get(f) {
            GaussMarkovEstimate::Model {
                correlation_time_s,
                sigma,
                ..
            } => Some((*correlation_time_s, *sigma)),
            GaussMarkovEstimate::NoEquivalent { .. } => None,
        };
        let value = match self {
            Quantity::CorrelationTime(f) => gauss_markov(f).map(|(tc, _)| tc),
            Quantity::Sigma(f) => gauss_markov(f).map(|(_, sigma)| sigma),
            Quantity::WhiteNoiseDensity => model.allan.white_noise_density,
            Quantity::BiasInstability => model.allan.bias_instability,
            Quantity::RateRandomWalk => model.allan.rate_random_walk,
        };
        value.filter(|v| v.is_finite())
    }
}

/// Distance of `value` from `median` in scaled MADs; `None` when the MAD is zero.
pub fn scaled_mads_from_median(value: f64, median: f64, mad: f64) -> Option<f64> {
    (mad > 0.0).then(|| (value - median).abs() / (MAD_TO_SIGMA * mad))
}

/// The spread of `(serial, value)` pairs; `None` when no unit has a value.
fn spread_of(values: &[(&str, Option<f64>)]) -> Option<Spread> {
    let present: Vec<(&str, f64)> = values
        .iter()
        .filter_map(|(s, v)| Some((*s, (*v)?)))
        .collect();
    let mut sorted: Vec<f64> = present.iter().map(|(_, v)| *v).collect();
    sorted.sort_by(f64::total_cmp);
    let median = median_of_sorted(&sorted);
    let mad = median_absolute_deviation(&sorted, median);
    let outliers = present
        .iter()
        .filter_map(|(serial, value)| {
            let distance = scaled_mads_from_median(*value, median, mad)?;
            is_outlying(distance).then(|| OutlyingValue {
                serial: serial.to_string(),
                value: *value,
                scaled_mads_from_median: distance,
            })
        })
        .collect();
    Some(Spread {
        units_with_value: sorted.len(),
        median,
        min: *sorted.first()?,
        max: *sorted.last()?,
        mad,
        outliers,
        without_value: values
            .iter()
            .filter(|(_, v)| v.is_none())
            .map(|(s, _)| s.to_string())
            .collect(),
    })
}

/// True beyond [`OUTLIER_SCALED_MADS`].
fn is_outlying(scaled_mads: f64) -> bool {
    scaled_mads > OUTLIER_SCALED_MADS
}

/// One unit's entry at a lot point: serial, temperature, the entry.
type Member<'a> = (&'a str, f64, &'a crate::stoch::bank::TemperatureEntry);

/// The entries of all units grouped into lot temperature points (see the module docs).
fn group_into_points<'a>(units: &[UnitBank<'a>]) -> Result<Vec<Vec<Member<'a>>>, LotError> {
    let mut all: Vec<Member<'a>> = units
        .iter()
        .flat_map(|u| {
            u.bank
                .entries
                .iter()
                .map(|e| (u.serial, e.temperature_c, e))
        })
        .collect();
    all.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut points: Vec<Vec<Member<'a>>> = Vec::new();
    for member in all {
        match points.last_mut() {
            Some(point) if member.1 - point[point.len() - 1].1 <= POINT_TOLERANCE_C => {
                check_one_entry_per_unit(point, &member)?;
                point.push(member);
            }
            _ => points.push(vec![member]),
        }
    }
    Ok(points)
}

/// Refuses a second entry of the same unit at one point.
fn check_one_entry_per_unit(point: &[Member<'_>], member: &Member<'_>) -> Result<(), LotError> {
    match point.iter().find(|m| m.0 == member.0) {
        Some(first) => Err(LotError::AmbiguousTemperature {
            serial: member.0.to_string(),
            first_c: first.1,
            second_c: member.1,
        }),
        None => Ok(()),
    }
}

/// Summarises a lot: spreads per point, channel and quantity, and the outliers.
///
/// # Errors
/// [`LotError`] for an empty lot, a repeated serial, or a unit with two entries at one point.
pub fn summarize_lot(lot: &str, units: &[UnitBank<'_>]) -> Result<LotSummary, LotError> {
    check_serials(units)?;
    let points: Vec<LotPoint> = group_into_points(units)?
        .iter()
        .map(|members| lot_point(members))
        .collect();
    let outliers = points.iter().flat_map(outliers_of_point).collect();
    Ok(LotSummary {
        lot: lot.to_string(),
        units: units.iter().map(|u| u.serial.to_string()).collect(),
        outlier_rule: format!(
            "|value - median| > {OUTLIER_SCALED_MADS} x {MAD_TO_SIGMA:.4} x MAD (MAD = median absolute deviation across the units with a value at that point; none flagged when MAD = 0)"
        ),
        points,
        outliers,
    })
}

/// Refuses an empty lot and repeated serials.
fn check_serials(units: &[UnitBank<'_>]) -> Result<(), LotError> {
    if units.is_empty() {
        return Err(LotError::NoUnits);
    }
    let mut seen = std::collections::BTreeSet::new();
    match units.iter().find(|u| !seen.insert(u.serial)) {
        Some(u) => Err(LotError::DuplicateSerial(u.serial.to_string())),
        None => Ok(()),
    }
}

/// The spreads of one lot point.
fn lot_point(members: &[Member<'_>]) -> LotPoint {
    let mut temperatures: Vec<f64> = members.iter().map(|m| m.1).collect();
    temperatures.sort_by(f64::total_cmp);
    let mut channels = BTreeMap::new();
    for channel in Channel::ALL {
        let spreads: BTreeMap<String, Spread> = Quantity::all()
            .into_iter()
            .filter_map(|q| {
                let values: Vec<(&str, Option<f64>)> = members
                    .iter()
                    .map(|m| (m.0, m.2.channels.get(&channel).and_then(|c| q.value(c))))
                    .collect();
                Some((q.key(channel.sensor()), spread_of(&values)?))
            })
            .collect();
        channels.insert(channel, spreads);
    }
    LotPoint {
        temperature_c: median_of_sorted(&temperatures),
        unit_temperatures_c: members.iter().map(|m| (m.0.to_string(), m.1)).collect(),
        channels,
    }
}

/// The outliers of one point, flattened with their point, channel and quantity.
fn outliers_of_point(point: &LotPoint) -> Vec<Outlier> {
    let mut found = Vec::new();
    for (channel, spreads) in &point.channels {
        for (quantity, spread) in spreads {
            found.extend(spread.outliers.iter().map(|o| Outlier {
                serial: o.serial.clone(),
                temperature_c: point.temperature_c,
                channel: *channel,
                quantity: quantity.clone(),
                value: o.value,
                median: spread.median,
                scaled_mads_from_median: o.scaled_mads_from_median,
            }));
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    // 1 / Φ⁻¹(3/4), with Φ⁻¹(0.75) = 0.674489750196081743... (Abramowitz & Stegun table 26.5);
    // the product is 1 to the last bit or two.
    #[test]
    fn mad_scale_is_the_normal_quartile() {
        assert!((MAD_TO_SIGMA * 0.674_489_750_196_081_7 - 1.0).abs() < 4e-16);
    }

    // 100 lies 97 / 1.4826 = 65 scaled MADs out; 1 lies 2 / 1.4826 = 1.35 out; zero MAD flags
    // nothing.
    #[test]
    fn outlier_rule_on_a_closed_form_sample() {
        let values: Vec<(&str, Option<f64>)> = vec![
            ("a", Some(1.0)),
            ("b", Some(2.0)),
            ("c", Some(3.0)),
            ("d", Some(4.0)),
            ("e", Some(100.0)),
            ("f", None),
        ];
        let spread = spread_of(&values).unwrap();
        assert_eq!(
            (spread.median, spread.min, spread.max, spread.mad),
            (3.0, 1.0, 100.0, 1.0)
        );
        assert_eq!(spread.units_with_value, 5);
        assert_eq!(spread.without_value, vec!["f".to_string()]);
        assert_eq!(spread.outliers.len(), 1);
        assert_eq!(spread.outliers[0].serial, "e");
        assert!((spread.outliers[0].scaled_mads_from_median - 97.0 / MAD_TO_SIGMA).abs() < 1e-12);
        let flat = spread_of(&[("a", Some(5.0)), ("b", Some(5.0)), ("c", Some(9.0))]).unwrap();
        assert_eq!(flat.mad, 0.0);
        assert!(flat.outliers.is_empty());
        assert!(spread_of(&[("a", None)]).is_none());
    }

    /// A bank whose entries sit at `temperatures_c`, gx only, every value `value`.
    fn bank(temperatures_c: &[f64], value: f64) -> ModelBank {
        let channel = serde_json::json!({
            "unit": "rad/s",
            "allan": { "tau_s": [1.0], "adev": [value], "white_noise_density": value,
                       "bias_instability": null, "rate_random_walk": null },
            "ar": { "method": "burg", "coefficients": [0.5], "noise_variance": value, "dt_s": 1.0 },
            "gauss_markov": {
                "ar_based": { "status": "no_equivalent", "reason": "test" },
                "irregular_ml": { "status": "model", "correlation_time_s": value, "sigma": value,
                                  "ci95_correlation_time_s": [null, null] },
                "acf_fit": { "status": "no_equivalent", "reason": "test" } } });
        let entries: Vec<serde_json::Value> = temperatures_c
            .iter()
            .map(|t| {
                serde_json::json!({
                "temperature_c": t, "source": "x.csv",
                "preprocessing": { "input_rate_hz": 1.0, "filter": null, "decimation_factor": 1,
                                   "modelling_rate_hz": 1.0 },
                "channels": { "gx": channel } })
            })
            .collect();
        serde_json::from_value(serde_json::json!({ "version": 1, "entries": entries })).unwrap()
    }

    // Entries within 2 °C of each other form one point whose temperature is their median; a
    // unit missing a point is simply absent from it; two entries of one unit at a point and a
    // repeated serial are refused.
    #[test]
    fn entries_are_matched_into_points_by_temperature() {
        let (a, b, c) = (
            bank(&[-0.3, 20.0], 1.0),
            bank(&[0.4, 21.5], 2.0),
            bank(&[0.1], 4.0),
        );
        let units = [
            UnitBank {
                serial: "a",
                bank: &a,
            },
            UnitBank {
                serial: "b",
                bank: &b,
            },
            UnitBank {
                serial: "c",
                bank: &c,
            },
        ];
        let summary = summarize_lot("lot", &units).unwrap();
        assert_eq!(summary.points.len(), 2);
        assert_eq!(summary.points[0].temperature_c, 0.1);
        assert_eq!(summary.points[1].temperature_c, 0.5 * (20.0 + 21.5));
        let tc = &summary.points[0].channels[&Channel::Gx]["irregular_ml_correlation_time_s"];
        assert_eq!((tc.median, tc.min, tc.max, tc.mad), (2.0, 1.0, 4.0, 1.0));
        assert_eq!(summary.points[1].unit_temperatures_c.len(), 2);
        let gx = &summary.points[0].channels[&Channel::Gx];
        assert!(!gx.contains_key("ar_based_sigma_rad_s"));
        assert!(summary.points[0].channels[&Channel::Ax].is_empty());
        let close = bank(&[0.0, 1.5], 1.0);
        let twice = [UnitBank {
            serial: "a",
            bank: &close,
        }];
        assert!(matches!(
            summarize_lot("lot", &twice),
            Err(LotError::AmbiguousTemperature { .. })
        ));
        let repeated = [units[0], units[0]];
        assert_eq!(
            summarize_lot("lot", &repeated),
            Err(LotError::DuplicateSerial("a".into()))
        );
        assert_eq!(summarize_lot("lot", &[]), Err(LotError::NoUnits));
    }
}
