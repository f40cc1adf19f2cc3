//! AR estimators against R, MATLAB, Stata/gretl, statsmodels, spectrum and numpy oracles, slow
//! reference implementations and closed forms.

pub mod data;

mod burg;
mod errors;
mod least_squares;
mod ljung_box;
mod real_data;
mod selection;
mod std_errors;
mod yule_walker;
