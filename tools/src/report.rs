//! Statistics as JSON, and the one-line summaries, shared by the
//! subcommands.

use serde_json::{json, Value};

/// Prints `v` as indented JSON on stdout (`--json` of every subcommand).
pub fn print_json(v: &Value) {
    say!(
        "{}",
        serde_json::to_string_pretty(v).expect("JSON of numbers")
    );
}

/// The line `decode` and `sharpen` print for a mesh they wrote.
pub fn print_written(
    input: &std::path::Path,
    output: &std::path::Path,
    mesh: &swm::TriMesh,
    seconds: f64,
) {
    say!(
        "{} -> {}: {} vertices, {} triangles, {:.3} s",
        input.display(),
        output.display(),
        mesh.vertex_count(),
        mesh.face_count(),
        seconds
    );
}

/// Each section's tag, bytes and bits per triangle (`t` triangles).
fn sections_json(sections: &[([u8; 4], usize)], t: f64) -> Vec<Value> {
    sections
        .iter()
        .map(|(tag, bytes)| {
            json!({
                "tag": String::from_utf8_lossy(tag),
                "bytes": bytes,
                "bits_per_triangle": 8.0 * *bytes as f64 / t,
            })
        })
        .collect()
}

/// The figures of a lossless-mode file.
pub fn lossless_json(s: &swm::LosslessStats, qp: u8) -> Value {
    let t = s.triangles.max(1) as f64;
    let sections = sections_json(&s.sections, t);
    let [c, l, e, r, s_] = s.clers;
    json!({
        "mode": "lossless",
        "qp": qp,
        "bytes": s.file_bytes,
        "vertices": s.vertices,
        "triangles": s.triangles,
        "components": s.components,
        "holes": s.holes,
        "handle_events": s.handle_events,
        "bits_per_triangle": 8.0 * s.file_bytes as f64 / t,
        "bits_per_vertex": 8.0 * s.file_bytes as f64 / s.vertices.max(1) as f64,
        "clers": { "C": c, "L": l, "E": e, "R": r, "S": s_ },
        "sections": sections,
        "attributes": s.attributes.iter().map(|a| json!({
            "kind": attribute_name(a.kind),
            "dims": a.dims,
            "bits": a.bits,
            "bytes": a.bytes,
        })).collect::<Vec<_>>(),
    })
}

/// An attribute stream's kind in words: "normals", "texture coordinates
/// 0", "colours 0", "generic 3".
pub fn attribute_name(kind: swm::AttributeKind) -> String {
    match kind {
        swm::AttributeKind::Normal => "normals".into(),
        swm::AttributeKind::TexCoord(n) => format!("texture coordinates {n}"),
        swm::AttributeKind::Color(n) => format!("colours {n}"),
        swm::AttributeKind::Generic(n) => format!("generic {n}"),
        _ => "unknown".into(),
    }
}

/// `--json`'s `attribute_report` (beside the lossless figures' `attributes`,
/// one entry per coded stream): what the file kept of the input's streams,
/// what it dropped and why, and the texture coordinates' error.
pub fn attributes_json(a: &swm::AttributeReport) -> Value {
    let names =
        |ks: &[swm::AttributeKind]| ks.iter().map(|&k| attribute_name(k)).collect::<Vec<_>>();
    serde_json::json!({
        "kept": names(&a.kept),
        "dropped": names(&a.dropped),
        "dropped_because": a.dropped_because.map(|d| d.to_string()),
        "texcoord_error": a.texcoord_error.map(|e| serde_json::json!({
            "rms_texels": e.rms_texels,
            "max_texels": e.max_texels,
            "texture_size": e.texture_size,
            "samples": e.samples,
        })),
    })
}

/// The report's line for the attributes a lossy file kept.
pub fn attributes_line(a: &swm::AttributeReport) -> String {
    let kept: Vec<String> = a.kept.iter().map(|&k| attribute_name(k)).collect();
    let mut line = match kept.is_empty() {
        true => "attributes kept: none".to_string(),
        false => format!("attributes kept: {}", kept.join(", ")),
    };
    match a.dropped_because {
        Some(why @ swm::AttributesDropped::SmoothNormals { .. }) => line.push_str(&format!(
            "; normals not coded: {why} (--keep-normals codes them)"
        )),
        Some(why @ swm::AttributesDropped::CostlyNormals { .. }) => line.push_str(&format!(
            "; normals not kept: {why} (--keep-normals keeps them)"
        )),
        Some(why @ swm::AttributesDropped::NoRoom { .. }) => {
            let names: Vec<String> = a.dropped.iter().map(|&k| attribute_name(k)).collect();
            line.push_str(&format!("; {} not kept: {why}", names.join(", ")))
        }
        _ => {}
    }
    if let Some(e) = a.texcoord_error {
        line.push_str(&format!(
            "; texture coordinates within {:.2} texels RMS, {:.1} at most, of a {} texture",
            e.rms_texels, e.max_texels, e.texture_size
        ));
    }
    line
}

/// The figures of a SwingWrapper file.
pub fn swing_json(s: &swm::SwingStats) -> Value {
    let t = s.triangles.max(1) as f64;
    let sections = sections_json(&s.sections, t);
    let [c, l, e, r, s_] = s.clers;
    json!({
        "mode": "swing",
        "edge_length": s.edge_length,
        "angle_bits": s.angle_bits,
        "predicted_angle_code": s.predicted_code,
        "bytes": s.file_bytes,
        "vertices": s.vertices,
        "triangles": s.triangles,
        "components": s.components,
        "handle_events": s.handle_events,
        "bits_per_triangle": 8.0 * s.file_bytes as f64 / t,
        "bits_per_vertex": 8.0 * s.file_bytes as f64 / s.vertices.max(1) as f64,
        "connectivity_bits_per_triangle": s.connectivity_bits_per_triangle,
        "geometry_bits_per_triangle": s.geometry_bits_per_triangle,
        "bits_per_angle": s.bits_per_angle,
        "cr_share": s.cr_share,
        "valence6_share": s.valence6_share,
        "holes": {
            "masked_triangles": s.holes_masked_triangles,
            "masked_share": s.masked_share(),
            "bytes": s.hole_bytes,
            "file_share": s.hole_bytes as f64 / s.file_bytes.max(1) as f64,
        },
        "loops": (s.loops > 0).then(|| json!({
            "count": s.loops,
            "points": s.loop_points,
            // One fan triangle per loop point.
            "fan_triangles": s.loop_points,
            "bytes": s.loop_bytes,
            "file_share": s.loop_bytes as f64 / s.file_bytes.max(1) as f64,
        })),
        "rest": { "triangles": s.rest_triangles, "components": s.rest_components, "bytes": s.rest_bytes },
        "density": s.density_levels.map(|(lo, hi)| json!({
            "min_level": lo,
            "max_level": hi,
            "bytes": s.density_bytes,
        })),
        "clers": { "C": c, "L": l, "E": e, "R": r, "S": s_ },
        "sections": sections,
    })
}

/// How the SwingWrapper encoder chose its edge length.
pub fn rate_json(r: &swm::RateReport) -> Value {
    let attempts: Vec<Value> = r
        .attempts
        .iter()
        .map(|a| match &a.outcome {
            Ok(bytes) => json!({ "edge_length": a.edge_length, "bytes": bytes }),
            Err(why) => json!({ "edge_length": a.edge_length, "failed": why.to_string() }),
        })
        .collect();
    json!({
        "requested_bytes": r.requested_bytes,
        "edge_length": r.edge_length,
        "reduced": r.reduced,
        "within_tolerance": r.within_tolerance,
        "work": r.work,
        "peak_memory_bytes": r.peak_memory_bytes,
        "attempts": attempts,
    })
}

/// What cleaning changed.
pub fn clean_json(r: &swm::CleanReport) -> Value {
    json!({
        "merged_vertices": r.merged_vertices,
        "unreferenced_vertices": r.unreferenced_vertices,
        "repeated_index_faces": r.repeated_index_faces,
        "zero_area_faces": r.zero_area_faces,
        "duplicate_faces": r.duplicate_faces,
        "flipped_faces": r.flipped_faces,
        "non_manifold_edges": r.non_manifold_edges,
        "non_manifold_vertices": r.non_manifold_vertices,
    })
}

/// The automatic mode's choice: the method written, and each candidate
/// under its method's name: its size and measured L2 (relative to the
/// diagonal), or `null` and, under `<name>_failure`, why it made none.
/// `candidates` lists them in the chooser's order.
pub fn choice_json(stats: &swm::EncodeStats, effort: swm::Effort) -> Value {
    let mut out = serde_json::json!({
        "chosen": stats.chosen().name(),
        "effort": effort.name(),
    });
    let mut list = Vec::new();
    for c in &stats.candidates {
        let name = c.method.name();
        let (figure, failure) = match &c.outcome {
            Ok(m) => (
                serde_json::json!({"bytes": m.bytes, "l2_rel": m.l2_relative}),
                Value::Null,
            ),
            Err(f) => (Value::Null, Value::String(f.to_string())),
        };
        out[name] = figure.clone();
        out[format!("{name}_failure")] = failure.clone();
        list.push(serde_json::json!({"method": name, "file": figure, "failure": failure}));
    }
    out["candidates"] = Value::Array(list);
    out
}

/// Why a retiled file decodes to other counts than its own, from what it
/// holds: " (the retiled triangles less N over holes, ..., as the file's
/// hint asks)", naming only what applies; empty when nothing does.
pub fn decoded_counts_why(s: &swm::SwingStats, hint: Option<swm::PostProcessing>) -> String {
    let mut parts = Vec::new();
    if s.holes_masked_triangles > 0 {
        parts.push(format!(
            "less {} masked over holes",
            s.holes_masked_triangles
        ));
    }
    if s.loop_points > 0 {
        parts.push(format!(
            "less the {} of the boundary loops' fans",
            s.loop_points
        ));
    }
    if s.rest_triangles > 0 {
        parts.push(format!("plus {} of the lossless rest", s.rest_triangles));
    }
    match hint {
        Some(h) if h.bend_steps > 0 => parts.push(format!(
            "after EdgeSharpener and {} Bender step{}, as the file's hint asks",
            h.bend_steps,
            if h.bend_steps == 1 { "" } else { "s" }
        )),
        Some(h) if h.sharpen => parts.push("after EdgeSharpener, as the file's hint asks".into()),
        _ => {}
    }
    if parts.is_empty() {
        String::new()
    } else {
        format!(" (the retiled triangles {})", parts.join(", "))
    }
}

/// One line: which method the automatic mode wrote, and what each
/// candidate measured (or why it made no file), errors in the unit used
/// throughout: x 1e-4 of the diagonal. A file more than 3% short of the
/// `requested` size says so, with the size asked for.
pub fn choice_line(
    stats: &swm::EncodeStats,
    effort: swm::Effort,
    requested: Option<u64>,
) -> String {
    let parts: Vec<String> = stats
        .candidates
        .iter()
        .filter(|c| !matches!(c.outcome, Err(swm::CandidateFailure::NotApplicable)))
        .map(|c| {
            let what = match &c.outcome {
                Ok(m) => {
                    let short = requested
                        .filter(|&r| m.bytes * 100 < r * 97)
                        .map(|r| format!(", short of the {r} asked: the largest file this method made within it"))
                        .unwrap_or_default();
                    match m.l2_relative {
                        Some(l2) => format!("L2 {:.3} at {} bytes{short}", 1e4 * l2, m.bytes),
                        None => format!("{} bytes, not measured{short}", m.bytes),
                    }
                }
                Err(f) => format!("none: {f}"),
            };
            format!("{} {what}", c.method.name())
        })
        .collect();
    format!(
        "method: {} (effort {}; L2 x 1e-4 of the diagonal: {})",
        stats.chosen().name(),
        effort.name(),
        parts.join("; ")
    )
}
