//! The one gate every number passes on its way out: thermonav writes no NaN and no infinity.
//!
//! serde_json writes a non-finite float as `null`, which a reader takes for "absent"; a CSV
//! writer would print `NaN`. Both would turn a failed computation into a result. Every JSON
//! document (files and `--json` on stdout) is first walked by [`check_finite`], which names the
//! first non-finite number by its path in the document; every CSV value goes through
//! [`write_finite`].

use serde::ser::{self, Serialize};
use std::fmt;
use std::io::{self, Write};

/// A number that is not finite, where it is.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "the result holds {value} at {path}: thermonav writes no NaN or infinity (the computation that produced it failed)"
)]
pub struct NonFinite {
    /// Where, as a JSON path (`models[2].rms_m`) or a CSV column.
    pub path: String,
    /// The value.
    pub value: f64,
}

impl ser::Error for NonFinite {
    fn custom<T: fmt::Display>(message: T) -> Self {
        Self {
            path: message.to_string(),
            value: f64::NAN,
        }
    }
}

/// Walks `value` as serde would serialise it and refuses the first non-finite number.
///
/// # Errors
/// [`NonFinite`] with the number's path.
pub fn check_finite(value: &impl Serialize) -> Result<(), NonFinite> {
    value.serialize(&mut Walker::default())
}

/// `value` as pretty-printed JSON, once [`check_finite`] has passed it.
///
/// # Errors
/// [`NonFinite`] as an [`io::Error`] of kind `InvalidData`, or serde_json's error.
pub fn finite_json_pretty(value: &impl Serialize) -> io::Result<String> {
    check_finite(value).map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))?;
    serde_json::to_string_pretty(value).map_err(io::Error::other)
}

/// Writes one CSV value: the shortest text that parses back to exactly `value`, positional for
/// magnitudes in \[1e-5, 1e16) and zero, scientific otherwise (the text of Rust's `{}` and
/// `{:e}` there, written by the Żmij algorithm, several times faster: a solution written at
/// the IMU rate spends most of its time formatting numbers).
///
/// # Errors
/// A NaN or an infinity, as [`NonFinite`] in an [`io::Error`] of kind `InvalidData` (nothing
/// is written), or the writer's error.
pub fn write_finite(out: &mut impl Write, value: f64) -> io::Result<()> {
    if !value.is_finite() {
        let path = "a CSV value".to_string();
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            NonFinite { path, value },
        ));
    }
    let mut buffer = zmij::Buffer::new();
    let text = buffer.format_finite(value);
    // Żmij writes integral values as `1.0` and positive exponents as `e+20`; Rust as `1` and
    // `e20`.
    match text.split_once("e+") {
        Some((mantissa, exponent)) => {
            out.write_all(mantissa.as_bytes())?;
            out.write_all(b"e")?;
            out.write_all(exponent.as_bytes())
        }
        None => out.write_all(text.strip_suffix(".0").unwrap_or(text).as_bytes()),
    }
}

/// The serializer that only looks: it keeps the path to the value it is at.
#[derive(Default)]
struct Walker {
    path: Vec<String>,
}

impl Walker {
    fn number(&self, value: f64) -> Result<(), NonFinite> {
        match value.is_finite() {
            true => Ok(()),
            false => Err(NonFinite {
                path: self.path_text(),
                value,
            }),
        }
    }

    fn path_text(&self) -> String {
        match self.path.concat() {
            p if p.is_empty() => "the document's top".to_string(),
            p => p.trim_start_matches('.').to_string(),
        }
    }

    /// Walks `value` one step deeper, at `step`.
    fn within<T: Serialize + ?Sized>(&mut self, step: String, value: &T) -> Result<(), NonFinite> {
        self.path.push(step);
        let walked = value.serialize(&mut *self);
        self.path.pop();
        walked
    }
}

/// A compound being walked: the walker and the next element's index.
struct Compound<'a> {
    walker: &'a mut Walker,
    index: usize,
    key: String,
}

impl Compound<'_> {
    fn element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        let step = format!("[{}]", self.index);
        self.index += 1;
        self.walker.within(step, value)
    }

    fn field<T: Serialize + ?Sized>(&mut self, name: &str, value: &T) -> Result<(), NonFinite> {
        self.walker.within(format!(".{name}"), value)
    }
}

macro_rules! finite_integers {
    ($($method:ident: $t:ty),*) => {
        $(fn $method(self, _: $t) -> Result<(), NonFinite> { Ok(()) })*
    };
}

impl<'a> ser::Serializer for &'a mut Walker {
    type Ok = ();
    type Error = NonFinite;
    type SerializeSeq = Compound<'a>;
    type SerializeTuple = Compound<'a>;
    type SerializeTupleStruct = Compound<'a>;
    type SerializeTupleVariant = Compound<'a>;
    type SerializeMap = Compound<'a>;
    type SerializeStruct = Compound<'a>;
    type SerializeStructVariant = Compound<'a>;

    finite_integers!(serialize_bool: bool, serialize_i8: i8, serialize_i16: i16,
        serialize_i32: i32, serialize_i64: i64, serialize_u8: u8, serialize_u16: u16,
        serialize_u32: u32, serialize_u64: u64, serialize_char: char, serialize_str: &str,
        serialize_bytes: &[u8]);

    fn serialize_f32(self, v: f32) -> Result<(), NonFinite> {
        self.number(f64::from(v))
    }
    fn serialize_f64(self, v: f64) -> Result<(), NonFinite> {
        self.number(v)
    }
    fn serialize_none(self) -> Result<(), NonFinite> {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), NonFinite> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), NonFinite> {
        Ok(())
    }
    fn serialize_unit_struct(self, _: &'static str) -> Result<(), NonFinite> {
        Ok(())
    }
    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
    ) -> Result<(), NonFinite> {
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<(), NonFinite> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<(), NonFinite> {
        self.within(format!(".{variant}"), value)
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Compound<'a>, NonFinite> {
        Ok(self.compound())
    }
    fn serialize_tuple(self, _: usize) -> Result<Compound<'a>, NonFinite> {
        Ok(self.compound())
    }
    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, NonFinite> {
        Ok(self.compound())
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, NonFinite> {
        Ok(self.compound())
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Compound<'a>, NonFinite> {
        Ok(self.compound())
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, NonFinite> {
        Ok(self.compound())
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, NonFinite> {
        Ok(self.compound())
    }
}

impl Walker {
    fn compound(&mut self) -> Compound<'_> {
        Compound {
            walker: self,
            index: 0,
            key: String::new(),
        }
    }
}

macro_rules! walk_elements {
    ($($trait:ident::$method:ident),*) => {
        $(impl ser::$trait for Compound<'_> {
            type Ok = ();
            type Error = NonFinite;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
                self.element(value)
            }
            fn end(self) -> Result<(), NonFinite> {
                Ok(())
            }
        })*
    };
}

walk_elements!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field
);

macro_rules! walk_fields {
    ($($trait:ident),*) => {
        $(impl ser::$trait for Compound<'_> {
            type Ok = ();
            type Error = NonFinite;
            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                name: &'static str,
                value: &T,
            ) -> Result<(), NonFinite> {
                self.field(name, value)
            }
            fn end(self) -> Result<(), NonFinite> {
                Ok(())
            }
        })*
    };
}

walk_fields!(SerializeStruct, SerializeStructVariant);

impl ser::SerializeMap for Compound<'_> {
    type Ok = ();
    type Error = NonFinite;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), NonFinite> {
        self.key = serde_json::to_string(key).unwrap_or_default();
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), NonFinite> {
        let step = format!(".{}", self.key.trim_matches('"'));
        self.walker.within(step, value)
    }
    fn end(self) -> Result<(), NonFinite> {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Serialize;
    use std::collections::BTreeMap;

    #[derive(Serialize)]
    struct Inner {
        rms_m: f64,
        ci: Option<[f64; 2]>,
    }

    #[derive(Serialize)]
    struct Outer {
        label: String,
        models: Vec<Inner>,
        by_channel: BTreeMap<String, f32>,
    }

    fn document(bad: f64) -> Outer {
        Outer {
            label: "x".into(),
            models: vec![
                Inner {
                    rms_m: 1.0,
                    ci: None,
                },
                Inner {
                    rms_m: 2.0,
                    ci: Some([0.5, bad]),
                },
            ],
            by_channel: BTreeMap::from([("gx".to_string(), 1.5)]),
        }
    }

    #[test]
    fn a_finite_document_passes_and_each_non_finite_number_is_named_by_its_path() {
        assert_eq!(check_finite(&document(3.0)), Ok(()));
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let e = check_finite(&document(bad)).unwrap_err();
            assert_eq!(e.path, "models[1].ci[1]");
            assert_eq!(e.value.to_bits(), bad.to_bits());
        }
        let mut map = document(1.0);
        map.by_channel.insert("gy".into(), f32::NAN);
        assert_eq!(check_finite(&map).unwrap_err().path, "by_channel.gy");
        assert_eq!(
            check_finite(&f64::NAN).unwrap_err().path,
            "the document's top"
        );
        // serde_json alone would have written null: the gate is what refuses.
        assert!(
            serde_json::to_string(&document(f64::NAN))
                .unwrap()
                .contains("null")
        );
        assert!(finite_json_pretty(&document(f64::NAN)).is_err());
    }

    /// The slow reference: Rust's own shortest round-trip text, `{}` in \[1e-5, 1e16) and
    /// for zero, `{:e}` otherwise.
    fn std_text(value: f64) -> String {
        if value != 0.0 && !(1e-5..1e16).contains(&value.abs()) {
            format!("{value:e}")
        } else {
            format!("{value}")
        }
    }

    fn written(value: f64) -> String {
        let mut out = Vec::new();
        write_finite(&mut out, value).unwrap();
        String::from_utf8(out).unwrap()
    }

    /// `text` parses back to exactly `value`, is as short as the standard library's text and
    /// in the same notation; where several texts of that length round-trip, Żmij may pick a
    /// neighbour of the one nearest the binary value (17 significant digits), so the two may
    /// differ by one in the last digit only.
    fn assert_shortest_exact(value: f64) {
        let (ours, reference) = (written(value), std_text(value));
        let back: f64 = ours.parse().unwrap();
        assert_eq!(back.to_bits(), value.to_bits(), "{ours} for {value:?}");
        assert_eq!(ours.len(), reference.len(), "{ours} against {reference}");
        let differing: Vec<_> = ours
            .bytes()
            .zip(reference.bytes())
            .enumerate()
            .filter(|(_, (a, b))| a != b)
            .collect();
        if let [(i, (a, b))] = differing[..] {
            let last_mantissa_digit = reference.find('e').unwrap_or(reference.len()) - 1;
            assert!(
                i == last_mantissa_digit && a.abs_diff(b) == 1,
                "{ours} against {reference}"
            );
        } else {
            assert!(differing.is_empty(), "{ours} against {reference}");
        }
    }

    // Every value round-trips in the standard library's notation and length: the boundaries
    // of the two notations, integers, subnormals, the extremes, and a million random bit
    // patterns and random values across the decades the outputs hold (seeded).
    #[test]
    fn a_csv_value_is_the_shortest_exact_text() {
        use rand::{RngExt, SeedableRng};
        let edges = [
            1e-5,
            9.999999999999999e-6,
            1e16,
            9999999999999998.0,
            1.0,
            -1.0,
            2.0,
            100.0,
            1e15,
            123456789.0,
            0.1,
            0.3,
            5e-324,
            f64::MIN_POSITIVE,
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            44.648808622357855,
            -63.57518023517192,
            17.0,
            0.004967942,
            1238642366184574.3,
        ];
        for v in edges.into_iter().chain(edges.map(|v| -v)) {
            assert_shortest_exact(v);
        }
        // Values with fewer than 17 significant digits have one shortest text: it is Rust's.
        for v in [0.0123, 1.5e-7, 44.6488, -2e20, 1e-300, 7.292115e-5] {
            assert_eq!(written(v), std_text(v));
        }
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x7a6d_696a);
        for _ in 0..1_000_000 {
            let bits = f64::from_bits(rng.random::<u64>());
            let decade = rng.random_range(-12.0..20.0);
            let scaled = rng.random_range(-1.0..1.0) * 10f64.powf(decade);
            let integral = rng.random_range(-1e6_f64..1e6).round();
            for v in [bits, scaled, integral]
                .into_iter()
                .filter(|v| v.is_finite())
            {
                assert_shortest_exact(v);
            }
        }
    }

    #[test]
    fn a_csv_value_is_written_exactly_or_refused() {
        let mut out = Vec::new();
        for v in [0.0123, 1.5e-7, 0.0, -0.0, -2e20] {
            write_finite(&mut out, v).unwrap();
            out.push(b',');
        }
        assert_eq!(String::from_utf8(out).unwrap(), "0.0123,1.5e-7,0,-0,-2e20,");
        let mut out = Vec::new();
        let e = write_finite(&mut out, f64::NAN).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::InvalidData);
        assert!(e.to_string().contains("NaN at a CSV value"), "{e}");
        assert!(out.is_empty());
    }
}
