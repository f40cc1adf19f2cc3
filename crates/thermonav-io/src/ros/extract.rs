//! A bag's topics as thermonav series.
//!
//! - **Time**: each sample is timed at its message's **header stamp** (`header.stamp`, ns since
//!   the epoch of the recording computer's clock: UTC for ROS time, not GPST, and not shifted),
//!   not at the record (log) time at which the recorder received it; [`StampLag`] reports how
//!   far the two differ. Header stamps must increase strictly within a topic (in record order).
//! - **Axes**: `sensor_msgs/Imu` is in the ROS body frame of REP 103 (x forward, y left, z up; a
//!   level unit at rest reads +g on z). thermonav's body frame is FRD, so both the angular
//!   velocity and the specific force become (x, −y, −z): a level unit at rest then reads
//!   az ≈ −9.8 m/s², as CONVENTIONS.md has it. The specific force stays a specific force.
//! - **Topic**: the one asked for; else the only topic of the needed type; else an error listing
//!   the candidates with their types and counts.
//! - **Temperature**: the nearest `sensor_msgs/Temperature` message in time (ties to the
//!   earlier), as the ULog reader does; a NaN temperature is "not measured" and left out.
//! - **Values**: every IMU sample and temperature passes the checks of every reader
//!   ([`crate::sample_checks`]: finite, at most 1e15 in SI, −80..150 °C with a hint for
//!   kelvin), refused naming the file, the topic, the message's index in it and its offset.
//! - **GNSS**: `NavSatFix` with `status.status` ≥ 0 (a fix) and finite latitude, longitude and
//!   altitude (above the WGS84 ellipsoid, as the message defines it); standard deviations from
//!   the diagonal of `position_covariance` (east-north-up, m²) when its type is not 0 (unknown).

use super::messages::Encoding;
use super::messages::{MessageType, decode_imu, decode_nav_sat_fix, decode_temperature};
use super::{Bag, Sink, Topic};
use crate::error::{ReadError, ReadErrorKind};
use crate::sample_checks::{imu_sample_problem, temperature_problem};
use serde::Serialize;
use std::path::Path;
use thermonav::gnss::GnssFix;
use thermonav::imu::{ImuSample, ImuSeries, SampleKind};
use thermonav::time::Timestamp;
use thermonav::units::deg_to_rad;

/// What [`imu_series`] did to the axes, for the sidecar.
pub const FRAME_NOTE: &str = "sensor_msgs/Imu is in the ROS body frame (REP 103: x forward, y \
    left, z up; a level unit at rest reads +g on z); written in thermonav's FRD frame as (x, -y, \
    -z) for both angular velocity and specific force (a level unit at rest reads az = -g)";

/// What the sample times are, for the sidecar.
pub const TIME_NOTE: &str = "t_s is each message's header stamp (header.stamp), seconds since \
    1970 on the recording computer's clock (ROS time, UTC unless the bag was recorded in \
    simulation time; not GPST); the record (log) time is not used, and stamp_lag_s says how \
    far it differs";

/// Header stamp minus record time over a topic's messages, s.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StampLag {
    /// Smallest (most negative: the stamp furthest before the record time), s.
    pub min_s: f64,
    /// Median, s.
    pub median_s: f64,
    /// Largest, s.
    pub max_s: f64,
}

impl StampLag {
    /// The range of `lags_ns` (stamp minus record time, ns); `None` when empty.
    fn of(mut lags_ns: Vec<i64>) -> Option<Self> {
        lags_ns.sort_unstable();
        let s = |ns: i64| ns as f64 * 1e-9;
        Some(Self {
            min_s: s(*lags_ns.first()?),
            median_s: s(lags_ns[lags_ns.len() / 2]),
            max_s: s(*lags_ns.last()?),
        })
    }
}

/// A topic as the sidecar names it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TopicSummary {
    /// Topic name.
    pub name: String,
    /// Type as the bag names it.
    pub type_name: String,
    /// Messages.
    pub count: usize,
}

impl TopicSummary {
    /// The summaries of a bag's topics.
    pub fn of_bag(bag: &Bag) -> Vec<Self> {
        bag.topics
            .iter()
            .map(|t| Self {
                name: t.name.clone(),
                type_name: t.type_name.clone(),
                count: t.count,
            })
            .collect()
    }
}

/// A problem with a topic.
fn topic_error(input: &str, what: String) -> ReadError {
    ReadError::new(input, None, ReadErrorKind::Unusable(what))
}

/// The topics of `bag` as `name (type, N messages)`, comma-separated.
fn listing<'a>(topics: impl Iterator<Item = &'a Topic>) -> String {
    let items: Vec<String> = topics
        .map(|t| format!("{} ({}, {} messages)", t.name, t.type_name, t.count))
        .collect();
    match items.is_empty() {
        true => "none".to_string(),
        false => items.join(", "),
    }
}

/// True for a topic of type `kind` that holds a message: one without (a channel or connection
/// declared and never used) is listed but never taken unasked, nor counted against another.
fn is_candidate(topic: &Topic, kind: MessageType) -> bool {
    topic.message_type == Some(kind) && topic.count > 0
}

/// The topic of type `kind`: `requested` by name, else the only one of that type that holds
/// messages.
///
/// # Errors
/// [`ReadErrorKind::Unusable`]: no topic of that name (listing every topic), one of another
/// type, or zero or several topics of the type with messages when none is requested (listing
/// them, and naming `option`, the command-line option that chooses one).
pub fn select_topic<'a>(
    bag: &'a Bag,
    kind: MessageType,
    requested: Option<&str>,
    option: &str,
    input: &str,
) -> Result<&'a Topic, ReadError> {
    let candidates = || bag.topics.iter().filter(|t| is_candidate(t, kind));
    if let Some(name) = requested {
        let named: Vec<&Topic> = bag.topics.iter().filter(|t| t.name == name).collect();
        return match named.iter().find(|t| t.message_type == Some(kind)) {
            Some(t) => Ok(t),
            None if named.is_empty() => Err(topic_error(
                input,
                format!(
                    "no topic {name} in the bag (topics: {})",
                    listing(bag.topics.iter())
                ),
            )),
            None => Err(topic_error(
                input,
                format!(
                    "topic {name} is {}, not {} (topics of that type: {})",
                    named[0].type_name,
                    kind.name(),
                    listing(candidates())
                ),
            )),
        };
    }
    let found: Vec<&Topic> = candidates().collect();
    match found[..] {
        [one] => Ok(one),
        [] => Err(topic_error(
            input,
            format!(
                "no {} topic in the bag (topics: {})",
                kind.name(),
                listing(bag.topics.iter())
            ),
        )),
        _ => Err(topic_error(
            input,
            format!(
                "{} topics of type {}: {}; choose one with {option}",
                found.len(),
                kind.name(),
                listing(found.into_iter())
            ),
        )),
    }
}

/// Where the IMU series of [`imu_series`] came from.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ImuExtract {
    /// The rates, in FRD, timed at the header stamps.
    #[serde(skip)]
    pub series: ImuSeries,
    /// The IMU topic read.
    pub topic: String,
    /// The temperature topic, when there is one.
    pub temperature_topic: Option<String>,
    /// How temperatures are assigned to samples.
    pub temperature_assignment: Option<&'static str>,
    /// Header stamp minus record time of the IMU messages.
    pub stamp_lag_s: Option<StampLag>,
    /// What was done to the axes.
    pub frame: &'static str,
    /// What the times are.
    pub time: &'static str,
}

/// Which topics to read.
#[derive(Debug, Clone, Copy, Default)]
pub struct TopicChoice<'a> {
    /// The IMU topic (`--topic`).
    pub imu: Option<&'a str>,
    /// The temperature topic (`--temperature-topic`).
    pub temperature: Option<&'a str>,
    /// The GNSS topic (`--gnss-topic`).
    pub gnss: Option<&'a str>,
}

/// A [`TopicChoice`] that owns its names: the topics a command line chose, kept in settings.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct TopicNames {
    /// The IMU topic (`--topic`).
    pub imu: Option<String>,
    /// The temperature topic (`--temperature-topic`).
    pub temperature: Option<String>,
    /// The GNSS topic (`--gnss-topic`).
    pub gnss: Option<String>,
}

impl TopicNames {
    /// The choice these names make.
    pub fn choice(&self) -> TopicChoice<'_> {
        TopicChoice {
            imu: self.imu.as_deref(),
            temperature: self.temperature.as_deref(),
            gnss: self.gnss.as_deref(),
        }
    }

    /// True when no topic is named (each is the only one of its type).
    pub fn is_empty(&self) -> bool {
        self.imu.is_none() && self.temperature.is_none() && self.gnss.is_none()
    }
}

/// How temperatures are assigned.
const NEAREST: &str =
    "nearest sensor_msgs/Temperature message in time (header stamps; ties to the earlier)";

/// The IMU of `bag` as rates in FRD, with `temp_c` when a temperature topic is chosen or is the
/// only one.
///
/// # Errors
/// Those of [`select_topic`]; a message that does not decode (naming its offset), a non-finite
/// value, a header stamp that does not increase; several temperature topics and none chosen.
pub fn imu_series(
    bag: &Bag,
    choice: TopicChoice<'_>,
    input: &str,
) -> Result<ImuExtract, ReadError> {
    let topic = select_topic(bag, MessageType::Imu, choice.imu, "--topic", input)?;
    let mut series = ImuSeries::new(SampleKind::Rates);
    let mut lags = Vec::with_capacity(topic.messages.len());
    for (k, m) in topic.messages.iter().enumerate() {
        let at = MessagePlace {
            topic: &topic.name,
            index: k,
            offset: m.offset,
        };
        let (sample, stamp_ns) = imu_message_sample(
            &m.data,
            &topic.encoding,
            at,
            series.time.last().copied(),
            input,
        )?;
        series.push(&sample);
        lags.push(stamp_ns.saturating_sub(m.log_time_ns));
    }
    if series.is_empty() {
        return Err(topic_error(
            input,
            format!("topic {} has no message", topic.name),
        ));
    }
    let temperature = temperature_topic(bag, choice.temperature, input)?;
    let temperature_topic = match temperature {
        Some(t) => {
            let (times, values) = temperature_records(t, input)?;
            series.temperature_c = Some(crate::ulog::px4::nearest_values(
                &series.time,
                &times,
                &values,
            ));
            Some(t.name.clone())
        }
        None => None,
    };
    Ok(ImuExtract {
        series,
        topic: topic.name.clone(),
        temperature_assignment: temperature_topic.as_ref().map(|_| NEAREST),
        temperature_topic,
        stamp_lag_s: StampLag::of(lags),
        frame: FRAME_NOTE,
        time: TIME_NOTE,
    })
}

/// Where a message is: its topic, its index in the topic and the file offset of its record.
#[derive(Debug, Clone, Copy)]
struct MessagePlace<'a> {
    topic: &'a str,
    index: usize,
    offset: u64,
}

/// An Imu message as a sample in FRD (ROS body axes x forward, y left, z up), checked as every
/// reader checks a sample ([`imu_sample_problem`]: finite, within 1e15 SI) and to come after
/// `previous`; with its header stamp, ns. The one decoding of the bag read whole and streamed.
fn imu_message_sample(
    data: &[u8],
    encoding: &Encoding,
    at: MessagePlace<'_>,
    previous: Option<Timestamp>,
    input: &str,
) -> Result<(ImuSample, i64), ReadError> {
    let MessagePlace {
        topic: name,
        index,
        offset,
    } = at;
    let imu = decode_imu(data, encoding, input, offset)?;
    let frd = |v: [f64; 3]| [v[0], -v[1], -v[2]];
    let sample = ImuSample {
        time: Timestamp::from_nanos(imu.stamp_ns),
        gyro: frd(imu.angular_velocity),
        accel: frd(imu.linear_acceleration),
        temperature_c: None,
    };
    if let Some(problem) = imu_sample_problem(sample.gyro, sample.accel, None) {
        return Err(topic_error(
            input,
            format!("at byte {offset}: {name} message {index}: {problem} (in FRD)"),
        ));
    }
    match previous {
        Some(previous) if sample.time <= previous => Err(topic_error(
            input,
            format!(
                "at byte {offset}: {name} message {index} is stamped {:.9} s, not after the \
                 previous message's {:.9} s",
                sample.time.as_seconds(),
                previous.as_seconds()
            ),
        )),
        _ => Ok((sample, imu.stamp_ns)),
    }
}

/// A Temperature message as (stamp, °C), checked as every reader checks a temperature
/// ([`temperature_problem`]); `None` for a NaN, "not measured". The one decoding of the bag
/// read whole and streamed.
fn temperature_message(
    data: &[u8],
    encoding: &Encoding,
    at: MessagePlace<'_>,
    input: &str,
) -> Result<Option<(Timestamp, f64)>, ReadError> {
    let t = decode_temperature(data, encoding, input, at.offset)?;
    if t.temperature_c.is_nan() {
        return Ok(None);
    }
    match temperature_problem(t.temperature_c) {
        Some(problem) => Err(topic_error(
            input,
            format!(
                "at byte {}: {} message {}: {problem}",
                at.offset, at.topic, at.index
            ),
        )),
        None => Ok(Some((Timestamp::from_nanos(t.stamp_ns), t.temperature_c))),
    }
}

/// The temperature topic: the one requested, else the only one, else none (several and none
/// requested: an error).
fn temperature_topic<'a>(
    bag: &'a Bag,
    requested: Option<&str>,
    input: &str,
) -> Result<Option<&'a Topic>, ReadError> {
    let count = bag
        .topics
        .iter()
        .filter(|t| is_candidate(t, MessageType::Temperature))
        .count();
    match (requested, count) {
        (None, 0) => Ok(None),
        _ => select_topic(
            bag,
            MessageType::Temperature,
            requested,
            "--temperature-topic",
            input,
        )
        .map(Some),
    }
}

/// A temperature topic's (stamps, °C), in stamp order; a NaN temperature is "not measured"
/// and left out (as the ULog reader does).
///
/// # Errors
/// A message that does not decode; a temperature outside the range every reader accepts
/// ([`temperature_problem`]: −80..150 °C, with a hint when it reads as kelvin; infinities
/// too), naming the message and its offset; no message with a temperature.
fn temperature_records(
    topic: &Topic,
    input: &str,
) -> Result<(Vec<Timestamp>, Vec<f64>), ReadError> {
    let mut records = Vec::with_capacity(topic.messages.len());
    for (k, m) in topic.messages.iter().enumerate() {
        let at = MessagePlace {
            topic: &topic.name,
            index: k,
            offset: m.offset,
        };
        records.extend(temperature_message(&m.data, &topic.encoding, at, input)?);
    }
    records.sort_by_key(|&(time, _)| time);
    if records.is_empty() {
        return Err(topic_error(
            input,
            format!(
                "temperature topic {} has no temperature ({} messages, every one NaN)",
                topic.name,
                topic.messages.len()
            ),
        ));
    }
    Ok(records.into_iter().unzip())
}

/// Where the fixes of [`gnss_fixes`] came from.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GnssExtract {
    /// The fixes, timed at the header stamps.
    #[serde(skip)]
    pub fixes: Vec<GnssFix>,
    /// The topic read.
    pub topic: String,
    /// Messages left out: `status.status` < 0 (no fix) or a non-finite position.
    pub messages_without_fix: usize,
    /// Header stamp minus record time of the fixes kept.
    pub stamp_lag_s: Option<StampLag>,
    /// What the height is.
    pub height: &'static str,
}

/// The GNSS fixes of `bag` (`NavSatFix`).
///
/// # Errors
/// Those of [`select_topic`]; a message that does not decode; a header stamp that does not
/// increase; no fix at all.
pub fn gnss_fixes(
    bag: &Bag,
    requested: Option<&str>,
    input: &str,
) -> Result<GnssExtract, ReadError> {
    let topic = select_topic(
        bag,
        MessageType::NavSatFix,
        requested,
        "--gnss-topic",
        input,
    )?;
    let mut fixes: Vec<GnssFix> = Vec::new();
    let (mut without, mut lags) = (0, Vec::new());
    for (k, m) in topic.messages.iter().enumerate() {
        let fix = decode_nav_sat_fix(&m.data, &topic.encoding, input, m.offset)?;
        let finite = [fix.latitude_deg, fix.longitude_deg, fix.altitude_m]
            .iter()
            .all(|v| v.is_finite());
        if fix.status < 0
            || !finite
            || fix.latitude_deg.abs() > 90.0
            || fix.longitude_deg.abs() > 180.0
        {
            without += 1;
            continue;
        }
        let time = Timestamp::from_nanos(fix.stamp_ns);
        if fixes.last().is_some_and(|p| time <= p.time) {
            return Err(topic_error(
                input,
                format!(
                    "at byte {}: {} message {k} is not stamped after the previous fix",
                    m.offset, topic.name
                ),
            ));
        }
        let c = fix.position_covariance;
        let sd = (fix.position_covariance_type != 0)
            .then(|| [c[4], c[0], c[8]].map(f64::sqrt))
            .filter(|sd| sd.iter().all(|v| v.is_finite() && *v > 0.0));
        fixes.push(GnssFix {
            time,
            latitude_rad: deg_to_rad(fix.latitude_deg),
            longitude_rad: deg_to_rad(fix.longitude_deg),
            height_m: fix.altitude_m,
            position_sd_ned_m: sd,
            velocity_ned_m_s: None,
            heading: None,
        });
        lags.push(fix.stamp_ns.saturating_sub(m.log_time_ns));
    }
    if fixes.is_empty() {
        return Err(topic_error(
            input,
            format!(
                "topic {} has no fix (status >= 0, finite position) in {} messages",
                topic.name, topic.count
            ),
        ));
    }
    Ok(GnssExtract {
        fixes,
        topic: topic.name.clone(),
        messages_without_fix: without,
        stamp_lag_s: StampLag::of(lags),
        height: "altitude above the WGS84 ellipsoid (NavSatFix.altitude); sd_n/sd_e/sd_u from the \
                 diagonal of position_covariance (east-north-up) when its type is not unknown",
    })
}

/// A [`Bag`] that keeps the bytes of the messages of `kinds` only (the others are counted).
struct Keeping<'k> {
    bag: Bag,
    kinds: &'k [MessageType],
}

impl Sink for Keeping<'_> {
    fn topic_index(&mut self, name: &str, type_name: &str, encoding: Encoding) -> usize {
        self.bag.topic_index(name, type_name, encoding)
    }

    fn wants(&self, k: usize) -> bool {
        self.bag.topics[k]
            .message_type
            .is_some_and(|t| self.kinds.contains(&t))
    }

    fn push(
        &mut self,
        k: usize,
        log_time_ns: i64,
        offset: u64,
        data: &[u8],
        input: &str,
    ) -> Result<(), ReadError> {
        self.bag.push(k, log_time_ns, offset, data, input)
    }

    fn count(&mut self, k: usize) {
        self.bag.count(k);
    }
}

/// How [`stream_imu_series`] reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StreamOptions {
    /// Samples a piece holds (at least 1).
    pub piece_len: usize,
    /// Whether to keep each sample's stamp lag (8 bytes a sample) for [`StampLag`].
    pub stamp_lags: bool,
    /// Whether to keep the `NavSatFix` messages (for [`gnss_fixes`]).
    pub gnss: bool,
}

/// What [`stream_imu_series`] read.
#[derive(Debug, Clone, PartialEq)]
pub struct StreamedImu {
    /// The IMU topic read.
    pub topic: String,
    /// The temperature topic, when there is one.
    pub temperature_topic: Option<String>,
    /// Samples delivered.
    pub samples: usize,
    /// Header stamp minus record time of the IMU messages, when asked for.
    pub stamp_lag_s: Option<StampLag>,
    /// The bag's topics with their counts, the messages of the `NavSatFix` topics kept when
    /// [`StreamOptions::gnss`] asks (no other message).
    pub bag: Bag,
}

/// The sink of the samples pass: topic `target`'s messages decoded, checked and delivered in
/// pieces, with the temperatures of `temperatures` (stamps, °C) assigned.
struct Samples<'d> {
    bag: Bag,
    target: usize,
    name: String,
    piece: ImuSeries,
    piece_len: usize,
    last: Option<Timestamp>,
    temperatures: Option<(Vec<Timestamp>, Vec<f64>)>,
    delivered: usize,
    /// Header stamp minus record time of each sample, ns, when asked for.
    lags: Option<Vec<i64>>,
    deliver: &'d mut dyn FnMut(ImuSeries) -> Result<(), ReadError>,
}

impl Samples<'_> {
    /// Hands the piece so far to the caller, its temperatures assigned.
    fn flush(&mut self) -> Result<(), ReadError> {
        if self.piece.is_empty() {
            return Ok(());
        }
        let mut piece = std::mem::replace(&mut self.piece, ImuSeries::new(SampleKind::Rates));
        if let Some((times, values)) = &self.temperatures {
            piece.temperature_c =
                Some(crate::ulog::px4::nearest_values(&piece.time, times, values));
        }
        self.delivered += piece.len();
        (self.deliver)(piece)
    }
}

impl Sink for Samples<'_> {
    fn topic_index(&mut self, name: &str, type_name: &str, encoding: Encoding) -> usize {
        self.bag.topic_index(name, type_name, encoding)
    }

    fn wants(&self, k: usize) -> bool {
        k == self.target
    }

    fn push(
        &mut self,
        k: usize,
        log_time_ns: i64,
        offset: u64,
        data: &[u8],
        input: &str,
    ) -> Result<(), ReadError> {
        let index = self.bag.topics[k].count;
        self.bag.count(k);
        let at = MessagePlace {
            topic: &self.name,
            index,
            offset,
        };
        let encoding = &self.bag.topics[k].encoding;
        let (sample, stamp_ns) = imu_message_sample(data, encoding, at, self.last, input)?;
        self.last = Some(sample.time);
        if let Some(lags) = &mut self.lags {
            lags.push(stamp_ns.saturating_sub(log_time_ns));
        }
        self.piece.push(&sample);
        match self.piece.len() >= self.piece_len {
            true => self.flush(),
            false => Ok(()),
        }
    }

    fn count(&mut self, k: usize) {
        self.bag.count(k);
    }
}

/// The IMU of the MCAP bag or ROS 1 bag at `path` (not gzip-compressed) as rates in FRD, read
/// in two passes record by record and
/// handed to `deliver` in pieces of `piece_len` samples (at least 1) as they are decoded, each
/// with `temp_c` from the temperature topic as [`imu_series`] assigns it: memory is a piece
/// and the chosen temperature topic's values (16 bytes a message; and 8 bytes a sample when
/// `options` ask for the [`StampLag`]), whatever the bag's length. The first pass lists the
/// topics (and keeps the `NavSatFix` messages when asked); the second decodes the chosen
/// temperature topic, the third the chosen IMU topic. The topics
/// are chosen, and every sample checked, as [`imu_series`] does.
///
/// # Errors
/// Those of [`super::read_bag_into`] and of [`imu_series`]; those of `deliver`, which stop the
/// reading.
pub fn stream_imu_series(
    path: &Path,
    choice: TopicChoice<'_>,
    options: StreamOptions,
    deliver: &mut dyn FnMut(ImuSeries) -> Result<(), ReadError>,
) -> Result<StreamedImu, ReadError> {
    let StreamOptions {
        piece_len,
        stamp_lags,
        gnss,
    } = options;
    let input = path.display().to_string();
    let format = super::detect_file(path, &input)?;
    let mut survey = Keeping {
        bag: Bag::new(format),
        kinds: match gnss {
            true => &[MessageType::NavSatFix],
            false => &[],
        },
    };
    super::read_bag_into(path, format, &mut survey)?;
    let bag = survey.bag;
    let topic = select_topic(&bag, MessageType::Imu, choice.imu, "--topic", &input)?;
    let target = bag
        .topics
        .iter()
        .position(|t| std::ptr::eq(t, topic))
        .unwrap_or(usize::MAX);
    let temperature = temperature_topic(&bag, choice.temperature, &input)?;
    let temperatures = match temperature {
        Some(t) => Some(stream_temperatures(path, &bag, t, &input)?),
        None => None,
    };
    let mut samples = Samples {
        bag: Bag::new(format),
        target,
        name: topic.name.clone(),
        piece: ImuSeries::new(SampleKind::Rates),
        piece_len: piece_len.max(1),
        last: None,
        temperatures,
        delivered: 0,
        lags: stamp_lags.then(Vec::new),
        deliver,
    };
    super::read_bag_into(path, format, &mut samples)?;
    samples.flush()?;
    if samples.delivered == 0 {
        return Err(topic_error(
            &input,
            format!("topic {} has no message", topic.name),
        ));
    }
    let stamp_lag_s = samples.lags.take().and_then(StampLag::of);
    let (topic, temperature_topic) = (topic.name.clone(), temperature.map(|t| t.name.clone()));
    Ok(StreamedImu {
        topic,
        temperature_topic,
        samples: samples.delivered,
        stamp_lag_s,
        bag,
    })
}

/// [`imu_series`] of the MCAP or ROS 1 bag at `path`, read record by record ([`stream_imu_series`]):
/// memory is the series and the messages of the temperature and `NavSatFix` topics, not the
/// bag's bytes nor its IMU messages.
///
/// # Errors
/// Those of [`stream_imu_series`].
pub fn stream_imu_extract(
    path: &Path,
    choice: TopicChoice<'_>,
) -> Result<(ImuExtract, Bag), ReadError> {
    let mut series = ImuSeries::new(SampleKind::Rates);
    let mut temperatures: Vec<f64> = Vec::new();
    let options = StreamOptions {
        piece_len: 1 << 16,
        stamp_lags: true,
        gnss: true,
    };
    let streamed = stream_imu_series(path, choice, options, &mut |piece| {
        series.time.extend_from_slice(&piece.time);
        for (all, part) in series.channels.iter_mut().zip(&piece.channels) {
            all.extend_from_slice(part);
        }
        temperatures.extend(piece.temperature_c.iter().flatten());
        Ok(())
    })?;
    if streamed.temperature_topic.is_some() {
        series.temperature_c = Some(temperatures);
    }
    let extract = ImuExtract {
        series,
        topic: streamed.topic,
        temperature_assignment: streamed.temperature_topic.as_ref().map(|_| NEAREST),
        temperature_topic: streamed.temperature_topic,
        stamp_lag_s: streamed.stamp_lag_s,
        frame: FRAME_NOTE,
        time: TIME_NOTE,
    };
    Ok((extract, streamed.bag))
}

/// The sink of the temperature pass: topic `target`'s messages decoded and checked as
/// [`temperature_records`] does, 16 bytes a message.
struct Temperatures {
    bag: Bag,
    target: usize,
    name: String,
    records: Vec<(Timestamp, f64)>,
}

impl Sink for Temperatures {
    fn topic_index(&mut self, name: &str, type_name: &str, encoding: Encoding) -> usize {
        self.bag.topic_index(name, type_name, encoding)
    }

    fn wants(&self, k: usize) -> bool {
        k == self.target
    }

    fn push(
        &mut self,
        k: usize,
        _log_time_ns: i64,
        offset: u64,
        data: &[u8],
        input: &str,
    ) -> Result<(), ReadError> {
        let index = self.bag.topics[k].count;
        self.bag.count(k);
        let at = MessagePlace {
            topic: &self.name,
            index,
            offset,
        };
        let encoding = &self.bag.topics[k].encoding;
        self.records
            .extend(temperature_message(data, encoding, at, input)?);
        Ok(())
    }

    fn count(&mut self, k: usize) {
        self.bag.count(k);
    }
}

/// The (stamps, °C) of `topic` of `bag` (the survey of the bag at `path`), in stamp order, read
/// in a pass of their own as [`temperature_records`] reads them from a bag in memory.
fn stream_temperatures(
    path: &Path,
    bag: &Bag,
    topic: &Topic,
    input: &str,
) -> Result<(Vec<Timestamp>, Vec<f64>), ReadError> {
    let mut sink = Temperatures {
        bag: Bag::new(bag.format),
        target: bag
            .topics
            .iter()
            .position(|t| std::ptr::eq(t, topic))
            .unwrap_or(usize::MAX),
        name: topic.name.clone(),
        records: Vec::new(),
    };
    super::read_bag_into(path, bag.format, &mut sink)?;
    let mut records = sink.records;
    records.sort_by_key(|&(time, _)| time);
    if records.is_empty() {
        return Err(topic_error(
            input,
            format!(
                "temperature topic {} has no temperature ({} messages, every one NaN)",
                topic.name, topic.count
            ),
        ));
    }
    Ok(records.into_iter().unzip())
}
