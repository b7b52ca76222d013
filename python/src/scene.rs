//! Whole glTF scenes (format-spec/09-gltf.md) from Python:
//! `swm.encode_scene` codes each triangle primitive of a `.glb` or
//! `.gltf` document inside `SWM_mesh_compression` and keeps the rest
//! (`swm::io::encode_scene`), `swm.decode_scene` expands it
//! (`swm::io::decode_scene`), `swm.scene_info` lists the primitives
//! (`swm::io::scene_info`). These are the library calls `swm encode
//! scene.glb -o out.glb`, `swm decode` and `swm info` make, with the
//! same options, so the same document gives the same bytes.
//!
//! A document comes as bytes or as a path. From a path, the file is read
//! here (under the limits) and its folder is where external buffers are
//! looked for; from bytes, `base` names that folder (without it, a
//! document with external buffers is refused by the library).

use crate::errors::IntoPyResult;
use crate::{effort_of, encode_mode, quantization, Limits};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};
use std::path::{Path, PathBuf};
use swm::io::{PrimitiveOutcome, SceneFormat};

/// The output container by its name.
fn format_of(format: &str) -> PyResult<SceneFormat> {
    match format {
        "glb" => Ok(SceneFormat::Glb),
        "gltf" => Ok(SceneFormat::Gltf),
        other => Err(PyValueError::new_err(format!(
            "format must be \"glb\" or \"gltf\", got {other:?}"
        ))),
    }
}

/// Exactly one of `data` and `path`, as the wrapper passes them.
fn one_source(data: Option<&[u8]>, path: Option<&Path>) -> PyResult<()> {
    match (data, path) {
        (Some(_), None) | (None, Some(_)) => Ok(()),
        _ => Err(PyValueError::new_err(
            "give the document as bytes or as a path, one of the two",
        )),
    }
}

/// Runs `work` on the document's bytes and the folder of its external
/// buffers, without the GIL; an error names `path` when there is one.
fn with_document<T: Send>(
    py: Python<'_>,
    data: Option<&[u8]>,
    path: Option<&Path>,
    base: Option<&Path>,
    limits: &swm::Limits,
    work: impl FnOnce(&[u8], Option<&Path>) -> Result<T, swm::Error> + Send,
) -> PyResult<T> {
    one_source(data, path)?;
    match (data, path) {
        (Some(bytes), _) => py.detach(|| work(bytes, base)).py_err(py),
        (None, Some(path)) => py
            .detach(|| {
                let bytes = swm::io::read_file_with(path, limits)?;
                work(&bytes[..], base.or(path.parent()))
            })
            .py_err_file(py, &path.to_string_lossy()),
        (None, None) => unreachable!("one_source checked it"),
    }
}

/// Compresses a glTF document: the output's bytes (with `report`,
/// `(bytes, dict)`). See `swm/__init__.py` for the documented wrapper.
#[pyfunction]
#[pyo3(signature = (data=None, *, path=None, base=None, bpv=None, size=None, edge_length=None,
                    mode="auto", angle_bits=None, qp=None, report=false, effort="default",
                    max_error=None, qn=None, qt=None, qg=None, keep_normals=false,
                    fallback=false, format="glb", limits=None))]
#[allow(clippy::too_many_arguments)]
pub fn encode_scene<'py>(
    py: Python<'py>,
    data: Option<&[u8]>,
    path: Option<PathBuf>,
    base: Option<PathBuf>,
    bpv: Option<f64>,
    size: Option<i128>,
    edge_length: Option<f64>,
    mode: &str,
    angle_bits: Option<i64>,
    qp: Option<i64>,
    report: bool,
    effort: &str,
    max_error: Option<f64>,
    qn: Option<i64>,
    qt: Option<i64>,
    qg: Option<i64>,
    keep_normals: bool,
    fallback: bool,
    format: &str,
    limits: Option<PyRef<'py, Limits>>,
) -> PyResult<Bound<'py, PyAny>> {
    one_source(data, path.as_deref())?;
    let effort = effort_of(effort)?;
    let format = format_of(format)?;
    let attribute_bits = quantization(qn, qt, qg).py_err(py)?;
    // Texture coordinates' bits: the one attribute option a swing or
    // displaced file has no use for (it carries all streams but them).
    let texcoord_bits = qt.is_some();
    // `swm encode`'s rules for a scene: those of a mesh, and no max_size
    // (the size is the whole scene's swm budget).
    let mode = encode_mode(
        py,
        bpv,
        size,
        edge_length,
        mode,
        None,
        angle_bits,
        qp,
        max_error,
        texcoord_bits,
    )?;
    let limits = Limits::to_swm(limits.as_deref());
    let options = swm::io::SceneOptions {
        encode: swm::EncodeOptions {
            mode,
            effort,
            attributes: attribute_bits,
            keep_smooth_normals: keep_normals,
            ..Default::default()
        },
        // As `swm encode`: the primitives coded losslessly with their
        // attributes in a lossy mode take --qp's bits (12 unless given);
        // with a size, a rate or an error bound they are coded at their
        // share, attributes and all.
        attributes_qp: crate::bits(qp.unwrap_or(12)),
        lossy_attributes: size.is_some() || bpv.is_some() || max_error.is_some(),
        fallback,
        format,
        limits,
    };
    let (encoded, input_bytes) = with_document(
        py,
        data,
        path.as_deref(),
        base.as_deref(),
        &limits,
        |bytes, base| {
            let encoded = swm::io::encode_scene(bytes, base, &options)?;
            Ok((encoded, bytes.len()))
        },
    )?;
    let bytes = PyBytes::new(py, &encoded.bytes);
    if !report {
        return Ok(bytes.into_any());
    }
    let r = &encoded.report;
    let primitives = PyList::empty(py);
    for p in &r.primitives {
        let d = PyDict::new(py);
        d.set_item("mesh", p.mesh)?;
        d.set_item("primitive", p.primitive)?;
        d.set_item("name", p.name.as_deref())?;
        match &p.outcome {
            PrimitiveOutcome::Coded(c) => {
                d.set_item("coded", true)?;
                d.set_item("method", c.method.name())?;
                d.set_item("bytes", c.bytes)?;
                d.set_item("share", c.share)?;
                d.set_item("input_vertices", c.input_vertices)?;
                d.set_item("input_triangles", c.input_triangles)?;
                d.set_item("vertices", c.vertices)?;
                d.set_item("triangles", c.triangles)?;
                d.set_item("attributes", &c.attributes)?;
            }
            PrimitiveOutcome::Uncoded(u) => {
                d.set_item("coded", false)?;
                d.set_item("kept_because", u.to_string())?;
            }
        }
        primitives.append(d)?;
    }
    let uncompressed: Vec<String> = r
        .uncoded()
        .map(|(p, u)| format!("{} ({u})", p.label()))
        .collect();
    let out = PyDict::new(py);
    out.set_item("bytes", encoded.bytes.len())?;
    out.set_item("input_bytes", input_bytes)?;
    out.set_item("swm_bytes", r.coded_bytes())?;
    out.set_item("requested", r.requested)?;
    out.set_item("primitives", primitives)?;
    out.set_item("uncompressed", uncompressed)?;
    out.set_item("unknown_extensions", &r.unknown_extensions)?;
    (bytes, out).into_pyobject(py).map(Bound::into_any)
}

/// Expands every primitive of a document coded in `SWM_mesh_compression`
/// (with `report`, `(bytes, dict)`).
#[pyfunction]
#[pyo3(signature = (data=None, *, path=None, base=None, format="glb", limits=None, report=false))]
pub fn decode_scene<'py>(
    py: Python<'py>,
    data: Option<&[u8]>,
    path: Option<PathBuf>,
    base: Option<PathBuf>,
    format: &str,
    limits: Option<PyRef<'py, Limits>>,
    report: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let format = format_of(format)?;
    let limits = Limits::to_swm(limits.as_deref());
    let options = swm::DecodeOptions {
        limits,
        ..swm::DecodeOptions::plain()
    };
    let decoded = with_document(
        py,
        data,
        path.as_deref(),
        base.as_deref(),
        &limits,
        |bytes, base| swm::io::decode_scene(bytes, base, &options, format),
    )?;
    let bytes = PyBytes::new(py, &decoded.bytes);
    if !report {
        return Ok(bytes.into_any());
    }
    let out = PyDict::new(py);
    out.set_item("bytes", decoded.bytes.len())?;
    out.set_item("primitives", decoded.primitives)?;
    out.set_item("decoded_vertices", decoded.vertices)?;
    out.set_item("decoded_triangles", decoded.triangles)?;
    (bytes, out).into_pyobject(py).map(Bound::into_any)
}

/// The primitives of a glTF document, coded or not, from its JSON alone.
#[pyfunction]
#[pyo3(signature = (data=None, *, path=None, base=None, limits=None))]
pub fn scene_info<'py>(
    py: Python<'py>,
    data: Option<&[u8]>,
    path: Option<PathBuf>,
    base: Option<PathBuf>,
    limits: Option<PyRef<'py, Limits>>,
) -> PyResult<Bound<'py, PyList>> {
    let limits = Limits::to_swm(limits.as_deref());
    let primitives = with_document(
        py,
        data,
        path.as_deref(),
        base.as_deref(),
        &limits,
        |bytes, base| swm::io::scene_info(bytes, base, &limits),
    )?;
    let out = PyList::empty(py);
    for p in primitives {
        let d = PyDict::new(py);
        d.set_item("mesh", p.mesh)?;
        d.set_item("primitive", p.primitive)?;
        d.set_item("name", p.name)?;
        d.set_item("swm_bytes", p.swm_bytes)?;
        d.set_item("vertices", p.vertices)?;
        d.set_item("triangles", p.triangles)?;
        d.set_item("attributes", p.attributes)?;
        out.append(d)?;
    }
    Ok(out)
}
