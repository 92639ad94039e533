//! Pretty JSON that never contains a NaN.
//!
//! serde_json writes a non-finite float as `null`, silently. Every value is therefore walked
//! first by a small checking serializer that stops at the first NaN or infinity and reports
//! its path (`profiles[1].tension`, index 7).

use std::fmt;
use std::io::Write;

use serde::Serialize;
use serde::ser;

use super::error::OutputError;

/// Writes `value` as pretty-printed JSON followed by a newline.
///
/// # Errors
/// [`OutputError::NonFinite`] naming the path of the first NaN or infinity (checked before
/// anything is written); [`OutputError::Json`] if serialisation fails; an I/O error.
///
/// # Example
/// ```
/// use capstan::output::{OutputError, write_json};
/// #[derive(serde::Serialize)]
/// struct Summary { ratio: f64, x2: Vec<f64> }
/// let mut s = Vec::new();
/// write_json(&mut s, &Summary { ratio: 2.0, x2: vec![0.0, 0.5] }).unwrap();
/// assert!(String::from_utf8(s).unwrap().starts_with("{\n  \"ratio\": 2.0,"));
/// let bad = Summary { ratio: 2.0, x2: vec![0.0, f64::INFINITY] };
/// match write_json(&mut Vec::new(), &bad) {
///     Err(OutputError::NonFinite { column, index, .. }) => assert_eq!((column.as_str(), index), ("x2", 1)),
///     other => panic!("{other:?}"),
/// }
/// ```
pub fn write_json<W: Write + ?Sized, T: Serialize + ?Sized>(
    w: &mut W,
    value: &T,
) -> Result<(), OutputError> {
    check_finite_json(value)?;
    serde_json::to_writer_pretty(&mut *w, value).map_err(json_error)?;
    w.write_all(b"\n")?;
    Ok(())
}

/// `value` as a pretty-printed JSON string (for stdout), with the same NaN refusal.
///
/// # Errors
/// As [`write_json`].
pub fn to_json_string<T: Serialize + ?Sized>(value: &T) -> Result<String, OutputError> {
    check_finite_json(value)?;
    Ok(serde_json::to_string_pretty(value)?)
}

/// An I/O failure inside serde_json stays an I/O error (so [`write_atomic`](super::write_atomic)
/// names the file).
fn json_error(e: serde_json::Error) -> OutputError {
    if e.is_io() {
        OutputError::from(std::io::Error::from(e))
    } else {
        OutputError::Json(e)
    }
}

/// Checks that `value` serialises without a NaN or infinity.
///
/// # Errors
/// [`OutputError::NonFinite`] with the path of the first offender (`column` is the path up to
/// the innermost array, `index` the position in it, 0 outside arrays); [`OutputError::Json`] if
/// `value`'s `Serialize` implementation fails.
pub fn check_finite_json<T: Serialize + ?Sized>(value: &T) -> Result<(), OutputError> {
    let mut checker = Checker {
        path: String::new(),
    };
    match value.serialize(&mut checker) {
        Ok(()) => Ok(()),
        Err(CheckError::NonFinite { path, value }) => {
            let (column, index) = split_index(&path);
            Err(OutputError::NonFinite {
                column,
                index,
                value,
            })
        }
        Err(CheckError::Custom(message)) => Err(OutputError::Json(ser::Error::custom(message))),
    }
}

/// `a.b[3]` -> (`a.b`, 3); `a.b` -> (`a.b`, 0).
fn split_index(path: &str) -> (String, usize) {
    if let Some(stripped) = path.strip_suffix(']')
        && let Some(open) = stripped.rfind('[')
        && let Ok(i) = stripped[open + 1..].parse()
    {
        return (stripped[..open].to_owned(), i);
    }
    let column = if path.is_empty() { "(value)" } else { path };
    (column.to_owned(), 0)
}

#[derive(Debug)]
enum CheckError {
    NonFinite { path: String, value: f64 },
    Custom(String),
}

impl fmt::Display for CheckError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite { path, value } => write!(f, "{path} = {value}"),
            Self::Custom(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for CheckError {}

impl ser::Error for CheckError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        Self::Custom(msg.to_string())
    }
}

/// Walks a value, keeping the JSON path of the current position.
struct Checker {
    path: String,
}

impl Checker {
    fn float(&self, value: f64) -> Result<(), CheckError> {
        if value.is_finite() {
            Ok(())
        } else {
            Err(CheckError::NonFinite {
                path: self.path.clone(),
                value,
            })
        }
    }

    fn nested<T: Serialize + ?Sized>(
        &mut self,
        segment: fmt::Arguments<'_>,
        value: &T,
    ) -> Result<(), CheckError> {
        let len = self.path.len();
        fmt::write(&mut self.path, segment).expect("writing to a String");
        let r = value.serialize(&mut *self);
        self.path.truncate(len);
        r
    }

    fn field<T: Serialize + ?Sized>(&mut self, key: &str, value: &T) -> Result<(), CheckError> {
        if self.path.is_empty() {
            self.nested(format_args!("{key}"), value)
        } else {
            self.nested(format_args!(".{key}"), value)
        }
    }
}

/// Sequences, tuples and maps: counts elements, remembers the pending map key.
struct Compound<'a> {
    checker: &'a mut Checker,
    index: usize,
    key: String,
}

impl Compound<'_> {
    fn element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), CheckError> {
        let i = self.index;
        self.index += 1;
        self.checker.nested(format_args!("[{i}]"), value)
    }
}

macro_rules! accept {
    ($($method:ident($ty:ty)),* $(,)?) => {
        $(fn $method(self, _v: $ty) -> Result<(), CheckError> { Ok(()) })*
    };
}

/// The `serialize_*` methods that open a [`Compound`] (sequences, tuples, maps, structs).
macro_rules! open_compound {
    ($compound:ty; $($method:ident($($arg:ident: $ty:ty),*)),* $(,)?) => {
        $(fn $method(self, $($arg: $ty),*) -> Result<$compound, CheckError> {
            Ok(self.compound())
        })*
    };
}

impl<'a> ser::Serializer for &'a mut Checker {
    type Ok = ();
    type Error = CheckError;
    type SerializeSeq = Compound<'a>;
    type SerializeTuple = Compound<'a>;
    type SerializeTupleStruct = Compound<'a>;
    type SerializeTupleVariant = Compound<'a>;
    type SerializeMap = Compound<'a>;
    type SerializeStruct = Compound<'a>;
    type SerializeStructVariant = Compound<'a>;

    accept!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_i128(i128),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_u128(u128),
        serialize_char(char),
        serialize_str(&str),
        serialize_bytes(&[u8]),
        serialize_unit_struct(&'static str),
    );

    fn serialize_f32(self, v: f32) -> Result<(), CheckError> {
        self.float(f64::from(v))
    }
    fn serialize_f64(self, v: f64) -> Result<(), CheckError> {
        self.float(v)
    }
    fn serialize_none(self) -> Result<(), CheckError> {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), CheckError> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), CheckError> {
        Ok(())
    }
    fn serialize_unit_variant(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
    ) -> Result<(), CheckError> {
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        value: &T,
    ) -> Result<(), CheckError> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<(), CheckError> {
        self.field(variant, value)
    }
    open_compound!(
        Compound<'a>;
        serialize_seq(_len: Option<usize>),
        serialize_tuple(_len: usize),
        serialize_tuple_struct(_name: &'static str, _len: usize),
        serialize_tuple_variant(_name: &'static str, _index: u32, _variant: &'static str, _len: usize),
        serialize_map(_len: Option<usize>),
        serialize_struct(_name: &'static str, _len: usize),
        serialize_struct_variant(_name: &'static str, _index: u32, _variant: &'static str, _len: usize),
    );
}

impl Checker {
    fn compound(&mut self) -> Compound<'_> {
        Compound {
            checker: self,
            index: 0,
            key: String::new(),
        }
    }
}

/// The serde compound traits whose elements are checked in order ([`Compound::element`]).
macro_rules! checked_elements {
    ($($serialize:ident::$method:ident),* $(,)?) => {$(
        impl ser::$serialize for Compound<'_> {
            type Ok = ();
            type Error = CheckError;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), CheckError> {
                self.element(value)
            }
            fn end(self) -> Result<(), CheckError> {
                Ok(())
            }
        }
    )*};
}

checked_elements!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field,
);

/// The serde compound traits whose fields are checked under their names.
macro_rules! checked_fields {
    ($($serialize:ident),* $(,)?) => {$(
        impl ser::$serialize for Compound<'_> {
            type Ok = ();
            type Error = CheckError;
            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                value: &T,
            ) -> Result<(), CheckError> {
                self.checker.field(key, value)
            }
            fn end(self) -> Result<(), CheckError> {
                Ok(())
            }
        }
    )*};
}

checked_fields!(SerializeStruct, SerializeStructVariant);

impl ser::SerializeMap for Compound<'_> {
    type Ok = ();
    type Error = CheckError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), CheckError> {
        self.key = key_name(key)?;
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), CheckError> {
        let key = std::mem::take(&mut self.key);
        self.checker.field(&key, value)
    }
    fn end(self) -> Result<(), CheckError> {
        Ok(())
    }
}

/// A map key as a name: a string, number, bool or unit variant, as JSON allows (serde_json's
/// own rendering of it); anything else is refused as serde_json refuses it.
fn key_name<T: Serialize + ?Sized>(key: &T) -> Result<String, CheckError> {
    match serde_json::to_value(key) {
        Ok(serde_json::Value::String(s)) => Ok(s),
        Ok(serde_json::Value::Number(n)) => Ok(n.to_string()),
        Ok(serde_json::Value::Bool(b)) => Ok(b.to_string()),
        _ => Err(key_error()),
    }
}

/// The same message serde_json gives for a key it cannot write.
fn key_error() -> CheckError {
    CheckError::Custom("key must be a string".to_owned())
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;

    #[derive(Serialize)]
    struct Inner {
        tension: Vec<f64>,
    }

    #[derive(Serialize)]
    struct Outer {
        name: &'static str,
        profiles: Vec<Inner>,
        extra: Option<f64>,
    }

    fn non_finite(r: Result<(), OutputError>) -> (String, usize) {
        match r {
            Err(OutputError::NonFinite { column, index, .. }) => (column, index),
            other => panic!("expected NonFinite, got {other:?}"),
        }
    }

    #[test]
    fn nested_nan_is_named_by_path() {
        let v = Outer {
            name: "x",
            profiles: vec![
                Inner { tension: vec![1.0] },
                Inner {
                    tension: vec![1.0, 2.0, f64::NAN],
                },
            ],
            extra: None,
        };
        assert_eq!(
            non_finite(check_finite_json(&v)),
            ("profiles[1].tension".to_owned(), 2)
        );
    }

    #[test]
    fn option_and_map_values_are_checked() {
        let v = Outer {
            name: "x",
            profiles: vec![],
            extra: Some(f64::NEG_INFINITY),
        };
        assert_eq!(non_finite(check_finite_json(&v)), ("extra".to_owned(), 0));
        let m: BTreeMap<&str, f64> = [("ok", 1.0), ("bad", f64::NAN)].into();
        assert_eq!(non_finite(check_finite_json(&m)), ("bad".to_owned(), 0));
        let m: BTreeMap<u32, f64> = [(3, f64::NAN)].into();
        assert_eq!(non_finite(check_finite_json(&m)), ("3".to_owned(), 0));
        let m: BTreeMap<bool, f64> = [(true, f64::NAN)].into();
        assert_eq!(non_finite(check_finite_json(&m)), ("true".to_owned(), 0));
        let m: BTreeMap<Vec<u8>, f64> = [(vec![1], 1.0)].into();
        assert!(check_finite_json(&m).is_err()); // a key JSON cannot write
        assert_eq!(
            non_finite(check_finite_json(&f32::NAN)),
            ("(value)".to_owned(), 0)
        );
    }

    #[test]
    fn finite_values_pass() {
        let v = Outer {
            name: "x",
            profiles: vec![Inner {
                tension: vec![1.0, 2.0],
            }],
            extra: Some(3.0),
        };
        check_finite_json(&v).unwrap();
        assert!(to_json_string(&v).unwrap().contains("\"tension\""));
    }
}
