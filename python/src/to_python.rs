//! Serde values as Python objects, built directly (no JSON text to write and parse again): a
//! run's summary becomes the dict `json.loads(summary.json)` would give, for a fraction of the
//! cost. It follows serde_json's data model exactly: structs and maps as dicts (keys as
//! strings), sequences as lists, enums externally tagged, `None` and non-finite floats as None.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use pyo3::BoundObject;
use serde::ser::{self, Serialize};

/// `value` as Python objects.
pub fn to_python<'py, T: Serialize + ?Sized>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    value.serialize(Builder { py }).map_err(|e| e.0)
}

/// A Python error carried through serde.
#[derive(Debug)]
pub struct Failure(PyErr);

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl std::error::Error for Failure {}

impl ser::Error for Failure {
    fn custom<T: std::fmt::Display>(msg: T) -> Self {
        Failure(PyValueError::new_err(msg.to_string()))
    }
}

impl From<PyErr> for Failure {
    fn from(e: PyErr) -> Self {
        Failure(e)
    }
}

#[derive(Clone, Copy)]
struct Builder<'py> {
    py: Python<'py>,
}

type Out<'py> = Result<Bound<'py, PyAny>, Failure>;

impl<'py> Builder<'py> {
    fn object<T: IntoPyObject<'py>>(self, v: T) -> Out<'py> {
        v.into_pyobject(self.py)
            .map(|o| o.into_any().into_bound())
            .map_err(|e| Failure(e.into()))
    }
}

/// A list being filled.
struct Seq<'py> {
    b: Builder<'py>,
    items: Vec<Bound<'py, PyAny>>,
    /// The variant a tuple variant is wrapped in.
    variant: Option<&'static str>,
}

/// A dict being filled.
struct Map<'py> {
    b: Builder<'py>,
    dict: Bound<'py, PyDict>,
    key: Option<Bound<'py, PyAny>>,
    /// The variant a struct variant is wrapped in.
    variant: Option<&'static str>,
}

impl<'py> Seq<'py> {
    fn push<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), Failure> {
        self.items.push(v.serialize(self.b)?);
        Ok(())
    }
    fn done(self) -> Out<'py> {
        let list = PyList::new(self.b.py, self.items)?.into_any();
        wrap(self.b, self.variant, list)
    }
}

/// `{variant: value}` for a variant with data, else the value.
fn wrap<'py>(b: Builder<'py>, variant: Option<&'static str>, value: Bound<'py, PyAny>) -> Out<'py> {
    match variant {
        Some(name) => {
            let d = PyDict::new(b.py);
            d.set_item(name, value)?;
            Ok(d.into_any())
        }
        None => Ok(value),
    }
}

/// A map key as a string, as JSON writes it.
fn key_string<'py>(key: Bound<'py, PyAny>) -> Out<'py> {
    if key.is_instance_of::<pyo3::types::PyString>() {
        Ok(key)
    } else {
        Ok(key.str()?.into_any())
    }
}

impl<'py> ser::Serializer for Builder<'py> {
    type Ok = Bound<'py, PyAny>;
    type Error = Failure;
    type SerializeSeq = Seq<'py>;
    type SerializeTuple = Seq<'py>;
    type SerializeTupleStruct = Seq<'py>;
    type SerializeTupleVariant = Seq<'py>;
    type SerializeMap = Map<'py>;
    type SerializeStruct = Map<'py>;
    type SerializeStructVariant = Map<'py>;

    fn serialize_bool(self, v: bool) -> Out<'py> {
        self.object(v)
    }
    fn serialize_i8(self, v: i8) -> Out<'py> {
        self.object(v)
    }
    fn serialize_i16(self, v: i16) -> Out<'py> {
        self.object(v)
    }
    fn serialize_i32(self, v: i32) -> Out<'py> {
        self.object(v)
    }
    fn serialize_i64(self, v: i64) -> Out<'py> {
        self.object(v)
    }
    fn serialize_u8(self, v: u8) -> Out<'py> {
        self.object(v)
    }
    fn serialize_u16(self, v: u16) -> Out<'py> {
        self.object(v)
    }
    fn serialize_u32(self, v: u32) -> Out<'py> {
        self.object(v)
    }
    fn serialize_u64(self, v: u64) -> Out<'py> {
        self.object(v)
    }
    fn serialize_f32(self, v: f32) -> Out<'py> {
        self.serialize_f64(f64::from(v))
    }
    fn serialize_f64(self, v: f64) -> Out<'py> {
        // JSON has no NaN or infinity: serde_json writes null.
        if v.is_finite() {
            self.object(v)
        } else {
            self.serialize_none()
        }
    }
    fn serialize_char(self, v: char) -> Out<'py> {
        self.object(v.to_string())
    }
    fn serialize_str(self, v: &str) -> Out<'py> {
        self.object(v)
    }
    fn serialize_bytes(self, v: &[u8]) -> Out<'py> {
        self.object(v.to_vec())
    }
    fn serialize_none(self) -> Out<'py> {
        Ok(self.py.None().into_bound(self.py))
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Out<'py> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Out<'py> {
        self.serialize_none()
    }
    fn serialize_unit_struct(self, _: &'static str) -> Out<'py> {
        self.serialize_none()
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, variant: &'static str) -> Out<'py> {
        self.object(variant)
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Out<'py> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Out<'py> {
        let inner = value.serialize(self)?;
        wrap(self, Some(variant), inner)
    }
    fn serialize_seq(self, len: Option<usize>) -> Result<Seq<'py>, Failure> {
        Ok(Seq {
            b: self,
            items: Vec::with_capacity(len.unwrap_or(0)),
            variant: None,
        })
    }
    fn serialize_tuple(self, len: usize) -> Result<Seq<'py>, Failure> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_struct(self, _: &'static str, len: usize) -> Result<Seq<'py>, Failure> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        len: usize,
    ) -> Result<Seq<'py>, Failure> {
        let mut s = self.serialize_seq(Some(len))?;
        s.variant = Some(variant);
        Ok(s)
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Map<'py>, Failure> {
        Ok(Map {
            b: self,
            dict: PyDict::new(self.py),
            key: None,
            variant: None,
        })
    }
    fn serialize_struct(self, _: &'static str, len: usize) -> Result<Map<'py>, Failure> {
        self.serialize_map(Some(len))
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        len: usize,
    ) -> Result<Map<'py>, Failure> {
        let mut m = self.serialize_map(Some(len))?;
        m.variant = Some(variant);
        Ok(m)
    }
}

/// The sequence kinds serde tells apart, all lists here: each hands its items to [`Seq::push`].
macro_rules! list {
    ($($kind:ident :: $method:ident),*) => {$(
        impl<'py> ser::$kind for Seq<'py> {
            type Ok = Bound<'py, PyAny>;
            type Error = Failure;
            fn $method<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), Failure> {
                self.push(v)
            }
            fn end(self) -> Out<'py> {
                self.done()
            }
        }
    )*};
}

list!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field
);

impl<'py> Map<'py> {
    fn field<T: Serialize + ?Sized>(&mut self, key: &str, v: &T) -> Result<(), Failure> {
        self.dict.set_item(key, v.serialize(self.b)?)?;
        Ok(())
    }
    fn done(self) -> Out<'py> {
        wrap(self.b, self.variant, self.dict.into_any())
    }
}

impl<'py> ser::SerializeMap for Map<'py> {
    type Ok = Bound<'py, PyAny>;
    type Error = Failure;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), Failure> {
        self.key = Some(key_string(key.serialize(self.b)?)?);
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), Failure> {
        let key = self
            .key
            .take()
            .ok_or_else(|| <Failure as ser::Error>::custom("a map value without its key"))?;
        self.dict.set_item(key, v.serialize(self.b)?)?;
        Ok(())
    }
    fn end(self) -> Out<'py> {
        self.done()
    }
}

/// Structs and struct variants, both dicts here: each hands its fields to [`Map::field`].
macro_rules! dict {
    ($($kind:ident),*) => {$(
        impl<'py> ser::$kind for Map<'py> {
            type Ok = Bound<'py, PyAny>;
            type Error = Failure;
            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                v: &T,
            ) -> Result<(), Failure> {
                self.field(key, v)
            }
            fn end(self) -> Out<'py> {
                self.done()
            }
        }
    )*};
}

dict!(SerializeStruct, SerializeStructVariant);
