//! Lossy encodes that keep attributes (issue 47, item 3), end to end on
//! spot from the shared corpus: `swm encode spot.obj` with no flags keeps
//! its texture coordinates, `swm decode` writes them as `vt` lines, every
//! decoded corner's coordinate is one of the input's at a vertex near
//! where it decodes (nothing interpolated across a chart's boundary: the
//! simplification keeps the input's values, `simplify::attributed`), the
//! texture coordinates' error is bounded, every effort level keeps them,
//! and the bytes are the same twice.

mod common;
use common::*;
use std::path::Path;

/// The input's (position, texture coordinate) corners.
fn corners(m: &swm::AttributedMesh) -> Vec<([f32; 3], [f32; 2])> {
    let uv = m.stream(swm::AttributeKind::TexCoord(0)).expect("uv");
    let mut out = Vec::new();
    for (f, t) in m.mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let q = uv.value(uv.corners[f][k]);
            out.push((m.mesh.positions[t[k] as usize], [q[0], q[1]]));
        }
    }
    out
}

/// Every decoded corner's texture coordinate is within `step` (the
/// 10-bit grid's half step over the coordinates' extent, and a little) of
/// a texture coordinate the input has at a vertex within `radius` of the
/// decoded vertex: a value of the chart it came from.
fn assert_in_charts(input: &swm::AttributedMesh, decoded: &swm::AttributedMesh, radius: f32) {
    let step = 1.0 / 1023.0;
    let known = corners(input);
    for (p, q) in corners(decoded) {
        let near = known.iter().any(|(kp, kq)| {
            let d2: f32 = (0..3).map(|k| (kp[k] - p[k]).powi(2)).sum();
            d2 <= radius * radius && (kq[0] - q[0]).abs() <= step && (kq[1] - q[1]).abs() <= step
        });
        assert!(
            near,
            "decoded corner at {p:?} has uv {q:?}: no input corner near it has it"
        );
    }
}

fn encode(spot: &Path, out: &Path, extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "encode",
        spot.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--force",
        "--json",
    ];
    args.extend(extra);
    json(&swm(&args))
}

#[test]
fn spot_keeps_its_texture_coordinates_by_default() {
    let Some(corpus) = shared_corpus() else {
        return;
    };
    let dir = scratch("lossy-attributes-spot");
    let spot = corpus.join("spot.obj");
    let (input, _) = swm::io::read_attributed_mesh_with(&spot, None, &Default::default()).unwrap();
    let diagonal = input.mesh.bbox_diagonal() as f32;

    // No flags: the default mode and rate keep the texture coordinates.
    let file = dir.join("spot.swm");
    let out = swm(&[
        "encode",
        spot.to_str().unwrap(),
        "-o",
        file.to_str().unwrap(),
    ]);
    let text = ok(&out);
    assert!(
        text.contains("attributes kept: texture coordinates 0"),
        "{text}"
    );
    assert!(
        !String::from_utf8_lossy(&out.stderr).contains("not kept"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let back = dir.join("back.obj");
    ok(&swm(&[
        "decode",
        file.to_str().unwrap(),
        "-o",
        back.to_str().unwrap(),
    ]));
    let obj = std::fs::read_to_string(&back).unwrap();
    assert!(obj.lines().any(|l| l.starts_with("vt ")), "no vt lines");
    let first = std::fs::read(&file).unwrap();

    for (effort, bpv, bound) in [
        ("fast", "8", 6.0),
        ("default", "8", 6.0),
        ("max", "8", 6.0),
        ("default", "4", 10.0),
    ] {
        let out = dir.join(format!("spot-{effort}-{bpv}.swm"));
        let v = encode(&spot, &out, &["--effort", effort, "--bpv", bpv]);
        assert_eq!(
            v["attribute_report"]["kept"],
            serde_json::json!(["texture coordinates 0"])
        );
        assert_eq!(v["attribute_report"]["dropped"], serde_json::json!([]));
        let texels = v["attribute_report"]["texcoord_error"]["rms_texels"]
            .as_f64()
            .unwrap();
        assert!(texels < bound, "{effort} {bpv} b/v: {texels} texels");
        let bytes = std::fs::read(&out).unwrap();
        let decoded = swm::decode_attributed(&bytes, &Default::default()).unwrap();
        // The refit moves a vertex by about its chord error, far below
        // 3% of the diagonal at these rates.
        assert_in_charts(&input, &decoded, 0.03 * diagonal);
    }

    // Deterministic: the same bytes again.
    ok(&swm(&[
        "encode",
        spot.to_str().unwrap(),
        "-o",
        file.to_str().unwrap(),
        "--force",
    ]));
    assert_eq!(std::fs::read(&file).unwrap(), first);
    let _ = std::fs::remove_dir_all(&dir);
}
