//! Attribute streams to and from a dict of per-vertex NumPy arrays.
//!
//! Python gets the split (GPU) form of `swm::AttributedMesh::split_vertices`:
//! one vertex per distinct position and values, so every array has one
//! row per vertex and the faces index them all, as trimesh, glTF and
//! vertex buffers want. Names follow trimesh's words (`vertex_normals`,
//! `uv`, `vertex_colors`): `normals`, `uv`, `colors`, with the set number
//! after a second set (`uv1`, `colors1`), and `generic{n}` for a generic
//! stream.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use swm::AttributeKind;

/// The dict key of a stream kind.
pub fn name(kind: AttributeKind) -> String {
    match kind {
        AttributeKind::Normal => "normals".into(),
        AttributeKind::TexCoord(0) => "uv".into(),
        AttributeKind::TexCoord(n) => format!("uv{n}"),
        AttributeKind::Color(0) => "colors".into(),
        AttributeKind::Color(n) => format!("colors{n}"),
        AttributeKind::Generic(n) => format!("generic{n}"),
        // `AttributeKind` is non-exhaustive: a kind this binding does not
        // know yet still reaches Python under its Debug name.
        other => format!("{other:?}").to_lowercase(),
    }
}

/// The stream kind of a dict key, the inverse of [`name`].
fn kind(key: &str) -> Option<AttributeKind> {
    let set = |rest: &str| -> Option<u8> {
        match rest {
            "" => Some(0),
            // "uv01" or "uv+1" would parse; only the canonical spelling is a key.
            n if !n.starts_with('0') && n.bytes().all(|b| b.is_ascii_digit()) => n.parse().ok(),
            _ => None,
        }
    };
    if key == "normals" {
        return Some(AttributeKind::Normal);
    }
    if let Some(rest) = key.strip_prefix("uv") {
        return set(rest).map(AttributeKind::TexCoord);
    }
    if let Some(rest) = key.strip_prefix("colors") {
        return set(rest).map(AttributeKind::Color);
    }
    let n = key.strip_prefix("generic")?;
    match n == "0" || (!n.starts_with('0') && n.bytes().all(|b| b.is_ascii_digit())) {
        true => n.parse().ok().map(AttributeKind::Generic),
        false => None,
    }
}

/// The streams of a split mesh as `{name: (n, dims) float32 array}`, in
/// the file's stream order. Each array owns the decoder's memory (no copy).
pub fn to_dict(py: Python<'_>, streams: Vec<swm::AttributeStream>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for s in streams {
        let dims = usize::from(s.dims);
        let rows = s.values.len() / dims.max(1);
        let array = Array2::from_shape_vec((rows, dims), s.values)
            .expect("a stream holds dims floats per value")
            .into_pyarray(py);
        out.set_item(name(s.kind), array)?;
    }
    Ok(out)
}

/// Streams of per-vertex arrays for `mesh` (each indexed by the
/// triangles), from a dict `to_dict` would give. Keys, shapes and row
/// counts are checked here so the error names the key; what the values
/// may be (finite, dims per kind) is the library's check.
pub fn from_dict(
    dict: &Bound<'_, PyDict>,
    mesh: &swm::TriMesh,
) -> PyResult<Vec<swm::AttributeStream>> {
    let mut streams = Vec::with_capacity(dict.len());
    for (key, value) in dict.iter() {
        let key: String = key
            .extract()
            .map_err(|_| PyTypeError::new_err("attribute names must be strings"))?;
        let kind = kind(&key).ok_or_else(|| {
            PyValueError::new_err(format!(
                "unknown attribute {key:?}: the names are \"normals\", \"uv\", \"uv1\", ..., \
                 \"colors\", \"colors1\", ... and \"generic0\", \"generic1\", ..."
            ))
        })?;
        let array: PyReadonlyArray2<'_, f32> = value.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "attribute {key:?} must be a float32 array of shape (n, dims)"
            ))
        })?;
        let [rows, dims] = [array.shape()[0], array.shape()[1]];
        if rows != mesh.positions.len() {
            return Err(PyValueError::new_err(format!(
                "attribute {key:?} has {rows} rows for {} vertices (one row per vertex)",
                mesh.positions.len()
            )));
        }
        let dims = u8::try_from(dims)
            .ok()
            .filter(|&d| kind.allows_dims(d))
            .ok_or_else(|| {
                PyValueError::new_err(format!(
                    "attribute {key:?} has {dims} columns, which a stream of its kind cannot have \
                     (normals 3, uv 2 or 3, colors 3 or 4, generic 1 to 4)"
                ))
            })?;
        // `iter` walks any strides in logical (row-major) order.
        let values: Vec<f32> = array.as_array().iter().copied().collect();
        streams.push(swm::AttributeStream::new(
            kind,
            dims,
            values,
            mesh.triangles.clone(),
        ));
    }
    // In kind order (normals, texture sets, colour sets, generic), as the
    // mesh readers give them: the same arrays make the same bytes as
    // `swm encode` of a file holding them, whatever the dict's order.
    streams.sort_by_key(|s| s.kind);
    Ok(streams)
}
