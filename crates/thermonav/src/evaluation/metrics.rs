//! Errors of a navigation solution against a reference trajectory inside GNSS outages.
//!
//! At every solution epoch inside an outage the reference is interpolated linearly in time
//! (latitude, longitude, height, and yaw on the circle); the north and east errors are the
//! NED components of the solution's position relative to it, the heading error is the
//! wrapped yaw difference. Against a position-only reference ([`ReferenceContent::PositionOnly`])
//! no heading error exists: every heading figure is absent (`None`, left out of the JSON and of
//! the error tables), never a number made up from a yaw the reference does not hold.

use crate::geo::position::Geodetic;
use crate::nav::outage::Outage;
use crate::nav::solution::SolutionEpoch;
use crate::time::Timestamp;
use crate::trajectory::{ReferenceContent, TrajectoryPoint};
use crate::units::wrap_pi;
use serde::Serialize;

/// The error at one epoch.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct EpochError {
    /// Epoch, s.
    pub time_s: f64,
    /// Seconds since the outage began.
    pub since_outage_start_s: f64,
    /// Solution minus reference, north, m.
    pub north_m: f64,
    /// Solution minus reference, east, m.
    pub east_m: f64,
    /// Horizontal distance, m.
    pub horizontal_m: f64,
    /// Solution minus reference heading, wrapped to (−180, 180], deg; absent against a
    /// position-only reference.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub heading_deg: Option<f64>,
}

impl EpochError {
    /// The names of [`EpochError::values`], as the columns of the per-model error tables.
    pub const COLUMNS: [&'static str; 6] = [
        "t_s",
        "since_outage_start_s",
        "north_m",
        "east_m",
        "horizontal_m",
        "heading_deg",
    ];

    /// The values in the order of [`EpochError::COLUMNS`], the heading left out when absent
    /// (see [`EpochError::columns`]).
    pub fn values(&self) -> Vec<f64> {
        let position = [
            self.time_s,
            self.since_outage_start_s,
            self.north_m,
            self.east_m,
            self.horizontal_m,
        ];
        position.into_iter().chain(self.heading_deg).collect()
    }

    /// The column names of errors scored against a reference holding `content`: without
    /// attitude, no `heading_deg`.
    pub fn columns(content: ReferenceContent) -> &'static [&'static str] {
        match content {
            ReferenceContent::Full => &Self::COLUMNS,
            ReferenceContent::PositionOnly => &Self::COLUMNS[..5],
        }
    }
}

/// Figures of one outage.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct OutageMetrics {
    /// Outage start, s.
    pub start_s: f64,
    /// Outage end, s.
    pub end_s: f64,
    /// Epochs evaluated.
    pub epochs: usize,
    /// RMS north error, m.
    pub rms_north_m: f64,
    /// RMS east error, m.
    pub rms_east_m: f64,
    /// RMS horizontal error, m.
    pub rms_horizontal_m: f64,
    /// RMS heading error, deg (absent against a position-only reference).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rms_heading_deg: Option<f64>,
    /// Largest |north error|, m.
    pub max_north_m: f64,
    /// Largest |east error|, m.
    pub max_east_m: f64,
    /// Largest horizontal error, m.
    pub max_horizontal_m: f64,
    /// Largest |heading error|, deg (absent against a position-only reference).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_heading_deg: Option<f64>,
}

/// Figures of a whole run over all its outages.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct RunMetrics {
    /// Mean over outages of the per-outage RMS north error, m (the paper's figure).
    pub rms_north_m: f64,
    /// Mean over outages of the per-outage RMS east error, m.
    pub rms_east_m: f64,
    /// Mean over outages of the per-outage RMS horizontal error, m.
    pub rms_horizontal_m: f64,
    /// Mean over outages of the per-outage RMS heading error, deg (absent against a
    /// position-only reference).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rms_heading_deg: Option<f64>,
    /// RMS over outages of the per-outage maximum horizontal error, m (KF-GINS's figure).
    pub max_drift_horizontal_m: f64,
    /// RMS over outages of the per-outage maximum |north error|, m.
    pub rms_of_max_north_m: f64,
    /// RMS over outages of the per-outage maximum |east error|, m.
    pub rms_of_max_east_m: f64,
    /// RMS over outages of the per-outage maximum |heading error|, deg (absent against a
    /// position-only reference).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rms_of_max_heading_deg: Option<f64>,
    /// Per outage.
    pub per_outage: Vec<OutageMetrics>,
}

/// The metrics a tournament ranks by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Metric {
    /// Mean per-outage RMS north error.
    RmsNorth,
    /// Mean per-outage RMS east error.
    RmsEast,
    /// Mean per-outage RMS horizontal error.
    RmsHorizontal,
    /// Mean per-outage RMS heading error.
    RmsHeading,
    /// RMS of the per-outage maximum horizontal error.
    MaxDriftHorizontal,
}

impl Metric {
    /// Every metric.
    pub const ALL: [Metric; 5] = [
        Metric::RmsNorth,
        Metric::RmsEast,
        Metric::RmsHorizontal,
        Metric::RmsHeading,
        Metric::MaxDriftHorizontal,
    ];

    /// Key with its unit, as in the JSON output.
    pub fn key(self) -> &'static str {
        match self {
            Metric::RmsNorth => "rms_north_m",
            Metric::RmsEast => "rms_east_m",
            Metric::RmsHorizontal => "rms_horizontal_m",
            Metric::RmsHeading => "rms_heading_deg",
            Metric::MaxDriftHorizontal => "max_drift_horizontal_m",
        }
    }

    /// The value of this metric in `m` (none for the heading against a position-only
    /// reference).
    pub fn of(self, m: &RunMetrics) -> Option<f64> {
        match self {
            Metric::RmsNorth => Some(m.rms_north_m),
            Metric::RmsEast => Some(m.rms_east_m),
            Metric::RmsHorizontal => Some(m.rms_horizontal_m),
            Metric::RmsHeading => m.rms_heading_deg,
            Metric::MaxDriftHorizontal => Some(m.max_drift_horizontal_m),
        }
    }
}

/// Checks that the reference trajectory covers every outage window, before any run.
///
/// # Errors
/// [`MetricsError::ReferenceCoverage`] for the first window that it does not cover (with NaN
/// bounds for an empty reference).
pub fn check_reference_covers(
    reference: &[TrajectoryPoint],
    outages: &[Outage],
) -> Result<(), MetricsError> {
    let span = reference.first().zip(reference.last());
    let covered = |w: &Outage| span.is_some_and(|(a, b)| a.time <= w.start && w.end <= b.time);
    match outages.iter().find(|w| !covered(w)) {
        None => Ok(()),
        Some(w) => Err(MetricsError::ReferenceCoverage {
            start_s: w.start.as_seconds(),
            end_s: w.end.as_seconds(),
            first_s: span.map_or(f64::NAN, |(a, _)| a.time.as_seconds()),
            last_s: span.map_or(f64::NAN, |(_, b)| b.time.as_seconds()),
        }),
    }
}

/// Why a solution cannot be evaluated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MetricsError {
    /// The reference does not cover an outage.
    #[error(
        "the reference trajectory ({first_s:.3}-{last_s:.3} s) does not cover the outage {start_s:.3}-{end_s:.3} s"
    )]
    ReferenceCoverage {
        /// Outage start, s.
        start_s: f64,
        /// Outage end, s.
        end_s: f64,
        /// First reference time, s.
        first_s: f64,
        /// Last reference time, s.
        last_s: f64,
    },
    /// No solution epoch inside an outage.
    #[error("no solution epoch inside the outage {start_s:.3}-{end_s:.3} s")]
    NoEpochs {
        /// Outage start, s.
        start_s: f64,
        /// Outage end, s.
        end_s: f64,
    },
    /// No outage to evaluate.
    #[error("no outage to evaluate")]
    NoOutage,
}

/// The reference at `t`, linearly interpolated (yaw on the circle); `None` outside it.
pub fn reference_at(reference: &[TrajectoryPoint], t: Timestamp) -> Option<(Geodetic, f64)> {
    let k = reference.partition_point(|p| p.time < t);
    let b = reference.get(k)?;
    if b.time == t {
        return Some((position_of(b), b.yaw_rad));
    }
    let a = reference.get(k.checked_sub(1)?)?;
    let w = t.since(a.time).as_seconds() / b.time.since(a.time).as_seconds();
    let lerp = |x: f64, y: f64| x + w * (y - x);
    let position = Geodetic {
        latitude_rad: lerp(a.latitude_rad, b.latitude_rad),
        longitude_rad: lerp(a.longitude_rad, b.longitude_rad),
        height_m: lerp(a.height_m, b.height_m),
    };
    Some((position, a.yaw_rad + w * wrap_pi(b.yaw_rad - a.yaw_rad)))
}

fn position_of(p: &TrajectoryPoint) -> Geodetic {
    Geodetic {
        latitude_rad: p.latitude_rad,
        longitude_rad: p.longitude_rad,
        height_m: p.height_m,
    }
}

/// One epoch of a solution as the metrics see it: its time, position and yaw. Our filters'
/// epochs ([`Pose::of_epoch`]) and an outside tool's trajectory ([`Pose::of_point`]) are scored
/// through the same arithmetic.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Epoch.
    pub time: Timestamp,
    /// Position.
    pub position: Geodetic,
    /// Yaw (heading), rad, in any turn (the error is wrapped).
    pub yaw_rad: f64,
}

impl Pose {
    /// The pose of a filter epoch (yaw from its attitude's Z-Y-X Euler angles).
    pub fn of_epoch(e: &SolutionEpoch) -> Self {
        let nav = &e.estimate.nav;
        let (_, _, yaw_rad) = nav.attitude.euler_zyx();
        Self {
            time: nav.time,
            position: nav.position,
            yaw_rad,
        }
    }

    /// The pose of a trajectory point (its yaw as it is: 0..360° and (−180°, 180°] score
    /// alike).
    pub fn of_point(p: &TrajectoryPoint) -> Self {
        Self {
            time: p.time,
            position: position_of(p),
            yaw_rad: p.yaw_rad,
        }
    }
}

/// A reference trajectory and what it holds (whether its yaw is a heading to score).
#[derive(Debug, Clone, Copy)]
pub struct Reference<'a> {
    /// Its points (attitude zero and unused when position-only).
    pub points: &'a [TrajectoryPoint],
    /// What it holds.
    pub content: ReferenceContent,
}

impl<'a> Reference<'a> {
    /// A reference with position, velocity and attitude.
    pub fn full(points: &'a [TrajectoryPoint]) -> Self {
        Self {
            points,
            content: ReferenceContent::Full,
        }
    }
}

/// The errors at the solution epochs inside `outage`.
///
/// # Errors
/// [`MetricsError`] when the reference does not cover the outage or no epoch falls in it.
pub fn outage_errors(
    reference: Reference,
    epochs: &[SolutionEpoch],
    outage: &Outage,
) -> Result<Vec<EpochError>, MetricsError> {
    let inside = epochs
        .iter()
        .filter(|e| outage.contains(e.estimate.nav.time))
        .map(Pose::of_epoch);
    pose_errors(reference, inside, outage)
}

/// The errors at the poses of `inside` (the solution's epochs inside `outage`).
///
/// # Errors
/// As [`outage_errors`].
pub fn pose_errors(
    reference: Reference,
    inside: impl Iterator<Item = Pose>,
    outage: &Outage,
) -> Result<Vec<EpochError>, MetricsError> {
    let (start_s, end_s) = (outage.start.as_seconds(), outage.end.as_seconds());
    let coverage = |first_s: f64, last_s: f64| MetricsError::ReferenceCoverage {
        start_s,
        end_s,
        first_s,
        last_s,
    };
    let points = reference.points;
    let (Some(first), Some(last)) = (points.first(), points.last()) else {
        return Err(coverage(f64::NAN, f64::NAN));
    };
    let scores_heading = reference.content.scores_heading();
    let errors = inside
        .map(|pose| {
            let (position, yaw) = reference_at(points, pose.time)
                .ok_or_else(|| coverage(first.time.as_seconds(), last.time.as_seconds()))?;
            let yaw = scores_heading.then_some(yaw);
            Ok(epoch_error(&pose, &position, yaw, outage))
        })
        .collect::<Result<Vec<_>, _>>()?;
    match errors.is_empty() {
        true => Err(MetricsError::NoEpochs { start_s, end_s }),
        false => Ok(errors),
    }
}

/// The error of `pose` against the reference `position` and `yaw` (if it has one) at its time.
fn epoch_error(pose: &Pose, position: &Geodetic, yaw: Option<f64>, outage: &Outage) -> EpochError {
    let d = pose.position.ned_from(position);
    EpochError {
        time_s: pose.time.as_seconds(),
        since_outage_start_s: pose.time.since(outage.start).as_seconds(),
        north_m: d.x(),
        east_m: d.y(),
        horizontal_m: d.x().hypot(d.y()),
        heading_deg: yaw.map(|yaw| wrap_pi(pose.yaw_rad - yaw).to_degrees()),
    }
}

fn rms(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v * v, n + 1));
    if n == 0 { 0.0 } else { (sum / n as f64).sqrt() }
}

fn max_abs(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, |m: f64, v| m.max(v.abs()))
}

/// The heading errors of `errors`, when every one has one (none against a position-only
/// reference).
fn heading_errors(errors: &[EpochError]) -> Option<Vec<f64>> {
    errors.iter().map(|e| e.heading_deg).collect()
}

/// The figures of one outage from its epoch errors.
pub fn outage_metrics(outage: &Outage, errors: &[EpochError]) -> OutageMetrics {
    let of = |f: fn(&EpochError) -> f64| errors.iter().map(f);
    let heading = heading_errors(errors);
    OutageMetrics {
        start_s: outage.start.as_seconds(),
        end_s: outage.end.as_seconds(),
        epochs: errors.len(),
        rms_north_m: rms(of(|e| e.north_m)),
        rms_east_m: rms(of(|e| e.east_m)),
        rms_horizontal_m: rms(of(|e| e.horizontal_m)),
        rms_heading_deg: heading.as_deref().map(|h| rms(h.iter().copied())),
        max_north_m: max_abs(of(|e| e.north_m)),
        max_east_m: max_abs(of(|e| e.east_m)),
        max_horizontal_m: max_abs(of(|e| e.horizontal_m)),
        max_heading_deg: heading.as_deref().map(|h| max_abs(h.iter().copied())),
    }
}

/// The overall figures from the per-outage ones.
///
/// # Errors
/// [`MetricsError::NoOutage`] for an empty list.
pub fn run_metrics(per_outage: Vec<OutageMetrics>) -> Result<RunMetrics, MetricsError> {
    if per_outage.is_empty() {
        return Err(MetricsError::NoOutage);
    }
    let n = per_outage.len() as f64;
    let mean = |f: fn(&OutageMetrics) -> f64| per_outage.iter().map(f).sum::<f64>() / n;
    let rms_of = |f: fn(&OutageMetrics) -> f64| rms(per_outage.iter().map(f));
    let heading = |f: fn(&OutageMetrics) -> Option<f64>| -> Option<Vec<f64>> {
        per_outage.iter().map(f).collect()
    };
    Ok(RunMetrics {
        rms_north_m: mean(|o| o.rms_north_m),
        rms_east_m: mean(|o| o.rms_east_m),
        rms_horizontal_m: mean(|o| o.rms_horizontal_m),
        rms_heading_deg: heading(|o| o.rms_heading_deg).map(|h| h.iter().sum::<f64>() / n),
        max_drift_horizontal_m: rms_of(|o| o.max_horizontal_m),
        rms_of_max_north_m: rms_of(|o| o.max_north_m),
        rms_of_max_east_m: rms_of(|o| o.max_east_m),
        rms_of_max_heading_deg: heading(|o| o.max_heading_deg).map(|h| rms(h.into_iter())),
        per_outage,
    })
}

/// Errors inside every outage and the run's figures.
///
/// # Errors
/// As [`outage_errors`] and [`run_metrics`].
pub fn evaluate_solution(
    reference: Reference,
    epochs: &[SolutionEpoch],
    outages: &[Outage],
) -> Result<(RunMetrics, Vec<Vec<EpochError>>), MetricsError> {
    evaluate_with(outages, |o| outage_errors(reference, epochs, o))
}

/// Errors of a trajectory (an outside tool's solution, or any trajectory file) inside every
/// outage and the run's figures: the same figures as [`evaluate_solution`] of the epochs the
/// trajectory was written from.
///
/// # Errors
/// As [`evaluate_solution`].
pub fn evaluate_trajectory(
    reference: Reference,
    points: &[TrajectoryPoint],
    outages: &[Outage],
) -> Result<(RunMetrics, Vec<Vec<EpochError>>), MetricsError> {
    evaluate_with(outages, |o| {
        let inside = points.iter().filter(|p| o.contains(p.time));
        pose_errors(reference, inside.map(Pose::of_point), o)
    })
}

/// The errors of every outage by `errors_of` and the run's figures.
fn evaluate_with(
    outages: &[Outage],
    errors_of: impl Fn(&Outage) -> Result<Vec<EpochError>, MetricsError>,
) -> Result<(RunMetrics, Vec<Vec<EpochError>>), MetricsError> {
    let errors = outages
        .iter()
        .map(errors_of)
        .collect::<Result<Vec<_>, _>>()?;
    let per_outage = outages
        .iter()
        .zip(&errors)
        .map(|(o, e)| outage_metrics(o, e))
        .collect();
    Ok((run_metrics(per_outage)?, errors))
}
