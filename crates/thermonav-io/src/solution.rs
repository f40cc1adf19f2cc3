//! The navigation solution's state file: per epoch, the standard deviations of the error
//! states and the estimated sensor errors, beside the solution trajectory (written with
//! [`crate::trajectory`], so that the solution reads back as a reference trajectory). The
//! split follows KF-GINS, which writes the navigation result, the IMU errors and the standard
//! deviations to separate files.
//!
//! ```text
//! t_s,sd_n_m,sd_e_m,sd_d_m,sd_vn_m_s,sd_ve_m_s,sd_vd_m_s,sd_att_n_deg,sd_att_e_deg,sd_att_d_deg,
//! bgx_deg_h,bgy_deg_h,bgz_deg_h,bax_mg,bay_mg,baz_mg,sgx_ppm,sgy_ppm,sgz_ppm,sax_ppm,say_ppm,saz_ppm,
//! sd_bgx_deg_h,…,sd_saz_ppm,in_outage
//! ```

use crate::atomic::AtomicFile;
use crate::atomic::write_atomically;
use crate::error::WriteError;
use crate::finite::write_finite;
use crate::text::write_time;
use crate::trajectory::{write_trajectory_header, write_trajectory_point};
use std::io::Write;
use std::path::Path;
use thermonav::ins::error_model::STATES;
use thermonav::nav::measurement::MeasurementKind;
use thermonav::nav::solution::{InnovationRecord, SolutionEpoch, SolutionSink};
use thermonav::trajectory::TrajectoryPoint;
use thermonav::units::{STANDARD_GRAVITY_M_S2, rad_per_s_to_deg_per_h};

/// Header names of the 21 standard deviations, in state order.
const SD_NAMES: [&str; STATES] = [
    "sd_n_m",
    "sd_e_m",
    "sd_d_m",
    "sd_vn_m_s",
    "sd_ve_m_s",
    "sd_vd_m_s",
    "sd_att_n_deg",
    "sd_att_e_deg",
    "sd_att_d_deg",
    "sd_bgx_deg_h",
    "sd_bgy_deg_h",
    "sd_bgz_deg_h",
    "sd_bax_mg",
    "sd_bay_mg",
    "sd_baz_mg",
    "sd_sgx_ppm",
    "sd_sgy_ppm",
    "sd_sgz_ppm",
    "sd_sax_ppm",
    "sd_say_ppm",
    "sd_saz_ppm",
];

/// Header names of the 12 sensor-error estimates.
const SENSOR_NAMES: [&str; 12] = [
    "bgx_deg_h",
    "bgy_deg_h",
    "bgz_deg_h",
    "bax_mg",
    "bay_mg",
    "baz_mg",
    "sgx_ppm",
    "sgy_ppm",
    "sgz_ppm",
    "sax_ppm",
    "say_ppm",
    "saz_ppm",
];

/// The factor from the SI value of state `i` to its unit in the file.
fn file_unit_factor(i: usize) -> f64 {
    match i {
        0..=5 => 1.0,
        6..=8 => 1f64.to_degrees(),
        9..=11 => rad_per_s_to_deg_per_h(1.0),
        12..=14 => 1000.0 / STANDARD_GRAVITY_M_S2,
        _ => 1e6,
    }
}

/// The names of the state file's number columns between `t_s` and `in_outage`, in file
/// order: nine navigation sds, twelve sensor estimates, twelve sensor sds.
pub fn state_column_names() -> impl Iterator<Item = &'static str> {
    (SD_NAMES[..9].iter().copied())
        .chain(SENSOR_NAMES)
        .chain(SD_NAMES[9..].iter().copied())
}

/// An epoch's values in the columns of [`state_column_names`], in their file units.
pub fn state_values(epoch: &SolutionEpoch) -> impl Iterator<Item = f64> + '_ {
    let s = &epoch.estimate.sensors;
    let sensors = (s.gyro_bias_rad_s.iter())
        .chain(&s.accel_bias_m_s2)
        .chain(&s.gyro_scale)
        .chain(&s.accel_scale)
        .enumerate()
        .map(|(k, v)| v * file_unit_factor(9 + k));
    let sd = |range: std::ops::Range<usize>| range.map(|i| epoch.sd[i] * file_unit_factor(i));
    sd(0..9).chain(sensors).chain(sd(9..STATES))
}

/// Writes the state file of `epochs`.
///
/// # Errors
/// [`WriteError::Empty`] for no epoch, [`WriteError::Io`].
pub fn write_solution_states(
    mut out: impl Write,
    epochs: &[SolutionEpoch],
) -> Result<(), WriteError> {
    if epochs.is_empty() {
        return Err(WriteError::Empty {
            what: "solution epochs",
        });
    }
    write_states_header(&mut out)?;
    for epoch in epochs {
        write_states_row(&mut out, epoch)?;
    }
    out.flush()?;
    Ok(())
}

/// The state file's header line.
fn write_states_header(out: &mut impl Write) -> Result<(), WriteError> {
    let header: Vec<&str> = std::iter::once("t_s")
        .chain(state_column_names())
        .chain(std::iter::once("in_outage"))
        .collect();
    writeln!(out, "{}", header.join(","))?;
    Ok(())
}

/// One epoch's line of the state file.
fn write_states_row(out: &mut impl Write, epoch: &SolutionEpoch) -> Result<(), WriteError> {
    write_time(out, epoch.estimate.nav.time)?;
    for value in state_values(epoch) {
        out.write_all(b",")?;
        write_finite(out, value)?;
    }
    writeln!(out, ",{}", u8::from(epoch.in_outage))?;
    Ok(())
}

/// Writes the state file to `path` atomically.
///
/// # Errors
/// As [`write_solution_states`], plus those of [`write_atomically`].
pub fn write_solution_states_file(
    path: impl AsRef<Path>,
    epochs: &[SolutionEpoch],
) -> Result<(), WriteError> {
    write_atomically(path, |file| write_solution_states(file, epochs))
}

/// Writes every measurement update of a run:
/// `t_s,kind,unit,innovation_1,innovation_2,innovation_3,sd_1,sd_2,sd_3,nis,gate_scale,accepted,forced`,
/// components north/east/down for position (m) and velocity (m/s), the first alone for
/// heading (deg); `sd_k` are square roots of the innovation covariance's diagonal;
/// `gate_scale` the factor the gate's quantile was widened by (1 = the plain gate).
///
/// # Errors
/// [`WriteError::Io`].
pub fn write_innovations(
    mut out: impl Write,
    records: &[InnovationRecord],
) -> Result<(), WriteError> {
    write_innovations_header(&mut out)?;
    for r in records {
        write_innovation_row(&mut out, r)?;
    }
    out.flush()?;
    Ok(())
}

/// The innovation file's header line.
fn write_innovations_header(out: &mut impl Write) -> Result<(), WriteError> {
    writeln!(
        out,
        "t_s,kind,unit,innovation_1,innovation_2,innovation_3,sd_1,sd_2,sd_3,nis,gate_scale,accepted,forced"
    )?;
    Ok(())
}

/// One update's line of the innovation file.
fn write_innovation_row(out: &mut impl Write, r: &InnovationRecord) -> Result<(), WriteError> {
    let (unit, factor) = match r.kind {
        MeasurementKind::Position => ("m", 1.0),
        MeasurementKind::Velocity => ("m/s", 1.0),
        MeasurementKind::Heading => ("deg", 1f64.to_degrees()),
    };
    write_time(out, r.time)?;
    write!(out, ",{},{unit}", r.kind.name())?;
    for value in r
        .innovation
        .iter()
        .chain(&r.sd)
        .map(|v| v * factor)
        .chain([r.nis, r.gate_scale])
    {
        out.write_all(b",")?;
        write_finite(out, value)?;
    }
    writeln!(out, ",{},{}", u8::from(r.accepted), u8::from(r.forced))?;
    Ok(())
}

/// Writes the updates to `path` atomically.
///
/// # Errors
/// As [`write_innovations`], plus those of [`write_atomically`].
pub fn write_innovations_file(
    path: impl AsRef<Path>,
    records: &[thermonav::nav::solution::InnovationRecord],
) -> Result<(), WriteError> {
    write_atomically(path, |file| write_innovations(file, records))
}

/// The three files of a navigation run (trajectory, state file, innovations) written as the
/// run goes: a [`SolutionSink`] whose every record becomes a line at once, into temporary
/// files that [`SolutionFilesWriter::finish`] renames into place. The lines are those of
/// [`crate::write_trajectory`], [`write_solution_states`] and [`write_innovations`], byte for
/// byte. A failed write is kept (later records are dropped) and returned by `finish`; a writer
/// dropped unfinished (the run failed) deletes its temporary files and leaves no output.
pub struct SolutionFilesWriter {
    trajectory: AtomicFile,
    states: AtomicFile,
    innovations: AtomicFile,
    epochs: usize,
    error: Option<WriteError>,
}

impl SolutionFilesWriter {
    /// Starts the three files (their headers written).
    ///
    /// # Errors
    /// Those of [`AtomicFile::create`], and [`WriteError::InFile`] for a header that fails.
    pub fn create(
        trajectory: impl AsRef<Path>,
        states: impl AsRef<Path>,
        innovations: impl AsRef<Path>,
    ) -> Result<Self, WriteError> {
        let mut writer = Self {
            trajectory: AtomicFile::create(trajectory)?,
            states: AtomicFile::create(states)?,
            innovations: AtomicFile::create(innovations)?,
            epochs: 0,
            error: None,
        };
        let trajectory = write_trajectory_header(&mut writer.trajectory);
        writer.keep(trajectory, Part::Trajectory);
        let states = write_states_header(&mut writer.states);
        writer.keep(states, Part::States);
        let innovations = write_innovations_header(&mut writer.innovations);
        writer.keep(innovations, Part::Innovations);
        match writer.error.take() {
            Some(error) => Err(error),
            None => Ok(writer),
        }
    }

    /// Renames the three files into place.
    ///
    /// # Errors
    /// The first failed write, wrapped with its file's path; [`WriteError::Empty`] for a run
    /// without epochs (as the whole-solution writers); those of [`AtomicFile::commit`].
    pub fn finish(mut self) -> Result<(), WriteError> {
        if self.epochs == 0 {
            let empty = Err(WriteError::Empty { what: "points" });
            self.keep(empty, Part::Trajectory);
        }
        if let Some(error) = self.error {
            return Err(error);
        }
        self.trajectory.commit()?;
        self.states.commit()?;
        self.innovations.commit()
    }

    /// Keeps the first error, wrapped with the path of its file.
    fn keep(&mut self, result: Result<(), WriteError>, part: Part) {
        let Err(error) = result else {
            return;
        };
        let file = match part {
            Part::Trajectory => &self.trajectory,
            Part::States => &self.states,
            Part::Innovations => &self.innovations,
        };
        let wrapped = WriteError::InFile {
            path: file.target().display().to_string(),
            source: Box::new(error),
        };
        self.error.get_or_insert(wrapped);
    }
}

/// One of the three files.
#[derive(Clone, Copy)]
enum Part {
    Trajectory,
    States,
    Innovations,
}

impl SolutionSink for SolutionFilesWriter {
    fn epoch(&mut self, epoch: &SolutionEpoch) {
        if self.error.is_some() {
            return;
        }
        self.epochs += 1;
        let point = TrajectoryPoint::from_nav_state(&epoch.estimate.nav);
        let trajectory = write_trajectory_point(&mut self.trajectory, &point);
        self.keep(trajectory, Part::Trajectory);
        let states = write_states_row(&mut self.states, epoch);
        self.keep(states, Part::States);
    }

    fn innovation(&mut self, record: &InnovationRecord) {
        if self.error.is_some() {
            return;
        }
        let innovations = write_innovation_row(&mut self.innovations, record);
        self.keep(innovations, Part::Innovations);
    }
}
