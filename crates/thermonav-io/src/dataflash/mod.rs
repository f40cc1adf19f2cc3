//! ArduPilot DataFlash logs (`.bin`), read from the format's documentation (ArduPilot's
//! "Adding a new log message" page and the format-character table of
//! `libraries/AP_Logger/LogStructure.h`).
//!
//! A log is a stream of records: the two bytes 0xA3 0x95, a message type id (u8), then the
//! type's fields packed little-endian without padding. Type 128 is `FMT`, which defines a type:
//! its id (u8), the whole record's length including the 3 header bytes (u8), a name
//! (`char[4]`), a format string (`char[16]`, one character per field) and comma-separated
//! column names (`char[64]`). Format characters: `a` int16\[32\], `b` i8, `B` u8, `h` i16,
//! `H` u16, `i` i32, `I` u32, `f` f32, `d` f64, `n` char\[4\], `N` char\[16\], `Z` char\[64\],
//! `c` i16 × 100, `C` u16 × 100, `e` i32 × 100, `E` u32 × 100 (the value times 100 is
//! stored: [`Value`] holds the stored integer divided by 100), `L` i32 latitude/longitude in
//! 1e-7 deg (divided by 10⁷), `M` u8 flight mode, `q` i64, `Q` u64.
//!
//! [`decode_dataflash`] keeps every type's records as raw bytes; [`MessageType::value`]
//! decodes one field. [`ardupilot`] extracts the IMU, its temperature and GPS fixes.
//!
//! What is refused, with the byte offset and what was expected there: bytes that are not a
//! record header, a record of a type no earlier FMT defined, an FMT whose length is not 3 plus
//! the sizes of its format characters (lengths are one byte, so no record can claim more than
//! 255 bytes), an unknown format character, column names that do not match the format, a type
//! redefined differently, and a file cut inside an FMT record. A partial data record at the
//! very end (the autopilot stopped mid-write, common after a power cut) is dropped and its
//! length reported, as for a ULog.

pub mod ardupilot;

use crate::error::{ReadError, ReadErrorKind};
use std::collections::BTreeMap;
use std::path::Path;

/// The two bytes that start every record.
pub const HEADER: [u8; 2] = [0xA3, 0x95];
/// The type id of FMT records.
pub const FMT_TYPE: u8 = 128;
/// Bytes of an FMT record: header, type, length, name, format, columns.
const FMT_LENGTH: usize = 3 + 1 + 1 + 4 + 16 + 64;
/// FMT's own format string.
const FMT_FORMAT: &str = "BBnNZ";

/// The format characters LogStructure.h defines.
pub const FORMAT_CHARACTERS: &str = "abBhHiIfdnNZcCeELMqQ";

/// How a field is stored: one format character.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FieldType(u8);

impl FieldType {
    /// The type of format character `c`, if LogStructure.h defines it.
    pub fn of(c: u8) -> Option<Self> {
        FORMAT_CHARACTERS.as_bytes().contains(&c).then_some(Self(c))
    }

    /// The format character.
    pub fn character(self) -> char {
        char::from(self.0)
    }

    /// Bytes the field takes.
    pub fn size(self) -> usize {
        match self.0 {
            b'a' => 64,
            b'b' | b'B' | b'M' => 1,
            b'h' | b'H' | b'c' | b'C' => 2,
            b'i' | b'I' | b'f' | b'e' | b'E' | b'L' | b'n' => 4,
            b'd' | b'q' | b'Q' => 8,
            b'N' => 16,
            _ => 64,
        }
    }

    /// The documented scale of the stored integer: 0.01 for `c`, `C`, `e`, `E`, 1e-7 for `L`,
    /// else 1 (as a divisor: the value is the stored integer divided by it).
    pub fn divisor(self) -> f64 {
        match self.0 {
            b'c' | b'C' | b'e' | b'E' => 100.0,
            b'L' => 1e7,
            _ => 1.0,
        }
    }
}

/// One decoded field.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A signed integer (`b`, `h`, `i`, `q`).
    Int(i64),
    /// An unsigned integer (`B`, `H`, `I`, `M`, `Q`).
    UInt(u64),
    /// A float (`f` widened exactly, `d`), or a scaled integer (`c`, `C`, `e`, `E`, `L`)
    /// divided by its documented scale (the correctly rounded quotient).
    Float(f64),
    /// Text (`n`, `N`, `Z`) up to the first NUL, invalid UTF-8 replaced.
    Text(String),
    /// `a`: 32 int16.
    Array(Vec<i16>),
}

impl Value {
    /// The value as a number (integers exactly up to 2⁵³); `None` for text and arrays.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Int(v) => Some(*v as f64),
            Value::UInt(v) => Some(*v as f64),
            Value::Float(v) => Some(*v),
            Value::Text(_) | Value::Array(_) => None,
        }
    }

    /// The value as an unsigned integer, when it is a non-negative integer.
    pub fn as_u64(&self) -> Option<u64> {
        match self {
            Value::Int(v) => u64::try_from(*v).ok(),
            Value::UInt(v) => Some(*v),
            _ => None,
        }
    }

    /// The text of `n`, `N`, `Z`.
    pub fn as_text(&self) -> Option<&str> {
        match self {
            Value::Text(t) => Some(t),
            _ => None,
        }
    }
}

/// One message type, as its FMT record defines it, with all its records.
#[derive(Debug, Clone)]
pub struct MessageType {
    /// Type id.
    pub id: u8,
    /// Name (up to 4 characters).
    pub name: String,
    /// Format string.
    pub format: String,
    /// Column names, one per format character.
    pub columns: Vec<String>,
    /// Whole record length including the header, bytes.
    pub length: usize,
    /// Each field's type and offset in the payload (after the 3 header bytes).
    fields: Vec<(FieldType, usize)>,
    /// Payloads (`length - 3` bytes each), back to back.
    payloads: Vec<u8>,
    /// File offset of each record, bytes.
    offsets: Vec<u64>,
}

impl MessageType {
    /// Records of this type.
    pub fn len(&self) -> usize {
        self.offsets.len()
    }

    /// True when the log has no record of this type.
    pub fn is_empty(&self) -> bool {
        self.offsets.is_empty()
    }

    /// The index of column `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }

    /// The format character of column `column`.
    pub fn field_type(&self, column: usize) -> FieldType {
        self.fields[column].0
    }

    /// File offset of record `record`, bytes.
    pub fn offset(&self, record: usize) -> u64 {
        self.offsets[record]
    }

    /// Field `column` of record `record`.
    ///
    /// # Panics
    /// When `column` or `record` is out of range (both come from this type).
    pub fn value(&self, column: usize, record: usize) -> Value {
        let (kind, at) = self.fields[column];
        let start = record * (self.length - 3) + at;
        decode_field(kind, &self.payloads[start..start + kind.size()])
    }
}

/// Little-endian bytes as an array.
fn le<const N: usize>(bytes: &[u8]) -> [u8; N] {
    let mut out = [0; N];
    out.copy_from_slice(&bytes[..N]);
    out
}

/// Text up to the first NUL.
fn text(bytes: &[u8]) -> String {
    let end = bytes.iter().position(|&b| b == 0).unwrap_or(bytes.len());
    String::from_utf8_lossy(&bytes[..end]).into_owned()
}

/// One field's value from its `kind.size()` bytes.
fn decode_field(kind: FieldType, b: &[u8]) -> Value {
    let scaled = |raw: f64| Value::Float(raw / kind.divisor());
    match kind.0 {
        b'b' => Value::Int(i64::from(b[0] as i8)),
        b'B' | b'M' => Value::UInt(u64::from(b[0])),
        b'h' => Value::Int(i64::from(i16::from_le_bytes(le(b)))),
        b'H' => Value::UInt(u64::from(u16::from_le_bytes(le(b)))),
        b'i' => Value::Int(i64::from(i32::from_le_bytes(le(b)))),
        b'I' => Value::UInt(u64::from(u32::from_le_bytes(le(b)))),
        b'q' => Value::Int(i64::from_le_bytes(le(b))),
        b'Q' => Value::UInt(u64::from_le_bytes(le(b))),
        b'f' => Value::Float(f64::from(f32::from_le_bytes(le(b)))),
        b'd' => Value::Float(f64::from_le_bytes(le(b))),
        b'c' => scaled(f64::from(i16::from_le_bytes(le(b)))),
        b'C' => scaled(f64::from(u16::from_le_bytes(le(b)))),
        b'e' | b'L' => scaled(f64::from(i32::from_le_bytes(le(b)))),
        b'E' => scaled(f64::from(u32::from_le_bytes(le(b)))),
        b'a' => Value::Array(
            b.chunks_exact(2)
                .map(|p| i16::from_le_bytes([p[0], p[1]]))
                .collect(),
        ),
        _ => Value::Text(text(b)),
    }
}

/// A decoded DataFlash log.
#[derive(Debug, Clone, Default)]
pub struct DataFlash {
    /// The message types by id (FMT itself included).
    types: BTreeMap<u8, MessageType>,
    /// Length of a partial record at the end of the file, bytes (0 when it ends cleanly).
    pub truncated_tail_bytes: usize,
}

impl DataFlash {
    /// The message type named `name`.
    pub fn message(&self, name: &str) -> Option<&MessageType> {
        self.types.values().find(|t| t.name == name)
    }

    /// Every message type, by id.
    pub fn message_types(&self) -> impl Iterator<Item = &MessageType> {
        self.types.values()
    }

    /// Records in the log (FMT records included).
    pub fn record_count(&self) -> usize {
        self.types.values().map(MessageType::len).sum()
    }
}

/// Reads and decodes the DataFlash log at `path` (gzip-compressed when it ends in `.gz`).
///
/// # Errors
/// [`ReadErrorKind::Open`]/[`ReadErrorKind::Read`] for the file; those of
/// [`decode_dataflash`].
pub fn read_dataflash_file(path: impl AsRef<Path>) -> Result<DataFlash, ReadError> {
    let (bytes, input) = crate::read_whole_file(path.as_ref())?;
    decode_dataflash(&bytes, &input)
}

/// True when `head` starts like a DataFlash log: the FMT record that defines FMT.
pub fn looks_like_dataflash(head: &[u8]) -> bool {
    head.len() >= 5 && head[..2] == HEADER && head[2] == FMT_TYPE && head[3] == FMT_TYPE
}

/// A problem at a byte offset of `input`.
fn at(input: &str, offset: usize, what: String) -> ReadError {
    ReadError::new(
        input,
        None,
        ReadErrorKind::Unusable(format!("at byte {offset}: {what}")),
    )
}

/// Decodes the bytes of a DataFlash log, named `input` in errors.
///
/// # Errors
/// [`ReadErrorKind::Unusable`] with the byte offset and what was expected there (see the
/// module's documentation); an empty file.
pub fn decode_dataflash(bytes: &[u8], input: &str) -> Result<DataFlash, ReadError> {
    if bytes.is_empty() {
        return Err(ReadError::new(input, None, ReadErrorKind::Empty));
    }
    let mut log = DataFlash::default();
    let mut offset = 0;
    while offset < bytes.len() {
        let rest = &bytes[offset..];
        if rest.len() >= 2 && rest[..2] != HEADER {
            return Err(at(
                input,
                offset,
                format!(
                    "expected a record header 0xA3 0x95, found 0x{:02X} 0x{:02X}",
                    rest[0], rest[1]
                ),
            ));
        }
        let Some(&id) = rest.get(2) else {
            log.truncated_tail_bytes = rest.len();
            break;
        };
        let length = record_length(&log, id, rest, offset, input)?;
        if rest.len() < length {
            log.truncated_tail_bytes = rest.len();
            break;
        }
        if id == FMT_TYPE {
            define(&mut log, &rest[3..FMT_LENGTH], offset, input)?;
        }
        if let Some(t) = log.types.get_mut(&id) {
            t.payloads.extend_from_slice(&rest[3..length]);
            t.offsets.push(offset as u64);
        }
        offset += length;
    }
    Ok(log)
}

/// The length of the record of type `id` at `offset`: FMT's fixed length, or the one its FMT
/// declared; an FMT cut by the end of the file is an error.
fn record_length(
    log: &DataFlash,
    id: u8,
    rest: &[u8],
    offset: usize,
    input: &str,
) -> Result<usize, ReadError> {
    if id == FMT_TYPE {
        return match rest.len() >= FMT_LENGTH {
            true => Ok(FMT_LENGTH),
            false => Err(at(
                input,
                offset,
                format!(
                    "the file ends inside an FMT record ({} of its {FMT_LENGTH} bytes; a \
                     truncated file)",
                    rest.len()
                ),
            )),
        };
    }
    match log.types.get(&id) {
        Some(t) => Ok(t.length),
        None => Err(at(
            input,
            offset,
            format!(
                "a record of message type {id}, which no earlier FMT record defines (expected \
                 its FMT first)"
            ),
        )),
    }
}

/// The type that the FMT payload `p` (after the header) defines, checked.
fn define(log: &mut DataFlash, p: &[u8], offset: usize, input: &str) -> Result<(), ReadError> {
    let (id, length) = (p[0], usize::from(p[1]));
    let (name, format, columns) = (text(&p[2..6]), text(&p[6..22]), text(&p[22..86]));
    let bad = |what: String| at(input, offset, format!("FMT of {name} (type {id}): {what}"));
    let mut fields = Vec::with_capacity(format.len());
    let mut size = 0;
    for c in format.bytes() {
        let kind = FieldType::of(c).ok_or_else(|| {
            bad(format!(
                "format character '{}' is not one of LogStructure.h's {FORMAT_CHARACTERS}",
                char::from(c).escape_default()
            ))
        })?;
        fields.push((kind, size));
        size += kind.size();
    }
    if length != 3 + size {
        return Err(bad(format!(
            "expected a length of {} bytes (3 header bytes and format \"{format}\"), found {length}",
            3 + size
        )));
    }
    let columns: Vec<String> = match columns.is_empty() {
        true => Vec::new(),
        false => columns.split(',').map(str::to_string).collect(),
    };
    if columns.len() != fields.len() {
        return Err(bad(format!(
            "expected {} column names for format \"{format}\", found {}",
            fields.len(),
            columns.len()
        )));
    }
    if id == FMT_TYPE && (format != FMT_FORMAT || name != "FMT") {
        return Err(bad(format!(
            "expected FMT's own definition (\"FMT\", \"{FMT_FORMAT}\"), found \"{name}\", \"{format}\""
        )));
    }
    if let Some(old) = log.types.get(&id) {
        return match old.format == format && old.name == name && old.columns == columns {
            true => Ok(()),
            false => Err(bad(format!(
                "redefines type {id} (first defined as {} \"{}\")",
                old.name, old.format
            ))),
        };
    }
    let payloads = Vec::new();
    let offsets = Vec::new();
    let t = MessageType {
        id,
        name,
        format,
        columns,
        length,
        fields,
        payloads,
        offsets,
    };
    log.types.insert(id, t);
    Ok(())
}
