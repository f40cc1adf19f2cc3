//! Physical lines of a text input, split in place in one large reused buffer.
//!
//! The input is read in blocks of [`BLOCK_BYTES`] into a buffer the lines are borrowed from;
//! line ends are found with `memchr` (vectorised). A line is copied only when it straddles two
//! blocks (its start is moved to the front of the buffer before the next block is read).

use crate::error::{ReadError, ReadErrorKind};
use std::io::{BufRead, ErrorKind};

/// Longest line accepted, bytes: far beyond any CSV row, small enough to bound memory when the
/// input is not a text file.
pub(crate) const MAX_LINE_BYTES: u64 = 1 << 20;

/// The buffer's size unless a longer line needs more: twice the capacity of the `BufReader`s
/// the files are opened with, so that each read, into the buffer's free part after
/// the unconsumed bytes are moved to its front, asks for at least a whole `BufReader` buffer,
/// and `BufReader` then reads straight into ours instead of copying every byte through its own;
/// small enough to stay in the L2 cache.
const BLOCK_BYTES: usize = 2 * crate::FILE_BUFFER_BYTES;

/// Buffer size to start with: small inputs (a test's string, a fuzz case) never pay for a
/// whole block.
const FIRST_BUFFER_BYTES: usize = 1 << 12;

/// Non-blank lines of an input, numbered as physical lines (1-based).
///
/// Blank lines (empty or whitespace only) are skipped wherever they are but still counted, so
/// line numbers in errors match an editor's. Line ends `\n` and `\r\n` are both accepted.
pub(crate) struct Lines<R> {
    reader: R,
    input: String,
    /// Bytes read and not yet consumed are `buffer[next..filled]`.
    buffer: Vec<u8>,
    filled: usize,
    /// The current line's content is `buffer[start..end]`.
    start: usize,
    end: usize,
    /// Where the next line starts.
    next: usize,
    /// The reader has reported its end.
    at_end: bool,
    number: u64,
}

impl<R: BufRead> Lines<R> {
    /// Lines of `reader`, which errors call `input`.
    pub(crate) fn new(reader: R, input: String) -> Self {
        Self {
            reader,
            input,
            buffer: vec![0; FIRST_BUFFER_BYTES],
            filled: 0,
            start: 0,
            end: 0,
            next: 0,
            at_end: false,
            number: 0,
        }
    }

    /// Moves to the next non-blank line; `Ok(false)` at the end of the input.
    #[inline]
    pub(crate) fn advance(&mut self) -> Result<bool, ReadError> {
        loop {
            if !self.read_physical_line()? {
                return Ok(false);
            }
            if !self.current().iter().all(u8::is_ascii_whitespace) {
                return Ok(true);
            }
        }
    }

    /// The current line without its line end.
    #[inline]
    pub(crate) fn current(&self) -> &[u8] {
        &self.buffer[self.start..self.end]
    }

    /// The current line without its line end, followed by whatever the buffer holds after it
    /// (its line end, later lines): room for word loads that run past the line's last field.
    /// The line is the first [`Lines::current`]`().len()` bytes.
    #[inline]
    pub(crate) fn current_and_after(&self) -> &[u8] {
        &self.buffer[self.start..self.filled]
    }

    /// The bytes read and not yet taken as lines: the next line's start, possibly without its
    /// end (for a decoder that finds the line end itself).
    #[inline]
    pub(crate) fn unread(&self) -> &[u8] {
        &self.buffer[self.next..self.filled]
    }

    /// Makes the first `content` bytes of [`Lines::unread`] the current line, `taken` bytes
    /// (its content and its line end, which the caller has seen) consumed: what
    /// [`Lines::advance`] does for a non-blank line, without the search for its end.
    #[inline]
    pub(crate) fn take_decoded_line(&mut self, content: usize, taken: usize) {
        debug_assert!(content < taken && self.next + taken <= self.filled);
        self.take_line(content, taken);
    }

    /// 1-based number of the current line (0 before the first).
    pub(crate) fn number(&self) -> u64 {
        self.number
    }

    /// An error about the current line.
    pub(crate) fn error_here(&self, kind: ReadErrorKind) -> ReadError {
        ReadError::new(self.input.as_str(), Some(self.number), kind)
    }

    /// An error about an earlier line, `number`.
    pub(crate) fn error_at(&self, number: u64, kind: ReadErrorKind) -> ReadError {
        ReadError::new(self.input.as_str(), Some(number), kind)
    }

    /// An error about the whole input.
    pub(crate) fn error_in_input(&self, kind: ReadErrorKind) -> ReadError {
        ReadError::new(self.input.as_str(), None, kind)
    }

    /// Finds the next physical line in the buffer, reading more when it holds no line end;
    /// `Ok(false)` at the end of the input.
    #[inline]
    fn read_physical_line(&mut self) -> Result<bool, ReadError> {
        loop {
            let pending = &self.buffer[self.next..self.filled];
            let newline = memchr::memchr(b'\n', pending);
            let pending_len = pending.len();
            if let Some(offset) = newline.filter(|&o| (o as u64) < MAX_LINE_BYTES) {
                self.take_line(offset, offset + 1);
                return Ok(true);
            }
            if pending_len as u64 >= MAX_LINE_BYTES {
                self.number += 1;
                return Err(self.error_here(ReadErrorKind::LineTooLong {
                    limit_bytes: MAX_LINE_BYTES,
                }));
            }
            if self.at_end {
                if pending_len == 0 {
                    return Ok(false);
                }
                self.take_line(pending_len, pending_len);
                return Ok(true);
            }
            self.refill()?;
        }
    }

    /// Makes the next `content` bytes the current line (without `\r` before its `\n`) and moves
    /// past `taken` bytes.
    #[inline]
    fn take_line(&mut self, content: usize, taken: usize) {
        self.number += 1;
        self.start = self.next;
        self.end = self.next + content;
        if self.end > self.start && self.buffer[self.end - 1] == b'\r' {
            self.end -= 1;
        }
        self.next += taken;
    }

    /// Moves the unconsumed bytes to the front of the buffer, grows it when they fill it, and
    /// reads once more (marking the end of the input when the reader has no more).
    fn refill(&mut self) -> Result<(), ReadError> {
        let full = self.filled == self.buffer.len();
        let one_line = self.next == 0;
        self.buffer.copy_within(self.next..self.filled, 0);
        self.filled -= self.next;
        (self.start, self.end, self.next) = (0, 0, 0);
        // Grows while a large input fills it up to a block, and beyond for a longer line.
        if full && (self.buffer.len() < BLOCK_BYTES || one_line) {
            let grown = (self.buffer.len() * 2).min(MAX_LINE_BYTES as usize + BLOCK_BYTES);
            self.buffer.resize(grown, 0);
        }
        loop {
            match self.reader.read(&mut self.buffer[self.filled..]) {
                Ok(0) => self.at_end = true,
                Ok(read) => self.filled += read,
                Err(e) if e.kind() == ErrorKind::Interrupted => continue,
                Err(e) => return Err(self.error_in_input(ReadErrorKind::Read(e))),
            }
            return Ok(());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::{BufReader, Read};

    /// A reader that hands out at most `step` bytes per read, to put line ends on every
    /// possible block boundary.
    struct Trickle<'a> {
        bytes: &'a [u8],
        step: usize,
    }

    impl Read for Trickle<'_> {
        fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
            let n = self.step.min(out.len()).min(self.bytes.len());
            out[..n].copy_from_slice(&self.bytes[..n]);
            self.bytes = &self.bytes[n..];
            Ok(n)
        }
    }

    /// The slow, obviously correct split: `str::lines` semantics on bytes, blank lines
    /// dropped, numbered from 1.
    fn reference_lines(text: &[u8]) -> Vec<(u64, Vec<u8>)> {
        let mut lines: Vec<&[u8]> = text.split(|&b| b == b'\n').collect();
        if text.last() == Some(&b'\n') || text.is_empty() {
            lines.pop();
        }
        lines
            .into_iter()
            .enumerate()
            .map(|(i, l)| (i as u64 + 1, l.strip_suffix(b"\r").unwrap_or(l).to_vec()))
            .filter(|(_, l)| !l.iter().all(u8::is_ascii_whitespace))
            .collect()
    }

    fn split(text: &[u8], step: usize) -> Vec<(u64, Vec<u8>)> {
        let reader = BufReader::with_capacity(7, Trickle { bytes: text, step });
        let mut lines = Lines::new(reader, "test".into());
        let mut out = Vec::new();
        while lines.advance().unwrap() {
            out.push((lines.number(), lines.current().to_vec()));
        }
        out
    }

    #[test]
    fn lines_match_the_plain_split_whatever_the_read_sizes() {
        let mut text = Vec::new();
        for k in 0..3000_usize {
            let line = format!("{k},{}", "x".repeat(k % 97));
            text.extend_from_slice(line.as_bytes());
            text.extend_from_slice(match k % 5 {
                0 => b"\r\n".as_slice(),
                1 => b"\n\n".as_slice(),
                2 => b"\n  \t\n".as_slice(),
                _ => b"\n".as_slice(),
            });
        }
        text.extend_from_slice(b"last line without end");
        let expected = reference_lines(&text);
        for step in [1, 2, 3, 61, 4096, 5000, 1 << 20] {
            assert_eq!(split(&text, step), expected, "step {step}");
        }
    }

    #[test]
    fn a_line_longer_than_the_limit_is_refused_with_its_number() {
        let mut text = b"a\nb\n".to_vec();
        text.extend(std::iter::repeat_n(b'x', MAX_LINE_BYTES as usize));
        let mut lines = Lines::new(&text[..], "long".into());
        assert!(lines.advance().unwrap());
        assert!(lines.advance().unwrap());
        let error = lines.advance().unwrap_err().to_string();
        assert!(error.starts_with("long:3"), "{error}");
    }

    #[test]
    fn a_line_just_under_the_limit_is_read_whole() {
        let mut text = vec![b'y'; MAX_LINE_BYTES as usize - 1];
        text.extend_from_slice(b"\nz");
        let expected = reference_lines(&text);
        assert_eq!(split(&text, 100_000), expected);
    }
}
