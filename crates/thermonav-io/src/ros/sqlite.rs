//! A minimal read-only reader of the SQLite database file format (sqlite.org/fileformat2.html),
//! enough for the tables of a rosbag2 `.db3`: the 100-byte header, table b-trees (interior
//! pages 0x05 and leaf pages 0x0D), records (varints and serial types) and overflow pages.
//!
//! Not read, and refused with an error naming it: UTF-16 text encodings, page sizes other than
//! powers of two from 512 to 65536, format versions above 2. Index b-trees are never visited
//! (only tables are read, from their root pages in `sqlite_schema`). A database in WAL mode is
//! read from the main file only: content still in the `-wal` file is not seen, which the caller
//! checks ([`super::db3::refuse_pending_wal`]).

use super::bytes::at;
use crate::error::ReadError;

/// The first 16 bytes of every SQLite database file.
pub const MAGIC: &[u8; 16] = b"SQLite format 3\0";

/// Deepest table b-tree accepted (SQLite itself stops at 20 levels).
const MAX_DEPTH: usize = 20;

/// A column value.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// NULL (also the stored value of an `INTEGER PRIMARY KEY`, which is the rowid).
    Null,
    /// An integer (serial types 1-6, 8, 9).
    Integer(i64),
    /// A real (serial type 7).
    Real(f64),
    /// Text (serial types 13, 15, …), lossy UTF-8.
    Text(String),
    /// A blob (serial types 12, 14, …).
    Blob(Vec<u8>),
}

/// One row of a table.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The rowid.
    pub rowid: i64,
    /// File offset of the row's cell.
    pub offset: u64,
    /// The record's values, in column order.
    pub values: Vec<Value>,
}

/// An entry of `sqlite_schema`.
#[derive(Debug, Clone, PartialEq)]
pub struct SchemaEntry {
    /// `table`, `index`, `view` or `trigger`.
    pub kind: String,
    /// The object's name.
    pub name: String,
    /// Root page of its b-tree (0 for views and triggers).
    pub root_page: u32,
    /// Its `CREATE` statement.
    pub sql: String,
}

/// An opened database file.
#[derive(Debug, Clone, Copy)]
pub struct Database<'a> {
    bytes: &'a [u8],
    input: &'a str,
    page_size: usize,
    usable: usize,
    page_count: u32,
    /// Header byte 19: 1 legacy (rollback journal), 2 WAL.
    pub read_version: u8,
}

/// A big-endian u16 at `i` of `b` (the caller checked the length).
fn be16(b: &[u8], i: usize) -> usize {
    usize::from(u16::from_be_bytes([b[i], b[i + 1]]))
}

/// A big-endian u32 at `i` of `b` (the caller checked the length).
fn be32(b: &[u8], i: usize) -> u32 {
    u32::from_be_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]])
}

/// A varint at `i` of `b`: its value and length, `None` when `b` ends inside it.
fn varint(b: &[u8], i: usize) -> Option<(u64, usize)> {
    let mut value: u64 = 0;
    for k in 0..9 {
        let byte = *b.get(i + k)?;
        if k == 8 {
            return Some(((value << 8) | u64::from(byte), 9));
        }
        value = (value << 7) | u64::from(byte & 0x7f);
        if byte & 0x80 == 0 {
            return Some((value, k + 1));
        }
    }
    None
}

impl<'a> Database<'a> {
    /// Checks the header of the file `bytes`, named `input` in errors.
    ///
    /// # Errors
    /// A file shorter than its header or its declared pages, a wrong magic, an unsupported page
    /// size, format version or text encoding.
    pub fn open(bytes: &'a [u8], input: &'a str) -> Result<Self, ReadError> {
        if bytes.len() < 100 || &bytes[..16] != MAGIC {
            return Err(at(
                input,
                0,
                "expected the 100-byte SQLite header starting \"SQLite format 3\" (not a SQLite \
                 database, or cut short)",
            ));
        }
        let page_size = match be16(bytes, 16) {
            1 => 65536,
            n if n.is_power_of_two() && (512..=32768).contains(&n) => n,
            n => {
                return Err(at(
                    input,
                    16,
                    format_args!("page size {n} is not a power of two from 512 to 65536"),
                ));
            }
        };
        let (write_version, read_version) = (bytes[18], bytes[19]);
        if !(1..=2).contains(&write_version) || !(1..=2).contains(&read_version) {
            return Err(at(
                input,
                18,
                format_args!(
                    "file format versions {write_version}/{read_version} are not supported (expected 1 legacy or 2 WAL)"
                ),
            ));
        }
        let usable = page_size.saturating_sub(usize::from(bytes[20]));
        if usable < 480 {
            return Err(at(
                input,
                20,
                format_args!(
                    "{} reserved bytes leave {usable} usable bytes per page (at least 480 needed)",
                    bytes[20]
                ),
            ));
        }
        let encoding = be32(bytes, 56);
        if encoding > 1 {
            return Err(at(
                input,
                56,
                format_args!(
                    "text encoding {encoding} (UTF-16) is not supported (expected 1, UTF-8)"
                ),
            ));
        }
        let file_pages = u32::try_from(bytes.len() / page_size).unwrap_or(u32::MAX);
        let header_pages = be32(bytes, 28);
        let header_valid = header_pages > 0 && be32(bytes, 24) == be32(bytes, 92);
        if header_valid && header_pages > file_pages {
            return Err(at(
                input,
                28,
                format_args!(
                    "the header gives {header_pages} pages of {page_size} bytes, but the file holds {file_pages} (a truncated file)"
                ),
            ));
        }
        Ok(Self {
            bytes,
            input,
            page_size,
            usable,
            page_count: if header_valid {
                header_pages
            } else {
                file_pages
            },
            read_version,
        })
    }

    /// Page `n` (1-based).
    fn page(&self, n: u32, what: &str) -> Result<&'a [u8], ReadError> {
        if n == 0 || n > self.page_count {
            return Err(at(
                self.input,
                0,
                format_args!(
                    "{what} is page {n}, outside the file's pages 1..={}",
                    self.page_count
                ),
            ));
        }
        let start = (n as usize - 1) * self.page_size;
        Ok(&self.bytes[start..start + self.page_size])
    }

    /// File offset of page `n`.
    fn page_offset(&self, n: u32) -> u64 {
        u64::from(n - 1) * self.page_size as u64
    }

    /// The entries of `sqlite_schema` (the table b-tree rooted on page 1).
    ///
    /// # Errors
    /// Those of [`Database::rows`]; an entry whose columns are not text, text, text, integer,
    /// text.
    pub fn schema(&self) -> Result<Vec<SchemaEntry>, ReadError> {
        let mut entries = Vec::new();
        self.rows(1, &mut |row| {
            let text = |k: usize| match row.values.get(k) {
                Some(Value::Text(t)) => t.clone(),
                _ => String::new(),
            };
            let root_page = match row.values.get(3) {
                Some(Value::Integer(n)) => u32::try_from(*n).unwrap_or(0),
                _ => 0,
            };
            entries.push(SchemaEntry {
                kind: text(0),
                name: text(1),
                root_page,
                sql: text(4),
            });
            Ok(())
        })?;
        Ok(entries)
    }

    /// Calls `visit` on every row of the table b-tree rooted at page `root`, in rowid order.
    ///
    /// # Errors
    /// A page that is not a table b-tree page, a page reached twice, a tree deeper than 20, a
    /// cell or record that runs past its page or the file, an overflow chain that ends early;
    /// and `visit`'s own errors.
    pub fn rows(
        &self,
        root: u32,
        visit: &mut dyn FnMut(Row) -> Result<(), ReadError>,
    ) -> Result<(), ReadError> {
        let mut seen = vec![false; self.page_count as usize + 1];
        self.visit_page(root, 0, &mut seen, visit)
    }

    /// One page of a table b-tree, and its children.
    fn visit_page(
        &self,
        n: u32,
        depth: usize,
        seen: &mut [bool],
        visit: &mut dyn FnMut(Row) -> Result<(), ReadError>,
    ) -> Result<(), ReadError> {
        let page = self.page(n, "a b-tree page")?;
        let bad = |what: std::fmt::Arguments<'_>| {
            at(
                self.input,
                self.page_offset(n),
                format_args!("page {n}: {what}"),
            )
        };
        if depth > MAX_DEPTH || std::mem::replace(&mut seen[n as usize], true) {
            return Err(bad(format_args!(
                "reached twice or deeper than {MAX_DEPTH} levels in a b-tree (a corrupt file)"
            )));
        }
        let header = if n == 1 { 100 } else { 0 };
        let kind = page[header];
        let interior = match kind {
            0x05 => true,
            0x0d => false,
            other => {
                return Err(bad(format_args!(
                    "expected a table b-tree page (type 0x05 or 0x0d), found type 0x{other:02x}"
                )));
            }
        };
        let cells = be16(page, header + 3);
        let pointers = header + if interior { 12 } else { 8 };
        if pointers + 2 * cells > self.usable {
            return Err(bad(format_args!("{cells} cells do not fit the page")));
        }
        for k in 0..cells {
            let cell = be16(page, pointers + 2 * k);
            if cell >= self.usable {
                return Err(bad(format_args!(
                    "cell {k} starts at {cell}, past the page's usable {} bytes",
                    self.usable
                )));
            }
            match interior {
                true if cell + 4 <= self.usable => {
                    self.visit_page(be32(page, cell), depth + 1, seen, visit)?
                }
                true => return Err(bad(format_args!("cell {k} is cut by the page end"))),
                false => visit(self.leaf_cell(n, page, cell, seen)?)?,
            }
        }
        match interior {
            true => self.visit_page(be32(page, header + 8), depth + 1, seen, visit),
            false => Ok(()),
        }
    }

    /// The row of the table leaf cell at `cell` of page `n`; `seen` marks the pages of the walk
    /// so far (its overflow pages are marked too).
    fn leaf_cell(
        &self,
        n: u32,
        page: &'a [u8],
        cell: usize,
        seen: &mut [bool],
    ) -> Result<Row, ReadError> {
        let offset = self.page_offset(n) + cell as u64;
        let bad = |what: &str| at(self.input, offset, format_args!("page {n}: {what}"));
        let usable = &page[..self.usable];
        let (size, a) = varint(usable, cell)
            .ok_or_else(|| bad("a cell's payload size is cut by the page end"))?;
        let (rowid, b) =
            varint(usable, cell + a).ok_or_else(|| bad("a cell's rowid is cut by the page end"))?;
        if size > self.bytes.len() as u64 {
            return Err(bad(&format!(
                "a cell's payload of {size} bytes is larger than the file"
            )));
        }
        let size = size as usize;
        let local = self.local_payload(size);
        let start = cell + a + b;
        let end = start + local;
        if end > self.usable || (local < size && end + 4 > self.usable) {
            return Err(bad("a cell's payload runs past the page"));
        }
        let mut payload = Vec::with_capacity(size);
        payload.extend_from_slice(&page[start..end]);
        if local < size {
            self.overflow(be32(page, end), size, &mut payload, offset, seen)?;
        }
        let values = record(&payload)
            .ok_or_else(|| bad("a record whose header or values do not fit its payload"))?;
        Ok(Row {
            rowid: rowid as i64,
            offset,
            values,
        })
    }

    /// Bytes of a table leaf payload of `size` bytes stored on the page itself (the rest goes
    /// to overflow pages), from the file format's formula.
    fn local_payload(&self, size: usize) -> usize {
        let u = self.usable;
        let x = u - 35;
        if size <= x {
            return size;
        }
        let m = ((u - 12) * 32 / 255) - 23;
        let k = m + ((size - m) % (u - 4));
        if k <= x { k } else { m }
    }

    /// Appends the overflow chain starting at page `first` until `payload` holds `size` bytes.
    /// Each page of a file belongs to one b-tree page or one overflow chain: a page already
    /// reached in this walk (`seen`: a chain naming itself, looping, or shared with another
    /// cell or a b-tree page) is refused, so a walk reads each page at most once and its
    /// payloads add up to at most the file.
    fn overflow(
        &self,
        first: u32,
        size: usize,
        payload: &mut Vec<u8>,
        offset: u64,
        seen: &mut [bool],
    ) -> Result<(), ReadError> {
        let mut next = first;
        while payload.len() < size {
            if next != 0
                && next <= self.page_count
                && std::mem::replace(&mut seen[next as usize], true)
            {
                return Err(at(
                    self.input,
                    offset,
                    format_args!(
                        "the overflow chain of a {size}-byte payload reaches page {next} a second \
                         time, after {} bytes (a chain that loops or is shared: a corrupt file)",
                        payload.len()
                    ),
                ));
            }
            if next == 0 {
                return Err(at(
                    self.input,
                    offset,
                    format_args!(
                        "the overflow chain of a {size}-byte payload ends after {} bytes (a corrupt file)",
                        payload.len()
                    ),
                ));
            }
            let page = self.page(next, "an overflow page")?;
            let take = (size - payload.len()).min(self.usable - 4);
            payload.extend_from_slice(&page[4..4 + take]);
            next = be32(page, 0);
        }
        Ok(())
    }
}

/// The values of a record, `None` when it does not fit `payload`.
fn record(payload: &[u8]) -> Option<Vec<Value>> {
    let (header_size, mut i) = varint(payload, 0)?;
    let header_size = usize::try_from(header_size)
        .ok()
        .filter(|&h| h <= payload.len())?;
    let mut body = header_size;
    let mut values = Vec::new();
    while i < header_size {
        let (serial, len) = varint(&payload[..header_size], i)?;
        i += len;
        let (value, used) = value(serial, payload.get(body..)?)?;
        values.push(value);
        body += used;
    }
    Some(values)
}

/// The value of serial type `serial` at the start of `b`, and its length.
fn value(serial: u64, b: &[u8]) -> Option<(Value, usize)> {
    let int = |n: usize| -> Option<(Value, usize)> {
        let bytes = b.get(..n)?;
        let mut v: i64 = if bytes[0] & 0x80 != 0 { -1 } else { 0 };
        for &byte in bytes {
            v = (v << 8) | i64::from(byte);
        }
        Some((Value::Integer(v), n))
    };
    match serial {
        0 => Some((Value::Null, 0)),
        1..=4 => int(serial as usize),
        5 => int(6),
        6 => int(8),
        7 => {
            let bytes = b.get(..8)?;
            Some((
                Value::Real(f64::from_be_bytes(std::array::from_fn(|i| bytes[i]))),
                8,
            ))
        }
        8 => Some((Value::Integer(0), 0)),
        9 => Some((Value::Integer(1), 0)),
        10 | 11 => None,
        n => {
            let len = usize::try_from((n - 12) / 2).ok()?;
            let bytes = b.get(..len)?;
            match n % 2 {
                0 => Some((Value::Blob(bytes.to_vec()), len)),
                _ => Some((
                    Value::Text(String::from_utf8_lossy(bytes).into_owned()),
                    len,
                )),
            }
        }
    }
}
