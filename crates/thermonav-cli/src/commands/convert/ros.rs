//! `thermonav convert BAG`: a ROS 2 bag (MCAP or SQLite `.db3`) or a ROS 1 bag to the canonical
//! IMU CSV (`--out`, rates in FRD at the header stamps, `temp_c` from the temperature topic),
//! optionally the canonical GNSS CSV (`--gnss-out`), and a sidecar `OUT.json` saying what was
//! read: the topics, the time and axes used, how far header stamps lie from record times.
//! Everything is read and checked before the first file is written. An MCAP or ROS 1 bag is
//! read record by record: memory is the series (about 64 bytes a sample), not the bag.

use crate::args::{ConvertArgs, ForeignFormatArg};
use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use serde::Serialize;
use thermonav_io::ros::extract::{
    GnssExtract, ImuExtract, TopicChoice, TopicSummary, gnss_fixes, imu_series, stream_imu_extract,
};
use thermonav_io::ros::{Bag, BagFormat, read_bag_file};

/// The sidecar: where the series came from, their time and axes.
#[derive(Serialize)]
struct BagRecord<'a> {
    input: String,
    format: BagFormat,
    imu: &'a ImuExtract,
    imu_samples: usize,
    gnss: Option<&'a GnssExtract>,
    gnss_fixes: Option<usize>,
    topics: Vec<TopicSummary>,
}

/// The bag format of a `--format` value, if it is one.
pub fn bag_format(format: ForeignFormatArg) -> Option<BagFormat> {
    match format {
        ForeignFormatArg::Ros2Mcap => Some(BagFormat::Ros2Mcap),
        ForeignFormatArg::Ros2Db3 => Some(BagFormat::Ros2Db3),
        ForeignFormatArg::Ros1Bag => Some(BagFormat::Ros1Bag),
        _ => None,
    }
}

/// The `--format` value of a bag format.
pub fn format_arg(format: BagFormat) -> ForeignFormatArg {
    match format {
        BagFormat::Ros2Mcap => ForeignFormatArg::Ros2Mcap,
        BagFormat::Ros2Db3 => ForeignFormatArg::Ros2Db3,
        BagFormat::Ros1Bag => ForeignFormatArg::Ros1Bag,
    }
}

/// The topic options of `args`.
fn choice(args: &ConvertArgs) -> TopicChoice<'_> {
    TopicChoice {
        imu: args.topics.topic.as_deref(),
        temperature: args.topics.temperature_topic.as_deref(),
        gnss: args.gnss_topic.as_deref(),
    }
}

/// Refuses the topic options for a format that is not a bag.
pub fn reject_topics(format: ForeignFormatArg, args: &ConvertArgs) -> Result<(), Failure> {
    let given = args.topics.topic.is_some()
        || args.gnss_topic.is_some()
        || args.topics.temperature_topic.is_some();
    match given && bag_format(format).is_none() {
        true => Err(anyhow!(
            "--topic, --gnss-topic and --temperature-topic go with --format ros2-mcap, ros2-db3 or ros1-bag only"
        ))
        .usage(),
        false => Ok(()),
    }
}

/// The IMU of the bag and the bag (its topics, and the messages of the GNSS topics): an MCAP
/// or ROS 1 bag not gzip-compressed is read record by record (memory is the series, not the
/// bag), a ROS 2 bag folder file after file.
fn read_imu(
    format: ForeignFormatArg,
    args: &ConvertArgs,
    input: &str,
) -> Result<(ImuExtract, Bag), Failure> {
    let format = bag_format(format);
    let streamed = format.is_none_or(|f| f != BagFormat::Ros2Db3) || args.input.is_dir();
    if streamed && crate::inputs::is_streamed_bag(&args.input) {
        return stream_imu_extract(&args.input, choice(args)).data();
    }
    let bag = read_bag_file(&args.input, format).data()?;
    let imu = imu_series(&bag, choice(args), input).data()?;
    Ok((imu, bag))
}

/// Converts a bag; returns the number of IMU samples and what they are.
pub fn convert(
    format: ForeignFormatArg,
    args: &ConvertArgs,
) -> Result<(usize, &'static str), Failure> {
    let input = args.input.display().to_string();
    let (imu, bag) = read_imu(format, args, &input)?;
    let gnss = match &args.gnss_out {
        Some(_) => Some(gnss_fixes(&bag, args.gnss_topic.as_deref(), &input).data()?),
        None => None,
    };
    if imu.temperature_topic.is_none() {
        eprintln!("note: no sensor_msgs/Temperature topic: no temp_c column");
    }
    let record = BagRecord {
        input,
        format: bag.format,
        imu: &imu,
        imu_samples: imu.series.len(),
        gnss: gnss.as_ref(),
        gnss_fixes: gnss.as_ref().map(|g| g.fixes.len()),
        topics: TopicSummary::of_bag(&bag),
    };
    let fixes = gnss.as_ref().map(|g| g.fixes.as_slice());
    super::write_log_outputs(args, &imu.series, fixes, &record)?;
    Ok((imu.series.len(), "IMU samples (rates)"))
}
