//! NumPy arrays to and from the library's `TriMesh`: one copy each way,
//! no Python object per element.
//!
//! Inputs arrive already normalized by `swm/__init__.py` (C-contiguous
//! float32 `(n, 3)` and uint32 `(m, 3)`); the shape checks here guard
//! direct callers of `swm._swm`.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Copies an `(n, 3)` array into rows of three.
fn rows<T: numpy::Element + Copy>(
    array: &PyReadonlyArray2<'_, T>,
    what: &str,
) -> PyResult<Vec<[T; 3]>> {
    let shape = array.shape();
    if shape[1] != 3 {
        return Err(PyValueError::new_err(format!(
            "{what} must have shape (n, 3), got ({}, {})",
            shape[0], shape[1]
        )));
    }
    // `as_array` handles any strides; rows are copied one by one.
    Ok(array
        .as_array()
        .rows()
        .into_iter()
        .map(|r| [r[0], r[1], r[2]])
        .collect())
}

/// The mesh of a `(vertices, faces)` pair (not validated: the library
/// validates what it is given).
pub fn mesh(
    vertices: &PyReadonlyArray2<'_, f32>,
    faces: &PyReadonlyArray2<'_, u32>,
) -> PyResult<swm::TriMesh> {
    Ok(swm::TriMesh::new(
        rows(vertices, "vertices")?,
        rows(faces, "faces")?,
    ))
}

/// `(n, 3)` NumPy array owning the rows' memory (no copy).
pub fn to_numpy<'py, T: numpy::Element>(
    py: Python<'py>,
    rows: Vec<[T; 3]>,
) -> Bound<'py, PyArray2<T>> {
    let n = rows.len();
    let flat: Vec<T> = rows.into_flattened();
    Array2::from_shape_vec((n, 3), flat)
        .expect("n rows of 3 make an (n, 3) array")
        .into_pyarray(py)
}
