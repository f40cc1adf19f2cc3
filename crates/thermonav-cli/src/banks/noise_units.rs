//! IEEE 952 noise terms in the units navigation engineers quote, one line of text (the JSON
//! form is [`thermonav_io::noise_terms`]).

use thermonav::stoch::noise_terms::Bound;
pub use thermonav_io::noise_terms::{TermJson, TermsJson, terms_json};

/// One term of the summary line: "N 2.0100 deg/sqrt(h) (1.98-2.04, tau 0.16-10.2 s)".
fn show(name: &str, t: &Option<TermJson>) -> String {
    let Some(t) = t else {
        return format!("{name} n/a");
    };
    let relation = if t.bound == Bound::AtMost { "<=" } else { "" };
    let ci = (t.ci_low.zip(t.ci_high)).map_or(String::new(), |(l, h)| format!("{l:.4}-{h:.4}, "));
    format!(
        "{name} {relation}{:.4} {} ({ci}tau {}-{} s)",
        t.value, t.unit, t.tau_min_s, t.tau_max_s
    )
}

/// One line summary: "N 2.0100 deg/sqrt(h) (…), B <=24.3000 deg/h (…), K n/a, Q n/a".
pub fn terms_line(t: &TermsJson) -> String {
    [
        show("N", &t.random_walk),
        show("B", &t.bias_instability),
        show("K", &t.rate_random_walk),
        show("Q", &t.quantization),
    ]
    .join(", ")
}
