//! Figure data read back from files that thermonav wrote (innovations CSVs, evaluation.json
//! and its per-model error CSVs), shared by `plot` and the HTML report.

use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use serde_json::Value;
use std::path::Path;
use thermonav_plot::figures::navigation::{Innovations, ModelErrors, RmsSeries};

/// The number at `key` of a JSON object, if any.
pub fn number(v: &Value, key: &str) -> Option<f64> {
    v.get(key).and_then(Value::as_f64)
}

/// The string at `key` of a JSON object, empty if none.
pub fn text(v: &Value, key: &str) -> String {
    v.get(key)
        .and_then(Value::as_str)
        .unwrap_or_default()
        .to_string()
}

/// Position (north, east, down) and heading innovations of an `integrate` innovations file,
/// accepted updates only, times from the first update.
pub fn innovations_of(path: &Path) -> Result<Vec<Innovations>, Failure> {
    let bytes = std::fs::read(path)
        .map_err(|e| anyhow!("{}: cannot read: {e}", path.display()))
        .data()?;
    // Bytes that are not UTF-8 become U+FFFD and fail the check of their line.
    let csv = String::from_utf8_lossy(&bytes);
    let rows = accepted_rows(path, &csv)?;
    let t0 = rows
        .first()
        .and_then(|r| r[0].parse::<f64>().ok())
        .unwrap_or(0.0);
    Ok([
        ("position", 0, "north position"),
        ("position", 1, "east position"),
        ("position", 2, "down position"),
        ("heading", 0, "heading"),
    ]
    .into_iter()
    .map(|(kind, k, name)| component(&rows, t0, kind, k, name))
    .filter(|c| !c.time_s.is_empty())
    .collect())
}

/// The checked rows of accepted updates; an error when there is none.
fn accepted_rows<'a>(path: &Path, csv: &'a str) -> Result<Vec<Vec<&'a str>>, Failure> {
    let columns: Vec<&str> = INNOVATIONS_HEADER.split(',').collect();
    let accepted = columns.iter().position(|c| *c == "accepted");
    let rows: Vec<Vec<&str>> = checked_innovation_rows(path, csv)?
        .into_iter()
        .filter(|f| f.len() == columns.len() && accepted.is_some_and(|k| f[k] == "1"))
        .collect();
    if rows.is_empty() {
        return Err(anyhow!(
            "{}: no accepted update (expected rows with accepted = 1)",
            path.display()
        ))
        .data();
    }
    Ok(rows)
}

/// Component `k` of the innovations of `kind`, times from `t0`.
fn component(rows: &[Vec<&str>], t0: f64, kind: &str, k: usize, name: &str) -> Innovations {
    let of_kind: Vec<&Vec<&str>> = rows.iter().filter(|r| r[1] == kind).collect();
    let column = |c: usize| -> Vec<f64> {
        of_kind
            .iter()
            .map(|r| r[c].parse().unwrap_or(f64::NAN))
            .collect()
    };
    Innovations {
        name: name.into(),
        unit: of_kind.first().map_or("", |r| r[2]).into(),
        time_s: column(0).iter().map(|t| t - t0).collect(),
        innovation: column(3 + k),
        sigma: column(6 + k),
    }
}

/// Header of the innovations CSV that `integrate` writes.
const INNOVATIONS_HEADER: &str = "t_s,kind,unit,innovation_1,innovation_2,innovation_3,sd_1,sd_2,sd_3,nis,gate_scale,accepted,forced";

/// The rows of an innovations CSV split into fields, each checked: the header, then `t_s`,
/// kind, unit, finite numbers, and 0 or 1 for `accepted` and `forced`; the error names the line.
fn checked_innovation_rows<'a>(path: &Path, csv: &'a str) -> Result<Vec<Vec<&'a str>>, Failure> {
    let mut lines = csv.lines();
    if lines.next() != Some(INNOVATIONS_HEADER) {
        return Err(anyhow!(
            "{}:1: expected the innovations header {INNOVATIONS_HEADER}",
            path.display()
        ))
        .data();
    }
    lines
        .enumerate()
        .map(|(k, line)| {
            let fields: Vec<&str> = line.split(',').collect();
            match is_innovation_row(&fields) {
                true => Ok(fields),
                false => Err(anyhow!(
                    "{}:{}: expected {INNOVATIONS_HEADER} (finite numbers, accepted and forced 0 or 1)",
                    path.display(),
                    k + 2
                ))
                .data(),
            }
        })
        .collect()
}

/// Whether `fields` is one innovations row: time, kind, unit, numbers, then two flags.
fn is_innovation_row(fields: &[&str]) -> bool {
    let finite = |f: &&str| f.parse::<f64>().is_ok_and(f64::is_finite);
    let flag = |f: &&str| matches!(*f, "0" | "1");
    fields.len() >= 6
        && finite(&fields[0])
        && fields[3..fields.len() - 2].iter().all(finite)
        && fields[fields.len() - 2..].iter().all(flag)
}

/// The first outage's errors of every model of `filter` and of the outside solutions, from
/// their CSVs.
pub fn outage_errors(
    models: &[Value],
    filter: &str,
    evaluation_dir: &Path,
) -> Result<Vec<ModelErrors>, Failure> {
    let mut out = Vec::new();
    let shown = |m: &&Value| text(m, "filter") == filter || text(m, "kind") == "outside";
    for m in models.iter().filter(shown) {
        let Some(stored) = m.get("errors_csv").and_then(Value::as_str) else {
            continue;
        };
        let path = errors_csv_path(evaluation_dir, Path::new(stored));
        let csv = std::fs::read_to_string(&path)
            .map_err(|e| anyhow!("{}: cannot read: {e}", path.display()))
            .data()?;
        out.push(model_errors(text(m, "label"), &first_outage_rows(&csv)));
    }
    Ok(out)
}

/// Where a model's errors CSV is: the stored path taken relative to the folder of the
/// evaluation.json that names it (how `evaluate` stores it), else in `errors/` beside it
/// (reports of older versions stored it relative to the folder `evaluate` ran in), else the
/// stored path as it is.
pub fn errors_csv_path(evaluation_dir: &Path, stored: &Path) -> std::path::PathBuf {
    let relative = evaluation_dir.join(stored);
    let beside = stored
        .file_name()
        .map(|name| evaluation_dir.join("errors").join(name));
    [Some(relative), beside]
        .into_iter()
        .flatten()
        .find(|p| p.is_file())
        .unwrap_or_else(|| stored.to_path_buf())
}

/// The rows of an errors CSV in the first outage, as numbers (complete rows only: seven
/// fields, or six without the heading of a position-only reference).
fn first_outage_rows(csv: &str) -> Vec<Vec<f64>> {
    csv.lines()
        .skip(1)
        .filter(|l| l.starts_with("1,"))
        .map(|l| l.split(',').filter_map(|x| x.parse().ok()).collect())
        .filter(|v: &Vec<f64>| v.len() == 6 || v.len() == 7)
        .collect()
}

/// One model's time, north, east and heading errors from its error rows (no heading when
/// the rows have none).
fn model_errors(model: String, rows: &[Vec<f64>]) -> ModelErrors {
    let column = |k: usize| rows.iter().filter_map(|r| r.get(k).copied()).collect();
    ModelErrors {
        model,
        time_s: column(2),
        north_m: column(3),
        east_m: column(4),
        heading_deg: column(6),
    }
}

/// Per filter, the bank entries' values at their temperatures, and the interpolated model at
/// the operating temperature as its own series.
pub fn rms_series(models: &[Value], filters: &[String], key: &str) -> Vec<RmsSeries> {
    let mut series = Vec::new();
    for filter in filters {
        for (kind, name) in [("entry", "bank models"), ("interpolated", "interpolated")] {
            let points = rms_points(models, filter, kind, key);
            if !points.is_empty() {
                series.push(RmsSeries {
                    model: format!("{} ({})", name, filter.to_uppercase()),
                    temperature_c: points.iter().map(|p| p.0).collect(),
                    rms: points.iter().map(|p| p.1).collect(),
                });
            }
        }
    }
    series
}

/// (temperature, value at `key`) of the models of one filter and kind.
fn rms_points(models: &[Value], filter: &str, kind: &str, key: &str) -> Vec<(f64, f64)> {
    models
        .iter()
        .filter(|m| text(m, "filter") == filter && text(m, "kind") == kind)
        .filter_map(|m| Some((number(m, "temperature_c")?, number(m, key)?)))
        .collect()
}
