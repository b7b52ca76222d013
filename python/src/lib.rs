//! `swm._swm`: the Python extension module over the `swm` library.
//!
//! Each function here is one library call: arrays are copied into a
//! `TriMesh` while the GIL is held, then the GIL is released
//! (`Python::detach`, PyO3's name for `allow_threads` since 0.26) for the
//! work itself, so other Python threads run while a mesh encodes. The
//! public, documented face is `swm/__init__.py`, which normalizes NumPy
//! inputs (dtype, shape, contiguity) before calling in here.
//!
//! Defaults are those of the `swm` command line, so that the same input
//! and options give the same bytes as `swm encode`.

mod arrays;
mod attributes;
mod errors;
mod file_info;
mod scene;

use errors::IntoPyResult;
use numpy::PyReadonlyArray2;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use std::path::PathBuf;

/// Caps on what decoding or reading an untrusted file may allocate
/// (`swm::Limits`); the defaults suit a desktop machine.
#[pyclass(frozen, module = "swm", eq)]
#[derive(Clone, PartialEq)]
struct Limits {
    /// Largest vertex count accepted.
    #[pyo3(get)]
    max_vertices: u64,
    /// Largest triangle count accepted.
    #[pyo3(get)]
    max_faces: u64,
    /// Largest allocation in bytes.
    #[pyo3(get)]
    max_alloc_bytes: u64,
}

#[pymethods]
impl Limits {
    #[new]
    #[pyo3(signature = (*, max_vertices=None, max_faces=None, max_alloc_bytes=None))]
    fn new(
        max_vertices: Option<u64>,
        max_faces: Option<u64>,
        max_alloc_bytes: Option<u64>,
    ) -> Self {
        let d = swm::Limits::default();
        Limits {
            max_vertices: max_vertices.unwrap_or(d.max_vertices),
            max_faces: max_faces.unwrap_or(d.max_faces),
            max_alloc_bytes: max_alloc_bytes.unwrap_or(d.max_alloc_bytes),
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "Limits(max_vertices={}, max_faces={}, max_alloc_bytes={})",
            self.max_vertices, self.max_faces, self.max_alloc_bytes
        )
    }
}

impl Limits {
    fn to_swm(limits: Option<&Limits>) -> swm::Limits {
        limits.map_or_else(swm::Limits::default, |l| swm::Limits {
            max_vertices: l.max_vertices,
            max_faces: l.max_faces,
            max_alloc_bytes: l.max_alloc_bytes,
            ..swm::Limits::default()
        })
    }
}

/// A positive count given as a Python int: negative values are the
/// library's out-of-range error, as a zero would be.
fn count(name: &'static str, value: i128) -> Result<u64, swm::Error> {
    u64::try_from(value).map_err(|_| {
        swm::ParameterError::OutOfRange {
            name,
            value: value as f64,
            min: 0.0,
            max: f64::MAX,
        }
        .into()
    })
}

/// A bit count as `u8`. A value beyond `u8` is passed as the nearest end
/// so that the library still names the option and its range, and the
/// error is then given the value the caller wrote.
fn bits(value: i64) -> u8 {
    value.clamp(0, u8::MAX as i64) as u8
}

/// Puts the caller's value back into an out-of-range error about `name`.
fn with_value(e: swm::Error, name: &str, value: i64) -> swm::Error {
    match e {
        swm::Error::Parameter(swm::ParameterError::OutOfRange {
            name: n, min, max, ..
        }) if n == name => swm::ParameterError::OutOfRange {
            name: n,
            value: value as f64,
            min,
            max,
        }
        .into(),
        e => e,
    }
}

/// The attribute quantization of `qn`, `qt` and `qg`, with the
/// defaults of `swm encode` (`swm::AttributeQuantization::default()`:
/// 8, 10 and 8) and its ranges, checked whether or not the mesh has a
/// stream of the kind (as the command line's parser checks them): normals
/// 4..=16 bits per octahedral coordinate, texture coordinates and
/// colours or generic components 2..=24. `qg` sets colours and generic
/// streams alike, as Draco's `-qg` and `swm encode --qg` do.
fn quantization(
    qn: Option<i64>,
    qt: Option<i64>,
    qg: Option<i64>,
) -> Result<swm::AttributeQuantization, swm::Error> {
    /// `value` if in `min..=max`, `default` without one.
    fn check(
        name: &'static str,
        value: Option<i64>,
        default: u8,
        (min, max): (u8, u8),
    ) -> Result<u8, swm::Error> {
        match value {
            None => Ok(default),
            Some(v) if (i64::from(min)..=i64::from(max)).contains(&v) => Ok(v as u8),
            Some(v) => Err(swm::ParameterError::OutOfRange {
                name,
                value: v as f64,
                min: min.into(),
                max: max.into(),
            }
            .into()),
        }
    }
    let d = swm::AttributeQuantization::default();
    let qg = check("qg", qg, d.color_bits, (2, 24))?;
    Ok(swm::AttributeQuantization {
        normal_bits: check("qn", qn, d.normal_bits, (4, 16))?,
        texcoord_bits: check("qt", qt, d.texcoord_bits, (2, 24))?,
        color_bits: qg,
        generic_bits: qg,
    })
}

/// `effort` by its name in `swm encode --effort`.
fn effort_of(effort: &str) -> PyResult<swm::Effort> {
    match effort {
        "fast" => Ok(swm::Effort::Fast),
        "default" => Ok(swm::Effort::Default),
        "max" => Ok(swm::Effort::Max),
        other => Err(PyValueError::new_err(format!(
            "effort must be \"fast\", \"default\" or \"max\", got {other:?}"
        ))),
    }
}

/// The `EncodeMode` for the options of `swm.encode`, with the rules of
/// `swm encode`: options the chosen mode has no use for are refused (a
/// `ValueError` naming them), not ignored.
#[allow(clippy::too_many_arguments)]
fn encode_mode(
    py: Python<'_>,
    bpv: Option<f64>,
    size: Option<i128>,
    edge_length: Option<f64>,
    mode: &str,
    max_size: Option<i128>,
    angle_bits: Option<i64>,
    qp: Option<i64>,
    max_error: Option<f64>,
    texcoord_bits: bool,
) -> PyResult<swm::EncodeMode> {
    if !matches!(mode, "auto" | "swing" | "displaced" | "lossless") {
        return Err(PyValueError::new_err(format!(
            "mode must be \"auto\", \"swing\", \"displaced\" or \"lossless\", got {mode:?}"
        )));
    }
    let refuse = |given: bool, message: &str| -> PyResult<()> {
        match given {
            true => Err(PyValueError::new_err(format!("mode=\"{mode}\" {message}"))),
            false => Ok(()),
        }
    };
    let targets = [
        bpv.is_some(),
        size.is_some(),
        edge_length.is_some(),
        max_error.is_some(),
    ];
    if targets.iter().filter(|&&t| t).count() > 1 {
        return Err(PyValueError::new_err(
            "give at most one of bpv, size, edge_length and max_error",
        ));
    }
    let sized = size.is_some() || bpv.is_some() || max_error.is_some();
    match mode {
        "auto" => {
            refuse(
                angle_bits.is_some(),
                "takes no angle_bits: the encoder chooses them (set them with mode=\"swing\")",
            )?;
            refuse(
                qp.is_some(),
                "takes no qp: the encoder chooses it \
                 (set it with mode=\"lossless\" and no size or bpv)",
            )?;
        }
        // Files that carry all streams but texture coordinates.
        "swing" | "displaced" => {
            refuse(qp.is_some(), "takes no qp (it is for mode=\"lossless\")")?;
            refuse(
                texcoord_bits,
                &format!(
                    "takes no qt: a {mode} file carries no texture coordinates \
                     (qt is for mode=\"auto\" or \"lossless\")"
                ),
            )?;
            refuse(
                max_error.is_some(),
                "takes no max_error (it is for mode=\"auto\" or \"lossless\")",
            )?;
            if mode == "displaced" {
                refuse(
                    angle_bits.is_some(),
                    "takes no angle_bits (they are for mode=\"swing\")",
                )?;
                refuse(
                    edge_length.is_some(),
                    "takes no edge_length (it is for mode=\"swing\" or \"auto\"): give size or bpv",
                )?;
            }
        }
        _ => {
            refuse(
                edge_length.is_some(),
                "takes no edge_length (size or bpv simplify the mesh to a size; \
                 edge_length is for mode=\"swing\" or \"auto\")",
            )?;
            refuse(
                angle_bits.is_some(),
                "takes no angle_bits (they are for mode=\"swing\")",
            )?;
            refuse(
                qp.is_some() && sized,
                "takes no qp with size or bpv: the encoder chooses it \
                 (give qp without a size for a file of all the input's triangles)",
            )?;
            refuse(
                max_size.is_some() && !sized,
                "takes max_size only with size or bpv",
            )?;
        }
    }
    let target = match (bpv, size, edge_length) {
        (_, Some(b), _) => swm::SwingTarget::Bytes(count("size", b).py_err(py)?),
        (_, _, Some(l)) => swm::SwingTarget::EdgeLength(l),
        _ if max_error.is_some() => {
            swm::SwingTarget::MaxError(swm::ErrorBound::Relative(max_error.unwrap_or(f64::NAN)))
        }
        // `swm encode`'s default target: 2 bits per input vertex.
        (bpv, _, _) => swm::SwingTarget::BitsPerVertex(bpv.unwrap_or(2.0)),
    };
    let max_bytes = match max_size {
        Some(m) => Some(count("max size", m).py_err(py)?),
        None => None,
    };
    Ok(match mode {
        "auto" => swm::EncodeMode::Auto { target, max_bytes },
        "swing" => swm::EncodeMode::Swing {
            target,
            angle_bits: angle_bits.map(bits),
            max_bytes,
        },
        "displaced" => swm::EncodeMode::Displaced { target, max_bytes },
        // Quadric simplification to the size, then lossless.
        _ if sized => swm::EncodeMode::Simplified { target, max_bytes },
        _ => swm::EncodeMode::Lossless {
            qp: bits(qp.unwrap_or(12)),
        },
    })
}

/// What `swm.encode(..., report=True)` returns beside the bytes: the
/// method that made the file and, as `swm encode --json` reports them,
/// the automatic mode's choice and what simplification kept.
fn encode_report<'py>(
    py: Python<'py>,
    stats: &swm::EncodeStats,
    effort: swm::Effort,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("method", stats.chosen().name())?;
    if stats.candidates.is_empty() {
        out.set_item("choice", py.None())?;
    } else {
        // As `swm encode --json`'s `method` object: each candidate under
        // its method's name, and why a missing one made no file.
        let d = PyDict::new(py);
        d.set_item("chosen", stats.chosen().name())?;
        d.set_item("effort", effort.name())?;
        let list = pyo3::types::PyList::empty(py);
        for c in &stats.candidates {
            let name = c.method.name();
            let (file, failure): (Option<Bound<'py, PyDict>>, Option<String>) = match &c.outcome {
                Ok(m) => {
                    let f = PyDict::new(py);
                    f.set_item("bytes", m.bytes)?;
                    f.set_item("l2_rel", m.l2_relative)?;
                    (Some(f), None)
                }
                Err(e) => (None, Some(e.to_string())),
            };
            d.set_item(name, file.clone())?;
            d.set_item(format!("{name}_failure"), failure.clone())?;
            let entry = PyDict::new(py);
            entry.set_item("method", name)?;
            entry.set_item("file", file)?;
            entry.set_item("failure", failure)?;
            list.append(entry)?;
        }
        d.set_item("candidates", list)?;
        out.set_item("choice", d)?;
    }
    match stats.simplified() {
        Some(s) => {
            let d = PyDict::new(py);
            d.set_item("input_faces", s.input_faces)?;
            d.set_item("faces", s.faces)?;
            d.set_item("qp", s.qp)?;
            out.set_item("simplified", d)?;
        }
        None => out.set_item("simplified", py.None())?,
    }
    out.set_item("attributes", attribute_report(py, &stats.attributes)?)?;
    match &stats.smallest_instead {
        Some(e) => {
            let d = PyDict::new(py);
            d.set_item("requested", e.requested)?;
            d.set_item("smallest", e.smallest)?;
            out.set_item("smallest_instead", d)?;
        }
        None => out.set_item("smallest_instead", py.None())?,
    }
    // As `swm encode --json`'s `check`: the file decoded and measured
    // against the input as `swm distance` measures it.
    match &stats.check {
        Some(c) => {
            let d = PyDict::new(py);
            d.set_item("decoded_vertices", c.decoded_vertices)?;
            d.set_item("decoded_triangles", c.decoded_triangles)?;
            d.set_item("area_ratio", c.area_ratio)?;
            d.set_item("l2_relative", c.l2_relative)?;
            d.set_item("hausdorff_relative", c.hausdorff_relative)?;
            d.set_item("samples", c.samples)?;
            out.set_item("check", d)?;
        }
        None => out.set_item("check", py.None())?,
    }
    Ok(out)
}

/// The report's `attributes` (`swm::AttributeReport`, `swm encode
/// --json`'s `attribute_report`): the streams kept and dropped under the
/// keys of the `attributes` dict (`"uv"`, `"normals"`, ...), why some
/// were dropped, and the decoded texture coordinates' error.
fn attribute_report<'py>(
    py: Python<'py>,
    a: &swm::AttributeReport,
) -> PyResult<Bound<'py, PyDict>> {
    let names = |kinds: &[swm::AttributeKind]| -> Vec<String> {
        kinds.iter().map(|&k| attributes::name(k)).collect()
    };
    let out = PyDict::new(py);
    out.set_item("kept", names(&a.kept))?;
    out.set_item("dropped", names(&a.dropped))?;
    match a.dropped_because {
        Some(why) => {
            let d = PyDict::new(py);
            // The reason as a word to match on, its figure, and the
            // library's sentence.
            match why {
                swm::AttributesDropped::SmoothNormals { rms_degrees } => {
                    d.set_item("reason", "smooth_normals")?;
                    d.set_item("rms_degrees", rms_degrees)?;
                }
                swm::AttributesDropped::CostlyNormals {
                    rms_degrees,
                    l2_kept,
                } => {
                    d.set_item("reason", "costly_normals")?;
                    d.set_item("rms_degrees", rms_degrees)?;
                    d.set_item("l2_kept", l2_kept)?;
                }
                swm::AttributesDropped::NoRoom { smallest } => {
                    d.set_item("reason", "no_room")?;
                    d.set_item("smallest", smallest)?;
                }
                swm::AttributesDropped::Method(m) => {
                    d.set_item("reason", "method")?;
                    d.set_item("method", m.name())?;
                }
                // `AttributesDropped` is non-exhaustive: a reason this
                // binding does not know yet still has its sentence.
                _ => d.set_item("reason", "other")?,
            }
            d.set_item("message", why.to_string())?;
            out.set_item("dropped_because", d)?;
        }
        None => out.set_item("dropped_because", py.None())?,
    }
    match a.texcoord_error {
        Some(e) => {
            let d = PyDict::new(py);
            d.set_item("rms_texels", e.rms_texels)?;
            d.set_item("max_texels", e.max_texels)?;
            d.set_item("texture_size", e.texture_size)?;
            d.set_item("samples", e.samples)?;
            out.set_item("texcoord_error", d)?;
        }
        None => out.set_item("texcoord_error", py.None())?,
    }
    Ok(out)
}

/// Encodes a mesh into `.swm` bytes (with `report`, `(bytes, dict)`).
/// See `swm/__init__.py` for the documented wrapper.
#[pyfunction]
#[pyo3(signature = (vertices, faces, *, bpv=None, size=None, edge_length=None,
                    mode="auto", max_size=None, angle_bits=None, qp=None, report=false,
                    effort="default", max_error=None, attributes=None, qn=None, qt=None,
                    qg=None, keep_normals=false, or_smallest=false))]
#[allow(clippy::too_many_arguments)]
fn encode<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f32>,
    faces: PyReadonlyArray2<'py, u32>,
    bpv: Option<f64>,
    size: Option<i128>,
    edge_length: Option<f64>,
    mode: &str,
    max_size: Option<i128>,
    angle_bits: Option<i64>,
    qp: Option<i64>,
    report: bool,
    effort: &str,
    max_error: Option<f64>,
    attributes: Option<Bound<'py, PyDict>>,
    qn: Option<i64>,
    qt: Option<i64>,
    qg: Option<i64>,
    keep_normals: bool,
    or_smallest: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let effort = effort_of(effort)?;
    // Out-of-range bits first, as the command line's parser refuses them
    // before it looks at the mode.
    let attribute_bits = quantization(qn, qt, qg).py_err(py)?;
    // Texture coordinates' bits: the one attribute option a swing or
    // displaced file has no use for (it carries all streams but them).
    let texcoord_bits = qt.is_some();
    let mode = encode_mode(
        py,
        bpv,
        size,
        edge_length,
        mode,
        max_size,
        angle_bits,
        qp,
        max_error,
        texcoord_bits,
    )?;
    let mesh = arrays::mesh(&vertices, &faces)?;
    // `Some` even when empty: a dict asks for `encode_attributed`,
    // which with no streams writes `encode`'s bytes.
    let streams = match &attributes {
        Some(dict) => Some(attributes::from_dict(dict, &mesh)?),
        None => None,
    };
    // The lossless, automatic and simplified modes code every attribute
    // (the automatic mode weighs only methods whose files carry them); a
    // retiled or displaced file carries all but texture coordinates, which
    // the library would drop: refused here rather than lost silently.
    let uvs = (streams.iter().flatten()).any(|s| matches!(s.kind, swm::AttributeKind::TexCoord(_)));
    if uvs
        && matches!(
            mode,
            swm::EncodeMode::Swing { .. } | swm::EncodeMode::Displaced { .. }
        )
    {
        return Err(PyValueError::new_err(
            "texture coordinates are coded by mode=\"auto\" or \"lossless\"; a swing or displaced file cannot carry them",
        ));
    }
    let options = swm::EncodeOptions {
        mode,
        effort,
        attributes: attribute_bits,
        keep_smooth_normals: keep_normals,
        or_smallest,
        ..Default::default()
    };
    let encoded = py
        .detach(|| match streams {
            Some(s) => swm::encode_attributed(&swm::AttributedMesh::new(mesh, s), &options),
            None => swm::encode(&mesh, &options),
        })
        .map_err(|e| {
            let e = with_value(e, "angle bits", angle_bits.unwrap_or(0));
            with_value(e, "qp", qp.unwrap_or(12))
        })
        .py_err(py)?;
    let bytes = PyBytes::new(py, &encoded.bytes);
    if report {
        (bytes, encode_report(py, &encoded.stats, effort)?)
            .into_pyobject(py)
            .map(Bound::into_any)
    } else {
        Ok(bytes.into_any())
    }
}

/// Decodes `.swm` bytes: `(vertices, faces)`, then `normals` with
/// `normals`, then a dict of per-vertex attribute arrays with
/// `attributes` (the split form; see `attributes.rs`). `max_level`: the
/// most subdivision levels of a displaced (mode 2) file to decode, 0 its
/// base mesh (default: every level; other modes ignore it).
#[pyfunction]
#[pyo3(signature = (data, *, sharpen=None, bend=None, normals=false, limits=None, max_level=None,
                    attributes=false))]
#[allow(clippy::too_many_arguments)]
fn decode<'py>(
    py: Python<'py>,
    data: &[u8],
    sharpen: Option<bool>,
    bend: Option<u32>,
    normals: bool,
    limits: Option<PyRef<'py, Limits>>,
    max_level: Option<u8>,
    attributes: bool,
) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
    let options = swm::DecodeOptions {
        limits: Limits::to_swm(limits.as_deref()),
        // None: as the file's post-processing hint says.
        sharpen,
        bend_steps: bend,
        max_level,
    };
    let (mesh, streams, n) = py
        .detach(|| {
            let (mesh, streams) = if attributes {
                let decoded = swm::decode_attributed(data, &options)?;
                // Without streams the split is the identity: skip its sort.
                let decoded = match decoded.streams.is_empty() {
                    true => decoded,
                    false => decoded.split_vertices(),
                };
                (decoded.mesh, decoded.streams)
            } else {
                (swm::decode(data, &options)?, Vec::new())
            };
            let n = normals.then(|| swm::vertex_normals(&mesh));
            Ok::<_, swm::Error>((mesh, streams, n))
        })
        .py_err(py)?;
    let mut out = vec![
        arrays::to_numpy(py, mesh.positions).into_any(),
        arrays::to_numpy(py, mesh.triangles).into_any(),
    ];
    if let Some(n) = n {
        out.push(arrays::to_numpy(py, n).into_any());
    }
    if attributes {
        out.push(attributes::to_dict(py, streams)?.into_any());
    }
    pyo3::types::PyTuple::new(py, out)
}

/// A `.swm` file's figures, the keys and values of `swm info --json`.
#[pyfunction]
#[pyo3(signature = (data, *, limits=None))]
fn info<'py>(
    py: Python<'py>,
    data: &[u8],
    limits: Option<PyRef<'py, Limits>>,
) -> PyResult<Bound<'py, PyDict>> {
    let limits = Limits::to_swm(limits.as_deref());
    let file = py.detach(|| swm::inspect(data, &limits)).py_err(py)?;
    file_info::to_dict(py, &file)
}

/// Metro distance between meshes A (the reference) and B, as
/// `swm distance --json` reports it.
#[pyfunction]
#[pyo3(signature = (a_vertices, a_faces, b_vertices, b_faces, *, samples=None, sampling="metro"))]
fn distance<'py>(
    py: Python<'py>,
    a_vertices: PyReadonlyArray2<'py, f32>,
    a_faces: PyReadonlyArray2<'py, u32>,
    b_vertices: PyReadonlyArray2<'py, f32>,
    b_faces: PyReadonlyArray2<'py, u32>,
    samples: Option<u64>,
    sampling: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let metro = match sampling {
        "metro" => true,
        "faces" => false,
        other => {
            return Err(PyValueError::new_err(format!(
                "sampling must be \"metro\" or \"faces\", got {other:?}"
            )))
        }
    };
    if samples == Some(0) {
        return Err(PyValueError::new_err("samples must be at least 1"));
    }
    let a = arrays::mesh(&a_vertices, &a_faces)?;
    let b = arrays::mesh(&b_vertices, &b_faces)?;
    let options = swm::metrics::DistanceOptions {
        face_samples: samples,
        vertex_samples: metro,
        edge_samples: metro,
        ..Default::default()
    };
    let d = py
        .detach(|| {
            // Each mesh is checked on its own, as `swm distance` reads them.
            a.validate()?;
            b.validate()?;
            swm::metrics::distance(&a, &b, &options)
        })
        .py_err(py)?;
    let side = |s: &swm::metrics::OneSided| -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("samples", s.samples)?;
        d.set_item("mean", s.mean)?;
        d.set_item("rms", s.rms)?;
        d.set_item("max", s.max)?;
        Ok(d)
    };
    let out = PyDict::new(py);
    out.set_item("l2", d.l2())?;
    out.set_item("hausdorff", d.hausdorff())?;
    out.set_item("mean", d.mean())?;
    out.set_item("l2_relative", d.l2_relative())?;
    out.set_item("hausdorff_relative", d.hausdorff_relative())?;
    out.set_item("diagonal", d.diagonal)?;
    out.set_item("forward", side(&d.forward)?)?;
    out.set_item("backward", side(&d.backward)?)?;
    Ok(out)
}

/// Reads a mesh file (.obj, .ply, .off, .stl, .gltf, .glb) as the command
/// line does: `(vertices, faces)`, or with `attributes` `(vertices,
/// faces, dict, dropped)`, the mesh in the split form with its streams
/// (as `decode(..., attributes=True)` gives them) and the names of the
/// attributes the file carried that the reader could not attach (the
/// wrapper warns about them, as `swm encode` does on standard error).
#[pyfunction]
#[pyo3(signature = (path, *, limits=None, attributes=false))]
fn read<'py>(
    py: Python<'py>,
    path: PathBuf,
    limits: Option<PyRef<'py, Limits>>,
    attributes: bool,
) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
    let limits = Limits::to_swm(limits.as_deref());
    if !attributes {
        let mesh = py
            .detach(|| swm::io::read_mesh_with(&path, &limits))
            .py_err_file(py, &path.to_string_lossy())?;
        return (
            arrays::to_numpy(py, mesh.positions),
            arrays::to_numpy(py, mesh.triangles),
        )
            .into_pyobject(py);
    }
    let (mesh, report) = py
        .detach(|| {
            let (m, report) = swm::io::read_attributed_mesh_with(&path, None, &limits)?;
            // Without streams the split is the identity: skip its sort.
            let m = match m.streams.is_empty() {
                true => m,
                false => m.split_vertices(),
            };
            Ok::<_, swm::Error>((m, report))
        })
        .py_err_file(py, &path.to_string_lossy())?;
    let dropped: Vec<&str> = report.dropped.names().collect();
    (
        arrays::to_numpy(py, mesh.mesh.positions),
        arrays::to_numpy(py, mesh.mesh.triangles),
        attributes::to_dict(py, mesh.streams)?,
        dropped,
    )
        .into_pyobject(py)
}

/// Writes a mesh file (.obj, .ply, .off, .stl, .glb), complete or not at
/// all (the library writes a temporary file and renames it).
#[pyfunction]
fn write<'py>(
    py: Python<'py>,
    path: PathBuf,
    vertices: PyReadonlyArray2<'py, f32>,
    faces: PyReadonlyArray2<'py, u32>,
) -> PyResult<()> {
    let mesh = arrays::mesh(&vertices, &faces)?;
    py.detach(|| swm::io::write_mesh(&path, &mesh))
        .py_err_file(py, &path.to_string_lossy())
}

#[pymodule]
fn _swm(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Limits>()?;
    m.add_function(wrap_pyfunction!(encode, m)?)?;
    m.add_function(wrap_pyfunction!(decode, m)?)?;
    m.add_function(wrap_pyfunction!(info, m)?)?;
    m.add_function(wrap_pyfunction!(distance, m)?)?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_function(wrap_pyfunction!(write, m)?)?;
    m.add_function(wrap_pyfunction!(scene::encode_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene::decode_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene::scene_info, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
