//! The Rauch-Tung-Striebel smoother for the error-state EKF: the forward run keeps, for every
//! covariance step k, its filtered start (estimate X_f(k) and covariance P_f(k), after the
//! updates at that time), the transition Φ_k, and the predicted end (X_p(k+1), P_p(k+1), before
//! the updates there). The backward pass then runs from the last filtered state:
//!
//! - gain C_k = P_f(k) Φ_kᵀ P_p(k+1)⁻¹;
//! - the smoothed state's error against the prediction, δ = X_s(k+1) ⊖ X_p(k+1), in the
//!   filter's own error convention ([`Estimate::error_from`]);
//! - X_s(k) = X_f(k) ⊕ C_k δ ([`Estimate::corrected_by`]);
//! - P_s(k) = P_f(k) + C_k (P_s(k+1) − P_p(k+1)) C_kᵀ.
//!
//! With feedback (the filter resets its error state after each update) the forward error
//! states are zero at every step's start, so this total-state form is the whole smoother
//! (Groves 2013, §3.4.2; Särkkä 2013, §8.2). The history costs three 21 × 21 matrices and two
//! estimates per step (about 11 KB), which [`MAX_SMOOTHED_STEPS`] bounds.

use super::error_state::Estimate;
use super::outage::Outages;
use super::solution::SolutionEpoch;
use crate::ins::error_model::SystemMatrix;

/// The most covariance steps a smoothed run keeps (about 11 KB each: 330 MB): 9 h at 1 Hz,
/// 55 min at the default 10 Hz. A longer run is refused before it starts.
pub const MAX_SMOOTHED_STEPS: usize = 30_000;

/// One covariance step of the forward run.
#[derive(Debug, Clone, PartialEq)]
pub struct ForwardStep {
    /// The filtered estimate at the step's start (after the updates at that time).
    pub filtered: Estimate,
    /// Its covariance.
    pub filtered_covariance: SystemMatrix,
    /// The error-state transition over the step.
    pub transition: SystemMatrix,
    /// The predicted estimate at the step's end (before the updates at that time).
    pub predicted: Estimate,
    /// Its covariance.
    pub predicted_covariance: SystemMatrix,
}

/// The forward run's history: its steps and its last filtered state.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ForwardHistory {
    steps: Vec<ForwardStep>,
    open: Option<(Estimate, SystemMatrix)>,
}

/// Why the backward pass stopped.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SmootherError {
    /// A predicted covariance that cannot be inverted.
    #[error(
        "the predicted covariance at t = {time_s:.3} s is not positive definite: the step cannot be smoothed"
    )]
    Singular {
        /// The step's end, s.
        time_s: f64,
    },
    /// Nothing was recorded.
    #[error("the forward run recorded no covariance step to smooth")]
    Empty,
}

impl ForwardHistory {
    /// A step starts from the filtered `estimate` with `covariance`.
    pub fn begin(&mut self, estimate: Estimate, covariance: SystemMatrix) {
        self.open = Some((estimate, covariance));
    }

    /// The open step ends with `transition` at the predicted `estimate` and `covariance`;
    /// the prediction is also the next step's start until an update replaces it.
    pub fn end(&mut self, transition: SystemMatrix, estimate: Estimate, covariance: SystemMatrix) {
        if let Some((filtered, filtered_covariance)) = self.open.take() {
            self.steps.push(ForwardStep {
                filtered,
                filtered_covariance,
                transition,
                predicted: estimate,
                predicted_covariance: covariance,
            });
        }
        self.open = Some((estimate, covariance));
    }

    /// Steps recorded.
    pub fn len(&self) -> usize {
        self.steps.len()
    }

    /// True when no step was recorded.
    pub fn is_empty(&self) -> bool {
        self.steps.is_empty()
    }

    /// The smoothed solution at every step's start and at the run's end (the last filtered
    /// state, which the smoother leaves as it is), in time order.
    ///
    /// # Errors
    /// [`SmootherError`] for no step or a predicted covariance that is not positive definite.
    pub fn smooth(&self, outages: &Outages) -> Result<Vec<SolutionEpoch>, SmootherError> {
        let (last, last_covariance) = self.open.ok_or(SmootherError::Empty)?;
        let mut epochs = Vec::with_capacity(self.steps.len() + 1);
        let (mut state, mut covariance) = (last, last_covariance);
        epochs.push(epoch(&state, &covariance, outages));
        for step in self.steps.iter().rev() {
            (state, covariance) = smoothed_start(step, &state, &covariance)?;
            epochs.push(epoch(&state, &covariance, outages));
        }
        epochs.reverse();
        Ok(epochs)
    }
}

/// One backward step: the smoothed start of `step` from the smoothed state at its end.
fn smoothed_start(
    step: &ForwardStep,
    next: &Estimate,
    next_covariance: &SystemMatrix,
) -> Result<(Estimate, SystemMatrix), SmootherError> {
    let singular = || SmootherError::Singular {
        time_s: step.predicted.nav.time.as_seconds(),
    };
    let cholesky = step.predicted_covariance.cholesky().ok_or_else(singular)?;
    // C = P_f Φᵀ P_p⁻¹, so Cᵀ = P_p⁻¹ Φ P_f (both covariances symmetric).
    let gain = cholesky
        .solve(&(step.transition * step.filtered_covariance))
        .transpose();
    let delta = next.error_from(&step.predicted);
    let state = step.filtered.corrected_by(&(gain * delta));
    let spread = next_covariance - step.predicted_covariance;
    let covariance = step.filtered_covariance + gain * spread * gain.transpose();
    Ok((state, (covariance + covariance.transpose()) * 0.5))
}

fn epoch(state: &Estimate, covariance: &SystemMatrix, outages: &Outages) -> SolutionEpoch {
    SolutionEpoch {
        estimate: *state,
        sd: std::array::from_fn(|i| covariance[(i, i)].max(0.0).sqrt()),
        in_outage: outages.contains(state.nav.time),
    }
}
