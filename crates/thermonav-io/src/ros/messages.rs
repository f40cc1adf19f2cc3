//! The message types read from bags, decoded from their two serialisations:
//!
//! - **CDR** (ROS 2, OMG DDS-XTYPES "XCDR1" plain encapsulation): a 4-byte encapsulation header
//!   (`00 01` little-endian, `00 00` big-endian, then two option bytes), then the fields in
//!   order, each primitive aligned to its own size counted from the end of that header; a string
//!   is a u32 length that counts its terminating NUL, then the bytes; fixed arrays are their
//!   elements; `builtin_interfaces/Time` is `int32 sec, uint32 nanosec`.
//! - **ROS 1** serialisation: little-endian, no alignment, a string is a u32 length and the bytes
//!   (no NUL); `std_msgs/Header` starts with `uint32 seq` and its `time` is `uint32 secs,
//!   uint32 nsecs`.
//!
//! Field order from the message definitions (`sensor_msgs/Imu`, `NavSatFix`, `NavSatStatus`,
//! `Temperature`, `geometry_msgs/TwistStamped`, `std_msgs/Header`), the same in ROS 1 and 2.

use super::bytes::at;
use crate::error::ReadError;

/// The serialisation of a topic's messages.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Encoding {
    /// ROS 2 CDR (an MCAP channel's `cdr`, a db3 topic's `cdr`).
    Cdr,
    /// ROS 1 serialisation (a ROS 1 bag, an MCAP channel's `ros1`).
    Ros1,
    /// Anything else (named as the file gives it): counted, never decoded.
    Other(String),
}

/// A message type this module decodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MessageType {
    /// `sensor_msgs/msg/Imu`.
    Imu,
    /// `sensor_msgs/msg/NavSatFix`.
    NavSatFix,
    /// `sensor_msgs/msg/Temperature`.
    Temperature,
    /// `geometry_msgs/msg/TwistStamped`.
    TwistStamped,
}

impl MessageType {
    /// The ROS 2 name of the type.
    pub fn name(self) -> &'static str {
        match self {
            Self::Imu => "sensor_msgs/msg/Imu",
            Self::NavSatFix => "sensor_msgs/msg/NavSatFix",
            Self::Temperature => "sensor_msgs/msg/Temperature",
            Self::TwistStamped => "geometry_msgs/msg/TwistStamped",
        }
    }

    /// The type named `name` in ROS 2 (`sensor_msgs/msg/Imu`) or ROS 1 (`sensor_msgs/Imu`) form.
    pub fn of(name: &str) -> Option<Self> {
        [
            Self::Imu,
            Self::NavSatFix,
            Self::Temperature,
            Self::TwistStamped,
        ]
        .into_iter()
        .find(|t| normalized_type(name) == t.name())
    }
}

impl MessageType {
    /// Fewest bytes a serialised message of the type takes, in either serialisation: a
    /// `std_msgs/Header` at its smallest (the stamp's 8 bytes and an empty `frame_id`'s 4-byte
    /// length) and the fixed fields, without the CDR encapsulation header, the ROS 1 `seq`,
    /// the CDR string's NUL or any alignment padding (each only adds bytes). A shorter message
    /// cannot be one of the type.
    pub fn min_bytes(self) -> usize {
        const HEADER: usize = 8 + 4;
        HEADER
            + match self {
                // orientation (4), its covariance (9), angular velocity (3) and its covariance
                // (9), linear acceleration (3) and its covariance (9): 37 float64.
                Self::Imu => 37 * 8,
                // status.status int8, status.service uint16, latitude, longitude, altitude,
                // position_covariance (9) float64, position_covariance_type uint8.
                Self::NavSatFix => 1 + 2 + 3 * 8 + 9 * 8 + 1,
                // temperature and variance.
                Self::Temperature => 2 * 8,
                // twist.linear and twist.angular.
                Self::TwistStamped => 6 * 8,
            }
    }
}

/// A type name in ROS 2 form: `pkg/Name` becomes `pkg/msg/Name`.
pub fn normalized_type(name: &str) -> String {
    match name.split('/').collect::<Vec<_>>()[..] {
        [package, base] => format!("{package}/msg/{base}"),
        _ => name.to_string(),
    }
}

/// Reads primitives of one message, checking every length against the bytes left.
pub struct Fields<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// Where alignment is counted from (4 in CDR: after the encapsulation header).
    origin: usize,
    big_endian: bool,
    aligned: bool,
    ros1: bool,
    input: &'a str,
    /// File offset of the message, for errors.
    offset: u64,
}

impl<'a> Fields<'a> {
    /// A reader of one message in `encoding`, found at file offset `offset` of `input`.
    ///
    /// # Errors
    /// A CDR message shorter than its header, or of another encapsulation than plain CDR.
    pub fn new(
        bytes: &'a [u8],
        encoding: &Encoding,
        input: &'a str,
        offset: u64,
    ) -> Result<Self, ReadError> {
        let mut fields = Self {
            bytes,
            pos: 0,
            origin: 0,
            big_endian: false,
            aligned: false,
            ros1: true,
            input,
            offset,
        };
        if *encoding == Encoding::Cdr {
            let header = fields.take(4, "the 4-byte CDR encapsulation header")?;
            fields.big_endian = match (header[0], header[1]) {
                (0, 0) => true,
                (0, 1) => false,
                (a, b) => {
                    return Err(fields.error(format_args!(
                        "CDR encapsulation {a:02x} {b:02x} is not supported (expected 00 01 \
                         little-endian or 00 00 big-endian plain CDR)"
                    )));
                }
            };
            (fields.origin, fields.aligned, fields.ros1) = (4, true, false);
        }
        Ok(fields)
    }

    fn error(&self, what: impl std::fmt::Display) -> ReadError {
        at(
            self.input,
            self.offset,
            format_args!("message byte {}: {what}", self.pos),
        )
    }

    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], ReadError> {
        if n > self.bytes.len() - self.pos {
            return Err(self.error(format_args!(
                "expected {what} ({n} bytes), but the message has {} bytes left (a message of \
                 another type, or cut short)",
                self.bytes.len() - self.pos
            )));
        }
        let out = &self.bytes[self.pos..self.pos + n];
        self.pos += n;
        Ok(out)
    }

    /// `N` bytes of a primitive, aligned and in little-endian order.
    fn primitive<const N: usize>(&mut self, what: &str) -> Result<[u8; N], ReadError> {
        if self.aligned {
            let misalignment = (self.pos - self.origin) % N;
            if misalignment != 0 {
                self.take(N - misalignment, "alignment padding")?;
            }
        }
        let slice = self.take(N, what)?;
        let mut out: [u8; N] = std::array::from_fn(|i| slice[i]);
        if self.big_endian {
            out.reverse();
        }
        Ok(out)
    }

    fn f64(&mut self, what: &str) -> Result<f64, ReadError> {
        self.primitive(what).map(f64::from_le_bytes)
    }

    fn u32(&mut self, what: &str) -> Result<u32, ReadError> {
        self.primitive(what).map(u32::from_le_bytes)
    }

    fn f64s<const N: usize>(&mut self, what: &str) -> Result<[f64; N], ReadError> {
        let mut out = [0.0; N];
        for v in &mut out {
            *v = self.f64(what)?;
        }
        Ok(out)
    }

    /// A string, skipped (its length checked against the bytes left).
    fn skip_string(&mut self, what: &str) -> Result<(), ReadError> {
        let len = self.u32(what)? as usize;
        self.take(len, what).map(|_| ())
    }

    /// A `std_msgs/Header`: its stamp, ns since the epoch of the bag's clock.
    fn header(&mut self) -> Result<i64, ReadError> {
        if self.ros1 {
            self.u32("header.seq")?;
        }
        let sec_bytes: [u8; 4] = self.primitive("header.stamp.sec")?;
        let sec = match self.ros1 {
            true => i64::from(u32::from_le_bytes(sec_bytes)),
            false => i64::from(i32::from_le_bytes(sec_bytes)),
        };
        let nanosec = self.u32("header.stamp.nanosec")?;
        if nanosec >= 1_000_000_000 {
            return Err(self.error(format_args!(
                "header.stamp.nanosec is {nanosec} (expected below 1e9)"
            )));
        }
        self.skip_string("header.frame_id")?;
        Ok(sec * 1_000_000_000 + i64::from(nanosec))
    }
}

/// A `sensor_msgs/Imu` (orientation and its covariance are read past, not kept).
#[derive(Debug, Clone, PartialEq)]
pub struct ImuMessage {
    /// Header stamp, ns.
    pub stamp_ns: i64,
    /// `angular_velocity`, rad/s, ROS body axes.
    pub angular_velocity: [f64; 3],
    /// `angular_velocity_covariance`, row-major.
    pub angular_velocity_covariance: [f64; 9],
    /// `linear_acceleration`, m/s², ROS body axes.
    pub linear_acceleration: [f64; 3],
    /// `linear_acceleration_covariance`, row-major.
    pub linear_acceleration_covariance: [f64; 9],
}

/// A `sensor_msgs/NavSatFix`.
#[derive(Debug, Clone, PartialEq)]
pub struct NavSatFixMessage {
    /// Header stamp, ns.
    pub stamp_ns: i64,
    /// `status.status`: -1 no fix, 0 fix, 1 SBAS, 2 GBAS.
    pub status: i8,
    /// `status.service` bits.
    pub service: u16,
    /// Latitude, degrees.
    pub latitude_deg: f64,
    /// Longitude, degrees.
    pub longitude_deg: f64,
    /// Altitude above the WGS84 ellipsoid, m.
    pub altitude_m: f64,
    /// Position covariance in east-north-up, m², row-major.
    pub position_covariance: [f64; 9],
    /// 0 unknown, 1 approximated, 2 diagonal known, 3 known.
    pub position_covariance_type: u8,
}

/// A `sensor_msgs/Temperature`.
#[derive(Debug, Clone, PartialEq)]
pub struct TemperatureMessage {
    /// Header stamp, ns.
    pub stamp_ns: i64,
    /// °C.
    pub temperature_c: f64,
    /// Variance, °C², 0 when unknown.
    pub variance: f64,
}

/// A `geometry_msgs/TwistStamped`.
#[derive(Debug, Clone, PartialEq)]
pub struct TwistStampedMessage {
    /// Header stamp, ns.
    pub stamp_ns: i64,
    /// `twist.linear`, m/s, in the header's frame.
    pub linear: [f64; 3],
    /// `twist.angular`, rad/s, in the header's frame.
    pub angular: [f64; 3],
}

/// Decodes a `sensor_msgs/Imu`.
///
/// # Errors
/// A message shorter than the type, a bad stamp or an unsupported CDR encapsulation, naming
/// the file offset `offset` of the message and the field.
pub fn decode_imu(
    bytes: &[u8],
    encoding: &Encoding,
    input: &str,
    offset: u64,
) -> Result<ImuMessage, ReadError> {
    let mut f = Fields::new(bytes, encoding, input, offset)?;
    let stamp_ns = f.header()?;
    f.f64s::<4>("orientation")?;
    f.f64s::<9>("orientation_covariance")?;
    Ok(ImuMessage {
        stamp_ns,
        angular_velocity: f.f64s("angular_velocity")?,
        angular_velocity_covariance: f.f64s("angular_velocity_covariance")?,
        linear_acceleration: f.f64s("linear_acceleration")?,
        linear_acceleration_covariance: f.f64s("linear_acceleration_covariance")?,
    })
}

/// Decodes a `sensor_msgs/NavSatFix`.
///
/// # Errors
/// As [`decode_imu`].
pub fn decode_nav_sat_fix(
    bytes: &[u8],
    encoding: &Encoding,
    input: &str,
    offset: u64,
) -> Result<NavSatFixMessage, ReadError> {
    let mut f = Fields::new(bytes, encoding, input, offset)?;
    let stamp_ns = f.header()?;
    let status = f.primitive::<1>("status.status")?[0] as i8;
    let service = u16::from_le_bytes(f.primitive("status.service")?);
    let [latitude_deg, longitude_deg, altitude_m] = f.f64s("latitude, longitude, altitude")?;
    Ok(NavSatFixMessage {
        stamp_ns,
        status,
        service,
        latitude_deg,
        longitude_deg,
        altitude_m,
        position_covariance: f.f64s("position_covariance")?,
        position_covariance_type: f.primitive::<1>("position_covariance_type")?[0],
    })
}

/// Decodes a `sensor_msgs/Temperature`.
///
/// # Errors
/// As [`decode_imu`].
pub fn decode_temperature(
    bytes: &[u8],
    encoding: &Encoding,
    input: &str,
    offset: u64,
) -> Result<TemperatureMessage, ReadError> {
    let mut f = Fields::new(bytes, encoding, input, offset)?;
    Ok(TemperatureMessage {
        stamp_ns: f.header()?,
        temperature_c: f.f64("temperature")?,
        variance: f.f64("variance")?,
    })
}

/// Decodes a `geometry_msgs/TwistStamped`.
///
/// # Errors
/// As [`decode_imu`].
pub fn decode_twist_stamped(
    bytes: &[u8],
    encoding: &Encoding,
    input: &str,
    offset: u64,
) -> Result<TwistStampedMessage, ReadError> {
    let mut f = Fields::new(bytes, encoding, input, offset)?;
    Ok(TwistStampedMessage {
        stamp_ns: f.header()?,
        linear: f.f64s("twist.linear")?,
        angular: f.f64s("twist.angular")?,
    })
}
