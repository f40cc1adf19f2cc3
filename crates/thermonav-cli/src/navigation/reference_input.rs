//! `--reference` (and `--initial-from`, and `plot trajectory`'s input) read in any form a user
//! has one: our trajectory CSV, a GNSS CSV, an RTKLIB `.pos` or a KF-GINS `.nav`, the kind
//! told by the content ([`thermonav_io::reference`]); its time checked against the run's.

use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use std::path::Path;
use thermonav::imu::ImuSeries;
use thermonav::time::Timestamp;
use thermonav::trajectory::{ReferenceContent, TrajectoryPoint};
use thermonav_io::Strictness;
use thermonav_io::reference::{
    Reference, ReferenceKind, read_reference_file, reference_kind_of_file,
};

/// Reads the reference at `path`, whatever its kind; errors name the file.
pub fn read_reference(path: &Path) -> Result<Reference, Failure> {
    crate::inputs::readable_twice(path, "reading a reference")?;
    read_reference_file(path, Strictness::Strict).data()
}

/// The kind of the reference at `path`, told by its content; errors name the file.
pub fn reference_kind(path: &Path) -> Result<ReferenceKind, Failure> {
    reference_kind_of_file(path).data()
}

/// Reads a reference a run starts from (`integrate --initial-from`): one with attitude. A
/// position-only one is refused, naming the file and what to do instead.
/// A reference that does not overlap the IMU record `imu` spanning `run` is refused.
pub fn read_start_reference(
    path: &Path,
    (run, imu): (RunSpan, &Path),
) -> Result<Vec<TrajectoryPoint>, Failure> {
    let reference = read_reference(path)?;
    check_has_attitude(&reference, path)?;
    check_overlap((&reference, path), (run, imu))?;
    Ok(reference.points)
}

/// Refuses a position-only reference where a run would take its attitude from it.
pub fn check_has_attitude(reference: &Reference, path: &Path) -> Result<(), Failure> {
    match reference.content() {
        ReferenceContent::Full => Ok(()),
        ReferenceContent::PositionOnly => Err(anyhow!(
            "{}: a {} holds positions only, no attitude for the run to start from: leave out --initial-from (the run aligns from GNSS), or give a trajectory CSV or a KF-GINS .nav",
            path.display(),
            reference.kind.name()
        ))
        .data(),
    }
}

/// The first and last time of `points`.
pub fn span_of(points: &[TrajectoryPoint]) -> Option<(Timestamp, Timestamp)> {
    Some((points.first()?.time, points.last()?.time))
}

/// The span of an IMU record's times, if it has any.
pub type RunSpan = Option<(Timestamp, Timestamp)>;

/// The first and last sample time of `series`.
pub fn record_span(series: &ImuSeries) -> RunSpan {
    Some((*series.time.first()?, *series.time.last()?))
}

/// Refuses a reference whose time does not overlap the run's (the IMU record `imu` spanning
/// `run`), naming both files and both time ranges, with a hint when the two are on
/// different time scales.
pub fn check_overlap(
    (reference, path): (&Reference, &Path),
    (run, imu): (RunSpan, &Path),
) -> Result<(), Failure> {
    let Some(span) = span_of(&reference.points) else {
        return Err(anyhow!("{}: no point", path.display())).data();
    };
    check_span_overlap((span, reference.kind, path), (run, imu))
}

/// [`check_overlap`] of a reference of `kind` spanning `span`.
pub fn check_span_overlap(
    (span, kind, path): ((Timestamp, Timestamp), ReferenceKind, &Path),
    (run, imu): (RunSpan, &Path),
) -> Result<(), Failure> {
    let Some(run) = run else { return Ok(()) };
    if span.0 <= run.1 && run.0 <= span.1 {
        return Ok(());
    }
    Err(anyhow!(
        "{}: the reference ({}) spans t = {} s, the IMU record {} spans t = {} s: they do not overlap, so nothing can be scored{}",
        path.display(),
        kind.name(),
        range_text(span),
        imu.display(),
        range_text(run),
        scale_hint(kind, span, run)
    ))
    .data()
}

/// `first–last` in seconds.
fn range_text((first, last): (Timestamp, Timestamp)) -> String {
    format!("{:.3}–{:.3}", first.as_seconds(), last.as_seconds())
}

/// Times from this many seconds on are a clock's (Unix or GPST seconds since 1970).
const CLOCK_TIME_S: f64 = 1e8;

/// Why two spans may not meet: one on a clock's scale and the other not.
fn scale_hint(
    kind: ReferenceKind,
    reference: (Timestamp, Timestamp),
    run: (Timestamp, Timestamp),
) -> String {
    let clock = |t: Timestamp| t.as_seconds() >= CLOCK_TIME_S;
    let gpst = matches!(kind, ReferenceKind::RtklibPos | ReferenceKind::KfGinsNav);
    match (clock(reference.0), clock(run.0)) {
        (true, false) if gpst => format!(
            " (the {} is read on the GPST scale, seconds since 1970 without leap seconds, as thermonav convert puts a receiver's log; the IMU's t_s counts from {:.3} s: convert the IMU log with thermonav convert, or shift its t_s onto GPST)",
            kind.name(),
            run.0.as_seconds()
        ),
        (true, false) | (false, true) => {
            " (one file's times are a clock's, seconds since 1970, and the other's are not: put both on one time scale)".into()
        }
        _ => String::new(),
    }
}
