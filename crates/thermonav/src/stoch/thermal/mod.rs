//! Deterministic thermal calibration: a channel's bias as a polynomial in temperature, with its
//! uncertainty, and the per-power-on offset kept apart from the repeatable curve.
//!
//! # Model
//! For observations (T_i, y_i), i = 1..n, of one channel (the mean of a static chamber
//! record, or samples or block means of a continuous temperature sweep, in the channel's rate
//! unit: rad/s or m/s²),
//!
//! ```text
//! y_i = Σ_{k=0..K} b_k (T_i − T_ref)^k + e_i,   e_i independent N(0, σ²),   K ≤ 3
//! ```
//!
//! the polynomial approach to MEMS thermal drift (Aggarwal, Syed, Niu & El-Sheimy 2008, "A
//! standard testing and calibration procedure for low cost MEMS inertial sensors and units",
//! Journal of Navigation 61(2), 323-336). b_k is in the channel's unit per °C^k.
//!
//! # Solve
//! The powers of T − T_ref over a −40..+85 °C range span ten orders of magnitude, so the fit is
//! made in the scaled variable z = (T − c)/s ∈ [−1, 1] (c the middle and s the half-width of
//! the data's temperature range): X_ik = z_i^k, X = QR (Householder), â = R⁻¹Qᵀy,
//! (XᵀX)⁻¹ = R⁻¹R⁻ᵀ. The coefficients are then moved to the reference basis, b = M a with
//! M_mk = C(k, m) (T_ref − c)^(k−m) / s^k, and Cov(b̂) = s_e² M (XᵀX)⁻¹ Mᵀ, where
//! s_e² = Σ e_i² / (n − p) is the residual variance and p = K + 1.
//!
//! # Order
//! Leave-one-out cross-validation in closed form: with the hat matrix H = X(XᵀX)⁻¹Xᵀ, whose
//! diagonal is h_ii = ‖row i of Q‖², the residual of observation i when the fit is made without
//! it is e_i / (1 − h_ii), and PRESS = Σ (e_i / (1 − h_ii))² (Allen 1974, "The relationship
//! between variable selection and data augmentation and a method for prediction",
//! Technometrics 16, 125-127). The rule: the candidate orders are K = 0..=min(3, d − 1), d the
//! number of distinct temperatures; an order is dropped when its design is numerically rank
//! deficient, when it leaves no residual degree of freedom (n ≤ p) or when some observation has
//! leverage 1 (its deletion residual is undefined). The order with the smallest PRESS is
//! chosen; an exact tie goes to the lower order. [`OrderChoice::Fixed`] skips the choice (the
//! PRESS values are still reported).
//!
//! # Band
//! The simultaneous 95 % band of Scheffé (1953, "A method for judging all contrasts in the
//! analysis of variance", Biometrika 40, 87-104): with x(T) = (1, d, …, d^K), d = T − T_ref,
//!
//! ```text
//! b̂(T) ± sqrt(p · F_{p, n−p; 0.95}) · sqrt(x(T)ᵀ Cov(b̂) x(T))
//! ```
//!
//! covers the whole true curve (every temperature at once) with probability 95 % when the
//! model holds. It assumes independent errors: raw samples of a sweep carry the sensor's
//! correlated noise (bias instability, Gauss-Markov), and the band is then too narrow; fit
//! [`block_means`] over blocks longer than the noise's correlation time instead.
//!
//! # Power-on offsets
//! A MEMS unit adds a turn-on bias that changes at every power-on but stays fixed while it
//! runs. [`fit_bias_curve_with_power_ons`] fits one free offset per power-on (fixed effects):
//!
//! ```text
//! y_ij = α_j + Σ_{k=1..K} a_k z_ij^k + e_ij     (j the power-on)
//! ```
//!
//! The shape a_1..a_K is learnt only from how the bias changes within a power-on, so at least
//! one power-on must span two or more temperatures. The repeatable curve takes the mean offset
//! ᾱ as its constant; each power-on's offset is reported as α_j − ᾱ with its standard
//! deviation. The spread of the offsets overstates the true spread between power-ons by their
//! estimation noise; [`PowerOnFit::between_power_on_sd`] removes it by the method of moments:
//! σ̂_b² = max(0, (Σ_j (α̂_j − ᾱ)² − Σ_j Var(α̂_j − ᾱ)) / (J − 1)).

mod bank_calibration;
mod calibration;
pub mod check;
pub mod clock_drift;
pub mod join;
pub mod legs;
mod observations;
mod power_on;
mod selection;
mod solve;
mod summary;
pub mod sweep_model;

use crate::imu::{Channel, SampleKind};
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};
use solve::{LeastSquares, Scaling, distinct, least_squares, range, to_reference_basis};
use statrs::distribution::{ContinuousCDF, FisherSnedecor};

pub use bank_calibration::{
    DEFAULT_SITE_HEIGHT_M, DEFAULT_SITE_LATITUDE_DEG, bank_power_on, calibrate_level_unit,
};
pub use calibration::{
    ChannelCalibration, CompensationError, CompensationSummary, LaggedBias, ScaleFactorCalibration,
    SensorDevices, ThermalCalibration, calibrate, without_signal,
};
pub use observations::{
    RecordMean, RecordSums, merge_records, power_on_records, record_mean, sweep_records,
};
pub use power_on::{PowerOnFit, PowerOnOffset, PowerOnRecord, fit_bias_curve_with_power_ons};
pub use summary::{BAND_SEARCH_POINTS, CalibrationSummary};

/// Highest polynomial order fitted (the cubic of PX4 and ArduPilot thermal calibration).
pub const MAX_ORDER: usize = 3;

/// Confidence of the simultaneous band.
pub const BAND_CONFIDENCE: f64 = 0.95;

/// Why a thermal curve cannot be fitted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ThermalError {
    /// Fewer observations than the smallest fit needs.
    #[error("{observations} observations: a thermal fit needs at least {needed}")]
    TooFewObservations {
        /// Observations given.
        observations: usize,
        /// Observations needed.
        needed: usize,
    },
    /// A temperature or value is NaN or infinite.
    #[error("observation {index} has a non-finite temperature or value")]
    NonFiniteObservation {
        /// Position of the observation.
        index: usize,
    },
    /// The reference temperature is NaN or infinite.
    #[error("the reference temperature {0} °C is not finite")]
    NonFiniteReference(f64),
    /// A fixed order above [`MAX_ORDER`].
    #[error("polynomial order {order} requested: at most {MAX_ORDER} is fitted")]
    OrderTooHigh {
        /// The order asked for.
        order: usize,
    },
    /// A fixed order the data cannot identify with a residual left over.
    #[error(
        "polynomial order {order} cannot be fitted to {observations} observations at {distinct_temperatures} distinct temperatures (it needs more distinct temperatures than its order and more observations than coefficients)"
    )]
    OrderNotIdentifiable {
        /// The order asked for.
        order: usize,
        /// Observations given.
        observations: usize,
        /// Distinct temperatures among them.
        distinct_temperatures: usize,
    },
    /// Not one order passes the rule of the module docs.
    #[error(
        "no polynomial order can be cross-validated on {observations} observations at {distinct_temperatures} distinct temperatures"
    )]
    NoValidOrder {
        /// Observations given.
        observations: usize,
        /// Distinct temperatures among them.
        distinct_temperatures: usize,
    },
    /// The power-on model needs at least two power-ons.
    #[error("{power_ons} power-on(s): separating per-power-on offsets needs at least 2")]
    TooFewPowerOns {
        /// Distinct power-ons given.
        power_ons: usize,
    },
    /// Every power-on was recorded at a single temperature.
    #[error(
        "every one of the {power_ons} power-ons was recorded at a single temperature, so each offset absorbs its power-on's bias and the curve's shape cannot be told apart from the offsets: at least 2 power-ons at 2 or more temperatures each (or power-ons that overlap in temperature) are needed"
    )]
    OffsetsUnidentifiable {
        /// Distinct power-ons given.
        power_ons: usize,
    },
    /// Temperature and value columns of a sweep differ in length.
    #[error("{temperatures} temperatures for {values} values")]
    LengthMismatch {
        /// Temperatures given.
        temperatures: usize,
        /// Values given.
        values: usize,
    },
    /// A block of zero samples (or a block length that is not positive).
    #[error("a block mean needs a positive block length and at least one sample per block")]
    EmptyBlock,
    /// A sweep record without a temperature column.
    #[error("a temperature sweep needs a temp_c column")]
    NoTemperature,
}

/// One observation of a channel at a temperature (a record's mean, a sample, a block mean).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TemperaturePoint {
    /// Sensor temperature, °C.
    pub temperature_c: f64,
    /// The channel's value in its rate unit (rad/s or m/s²).
    pub value: f64,
}

/// How the polynomial order is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OrderChoice {
    /// Smallest leave-one-out PRESS under the rule of the module docs.
    CrossValidated,
    /// This order (0..=3), when the data identify it.
    Fixed(usize),
}

/// Settings of a thermal fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitSettings {
    /// T_ref, °C; `None` takes the middle of the data's temperature range.
    pub reference_temperature_c: Option<f64>,
    /// How the order is chosen.
    pub order: OrderChoice,
}

impl Default for FitSettings {
    fn default() -> Self {
        FitSettings {
            reference_temperature_c: None,
            order: OrderChoice::CrossValidated,
        }
    }
}

/// What a thermal curve describes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ThermalQuantity {
    /// The channel's bias, in its rate unit (rad/s or m/s²).
    Bias,
}

/// How the order of a curve was chosen, with the evidence.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OrderSelection {
    /// The rule applied.
    pub choice: OrderChoice,
    /// Leave-one-out PRESS, Σ (e_i / (1 − h_ii))², for orders 0..=3 (channel unit squared);
    /// `None` where the order is not a candidate.
    pub press: Vec<Option<f64>>,
}

/// A fitted thermal curve of one channel: b(T) = Σ b_k (T − T_ref)^k.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ThermalCurve {
    /// The channel.
    pub channel: Channel,
    /// What the curve describes.
    pub quantity: ThermalQuantity,
    /// T_ref, °C.
    pub reference_temperature_c: f64,
    /// Polynomial order K.
    pub order: usize,
    /// b_0..b_K, each in the unit of [`ThermalCurve::coefficient_units`].
    pub coefficients: Vec<f64>,
    /// Unit of each coefficient: the channel's unit per °C^k.
    pub coefficient_units: Vec<String>,
    /// Cov(b̂), (K+1)×(K+1), row-major, in the products of the coefficients' units.
    pub coefficient_covariance: Vec<Vec<f64>>,
    /// s_e, the residual standard deviation, channel unit.
    pub residual_sd: f64,
    /// n − (number of fitted parameters).
    pub residual_degrees_of_freedom: usize,
    /// Observations fitted.
    pub observations: usize,
    /// Distinct temperatures among them.
    pub distinct_temperatures: usize,
    /// Coldest and warmest temperature of the data, °C.
    pub temperature_range_c: [f64; 2],
    /// Confidence of the simultaneous band ([`BAND_CONFIDENCE`]).
    pub band_confidence: f64,
    /// sqrt(p · F_{p, n−p; confidence}), the band's multiple of the curve's standard error.
    pub scheffe_factor: f64,
    /// How the order was chosen.
    pub order_selection: OrderSelection,
}

impl ThermalCurve {
    /// b̂(T), channel unit. A non-finite temperature gives NaN.
    pub fn value_at(&self, temperature_c: f64) -> f64 {
        let d = temperature_c - self.reference_temperature_c;
        self.coefficients
            .iter()
            .rev()
            .fold(0.0, |acc, b| acc * d + b)
    }

    /// Standard error of b̂(T), sqrt(x(T)ᵀ Cov(b̂) x(T)), channel unit.
    pub fn standard_error_at(&self, temperature_c: f64) -> f64 {
        let x = powers(temperature_c - self.reference_temperature_c, self.order + 1);
        let quadratic: f64 = self
            .coefficient_covariance
            .iter()
            .zip(&x)
            .map(|(row, xi)| xi * row.iter().zip(&x).map(|(c, xj)| c * xj).sum::<f64>())
            .sum();
        quadratic.max(0.0).sqrt()
    }

    /// (b̂(T), half-width of the simultaneous band at T), channel unit. The band is meant for
    /// [`ThermalCurve::temperature_range_c`]; beyond it the value is an extrapolation that
    /// relies on the polynomial holding there.
    pub fn band_at(&self, temperature_c: f64) -> (f64, f64) {
        (
            self.value_at(temperature_c),
            self.scheffe_factor * self.standard_error_at(temperature_c),
        )
    }
}

/// 1, d, d², … (`terms` of them).
fn powers(d: f64, terms: usize) -> Vec<f64> {
    (0..terms).map(|k| d.powi(k as i32)).collect()
}

/// Fits the bias curve of `channel` to observations at several temperatures.
///
/// # Errors
/// Fewer than 2 observations, a non-finite temperature, value or reference, a fixed order
/// above 3 or beyond what the data identify, or no order passing the rule of the module docs.
///
/// # Example
/// ```
/// use thermonav::imu::Channel;
/// use thermonav::stoch::thermal::{FitSettings, TemperaturePoint, fit_bias_curve};
/// let points: Vec<TemperaturePoint> = [-40.0, -20.0, 0.0, 20.0, 40.0, 60.0]
///     .iter()
///     .zip([1.1e-3, 0.4e-3, 0.05e-3, 0.0, 0.3e-3, 0.9e-3])
///     .map(|(&temperature_c, value)| TemperaturePoint { temperature_c, value })
///     .collect();
/// let settings = FitSettings { reference_temperature_c: Some(25.0), ..FitSettings::default() };
/// let curve = fit_bias_curve(Channel::Gx, &points, settings)?;
/// let (bias, half_width) = curve.band_at(10.0);
/// assert!(half_width > 0.0 && bias.abs() < 1e-3);
/// # Ok::<(), thermonav::stoch::thermal::ThermalError>(())
/// ```
pub fn fit_bias_curve(
    channel: Channel,
    points: &[TemperaturePoint],
    settings: FitSettings,
) -> Result<ThermalCurve, ThermalError> {
    check_points(points.iter().map(|p| (p.temperature_c, p.value)), 2)?;
    let temperatures = || points.iter().map(|p| p.temperature_c);
    let reference_c = reference_temperature(settings, temperatures())?;
    let scaling = Scaling::of(temperatures());
    let y = DVector::from_iterator(points.len(), points.iter().map(|p| p.value));
    let design = |order: usize| {
        DMatrix::from_fn(points.len(), order + 1, |i, k| {
            scaling.z(points[i].temperature_c).powi(k as i32)
        })
    };
    let data = DataShape::of(points.len(), temperatures());
    let identifiable = data.distinct_temperatures - 1;
    let (fits, selection) = fit_orders(
        settings.order,
        data,
        identifiable,
        |k| k + 1,
        |order| {
            least_squares(&design(order), &y).map(|ls| {
                let press = ls.press(|_| true);
                (ls, press)
            })
        },
    )?;
    let fit = &fits[selection.1];
    let p = selection.1 + 1;
    let variance = fit.rss() / (points.len() - p) as f64;
    let covariance = &fit.inverse_gram * variance;
    Ok(curve_from(
        CurveParts {
            channel,
            reference_c,
            scaling,
            coefficients: fit.coefficients.clone(),
            covariance,
            residual_sd: variance.sqrt(),
            residual_degrees_of_freedom: points.len() - p,
            data,
        },
        selection.0,
    ))
}

/// Means of consecutive blocks of `block_len` samples of a temperature sweep (temperature and
/// value averaged alike); a last, incomplete block is dropped.
///
/// # Errors
/// Columns of different lengths, or `block_len` = 0.
pub fn block_means(
    temperatures_c: &[f64],
    values: &[f64],
    block_len: usize,
) -> Result<Vec<TemperaturePoint>, ThermalError> {
    if temperatures_c.len() != values.len() {
        return Err(ThermalError::LengthMismatch {
            temperatures: temperatures_c.len(),
            values: values.len(),
        });
    }
    if block_len == 0 {
        return Err(ThermalError::EmptyBlock);
    }
    let mean = |xs: &[f64]| xs.iter().sum::<f64>() / xs.len() as f64;
    Ok(temperatures_c
        .chunks_exact(block_len)
        .zip(values.chunks_exact(block_len))
        .map(|(t, v)| TemperaturePoint {
            temperature_c: mean(t),
            value: mean(v),
        })
        .collect())
}

/// Size of a data set, as the order rule sees it.
#[derive(Debug, Clone, Copy)]
struct DataShape {
    observations: usize,
    distinct_temperatures: usize,
    range_c: (f64, f64),
}

impl DataShape {
    fn of(observations: usize, temperatures_c: impl Iterator<Item = f64> + Clone) -> Self {
        DataShape {
            observations,
            distinct_temperatures: distinct(temperatures_c.clone()),
            range_c: range(temperatures_c),
        }
    }
}

/// Refuses too few observations and non-finite ones.
fn check_points(
    points: impl ExactSizeIterator<Item = (f64, f64)>,
    needed: usize,
) -> Result<(), ThermalError> {
    if points.len() < needed {
        return Err(ThermalError::TooFewObservations {
            observations: points.len(),
            needed,
        });
    }
    for (index, (t, v)) in points.enumerate() {
        if !t.is_finite() || !v.is_finite() {
            return Err(ThermalError::NonFiniteObservation { index });
        }
    }
    Ok(())
}

/// The reference temperature asked for, or the middle of the data's range.
fn reference_temperature(
    settings: FitSettings,
    temperatures_c: impl Iterator<Item = f64>,
) -> Result<f64, ThermalError> {
    match settings.reference_temperature_c {
        Some(t) if t.is_finite() => Ok(t),
        Some(t) => Err(ThermalError::NonFiniteReference(t)),
        None => Ok(Scaling::of(temperatures_c).centre_c),
    }
}

/// The fits of the candidate orders 0..=min(3, `identifiable`) (index = order, up to the first
/// order whose design is rank deficient or leaves no residual) and the chosen (selection,
/// order). `parameters(k)` is the number of fitted parameters of order k; `fit(k)` returns its
/// fit with its PRESS (`None` when undefined).
fn fit_orders(
    choice: OrderChoice,
    data: DataShape,
    identifiable: usize,
    parameters: impl Fn(usize) -> usize,
    fit: impl Fn(usize) -> Option<(LeastSquares, Option<f64>)>,
) -> Result<(Vec<LeastSquares>, (OrderSelection, usize)), ThermalError> {
    if let OrderChoice::Fixed(order) = choice
        && order > MAX_ORDER
    {
        return Err(ThermalError::OrderTooHigh { order });
    }
    let highest = MAX_ORDER.min(identifiable);
    let mut fits = Vec::new();
    let mut press = vec![None; MAX_ORDER + 1];
    for order in (0..=highest).take_while(|&k| data.observations > parameters(k)) {
        let Some((ls, order_press)) = fit(order) else {
            break;
        };
        press[order] = order_press;
        fits.push(ls);
    }
    let chosen = match choice {
        OrderChoice::Fixed(order) if order < fits.len() => order,
        OrderChoice::Fixed(order) => {
            return Err(ThermalError::OrderNotIdentifiable {
                order,
                observations: data.observations,
                distinct_temperatures: data.distinct_temperatures,
            });
        }
        OrderChoice::CrossValidated => {
            smallest_press(&press).ok_or(ThermalError::NoValidOrder {
                observations: data.observations,
                distinct_temperatures: data.distinct_temperatures,
            })?
        }
    };
    Ok((fits, (OrderSelection { choice, press }, chosen)))
}

/// The order of the smallest PRESS (the lower order on an exact tie).
fn smallest_press(press: &[Option<f64>]) -> Option<usize> {
    press
        .iter()
        .enumerate()
        .filter_map(|(k, p)| p.map(|p| (k, p)))
        .fold(None, |best: Option<(usize, f64)>, (k, p)| match best {
            Some((_, q)) if q <= p => best,
            _ => Some((k, p)),
        })
        .map(|(k, _)| k)
}

/// A fitted curve in the scaled basis, before it is moved to T − T_ref.
struct CurveParts {
    channel: Channel,
    reference_c: f64,
    scaling: Scaling,
    /// a_0..a_K in powers of z.
    coefficients: DVector<f64>,
    /// Cov(â).
    covariance: DMatrix<f64>,
    residual_sd: f64,
    residual_degrees_of_freedom: usize,
    data: DataShape,
}

/// The curve in the reference basis, with its band.
fn curve_from(parts: CurveParts, order_selection: OrderSelection) -> ThermalCurve {
    let terms = parts.coefficients.len();
    let m = to_reference_basis(parts.scaling, parts.reference_c, terms);
    let coefficients = &m * &parts.coefficients;
    let covariance = &m * &parts.covariance * m.transpose();
    let unit = parts.channel.si_unit(SampleKind::Rates);
    ThermalCurve {
        channel: parts.channel,
        quantity: ThermalQuantity::Bias,
        reference_temperature_c: parts.reference_c,
        order: terms - 1,
        coefficients: coefficients.iter().copied().collect(),
        coefficient_units: (0..terms).map(|k| coefficient_unit(unit, k)).collect(),
        coefficient_covariance: (0..terms)
            .map(|i| (0..terms).map(|j| covariance[(i, j)]).collect())
            .collect(),
        residual_sd: parts.residual_sd,
        residual_degrees_of_freedom: parts.residual_degrees_of_freedom,
        observations: parts.data.observations,
        distinct_temperatures: parts.data.distinct_temperatures,
        temperature_range_c: [parts.data.range_c.0, parts.data.range_c.1],
        band_confidence: BAND_CONFIDENCE,
        scheffe_factor: scheffe_factor(terms, parts.residual_degrees_of_freedom),
        order_selection,
    }
}

/// `unit`, `unit/°C`, `unit/°C^k`.
fn coefficient_unit(unit: &str, k: usize) -> String {
    match k {
        0 => unit.to_string(),
        1 => format!("{unit}/°C"),
        _ => format!("{unit}/°C^{k}"),
    }
}

/// sqrt(p · F_{p, ν; BAND_CONFIDENCE}); p ≥ 1 and ν ≥ 1 by construction of the fits.
fn scheffe_factor(p: usize, dof: usize) -> f64 {
    let f = FisherSnedecor::new(p as f64, dof as f64)
        .expect("p and the residual degrees of freedom are at least 1")
        .inverse_cdf(BAND_CONFIDENCE);
    (p as f64 * f).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points(ts: &[f64], f: impl Fn(f64) -> f64) -> Vec<TemperaturePoint> {
        ts.iter()
            .map(|&t| TemperaturePoint {
                temperature_c: t,
                value: f(t),
            })
            .collect()
    }

    #[test]
    fn an_exact_quadratic_is_recovered_in_the_reference_basis() {
        let ts = [-40.0, -25.0, -10.0, 5.0, 20.0, 35.0, 50.0, 65.0, 80.0];
        // A little alternating noise keeps the residual away from zero.
        let pts: Vec<_> = points(&ts, |t| {
            1e-3 + 2e-5 * (t - 25.0) + 3e-7 * (t - 25.0).powi(2)
        })
        .into_iter()
        .enumerate()
        .map(|(i, p)| TemperaturePoint {
            value: p.value + if i % 2 == 0 { 1e-9 } else { -1e-9 },
            ..p
        })
        .collect();
        let settings = FitSettings {
            reference_temperature_c: Some(25.0),
            order: OrderChoice::Fixed(2),
        };
        let curve = fit_bias_curve(Channel::Gz, &pts, settings).unwrap();
        assert!((curve.coefficients[0] - 1e-3).abs() < 1e-8);
        assert!((curve.coefficients[1] - 2e-5).abs() < 1e-10);
        assert!((curve.coefficients[2] - 3e-7).abs() < 1e-12);
        assert_eq!(curve.coefficient_units[2], "rad/s/°C^2");
    }

    #[test]
    fn order_never_reaches_the_number_of_distinct_temperatures() {
        let pts = points(&[0.0, 0.0, 20.0, 20.0, 40.0], |t| 1e-4 * t * t);
        let curve = fit_bias_curve(Channel::Ax, &pts, FitSettings::default()).unwrap();
        assert!(curve.order < 3);
        assert_eq!(curve.order_selection.press[3], None);
        let fixed = FitSettings {
            order: OrderChoice::Fixed(3),
            ..FitSettings::default()
        };
        assert!(matches!(
            fit_bias_curve(Channel::Ax, &pts, fixed),
            Err(ThermalError::OrderNotIdentifiable { order: 3, .. })
        ));
    }

    #[test]
    fn bad_inputs_are_refused() {
        let one = points(&[10.0], |_| 0.0);
        assert!(matches!(
            fit_bias_curve(Channel::Gx, &one, FitSettings::default()),
            Err(ThermalError::TooFewObservations { .. })
        ));
        let nan = points(&[10.0, f64::NAN, 30.0], |_| 0.0);
        assert_eq!(
            fit_bias_curve(Channel::Gx, &nan, FitSettings::default()),
            Err(ThermalError::NonFiniteObservation { index: 1 })
        );
        let fine = points(&[10.0, 20.0, 30.0], |t| t);
        let high = FitSettings {
            order: OrderChoice::Fixed(4),
            ..FitSettings::default()
        };
        assert_eq!(
            fit_bias_curve(Channel::Gx, &fine, high),
            Err(ThermalError::OrderTooHigh { order: 4 })
        );
        let inf = FitSettings {
            reference_temperature_c: Some(f64::INFINITY),
            ..FitSettings::default()
        };
        assert!(matches!(
            fit_bias_curve(Channel::Gx, &fine, inf),
            Err(ThermalError::NonFiniteReference(_))
        ));
    }

    #[test]
    fn block_means_average_consecutive_samples() {
        let means = block_means(&[1.0, 3.0, 5.0, 7.0, 9.0], &[2.0, 4.0, 6.0, 8.0, 0.0], 2).unwrap();
        assert_eq!(means.len(), 2);
        assert_eq!(means[1].temperature_c, 6.0);
        assert_eq!(means[1].value, 7.0);
        assert_eq!(
            block_means(&[1.0], &[], 1),
            Err(ThermalError::LengthMismatch {
                temperatures: 1,
                values: 0
            })
        );
    }
}
