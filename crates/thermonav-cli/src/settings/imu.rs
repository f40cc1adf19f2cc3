//! How a command takes its IMU record: the mounting (`--imu-rotation`, every command that
//! reads an IMU), the rate of a file without times (`--rate-hz`) and any subset of the six
//! channels (the static analyses, `characterize` and `allan`), resolved once into the
//! reader's [`ImuOptions`]; the topics of a ROS bag (`--topic`, `--temperature-topic`) into
//! [`TopicNames`]. Navigation needs all six channels: its reader refuses a subset,
//! naming every absent column.

use crate::args::{BagTopicArgs, ImuRotationArgs, SampleRateArgs};
use crate::failure::Failure;
use thermonav::setting::positive;
use thermonav_io::ros::extract::TopicNames;
use thermonav_io::{ChannelRule, ImuOptions};

/// The reader's options from `--imu-rotation` alone (times from the file's `t_s`, all six
/// channels).
pub fn rotation_only(rotation: &ImuRotationArgs) -> ImuOptions {
    ImuOptions {
        mounting: rotation.imu_rotation,
        ..ImuOptions::default()
    }
}

/// The options of a static analysis: `--imu-rotation`, `--rate-hz` (a positive rate) and
/// any subset of the channels.
pub fn options(rotation: &ImuRotationArgs, rate: &SampleRateArgs) -> Result<ImuOptions, Failure> {
    let rate_hz = match rate.rate_hz {
        Some(hz) => Some(positive("rate_hz", hz)?),
        None => None,
    };
    Ok(ImuOptions {
        rate_hz,
        channels: ChannelRule::AnySubset,
        ..rotation_only(rotation)
    })
}

/// The mounting as recorded in JSON outputs and sidecars: its text (`-y,x,z`,
/// `rpy:0,0,90`), which `--imu-rotation` reads back; `None` without one.
pub fn rotation_text(options: &ImuOptions) -> Option<String> {
    options.mounting.map(|m| m.to_string())
}

/// The topics `--topic` and `--temperature-topic` name (none: each the only one of its type).
pub fn topics(args: &BagTopicArgs) -> TopicNames {
    TopicNames {
        imu: args.topic.clone(),
        temperature: args.temperature_topic.clone(),
        gnss: None,
    }
}
