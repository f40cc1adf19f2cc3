//! Bounds-checked little- and big-endian reads over a byte slice, each failure a [`ReadError`]
//! naming the input, the byte offset and what was expected there.

use crate::error::{ReadError, ReadErrorKind};

/// A problem at byte `offset` of `input`.
pub fn at(input: &str, offset: u64, what: impl std::fmt::Display) -> ReadError {
    ReadError::new(
        input,
        None,
        ReadErrorKind::Unusable(format!("at byte {offset}: {what}")),
    )
}

/// A cursor over `bytes`, which start at file offset `base` (for errors).
#[derive(Debug, Clone)]
pub struct Cursor<'a> {
    /// The bytes read.
    bytes: &'a [u8],
    /// Position in `bytes`.
    pos: usize,
    /// File offset of `bytes[0]` (for a decompressed chunk: the chunk record's offset).
    base: u64,
    /// The input's name.
    input: &'a str,
}

impl<'a> Cursor<'a> {
    /// A cursor at the start of `bytes`, found at file offset `base` of `input`.
    pub fn new(bytes: &'a [u8], base: u64, input: &'a str) -> Self {
        Self {
            bytes,
            pos: 0,
            base,
            input,
        }
    }

    /// The file offset of the next byte.
    pub fn offset(&self) -> u64 {
        self.base + self.pos as u64
    }

    /// Bytes left.
    pub fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    /// Whether every byte was read.
    pub fn is_empty(&self) -> bool {
        self.remaining() == 0
    }

    /// An error at the current offset.
    pub fn error(&self, what: impl std::fmt::Display) -> ReadError {
        at(self.input, self.offset(), what)
    }

    /// The next `n` bytes, `what` naming them in the error when fewer are left.
    pub fn take(&mut self, n: u64, what: &str) -> Result<&'a [u8], ReadError> {
        match usize::try_from(n).ok().filter(|&n| n <= self.remaining()) {
            Some(n) => {
                let out = &self.bytes[self.pos..self.pos + n];
                self.pos += n;
                Ok(out)
            }
            None => Err(self.error(format_args!(
                "expected {what} of {n} bytes, but only {} bytes are left (a truncated file, or a \
                 corrupt length field)",
                self.remaining()
            ))),
        }
    }

    /// The next `N` bytes as an array.
    fn array<const N: usize>(&mut self, what: &str) -> Result<[u8; N], ReadError> {
        let slice = self.take(N as u64, what)?;
        Ok(std::array::from_fn(|i| slice[i]))
    }

    /// A byte.
    pub fn u8(&mut self, what: &str) -> Result<u8, ReadError> {
        Ok(self.array::<1>(what)?[0])
    }

    /// A little-endian u16.
    pub fn u16_le(&mut self, what: &str) -> Result<u16, ReadError> {
        self.array(what).map(u16::from_le_bytes)
    }

    /// A little-endian u32.
    pub fn u32_le(&mut self, what: &str) -> Result<u32, ReadError> {
        self.array(what).map(u32::from_le_bytes)
    }

    /// A little-endian u64.
    pub fn u64_le(&mut self, what: &str) -> Result<u64, ReadError> {
        self.array(what).map(u64::from_le_bytes)
    }

    /// The rest of the bytes.
    pub fn rest(&mut self) -> &'a [u8] {
        let out = &self.bytes[self.pos..];
        self.pos = self.bytes.len();
        out
    }
}

/// Most bytes one compressed chunk may declare (and expand to): 64 MiB. Recorders write far
/// smaller chunks (ROS 1's `rosbag record` 768 KiB by default, rosbag2's MCAP storage and the
/// `mcap` tools 4 MiB), so no honest bag comes near it; a chunk beyond it is refused before
/// anything is decompressed, so memory stays bounded whatever the record declares.
pub const MAX_CHUNK_BYTES: u64 = 64 << 20;

/// Most bytes a file's compressed chunks may expand to altogether, per byte of the file.
/// Recorded IMU data compresses 2-10 times (floats with noise in their low bits; the test bags
/// 3-5 times), images and point clouds less; 100 times is beyond any honest bag and bounds the
/// work a small file can ask for.
pub const MAX_EXPANSION_RATIO: u64 = 100;

/// The file's expansion bound is never below this (small files of highly repetitive test data
/// compress far more than 100 times, and 64 MiB is quick to decompress).
pub const MIN_EXPANSION_BYTES: u64 = 64 << 20;

/// What a file's compressed chunks have expanded to so far, against the file's bound: the
/// larger of [`MAX_EXPANSION_RATIO`] times the file's size and [`MIN_EXPANSION_BYTES`].
#[derive(Debug, Clone)]
pub struct Expansion {
    /// The file's size, bytes.
    file_bytes: u64,
    /// The bound, bytes.
    limit: u64,
    /// Bytes the chunks read so far declared.
    used: u64,
}

impl Expansion {
    /// The bound of a file of `file_bytes` bytes.
    pub fn for_file(file_bytes: u64) -> Self {
        Self {
            file_bytes,
            limit: file_bytes
                .saturating_mul(MAX_EXPANSION_RATIO)
                .max(MIN_EXPANSION_BYTES),
            used: 0,
        }
    }

    /// Bytes the compressed chunks read so far expanded to.
    pub fn used(&self) -> u64 {
        self.used
    }
}

/// Checks a chunk before it is read: `compression` known, an uncompressed chunk's records
/// `stored` bytes as `declared`, a compressed one's `declared` at most [`MAX_CHUNK_BYTES`] and
/// within what is left of the file's [`Expansion`] bound (then counted in it). `at` is the
/// file offsets of the chunk record and of its records.
///
/// # Errors
/// Each of those, naming the file, the chunk's offset and the figures.
pub fn chunk_bounds(
    compression: &str,
    stored: u64,
    declared: u64,
    (chunk_offset, records_offset): (u64, u64),
    input: &str,
    expansion: &mut Expansion,
) -> Result<(), ReadError> {
    let refuse = |what: std::fmt::Arguments<'_>| at_chunk(input, chunk_offset, compression, what);
    if matches!(compression, "" | "none") {
        return match stored == declared {
            true => Ok(()),
            false => Err(refuse(format_args!(
                "holds {stored} bytes, but its record declares {declared}"
            ))),
        };
    }
    if !matches!(compression, "zstd" | "lz4" | "bz2") {
        return Err(at(
            input,
            records_offset,
            format_args!(
                "chunk compression \"{compression}\" is not supported (expected none, zstd, lz4 \
                 or bz2)"
            ),
        ));
    }
    if declared > MAX_CHUNK_BYTES {
        return Err(refuse(format_args!(
            "declares {declared} bytes uncompressed ({stored} compressed), above the \
             {MAX_CHUNK_BYTES}-byte (64 MiB) limit of a chunk (recorders write chunks of 768 KiB \
             to 4 MiB): a corrupt size or a decompression bomb"
        )));
    }
    let total = expansion.used.saturating_add(declared);
    if total > expansion.limit {
        return Err(refuse(format_args!(
            "declares {declared} bytes uncompressed ({stored} compressed), which would bring the \
             file's chunks to {total} bytes, above the {}-byte limit for this {}-byte file \
             ({MAX_EXPANSION_RATIO} times its size, at least {MIN_EXPANSION_BYTES}): a \
             decompression bomb, or data far more repetitive than a recording",
            expansion.limit, expansion.file_bytes
        )));
    }
    expansion.used = total;
    Ok(())
}

/// Checks what a chunk decompressed to: `produced` bytes read (at most `declared`), `more`
/// when the decompressor had bytes past them.
///
/// # Errors
/// Fewer bytes than declared, or more, naming the chunk's offset and the figures.
pub fn check_expansion(
    compression: &str,
    (produced, more): (u64, bool),
    declared: u64,
    stored: u64,
    chunk_offset: u64,
    input: &str,
) -> Result<(), ReadError> {
    let refuse = |what: std::fmt::Arguments<'_>| at_chunk(input, chunk_offset, compression, what);
    if more {
        return Err(refuse(format_args!(
            "({stored} bytes compressed) expands to more than the {declared} bytes its record \
             declares (decompression stopped there)"
        )));
    }
    match produced == declared {
        true => Ok(()),
        false => Err(refuse(format_args!(
            "holds {produced} bytes uncompressed, but its record declares {declared}"
        ))),
    }
}

/// A problem with the `compression` chunk whose record starts at `chunk_offset` of `input`.
fn at_chunk(
    input: &str,
    chunk_offset: u64,
    compression: &str,
    what: std::fmt::Arguments<'_>,
) -> ReadError {
    let name = match compression {
        "" => "uncompressed",
        other => other,
    };
    at(input, chunk_offset, format_args!("the {name} chunk {what}"))
}

/// The words of a zstd decoder's refusal: ruzstd prints its frame-header errors with Rust's
/// debug text (`MagicNumberReadError(Error { .. })`); their own display says it in words.
pub fn zstd_error_text(error: &ruzstd::decoding::errors::FrameDecoderError) -> String {
    use ruzstd::decoding::errors::FrameDecoderError as Refusal;
    match error {
        Refusal::ReadFrameHeaderError(e) => e.to_string(),
        Refusal::FrameHeaderError(e) => e.to_string(),
        Refusal::DictionaryDecodeError(e) => e.to_string(),
        other => other.to_string(),
    }
}

/// The decompressor of a chunk of `compression` (none, lz4, bz2, else zstd: [`chunk_bounds`]
/// admits only these four) over its stored bytes: the one place both bag readers make it.
/// `offset` is the chunk record's, for the refusal of a zstd chunk that is not a zstd frame.
///
/// # Errors
/// A zstd chunk whose frame header does not read, in words ([`zstd_error_text`]).
pub fn chunk_decoder<'r>(
    compression: &str,
    stored: &'r mut dyn std::io::Read,
    input: &str,
    offset: u64,
) -> Result<Box<dyn std::io::Read + 'r>, ReadError> {
    Ok(match compression {
        "" | "none" => Box::new(stored),
        "lz4" => Box::new(lz4_flex::frame::FrameDecoder::new(stored)),
        "bz2" => Box::new(bzip2_rs::DecoderReader::new(stored)),
        _ => Box::new(
            ruzstd::decoding::StreamingDecoder::new(stored).map_err(|e| {
                at(
                    input,
                    offset,
                    format_args!(
                        "the zstd chunk does not decompress: {}",
                        zstd_error_text(&e)
                    ),
                )
            })?,
        ),
    })
}
