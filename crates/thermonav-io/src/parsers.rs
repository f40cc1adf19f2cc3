//! Every reader of this crate behind one enum, parsing from bytes: what the fuzz targets
//! (`fuzz/fuzz_targets/*.rs`) call and what the corpus replay test feeds the saved inputs to.
//!
//! Each parser runs strictly with default settings, except where a setting opens more code to
//! the input (NMEA keeps headings and level velocities; the raw IMU reader uses a fixed tag).

use crate::raw_imu::{RawImuSettings, TimeTag};
use crate::{
    Strictness, bank, dataflash, kf_gins, motion, nmea, outside_solution, profile, raw_imu, ros,
    rtklib_pos, temperature_table, truth, ulog,
};
use std::io::Cursor;
use thermonav::time::{Duration, Timestamp};

/// One reader of this crate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Parser {
    /// Canonical IMU CSV ([`crate::read_imu`]).
    CanonicalImu,
    /// Canonical GNSS CSV ([`crate::read_gnss`]).
    CanonicalGnss,
    /// Canonical reference-trajectory CSV ([`crate::read_trajectory`]).
    CanonicalTrajectory,
    /// Model bank JSON ([`bank::parse_bank`]).
    BankJson,
    /// Sensor profile TOML ([`profile::parse_profile_bytes`]).
    ProfileToml,
    /// RTKLIB `.pos` ([`rtklib_pos::read_rtklib_pos`]).
    RtklibPos,
    /// NMEA 0183 ([`nmea::read_nmea`]).
    Nmea,
    /// KF-GINS IMU increments ([`kf_gins::read_kf_gins_imu`]).
    KfGinsImu,
    /// KF-GINS GNSS positions ([`kf_gins::read_kf_gins_gnss`]).
    KfGinsGnss,
    /// KF-GINS `.nav` trajectory ([`kf_gins::read_kf_gins_nav`]).
    KfGinsNav,
    /// Raw IMU CSV timed by a fixed tag ([`raw_imu::read_raw_imu`]).
    RawImu,
    /// RTKLIB time-tag file ([`raw_imu::decode_time_tag`]).
    TimeTag,
    /// PX4 ULog ([`ulog::decode_ulog`]), then its IMU and GNSS extraction
    /// ([`ulog::px4::imu_series`], [`ulog::px4::gnss_fixes`]) and the raw sensor series of
    /// a thermal sweep ([`ulog::px4::raw_sensor_series`]).
    Ulog,
    /// Survey truth JSON ([`truth::parse_truth`]).
    TruthJson,
    /// Temperature table CSV ([`temperature_table::parse_temperature_table`]).
    TemperatureTable,
    /// Motion definition TOML ([`motion::parse_motion`]).
    MotionToml,
    /// ROS 2 MCAP bag ([`ros::mcap::decode_mcap`]), then its IMU (with temperature) and GNSS
    /// extraction ([`ros::extract::imu_series`], [`ros::extract::gnss_fixes`]).
    Ros2Mcap,
    /// rosbag2 SQLite `.db3` ([`ros::db3::decode_db3`]), then the same extraction.
    Ros2Db3,
    /// ROS 1 bag v2.0 ([`ros::ros1::decode_ros1`]), then the same extraction.
    Ros1Bag,
    /// ArduPilot DataFlash ([`dataflash::decode_dataflash`]), then its IMU and GPS extraction
    /// ([`dataflash::ardupilot::imu_series`], [`dataflash::ardupilot::gnss_fixes`]).
    DataFlash,
    /// An outside solution ([`outside_solution::read_solution`]) read as each of its formats
    /// (our trajectory CSV, KF-GINS `.nav`, RTKLIB `.pos` with the course over ground as yaw).
    OutsideSolution,
}

/// Why a parser refused its input (any reader's error, as text).
pub type ParseFailure = Box<dyn std::error::Error + Send + Sync>;

impl Parser {
    /// Every parser, in the order of the fuzz targets.
    pub const ALL: [Parser; 21] = [
        Parser::CanonicalImu,
        Parser::CanonicalGnss,
        Parser::CanonicalTrajectory,
        Parser::BankJson,
        Parser::ProfileToml,
        Parser::RtklibPos,
        Parser::Nmea,
        Parser::KfGinsImu,
        Parser::KfGinsGnss,
        Parser::KfGinsNav,
        Parser::RawImu,
        Parser::TimeTag,
        Parser::Ulog,
        Parser::TruthJson,
        Parser::TemperatureTable,
        Parser::MotionToml,
        Parser::Ros2Mcap,
        Parser::Ros2Db3,
        Parser::Ros1Bag,
        Parser::DataFlash,
        Parser::OutsideSolution,
    ];

    /// The fuzz target's name (also the corpus folder's).
    pub fn target_name(self) -> &'static str {
        match self {
            Parser::CanonicalImu => "canonical_imu",
            Parser::CanonicalGnss => "canonical_gnss",
            Parser::CanonicalTrajectory => "canonical_trajectory",
            Parser::BankJson => "bank_json",
            Parser::ProfileToml => "profile_toml",
            Parser::RtklibPos => "rtklib_pos",
            Parser::Nmea => "nmea",
            Parser::KfGinsImu => "kf_gins_imu",
            Parser::KfGinsGnss => "kf_gins_gnss",
            Parser::KfGinsNav => "kf_gins_nav",
            Parser::RawImu => "raw_imu",
            Parser::TimeTag => "time_tag",
            Parser::Ulog => "ulog",
            Parser::TruthJson => "truth_json",
            Parser::TemperatureTable => "temperature_table",
            Parser::MotionToml => "motion_toml",
            Parser::Ros2Mcap => "ros2_mcap",
            Parser::Ros2Db3 => "ros2_db3",
            Parser::Ros1Bag => "ros1_bag",
            Parser::DataFlash => "dataflash",
            Parser::OutsideSolution => "outside_solution",
        }
    }

    /// Parses `bytes` (named `input` in errors) and returns how many records it found.
    ///
    /// # Errors
    /// The reader's own error for input it refuses; never a panic.
    pub fn record_count(self, bytes: &[u8], input: &str) -> Result<usize, ParseFailure> {
        let text = || Cursor::new(bytes);
        Ok(match self {
            Parser::CanonicalImu => crate::read_imu(text(), input, Strictness::Strict)?.len(),
            Parser::CanonicalGnss => crate::read_gnss(text(), input, Strictness::Strict)?.len(),
            Parser::CanonicalTrajectory => {
                crate::read_trajectory(text(), input, Strictness::Strict)?.len()
            }
            Parser::BankJson => bank::parse_bank(bytes, input)?.entries.len(),
            Parser::ProfileToml => profile::parse_profile_bytes(bytes, input)?.channels.len(),
            Parser::RtklibPos => {
                rtklib_pos::read_rtklib_pos(text(), input, Default::default())?.len()
            }
            Parser::Nmea => nmea::read_nmea(text(), input, nmea_settings())?.len(),
            Parser::KfGinsImu => {
                kf_gins::read_kf_gins_imu(text(), input, None, Strictness::Strict)?.len()
            }
            Parser::KfGinsGnss => {
                kf_gins::read_kf_gins_gnss(text(), input, None, Strictness::Strict)?.len()
            }
            Parser::KfGinsNav => {
                kf_gins::read_kf_gins_nav(text(), input, Strictness::Strict)?.len()
            }
            Parser::RawImu => {
                raw_imu::read_raw_imu(text(), input, &FIXED_TAG, RawImuSettings::default())?.len()
            }
            Parser::TimeTag => raw_imu::decode_time_tag(bytes, input)?.pairs,
            Parser::Ulog => ulog_record_count(bytes, input)?,
            Parser::TruthJson => {
                let scale = thermonav::nav::sensor_model::ScaleFactorPrior::default();
                truth::parse_truth(bytes, input, &scale)?.range_c().len()
            }
            Parser::TemperatureTable => temperature_table::parse_temperature_table(text(), input)?
                .t_s
                .len(),
            Parser::MotionToml => {
                let text = std::str::from_utf8(bytes)?;
                motion::parse_motion(text, input)?.segments.len()
            }
            Parser::Ros2Mcap => bag_record_count(bytes, input, ros::BagFormat::Ros2Mcap)?,
            Parser::Ros2Db3 => bag_record_count(bytes, input, ros::BagFormat::Ros2Db3)?,
            Parser::Ros1Bag => bag_record_count(bytes, input, ros::BagFormat::Ros1Bag)?,
            Parser::DataFlash => dataflash_record_count(bytes, input)?,
            Parser::OutsideSolution => solution_point_count(bytes, input)?,
        })
    }
}

/// The records of a ULog, after its IMU and GNSS extraction has run (a log without those
/// topics is still counted: the extraction's refusal is an answer, not a failure).
fn ulog_record_count(bytes: &[u8], input: &str) -> Result<usize, ParseFailure> {
    let log = ulog::decode_ulog(bytes, input)?;
    let scale = ulog::px4::time_scale(&log, ulog::px4::default_gpst_minus_utc());
    let _ = ulog::px4::imu_series(&log, input, scale);
    let _ = ulog::px4::gnss_fixes(&log, input, scale);
    let _ = ulog::px4::raw_sensor_series(&log, input, scale, 0);
    Ok(log.record_counts().values().sum())
}

/// The messages of a bag, after its IMU and GNSS extraction has run (a bag without those
/// topics is still counted, as for a ULog).
fn bag_record_count(
    bytes: &[u8],
    input: &str,
    format: ros::BagFormat,
) -> Result<usize, ParseFailure> {
    let bag = ros::decode_bag(bytes, input, format)?;
    let _ = ros::extract::imu_series(&bag, Default::default(), input);
    let _ = ros::extract::gnss_fixes(&bag, None, input);
    Ok(bag.message_count())
}

/// The records of a DataFlash log, after its IMU (the first instance, so that a log with
/// several still reaches the decoding) and GPS extraction has run.
fn dataflash_record_count(bytes: &[u8], input: &str) -> Result<usize, ParseFailure> {
    use dataflash::ardupilot::{gnss_fixes, imu_instances, imu_series, time_scale};
    let log = dataflash::decode_dataflash(bytes, input)?;
    let scale = time_scale(&log);
    let first = imu_instances(&log).first().map(|s| s.instance);
    let _ = imu_series(&log, first, "--imu-instance", input, scale);
    let _ = gnss_fixes(&log, input, scale);
    Ok(log.record_count())
}

/// The points of `bytes` read as every outside-solution format: their total, or the last
/// format's error when none reads them.
fn solution_point_count(bytes: &[u8], input: &str) -> Result<usize, ParseFailure> {
    use outside_solution::{SolutionFormat, read_solution};
    let formats = [
        SolutionFormat::Csv,
        SolutionFormat::KfGinsNav,
        SolutionFormat::RtklibPos,
    ];
    let mut outcome: Result<usize, ParseFailure> = Ok(0);
    let mut any = false;
    for format in formats {
        match read_solution(Cursor::new(bytes), input, format, Strictness::Strict) {
            Ok(points) => {
                any = true;
                outcome = Ok(outcome.unwrap_or(0) + points.len());
            }
            Err(e) if !any => outcome = Err(e.into()),
            Err(_) => {}
        }
    }
    outcome
}

/// NMEA settings that keep headings and level velocities, so that every sentence is decoded.
fn nmea_settings() -> nmea::NmeaSettings {
    nmea::NmeaSettings {
        heading_sd_rad: Some(0.01),
        level_velocity: true,
        ..Default::default()
    }
}

/// The tag of the raw IMU parser: a log starting 2024-01-01 that lasted an hour.
const FIXED_TAG: TimeTag = TimeTag {
    start: Timestamp::from_nanos(1_704_067_200 * 1_000_000_000),
    start_tick_ms: 0,
    span: Duration::from_nanos(3_600 * 1_000_000_000),
    pairs: 2,
};
