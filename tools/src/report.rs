//! Statistics as JSON, shared by the subcommands.

use serde_json::{json, Value};

/// Prints `v` as indented JSON on stdout (`--json` of every subcommand).
pub fn print_json(v: &Value) {
    say!(
        "{}",
        serde_json::to_string_pretty(v).expect("JSON of numbers")
    );
}

/// The figures of a lossless-mode file.
pub fn lossless_json(s: &swm::LosslessStats, qp: u8) -> Value {
    let t = s.triangles.max(1) as f64;
    let sections: Vec<Value> = s
        .sections
        .iter()
        .map(|(tag, bytes)| {
            json!({
                "tag": String::from_utf8_lossy(tag),
                "bytes": bytes,
                "bits_per_triangle": 8.0 * *bytes as f64 / t,
            })
        })
        .collect();
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
