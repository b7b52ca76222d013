//! `swm.info(data)`: a `.swm` file's figures as a dict with the keys and
//! values of `swm info --json` (tools/src/report.rs builds that JSON from
//! the same `swm::FileInfo`; the Python tests compare the two).

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// Each section's tag, bytes and bits per triangle (`t` triangles).
fn sections<'py>(
    py: Python<'py>,
    sections: &[([u8; 4], usize)],
    t: f64,
) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for (tag, bytes) in sections {
        let d = PyDict::new(py);
        d.set_item("tag", String::from_utf8_lossy(tag))?;
        d.set_item("bytes", bytes)?;
        d.set_item("bits_per_triangle", 8.0 * *bytes as f64 / t)?;
        list.append(d)?;
    }
    Ok(list)
}

/// The CLERS histogram, by letter.
fn clers<'py>(py: Python<'py>, clers: [u64; 5]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (letter, n) in ["C", "L", "E", "R", "S"].into_iter().zip(clers) {
        d.set_item(letter, n)?;
    }
    Ok(d)
}

/// The `ATTR` streams (kind in words, as `swm info` names them; dims,
/// bits, bytes).
fn attributes<'py>(
    py: Python<'py>,
    streams: &[swm::AttributeInfo],
) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for a in streams {
        let kind = match a.kind {
            swm::AttributeKind::Normal => "normals".into(),
            swm::AttributeKind::TexCoord(n) => format!("texture coordinates {n}"),
            swm::AttributeKind::Color(n) => format!("colours {n}"),
            swm::AttributeKind::Generic(n) => format!("generic {n}"),
            _ => "unknown".into(),
        };
        let d = PyDict::new(py);
        d.set_item("kind", kind)?;
        d.set_item("dims", a.dims)?;
        d.set_item("bits", a.bits)?;
        d.set_item("bytes", a.bytes)?;
        list.append(d)?;
    }
    Ok(list)
}

/// The figures of a file, as `swm info --json` prints them.
pub fn to_dict<'py>(py: Python<'py>, info: &swm::FileInfo) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    match &info.swing {
        None => {
            let s = &info.stats;
            let t = s.triangles.max(1) as f64;
            d.set_item("mode", "lossless")?;
            d.set_item("qp", info.qp)?;
            d.set_item("bytes", s.file_bytes)?;
            d.set_item("vertices", s.vertices)?;
            d.set_item("triangles", s.triangles)?;
            d.set_item("components", s.components)?;
            d.set_item("holes", s.holes)?;
            d.set_item("handle_events", s.handle_events)?;
            d.set_item("bits_per_triangle", 8.0 * s.file_bytes as f64 / t)?;
            let v = s.vertices.max(1) as f64;
            d.set_item("bits_per_vertex", 8.0 * s.file_bytes as f64 / v)?;
            d.set_item("clers", clers(py, s.clers)?)?;
            d.set_item("sections", sections(py, &s.sections, t)?)?;
            d.set_item("attributes", attributes(py, &s.attributes)?)?;
            if info.mode == swm::Mode::Displaced {
                d.set_item("mode", "displaced")?;
                d.set_item("level_bytes", &info.levels)?;
                if let Some(x) = &info.displaced {
                    d.set_item("prediction", x.rule.name())?;
                    d.set_item("steps", &x.steps)?;
                    d.set_item("bends", &x.bends)?;
                    d.set_item("bare_base", x.bare_base)?;
                    d.set_item("base_bytes", x.base_bytes)?;
                }
            }
        }
        Some(s) => {
            let t = s.triangles.max(1) as f64;
            d.set_item("mode", "swing")?;
            d.set_item("edge_length", s.edge_length)?;
            d.set_item("angle_bits", s.angle_bits)?;
            d.set_item("predicted_angle_code", s.predicted_code)?;
            d.set_item("bytes", s.file_bytes)?;
            d.set_item("vertices", s.vertices)?;
            d.set_item("triangles", s.triangles)?;
            d.set_item("components", s.components)?;
            d.set_item("handle_events", s.handle_events)?;
            d.set_item("bits_per_triangle", 8.0 * s.file_bytes as f64 / t)?;
            let v = s.vertices.max(1) as f64;
            d.set_item("bits_per_vertex", 8.0 * s.file_bytes as f64 / v)?;
            d.set_item(
                "connectivity_bits_per_triangle",
                s.connectivity_bits_per_triangle,
            )?;
            d.set_item("geometry_bits_per_triangle", s.geometry_bits_per_triangle)?;
            d.set_item("bits_per_angle", s.bits_per_angle)?;
            d.set_item("cr_share", s.cr_share)?;
            d.set_item("valence6_share", s.valence6_share)?;
            let holes = PyDict::new(py);
            holes.set_item("masked_triangles", s.holes_masked_triangles)?;
            holes.set_item("masked_share", s.masked_share())?;
            holes.set_item("bytes", s.hole_bytes)?;
            let share = s.hole_bytes as f64 / s.file_bytes.max(1) as f64;
            holes.set_item("file_share", share)?;
            d.set_item("holes", holes)?;
            if s.loops > 0 {
                let loops = PyDict::new(py);
                loops.set_item("count", s.loops)?;
                loops.set_item("points", s.loop_points)?;
                // One fan triangle per loop point.
                loops.set_item("fan_triangles", s.loop_points)?;
                loops.set_item("bytes", s.loop_bytes)?;
                let share = s.loop_bytes as f64 / s.file_bytes.max(1) as f64;
                loops.set_item("file_share", share)?;
                d.set_item("loops", loops)?;
            } else {
                d.set_item("loops", py.None())?;
            }
            let rest = PyDict::new(py);
            rest.set_item("triangles", s.rest_triangles)?;
            rest.set_item("components", s.rest_components)?;
            rest.set_item("bytes", s.rest_bytes)?;
            d.set_item("rest", rest)?;
            match s.density_levels {
                Some((lo, hi)) => {
                    let density = PyDict::new(py);
                    density.set_item("min_level", lo)?;
                    density.set_item("max_level", hi)?;
                    density.set_item("bytes", s.density_bytes)?;
                    d.set_item("density", density)?;
                }
                None => d.set_item("density", py.None())?,
            }
            d.set_item("clers", clers(py, s.clers)?)?;
            d.set_item("sections", sections(py, &s.sections, t)?)?;
        }
    }
    let (major, minor) = info.version;
    d.set_item("version", format!("{major}.{minor}"))?;
    let framing = match info.framing {
        swm::Framing::Fixed => "fixed",
        _ => "compact",
    };
    d.set_item("framing", framing)?;
    d.set_item("frame_bytes", info.frame_bytes)?;
    // The encoder's post-processing hint (what a default decode runs).
    match info.post {
        Some(p) => {
            let post = PyDict::new(py);
            post.set_item("sharpen", p.sharpen)?;
            post.set_item("bend_steps", p.bend_steps)?;
            d.set_item("post", post)?;
        }
        None => d.set_item("post", py.None())?,
    }
    Ok(d)
}
