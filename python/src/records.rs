//! `read_imu` and `read_gnss`: canonical CSVs read by thermonav-io's readers into NumPy
//! arrays named like the files' columns (units in the names).

use crate::arrays::array;
use crate::error;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};
use thermonav::gnss::GnssFix;
use thermonav::imu::{ImuSeries, SampleKind};
use thermonav::time::Timestamp;
use thermonav_io::imu::channel_column_names;
use thermonav_io::{Strictness, read_gnss_file, read_imu_file};

/// The reading rules: strict (every defect refused) or lenient.
fn strictness(strict: bool) -> Strictness {
    if strict {
        Strictness::Strict
    } else {
        Strictness::Lenient
    }
}

/// The file name of `path`, the bank's `source` of a record.
pub(crate) fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// Times as integer nanoseconds and as seconds.
fn set_times(
    out: &Bound<'_, PyDict>,
    times: impl Iterator<Item = Timestamp> + Clone,
) -> PyResult<()> {
    let py = out.py();
    out.set_item(
        "t_ns",
        array(py, times.clone().map(|t| t.as_nanos()).collect()),
    )?;
    out.set_item("t_s", array(py, times.map(|t| t.as_seconds()).collect()))
}

/// An IMU record's columns: `t_ns`, `t_s`, the six channels in SI, `temp_c` when recorded.
pub(crate) fn imu_dict<'py>(
    py: Python<'py>,
    series: ImuSeries,
    path: &Path,
) -> PyResult<Bound<'py, PyDict>> {
    let kind = series.kind.unwrap_or(SampleKind::Rates);
    let out = PyDict::new(py);
    out.set_item("source", file_name(path))?;
    out.set_item("path", path.display().to_string())?;
    out.set_item(
        "kind",
        match kind {
            SampleKind::Rates => "rates",
            SampleKind::Increments => "increments",
        },
    )?;
    set_times(&out, series.time.iter().copied())?;
    for (name, column) in channel_column_names(kind).into_iter().zip(series.channels) {
        out.set_item(name, array(py, column))?;
    }
    if let Some(temperature) = series.temperature_c {
        out.set_item("temp_c", array(py, temperature))?;
    }
    Ok(out)
}

/// Reads a canonical IMU CSV (any accepted unit, converted to SI once).
#[pyfunction]
#[pyo3(signature = (path, strict=true))]
pub fn read_imu(py: Python<'_>, path: PathBuf, strict: bool) -> PyResult<Bound<'_, PyDict>> {
    let series = py
        .detach(|| read_imu_file(&path, strictness(strict)))
        .map_err(error)?;
    imu_dict(py, series, &path)
}

/// One optional GNSS column: its values, NaN where a fix lacks the group.
fn optional(fixes: &[GnssFix], value: impl Fn(&GnssFix) -> Option<f64>) -> Vec<f64> {
    fixes.iter().map(|f| value(f).unwrap_or(f64::NAN)).collect()
}

/// Reads a canonical GNSS CSV: positions in degrees and metres, with the optional groups
/// (position sd, NED velocity, dual-antenna heading) as NaN where a fix lacks them.
#[pyfunction]
#[pyo3(signature = (path, strict=true))]
pub fn read_gnss(py: Python<'_>, path: PathBuf, strict: bool) -> PyResult<Bound<'_, PyDict>> {
    let fixes = py
        .detach(|| read_gnss_file(&path, strictness(strict)))
        .map_err(error)?;
    let out = PyDict::new(py);
    out.set_item("source", file_name(&path))?;
    out.set_item("path", path.display().to_string())?;
    set_times(&out, fixes.iter().map(|f| f.time))?;
    let degrees = thermonav::units::rad_to_deg;
    out.set_item(
        "lat_deg",
        array(py, optional(&fixes, |f| Some(degrees(f.latitude_rad)))),
    )?;
    out.set_item(
        "lon_deg",
        array(py, optional(&fixes, |f| Some(degrees(f.longitude_rad)))),
    )?;
    out.set_item("h_m", array(py, optional(&fixes, |f| Some(f.height_m))))?;
    for (k, name) in ["sd_n_m", "sd_e_m", "sd_u_m"].into_iter().enumerate() {
        out.set_item(
            name,
            array(py, optional(&fixes, |f| f.position_sd_ned_m.map(|v| v[k]))),
        )?;
    }
    for (k, name) in ["vn_m_s", "ve_m_s", "vd_m_s"].into_iter().enumerate() {
        out.set_item(
            name,
            array(py, optional(&fixes, |f| f.velocity_ned_m_s.map(|v| v[k]))),
        )?;
    }
    let heading = |f: &GnssFix| f.heading.map(|h| degrees(h.heading_rad));
    out.set_item("heading_deg", array(py, optional(&fixes, heading)))?;
    let heading_sd = |f: &GnssFix| f.heading.map(|h| degrees(h.sd_rad));
    out.set_item("sd_heading_deg", array(py, optional(&fixes, heading_sd)))?;
    Ok(out)
}
