//! A static IMU in a thermal chamber: the records the method starts from.
//!
//! The IMU sits level, x axis north, at a known site. Each channel reads the true static
//! signal (Earth rate for gyros, specific force −g along z for accelerometers, see
//! CONVENTIONS.md) through its error model at the chamber's temperature:
//!
//! y_k = (1 + s_k) u + b_on + c (T_k − T_ref) + b_GM,k + b_RW,k + n_k, then quantised,
//!
//! with u the true signal, s_k the scale-factor error (deterministic temperature term plus an
//! optional Gauss-Markov term, in ppm), b_on the turn-on bias, c the bias temperature
//! coefficient, T_k the chamber temperature (set point plus a slow Gauss-Markov wander), b_GM
//! the temperature-dependent Gauss-Markov bias, b_RW a bias random walk and n_k white noise of
//! density N averaged over the actual interval (variance N²/dt_k). Every process steps with
//! the actual dt_k of its sample.

use super::clock::{ClockError, SampleClock};
use super::errors::{ChannelErrors, gauss_markov_step, standard_normal};
use crate::geo::{gravity::gravity_ned, wgs84::earth_rate_ned};
use crate::imu::{Channel, ImuSeries, SampleKind};
use crate::rng::{SimRng, named_rng};
use crate::sensor::{ChannelProfile, ProfileError, SensorProfile};
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
        }
    }
}

/// What to simulate at one temperature.
#[derive(Debug, Clone, PartialEq)]
pub struct ChamberRun {
    /// Chamber set point, °C.
    pub set_point_c: f64,
    /// Record length, s.
    pub duration_s: f64,
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
    /// Turn-on bias drawn for this run.
    pub turn_on_bias: f64,
    /// Deterministic bias at the set point, c (T − T_ref).
    pub temperature_bias: f64,
    /// The true static signal u.
    pub true_signal: f64,
    /// Quantisation step.
    pub quantization_step: f64,
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
    /// Set point, °C.
    pub temperature_c: f64,
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
        "chamber set point {set_point_c} °C and wander σ {sigma_c} °C / Tc {correlation_time_s} s must be finite (σ ≥ 0, Tc > 0)"
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
    let stream = |what: &str| named_rng(run.seed, &format!("chamber/{}/{what}", run.set_point_c));
    let time = run.clock.timestamps(run.duration_s, &mut stream("clock"))?;
    let dt_s = intervals_s(&time);
    let temperature_c = chamber_temperature(run, &dt_s, &mut stream("temperature"));
    let signal = static_signal(run.site);
    let mut series = ImuSeries::new(SampleKind::Rates);
    let mut channels = BTreeMap::new();
    for channel in Channel::ALL {
        let p = &profile.channels[&channel];
        let mut rng = stream(channel.name());
        let mut errors = ChannelErrors::new(
            p,
            profile.reference_temperature_c,
            run.set_point_c,
            &mut rng,
        );
        let truth = channel_truth(
            p,
            &errors,
            profile.reference_temperature_c,
            run.set_point_c,
            signal[channel.index()],
            channel,
        );
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
            temperature_c: run.set_point_c,
            channels,
        },
    })
}

fn validate_run(run: &ChamberRun) -> Result<(), ChamberError> {
    let w = run.wander;
    let ok = run.set_point_c.is_finite()
        && w.sigma_c.is_finite()
        && w.sigma_c >= 0.0
        && w.correlation_time_s.is_finite()
        && w.correlation_time_s > 0.0;
    if ok {
        Ok(())
    } else {
        Err(ChamberError::Chamber {
            set_point_c: run.set_point_c,
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

/// Set point plus a stationary Gauss-Markov wander.
fn chamber_temperature(run: &ChamberRun, dt_s: &[f64], rng: &mut SimRng) -> Vec<f64> {
    let w = run.wander;
    let mut x = w.sigma_c * standard_normal(rng);
    dt_s.iter()
        .enumerate()
        .map(|(k, &dt)| {
            if k > 0 {
                x = gauss_markov_step(x, dt, w.correlation_time_s, w.sigma_c, standard_normal(rng));
            }
            run.set_point_c + x
        })
        .collect()
}

fn channel_truth(
    p: &ChannelProfile,
    errors: &ChannelErrors<'_>,
    reference_c: f64,
    set_point_c: f64,
    true_signal: f64,
    channel: Channel,
) -> ChannelTruth {
    let bias = errors.bias_parameters();
    ChannelTruth {
        unit: channel.si_unit(SampleKind::Rates),
        gauss_markov: TrueGaussMarkov {
            correlation_time_s: bias.correlation_time_s,
            sigma: bias.sigma,
        },
        white_noise_density: p.white_noise_density,
        rate_random_walk: p.bias_random_walk_density,
        turn_on_bias: errors.turn_on_bias(),
        temperature_bias: p.bias_temperature_coefficient_per_c * (set_point_c - reference_c),
        true_signal,
        quantization_step: p.quantization_step,
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
            set_point_c: 20.0,
            duration_s,
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
