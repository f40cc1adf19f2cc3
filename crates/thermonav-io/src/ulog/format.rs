//! ULog message formats ('F' definitions): parsing the text `name:type field;…` and flattening
//! a format, with its nested types and arrays, into primitive fields at byte offsets.

use std::collections::BTreeMap;

/// A primitive ULog type, little-endian in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Primitive {
    /// `int8_t`.
    I8,
    /// `uint8_t`.
    U8,
    /// `int16_t`.
    I16,
    /// `uint16_t`.
    U16,
    /// `int32_t`.
    I32,
    /// `uint32_t`.
    U32,
    /// `int64_t`.
    I64,
    /// `uint64_t`.
    U64,
    /// `float` (IEEE 754 binary32).
    F32,
    /// `double` (IEEE 754 binary64).
    F64,
    /// `bool` (one byte, non-zero is true).
    Bool,
    /// `char` (one byte of text).
    Char,
}

impl Primitive {
    /// The primitive named `name` in a format definition, if it is one.
    pub fn from_name(name: &str) -> Option<Self> {
        Some(match name {
            "int8_t" => Self::I8,
            "uint8_t" => Self::U8,
            "int16_t" => Self::I16,
            "uint16_t" => Self::U16,
            "int32_t" => Self::I32,
            "uint32_t" => Self::U32,
            "int64_t" => Self::I64,
            "uint64_t" => Self::U64,
            "float" => Self::F32,
            "double" => Self::F64,
            "bool" => Self::Bool,
            "char" => Self::Char,
            _ => return None,
        })
    }

    /// Size in bytes.
    pub fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 | Self::Bool | Self::Char => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::I64 | Self::U64 | Self::F64 => 8,
        }
    }

    /// The value at the start of `bytes` (at least [`Primitive::size`] long) as an `f64`
    /// (64-bit integers beyond 2⁵³ round).
    pub fn decode_f64(self, bytes: &[u8]) -> f64 {
        match self {
            Self::F32 => f64::from(f32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]])),
            Self::F64 => f64::from_le_bytes(std::array::from_fn(|i| bytes[i])),
            _ => self.decode_integer(bytes).map_or(f64::NAN, |v| v as f64),
        }
    }

    /// The value at the start of `bytes` as an exact integer (`None` for `float`/`double`).
    pub fn decode_integer(self, bytes: &[u8]) -> Option<i128> {
        let mut wide = [0; 8];
        wide[..self.size()].copy_from_slice(&bytes[..self.size()]);
        Some(match self {
            Self::I8 => i128::from(bytes[0] as i8),
            Self::U8 | Self::Bool | Self::Char => i128::from(bytes[0]),
            Self::I16 => i128::from(i16::from_le_bytes([bytes[0], bytes[1]])),
            Self::U16 => i128::from(u16::from_le_bytes([bytes[0], bytes[1]])),
            Self::I32 => i128::from(i32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]])),
            Self::U32 => i128::from(u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]])),
            Self::I64 => i128::from(i64::from_le_bytes(wide)),
            Self::U64 => i128::from(u64::from_le_bytes(wide)),
            Self::F32 | Self::F64 => return None,
        })
    }
}

/// One field of a format definition as written: `type[count] name`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FieldDefinition {
    /// Type name: a primitive or another format's name.
    pub type_name: String,
    /// Array length, `None` for a scalar.
    pub array_len: Option<usize>,
    /// Field name.
    pub name: String,
}

impl FieldDefinition {
    /// A padding field (`_padding0`, …): bytes that are skipped.
    pub fn is_padding(&self) -> bool {
        self.name.starts_with("_padding")
    }
}

/// One 'F' message: a named list of fields.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FormatDefinition {
    /// The format's (message's) name.
    pub name: String,
    /// Its fields in file order.
    pub fields: Vec<FieldDefinition>,
}

/// Parses `type name` or `type[n] name`.
pub fn parse_field(text: &str) -> Result<FieldDefinition, String> {
    let (type_text, name) = text
        .trim()
        .split_once(' ')
        .ok_or_else(|| format!("field \"{text}\": expected \"type name\""))?;
    let (type_name, array_len) = match type_text.split_once('[') {
        None => (type_text, None),
        Some((base, rest)) => {
            let count = rest
                .strip_suffix(']')
                .and_then(|n| n.parse::<usize>().ok())
                .filter(|&n| n > 0 && n <= MAX_ARRAY_LEN)
                .ok_or_else(|| {
                    format!("field \"{text}\": expected an array length [1..{MAX_ARRAY_LEN}]")
                })?;
            (base, Some(count))
        }
    };
    if type_name.is_empty() || name.trim().is_empty() {
        return Err(format!("field \"{text}\": expected \"type name\""));
    }
    Ok(FieldDefinition {
        type_name: type_name.to_string(),
        array_len,
        name: name.trim().to_string(),
    })
}

/// The longest array accepted in a definition (guards against absurd sizes in broken files).
const MAX_ARRAY_LEN: usize = 1 << 16;

/// Parses the text of an 'F' message: `name:type field;type field;…`.
pub fn parse_format(text: &str) -> Result<FormatDefinition, String> {
    let (name, body) = text
        .split_once(':')
        .ok_or_else(|| "expected \"name:type field;…\"".to_string())?;
    if name.is_empty() {
        return Err("a format without a name".to_string());
    }
    let fields = body
        .split(';')
        .filter(|f| !f.trim().is_empty())
        .map(parse_field)
        .collect::<Result<Vec<_>, _>>()?;
    Ok(FormatDefinition {
        name: name.to_string(),
        fields,
    })
}

/// A primitive field of a flattened format, at its byte offset in a data record.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FlatField {
    /// Path, as pyulog names it: `gyro_rad[0]`, `esc[2].esc_rpm`.
    pub name: String,
    /// Its type.
    pub primitive: Primitive,
    /// Offset from the start of the record, bytes.
    pub offset: usize,
}

/// A format flattened to primitives.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct FlatLayout {
    /// Primitive fields (padding left out) in file order.
    pub fields: Vec<FlatField>,
    /// Size of a record, bytes (trailing padding of the top-level format not counted: the
    /// logger does not write it).
    pub size: usize,
}

impl FlatLayout {
    /// The field named `name`.
    pub fn field(&self, name: &str) -> Option<&FlatField> {
        self.fields.iter().find(|f| f.name == name)
    }
}

/// The largest record a 'D' message can carry: its u16 size less the message id, bytes. A
/// format that flattens to more can never be logged (and checking it bounds the work and
/// memory a hostile definition can ask for).
const MAX_RECORD_BYTES: usize = u16::MAX as usize - 2;

/// Nesting deeper than this is taken as a cycle in the definitions.
const MAX_NESTING: usize = 16;

/// Flattens the format `name` from `formats`.
///
/// # Errors
/// A text naming the unknown nested type, or a nesting deeper than 16 (a cycle).
pub fn flatten(
    name: &str,
    formats: &BTreeMap<String, FormatDefinition>,
) -> Result<FlatLayout, String> {
    let mut layout = FlatLayout::default();
    let end = append_fields(name, "", 0, formats, &mut layout.fields, 0)?;
    layout.size = end - trailing_padding(&formats[name], formats)?;
    Ok(layout)
}

/// Appends the primitives of format `name` starting at `offset`, named under `prefix`;
/// returns the offset after it.
fn append_fields(
    name: &str,
    prefix: &str,
    mut offset: usize,
    formats: &BTreeMap<String, FormatDefinition>,
    out: &mut Vec<FlatField>,
    depth: usize,
) -> Result<usize, String> {
    if depth > MAX_NESTING {
        return Err(format!(
            "type {name} nests deeper than {MAX_NESTING} levels"
        ));
    }
    let format = formats
        .get(name)
        .ok_or_else(|| format!("no format definition for type {name}"))?;
    for field in &format.fields {
        for index in 0..field.array_len.unwrap_or(1) {
            if offset > MAX_RECORD_BYTES {
                return Err(format!(
                    "type {name} is larger than a ULog message can hold ({MAX_RECORD_BYTES} bytes)"
                ));
            }
            let element = element_path(prefix, field, index)?;
            offset = match Primitive::from_name(&field.type_name) {
                Some(primitive) => {
                    if !field.is_padding() {
                        out.push(FlatField {
                            name: element,
                            primitive,
                            offset,
                        });
                    }
                    offset + primitive.size()
                }
                None => {
                    let nested_prefix = format!("{element}.");
                    let end = append_fields(
                        &field.type_name,
                        &nested_prefix,
                        offset,
                        formats,
                        out,
                        depth + 1,
                    )?;
                    // Every element must take bytes: the size guard above then bounds the
                    // work, which arrays of an empty type would otherwise multiply unseen.
                    if end == offset {
                        return Err(format!(
                            "field {element} has type {}, which occupies no bytes",
                            field.type_name
                        ));
                    }
                    end
                }
            };
        }
    }
    Ok(offset)
}

/// The longest path of a flattened field, bytes: PX4's deepest nested names are under a
/// hundred; a longer one is a corrupt or hostile definition, whose names, repeated for every
/// array element, would otherwise take gigabytes.
pub const MAX_FIELD_PATH_BYTES: usize = 256;

/// The path of element `index` of `field` under `prefix` (`esc[2].esc_rpm`; no index for a
/// scalar), at most [`MAX_FIELD_PATH_BYTES`] long.
fn element_path(prefix: &str, field: &FieldDefinition, index: usize) -> Result<String, String> {
    // The index adds at most 7 bytes (`[65535]`): checked before anything is built.
    if prefix.len() + field.name.len() + 7 > MAX_FIELD_PATH_BYTES {
        return Err(format!(
            "field {prefix}{} has a name of {} bytes, longer than the {MAX_FIELD_PATH_BYTES} a ULog field name takes",
            field.name.chars().take(40).collect::<String>(),
            prefix.len() + field.name.len()
        ));
    }
    Ok(match field.array_len {
        None => format!("{prefix}{}", field.name),
        Some(_) => format!("{prefix}{}[{index}]", field.name),
    })
}

/// Bytes of padding at the end of a top-level format (only primitive padding fields).
fn trailing_padding(
    format: &FormatDefinition,
    formats: &BTreeMap<String, FormatDefinition>,
) -> Result<usize, String> {
    let Some(last) = format.fields.last().filter(|f| f.is_padding()) else {
        return Ok(0);
    };
    let count = last.array_len.unwrap_or(1);
    match Primitive::from_name(&last.type_name) {
        Some(primitive) => Ok(primitive.size() * count),
        None => {
            let mut scratch = Vec::new();
            Ok(append_fields(&last.type_name, "", 0, formats, &mut scratch, 1)? * count)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn formats(texts: &[&str]) -> BTreeMap<String, FormatDefinition> {
        texts
            .iter()
            .map(|t| parse_format(t).unwrap())
            .map(|f| (f.name.clone(), f))
            .collect()
    }

    #[test]
    fn nested_arrays_and_padding_flatten_to_offsets_counted_by_hand() {
        // Offsets by hand: timestamp 0..8, two `pair`s of (u16 a, u8 _padding0[2], float b)
        // = 7 bytes each at 8 and 15, flag at 22, trailing _padding0[3] (not logged).
        let f = formats(&[
            "pair:uint16_t a;uint8_t[1] _padding0;float b;",
            "top:uint64_t timestamp;pair[2] p;bool flag;uint8_t[3] _padding0;",
        ]);
        let layout = flatten("top", &f).unwrap();
        let got: Vec<(&str, usize)> = layout
            .fields
            .iter()
            .map(|x| (x.name.as_str(), x.offset))
            .collect();
        assert_eq!(
            got,
            [
                ("timestamp", 0),
                ("p[0].a", 8),
                ("p[0].b", 11),
                ("p[1].a", 15),
                ("p[1].b", 18),
                ("flag", 22)
            ]
        );
        assert_eq!(layout.size, 23);
    }

    #[test]
    fn unknown_types_cycles_and_bad_arrays_are_refused() {
        assert!(flatten("a", &formats(&["a:nothing x;"])).is_err());
        assert!(flatten("a", &formats(&["a:b x;", "b:a y;"])).is_err());
        assert!(parse_format("a:float[0] x;").is_err());
        assert!(parse_format("a:float[3 x;").is_err());
        assert!(parse_format("no colon").is_err());
        // 65 536 × 65 536 × 8 bytes: refused long before it is expanded.
        let huge = formats(&["a:b[65536] x;", "b:double[65536] y;"]);
        assert!(
            flatten("a", &huge)
                .unwrap_err()
                .contains("larger than a ULog message")
        );
    }

    #[test]
    fn primitives_decode_little_endian() {
        // Little-endian bytes of known values (IEEE 754: 1.5f32 = 0x3FC00000).
        assert_eq!(Primitive::F32.decode_f64(&[0, 0, 0xC0, 0x3F]), 1.5);
        assert_eq!(Primitive::I16.decode_integer(&[0xFE, 0xFF]), Some(-2));
        assert_eq!(
            Primitive::U64.decode_integer(&u64::MAX.to_le_bytes()),
            Some(i128::from(u64::MAX))
        );
        assert_eq!(Primitive::F64.decode_integer(&[0; 8]), None);
    }
}
