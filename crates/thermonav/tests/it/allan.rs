//! Allan deviation, confidence intervals and noise-term fit (`thermonav::stoch::allan`)
//! against allantools, Stable32, NIST SP 1065 published values and closed forms.

mod confidence;
mod data;
mod deviation;
mod noise_terms;
