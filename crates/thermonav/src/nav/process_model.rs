//! The process model of the 21-state error filter over one covariance step: what the EKF
//! linearises (Φ from F at the step's start, the discretised Q) and what the UKF propagates
//! through the nonlinear mechanization (each sigma point's nominal mechanized over the step with
//! the summed increments, differenced against the nominal start propagated the same way, and the
//! Gauss-Markov states decayed over the step).

use super::error_state::{ErrorVector, Estimate};
use super::sensor_model::ImuStochasticModel;
use crate::ins::error_model::system_matrix;
use crate::ins::mechanization::mechanize;
use crate::ins::state::Increment;
use crate::ins::transition::{ProcessNoise, Transition};

/// One covariance step: the nominal at its start, the raw increments summed over it, and the
/// model in force.
#[derive(Debug, Clone)]
pub struct ProcessStep {
    start: Estimate,
    raw: Increment,
    transition: Transition,
    noise: ProcessNoise,
    /// exp(−Δt/Tc) of the gyro bias, accelerometer bias, gyro scale and accelerometer scale
    /// states, three axes each.
    decay: [[f64; 3]; 4],
}

impl ProcessStep {
    /// The step from `start` over the summed raw increments `raw`, with `model`.
    pub fn new(start: &Estimate, raw: &Increment, model: &ImuStochasticModel) -> Self {
        let dt = raw.dt_s();
        let corrected = start.sensors.correct(raw);
        let f = system_matrix(
            &start.nav,
            &corrected.delta_angle.scale(1.0 / dt),
            &corrected.delta_velocity.scale(1.0 / dt),
            &model.correlation_times(),
        );
        let transition = model.transition_matrix(&f, dt);
        let noise = model.process_noise(&start.nav.attitude, &transition, dt);
        let decay = model
            .gauss_markov_states()
            .map(|(_, group)| group.map(|gm| gm.transition(dt)));
        Self {
            start: *start,
            raw: *raw,
            transition,
            noise,
            decay,
        }
    }

    /// Φ of the linearised error dynamics over the step.
    pub fn transition(&self) -> &Transition {
        &self.transition
    }

    /// The process noise Q over the step.
    pub fn noise(&self) -> &ProcessNoise {
        &self.noise
    }

    /// The nominal start mechanized over the step with its own corrections: what the
    /// propagated sigma points are differenced against.
    pub fn reference(&self) -> Estimate {
        let corrected = self.start.sensors.correct(&self.raw);
        Estimate {
            nav: mechanize(&self.start.nav, &corrected, &corrected),
            sensors: self.start.sensors,
        }
    }

    /// The error δx at the step's start carried through the nonlinear model to its end,
    /// relative to `reference` ([`Self::reference`]).
    pub fn propagate_error(&self, dx: &ErrorVector, reference: &Estimate) -> ErrorVector {
        let point = self.start.corrected_by(dx);
        let inc = point.sensors.correct(&self.raw);
        let moved = Estimate {
            nav: mechanize(&point.nav, &inc, &inc),
            sensors: point.sensors,
        };
        let mut out = moved.error_from(reference);
        for (g, factors) in self.decay.iter().enumerate() {
            for (k, factor) in factors.iter().enumerate() {
                out[9 + 3 * g + k] *= factor;
            }
        }
        out
    }
}
