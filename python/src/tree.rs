//! A serde serializer into Python objects: maps and structs become dicts, strings and numbers
//! their Python types, and a list of numbers a numpy array (`float64`, or `int64` for counts);
//! a list of equal-shape float arrays one array of one more dimension (a `[roller][angle]`
//! curve 2-D, a `[roller][crank][slice]` line load 3-D). A tuple struct (a value and its
//! uncertainty, `report::fit::ValueSigma`) becomes a Python tuple, whatever its items. Each
//! array owns its data (copied out of the document), so it outlives the run it came from.
//!
//! The typed documents of the results JSON go through it unchanged, so the keys, units and
//! shapes are the JSON's, with no text in between.

use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyList, PyString, PyTuple};
use serde::ser::{self, Serialize};
use std::fmt;

/// `value` as Python objects, its lists of numbers numpy arrays.
pub(crate) fn to_py<T: Serialize + ?Sized>(py: Python<'_>, value: &T) -> PyResult<Py<PyAny>> {
    convert(py, value, true)
}

/// `value` as plain Python objects: lists stay lists.
pub(crate) fn to_plain_py<T: Serialize + ?Sized>(py: Python<'_>, value: &T) -> PyResult<Py<PyAny>> {
    convert(py, value, false)
}

fn convert<T: Serialize + ?Sized>(py: Python<'_>, value: &T, arrays: bool) -> PyResult<Py<PyAny>> {
    let node = value
        .serialize(Ser { py, arrays })
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.0))?;
    node.into_py(py)
        .map(Bound::unbind)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.0))
}

/// A serialised value, numbers kept apart until their list is known to be all numbers.
pub(crate) enum Node<'py> {
    Float(f64),
    Int(i64),
    Floats(Vec<f64>),
    /// A `float64` array of 2 or more dimensions: its shape and its values in C order.
    Array(Vec<usize>, Vec<f64>),
    Obj(Bound<'py, PyAny>),
}

#[derive(Debug)]
pub(crate) struct SerError(String);

impl fmt::Display for SerError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SerError {}

impl ser::Error for SerError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        SerError(msg.to_string())
    }
}

fn py_err(e: PyErr) -> SerError {
    SerError(e.to_string())
}

impl<'py> Node<'py> {
    fn into_py(self, py: Python<'py>) -> Result<Bound<'py, PyAny>, SerError> {
        Ok(match self {
            Node::Float(x) => pyo3::types::PyFloat::new(py, x).into_any(),
            Node::Int(i) => i
                .into_pyobject(py)
                .unwrap_or_else(|e| match e {})
                .into_any(),
            Node::Floats(v) => PyArray1::from_vec(py, v).into_any(),
            Node::Array(shape, v) => PyArray1::from_vec(py, v)
                .reshape(shape)
                .map_err(py_err)?
                .into_any(),
            Node::Obj(o) => o,
        })
    }
}

/// The list `items`: an array when arrays are asked for and they are all numbers or all
/// equal-length float arrays, else a Python list.
fn list<'py>(py: Python<'py>, items: Vec<Node<'py>>, arrays: bool) -> Result<Node<'py>, SerError> {
    if arrays && !items.is_empty() {
        if items.iter().all(|n| matches!(n, Node::Float(_))) {
            let v = items
                .into_iter()
                .map(|n| match n {
                    Node::Float(x) => x,
                    _ => unreachable!("all floats"),
                })
                .collect();
            return Ok(Node::Floats(v));
        }
        if items.iter().all(|n| matches!(n, Node::Int(_))) {
            let v: Vec<i64> = items
                .into_iter()
                .map(|n| match n {
                    Node::Int(i) => i,
                    _ => unreachable!("all ints"),
                })
                .collect();
            return Ok(Node::Obj(PyArray1::from_vec(py, v).into_any()));
        }
        if let Some(shape) = common_shape(&items) {
            let mut flat = Vec::with_capacity(items.len() * shape.iter().product::<usize>());
            for item in &items {
                match item {
                    Node::Floats(v) | Node::Array(_, v) => flat.extend_from_slice(v),
                    _ => unreachable!("all arrays"),
                }
            }
            let mut dims = vec![items.len()];
            dims.extend(shape);
            return Ok(Node::Array(dims, flat));
        }
    }
    let out = PyList::empty(py);
    for item in items {
        out.append(item.into_py(py)?).map_err(py_err)?;
    }
    Ok(Node::Obj(out.into_any()))
}

/// The shape every item shares when all are float arrays of one shape (none else).
fn common_shape(items: &[Node<'_>]) -> Option<Vec<usize>> {
    let shape = |n: &Node<'_>| match n {
        Node::Floats(v) => Some(vec![v.len()]),
        Node::Array(shape, _) => Some(shape.clone()),
        _ => None,
    };
    let first = shape(items.first()?)?;
    items
        .iter()
        .all(|n| shape(n).as_ref() == Some(&first))
        .then_some(first)
}

/// The serializer: each value becomes a [`Node`].
#[derive(Clone, Copy)]
pub(crate) struct Ser<'py> {
    py: Python<'py>,
    /// Lists of numbers become numpy arrays.
    arrays: bool,
}

/// A list being serialised.
pub(crate) struct Seq<'py> {
    py: Python<'py>,
    arrays: bool,
    items: Vec<Node<'py>>,
}

/// A map or struct being serialised.
pub(crate) struct Map<'py> {
    py: Python<'py>,
    arrays: bool,
    dict: Bound<'py, PyDict>,
    key: Option<Bound<'py, PyAny>>,
}

impl<'py> Ser<'py> {
    fn obj(self, o: Bound<'py, PyAny>) -> Result<Node<'py>, SerError> {
        Ok(Node::Obj(o))
    }

    fn none(self) -> Result<Node<'py>, SerError> {
        self.obj(self.py.None().into_bound(self.py))
    }
}

impl<'py> ser::Serializer for Ser<'py> {
    type Ok = Node<'py>;
    type Error = SerError;
    type SerializeSeq = Seq<'py>;
    type SerializeTuple = Seq<'py>;
    type SerializeTupleStruct = Seq<'py>;
    type SerializeTupleVariant = ser::Impossible<Node<'py>, SerError>;
    type SerializeMap = Map<'py>;
    type SerializeStruct = Map<'py>;
    type SerializeStructVariant = ser::Impossible<Node<'py>, SerError>;

    fn serialize_bool(self, v: bool) -> Result<Self::Ok, SerError> {
        self.obj(PyBool::new(self.py, v).to_owned().into_any())
    }
    fn serialize_i8(self, v: i8) -> Result<Self::Ok, SerError> {
        Ok(Node::Int(v.into()))
    }
    fn serialize_i16(self, v: i16) -> Result<Self::Ok, SerError> {
        Ok(Node::Int(v.into()))
    }
    fn serialize_i32(self, v: i32) -> Result<Self::Ok, SerError> {
        Ok(Node::Int(v.into()))
    }
    fn serialize_i64(self, v: i64) -> Result<Self::Ok, SerError> {
        Ok(Node::Int(v))
    }
    fn serialize_u8(self, v: u8) -> Result<Self::Ok, SerError> {
        Ok(Node::Int(v.into()))
    }
    fn serialize_u16(self, v: u16) -> Result<Self::Ok, SerError> {
        Ok(Node::Int(v.into()))
    }
    fn serialize_u32(self, v: u32) -> Result<Self::Ok, SerError> {
        Ok(Node::Int(v.into()))
    }
    fn serialize_u64(self, v: u64) -> Result<Self::Ok, SerError> {
        match i64::try_from(v) {
            Ok(i) => Ok(Node::Int(i)),
            Err(_) => self.obj(
                v.into_pyobject(self.py)
                    .unwrap_or_else(|e| match e {})
                    .into_any(),
            ),
        }
    }
    fn serialize_f32(self, v: f32) -> Result<Self::Ok, SerError> {
        Ok(Node::Float(v.into()))
    }
    fn serialize_f64(self, v: f64) -> Result<Self::Ok, SerError> {
        Ok(Node::Float(v))
    }
    fn serialize_char(self, v: char) -> Result<Self::Ok, SerError> {
        self.serialize_str(v.encode_utf8(&mut [0; 4]))
    }
    fn serialize_str(self, v: &str) -> Result<Self::Ok, SerError> {
        self.obj(PyString::new(self.py, v).into_any())
    }
    fn serialize_bytes(self, v: &[u8]) -> Result<Self::Ok, SerError> {
        self.obj(pyo3::types::PyBytes::new(self.py, v).into_any())
    }
    fn serialize_none(self) -> Result<Self::Ok, SerError> {
        self.none()
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<Self::Ok, SerError> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<Self::Ok, SerError> {
        self.none()
    }
    fn serialize_unit_struct(self, _name: &'static str) -> Result<Self::Ok, SerError> {
        self.none()
    }
    fn serialize_unit_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
    ) -> Result<Self::Ok, SerError> {
        self.serialize_str(variant)
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        value: &T,
    ) -> Result<Self::Ok, SerError> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<Self::Ok, SerError> {
        let dict = PyDict::new(self.py);
        let inner = value.serialize(self)?.into_py(self.py)?;
        dict.set_item(variant, inner).map_err(py_err)?;
        self.obj(dict.into_any())
    }
    fn serialize_seq(self, len: Option<usize>) -> Result<Seq<'py>, SerError> {
        Ok(Seq {
            py: self.py,
            arrays: self.arrays,
            items: Vec::with_capacity(len.unwrap_or(0)),
        })
    }
    fn serialize_tuple(self, len: usize) -> Result<Seq<'py>, SerError> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_struct(self, _name: &'static str, len: usize) -> Result<Seq<'py>, SerError> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_variant(
        self,
        name: &'static str,
        _index: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<Self::SerializeTupleVariant, SerError> {
        Err(SerError(format!(
            "{name}::{variant}: tuple variants are not supported"
        )))
    }
    fn serialize_map(self, _len: Option<usize>) -> Result<Map<'py>, SerError> {
        Ok(Map {
            py: self.py,
            arrays: self.arrays,
            dict: PyDict::new(self.py),
            key: None,
        })
    }
    fn serialize_struct(self, _name: &'static str, len: usize) -> Result<Map<'py>, SerError> {
        self.serialize_map(Some(len))
    }
    fn serialize_struct_variant(
        self,
        name: &'static str,
        _index: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<Self::SerializeStructVariant, SerError> {
        Err(SerError(format!(
            "{name}::{variant}: struct variants are not supported"
        )))
    }
}

impl<'py> ser::SerializeSeq for Seq<'py> {
    type Ok = Node<'py>;
    type Error = SerError;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), SerError> {
        self.items.push(value.serialize(Ser {
            py: self.py,
            arrays: self.arrays,
        })?);
        Ok(())
    }
    fn end(self) -> Result<Node<'py>, SerError> {
        list(self.py, self.items, self.arrays)
    }
}

impl<'py> ser::SerializeTuple for Seq<'py> {
    type Ok = Node<'py>;
    type Error = SerError;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), SerError> {
        ser::SerializeSeq::serialize_element(self, value)
    }
    fn end(self) -> Result<Node<'py>, SerError> {
        ser::SerializeSeq::end(self)
    }
}

impl<'py> ser::SerializeTupleStruct for Seq<'py> {
    type Ok = Node<'py>;
    type Error = SerError;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), SerError> {
        ser::SerializeSeq::serialize_element(self, value)
    }
    /// A Python tuple, never an array.
    fn end(self) -> Result<Node<'py>, SerError> {
        let items = (self.items.into_iter())
            .map(|item| item.into_py(self.py))
            .collect::<Result<Vec<_>, _>>()?;
        let tuple = PyTuple::new(self.py, items).map_err(py_err)?;
        Ok(Node::Obj(tuple.into_any()))
    }
}

impl<'py> ser::SerializeMap for Map<'py> {
    type Ok = Node<'py>;
    type Error = SerError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), SerError> {
        self.key = Some(
            key.serialize(Ser {
                py: self.py,
                arrays: self.arrays,
            })?
            .into_py(self.py)?,
        );
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), SerError> {
        let key = self
            .key
            .take()
            .ok_or_else(|| SerError("a map value without its key".into()))?;
        let value = value
            .serialize(Ser {
                py: self.py,
                arrays: self.arrays,
            })?
            .into_py(self.py)?;
        self.dict.set_item(key, value).map_err(py_err)
    }
    fn end(self) -> Result<Node<'py>, SerError> {
        Ok(Node::Obj(self.dict.into_any()))
    }
}

impl<'py> ser::SerializeStruct for Map<'py> {
    type Ok = Node<'py>;
    type Error = SerError;
    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<(), SerError> {
        let value = value
            .serialize(Ser {
                py: self.py,
                arrays: self.arrays,
            })?
            .into_py(self.py)?;
        self.dict.set_item(key, value).map_err(py_err)
    }
    fn skip_field(&mut self, _key: &'static str) -> Result<(), SerError> {
        Ok(())
    }
    fn end(self) -> Result<Node<'py>, SerError> {
        Ok(Node::Obj(self.dict.into_any()))
    }
}
