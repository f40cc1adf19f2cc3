//! The bank as text: correlation times with their intervals, per temperature and channel,
//! and its thermal calibration per channel in deg/h and mg.

use thermonav::imu::{Channel, SampleKind, Sensor};
use thermonav::stoch::bank::{
    AllanSummary, ChannelModel, GaussMarkovEstimate, GaussMarkovSource, ModelBank,
};
use thermonav::stoch::thermal::clock_drift::{ClockDrift, LegTrend, clock_drift};
use thermonav::stoch::thermal::legs::LegDirection;
use thermonav::stoch::thermal::sweep_model::{ChoiceRule, HeldOutSelection};
use thermonav::stoch::thermal::{
    CalibrationSummary, ChannelCalibration, ScaleFactorCalibration, ThermalCalibration,
};
use thermonav_io::noise_terms::{Units, term_units};
use thermonav_plot::figures::DisplayUnits;

/// Width of a rate column of the thermal table, characters.
const RATE_WIDTH: usize = 17;

/// The title line of the thermal table of static set points.
const THERMAL_TITLE: &str =
    "thermal calibration: repeatable bias b(T) = Σ b_k (T − T_ref)^k, simultaneous 95 % band";

/// The title line of the thermal table of a calibration from sweeps, whose band is the
/// held-out one.
const SWEEP_THERMAL_TITLE: &str = "thermal calibration from sweeps: repeatable bias b(T) = Σ b_k (T − T_ref)^k, 95 % band from the held-out spread (below)";

/// The columns of a thermal row before its rates.
const CURVE_HEAD: &str = "ch   order   Tref_C         range_C";

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

/// The bank as a table of correlation times (or, for a bank from sweeps alone, a line saying
/// it has no noise models), then its thermal calibration when it has one.
pub fn print_bank_table(bank: &ModelBank) {
    if bank.entries.is_empty() {
        println!(
            "no noise models: a thermal calibration alone (from sweeps, whose temperature never holds still, while the Allan, AR and Gauss-Markov fits take a record at one temperature); `--thermal-from` joins it to another bank's noise models"
        );
        bank.thermal.iter().for_each(print_thermal_table);
        return;
    }
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
                show_estimate(g.get(GaussMarkovSource::IRREGULAR_ML)),
                show_estimate(g.get(GaussMarkovSource::AR_BASED)),
                show_estimate(g.get(GaussMarkovSource::ACF_FIT))
            );
        }
    }
    print_noise_terms(bank);
    bank.thermal.iter().for_each(print_thermal_table);
}

/// What the noise-term table's columns are and how B is read.
const NOISE_TERMS_NOTE: &str = "noise terms from the Allan deviation of the raw record (IEEE Std 952): N white noise (angle or velocity random walk); B bias instability = minimum Allan deviation / 0.664 (the flicker floor sits at sqrt(2 ln 2 / pi) = 0.664 B), \"<=\" a bound where the curve's lowest point is its last; K rate random walk; sigma of the exact-ML Gauss-Markov model";

/// Width of a noise-term cell, characters.
const TERM_WIDTH: usize = 22;

/// Per entry and channel: N, B and K with their edge units, and the exact-ML sigma.
fn print_noise_terms(bank: &ModelBank) {
    println!("\n{NOISE_TERMS_NOTE}");
    let head = ["N", "B", "K", "sigma (exact ML)"].map(|h| format!("{h:<TERM_WIDTH$}"));
    println!("{:>7} {:<4} {}", "temp_C", "ch", head.join(" "));
    for e in &bank.entries {
        for (c, m) in &e.channels {
            let cells = noise_term_cells(c.sensor(), m).map(|v| format!("{v:<TERM_WIDTH$}"));
            println!(
                "{:>7.1} {:<4} {}",
                e.temperature_c,
                c.name(),
                cells.join(" ")
            );
        }
    }
}

/// N, B, K and sigma of one channel, each with its unit, or `n/a`.
fn noise_term_cells(sensor: Sensor, m: &ChannelModel) -> [String; 4] {
    let [_, n, b, k, _] = term_units(sensor);
    let allan: &AllanSummary = &m.allan;
    let bias = match (allan.bias_instability, allan.bias_instability_at_most) {
        (Some(v), _) => term_cell("", Some(v), b),
        (None, bound) => term_cell("<=", bound, b),
    };
    let sigma = match m.gauss_markov.get(GaussMarkovSource::IRREGULAR_ML) {
        GaussMarkovEstimate::Model { sigma, .. } => {
            let unit = DisplayUnits::Navigation.rate_unit(sensor);
            format!(
                "{} {unit}",
                significant(DisplayUnits::Navigation.rate(sensor, *sigma))
            )
        }
        GaussMarkovEstimate::NoEquivalent { .. } => "none".to_string(),
    };
    [
        term_cell("", allan.white_noise_density, n),
        bias,
        term_cell("", allan.rate_random_walk, k),
        sigma,
    ]
}

/// "0.2013 deg/sqrt(h)" (with `relation` before the number), or `n/a`.
fn term_cell(relation: &str, si: Option<f64>, (_, unit, to_edge): Units) -> String {
    si.map_or("n/a".to_string(), |v| {
        format!("{relation}{} {unit}", significant(to_edge(v)))
    })
}

/// A value with four significant digits, in decimals between 1e-3 and 1e5.
pub fn significant(value: f64) -> String {
    let magnitude = value.abs();
    if !(1e-3..1e5).contains(&magnitude) {
        return format!("{value:.3e}");
    }
    let decimals = (3 - magnitude.log10().floor() as i32).max(0) as usize;
    format!("{value:.decimals$}")
}

/// The thermal calibration: a table per sensor in deg/h or mg, then what it cannot tell.
pub fn print_thermal_table(calibration: &ThermalCalibration) {
    let from_sweeps = calibration.channels.values().any(|c| c.selection.is_some());
    let title = if from_sweeps {
        SWEEP_THERMAL_TITLE
    } else {
        THERMAL_TITLE
    };
    println!("\n{title}");
    for sensor in [Sensor::Gyro, Sensor::Accelerometer] {
        print_sensor_rows(calibration, sensor);
    }
    print_held_out_choice(calibration);
    println!("{}", scale_factor_note(&calibration.scale_factor));
    print_removed_signal(calibration);
}

/// For a calibration from sweeps: per channel the model chosen on held-out legs, its lag, and
/// the spread its band carries (deg/h or mg); the table above shows the best curve in T alone.
fn print_held_out_choice(calibration: &ThermalCalibration) {
    let chosen: Vec<_> = Channel::ALL
        .into_iter()
        .filter_map(|c| Some((c, calibration.channels.get(&c)?)))
        .filter_map(|(c, cal)| Some((c, cal, cal.selection.as_ref()?)))
        .collect();
    if chosen.is_empty() {
        return;
    }
    let legs = calibration.legs.len();
    println!(
        "model chosen on held-out data ({legs} leg{}; the table shows the best curve in T alone):",
        if legs == 1 { "" } else { "s" }
    );
    let within_legs = chosen
        .iter()
        .any(|(_, _, s)| s.rule == ChoiceRule::LeaveOneSegmentOut);
    for (channel, cal, selection) in chosen {
        println!("  {}", held_out_line(channel, cal, selection));
    }
    if within_legs {
        println!("{WITHIN_LEGS_NOTE}");
    }
    for channel in Channel::ALL {
        if let Some(drift) = clock_drift(&calibration.sweep_blocks, &calibration.legs, channel) {
            println!("{}", clock_drift_line(channel, &drift));
        }
    }
}

/// A channel that drifts with time ([`clock_drift`]), in deg/h or mg.
fn clock_drift_line(channel: Channel, drift: &ClockDrift) -> String {
    let unit = DisplayUnits::Navigation.rate_unit(channel.sensor());
    let show = |si: f64| DisplayUnits::Navigation.rate(channel.sensor(), si);
    let [a, b] = drift.legs;
    let direction = |t: &LegTrend| match t.direction {
        LegDirection::Warming => "warming",
        LegDirection::Cooling => "cooling",
    };
    format!(
        "note: {} follows the clock, not the temperature: {:+.3} ± {:.3} {unit} per °C on leg {} ({}), {:+.3} ± {:.3} on leg {} ({}), a change of {:+.3} and {:+.3} {unit} over them; no curve in temperature removes a drift with time",
        channel.name(),
        show(a.slope_per_c),
        show(a.slope_half_width_per_c),
        a.leg,
        direction(&a),
        show(b.slope_per_c),
        show(b.slope_half_width_per_c),
        b.leg,
        direction(&b),
        show(a.change),
        show(b.change),
    )
}

/// What a choice made within one leg cannot see.
const WITHIN_LEGS_NOTE: &str = "note: where the blocks were left out a fifth at a time (one leg, or legs that share no temperature), the choice and the band see only the spread within those legs: a leg that runs the other way may differ by the loop a thermal lag draws or by a drift with time, which one leg cannot show (on the CATS record such bands covered 20-100 % of an unseen leg's 30 s blocks); check the calibration on another record with `thermonav bank check`";

/// One channel's chosen model, its held-out RMS against order 0, and its band's spread.
fn held_out_line(
    channel: Channel,
    cal: &ChannelCalibration,
    selection: &HeldOutSelection,
) -> String {
    let unit = DisplayUnits::Navigation.rate_unit(channel.sensor());
    let show = |si: f64| DisplayUnits::Navigation.rate(channel.sensor(), si);
    let rms = |order: usize, lag: bool| {
        selection
            .scores
            .iter()
            .find(|s| s.candidate.order == order && s.candidate.lag == lag)
            .and_then(|s| s.held_out_rms)
    };
    let scores = match (
        rms(0, false),
        rms(selection.chosen.order, selection.chosen.lag),
    ) {
        (Some(none), Some(this)) => format!(
            "held-out rms {:.3} {unit} (order 0: {:.3})",
            show(this),
            show(none)
        ),
        _ => String::new(),
    };
    let level = (selection.spread.level_sd).map_or(String::new(), |l| {
        format!(", level sd {:.3} {unit}", show(l))
    });
    let rule = match selection.rule {
        ChoiceRule::LeaveOneLegOut => "leave one leg out",
        ChoiceRule::LeaveOneSegmentOut => "leave one fifth of the blocks out",
    };
    format!(
        "{}: {}; {scores}; band: shape sd {:.3} {unit}{level} ({rule})",
        channel.name(),
        chosen_model(cal, selection.chosen.order),
        show(selection.spread.shape_sd),
    )
}

/// The chosen model in words.
fn chosen_model(cal: &ChannelCalibration, order: usize) -> String {
    match (&cal.lagged, order) {
        (Some(l), order) => {
            let side = |v: Option<f64>| v.map_or("open".to_string(), |v| format!("{v:.0}"));
            let [lo, hi] = l.lag.tau_interval_s;
            format!(
                "b(T + tau dT/dt) of order {order}, tau {:.0} s [95 %: {}, {}]",
                l.lag.tau_s,
                side(lo),
                side(hi)
            )
        }
        (None, 0) => {
            "order 0: no thermal term predicts held-out data better, left uncompensated".into()
        }
        (None, order) => format!("b(T) of order {order}"),
    }
}

/// The static signal taken off each channel before the fit (az's gravity).
fn print_removed_signal(calibration: &ThermalCalibration) {
    for (channel, signal) in &calibration.removed_signal {
        let unit = channel.si_unit(SampleKind::Rates);
        println!(
            "{}: {signal:.5} {unit} (the site's gravity along the record's specific force) taken off before the fit",
            channel.name()
        );
    }
}

/// The header and rows of one sensor's calibrated channels.
fn print_sensor_rows(calibration: &ThermalCalibration, sensor: Sensor) {
    println!(
        "{}",
        thermal_header(DisplayUnits::Navigation.rate_unit(sensor))
    );
    let channels = Channel::ALL.into_iter().filter(|c| c.sensor() == sensor);
    for (channel, summary) in channels.filter_map(|c| Some((c, calibration.summary(c)?))) {
        println!("{}", thermal_row(channel, &summary));
    }
}

/// The header of a thermal table whose rates are in `unit`.
fn thermal_header(unit: &str) -> String {
    let names = ["b(Tmin)", "b(Tref)", "b(Tmax)", "max band ±", "residual sd"];
    let cell = |name: &str| format!("{:>RATE_WIDTH$}", format!("{name} {unit}"));
    let rates = names.map(cell).join(" ");
    format!(
        "{CURVE_HEAD} {rates} {:>9} {}",
        "power_ons",
        cell("between sd")
    )
}

/// One channel's row of the thermal table.
fn thermal_row(channel: Channel, s: &CalibrationSummary) -> String {
    let rates = s.rate_values().map(|si| rate_cell(channel, si)).join(" ");
    let between = between_cell(channel, s.between_power_on_sd);
    format!(
        "{} {rates} {:>9} {between}",
        curve_cells(channel, s),
        s.power_ons
    )
}

/// The spread between power-ons in deg/h or mg, or n/a when not separated.
fn between_cell(channel: Channel, sd_si: Option<f64>) -> String {
    sd_si.map_or(format!("{:>RATE_WIDTH$}", "n/a"), |si| {
        rate_cell(channel, si)
    })
}

/// The channel, order, reference and range columns of a thermal row.
fn curve_cells(channel: Channel, s: &CalibrationSummary) -> String {
    let [low, high] = s.temperature_range_c;
    let range = format!("{low:.1}..{high:.1}");
    let (name, order, reference) = (channel.name(), s.order, s.reference_temperature_c);
    format!("{name:<4} {order:>5} {reference:>8.1} {range:>15}")
}

/// A rate of `channel` (SI) in deg/h or mg.
fn rate_cell(channel: Channel, si: f64) -> String {
    let shown = DisplayUnits::Navigation.rate(channel.sensor(), si);
    format!("{shown:>RATE_WIDTH$.3}")
}

/// What the calibration says of scale factor.
fn scale_factor_note(scale_factor: &ScaleFactorCalibration) -> String {
    match scale_factor {
        ScaleFactorCalibration::NotIdentifiable { reason } => {
            format!("scale factor against temperature: not identifiable from {reason}")
        }
    }
}
