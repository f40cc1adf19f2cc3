//! rosbag2's SQLite storage (`.db3`), over the minimal reader [`super::sqlite`].
//!
//! Two tables are read, by column position as every rosbag2 version since Foxy creates them:
//! `topics(id INTEGER PRIMARY KEY, name, type, serialization_format, …)` and
//! `messages(id INTEGER PRIMARY KEY, topic_id, timestamp, data)`; `timestamp` is the record
//! (receive) time in ns. The other tables (`schema`, `metadata`, `message_definitions`) and the
//! index `timestamp_idx` are not needed. A topic's `serialization_format` `cdr` is ROS 2 CDR.

use super::messages::Encoding;
use super::sqlite::{Database, Row, Value};
use super::{Bag, BagFormat, Sink};
use crate::error::{ReadError, ReadErrorKind};
use std::collections::HashMap;
use std::path::Path;

/// Decodes the bytes of a rosbag2 `.db3` file, named `input` in errors.
///
/// # Errors
/// Those of [`Database::open`] and [`Database::rows`]; no `topics` or `messages` table (not a
/// rosbag2 bag); a row whose columns are not of the types above, or that names an unknown
/// topic id.
pub fn decode_db3(bytes: &[u8], input: &str) -> Result<Bag, ReadError> {
    let mut bag = Bag::new(BagFormat::Ros2Db3);
    read_db3(bytes, input, &mut bag)?;
    Ok(bag)
}

/// Reads the bytes of a rosbag2 `.db3` file into `sink`: its topics, then each message row, its
/// data handed over when the sink wants it (else counted).
///
/// # Errors
/// Those of [`decode_db3`]; the sink's.
pub fn read_db3<S: Sink>(bytes: &[u8], input: &str, sink: &mut S) -> Result<(), ReadError> {
    let db = Database::open(bytes, input)?;
    let schema = db.schema()?;
    let root = |name: &str| {
        schema
            .iter()
            .find(|e| e.kind == "table" && e.name == name)
            .map(|e| e.root_page)
            .ok_or_else(|| {
                let tables: Vec<&str> = schema
                    .iter()
                    .filter(|e| e.kind == "table")
                    .map(|e| e.name.as_str())
                    .collect();
                ReadError::new(
                    input,
                    None,
                    ReadErrorKind::Unusable(format!(
                        "no table {name} in sqlite_schema (tables: {}): not a rosbag2 SQLite bag",
                        tables.join(", ")
                    )),
                )
            })
    };
    let (topics_root, messages_root) = (root("topics")?, root("messages")?);
    let mut by_id: HashMap<i64, usize> = HashMap::new();
    db.rows(topics_root, &mut |row| {
        let id = integer_or_rowid(&row, 0, input, "topics.id")?;
        let name = text(&row, 1, input, "topics.name")?;
        let type_name = text(&row, 2, input, "topics.type")?;
        let encoding = match text(&row, 3, input, "topics.serialization_format")?.as_str() {
            "cdr" => Encoding::Cdr,
            other => Encoding::Other(other.to_string()),
        };
        by_id.insert(id, sink.topic_index(&name, &type_name, encoding));
        Ok(())
    })?;
    db.rows(messages_root, &mut |row| {
        let topic_id = integer_or_rowid(&row, 1, input, "messages.topic_id")?;
        let timestamp = integer_or_rowid(&row, 2, input, "messages.timestamp")?;
        let k = *by_id.get(&topic_id).ok_or_else(|| {
            column_error(
                &row,
                input,
                format!("messages.topic_id {topic_id} is no id of the topics table"),
            )
        })?;
        match row.values.get(3) {
            Some(Value::Blob(_)) if !sink.wants(k) => sink.count(k),
            Some(Value::Blob(data)) => sink.push(k, timestamp, row.offset, data, input)?,
            _ => {
                return Err(column_error(
                    &row,
                    input,
                    "expected messages.data as a blob".to_string(),
                ));
            }
        }
        Ok(())
    })?;
    Ok(())
}

/// An error about a row.
fn column_error(row: &Row, input: &str, what: String) -> ReadError {
    super::bytes::at(input, row.offset, format_args!("row {}: {what}", row.rowid))
}

/// Column `k` as an integer; NULL in column 0 is the rowid (`INTEGER PRIMARY KEY`).
fn integer_or_rowid(row: &Row, k: usize, input: &str, name: &str) -> Result<i64, ReadError> {
    match row.values.get(k) {
        Some(Value::Integer(v)) => Ok(*v),
        Some(Value::Null) | None if k == 0 => Ok(row.rowid),
        _ => Err(column_error(
            row,
            input,
            format!("expected {name} as an integer"),
        )),
    }
}

/// Column `k` as text.
fn text(row: &Row, k: usize, input: &str, name: &str) -> Result<String, ReadError> {
    match row.values.get(k) {
        Some(Value::Text(t)) => Ok(t.clone()),
        _ => Err(column_error(row, input, format!("expected {name} as text"))),
    }
}

/// Refuses a `.db3` whose `-wal` file beside it holds content not yet written back to the
/// database file (a recorder still running, or killed): this reader sees the main file only.
///
/// # Errors
/// [`ReadErrorKind::Unusable`] naming the `-wal` file and its size.
pub fn refuse_pending_wal(path: &Path, input: &str) -> Result<(), ReadError> {
    let mut wal = path.as_os_str().to_owned();
    wal.push("-wal");
    match std::fs::metadata(&wal) {
        Ok(m) if m.len() > 0 => Err(ReadError::new(
            input,
            None,
            ReadErrorKind::Unusable(format!(
                "{} holds {} bytes of write-ahead log not yet in the database file (only the \
                 main file is read): stop the recorder, or checkpoint it with sqlite3 \
                 (PRAGMA wal_checkpoint), then read the bag again",
                Path::new(&wal).display(),
                m.len()
            )),
        )),
        _ => Ok(()),
    }
}
