//! General optimisers: the extremum of a function the caller gives, knowing nothing of what it
//! computes (this module takes nothing from the rest of the crate).
//!
//! Which to use:
//! - [`nelder_mead::nelder_mead`]: the minimum of a function of two variables without
//!   derivatives; each iteration asks for its four candidate points at once
//!   ([`nelder_mead::Objective`]), which pays where evaluating several points costs about what
//!   one does (the noisy Gauss-Markov likelihood's multi-lane Kalman pass).
//! - [`newton::newton_maximum`]: the maximum of a smooth function of one variable, three points
//!   a call, in a few calls near a concave top; `None` where its steps are not to be trusted.
//! - [`brent::brent_maximum`]: the maximum of a unimodal function on a bracket, parabolic steps
//!   safeguarded by golden sections; the fallback where Newton's steps are not trusted.
//! - [`golden_section`]: the maximum (to a width) or the minimum (after a number of steps) of a
//!   unimodal function on a bracket; no smoothness assumed, and each step costs one evaluation.
//! - [`levenberg_marquardt::minimise`]: a sum of squared residuals over a dozen coordinates or so,
//!   with a central-difference Jacobian.
//!
//! Each is tested against closed forms (Rosenbrock's valley, quadratics, x e^{−x}, an exact
//! exponential decay) and, where it evaluates in batches, against the method as first written,
//! one evaluation at a time, bit for bit.

pub mod brent;
pub mod golden_section;
pub mod levenberg_marquardt;
pub mod nelder_mead;
pub mod newton;
