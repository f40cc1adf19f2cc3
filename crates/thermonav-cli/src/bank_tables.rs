//! The bank as text: correlation times with their intervals, per temperature and channel.

use thermonav::stoch::bank::{GaussMarkovEstimate, ModelBank};

/// "123.4 s [100.2, 150.3]" or "none".
pub fn show_estimate(e: &GaussMarkovEstimate) -> String {
    match e {
        GaussMarkovEstimate::Model {
            correlation_time_s,
            ci95_correlation_time_s: [None, None],
            ..
        } => format!("{correlation_time_s:.1}"),
        GaussMarkovEstimate::Model {
            correlation_time_s,
            ci95_correlation_time_s: [lo, hi],
            ..
        } => {
            let side = |v: &Option<f64>| v.map_or("inf".to_string(), |v| format!("{v:.1}"));
            format!("{correlation_time_s:.1} [{}, {}]", side(lo), side(hi))
        }
        GaussMarkovEstimate::NoEquivalent { .. } => "none".to_string(),
    }
}

/// The bank as a table of correlation times.
pub fn print_bank_table(bank: &ModelBank) {
    println!(
        "{:>7} {:<4} {:>28} {:>28} {:>16}",
        "temp_C", "ch", "Tc exact ML s [95 %]", "Tc AR-based s [95 %]", "Tc ACF fit s"
    );
    for e in &bank.entries {
        for (c, m) in &e.channels {
            let g = &m.gauss_markov;
            println!(
                "{:>7.1} {:<4} {:>28} {:>28} {:>16}",
                e.temperature_c,
                c.name(),
                show_estimate(&g.irregular_ml),
                show_estimate(&g.ar_based),
                show_estimate(&g.acf_fit)
            );
        }
    }
}
