//! A static IMU in a thermal chamber: the records the method starts from.
//!
//! The IMU sits level, x axis north, at a known site. Each channel reads the true static
//! signal (Earth rate for gyros, specific force −g along z for accelerometers, see
//! CONVENTIONS.md) through its error model at the chamber's temperature:
//!
//! y_k = (1 + s_k) u + b_unit + b_p + c₁ ΔT_k + c₂ ΔT_k² + b_GM,k + b_RW,k + n_k, then quantised,
//!
//! with u the true signal, s_k the scale-factor error (deterministic temperature term plus an
//! optional Gauss-Markov term, in ppm), b_unit the unit's fixed bias and b_p the power-on's
//! offset (`sim::unit`: the same unit in every run, a new offset at each power-on), c₁, c₂ the
//! bias temperature coefficients, ΔT_k = T_k − T_ref with T_k the chamber temperature (a set
//! point, a linear ramp or a replayed program, plus a slow Gauss-Markov wander; where the
//! profile gives a thermal lag, the structure's first-order lag of it), b_GM
//! the temperature-dependent Gauss-Markov bias, b_RW a bias random walk and n_k white noise of
//! density N averaged over the actual interval (variance N²/dt_k). Every process steps with
//! the actual dt_k of its sample.

use super::clock::{ClockError, SampleClock};
use super::errors::{ChannelErrors, gauss_markov_step, standard_normal};
use super::temperature_program::TemperatureProgram;
use super::unit::SimulatedUnit;
use crate::geo::{gravity::gravity_ned, wgs84::earth_rate_ned};
use crate::imu::{Channel, ImuSeries, SampleKind};
use crate::rng::{SimRng, named_rng};
use crate::sensor::{ChannelProfile, ProfileError, SensorProfile};
use crate::stoch::thermal::{DEFAULT_SITE_HEIGHT_M, DEFAULT_SITE_LATITUDE_DEG};
use crate::time::Timestamp;
use serde::Serialize;
use std::collections::BTreeMap;

/// Where the chamber stands.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Site {
    /// Geodetic latitude, rad.
    pub latitude_rad: f64,
    /// Ellipsoidal height, m.
    pub height_m: f64,
}

impl Default for Site {
    /// The site a thermal calibration assumes unless given ([`DEFAULT_SITE_LATITUDE_DEG`],
    /// [`DEFAULT_SITE_HEIGHT_M`]).
    fn default() -> Self {
        Self {
            latitude_rad: DEFAULT_SITE_LATITUDE_DEG.to_radians(),
            height_m: DEFAULT_SITE_HEIGHT_M,
        }
    }
}

/// Slow wander of the chamber temperature around its set point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ChamberWander {
    /// Standard deviation of the wander, °C.
    pub sigma_c: f64,
    /// Its correlation time, s.
    pub correlation_time_s: f64,
}

/// A whole campaign's plan, as the paper ran it: six set points from −40 to +60 °C, 3 h at
/// 200 Hz each, a clock with 50 µs of jitter that drops one sample in a thousand, and a chamber
/// temperature wandering by 0.05 °C with a 10 min correlation time.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CampaignSettings {
    /// Chamber set points, °C.
    pub temperatures_c: Vec<f64>,
    /// Record length per set point, s.
    pub duration_s: f64,
    /// Sampling rate, Hz.
    pub rate_hz: f64,
    /// Timestamp jitter (standard deviation), s.
    pub jitter_s: f64,
    /// Probability that a sample is dropped.
    pub drop_probability: f64,
    /// Slow wander of the chamber temperature.
    pub wander: ChamberWander,
    /// Power-ons of the unit: each visits every set point, powered throughout (the first
    /// one's records make the model bank; the others repeat them, so that the power-on
    /// offsets can be told apart from the thermal curve).
    pub power_ons: u32,
    /// Record length of the further power-ons, s (`None`: as the first's); their records
    /// serve the thermal calibration's means only, so they may be shorter.
    pub repeat_duration_s: Option<f64>,
    /// A temperature sweep of the same unit after the set points, in a power-on of its own.
    pub ramp: Option<Ramp>,
    /// A chamber program replayed after the set points (none with the default plan), in a
    /// power-on of its own.
    pub program: Option<TemperatureProgram>,
}

impl Default for CampaignSettings {
    fn default() -> Self {
        Self {
            temperatures_c: vec![-40.0, -20.0, 0.0, 20.0, 40.0, 60.0],
            duration_s: 10_800.0,
            rate_hz: 200.0,
            jitter_s: 50e-6,
            drop_probability: 0.001,
            wander: ChamberWander {
                sigma_c: 0.05,
                correlation_time_s: 600.0,
            },
            power_ons: 1,
            repeat_duration_s: None,
            ramp: None,
            program: None,
        }
    }
}

/// A linear temperature sweep of the chamber (the PX4 way of thermal calibration: one log
/// while the unit warms or cools through its range).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Ramp {
    /// Start temperature, °C.
    pub start_c: f64,
    /// End temperature, °C.
    pub end_c: f64,
    /// Rate, °C/min (positive; the sign follows from start and end).
    pub rate_c_per_min: f64,
}

impl Ramp {
    /// Length of the sweep, s.
    pub fn duration_s(&self) -> f64 {
        (self.end_c - self.start_c).abs() / self.rate_c_per_min * 60.0
    }

    /// The ramp's temperature `t_s` after its start, °C (the end value held after the end).
    pub fn temperature_at(&self, t_s: f64) -> f64 {
        let step = self.rate_c_per_min / 60.0 * t_s.max(0.0);
        let span = self.end_c - self.start_c;
        self.start_c + span.signum() * step.min(span.abs())
    }
}

/// The chamber's temperature during a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ChamberTemperature {
    /// Held at a set point, °C.
    SetPoint {
        /// The set point, °C.
        temperature_c: f64,
    },
    /// Swept linearly.
    Ramp(Ramp),
    /// A chamber program replayed: linear between its rows, its end values held; the
    /// record lasts to its last row.
    Program(TemperatureProgram),
}

impl ChamberTemperature {
    /// The temperature the run is named after and its truth is given at: the set point, or
    /// the middle of the ramp, °C.
    pub fn nominal_c(&self) -> f64 {
        match self {
            Self::SetPoint { temperature_c } => *temperature_c,
            Self::Ramp(r) => 0.5 * (r.start_c + r.end_c),
            Self::Program(p) => {
                let (low, high) = p
                    .temperature_c
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| {
                        (lo.min(t), hi.max(t))
                    });
                0.5 * (low + high)
            }
        }
    }

    /// The temperature `t_s` after the start, before the wander, °C.
    fn at(&self, t_s: f64) -> f64 {
        match self {
            Self::SetPoint { temperature_c } => *temperature_c,
            Self::Ramp(r) => r.temperature_at(t_s),
            Self::Program(p) => p.at(t_s),
        }
    }

    /// The name of the run's generators.
    fn stream_name(&self) -> String {
        match self {
            Self::SetPoint { temperature_c } => temperature_c.to_string(),
            Self::Ramp(_) => "ramp".into(),
            Self::Program(_) => "program".into(),
        }
    }
}

/// What to simulate in one chamber run.
#[derive(Debug, Clone, PartialEq)]
pub struct ChamberRun {
    /// The chamber's temperature.
    pub temperature: ChamberTemperature,
    /// Record length, s (a ramp's own length when it sweeps).
    pub duration_s: f64,
    /// The unit in the chamber.
    pub unit: SimulatedUnit,
    /// Which power-on of the unit this run belongs to (runs of one power-on share its
    /// offset).
    pub power_on: u32,
    /// Sampling clock.
    pub clock: SampleClock,
    /// Site of the chamber.
    pub site: Site,
    /// Temperature wander.
    pub wander: ChamberWander,
    /// User seed; every draw comes from a generator named after the set point and quantity.
    pub seed: u64,
}

/// The true error parameters of one channel during a run (the bank's key names).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelTruth {
    /// Unit of the bias values (`rad/s` or `m/s^2`).
    pub unit: &'static str,
    /// True Gauss-Markov bias at the set point.
    pub gauss_markov: TrueGaussMarkov,
    /// White-noise density N (rad/√s or m/s/√s).
    pub white_noise_density: f64,
    /// Bias random-walk density K.
    pub rate_random_walk: f64,
    /// The unit's fixed bias (the same in every run of the unit).
    pub unit_bias: f64,
    /// This power-on's offset.
    pub power_on_offset: f64,
    /// Deterministic bias at the nominal temperature, c₁ ΔT + c₂ ΔT².
    pub temperature_bias: f64,
    /// The repeatable bias at the nominal temperature: `unit_bias + temperature_bias`.
    pub repeatable_bias: f64,
    /// The true static signal u.
    pub true_signal: f64,
    /// Quantisation step.
    pub quantization_step: f64,
    /// Thermal lag of the structure behind the temperature sensor, s (the recorded
    /// temperature is the sensor's; the temperature terms act at the structure's).
    pub thermal_lag_s: f64,
}

/// True Gauss-Markov parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TrueGaussMarkov {
    /// Correlation time Tc, s.
    pub correlation_time_s: f64,
    /// Standard deviation σ.
    pub sigma: f64,
}

/// The truth of one run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunTruth {
    /// Nominal temperature (set point, or middle of the ramp), °C.
    pub temperature_c: f64,
    /// The chamber's temperature.
    pub chamber: ChamberTemperature,
    /// The power-on the run belongs to.
    pub power_on: u32,
    /// Per channel.
    pub channels: BTreeMap<Channel, ChannelTruth>,
}

/// A simulated record with its truth.
#[derive(Debug, Clone, PartialEq)]
pub struct ChamberRecord {
    /// The IMU series (rates, SI, with temperature).
    pub series: ImuSeries,
    /// The parameters it was drawn with.
    pub truth: RunTruth,
}

/// Why a run cannot be simulated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ChamberError {
    /// Invalid clock or duration.
    #[error(transparent)]
    Clock(#[from] ClockError),
    /// Invalid profile.
    #[error(transparent)]
    Profile(#[from] ProfileError),
    /// Invalid temperature or wander.
    #[error(
        "chamber temperature {set_point_c} °C and wander σ {sigma_c} °C / Tc {correlation_time_s} s must be finite (σ ≥ 0, Tc > 0; a ramp needs distinct finite ends and a positive rate)"
    )]
    Chamber {
        /// Set point.
        set_point_c: f64,
        /// Wander σ.
        sigma_c: f64,
        /// Wander Tc.
        correlation_time_s: f64,
    },
}

/// The default site: Calgary (51.08° N, 1100 m), where the paper's chamber tests were run.
pub fn calgary() -> Site {
    Site {
        latitude_rad: crate::units::deg_to_rad(51.08),
        height_m: 1100.0,
    }
}

/// The true static signal of each channel for a level IMU, x north, at `site`.
pub fn static_signal(site: Site) -> [f64; 6] {
    let w = earth_rate_ned(site.latitude_rad);
    let g = gravity_ned(site.latitude_rad, site.height_m);
    [w[0], w[1], w[2], -g[0], -g[1], -g[2]]
}

/// Simulates one chamber run.
///
/// # Errors
/// [`ChamberError`] for an invalid profile, clock, duration or chamber setting.
pub fn simulate_chamber_run(
    profile: &SensorProfile,
    run: &ChamberRun,
) -> Result<ChamberRecord, ChamberError> {
    profile.validate()?;
    validate_run(run)?;
    let name = run.temperature.stream_name();
    let power_on = run.power_on;
    let stream = |what: &str| named_rng(run.seed, &format!("chamber/{name}/p{power_on}/{what}"));
    let time = run
        .clock
        .timestamps(run_duration_s(run), &mut stream("clock"))?;
    let dt_s = intervals_s(&time);
    let temperature_c = chamber_temperature(run, &dt_s, &mut stream("temperature"));
    let nominal_c = run.temperature.nominal_c();
    let signal = static_signal(run.site);
    let mut series = ImuSeries::new(SampleKind::Rates);
    let mut channels = BTreeMap::new();
    for channel in Channel::ALL {
        let p = &profile.channels[&channel];
        let mut rng = stream(channel.name());
        let constant = ConstantBias {
            unit: run.unit.fixed_bias(profile, channel),
            power_on: run.unit.power_on_offset(
                profile,
                channel,
                run.seed,
                &format!("chamber/{power_on}"),
            ),
        };
        let mut errors = ChannelErrors::new(
            p,
            profile.reference_temperature_c,
            temperature_c[0],
            constant.unit + constant.power_on,
            &mut rng,
        );
        let at = TruthTemperature {
            nominal_c,
            reference_c: profile.reference_temperature_c,
        };
        let truth = channel_truth(p, constant, at, signal[channel.index()], channel);
        series.channels[channel.index()] = channel_values(
            &mut errors,
            truth.true_signal,
            &temperature_c,
            &dt_s,
            &mut rng,
        );
        channels.insert(channel, truth);
    }
    series.time = time;
    series.temperature_c = Some(temperature_c);
    Ok(ChamberRecord {
        series,
        truth: RunTruth {
            temperature_c: nominal_c,
            chamber: run.temperature.clone(),
            power_on,
            channels,
        },
    })
}

/// The record's length: the ramp's for a sweep, the program's to its last row, else the
/// run's.
fn run_duration_s(run: &ChamberRun) -> f64 {
    match &run.temperature {
        ChamberTemperature::Ramp(r) => r.duration_s(),
        ChamberTemperature::Program(p) => p.end_s(),
        ChamberTemperature::SetPoint { .. } => run.duration_s,
    }
}

fn validate_run(run: &ChamberRun) -> Result<(), ChamberError> {
    let w = run.wander;
    let ramp_ok = match &run.temperature {
        ChamberTemperature::Program(p) => p.is_valid() && p.end_s() > 0.0,
        ChamberTemperature::Ramp(r) => {
            r.start_c.is_finite()
                && r.end_c.is_finite()
                && r.start_c != r.end_c
                && r.rate_c_per_min.is_finite()
                && r.rate_c_per_min > 0.0
        }
        ChamberTemperature::SetPoint { .. } => true,
    };
    let ok = ramp_ok
        && run.temperature.nominal_c().is_finite()
        && w.sigma_c.is_finite()
        && w.sigma_c >= 0.0
        && w.correlation_time_s.is_finite()
        && w.correlation_time_s > 0.0;
    if ok {
        Ok(())
    } else {
        Err(ChamberError::Chamber {
            set_point_c: run.temperature.nominal_c(),
            sigma_c: w.sigma_c,
            correlation_time_s: w.correlation_time_s,
        })
    }
}

/// dt_k = t_k − t_{k−1} in seconds, with dt_0 = dt_1 (the first sample's averaging interval is
/// taken as the next one's).
fn intervals_s(time: &[Timestamp]) -> Vec<f64> {
    let mut dt: Vec<f64> = time
        .windows(2)
        .map(|w| w[1].since(w[0]).as_seconds())
        .collect();
    let first = dt.first().copied().unwrap_or(0.0);
    dt.insert(0, first);
    dt
}

/// Set point or ramp plus a stationary Gauss-Markov wander.
fn chamber_temperature(run: &ChamberRun, dt_s: &[f64], rng: &mut SimRng) -> Vec<f64> {
    let w = run.wander;
    let mut x = w.sigma_c * standard_normal(rng);
    let mut elapsed_s = 0.0;
    dt_s.iter()
        .enumerate()
        .map(|(k, &dt)| {
            if k > 0 {
                x = gauss_markov_step(x, dt, w.correlation_time_s, w.sigma_c, standard_normal(rng));
                elapsed_s += dt;
            }
            run.temperature.at(elapsed_s) + x
        })
        .collect()
}

/// The constant bias of a run: the unit's and the power-on's.
#[derive(Debug, Clone, Copy)]
struct ConstantBias {
    unit: f64,
    power_on: f64,
}

/// Where a run's truth is stated: its nominal temperature and the profile's reference, °C.
#[derive(Debug, Clone, Copy)]
struct TruthTemperature {
    nominal_c: f64,
    reference_c: f64,
}

fn channel_truth(
    p: &ChannelProfile,
    constant: ConstantBias,
    at: TruthTemperature,
    true_signal: f64,
    channel: Channel,
) -> ChannelTruth {
    let bias = p.bias_at(at.nominal_c);
    let temperature_bias = p.temperature_bias(at.nominal_c - at.reference_c);
    ChannelTruth {
        unit: channel.si_unit(SampleKind::Rates),
        gauss_markov: TrueGaussMarkov {
            correlation_time_s: bias.correlation_time_s,
            sigma: bias.sigma,
        },
        white_noise_density: p.white_noise_density,
        rate_random_walk: p.bias_random_walk_density,
        unit_bias: constant.unit,
        power_on_offset: constant.power_on,
        temperature_bias,
        repeatable_bias: constant.unit + temperature_bias,
        true_signal,
        quantization_step: p.quantization_step,
        thermal_lag_s: p.thermal_lag_s,
    }
}

/// The measured values of one channel (the Gauss-Markov processes start stationary, so the
/// record has no warm-up transient).
fn channel_values(
    errors: &mut ChannelErrors<'_>,
    u: f64,
    temperature_c: &[f64],
    dt_s: &[f64],
    rng: &mut SimRng,
) -> Vec<f64> {
    dt_s.iter()
        .zip(temperature_c)
        .map(|(&dt, &temp)| errors.measure(u, dt, temp, rng))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensor::{GaussMarkovPoint, adis16364_like};

    /// A profile whose channels carry only what a test switches on.
    fn bare_profile(white: f64, tc_s: f64, sigma: f64) -> SensorProfile {
        let bias = GaussMarkovPoint {
            temperature_c: 0.0,
            correlation_time_s: tc_s,
            sigma,
        };
        adis16364_like().with_every_channel(&ChannelProfile::stochastic_only(white, bias, 0.0))
    }

    fn run(rate_hz: f64, duration_s: f64, seed: u64) -> ChamberRun {
        ChamberRun {
            temperature: ChamberTemperature::SetPoint {
                temperature_c: 20.0,
            },
            duration_s,
            unit: SimulatedUnit::default(),
            power_on: 1,
            clock: SampleClock::new(rate_hz, 0.0, 0.0).unwrap(),
            site: calgary(),
            wander: ChamberWander {
                sigma_c: 0.05,
                correlation_time_s: 600.0,
            },
            seed,
        }
    }

    fn mean_var(x: &[f64]) -> (f64, f64) {
        let n = x.len() as f64;
        let mean = x.iter().sum::<f64>() / n;
        (mean, x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n)
    }

    #[test]
    fn static_signal_is_earth_rate_and_minus_gravity() {
        // Closed form at 51.08° N: ω_ie cos φ north, −ω_ie sin φ down; f_z = −γ.
        let s = static_signal(calgary());
        let lat = 51.08_f64.to_radians();
        assert!((s[0] - 7.292115e-5 * lat.cos()).abs() < 1e-18);
        assert!((s[2] + 7.292115e-5 * lat.sin()).abs() < 1e-18);
        assert!(s[5] < -9.80 && s[5] > -9.82, "{}", s[5]);
    }

    #[test]
    fn white_noise_variance_is_density_squared_over_dt_at_any_rate() {
        // Var = N²/dt. With n samples the sample variance has relative sd √(2/n); at n ≥ 20 000
        // that is ≤ 1 %, so 4 % is four sd.
        let n_density = 1e-3;
        let profile = bare_profile(n_density, 1.0, 1e-12);
        for rate in [20.0, 200.0] {
            let rec = simulate_chamber_run(&profile, &run(rate, 20_000.0 / rate, 1)).unwrap();
            let (_, var) = mean_var(rec.series.channel(Channel::Gx));
            let expected = n_density * n_density * rate;
            assert!(
                (var / expected - 1.0).abs() < 0.04,
                "rate {rate}: {var} vs {expected}"
            );
        }
    }

    #[test]
    fn gauss_markov_bias_has_its_variance_and_correlation_at_any_rate() {
        // Tc = 2 s, σ = 1, 4000 s: about 1000 correlation times. The sample variance of a GM
        // series has relative sd ≈ √(2 Tc/T) ≈ 3 %; 12 % is four sd. Lag-1 correlation
        // φ = exp(−dt/Tc) has sd ≈ √((1−φ²)/n), tiny here; 0.01 absolute is generous and still
        // tells the exact step from the 1 − dt/Tc approximation at 10 Hz (0.9512 vs 0.95).
        let profile = bare_profile(0.0, 2.0, 1.0);
        for rate in [10.0, 1000.0] {
            let rec = simulate_chamber_run(&profile, &run(rate, 4000.0, 2)).unwrap();
            let x = rec.series.channel(Channel::Ay);
            let (mean, var) = mean_var(x);
            assert!((var - 1.0).abs() < 0.12, "rate {rate}: var {var}");
            let lag1 = x
                .windows(2)
                .map(|w| (w[0] - mean) * (w[1] - mean))
                .sum::<f64>()
                / (x.len() as f64 * var);
            let phi = (-1.0 / (rate * 2.0)).exp();
            assert!((lag1 - phi).abs() < 0.01, "rate {rate}: {lag1} vs {phi}");
        }
    }

    #[test]
    fn gauss_markov_autocorrelation_is_exponential_over_many_lags() {
        // Tc = 2 s sampled at 10 Hz for 40 000 s (20 000 correlation times). The sample ACF at
        // lag τ has standard error below √(Tc/T) ≈ 0.007 (Bartlett); 0.03 is four of those,
        // checked at τ = 0.5, 1, 2, 4 and 8 s against exp(−τ/Tc).
        let profile = bare_profile(0.0, 2.0, 1.0);
        let rec = simulate_chamber_run(&profile, &run(10.0, 40_000.0, 5)).unwrap();
        let rho = crate::stoch::acf::autocorrelation(
            rec.series.channel(Channel::Gz),
            80,
            crate::stoch::acf::Demean::Subtract,
        )
        .unwrap();
        for lag in [5, 10, 20, 40, 80] {
            let expected = (-(lag as f64) * 0.1 / 2.0).exp();
            assert!(
                (rho[lag] - expected).abs() < 0.03,
                "lag {lag}: {} vs {expected}",
                rho[lag]
            );
        }
    }

    #[test]
    fn a_lagging_structure_reads_the_bias_of_the_closed_form_lag_on_a_ramp() {
        // A noiseless channel with b = c₁ (T_s − T_ref) on a ramp T(t) = T₀ + r t that starts
        // with the structure at T₀: the first-order lag has the closed form
        // T_s(t) = T(t) − τ r (1 − e^(−t/τ)). The simulator steps it exactly for a linear T, so
        // the reading equals the closed form to rounding (1e-12 of a bias of about 6e-3).
        let tau_s = 150.0;
        let c1 = 1e-4;
        let mut profile = bare_profile(0.0, 1.0, 1e-30);
        for p in profile.channels.values_mut() {
            p.bias_temperature_coefficient_per_c = c1;
            p.thermal_lag_s = tau_s;
        }
        let ramp = Ramp {
            start_c: 0.0,
            end_c: 60.0,
            rate_c_per_min: 2.0,
        };
        let mut chamber = run(4.0, 0.0, 1);
        chamber.temperature = ChamberTemperature::Ramp(ramp);
        chamber.wander.sigma_c = 0.0;
        let rec = simulate_chamber_run(&profile, &chamber).unwrap();
        let u = static_signal(chamber.site)[0];
        let start = rec.series.time[0];
        let r = ramp.rate_c_per_min / 60.0;
        let mut checked = 0;
        for (k, &t) in rec.series.time.iter().enumerate().step_by(37) {
            let t_s = t.since(start).as_seconds();
            let sensor = ramp.temperature_at(t_s);
            let structure = sensor - tau_s * r * (1.0 - (-t_s / tau_s).exp());
            let expected = u + c1 * (structure - profile.reference_temperature_c);
            let got = rec.series.channel(Channel::Gx)[k];
            assert!(
                (got - expected).abs() < 1e-12,
                "t {t_s}: {got} vs {expected}"
            );
            assert!((rec.series.temperature_c.as_ref().unwrap()[k] - sensor).abs() < 1e-9);
            checked += 1;
        }
        assert!(checked > 100);
        assert_eq!(rec.truth.channels[&Channel::Gx].thermal_lag_s, tau_s);
    }

    #[test]
    fn a_program_is_replayed_to_its_last_row() {
        // Cool 20 → −10 °C in 600 s, dwell 300 s: the record lasts 900 s and its temperature
        // column (no wander) is the program's piecewise-linear value.
        let program = TemperatureProgram {
            t_s: vec![0.0, 600.0, 900.0],
            temperature_c: vec![20.0, -10.0, -10.0],
        };
        let mut chamber = run(2.0, 0.0, 4);
        chamber.temperature = ChamberTemperature::Program(program.clone());
        chamber.wander.sigma_c = 0.0;
        let rec = simulate_chamber_run(&adis16364_like(), &chamber).unwrap();
        let time = &rec.series.time;
        let span = time.last().unwrap().since(time[0]).as_seconds();
        assert!((span - 900.0).abs() <= 0.5, "{span}");
        for (t, temp) in time.iter().zip(rec.series.temperature_c.as_ref().unwrap()) {
            let expected = program.at(t.since(time[0]).as_seconds());
            assert!((temp - expected).abs() < 1e-9, "{temp} vs {expected}");
        }
        assert_eq!(rec.truth.temperature_c, 5.0);
    }

    #[test]
    fn runs_are_reproducible_and_seeds_matter() {
        let profile = adis16364_like();
        let a = simulate_chamber_run(&profile, &run(100.0, 5.0, 9)).unwrap();
        let b = simulate_chamber_run(&profile, &run(100.0, 5.0, 9)).unwrap();
        let c = simulate_chamber_run(&profile, &run(100.0, 5.0, 10)).unwrap();
        assert_eq!(a, b);
        assert_ne!(a.series.channels, c.series.channels);
    }

    #[test]
    fn quantised_values_are_multiples_of_the_lsb() {
        let profile = adis16364_like();
        let rec = simulate_chamber_run(&profile, &run(200.0, 2.0, 3)).unwrap();
        let lsb = profile.channels[&Channel::Az].quantization_step;
        for v in rec.series.channel(Channel::Az) {
            assert!(((v / lsb) - (v / lsb).round()).abs() < 1e-6);
        }
        let az_mean = mean_var(rec.series.channel(Channel::Az)).0;
        assert!((az_mean + 9.81).abs() < 0.1, "az reads about −g: {az_mean}");
    }
}
