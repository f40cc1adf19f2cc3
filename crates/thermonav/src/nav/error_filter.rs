//! The error-state filters behind one interface: the EKF and the UKF both predict over a
//! [`ProcessStep`] and update with a [`Measurement`], taking the filter by value and giving back
//! the new one, so that the engine can keep the old one when the gate rejects an update.

use super::error_state::ErrorVector;
use super::measurement::Linearized;
use super::process_model::ProcessStep;
use crate::filter::FilterError;
use crate::filter::ekf::joseph_update;
use crate::filter::sigma_points::SigmaPointScheme;
use crate::filter::ukf::Ukf;
use crate::ins::error_model::{STATES, SystemMatrix};
use nalgebra::{SMatrix, SVector};

/// A measurement as both filters see it: the EKF its linearisation, the UKF the nonlinear model
/// `model` (the measurement relative to the nominal prediction, so that `model(0) = 0`) with the
/// measured `z` on the same scale.
pub struct Measurement<'h, const M: usize> {
    /// Residual, Jacobian and noise.
    pub linearized: Linearized<M>,
    /// The measurement minus the nominal prediction.
    pub z: SVector<f64, M>,
    /// The prediction at the nominal corrected by δx, minus the nominal prediction.
    pub model: &'h dyn Fn(&ErrorVector) -> SVector<f64, M>,
}

/// A filter after a prediction, and the error-state mean to fold into the nominal when the
/// prediction moved it (the UKF's; the EKF's mean stays zero).
pub struct Predicted<F> {
    /// The filter.
    pub filter: F,
    /// The mean error to fold into the nominal, if any.
    pub shift: Option<ErrorVector>,
}

/// A filter after an update, the correction to fold into the nominal, and the innovation.
pub struct Updated<F, const M: usize> {
    /// The filter (its error mean reset to zero).
    pub filter: F,
    /// The correction δx.
    pub correction: ErrorVector,
    /// Measured minus predicted.
    pub innovation: SVector<f64, M>,
    /// Its covariance S.
    pub covariance: SMatrix<f64, M, M>,
    /// νᵀ S⁻¹ ν.
    pub nis: f64,
}

/// What the engine needs of an error-state filter.
pub trait ErrorStateFilter: Clone + Sized {
    /// The error-state covariance.
    fn covariance(&self) -> &SystemMatrix;
    /// Propagates over one step.
    ///
    /// # Errors
    /// [`FilterError`] when the covariance stops being usable.
    fn predict(self, step: &ProcessStep) -> Result<Predicted<Self>, FilterError>;
    /// Applies one measurement.
    ///
    /// # Errors
    /// [`FilterError`] for a singular innovation or an unusable covariance.
    fn update<const M: usize>(
        self,
        measurement: &Measurement<'_, M>,
    ) -> Result<Updated<Self, M>, FilterError>;
}

/// The extended filter: P propagated by Φ and Q, Joseph-form updates. P is boxed so that
/// moving the filter by value (every covariance step) moves a pointer, not 3.5 kB.
#[derive(Debug, Clone)]
pub struct ErrorEkf {
    p: Box<SystemMatrix>,
}

impl ErrorEkf {
    /// The filter with covariance `p0`.
    pub fn new(p0: SystemMatrix) -> Self {
        Self { p: Box::new(p0) }
    }
}

impl ErrorStateFilter for ErrorEkf {
    fn covariance(&self) -> &SystemMatrix {
        &self.p
    }

    fn predict(mut self, step: &ProcessStep) -> Result<Predicted<Self>, FilterError> {
        *self.p = step.transition().propagate(&self.p, step.noise());
        Ok(Predicted {
            filter: self,
            shift: None,
        })
    }

    fn update<const M: usize>(
        mut self,
        measurement: &Measurement<'_, M>,
    ) -> Result<Updated<Self, M>, FilterError> {
        let lin = &measurement.linearized;
        let mut x = ErrorVector::zeros();
        let innovation = joseph_update(
            &mut x,
            &mut self.p,
            &lin.residual,
            &lin.jacobian,
            &lin.noise,
        )?;
        Ok(Updated {
            filter: self,
            correction: x,
            innovation: -innovation.residual,
            covariance: innovation.covariance,
            nis: innovation.nis,
        })
    }
}

/// The unscented filter: sigma points through the nonlinear process and measurement models.
#[derive(Debug, Clone)]
pub struct ErrorUkf {
    inner: Box<Ukf<STATES>>,
}

impl ErrorUkf {
    /// The filter with covariance `p0` and the sigma points of `scheme`.
    pub fn new(p0: SystemMatrix, scheme: SigmaPointScheme) -> Self {
        Self {
            inner: Box::new(Ukf::new(ErrorVector::zeros(), p0, scheme)),
        }
    }
}

impl ErrorStateFilter for ErrorUkf {
    fn covariance(&self) -> &SystemMatrix {
        &self.inner.p
    }

    fn predict(mut self, step: &ProcessStep) -> Result<Predicted<Self>, FilterError> {
        let reference = step.reference();
        self.inner.predict(
            |dx| step.propagate_error(dx, &reference),
            &step.noise().to_matrix(),
        )?;
        let shift = self.inner.x;
        self.inner.x = ErrorVector::zeros();
        Ok(Predicted {
            filter: self,
            shift: Some(shift),
        })
    }

    fn update<const M: usize>(
        mut self,
        measurement: &Measurement<'_, M>,
    ) -> Result<Updated<Self, M>, FilterError> {
        let innovation = self.inner.update(
            &measurement.z,
            measurement.model,
            &measurement.linearized.noise,
        )?;
        let correction = self.inner.x;
        self.inner.x = ErrorVector::zeros();
        Ok(Updated {
            filter: self,
            correction,
            innovation: innovation.residual,
            covariance: innovation.covariance,
            nis: innovation.nis,
        })
    }
}

/// The filter a run chose: either one, behind the same interface. (The EKF's covariance is kept
/// inline, on purpose: it is copied for every gated update and moved at every step, which a box
/// would turn into an allocation each.)
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
pub enum ChosenFilter {
    /// The EKF.
    Ekf(ErrorEkf),
    /// The UKF.
    Ukf(ErrorUkf),
}

impl ChosenFilter {
    /// An EKF with a zero covariance, to stand in while the filter is moved out by value
    /// (made once per run and swapped in and out: no allocation per step).
    pub fn stand_in() -> Self {
        Self::Ekf(ErrorEkf::new(SystemMatrix::zeros()))
    }
}

impl ErrorStateFilter for ChosenFilter {
    fn covariance(&self) -> &SystemMatrix {
        match self {
            Self::Ekf(f) => f.covariance(),
            Self::Ukf(f) => f.covariance(),
        }
    }

    fn predict(self, step: &ProcessStep) -> Result<Predicted<Self>, FilterError> {
        Ok(match self {
            Self::Ekf(f) => f.predict(step)?.map(Self::Ekf),
            Self::Ukf(f) => f.predict(step)?.map(Self::Ukf),
        })
    }

    fn update<const M: usize>(
        self,
        measurement: &Measurement<'_, M>,
    ) -> Result<Updated<Self, M>, FilterError> {
        Ok(match self {
            Self::Ekf(f) => f.update(measurement)?.map(Self::Ekf),
            Self::Ukf(f) => f.update(measurement)?.map(Self::Ukf),
        })
    }
}

impl<F> Predicted<F> {
    /// The same prediction with the filter wrapped by `wrap`.
    pub fn map<G>(self, wrap: impl FnOnce(F) -> G) -> Predicted<G> {
        Predicted {
            filter: wrap(self.filter),
            shift: self.shift,
        }
    }
}

impl<F, const M: usize> Updated<F, M> {
    /// The same update with the filter wrapped by `wrap`.
    pub fn map<G>(self, wrap: impl FnOnce(F) -> G) -> Updated<G, M> {
        Updated {
            filter: wrap(self.filter),
            correction: self.correction,
            innovation: self.innovation,
            covariance: self.covariance,
            nis: self.nis,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::Vector;
    use crate::ins::state::Increment;
    use crate::nav::error_state::sample_estimate;
    use crate::nav::measurement::{AntennaGeometry, antenna_position, position_linearized};
    use crate::nav::sensor_model::ScaleFactorPrior;
    use crate::sensor::adis16364_like;
    use crate::time::{Duration, Timestamp};

    /// A covariance small enough for the error dynamics to be linear over one step (1 cm, 1 mm/s,
    /// 10 µrad and bias-sized sensor sds), so that the two filters must agree.
    fn small_covariance() -> SystemMatrix {
        let sd = [
            0.01, 0.01, 0.01, 1e-3, 1e-3, 1e-3, 1e-5, 1e-5, 1e-5, 1e-5, 1e-5, 1e-5, 1e-4, 1e-4,
            1e-4, 1e-5, 1e-5, 1e-5, 1e-5, 1e-5, 1e-5,
        ];
        SystemMatrix::from_diagonal(&SVector::from(sd.map(|s: f64| s * s)))
    }

    fn step() -> ProcessStep {
        let model = adis16364_like()
            .stochastic_model(17.0, &ScaleFactorPrior::default())
            .unwrap();
        let raw = Increment {
            time: Timestamp::from_nanos(100_000_000),
            dt: Duration::from_nanos(100_000_000),
            delta_angle: Vector::new(0.002, -0.001, 0.01),
            delta_velocity: Vector::new(0.1, 0.02, -0.98),
        };
        ProcessStep::new(&sample_estimate(), &raw, &model)
    }

    // One interface, two algorithms: on a covariance this small the UKF's sigma points through
    // the nonlinear mechanization give the EKF's ΦPΦᵀ + Q, each entry within 1 % of
    // √(PᵢᵢPⱼⱼ) (what is left is the second-order terms and the UKF's mean shift, itself below
    // 1e-3 of the sds).
    #[test]
    fn the_ekf_and_the_ukf_predict_alike_on_a_small_covariance() {
        let step = step();
        let scheme = SigmaPointScheme::MerweScaled {
            alpha: 1.0,
            beta: 2.0,
            kappa: 0.0,
        };
        let ekf = ErrorEkf::new(small_covariance()).predict(&step).unwrap();
        let ukf = ErrorUkf::new(small_covariance(), scheme)
            .predict(&step)
            .unwrap();
        assert!(ekf.shift.is_none());
        let (a, b) = (ekf.filter.covariance(), ukf.filter.covariance());
        for i in 0..STATES {
            let shift = ukf.shift.unwrap()[i];
            assert!(shift.abs() < 1e-3 * a[(i, i)].sqrt(), "shift {i}: {shift}");
            for j in 0..STATES {
                let scale = (a[(i, i)] * a[(j, j)]).sqrt();
                assert!((a[(i, j)] - b[(i, j)]).abs() < 0.01 * scale, "({i}, {j})");
            }
        }
    }

    // The same for a position update 2 cm off: the corrections agree within 1 % of the position
    // sd, and the innovations (measured minus predicted, the same sign for both) to 1e-9 m.
    #[test]
    fn the_ekf_and_the_ukf_update_alike_on_a_small_covariance() {
        let nominal = sample_estimate();
        let geometry = AntennaGeometry::default();
        let origin = antenna_position(&nominal, &geometry);
        let measured = origin.displaced(&Vector::new(0.02, -0.01, 0.005));
        let lin = position_linearized(&nominal, &geometry, &measured, [0.01; 3]);
        let z = measured.ned_from(&origin).raw();
        let model = |dx: &ErrorVector| {
            antenna_position(&nominal.corrected_by(dx), &geometry)
                .ned_from(&origin)
                .raw()
        };
        let measurement = Measurement {
            linearized: lin,
            z,
            model: &model,
        };
        let scheme = SigmaPointScheme::MerweScaled {
            alpha: 1.0,
            beta: 2.0,
            kappa: 0.0,
        };
        let ekf = ErrorEkf::new(small_covariance())
            .update(&measurement)
            .unwrap();
        let ukf = ErrorUkf::new(small_covariance(), scheme)
            .update(&measurement)
            .unwrap();
        for k in 0..3 {
            assert!((ekf.innovation[k] - ukf.innovation[k]).abs() < 1e-9);
            assert!((ekf.correction[k] - ukf.correction[k]).abs() < 1e-4);
        }
        assert!((ekf.nis - ukf.nis).abs() < 1e-6 * ekf.nis.max(1.0));
    }
}
