//! `ar` and `gauss_markov`: autoregressive models and the bank's three Gauss-Markov families,
//! with the library functions `thermonav ar` and `thermonav characterize` call.

use crate::arrays::{
    array, check_finite, check_same_length, median_interval_s, samples, timestamps,
};
use crate::{error, to_python};
use numpy::PyReadonlyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use thermonav::stoch::ar::order::{Criterion, DEFAULT_AUTO_MAX_ORDER, Order, fit_ar_order};
use thermonav::stoch::ar::{ArMethod, ArModel, MAX_AR_ORDER, fit_ar};
use thermonav::stoch::bank::{GaussMarkovEstimate, GaussMarkovSource};
use thermonav::stoch::gauss_markov::LagWindow;
use thermonav::stoch::gm_family::acf_fit::acf_model;
use thermonav::stoch::gm_family::ar_based::from_ar1;
use thermonav::stoch::noisy_gauss_markov::fit_noisy_gauss_markov;

/// The estimator called `name` (yule-walker, burg, covariance, modified-covariance).
fn method_of(name: &str) -> PyResult<ArMethod> {
    ArMethod::from_name(name).ok_or_else(|| {
        error(format!(
            "method {name:?}: expected \"yule-walker\", \"burg\", \"covariance\" or \"modified-covariance\""
        ))
    })
}

/// The order: an integer, or "auto" (BIC up to `max_order`), in the range the library's
/// [`Order::validate`] accepts.
fn order_of(order: &Bound<'_, PyAny>, max_order: usize) -> PyResult<Order> {
    let auto = order.cast::<PyString>().map(|s| s.to_string());
    let (order, option) = match auto.as_deref() {
        Ok("auto") => (
            Order::Auto {
                criterion: Criterion::Bic,
                max_order,
            },
            format!("max_order {max_order}"),
        ),
        _ => match order.extract::<usize>() {
            Ok(p) => (Order::Fixed(p), format!("order {p}")),
            Err(_) => {
                return Err(error(format!(
                    "order {order}: expected an integer from 1 to {MAX_AR_ORDER} (the fit costs samples × order²) or \"auto\""
                )));
            }
        },
    };
    order
        .validate()
        .map_err(|e| error(format!("{option}: {e}")))?;
    Ok(order)
}

/// The AR-based Gauss-Markov model of an AR(1) fit (the paper's eqs 8-10), with its c₁, as
/// `thermonav ar --json`'s `gauss_markov`.
fn ar_based_model<'py>(py: Python<'py>, ar1: &ArModel, dt_s: f64) -> PyResult<Bound<'py, PyAny>> {
    let model = to_python(py, &from_ar1(ar1, dt_s))?;
    model.set_item("c1", ar1.coefficients[0])?;
    Ok(model)
}

/// An AR model of `x` (module docs of the Python package: `thermonav.ar`).
#[pyfunction]
#[pyo3(signature = (x, method=ArMethod::default().name(), order=None, max_order=DEFAULT_AUTO_MAX_ORDER, dt_s=None))]
pub fn ar<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    method: &str,
    order: Option<&Bound<'py, PyAny>>,
    max_order: usize,
    dt_s: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let method = method_of(method)?;
    let order = match order {
        Some(order) => order_of(order, max_order)?,
        None => order_of(PyString::new(py, "auto").as_any(), max_order)?,
    };
    let x = samples(&x);
    check_finite("x", &x)?;
    let (model, ar1) = py
        .detach(|| {
            Ok::<_, thermonav::stoch::ar::ArError>((
                fit_ar_order(&x, order, method)?,
                fit_ar(&x, 1, method)?,
            ))
        })
        .map_err(error)?;
    let out = PyDict::new(py);
    out.set_item("method", method.name())?;
    out.set_item("order", model.order())?;
    out.set_item("coefficients", array(py, model.coefficients))?;
    out.set_item("coefficient_std_errors", array(py, model.std_errors))?;
    out.set_item("noise_variance", model.noise_variance)?;
    if let Some(dt_s) = dt_s {
        out.set_item("sample_interval_s", dt_s)?;
        out.set_item("gauss_markov", ar_based_model(py, &ar1, dt_s)?)?;
    }
    Ok(out)
}

/// A first-order Gauss-Markov model of samples `x` at times `t_s` (module docs of the Python
/// package: `thermonav.gauss_markov`).
#[pyfunction]
#[pyo3(signature = (t_s, x, family=GaussMarkovSource::default().name(), method=ArMethod::default().name()))]
pub fn gauss_markov<'py>(
    py: Python<'py>,
    t_s: PyReadonlyArray1<'py, f64>,
    x: PyReadonlyArray1<'py, f64>,
    family: &str,
    method: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let (t, x) = (samples(&t_s), samples(&x));
    check_same_length(["t_s", "x"], [t.len(), x.len()])?;
    check_finite("x", &x)?;
    let times = timestamps("t_s", &t)?;
    let model = match family {
        "irregular_ml" => {
            let outcome = py
                .detach(|| fit_noisy_gauss_markov(&t, &x))
                .map_err(error)?;
            to_python(py, &outcome)?
        }
        "ar_based" => {
            let (method, dt_s) = (method_of(method)?, median_interval_s("t_s", &times)?);
            let ar1 = py.detach(|| fit_ar(&x, 1, method)).map_err(error)?;
            with_interval(ar_based_model(py, &ar1, dt_s)?, dt_s)?
        }
        "acf_fit" => {
            let dt_s = median_interval_s("t_s", &times)?;
            let fit: GaussMarkovEstimate =
                py.detach(|| acf_model(&x, dt_s, LagWindow::FirstZeroCrossing));
            with_interval(to_python(py, &fit)?, dt_s)?
        }
        other => {
            return Err(error(format!(
                "family {other:?}: expected \"irregular_ml\", \"ar_based\" or \"acf_fit\""
            )));
        }
    };
    model.set_item("family", family)?;
    Ok(model)
}

/// `model` with the sampling interval it was computed with.
fn with_interval(model: Bound<'_, PyAny>, dt_s: f64) -> PyResult<Bound<'_, PyAny>> {
    model.set_item("sample_interval_s", dt_s)?;
    Ok(model)
}
