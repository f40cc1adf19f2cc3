//! A ULog written byte by byte from the format description, for tests: messages, formats,
//! subscriptions and data records (shared by the io and the CLI tests).
#![allow(dead_code)]

/// Appends one message of type `kind`.
pub fn message(out: &mut Vec<u8>, kind: u8, payload: &[u8]) {
    out.extend_from_slice(&(payload.len() as u16).to_le_bytes());
    out.push(kind);
    out.extend_from_slice(payload);
}

pub fn format(out: &mut Vec<u8>, text: &str) {
    message(out, b'F', text.as_bytes());
}

pub fn subscribe(out: &mut Vec<u8>, msg_id: u16, name: &str) {
    subscribe_instance(out, msg_id, name, 0);
}

/// Subscribes `msg_id` to instance `multi_id` of topic `name`.
pub fn subscribe_instance(out: &mut Vec<u8>, msg_id: u16, name: &str, multi_id: u8) {
    let mut payload = vec![multi_id];
    payload.extend_from_slice(&msg_id.to_le_bytes());
    payload.extend_from_slice(name.as_bytes());
    message(out, b'A', &payload);
}

pub fn data(out: &mut Vec<u8>, msg_id: u16, record: &[u8]) {
    let mut payload = msg_id.to_le_bytes().to_vec();
    payload.extend_from_slice(record);
    message(out, b'D', &payload);
}

/// Little-endian concatenation helper.
#[derive(Default)]
pub struct Record(pub Vec<u8>);

impl Record {
    pub fn u64(mut self, v: u64) -> Self {
        self.0.extend_from_slice(&v.to_le_bytes());
        self
    }
    pub fn f32(mut self, v: f32) -> Self {
        self.0.extend_from_slice(&v.to_le_bytes());
        self
    }
    pub fn f64(mut self, v: f64) -> Self {
        self.0.extend_from_slice(&v.to_le_bytes());
        self
    }
    pub fn u16(mut self, v: u16) -> Self {
        self.0.extend_from_slice(&v.to_le_bytes());
        self
    }
    pub fn u8(mut self, v: u8) -> Self {
        self.0.push(v);
        self
    }
}

/// The header and flag bits of a log, before its formats.
pub fn log_start() -> Vec<u8> {
    let mut out = b"ULog\x01\x12\x35".to_vec();
    out.push(1);
    out.extend_from_slice(&1_000_u64.to_le_bytes());
    message(&mut out, b'B', &[0; 40]);
    out
}
