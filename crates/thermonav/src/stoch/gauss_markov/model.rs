//! The first-order Gauss-Markov model and its interval types.

use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, Normal};

use super::GaussMarkovError;

/// A stationary first-order Gauss-Markov process: `dx/dt = -x/Tc + w(t)`, white `w`.
///
/// Equations (method.md, Gelb 1974 §3.8, Groves 2013 §14.2): autocovariance
/// `R(tau) = sigma^2 exp(-|tau|/Tc)` (eq. 2), discrete transition over a step `dt`
/// `x_k = exp(-dt/Tc) x_{k-1} + w_k` (eq. 3) with the exact driving-noise variance
/// `sigma^2 (1 - exp(-2 dt/Tc))` (eq. 4), and white-noise spectral density `q = 2 sigma^2 / Tc`
/// (eq. 1). The process is zero-mean; a constant bias is carried outside the model.
///
/// Both parameters are validated at construction (finite, > 0, and `sigma^2` and `q`
/// representable), so every method returns finite numbers for finite non-negative `dt`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "UncheckedGaussMarkov", into = "UncheckedGaussMarkov")]
pub struct GaussMarkov {
    correlation_time_s: f64,
    sigma: f64,
}

/// The serialised form; checked through [`GaussMarkov::new`] when read.
#[derive(Serialize, Deserialize)]
struct UncheckedGaussMarkov {
    correlation_time_s: f64,
    sigma: f64,
}

impl TryFrom<UncheckedGaussMarkov> for GaussMarkov {
    type Error = GaussMarkovError;
    fn try_from(raw: UncheckedGaussMarkov) -> Result<Self, Self::Error> {
        GaussMarkov::new(raw.correlation_time_s, raw.sigma)
    }
}

impl From<GaussMarkov> for UncheckedGaussMarkov {
    fn from(model: GaussMarkov) -> Self {
        Self {
            correlation_time_s: model.correlation_time_s,
            sigma: model.sigma,
        }
    }
}

/// `Ok(value)` when `value` is finite and > 0.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, GaussMarkovError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(GaussMarkovError::NotPositive { name, value })
    }
}

/// `Ok(value)` when `value` is finite and > 0, else an out-of-range error naming it.
fn representable(quantity: &'static str, value: f64) -> Result<f64, GaussMarkovError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(GaussMarkovError::OutOfRange { quantity, value })
    }
}

impl GaussMarkov {
    /// The model with correlation time `correlation_time_s` (s) and standard deviation `sigma`
    /// (in the unit of the modelled quantity).
    ///
    /// # Errors
    /// [`GaussMarkovError::NotPositive`] when either parameter is not finite and > 0;
    /// [`GaussMarkovError::OutOfRange`] when `sigma^2` or `q = 2 sigma^2 / Tc` overflows or
    /// underflows to zero.
    pub fn new(correlation_time_s: f64, sigma: f64) -> Result<Self, GaussMarkovError> {
        positive("correlation time (s)", correlation_time_s)?;
        positive("sigma", sigma)?;
        let variance = representable("sigma^2", sigma * sigma)?;
        representable("q = 2 sigma^2 / Tc", 2.0 * variance / correlation_time_s)?;
        Ok(Self {
            correlation_time_s,
            sigma,
        })
    }

    /// Correlation time `Tc`, s.
    pub fn correlation_time_s(&self) -> f64 {
        self.correlation_time_s
    }

    /// Standard deviation `sigma` of the stationary process.
    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// Stationary variance `sigma^2`.
    pub fn variance(&self) -> f64 {
        self.sigma * self.sigma
    }

    /// Transition coefficient over a step of `dt_s` seconds: `exp(-|dt|/Tc)` (eq. 3).
    pub fn phi(&self, dt_s: f64) -> f64 {
        (-dt_s.abs() / self.correlation_time_s).exp()
    }

    /// Exact variance of the driving noise over a step of `dt_s` seconds (eq. 4):
    /// `sigma^2 (1 - exp(-2 |dt|/Tc))`, evaluated with `expm1` so that it stays accurate when
    /// `dt << Tc`. Its first-order approximation `2 sigma^2 dt / Tc = q dt` is never used: it
    /// overstates the variance once `dt` is not small against `Tc`.
    pub fn driving_noise_variance(&self, dt_s: f64) -> f64 {
        -self.variance() * (-2.0 * dt_s.abs() / self.correlation_time_s).exp_m1()
    }

    /// Autocovariance at lag `tau_s` seconds (eq. 2): `sigma^2 exp(-|tau|/Tc)`.
    pub fn autocorrelation(&self, tau_s: f64) -> f64 {
        self.variance() * self.phi(tau_s)
    }

    /// Spectral density of the continuous driving white noise (eq. 1): `q = 2 sigma^2 / Tc`,
    /// in (unit)^2 per hertz-second, i.e. (unit)^2 s.
    pub fn spectral_density_q(&self) -> f64 {
        2.0 * self.variance() / self.correlation_time_s
    }

    /// One exact step of the process (eqs. 3-4): the value `dt_s` seconds after `previous`,
    /// given a standard normal draw `standard_normal`.
    pub fn next_value(&self, previous: f64, dt_s: f64, standard_normal: f64) -> f64 {
        self.phi(dt_s) * previous + self.driving_noise_variance(dt_s).sqrt() * standard_normal
    }
}

/// A confidence level strictly between 0 and 1 (for example 0.95).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ConfidenceLevel(f64);

impl ConfidenceLevel {
    /// The conventional 95 % level.
    pub const NINETY_FIVE_PERCENT: Self = Self(0.95);

    /// The level `probability`.
    ///
    /// # Errors
    /// [`GaussMarkovError::InvalidConfidenceLevel`] unless `0 < probability < 1`.
    pub fn new(probability: f64) -> Result<Self, GaussMarkovError> {
        if probability > 0.0 && probability < 1.0 {
            Ok(Self(probability))
        } else {
            Err(GaussMarkovError::InvalidConfidenceLevel { value: probability })
        }
    }

    /// The probability, in (0, 1).
    pub fn probability(self) -> f64 {
        self.0
    }

    /// The two-sided standard normal quantile `z` with `P(|Z| <= z) = level`
    /// (1.959964 at 95 %), from `statrs`.
    pub fn normal_quantile(self) -> f64 {
        Normal::standard().inverse_cdf(0.5 + 0.5 * self.0)
    }

    /// The chi-square (1 degree of freedom) quantile at this level (3.841459 at 95 %),
    /// computed as `z^2`, which is exact for one degree of freedom.
    pub fn chi_square_1dof_quantile(self) -> f64 {
        let z = self.normal_quantile();
        z * z
    }
}

/// Upper end of a correlation-time interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum UpperBound {
    /// A finite bound, in seconds.
    Finite(f64),
    /// The data cannot exclude arbitrarily long correlation times (random-walk-like behaviour
    /// inside the interval): no finite upper bound exists.
    Unbounded,
}

/// A confidence interval for the correlation time `Tc`.
///
/// `lower_s` is 0 when the data cannot exclude arbitrarily short correlation times (white
/// noise); `upper` is [`UpperBound::Unbounded`] when they cannot exclude arbitrarily long ones.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CorrelationTimeInterval {
    /// Lower bound, s (>= 0).
    pub lower_s: f64,
    /// Upper bound.
    pub upper: UpperBound,
    /// The confidence level of the interval.
    pub level: ConfidenceLevel,
}

impl CorrelationTimeInterval {
    /// Whether `correlation_time_s` lies inside the interval (bounds included).
    pub fn contains(&self, correlation_time_s: f64) -> bool {
        let below_upper = match self.upper {
            UpperBound::Finite(upper_s) => correlation_time_s <= upper_s,
            UpperBound::Unbounded => true,
        };
        correlation_time_s >= self.lower_s && below_upper
    }
}
