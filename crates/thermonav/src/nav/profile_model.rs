//! The filter's model of an IMU taken from the description of its errors: the model a sensor
//! profile implies at a temperature ([`SensorProfile::stochastic_model`]) and the one a data
//! sheet's figures imply ([`DatasheetValues::model`]). The profile and the data sheet describe
//! the sensor ([`crate::sensor`], which knows nothing of the filter); the filter builds its
//! model from them here.

use super::sensor_model::{
    AxisModel, GaussMarkovParameters, ImuStochasticModel, ScaleFactorPrior, SensorModelError,
};
use crate::imu::Channel;
use crate::sensor::{DatasheetValues, SensorProfile};
use crate::stoch::noise_terms::GAUSS_MARKOV_ADEV_PEAK_RATIO;
use crate::units::{
    arw_deg_per_sqrt_h_to_rad_per_sqrt_s, deg_to_rad, mg_to_m_per_s2,
    vrw_m_per_s_per_sqrt_h_to_m_per_s_per_sqrt_s,
};

impl DatasheetValues {
    /// The filter model these figures imply.
    pub fn model(&self, scale: &ScaleFactorPrior) -> ImuStochasticModel {
        let axis = |white: f64, stability: f64, scale_factor| AxisModel {
            white_noise_density: white,
            bias: GaussMarkovParameters {
                correlation_time_s: self.correlation_time_s,
                sigma: stability / GAUSS_MARKOV_ADEV_PEAK_RATIO,
            },
            scale_factor,
        };
        let gyro = axis(
            arw_deg_per_sqrt_h_to_rad_per_sqrt_s(self.gyro_arw_deg_sqrt_h),
            deg_to_rad(self.gyro_bias_stability_deg_s),
            scale.gyro,
        );
        let accel = axis(
            vrw_m_per_s_per_sqrt_h_to_m_per_s_per_sqrt_s(self.accel_vrw_m_s_sqrt_h),
            mg_to_m_per_s2(self.accel_bias_stability_mg),
            scale.accel,
        );
        ImuStochasticModel {
            gyro: [gyro; 3],
            accel: [accel; 3],
        }
    }
}

impl SensorProfile {
    /// The model a sensor profile implies at `temperature_c`: its white-noise densities, its
    /// Gauss-Markov bias at that temperature, its scale-factor Gauss-Markov process where it
    /// has one and the prior otherwise. For simulated data this is the true model; for a
    /// data-sheet profile it is the temperature-blind baseline.
    ///
    /// # Errors
    /// [`SensorModelError::Parameter`] when a channel is missing or a value is unusable.
    pub fn stochastic_model(
        &self,
        temperature_c: f64,
        scale: &ScaleFactorPrior,
    ) -> Result<ImuStochasticModel, SensorModelError> {
        let axis = |channel: Channel, prior: GaussMarkovParameters| {
            let p = self
                .channel(channel)
                .ok_or_else(|| SensorModelError::Parameter {
                    what: format!("profile channel {}", channel.name()),
                    value: f64::NAN,
                })?;
            let bias = p.bias_at(temperature_c);
            Ok::<_, SensorModelError>(AxisModel {
                white_noise_density: p.white_noise_density,
                bias: GaussMarkovParameters {
                    correlation_time_s: bias.correlation_time_s,
                    sigma: bias.sigma,
                },
                scale_factor: p.scale_factor_gauss_markov.map_or(prior, |g| {
                    GaussMarkovParameters {
                        correlation_time_s: g.correlation_time_s,
                        sigma: g.sigma_ppm * 1e-6,
                    }
                }),
            })
        };
        ImuStochasticModel::from_axes(axis, scale)
    }
}
