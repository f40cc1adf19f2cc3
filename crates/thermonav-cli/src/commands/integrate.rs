//! `thermonav integrate`: the 21-state GNSS/INS filter on an IMU and a GNSS file, with the
//! bank's noise model at a chosen temperature; writes the solution trajectory and its state
//! file, and reports the innovation statistics.

use crate::args::IntegrateArgs;
use crate::failure::Failure;
use crate::navigation::integration::integrate;
use crate::navigation::outcome::Summary;
use crate::report::{print_json, print_rows};
use thermonav::nav::report::{FinalJson, InnovationJson, RunReport};
use thermonav::nav::time_offset::{IntervalEnd, TimeOffsetEstimate};

/// Runs `integrate`.
pub fn run(args: &IntegrateArgs) -> Result<(), Failure> {
    let settings = crate::settings::navigation::integrate(args)?;
    let summary = integrate(&settings)?;
    if let Some(warning) = time_offset_warning(&summary) {
        eprintln!("warning: {warning}");
    }
    if args.json {
        return print_json(&summary);
    }
    print_rows(&summary_rows(&summary));
    Ok(())
}

type Row = (&'static str, String);

/// The time-offset search's warning when the data do not determine the offset.
fn time_offset_warning(s: &Summary) -> Option<&str> {
    s.time_offset.as_ref()?.warning.as_deref()
}

fn summary_rows(s: &Summary) -> Vec<Row> {
    let mut rows = run_rows(&s.run);
    rows.extend(s.time_offset.as_ref().map(time_offset_row));
    rows.extend(s.run.innovations.iter().map(innovation_row));
    rows.extend(s.run.last.as_ref().map(final_rows).unwrap_or_default());
    rows.push(("solution", s.files.solution.display().to_string()));
    rows.push(("states", s.files.states.display().to_string()));
    rows.push(("innovations", s.files.innovations.display().to_string()));
    if let Some([trajectory, _]) = &s.files.smoothed {
        rows.push(("smoothed", trajectory.display().to_string()));
    }
    rows
}

/// A unit variant's JSON name in words ("course_over_ground" as "course over ground").
fn in_words(choice: impl serde::Serialize) -> String {
    let name = serde_json::to_value(choice).map_or_else(|_| String::new(), |v| v.to_string());
    name.trim_matches('"').replace('_', " ")
}

/// Where the initial state came from, in words, with the course baseline when there is one
/// and the still span that levelled it.
fn initial_state_text(s: &RunReport) -> String {
    let heading = heading_text(s);
    match &s.still_start {
        Some(still) => format!(
            "{heading}; levelled still over {:.1} s (roll {:.2} deg, pitch {:.2} deg, gyro biases {} deg/h)",
            still.duration_s,
            still.roll_rad.to_degrees(),
            still.pitch_rad.to_degrees(),
            still
                .gyro_bias_rad_s
                .map(|b| format!("{:.0}", b.to_degrees() * 3600.0))
                .join(", ")
        ),
        None => heading,
    }
}

/// Where the initial heading came from, in words, with the course baseline when there is one.
fn heading_text(s: &RunReport) -> String {
    let source = in_words(s.initial);
    match &s.course_baseline {
        Some(c) => format!(
            "{source} along {:.2} m in {:.2} s ({} fixes, course sd {:.2} deg)",
            c.distance_m,
            c.duration_s,
            c.fixes,
            c.course_sd_rad.to_degrees()
        ),
        None => source,
    }
}

/// The initial bias sds and their source, in words.
fn initial_bias_text(s: &RunReport) -> String {
    let b = &s.initial_bias_sd;
    let [g, a] =
        [b.gyro_deg_h, b.accel_mg].map(|v| format!("{:.1}, {:.1}, {:.1}", v[0], v[1], v[2]));
    let gyro_source = match b.gyro_from_still_start {
        true => " (still start)",
        false => "",
    };
    format!(
        "gyro {g} deg/h{gyro_source}, accel {a} mg ({})",
        in_words(b.source)
    )
}

/// The filter, and the Gaussian sum it runs as when there is one.
fn filter_text(s: &RunReport) -> String {
    match &s.bias_hypotheses {
        None => s.filter.name().to_string(),
        Some(h) => format!(
            "{}, a Gaussian sum of {} over ±{} sd of the z-gyro bias prior",
            s.filter.name(),
            h.members,
            h.span_sd
        ),
    }
}

/// The estimated IMU-GNSS time offset, in words: the maximum, its likelihood-ratio interval
/// (an open end said so), the dispersion the threshold allows for and the search's cost.
fn time_offset_row(t: &TimeOffsetEstimate) -> Row {
    let end = |e: IntervalEnd| match e {
        IntervalEnd::Within { offset_s } => format!("{:+.1}", 1e3 * offset_s),
        IntervalEnd::AtBracketEnd { offset_s } => {
            format!("{:+.0} (open: bracket end)", 1e3 * offset_s)
        }
    };
    let sd = match t.time_offset_sd_s {
        Some(sd) => format!("sd {:.1} ms", 1e3 * sd),
        None => "no sd: the interval is open".to_string(),
    };
    let applied = match t.applied {
        true => format!("{:+.1} ms added to the IMU times", 1e3 * t.time_offset_s),
        false => format!(
            "not determined, not applied (the IMU times as given, 0 ms); the likelihood's maximum at {:+.1} ms",
            1e3 * t.time_offset_s
        ),
    };
    (
        "IMU time offset",
        format!(
            "{applied}; 95 % likelihood-ratio interval {} to {} ms ({sd}; NIS dispersion {:.2}, drop {:.2}; {}; {} runs over ±{:.0} ms)",
            end(t.lower),
            end(t.upper),
            t.dispersion,
            t.likelihood_drop,
            in_words(t.observability),
            t.runs,
            1e3 * t.bracket_s[1]
        ),
    )
}

fn run_rows(s: &RunReport) -> Vec<Row> {
    let m = &s.model;
    vec![
        ("filter", filter_text(s)),
        (
            "model",
            format!(
                "{:?} at {:.1} °C ({:?})",
                m.gauss_markov_source, m.temperature_c, m.selection
            ),
        ),
        ("initial state", initial_state_text(s)),
        ("static alignment", s.static_alignment.words()),
        ("GNSS position sd", s.gnss_sd.words()),
        ("initial bias sd", initial_bias_text(s)),
        ("outages", s.outages.len().to_string()),
        ("IMU samples", s.imu_samples.to_string()),
        ("duration", format!("{:.1} s", s.duration_s)),
        (
            "processing",
            format!(
                "{:.2} s ({:.0}x real time)",
                s.processing_time_s, s.real_time_factor
            ),
        ),
    ]
}

fn innovation_row(i: &InnovationJson) -> Row {
    (
        i.kind.name(),
        format!(
            "{} updates, {} rejected ({} forced in after a run of rejections), mean NIS {:.2} (expected {}), {:.0} % inside the 95 % band",
            i.offered,
            i.rejected,
            i.forced,
            i.mean_nis,
            i.dimension,
            100.0 * i.fraction_nis_in_95
        ),
    )
}

fn three(v: [f64; 3], digits: usize) -> String {
    format!("{:.digits$}, {:.digits$}, {:.digits$}", v[0], v[1], v[2])
}

fn final_rows(f: &FinalJson) -> Vec<Row> {
    vec![
        (
            "final sd position N,E,D",
            format!("{} m", three(f.sd_position_ned_m, 3)),
        ),
        (
            "final sd attitude N,E,D",
            format!("{} deg", three(f.sd_attitude_ned_deg, 3)),
        ),
        (
            "gyro bias x,y,z",
            format!("{} deg/h", three(f.gyro_bias_deg_h, 1)),
        ),
        (
            "accel bias x,y,z",
            format!("{} mg", three(f.accel_bias_mg, 2)),
        ),
    ]
}
