//! PX4 ULog files (`.ulg`), read from the public format description (PX4 user guide, "ULog File
//! Format", file version 1).
//!
//! A file is a 16-byte header (the magic `ULog` 0x01 0x12 0x35, a version byte, the start time
//! in µs since boot), then messages of `u16 size`, `u8 type`, `size` bytes of payload, all
//! little-endian. Definitions: 'B' flag bits, 'F' formats, 'I' info, 'M' multi-part info, 'P'
//! parameters, 'Q' default parameters. Data: 'A' subscribe a format under a message id, 'R'
//! unsubscribe, 'D' data, 'L' log text, 'C' tagged log text, 'S' sync, 'O' dropout.
//!
//! [`decode_ulog`] keeps the records of every subscription as raw bytes and flattens each format
//! ([`format`](mod@format)) into primitive fields at byte offsets, so any topic can be read by field name
//! ([`Topic`]). [`px4`] extracts the IMU, its temperature and GNSS into thermonav's series.
//!
//! What is skipped, and counted: messages of unknown type (the format allows new types and
//! tells readers to skip them), data for a message id never subscribed. A partial message at
//! the very end (the logger stopped mid-write, common after a power cut) is dropped and its
//! length reported; a file cut inside its header or its definitions is an error. An unknown
//! bit in the incompatible flags is an error (the format forbids reading such a file). With
//! the "data appended" flag, the appended data follows in the same message stream and is
//! read in order.

pub mod format;
pub mod px4;

use crate::error::{ReadError, ReadErrorKind};
use format::{FlatField, FlatLayout, FormatDefinition, Primitive, flatten, parse_format};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// The first 7 bytes of every ULog file.
pub const MAGIC: [u8; 7] = *b"ULog\x01\x12\x35";

/// Header bytes: magic, version, start timestamp.
const HEADER_BYTES: usize = 16;
/// Message header bytes: size (u16) and type (u8).
const MESSAGE_HEADER_BYTES: usize = 3;

/// One subscription ('A' message) with all its data records.
#[derive(Debug, Clone)]
pub struct Subscription {
    /// The format's name (the uORB topic).
    pub name: String,
    /// Instance of the topic (`multi_id`).
    pub multi_id: u8,
    /// The layout of a record.
    pub layout: FlatLayout,
    /// The records, `layout.size` bytes each, back to back.
    records: Vec<u8>,
    /// File offset of each record's message, bytes.
    offsets: Vec<u64>,
}

/// A log text ('L', or 'C' with its tag).
#[derive(Debug, Clone, PartialEq)]
pub struct LoggedText {
    /// Log level, as in syslog ('0'..'7' as ASCII digits in PX4).
    pub level: u8,
    /// Tag of a 'C' message; `None` for 'L'.
    pub tag: Option<u16>,
    /// Time, µs since boot.
    pub timestamp_us: u64,
    /// The text.
    pub text: String,
}

/// Messages that were skipped, by reason.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Skipped {
    /// Messages of an unknown type, by type byte.
    pub unknown_types: BTreeMap<u8, usize>,
    /// 'D' messages for a message id that no 'A' message subscribed.
    pub unsubscribed_data: usize,
    /// Length of a partial message at the end of the file, bytes (0 when the file ends cleanly).
    pub truncated_tail_bytes: usize,
}

/// A decoded ULog file.
#[derive(Debug, Clone)]
pub struct Ulog {
    /// File format version (header byte 7).
    pub version: u8,
    /// Start of logging, µs since boot.
    pub start_timestamp_us: u64,
    /// Largest timestamp of any data record or log text, µs since boot.
    pub last_timestamp_us: u64,
    /// Format definitions by name.
    pub formats: BTreeMap<String, FormatDefinition>,
    /// 'I' information values by key (`char[5] sys_name` → `sys_name`).
    pub info: BTreeMap<String, InfoValue>,
    /// Keys of 'M' multi-part information, with their number of values (a value is a
    /// message with `is_continued` = 0 and the messages continuing it).
    pub multi_info: BTreeMap<String, usize>,
    /// Number of parameters in the definitions ('P').
    pub initial_parameters: usize,
    /// Number of parameter changes in the data section ('P' after the first 'A').
    pub changed_parameters: usize,
    /// Number of default-parameter messages ('Q').
    pub default_parameters: usize,
    /// Subscriptions in the order of their 'A' messages.
    pub subscriptions: Vec<Subscription>,
    /// Log texts ('L' and 'C').
    pub logged: Vec<LoggedText>,
    /// Dropouts ('O'): lost data, each with its length in ms.
    pub dropouts_ms: Vec<u16>,
    /// Sync messages ('S').
    pub syncs: usize,
    /// What was skipped.
    pub skipped: Skipped,
}

/// An information value.
#[derive(Debug, Clone, PartialEq)]
pub enum InfoValue {
    /// `char[n]`: text (lossy UTF-8).
    Text(String),
    /// An integer type.
    Integer(i128),
    /// `float` or `double`.
    Real(f64),
    /// Anything else (arrays of numbers, nested types): the raw bytes.
    Bytes(Vec<u8>),
}

/// Reads and decodes a ULog file.
///
/// # Errors
/// [`ReadErrorKind::Open`]/[`ReadErrorKind::Read`], and those of [`decode_ulog`].
pub fn read_ulog_file(path: impl AsRef<Path>) -> Result<Ulog, ReadError> {
    let (bytes, input) = crate::read_whole_file(path.as_ref())?;
    decode_ulog(&bytes, &input)
}

/// A problem at a byte offset of `input`.
fn at(input: &str, offset: usize, what: String) -> ReadError {
    ReadError::new(
        input,
        None,
        ReadErrorKind::Unusable(format!("at byte {offset}: {what}")),
    )
}

/// Decodes the bytes of a ULog file, named `input` in errors.
///
/// # Errors
/// [`ReadErrorKind::Unusable`] with the byte offset and what was expected there: a file
/// shorter than the header, a wrong magic, a message cut short before the first
/// subscription, an unknown incompatible flag, a format that does not parse or names an
/// unknown type, a subscription of an undefined format, a data record shorter than its format.
pub fn decode_ulog(bytes: &[u8], input: &str) -> Result<Ulog, ReadError> {
    if bytes.len() < HEADER_BYTES {
        return Err(at(
            input,
            bytes.len(),
            format!("the file ends inside the {HEADER_BYTES}-byte ULog header"),
        ));
    }
    if bytes[..MAGIC.len()] != MAGIC {
        return Err(at(
            input,
            0,
            "expected the ULog magic bytes \"ULog\" 01 12 35 (not a PX4 ULog file)".to_string(),
        ));
    }
    let mut decoder = Decoder {
        input,
        log: Ulog {
            version: bytes[7],
            start_timestamp_us: u64_at(bytes, 8),
            last_timestamp_us: 0,
            formats: BTreeMap::new(),
            info: BTreeMap::new(),
            multi_info: BTreeMap::new(),
            initial_parameters: 0,
            changed_parameters: 0,
            default_parameters: 0,
            subscriptions: Vec::new(),
            logged: Vec::new(),
            dropouts_ms: Vec::new(),
            syncs: 0,
            skipped: Skipped::default(),
        },
        by_msg_id: HashMap::new(),
        in_data: false,
        layout_fields: 0,
    };
    let mut offset = HEADER_BYTES;
    while offset < bytes.len() {
        let rest = &bytes[offset..];
        let size = match rest.len() >= MESSAGE_HEADER_BYTES {
            true => usize::from(u16::from_le_bytes([rest[0], rest[1]])),
            false => usize::MAX,
        };
        if size == usize::MAX || rest.len() < MESSAGE_HEADER_BYTES + size {
            if !decoder.in_data {
                return Err(at(
                    input,
                    offset,
                    format!(
                        "the file ends inside a message of the definitions section ({} bytes \
                         left; a truncated file)",
                        rest.len()
                    ),
                ));
            }
            decoder.log.skipped.truncated_tail_bytes = rest.len();
            break;
        }
        let payload = &rest[MESSAGE_HEADER_BYTES..MESSAGE_HEADER_BYTES + size];
        decoder.message(rest[2], payload, offset)?;
        offset += MESSAGE_HEADER_BYTES + size;
    }
    Ok(decoder.log)
}

/// Decoding state.
struct Decoder<'a> {
    input: &'a str,
    log: Ulog,
    /// Subscription index by message id.
    by_msg_id: HashMap<u16, usize>,
    /// Past the definitions (after the first 'A', 'D', 'L' or 'C').
    in_data: bool,
    /// Fields in the layouts of all subscriptions so far.
    layout_fields: usize,
}

/// Most fields the layouts of all subscriptions may hold together: each 'A' message flattens
/// its format again, so a small file of many subscriptions to a wide format could otherwise
/// ask for gigabytes.
const MAX_LAYOUT_FIELDS: usize = 1 << 18;

/// Little-endian u64 at `offset` (the caller checked the length).
fn u64_at(bytes: &[u8], offset: usize) -> u64 {
    u64::from_le_bytes(std::array::from_fn(|i| bytes[offset + i]))
}

/// Little-endian u16 at `offset` (the caller checked the length).
fn u16_at(bytes: &[u8], offset: usize) -> u16 {
    u16::from_le_bytes([bytes[offset], bytes[offset + 1]])
}

impl Decoder<'_> {
    /// Handles one message of type `kind` with its `payload`, found at file `offset`.
    fn message(&mut self, kind: u8, payload: &[u8], offset: usize) -> Result<(), ReadError> {
        let short = |need: usize, what: &str| match payload.len() >= need {
            true => Ok(()),
            false => Err(at(
                self.input,
                offset,
                format!(
                    "a '{}' message of {} bytes, expected at least {need} ({what})",
                    kind as char,
                    payload.len()
                ),
            )),
        };
        match kind {
            b'B' => {
                short(40, "8 compat and 8 incompat flag bytes, 3 appended offsets")?;
                self.flag_bits(payload, offset)
            }
            b'F' => self.format(payload, offset),
            b'I' => {
                short(1, "key length")?;
                self.info(payload, offset)
            }
            b'M' => {
                short(2, "continuation flag, key length")?;
                let (key, _) = self.key_value(&payload[1..], offset)?;
                // A value spans one message with is_continued = 0 and those continuing it.
                let values = self.log.multi_info.entry(key).or_insert(0);
                if payload[0] == 0 || *values == 0 {
                    *values += 1;
                }
                Ok(())
            }
            b'P' => {
                match self.in_data {
                    true => self.log.changed_parameters += 1,
                    false => self.log.initial_parameters += 1,
                }
                Ok(())
            }
            b'Q' => {
                self.log.default_parameters += 1;
                Ok(())
            }
            b'A' => {
                short(3, "multi id, message id")?;
                self.subscribe(payload, offset)
            }
            b'R' => {
                short(2, "message id")?;
                self.by_msg_id.remove(&u16_at(payload, 0));
                Ok(())
            }
            b'D' => {
                short(2, "message id")?;
                self.in_data = true;
                self.data(payload, offset)
            }
            b'L' => {
                short(9, "log level, timestamp")?;
                self.logged(payload[0], None, &payload[1..])
            }
            b'C' => {
                short(11, "log level, tag, timestamp")?;
                self.logged(payload[0], Some(u16_at(payload, 1)), &payload[3..])
            }
            b'S' => {
                self.log.syncs += 1;
                Ok(())
            }
            b'O' => {
                short(2, "duration in ms")?;
                self.log.dropouts_ms.push(u16_at(payload, 0));
                Ok(())
            }
            other => {
                *self.log.skipped.unknown_types.entry(other).or_insert(0) += 1;
                Ok(())
            }
        }
    }

    /// 'B': refuses unknown incompatible flags (bit 0 of byte 0, data appended, is known).
    fn flag_bits(&mut self, payload: &[u8], offset: usize) -> Result<(), ReadError> {
        let incompat = &payload[8..16];
        let unknown = incompat[0] & !1 != 0 || incompat[1..].iter().any(|&b| b != 0);
        match unknown {
            true => Err(at(
                self.input,
                offset,
                format!(
                    "incompatible flag bits {incompat:02x?} that this reader does not know \
                     (expected at most bit 0 of byte 0, data appended)"
                ),
            )),
            false => Ok(()),
        }
    }

    /// 'F': a format definition.
    fn format(&mut self, payload: &[u8], offset: usize) -> Result<(), ReadError> {
        let text = String::from_utf8_lossy(payload);
        let format = parse_format(&text)
            .map_err(|e| at(self.input, offset, format!("format definition: {e}")))?;
        self.log.formats.insert(format.name.clone(), format);
        Ok(())
    }

    /// `u8 key length, key ("type name"), value` → (name, (type, value bytes)).
    fn key_value<'p>(
        &self,
        payload: &'p [u8],
        offset: usize,
    ) -> Result<(String, (String, &'p [u8])), ReadError> {
        let key_len = usize::from(payload[0]);
        let key = payload.get(1..1 + key_len).ok_or_else(|| {
            at(
                self.input,
                offset,
                format!("a key of {key_len} bytes that runs past its message"),
            )
        })?;
        let key = String::from_utf8_lossy(key);
        let (type_name, name) = key.split_once(' ').unwrap_or(("", &key));
        Ok((
            name.to_string(),
            (type_name.to_string(), &payload[1 + key_len..]),
        ))
    }

    /// 'I': one information value.
    fn info(&mut self, payload: &[u8], offset: usize) -> Result<(), ReadError> {
        let (name, (type_name, value)) = self.key_value(payload, offset)?;
        self.log.info.insert(name, info_value(&type_name, value));
        Ok(())
    }

    /// 'A': subscribes message id to a format.
    fn subscribe(&mut self, payload: &[u8], offset: usize) -> Result<(), ReadError> {
        self.in_data = true;
        let multi_id = payload[0];
        let msg_id = u16_at(payload, 1);
        let name = String::from_utf8_lossy(&payload[3..]).to_string();
        if !self.log.formats.contains_key(&name) {
            return Err(at(
                self.input,
                offset,
                format!("a subscription to {name}, which no format definition ('F') defines"),
            ));
        }
        let layout = flatten(&name, &self.log.formats)
            .map_err(|e| at(self.input, offset, format!("format {name}: {e}")))?;
        self.layout_fields += layout.fields.len();
        if self.layout_fields > MAX_LAYOUT_FIELDS {
            return Err(at(
                self.input,
                offset,
                format!(
                    "the subscriptions so far lay out more than {MAX_LAYOUT_FIELDS} fields in \
                     all (a PX4 log has a few thousand): a corrupt file?"
                ),
            ));
        }
        self.by_msg_id.insert(msg_id, self.log.subscriptions.len());
        self.log.subscriptions.push(Subscription {
            name,
            multi_id,
            layout,
            records: Vec::new(),
            offsets: Vec::new(),
        });
        Ok(())
    }

    /// 'D': one record of a subscription.
    fn data(&mut self, payload: &[u8], offset: usize) -> Result<(), ReadError> {
        let Some(&index) = self.by_msg_id.get(&u16_at(payload, 0)) else {
            self.log.skipped.unsubscribed_data += 1;
            return Ok(());
        };
        let subscription = &mut self.log.subscriptions[index];
        let record = &payload[2..];
        let size = subscription.layout.size;
        if record.len() < size {
            return Err(at(
                self.input,
                offset,
                format!(
                    "a {} record of {} bytes, expected {size} (its format)",
                    subscription.name,
                    record.len()
                ),
            ));
        }
        subscription.records.extend_from_slice(&record[..size]);
        subscription.offsets.push(offset as u64);
        if let Some(timestamp) = subscription.layout.field("timestamp") {
            let value = timestamp
                .primitive
                .decode_integer(&record[timestamp.offset..]);
            if let Some(us) = value.and_then(|v| u64::try_from(v).ok()) {
                self.log.last_timestamp_us = self.log.last_timestamp_us.max(us);
            }
        }
        Ok(())
    }

    /// 'L' or 'C': a log text (`rest` = timestamp then text).
    fn logged(&mut self, level: u8, tag: Option<u16>, rest: &[u8]) -> Result<(), ReadError> {
        self.in_data = true;
        let timestamp_us = u64_at(rest, 0);
        self.log.last_timestamp_us = self.log.last_timestamp_us.max(timestamp_us);
        self.log.logged.push(LoggedText {
            level,
            tag,
            timestamp_us,
            text: String::from_utf8_lossy(&rest[8..]).to_string(),
        });
        Ok(())
    }
}

/// An information value of type `type_name` from its bytes.
fn info_value(type_name: &str, value: &[u8]) -> InfoValue {
    if type_name.starts_with("char[") {
        return InfoValue::Text(String::from_utf8_lossy(value).to_string());
    }
    match Primitive::from_name(type_name).filter(|p| p.size() == value.len()) {
        Some(p @ (Primitive::F32 | Primitive::F64)) => InfoValue::Real(p.decode_f64(value)),
        Some(p) => p
            .decode_integer(value)
            .map_or_else(|| InfoValue::Bytes(value.to_vec()), InfoValue::Integer),
        None => InfoValue::Bytes(value.to_vec()),
    }
}

impl Ulog {
    /// The subscription of topic `name`, instance `multi_id`.
    pub fn topic(&self, name: &str, multi_id: u8) -> Option<Topic<'_>> {
        self.subscriptions
            .iter()
            .find(|s| s.name == name && s.multi_id == multi_id)
            .map(|subscription| Topic { subscription })
    }

    /// Number of data records of every (topic, multi id).
    pub fn record_counts(&self) -> BTreeMap<(String, u8), usize> {
        let mut counts = BTreeMap::new();
        for s in &self.subscriptions {
            *counts.entry((s.name.clone(), s.multi_id)).or_insert(0) += s.len();
        }
        counts
    }
}

impl Subscription {
    /// Number of records.
    pub fn len(&self) -> usize {
        self.offsets.len()
    }

    /// Whether there is no record.
    pub fn is_empty(&self) -> bool {
        self.offsets.is_empty()
    }
}

/// Read access to one topic's records by field name.
#[derive(Debug, Clone, Copy)]
pub struct Topic<'a> {
    subscription: &'a Subscription,
}

impl<'a> Topic<'a> {
    /// The topic's name.
    pub fn name(&self) -> &'a str {
        &self.subscription.name
    }

    /// Number of records.
    pub fn len(&self) -> usize {
        self.subscription.len()
    }

    /// Whether there is no record.
    pub fn is_empty(&self) -> bool {
        self.subscription.is_empty()
    }

    /// The field `name` (`gyro_rad[0]`, `timestamp`).
    pub fn field(&self, name: &str) -> Option<&'a FlatField> {
        self.subscription.layout.field(name)
    }

    /// The first of `names` that the topic has.
    pub fn first_field(&self, names: &[&str]) -> Option<&'a FlatField> {
        names.iter().find_map(|n| self.field(n))
    }

    /// Bytes of record `index`.
    fn record(&self, index: usize) -> &'a [u8] {
        let size = self.subscription.layout.size;
        &self.subscription.records[index * size..(index + 1) * size]
    }

    /// Field `field` of record `index` as `f64`.
    pub fn real(&self, field: &FlatField, index: usize) -> f64 {
        field
            .primitive
            .decode_f64(&self.record(index)[field.offset..])
    }

    /// Field `field` of record `index` as an exact integer (`None` for floating point).
    pub fn integer(&self, field: &FlatField, index: usize) -> Option<i128> {
        field
            .primitive
            .decode_integer(&self.record(index)[field.offset..])
    }

    /// File offset of record `index`'s message, bytes.
    pub fn file_offset(&self, index: usize) -> u64 {
        self.subscription.offsets[index]
    }
}
