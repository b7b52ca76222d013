//! Golden files of the `.swm` format (format-spec/versions.md): every
//! golden file of every released version must keep decoding, forever, to
//! the mesh whose hash its page of the spec lists.
//!
//! `lossless-v1.0.swm` is specified byte by byte in
//! format-spec/04-lossless.md ("Golden file and worked example").

use swm::{DecodeOptions, EncodeMode, EncodeOptions, TriMesh};

const LOSSLESS_V1_0: &[u8] = include_bytes!("../format-spec/golden/lossless-v1.0.swm");

/// The test vector of format-spec/04-lossless.md.
const LOSSLESS_V1_0_VERTICES: usize = 48;
const LOSSLESS_V1_0_TRIANGLES: usize = 94;
const LOSSLESS_V1_0_FNV1A64: u64 = 0xEE8C_6338_75C1_F50B;

/// 64-bit FNV-1a of a mesh: every position in vertex order as three
/// little-endian `f32`s, then every triangle as three little-endian `u32`s.
fn mesh_hash(mesh: &TriMesh) -> u64 {
    let positions = mesh.positions.iter().flatten().map(|c| c.to_le_bytes());
    let triangles = mesh.triangles.iter().flatten().map(|v| v.to_le_bytes());
    positions
        .chain(triangles)
        .fold(FNV_OFFSET, |h, b| fnv1a(h, &b))
}

/// FNV-1a 64's starting value.
const FNV_OFFSET: u64 = 0xCBF2_9CE4_8422_2325;

/// FNV-1a 64 of `bytes`, continuing from `h`.
fn fnv1a(h: u64, bytes: &[u8]) -> u64 {
    bytes.iter().fold(h, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01B3)
    })
}

/// The mesh the golden file encodes: a torus grid of 8 × 6 vertices
/// (R = 1, r = 0.4) with quad (3, 2) removed, so it has a handle and a
/// hole. Cosines and sines of multiples of 45° and 60° come from `sqrt`
/// alone, which IEEE 754 rounds exactly, so every platform builds the same
/// `f32` positions.
fn golden_torus() -> TriMesh {
    let h = 0.5f64.sqrt();
    let t = 0.75f64.sqrt();
    let cos8 = [1.0, h, 0.0, -h, -1.0, -h, 0.0, h];
    let sin8 = [0.0, h, 1.0, h, 0.0, -h, -1.0, -h];
    let cos6 = [1.0, 0.5, -0.5, -1.0, -0.5, 0.5];
    let sin6 = [0.0, t, t, 0.0, -t, -t];
    let (nu, nv) = (8u32, 6u32);
    let mut positions = Vec::new();
    for i in 0..nu as usize {
        for j in 0..nv as usize {
            let rho = 1.0 + 0.4 * cos6[j];
            positions.push([
                (rho * cos8[i]) as f32,
                (rho * sin8[i]) as f32,
                (0.4 * sin6[j]) as f32,
            ]);
        }
    }
    let id = |i: u32, j: u32| (i % nu) * nv + j % nv;
    let mut triangles = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            if (i, j) == (3, 2) {
                continue;
            }
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    TriMesh::new(positions, triangles)
}

/// Must hold forever: a failure means the decoder no longer reads format
/// 1.0 as specified.
#[test]
fn lossless_v1_0_decodes_to_its_test_vector() {
    let mesh = swm::decode(LOSSLESS_V1_0, &DecodeOptions::default())
        .expect("golden file lossless-v1.0.swm must decode");
    assert_eq!(mesh.positions.len(), LOSSLESS_V1_0_VERTICES);
    assert_eq!(mesh.triangles.len(), LOSSLESS_V1_0_TRIANGLES);
    assert_eq!(
        mesh_hash(&mesh),
        LOSSLESS_V1_0_FNV1A64,
        "decoded mesh differs from format-spec/04-lossless.md's test vector"
    );
    // Spot checks from the worked example of the spec.
    assert_eq!(
        mesh.positions[0].map(f32::to_bits),
        [0x3FB3_3333, 0x39B3_3E67, 0x3986_7B95]
    );
    assert_eq!(&mesh.triangles[..3], &[[0, 1, 2], [3, 0, 2], [4, 3, 2]]);
}

/// The golden mesh's input is rebuilt here; the decoded mesh has its
/// triangles (lossless connectivity) and positions within half a step.
#[test]
fn lossless_v1_0_is_the_golden_torus() {
    let input = golden_torus();
    let mesh = swm::decode(LOSSLESS_V1_0, &DecodeOptions::default()).unwrap();
    // Every decoded position is within half a grid step (2.8 / 4095 / 2)
    // of a distinct input vertex.
    let half_step = 2.8f64 / 4095.0 / 2.0 * (1.0 + 1e-6);
    let mut used = vec![false; input.positions.len()];
    for p in &mesh.positions {
        let k = (0..input.positions.len())
            .find(|&k| {
                !used[k]
                    && (0..3)
                        .all(|a| (p[a] as f64 - input.positions[k][a] as f64).abs() <= half_step)
            })
            .expect("a decoded vertex matches no input vertex");
        used[k] = true;
    }
}

/// swm's encoder, given the same input and options, writes the golden
/// bytes again. This pins the *encoder* (its choices, e.g. of subsets and
/// start corners), not the format: if an encoder change that keeps the
/// format breaks it, the golden file stays as it is and this check is
/// what changes (compare decoded meshes instead of bytes).
#[test]
fn lossless_v1_0_reencodes_to_the_same_bytes() {
    let options = EncodeOptions {
        mode: EncodeMode::Lossless { qp: 12 },
        framing: swm::Framing::Fixed,
        ..EncodeOptions::default()
    };
    let encoded = swm::encode(&golden_torus(), &options).unwrap();
    assert_eq!(
        encoded.bytes, LOSSLESS_V1_0,
        "re-encoding the golden torus no longer gives golden/lossless-v1.0.swm"
    );
}

const LOSSLESS_COMPACT_V1_1: &[u8] =
    include_bytes!("../format-spec/golden/lossless-compact-v1.1.swm");

/// The golden torus in the compact framing (format 1.1): the same
/// sections as `lossless-v1.0.swm`, so the same mesh, in fewer bytes.
/// Must hold forever.
#[test]
fn lossless_compact_v1_1_decodes_to_the_1_0_test_vector() {
    let mesh = swm::decode(LOSSLESS_COMPACT_V1_1, &DecodeOptions::default())
        .expect("golden file lossless-compact-v1.1.swm must decode");
    assert_eq!(mesh.positions.len(), LOSSLESS_V1_0_VERTICES);
    assert_eq!(mesh.triangles.len(), LOSSLESS_V1_0_TRIANGLES);
    assert_eq!(mesh_hash(&mesh), LOSSLESS_V1_0_FNV1A64);
    assert_eq!(LOSSLESS_COMPACT_V1_1.len(), LOSSLESS_V1_0_COMPACT_LEN);
    assert_eq!(&LOSSLESS_COMPACT_V1_1[4..8], &[1, 1, 1, 0], "1.1, compact");
    let info = swm::inspect(LOSSLESS_COMPACT_V1_1, &Default::default()).unwrap();
    assert_eq!(info.framing, swm::Framing::Compact);
    assert_eq!(info.frame_bytes, 26);
}

/// Its length: the 1.0 file less 33 bytes of framing (three counts of 4
/// bytes become 1, the section count 2 → 1, four entries of 8 become 2,
/// but GEOM's, whose length needs a second varint byte, 3).
const LOSSLESS_V1_0_COMPACT_LEN: usize = 278 - 33;

/// The default encoder writes the compact golden file (see
/// `lossless_v1_0_reencodes_to_the_same_bytes` for what this pins).
#[test]
fn lossless_compact_v1_1_reencodes_to_the_same_bytes() {
    let options = EncodeOptions {
        mode: EncodeMode::Lossless { qp: 12 },
        ..EncodeOptions::default()
    };
    let encoded = swm::encode(&golden_torus(), &options).unwrap();
    assert_eq!(encoded.bytes, LOSSLESS_COMPACT_V1_1);
}

/// Writes the compact golden file (run once, by hand:
/// `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_lossless_compact_golden`).
#[test]
#[ignore]
fn write_lossless_compact_golden() {
    let options = EncodeOptions {
        mode: EncodeMode::Lossless { qp: 12 },
        ..EncodeOptions::default()
    };
    write_golden("lossless-compact-v1.1.swm", &golden_torus(), &options);
}

const SWING_V1_0: &[u8] = include_bytes!("../format-spec/golden/swing-v1.0.swm");

/// The test vector of format-spec/05-swing.md ("Golden file").
const SWING_V1_0_FNV1A64: u64 = 0x8249_F4EE_6BE4_5A0B;

/// The golden swing file's input: an icosahedron subdivided three times
/// with every vertex pushed onto the unit sphere (only `sqrt` and
/// division, which IEEE 754 rounds exactly, so every platform builds the
/// same `f32` positions). Written out here rather than taken from
/// `corpus/gen`, whose generators may change: this input is frozen with
/// the file.
fn golden_sphere() -> TriMesh {
    golden_icosphere(3)
}

/// The golden sphere's construction with `subdivisions` levels.
fn golden_icosphere(subdivisions: u32) -> TriMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut p: Vec<[f64; 3]> = vec![
        [-1., t, 0.],
        [1., t, 0.],
        [-1., -t, 0.],
        [1., -t, 0.],
        [0., -1., t],
        [0., 1., t],
        [0., -1., -t],
        [0., 1., -t],
        [t, 0., -1.],
        [t, 0., 1.],
        [-t, 0., -1.],
        [-t, 0., 1.],
    ];
    let unit = |q: [f64; 3]| {
        let n = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
        [q[0] / n, q[1] / n, q[2] / n]
    };
    for q in &mut p {
        *q = unit(*q);
    }
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut made = std::collections::HashMap::new();
        let mut next = Vec::new();
        for tri in &f {
            let m: [u32; 3] = core::array::from_fn(|k| {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                *made.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    let (pa, pb) = (p[a as usize], p[b as usize]);
                    p.push(unit([pa[0] + pb[0], pa[1] + pb[1], pa[2] + pb[2]]));
                    p.len() as u32 - 1
                })
            });
            next.extend([
                [tri[0], m[0], m[2]],
                [tri[1], m[1], m[0]],
                [tri[2], m[2], m[1]],
                m,
            ]);
        }
        f = next;
    }
    TriMesh::new(p.iter().map(|q| q.map(|c| c as f32)).collect(), f)
}

fn golden_swing_options() -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Swing {
            target: swm::SwingTarget::EdgeLength(0.25),
            angle_bits: Some(8),
            max_bytes: None,
        },
        // The golden file predates approximating tips (issue 19): it was
        // made with every tip aimed at the sphere, as the thesis places
        // them.
        swing: swm::SwingTuning {
            approximate_tips: false,
            fit_tips: false,
            adaptive_density: false,
            front_contexts: false,
            loop_start: false,
            crease_tips: false,
            post_hint: false,
        },
        // The golden files predate the compact framing (format 1.1).
        framing: swm::Framing::Fixed,
        ..EncodeOptions::default()
    }
}

/// Encodes `mesh` with `options`, writes the bytes and prints the
/// figures its spec page quotes. The file goes to `format-spec/golden/NAME`
/// only when `SWM_WRITE_GOLDEN=1` asks for it (a golden file is made once,
/// by hand); otherwise to a temporary folder, so that `cargo test --
/// --include-ignored` never rewrites the committed files (issue 48).
/// Where the `write_*` tests write: format-spec/golden with
/// `SWM_WRITE_GOLDEN=1`, else a scratch folder.
fn golden_dir() -> std::path::PathBuf {
    if std::env::var_os("SWM_WRITE_GOLDEN").is_some_and(|v| v == "1") {
        std::path::PathBuf::from(format!(
            "{}/../format-spec/golden",
            env!("CARGO_MANIFEST_DIR")
        ))
    } else {
        let dir = std::env::temp_dir().join(format!("swm-golden-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }
}

/// [`write_golden`] for a mesh with attribute streams: also prints each
/// stream's value count and the hash continued over them.
fn write_attributed_golden(name: &str, mesh: &swm::AttributedMesh, options: &EncodeOptions) {
    let encoded = swm::encode_attributed(mesh, options).unwrap();
    let decoded = swm::decode_attributed(&encoded.bytes, &DecodeOptions::default()).unwrap();
    let path = golden_dir().join(name);
    std::fs::write(&path, &encoded.bytes).unwrap();
    let info = swm::inspect(&encoded.bytes, &Default::default()).unwrap();
    let values: Vec<usize> = decoded.streams.iter().map(|s| s.value_count()).collect();
    println!("{}", path.display());
    println!(
        "{} bytes, {} vertices, {} triangles, values {values:?}, levels {:?}, sections {:?}, hash {:#018X}",
        encoded.bytes.len(),
        decoded.mesh.positions.len(),
        decoded.mesh.triangles.len(),
        info.levels,
        info.stats.sections,
        attributed_hash(&decoded)
    );
}

fn write_golden(name: &str, mesh: &TriMesh, options: &EncodeOptions) {
    let encoded = swm::encode(mesh, options).unwrap();
    let decoded = swm::decode(&encoded.bytes, &DecodeOptions::default()).unwrap();
    let path = golden_dir().join(name);
    std::fs::write(&path, &encoded.bytes).unwrap();
    println!("{}", path.display());
    println!(
        "{} bytes, {} vertices, {} triangles, hash {:#018X}",
        encoded.bytes.len(),
        decoded.positions.len(),
        decoded.triangles.len(),
        mesh_hash(&decoded)
    );
}

/// Writes the golden swing file (run once, by hand, when the file is
/// made: `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_swing_golden`).
#[test]
#[ignore]
fn write_swing_golden() {
    write_golden("swing-v1.0.swm", &golden_sphere(), &golden_swing_options());
}

/// Must hold forever: a failure means the decoder no longer reads the
/// swing mode of format 1.0 as specified.
#[test]
fn swing_v1_0_decodes_to_its_test_vector() {
    let mesh = swm::decode(SWING_V1_0, &DecodeOptions::default())
        .expect("golden file swing-v1.0.swm must decode");
    assert_eq!(
        mesh_hash(&mesh),
        SWING_V1_0_FNV1A64,
        "decoded mesh differs from format-spec/05-swing.md's test vector"
    );
    // Every vertex lies on the unit sphere up to quantization of its angle.
    for p in &mesh.positions {
        let r = p.iter().map(|&c| (c as f64).powi(2)).sum::<f64>().sqrt();
        assert!((r - 1.0).abs() < 0.02, "vertex at radius {r}");
    }
}

/// The encoder still writes the golden bytes from the golden sphere (pins
/// the encoder on this platform, not the format; see the lossless twin).
#[test]
fn swing_v1_0_reencodes_to_the_same_bytes() {
    let encoded = swm::encode(&golden_sphere(), &golden_swing_options()).unwrap();
    assert_eq!(
        encoded.bytes, SWING_V1_0,
        "re-encoding the golden sphere no longer gives golden/swing-v1.0.swm"
    );
}

// --- Format 1.1: SwingWrapper with a density (DENS) ---

const SWING_V1_1: &[u8] = include_bytes!("../format-spec/golden/swing-v1.1.swm");

/// The test vector of format-spec/05-swing.md ("Golden file", 1.1).
const SWING_V1_1_FNV1A64: u64 = 0xCCF2_F190_949E_85B4;

/// The 1.1 golden file's input: the golden sphere stretched into the
/// ellipsoid x² + (y/0.5)² + (z/0.25)² = 1 (one binary32 multiplication
/// per coordinate, exact on every platform), whose curvature varies
/// enough for the edge length to step.
fn golden_ellipsoid() -> TriMesh {
    let mut m = golden_sphere();
    for p in &mut m.positions {
        p[1] *= 0.5;
        p[2] *= 0.25;
    }
    m
}

fn golden_adaptive_options() -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Swing {
            target: swm::SwingTarget::EdgeLength(0.2),
            angle_bits: Some(8),
            max_bytes: None,
        },
        swing: swm::SwingTuning {
            approximate_tips: false,
            fit_tips: false,
            adaptive_density: true,
            front_contexts: false,
            loop_start: false,
            crease_tips: false,
            post_hint: false,
        },
        // The golden files predate the compact framing (format 1.1).
        framing: swm::Framing::Fixed,
        ..EncodeOptions::default()
    }
}

/// Writes the 1.1 golden file (run once, by hand:
/// `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_swing_v1_1_golden`).
#[test]
#[ignore]
fn write_swing_v1_1_golden() {
    write_golden(
        "swing-v1.1.swm",
        &golden_ellipsoid(),
        &golden_adaptive_options(),
    );
}

/// Must hold forever: a failure means the decoder no longer reads the
/// DENS section of format 1.1 as specified.
#[test]
fn swing_v1_1_decodes_to_its_test_vector() {
    let info = swm::inspect(SWING_V1_1, &Default::default()).unwrap();
    assert_eq!(info.version, (1, 1));
    let swing = info.swing.expect("a SwingWrapper file");
    assert!(
        swing.sections.iter().any(|(t, _)| t == b"DENS"),
        "the 1.1 golden file has a DENS section"
    );
    assert_eq!(
        (swing.density_levels, swing.density_bytes),
        (Some((-1, 2)), 20)
    );
    let mesh = swm::decode(SWING_V1_1, &DecodeOptions::default())
        .expect("golden file swing-v1.1.swm must decode");
    assert_eq!(
        mesh_hash(&mesh),
        SWING_V1_1_FNV1A64,
        "decoded mesh differs from format-spec/05-swing.md's test vector"
    );
}

/// The encoder still writes the 1.1 golden bytes from the golden
/// ellipsoid (pins the encoder's density rule on this platform).
#[test]
fn swing_v1_1_reencodes_to_the_same_bytes() {
    let encoded = swm::encode(&golden_ellipsoid(), &golden_adaptive_options()).unwrap();
    assert_eq!(
        encoded.bytes, SWING_V1_1,
        "re-encoding the golden ellipsoid no longer gives golden/swing-v1.1.swm"
    );
}

// --- Format 1.1: SwingWrapper with front contexts (CLRF) and DENS ---

const SWING_FRONT_V1_1: &[u8] = include_bytes!("../format-spec/golden/swing-front-v1.1.swm");

/// The test vector of format-spec/05-swing.md ("Golden file", CLRF).
const SWING_FRONT_V1_1_FNV1A64: u64 = 0x17C1_0DEB_FC4D_CD98;

/// The golden ellipsoid retiled as the 1.1 golden file is, with its
/// symbols in `CLRF`.
fn golden_front_options() -> EncodeOptions {
    let mut options = golden_adaptive_options();
    options.mode = EncodeMode::Swing {
        target: swm::SwingTarget::EdgeLength(0.1),
        angle_bits: Some(8),
        max_bytes: None,
    };
    options.swing.front_contexts = true;
    options
}

/// Writes the CLRF golden file (run once, by hand:
/// `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_swing_front_v1_1_golden`).
#[test]
#[ignore]
fn write_swing_front_v1_1_golden() {
    write_golden(
        "swing-front-v1.1.swm",
        &golden_ellipsoid(),
        &golden_front_options(),
    );
}

/// Must hold forever: a failure means the decoder no longer reads the
/// CLRF section of format 1.1 as specified.
#[test]
fn swing_front_v1_1_decodes_to_its_test_vector() {
    let info = swm::inspect(SWING_FRONT_V1_1, &Default::default()).unwrap();
    assert_eq!(info.version, (1, 1));
    let swing = info.swing.expect("a SwingWrapper file");
    let tags: Vec<&[u8; 4]> = swing.sections.iter().map(|(t, _)| t).collect();
    assert!(
        tags.contains(&b"CLRF") && tags.contains(&b"DENS"),
        "{tags:?}"
    );
    assert!(!tags.contains(&b"CLRS"));
    assert!(info.stats.clers[4] > 0, "the golden file has an S");
    let mesh = swm::decode(SWING_FRONT_V1_1, &DecodeOptions::default())
        .expect("golden file swing-front-v1.1.swm must decode");
    assert_eq!(
        mesh_hash(&mesh),
        SWING_FRONT_V1_1_FNV1A64,
        "decoded mesh differs from format-spec/05-swing.md's test vector"
    );
}

/// The encoder still writes the CLRF golden bytes (pins the encoder's
/// choice of CLRF and of each S's node on this platform).
#[test]
fn swing_front_v1_1_reencodes_to_the_same_bytes() {
    let encoded = swm::encode(&golden_ellipsoid(), &golden_front_options()).unwrap();
    assert_eq!(
        encoded.bytes, SWING_FRONT_V1_1,
        "re-encoding the golden ellipsoid no longer gives golden/swing-front-v1.1.swm"
    );
}

// --- Format 1.1: SwingWrapper started on a boundary loop (LOOP) ---

const SWING_LOOP_V1_1: &[u8] = include_bytes!("../format-spec/golden/swing-loop-v1.1.swm");

/// The test vector of format-spec/05-swing.md ("Golden file", LOOP).
const SWING_LOOP_V1_1_FNV1A64: u64 = 0x0994_2253_92D8_A1EF;

/// The LOOP golden file's input: the golden sphere without the faces
/// whose three vertices all lie above z = 0.5 (binary32 comparisons): a
/// cap with one boundary loop.
fn golden_cap() -> TriMesh {
    let m = golden_sphere();
    let high = |v: u32| m.positions[v as usize][2] > 0.5;
    let kept = m
        .triangles
        .iter()
        .copied()
        .filter(|t| !t.iter().all(|&v| high(v)))
        .collect();
    TriMesh::new(m.positions.clone(), kept)
}

fn golden_loop_options() -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Swing {
            target: swm::SwingTarget::EdgeLength(0.2),
            angle_bits: Some(8),
            max_bytes: None,
        },
        swing: swm::SwingTuning {
            approximate_tips: false,
            fit_tips: false,
            adaptive_density: false,
            front_contexts: true,
            loop_start: true,
            crease_tips: false,
            post_hint: false,
        },
        ..EncodeOptions::default()
    }
}

/// Writes the LOOP golden file (run once, by hand:
/// `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_swing_loop_v1_1_golden`).
#[test]
#[ignore]
fn write_swing_loop_v1_1_golden() {
    write_golden("swing-loop-v1.1.swm", &golden_cap(), &golden_loop_options());
}

/// Must hold forever: a failure means the decoder no longer reads the
/// LOOP section of format 1.1 as specified.
#[test]
fn swing_loop_v1_1_decodes_to_its_test_vector() {
    let info = swm::inspect(SWING_LOOP_V1_1, &Default::default()).unwrap();
    assert_eq!(info.version, (1, 1));
    let swing = info.swing.expect("a SwingWrapper file");
    let tags: Vec<&[u8; 4]> = swing.sections.iter().map(|(t, _)| t).collect();
    // One hole, the loop's: its fan goes without a HOLE section.
    assert!(
        tags.contains(&b"LOOP") && !tags.contains(&b"HOLE"),
        "{tags:?}"
    );
    assert_eq!(swing.loops, 1);
    assert_eq!(swing.holes_masked_triangles, 0);
    let mesh = swm::decode(SWING_LOOP_V1_1, &DecodeOptions::default())
        .expect("golden file swing-loop-v1.1.swm must decode");
    assert_eq!(
        mesh_hash(&mesh),
        SWING_LOOP_V1_1_FNV1A64,
        "decoded mesh differs from format-spec/05-swing.md's test vector"
    );
}

/// The encoder still writes the LOOP golden bytes from the golden cap
/// (pins the loop's resampling and residuals on this platform).
#[test]
fn swing_loop_v1_1_reencodes_to_the_same_bytes() {
    let encoded = swm::encode(&golden_cap(), &golden_loop_options()).unwrap();
    assert_eq!(
        encoded.bytes, SWING_LOOP_V1_1,
        "re-encoding the golden cap no longer gives golden/swing-loop-v1.1.swm"
    );
}

// --- Format 1.1: the post-processing hint (post) ---

const SWING_POST_V1_1: &[u8] = include_bytes!("../format-spec/golden/swing-post-v1.1.swm");

/// The plain decode's hash, from format-spec/06-post.md ("Golden file
/// and test vectors"; the sharpened and bent ones are below).
const SWING_POST_V1_1_PLAIN_FNV1A64: u64 = 0x8D73_D847_7D16_0DA4;

/// The hint golden file's input: the box [-1, 1]³, each face a grid of
/// 8 × 8 squares cut along one diagonal (every coordinate a multiple of
/// 1/4: exact in binary32 on every platform).
fn golden_box() -> TriMesh {
    const N: i32 = 8;
    let mut index = std::collections::HashMap::new();
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut vertex = |p: [i32; 3]| -> u32 {
        *index.entry(p).or_insert_with(|| {
            positions.push(p.map(|c| c as f32 / (N / 2) as f32 - 1.0));
            (positions.len() - 1) as u32
        })
    };
    // Each face: a fixed axis at 0 or N, the other two (u, v) in the order
    // that makes (u × v) point outwards.
    for axis in 0..3 {
        for side in [0, N] {
            let (mut u, mut v) = ((axis + 1) % 3, (axis + 2) % 3);
            if side == 0 {
                std::mem::swap(&mut u, &mut v);
            }
            let at = |i: i32, j: i32| {
                let mut p = [0; 3];
                p[axis] = side;
                p[u] = i;
                p[v] = j;
                p
            };
            for i in 0..N {
                for j in 0..N {
                    let a = vertex(at(i, j));
                    let b = vertex(at(i + 1, j));
                    let c = vertex(at(i + 1, j + 1));
                    let d = vertex(at(i, j + 1));
                    triangles.push([a, b, c]);
                    triangles.push([a, c, d]);
                }
            }
        }
    }
    TriMesh::new(positions, triangles)
}

fn golden_post_options() -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Swing {
            target: swm::SwingTarget::EdgeLength(0.3),
            angle_bits: Some(8),
            max_bytes: None,
        },
        swing: swm::SwingTuning {
            approximate_tips: false,
            fit_tips: false,
            adaptive_density: false,
            front_contexts: true,
            loop_start: true,
            crease_tips: false,
            post_hint: true,
        },
        ..EncodeOptions::default()
    }
}

/// Writes the hint golden file (run once, by hand:
/// `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_swing_post_v1_1_golden`).
#[test]
#[ignore]
fn write_swing_post_v1_1_golden() {
    let options = golden_post_options();
    write_golden("swing-post-v1.1.swm", &golden_box(), &options);
    let encoded = swm::encode(&golden_box(), &options).unwrap();
    let plain = swm::decode(&encoded.bytes, &DecodeOptions::plain()).unwrap();
    println!(
        "plain: {} vertices, {} triangles, hash {:#018X}; hint {:?}",
        plain.positions.len(),
        plain.triangles.len(),
        mesh_hash(&plain),
        encoded.stats.hint()
    );
}

/// Must hold forever: the hint golden file says "EdgeSharpener", its
/// default decode follows it, and explicit options override it.
#[test]
fn swing_post_v1_1_decodes_to_its_test_vector() {
    let info = swm::inspect(SWING_POST_V1_1, &Default::default()).unwrap();
    assert_eq!(info.version, (1, 1));
    assert_eq!(
        info.post,
        Some(swm::PostProcessing {
            sharpen: true,
            bend_steps: 0
        })
    );
    let plain = swm::decode(SWING_POST_V1_1, &DecodeOptions::plain())
        .expect("golden file swing-post-v1.1.swm must decode");
    assert_eq!(
        mesh_hash(&plain),
        SWING_POST_V1_1_PLAIN_FNV1A64,
        "decoded mesh differs from format-spec/06-post.md's test vector"
    );
    let default = swm::decode(SWING_POST_V1_1, &DecodeOptions::default()).unwrap();
    let sharpened = swm::sharpen(&plain, &Default::default()).unwrap().mesh;
    assert_eq!(default, sharpened, "the default decode follows the hint");
    assert_ne!(default, plain);
}

/// The sharpened and bent test vectors of format-spec/06-post.md
/// ("Golden file and test vectors"): the decode of swing-post-v1.1.swm
/// that its hint asks for (EdgeSharpener alone), then with one and two
/// Bender steps after it; (Bender steps, vertices, triangles, FNV-1a 64
/// of `mesh_hash`).
const SWING_POST_V1_1_POST: [(u32, usize, usize, u64); 3] = [
    (0, 375, 746, 0x4C09_5F9B_1B6D_50F0),
    (1, 1494, 2984, 0x1459_7F9D_A8FC_DA8A),
    (2, 5970, 11936, 0x2045_1A0D_3C12_9692),
];

/// What EdgeSharpener reports on the plain decode of swing-post-v1.1.swm
/// (06-post.md): smooth edges, chamfer edges, corners, snapped, unmoved,
/// slivers collapsed, vertices removed, sharp edges.
const SWING_POST_V1_1_REPORT: [u64; 8] = [707, 73, 1, 71, 3, 0, 0, 146];

/// Must hold forever (the figures are part of 06-post.md): the default
/// decode of the hint golden file, and the same file sharpened and bent
/// by one and two steps on the caller's request, counted and hashed; and
/// EdgeSharpener's intermediate counts, which a second implementation can
/// compare on the way.
#[test]
fn swing_post_v1_1_sharpens_and_bends_to_its_test_vectors() {
    let mut got = Vec::new();
    for (bend, ..) in SWING_POST_V1_1_POST {
        let options = if bend == 0 {
            DecodeOptions::default()
        } else {
            DecodeOptions {
                sharpen: Some(true),
                bend_steps: Some(bend),
                ..DecodeOptions::default()
            }
        };
        let mesh = swm::decode(SWING_POST_V1_1, &options).unwrap();
        got.push((
            bend,
            mesh.positions.len(),
            mesh.triangles.len(),
            mesh_hash(&mesh),
        ));
    }
    let plain = swm::decode(SWING_POST_V1_1, &DecodeOptions::plain()).unwrap();
    let r = swm::sharpen(&plain, &Default::default()).unwrap().report;
    let report = [
        r.smooth_edges,
        r.chamfer_edges,
        r.corners,
        r.snapped,
        r.unmoved.total(),
        r.slivers_collapsed,
        r.vertices_removed,
        r.sharp_edges,
    ];
    assert_eq!(
        got, SWING_POST_V1_1_POST,
        "the sharpened (and bent) decodes differ from format-spec/06-post.md's test vectors"
    );
    assert_eq!(
        report, SWING_POST_V1_1_REPORT,
        "EdgeSharpener's counts differ from format-spec/06-post.md's"
    );
}

/// 06-post.md's test vectors on two golden files with boundaries, which
/// Bender treats as sharp: EdgeSharpener and one Bender step asked for by
/// the caller; (file, vertices, triangles, FNV-1a 64 of `mesh_hash`).
const POST_WITH_BOUNDARIES: [(&str, &[u8], usize, usize, u64); 2] = [
    (
        "lossless-v1.0.swm",
        LOSSLESS_V1_0,
        319,
        632,
        0xA943_5954_B356_5704,
    ),
    (
        "swing-loop-v1.1.swm",
        SWING_LOOP_V1_1,
        1242,
        2428,
        0xDE49_33D6_47BC_BB0C,
    ),
];

#[test]
fn sharpened_and_bent_boundaries_decode_to_their_test_vectors() {
    let options = DecodeOptions {
        sharpen: Some(true),
        bend_steps: Some(1),
        ..DecodeOptions::default()
    };
    for (name, bytes, vertices, triangles, hash) in POST_WITH_BOUNDARIES {
        let mesh = swm::decode(bytes, &options).unwrap();
        assert_eq!(
            (mesh.positions.len(), mesh.triangles.len(), mesh_hash(&mesh)),
            (vertices, triangles, hash),
            "{name} sharpened and bent differs from format-spec/06-post.md's test vector"
        );
    }
}

/// The encoder still writes the hint golden bytes from the golden box.
#[test]
fn swing_post_v1_1_reencodes_to_the_same_bytes() {
    let encoded = swm::encode(&golden_box(), &golden_post_options()).unwrap();
    assert_eq!(
        encoded.bytes, SWING_POST_V1_1,
        "re-encoding the golden box no longer gives golden/swing-post-v1.1.swm"
    );
}

// --- Format 1.1: a hint for EdgeSharpener and Bender, and a cleanup ---

const SWING_BEND_V1_1: &[u8] = include_bytes!("../format-spec/golden/swing-bend-v1.1.swm");

/// The golden box retiled at L = 0.25, its hint measured: EdgeSharpener
/// and one Bender step (format-spec/06-post.md, "Golden file and test
/// vectors"). Where its corners' chamfers meet, one snap leaves a sliver
/// that the cleanup collapses.
fn golden_bend_options() -> EncodeOptions {
    let mut options = golden_post_options();
    options.mode = EncodeMode::Swing {
        target: swm::SwingTarget::EdgeLength(0.25),
        angle_bits: Some(8),
        max_bytes: None,
    };
    options
}

/// The test vectors of 06-post.md: (Bender steps after EdgeSharpener,
/// vertices, triangles, FNV-1a 64 of `mesh_hash`); one step is the
/// default decode, which the hint asks for.
const SWING_BEND_V1_1_POST: [(u32, usize, usize, u64); 3] = [
    (0, 499, 994, 0x351A_D3BB_A5ED_3C9E),
    (1, 1990, 3976, 0x4689_9CF4_6A17_8432),
    (2, 7954, 15904, 0xA1BC_DB8E_0856_5503),
];

/// Its plain decode: vertices, triangles, FNV-1a 64.
const SWING_BEND_V1_1_PLAIN: (usize, usize, u64) = (394, 784, 0xE7FE_2652_FCBC_EAB5);

/// Writes the Sharpen&Bend golden file (run once, by hand:
/// `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_swing_bend_v1_1_golden`).
#[test]
#[ignore]
fn write_swing_bend_v1_1_golden() {
    let options = golden_bend_options();
    write_golden("swing-bend-v1.1.swm", &golden_box(), &options);
    let encoded = swm::encode(&golden_box(), &options).unwrap();
    println!("hint {:?}", encoded.stats.hint());
}

/// Must hold forever: the hint says EdgeSharpener and one Bender step, the
/// default decode follows it, and every figure of 06-post.md's table for
/// this file (plain, sharpened, bent once and twice, EdgeSharpener's
/// counts) holds.
#[test]
fn swing_bend_v1_1_decodes_to_its_test_vectors() {
    let info = swm::inspect(SWING_BEND_V1_1, &Default::default()).unwrap();
    assert_eq!(info.version, (1, 1));
    assert_eq!(
        info.post,
        Some(swm::PostProcessing {
            sharpen: true,
            bend_steps: 1
        })
    );
    let plain = swm::decode(SWING_BEND_V1_1, &DecodeOptions::plain())
        .expect("golden file swing-bend-v1.1.swm must decode");
    assert_eq!(
        (
            plain.positions.len(),
            plain.triangles.len(),
            mesh_hash(&plain)
        ),
        SWING_BEND_V1_1_PLAIN
    );
    for (bend, vertices, triangles, hash) in SWING_BEND_V1_1_POST {
        let options = DecodeOptions {
            sharpen: Some(true),
            bend_steps: Some(bend),
            ..DecodeOptions::default()
        };
        let mesh = swm::decode(SWING_BEND_V1_1, &options).unwrap();
        assert_eq!(
            (mesh.positions.len(), mesh.triangles.len(), mesh_hash(&mesh)),
            (vertices, triangles, hash),
            "swing-bend-v1.1.swm sharpened and bent {bend} times differs from \
             format-spec/06-post.md's test vector"
        );
        if bend == 1 {
            let default = swm::decode(SWING_BEND_V1_1, &DecodeOptions::default()).unwrap();
            assert_eq!(default, mesh, "the default decode follows the hint");
        }
    }
    let r = swm::sharpen(&plain, &Default::default()).unwrap().report;
    assert_eq!(
        [
            r.smooth_edges,
            r.chamfer_edges,
            r.corners,
            r.snapped,
            r.unmoved.total(),
            r.slivers_collapsed,
            r.vertices_removed,
            r.sharp_edges,
        ],
        [941, 102, 4, 103, 3, 1, 1, 164],
        "EdgeSharpener's counts differ from format-spec/06-post.md's"
    );
}

/// The encoder still writes the Sharpen&Bend golden bytes from the box.
#[test]
fn swing_bend_v1_1_reencodes_to_the_same_bytes() {
    let encoded = swm::encode(&golden_box(), &golden_bend_options()).unwrap();
    assert_eq!(
        encoded.bytes, SWING_BEND_V1_1,
        "re-encoding the golden box no longer gives golden/swing-bend-v1.1.swm"
    );
}

// --- Format 1.1: tips on creases (RADS) ---

const SWING_CREASE_V1_1: &[u8] = include_bytes!("../format-spec/golden/swing-crease-v1.1.swm");

/// The test vector of format-spec/05-swing.md ("Golden file", RADS).
const SWING_CREASE_V1_1_FNV1A64: u64 = 0x14FE_1EB9_1EB8_A9CC;

fn golden_crease_options() -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Swing {
            target: swm::SwingTarget::EdgeLength(0.3),
            angle_bits: Some(8),
            max_bytes: None,
        },
        swing: swm::SwingTuning {
            approximate_tips: false,
            fit_tips: false,
            adaptive_density: false,
            front_contexts: true,
            loop_start: true,
            crease_tips: true,
            post_hint: false,
        },
        ..EncodeOptions::default()
    }
}

/// Writes the RADS golden file (run once, by hand:
/// `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_swing_crease_v1_1_golden`).
#[test]
#[ignore]
fn write_swing_crease_v1_1_golden() {
    let options = golden_crease_options();
    write_golden("swing-crease-v1.1.swm", &golden_box(), &options);
    let encoded = swm::encode(&golden_box(), &options).unwrap();
    let mesh = swm::decode(&encoded.bytes, &DecodeOptions::plain()).unwrap();
    println!(
        "{} bytes: {} vertices, {} triangles, hash {:#018X}; sections {:?}",
        encoded.bytes.len(),
        mesh.positions.len(),
        mesh.triangles.len(),
        mesh_hash(&mesh),
        encoded.stats.swing().map(|s| &s.sections)
    );
}

/// Must hold forever: a failure means the decoder no longer reads the
/// RADS section of format 1.1 as specified.
#[test]
fn swing_crease_v1_1_decodes_to_its_test_vector() {
    let info = swm::inspect(SWING_CREASE_V1_1, &Default::default()).unwrap();
    assert_eq!(info.version, (1, 1));
    let swing = info.swing.expect("a SwingWrapper file");
    let tags: Vec<&[u8; 4]> = swing.sections.iter().map(|(t, _)| t).collect();
    assert!(
        tags.contains(&b"RADS") && tags.contains(&b"CLRF"),
        "{tags:?}"
    );
    let mesh = swm::decode(SWING_CREASE_V1_1, &DecodeOptions::default())
        .expect("golden file swing-crease-v1.1.swm must decode");
    assert_eq!(
        mesh_hash(&mesh),
        SWING_CREASE_V1_1_FNV1A64,
        "decoded mesh differs from format-spec/05-swing.md's test vector"
    );
}

/// The encoder still writes the RADS golden bytes from the golden box.
#[test]
fn swing_crease_v1_1_reencodes_to_the_same_bytes() {
    let encoded = swm::encode(&golden_box(), &golden_crease_options()).unwrap();
    assert_eq!(
        encoded.bytes, SWING_CREASE_V1_1,
        "re-encoding the golden box no longer gives golden/swing-crease-v1.1.swm"
    );
}

// --- CLRD and GEOF: lossless symbols and positions of a dense mesh ---

/// The golden sphere (642 vertices) at 6 bits, where vertices are about
/// four grid steps apart and nearly every vertex has valence 6: the
/// encoder keeps `CLRD` and `GEOF`, smaller than `CLRS` and `GEOM`.
fn golden_dense_options() -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Lossless { qp: 6 },
        ..EncodeOptions::default()
    }
}

const LOSSLESS_DENSE_V1_1: &[u8] = include_bytes!("../format-spec/golden/lossless-dense-v1.1.swm");

/// The test vector of format-spec/04-lossless.md ("Golden file of CLRD
/// and GEOF").
const LOSSLESS_DENSE_V1_1_FNV1A64: u64 = 0xF6EC_ED5E_393D_6A5F;

/// Writes the dense golden file (run once, by hand:
/// `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_lossless_dense_v1_1_golden`).
#[test]
#[ignore]
fn write_lossless_dense_v1_1_golden() {
    let options = golden_dense_options();
    write_golden("lossless-dense-v1.1.swm", &golden_sphere(), &options);
    let encoded = swm::encode(&golden_sphere(), &options).unwrap();
    println!(
        "sections {:?}",
        encoded.stats.lossless().map(|s| &s.sections)
    );
}

/// Must hold forever: a failure means the decoder no longer reads the
/// CLRD and GEOF sections of format 1.1 as specified.
#[test]
fn lossless_dense_v1_1_decodes_to_its_test_vector() {
    let info = swm::inspect(LOSSLESS_DENSE_V1_1, &Default::default()).unwrap();
    assert_eq!(info.version, (1, 1));
    let tags: Vec<&[u8; 4]> = info.stats.sections.iter().map(|(t, _)| t).collect();
    assert!(
        tags.contains(&b"CLRD") && tags.contains(&b"GEOF"),
        "{tags:?}"
    );
    assert!(!tags.contains(&b"CLRS") && !tags.contains(&b"GEOM"));
    let mesh = swm::decode(LOSSLESS_DENSE_V1_1, &DecodeOptions::default())
        .expect("golden file lossless-dense-v1.1.swm must decode");
    assert_eq!((mesh.positions.len(), mesh.triangles.len()), (642, 1280));
    assert_eq!(
        mesh_hash(&mesh),
        LOSSLESS_DENSE_V1_1_FNV1A64,
        "decoded mesh differs from format-spec/04-lossless.md's test vector"
    );
}

/// The encoder still writes the dense golden bytes from the golden sphere.
#[test]
fn lossless_dense_v1_1_reencodes_to_the_same_bytes() {
    let encoded = swm::encode(&golden_sphere(), &golden_dense_options()).unwrap();
    assert_eq!(
        encoded.bytes, LOSSLESS_DENSE_V1_1,
        "re-encoding the golden sphere no longer gives golden/lossless-dense-v1.1.swm"
    );
}

/// 06-post.md's test vectors for fans of more than 16 triangles (its
/// "Large fans"), on `golden_fans`: (vertices, triangles, FNV-1a 64) of
/// the mesh, of one Bender step without sharp edges, and of EdgeSharpener
/// (which tags 24 edges and changes nothing else) then one Bender step.
const FANS: [(usize, usize, u64); 3] = [
    (48, 68, 0x579A_052E_28CB_A4F1),
    (161, 272, 0xCF50_E9FD_0F3F_CE61),
    (161, 272, 0xDE52_1FCA_379E_8756),
];

#[test]
fn large_fans_sharpen_and_bend_to_their_test_vectors() {
    let figures = |m: &TriMesh| (m.positions.len(), m.triangles.len(), mesh_hash(m));
    let mesh = golden_fans();
    let none = swm::SharpEdges::default();
    let bent = swm::bend(&mesh, &none, 1, &Default::default())
        .unwrap()
        .mesh;
    let sharpened = swm::sharpen(&mesh, &Default::default()).unwrap();
    assert_eq!(sharpened.mesh, mesh);
    assert_eq!(sharpened.sharp.len(), 24);
    let both = swm::bend(&sharpened.mesh, &sharpened.sharp, 1, &Default::default())
        .unwrap()
        .mesh;
    assert_eq!(
        [figures(&mesh), figures(&bent), figures(&both)],
        FANS,
        "the large fans' figures differ from format-spec/06-post.md's"
    );
}

/// Two components with fans of more than 16 triangles: a square pyramid
/// whose apex and base centre each have 24, and an open half-fan whose
/// centre, on the boundary, has 20 between its two boundary edges.
fn golden_fans() -> TriMesh {
    let mut positions: Vec<[f32; 3]> = Vec::new();
    let mut triangles = Vec::new();
    // The perimeter of [-3, 3]², counter-clockwise from (-3, -3).
    for i in 0..24 {
        let (side, k) = (i / 6, (i % 6) as f32);
        let (x, y) = match side {
            0 => (-3.0 + k, -3.0),
            1 => (3.0, -3.0 + k),
            2 => (3.0 - k, 3.0),
            _ => (-3.0, 3.0 - k),
        };
        positions.push([x, y, 0.0]);
    }
    positions.push([0.0, 0.0, 3.0]);
    positions.push([0.0, 0.0, 0.0]);
    for i in 0..24u32 {
        let j = (i + 1) % 24;
        triangles.push([i, j, 24]);
        triangles.push([j, i, 25]);
    }
    // The half-fan: centre (10, 0, 0), then the upper half of the
    // perimeter of [-5, 5]² around it, z = -1, 0, 1 in turn.
    positions.push([10.0, 0.0, 0.0]);
    for j in 0..=20u32 {
        let (x, y) = match j {
            0..=5 => (5.0, j as f32),
            6..=15 => (5.0 - (j - 5) as f32, 5.0),
            _ => (-5.0, 5.0 - (j - 15) as f32),
        };
        positions.push([10.0 + x, y, (j % 3) as f32 - 1.0]);
    }
    for j in 0..20u32 {
        triangles.push([26, 27 + j, 28 + j]);
    }
    TriMesh::new(positions, triangles)
}

// --- Format 1.2: displaced subdivision (mode 2) ---

const DISPLACED_V1_2: &[u8] = include_bytes!("../format-spec/golden/displaced-v1.2.swm");

/// The test vector of format-spec/07-displaced.md ("Golden file").
const DISPLACED_V1_2_FNV1A64: u64 = 0xF4E1_F0D8_C591_DCC1;

/// The displaced golden file's input: the golden sphere's construction
/// with five subdivisions (20,480 triangles) stretched to the golden
/// ellipsoid, without the triangles whose three vertices have x > 0.5
/// (binary32 comparisons): one boundary loop, so the midpoint fallback is
/// in the file.
fn golden_open_ellipsoid() -> TriMesh {
    let mut m = golden_icosphere(5);
    for p in &mut m.positions {
        p[1] *= 0.5;
        p[2] *= 0.25;
    }
    let high = |v: u32| m.positions[v as usize][0] > 0.5;
    let kept = m
        .triangles
        .iter()
        .copied()
        .filter(|t| !t.iter().all(|&v| high(v)))
        .collect();
    TriMesh::new(m.positions.clone(), kept)
}

/// The golden open ellipsoid coded by displaced subdivision at 1,500
/// bytes (two levels).
fn golden_displaced_options() -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Displaced {
            target: swm::SwingTarget::Bytes(1500),
            max_bytes: None,
        },
        ..EncodeOptions::default()
    }
}

/// Wrote the 1.2 golden file (run once, by hand:
/// `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_displaced_v1_2_golden`).
/// The encoder has changed since (it fits bends now, and writes
/// `displaced-bend-v1.2.swm` from the same input): run now, it would
/// replace the golden file with other bytes.
#[test]
#[ignore]
fn write_displaced_v1_2_golden() {
    write_golden(
        "displaced-v1.2.swm",
        &golden_open_ellipsoid(),
        &golden_displaced_options(),
    );
}

/// Must hold forever: a failure means the decoder no longer reads mode 2
/// of format 1.2 as specified.
#[test]
fn displaced_v1_2_decodes_to_its_test_vector() {
    let info = swm::inspect(DISPLACED_V1_2, &Default::default()).unwrap();
    assert_eq!((info.version, info.mode), ((1, 2), swm::Mode::Displaced));
    let mesh = swm::decode(DISPLACED_V1_2, &DecodeOptions::default())
        .expect("golden file displaced-v1.2.swm must decode");
    assert_eq!(
        mesh_hash(&mesh),
        DISPLACED_V1_2_FNV1A64,
        "decoded mesh differs from format-spec/07-displaced.md's test vector"
    );
    // Two levels: the file cut after the first decodes to a quarter of
    // the triangles, and after none to the base.
    let limits = swm::Limits::default();
    for (levels, triangles) in [(1, 2256), (0, 564)] {
        let cut = swm::cut_levels(DISPLACED_V1_2, levels, &limits).unwrap();
        let coarse = swm::decode(&cut, &DecodeOptions::default()).unwrap();
        assert_eq!(coarse.triangles.len(), triangles);
    }
}

const DISPLACED_BEND_V1_2: &[u8] = include_bytes!("../format-spec/golden/displaced-bend-v1.2.swm");

/// The test vector of format-spec/07-displaced.md ("Golden files"): the
/// decoded mesh of `displaced-bend-v1.2.swm`, whose levels carry bends.
const DISPLACED_BEND_V1_2_FNV1A64: u64 = 0x4919_A718_3C86_C276;

/// Wrote the second 1.2 golden file, the golden open ellipsoid at
/// [`golden_displaced_options`] by the encoder that fits bends (run once,
/// by hand: `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored
/// write_displaced_bend_v1_2_golden`). The first one
/// (`displaced-v1.2.swm`, from the encoder before bends) stays the test
/// vector of files without them. The encoder has changed since (it
/// writes a bare base, `displaced-bare-v1.2.swm`): run now, it would
/// replace the golden file with other bytes.
#[test]
#[ignore]
fn write_displaced_bend_v1_2_golden() {
    write_golden(
        "displaced-bend-v1.2.swm",
        &golden_open_ellipsoid(),
        &golden_displaced_options(),
    );
}

/// Must hold forever: a failure means the decoder no longer reads bends
/// (`HEAD`'s flag bit and codes) as format-spec/07-displaced.md says.
#[test]
fn displaced_bend_v1_2_decodes_to_its_test_vector() {
    let info = swm::inspect(DISPLACED_BEND_V1_2, &Default::default()).unwrap();
    assert_eq!((info.version, info.mode), ((1, 2), swm::Mode::Displaced));
    // The rule byte's bit 7: bends follow the steps (`HEAD` is the
    // compact framing's first payload, after the 1-byte code and length
    // entries).
    let mesh = swm::decode(DISPLACED_BEND_V1_2, &DecodeOptions::default())
        .expect("golden file displaced-bend-v1.2.swm must decode");
    assert_eq!(
        mesh_hash(&mesh),
        DISPLACED_BEND_V1_2_FNV1A64,
        "decoded mesh differs from format-spec/07-displaced.md's test vector"
    );
    let limits = swm::Limits::default();
    let cut = swm::cut_levels(DISPLACED_BEND_V1_2, 1, &limits).unwrap();
    let coarse = swm::decode(&cut, &DecodeOptions::default()).unwrap();
    assert_eq!(coarse.triangles.len() * 4, mesh.triangles.len());
}

const DISPLACED_BARE_V1_2: &[u8] = include_bytes!("../format-spec/golden/displaced-bare-v1.2.swm");

/// The test vector of format-spec/07-displaced.md ("Golden files"): the
/// decoded mesh of `displaced-bare-v1.2.swm`, whose `BASE` is bare.
const DISPLACED_BARE_V1_2_FNV1A64: u64 = 0x054B_C755_0F5E_DA73;

/// Wrote the third 1.2 golden file, the golden open ellipsoid at
/// [`golden_displaced_options`] by the encoder that writes bare bases
/// (run once, by hand: `SWM_WRITE_GOLDEN=1 cargo test --test golden --
/// --ignored write_displaced_bare_v1_2_golden`). The bend golden file
/// (a whole mode-0 file in `BASE`) stays the test vector of bends
/// without a bare base.
#[test]
#[ignore]
fn write_displaced_bare_v1_2_golden() {
    write_golden(
        "displaced-bare-v1.2.swm",
        &golden_open_ellipsoid(),
        &golden_displaced_options(),
    );
}

/// Must hold forever: a failure means the decoder no longer reads a bare
/// `BASE` (`HEAD`'s bit 6) as format-spec/07-displaced.md says.
#[test]
fn displaced_bare_v1_2_decodes_to_its_test_vector() {
    let info = swm::inspect(DISPLACED_BARE_V1_2, &Default::default()).unwrap();
    assert_eq!((info.version, info.mode), ((1, 2), swm::Mode::Displaced));
    let mesh = swm::decode(DISPLACED_BARE_V1_2, &DecodeOptions::default())
        .expect("golden file displaced-bare-v1.2.swm must decode");
    assert_eq!(
        mesh_hash(&mesh),
        DISPLACED_BARE_V1_2_FNV1A64,
        "decoded mesh differs from format-spec/07-displaced.md's test vector"
    );
    let limits = swm::Limits::default();
    for levels in [1, 0] {
        let cut = swm::cut_levels(DISPLACED_BARE_V1_2, levels, &limits).unwrap();
        let coarse = swm::decode(&cut, &DecodeOptions::default()).unwrap();
        assert_eq!(
            coarse.triangles.len() << (2 * (2 - levels)),
            mesh.triangles.len()
        );
    }
}

/// The encoder still writes the bare golden file's bytes from the golden
/// open ellipsoid: a file of mode 2 of format 1.2 with bends and a bare
/// base.
#[test]
fn displaced_v1_2_reencodes_to_the_same_bytes() {
    let encoded = swm::encode(&golden_open_ellipsoid(), &golden_displaced_options()).unwrap();
    assert!(
        encoded.bytes == DISPLACED_BARE_V1_2,
        "re-encoding the golden open ellipsoid no longer gives golden/displaced-bare-v1.2.swm"
    );
}

// --- Format 1.2: vertex attributes in the lossless mode (ATTR) ---

/// The golden torus (with its hole) with texture coordinates (`u = i/8`,
/// `v = j/6`: seams where `i` or `j` wraps, each grid value shared by the
/// corners of its vertex) and its unit normals `(cos φ·cos θ, sin φ·cos θ,
/// sin θ)`, from the same exact cosines: format-spec/08-attributes.md's
/// golden mesh.
fn golden_textured_torus() -> swm::AttributedMesh {
    let mesh = golden_torus();
    let h = 0.5f64.sqrt();
    let t = 0.75f64.sqrt();
    let cos8 = [1.0, h, 0.0, -h, -1.0, -h, 0.0, h];
    let sin8 = [0.0, h, 1.0, h, 0.0, -h, -1.0, -h];
    let cos6 = [1.0, 0.5, -0.5, -1.0, -0.5, 0.5];
    let sin6 = [0.0, t, t, 0.0, -t, -t];
    let (nu, nv) = (8u32, 6u32);
    let mut normals = Vec::new();
    for i in 0..nu as usize {
        for j in 0..nv as usize {
            normals.extend([cos8[i] * cos6[j], sin8[i] * cos6[j], sin6[j]].map(|x| x as f32));
        }
    }
    let mut uv = Vec::new();
    for i in 0..=nu {
        for j in 0..=nv {
            uv.extend([i as f32 / nu as f32, j as f32 / nv as f32]);
        }
    }
    let uv_id = |i: u32, j: u32| i * (nv + 1) + j;
    let mut uv_corners = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            if (i, j) == (3, 2) {
                continue;
            }
            let (a, b, c, d) = (
                uv_id(i, j),
                uv_id(i + 1, j),
                uv_id(i + 1, j + 1),
                uv_id(i, j + 1),
            );
            uv_corners.push([a, b, c]);
            uv_corners.push([a, c, d]);
        }
    }
    let normal_corners = mesh.triangles.clone();
    swm::AttributedMesh::new(
        mesh,
        vec![
            swm::AttributeStream::new(swm::AttributeKind::TexCoord(0), 2, uv, uv_corners),
            swm::AttributeStream::new(swm::AttributeKind::Normal, 3, normals, normal_corners),
        ],
    )
}

fn golden_attr_options() -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Lossless { qp: 11 },
        ..Default::default()
    }
}

/// [`mesh_hash`] continued over each stream: its values as
/// little-endian `f32`s, then its triples as little-endian `u32`s.
fn attributed_hash(m: &swm::AttributedMesh) -> u64 {
    let mut bytes = Vec::new();
    for s in &m.streams {
        for v in &s.values {
            bytes.extend(v.to_le_bytes());
        }
        for t in &s.corners {
            for i in t {
                bytes.extend(i.to_le_bytes());
            }
        }
    }
    let mut h = mesh_hash(&m.mesh);
    for b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01B3);
    }
    h
}

const LOSSLESS_ATTR_V1_2: &[u8] = include_bytes!("../format-spec/golden/lossless-attr-v1.2.swm");

/// The test vector of format-spec/08-attributes.md ("Golden file").
const LOSSLESS_ATTR_V1_2_FNV1A64: u64 = 0xF2D1_1078_3D1F_3C4E;

/// Writes the attribute golden file (run once, by hand:
/// `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_lossless_attr_v1_2_golden`).
#[test]
#[ignore]
fn write_lossless_attr_v1_2_golden() {
    write_attributed_golden(
        "lossless-attr-v1.2.swm",
        &golden_textured_torus(),
        &golden_attr_options(),
    );
}

/// Must hold forever: a failure means the decoder no longer reads `ATTR`
/// of format 1.2 as specified.
#[test]
fn lossless_attr_v1_2_decodes_to_its_test_vector() {
    let info = swm::inspect(LOSSLESS_ATTR_V1_2, &Default::default()).unwrap();
    assert_eq!((info.version, info.mode), ((1, 2), swm::Mode::Lossless));
    assert_eq!(info.attributes.len(), 2);
    let m = swm::decode_attributed(LOSSLESS_ATTR_V1_2, &DecodeOptions::default())
        .expect("golden file lossless-attr-v1.2.swm must decode");
    assert_eq!(
        attributed_hash(&m),
        LOSSLESS_ATTR_V1_2_FNV1A64,
        "decoded mesh differs from format-spec/08-attributes.md's test vector"
    );
    // The plain decoder gives the same mesh, the torus's.
    let plain = swm::decode(LOSSLESS_ATTR_V1_2, &DecodeOptions::default()).unwrap();
    assert_eq!(plain, m.mesh);
}

/// The encoder still writes the golden bytes from the golden torus.
#[test]
fn lossless_attr_v1_2_reencodes_to_the_same_bytes() {
    let encoded = swm::encode_attributed(&golden_textured_torus(), &golden_attr_options()).unwrap();
    assert_eq!(
        encoded.bytes, LOSSLESS_ATTR_V1_2,
        "re-encoding the golden textured torus no longer gives golden/lossless-attr-v1.2.swm"
    );
}

// --- Format 1.2: ATTR over a displaced file's finest level ---

/// The golden open ellipsoid with a colour per vertex, a linear function
/// of its position, `(0.5 + 0.5x, 0.5 + y, 0.5 + 2z)` in binary32 (each
/// component within 0 … 1 on the ellipsoid): format-spec/08-attributes.md's
/// golden mesh "over a decoded mesh".
fn golden_coloured_ellipsoid() -> swm::AttributedMesh {
    let mesh = golden_open_ellipsoid();
    let colours = mesh
        .positions
        .iter()
        .flat_map(|p| [0.5 + 0.5 * p[0], 0.5 + p[1], 0.5 + 2.0 * p[2]])
        .collect();
    let stream = swm::AttributeStream::new(
        swm::AttributeKind::Color(0),
        3,
        colours,
        mesh.triangles.clone(),
    );
    swm::AttributedMesh::new(mesh, vec![stream])
}

/// The coloured ellipsoid coded by displaced subdivision at 2,500 bytes,
/// colours included.
fn golden_displaced_attr_options() -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Displaced {
            target: swm::SwingTarget::Bytes(2500),
            max_bytes: None,
        },
        ..EncodeOptions::default()
    }
}

const DISPLACED_ATTR_V1_2: &[u8] = include_bytes!("../format-spec/golden/displaced-attr-v1.2.swm");

/// The test vector of format-spec/08-attributes.md ("Golden file").
const DISPLACED_ATTR_V1_2_FNV1A64: u64 = 0x2F2D_3227_BE54_D0D0;

/// Writes the golden file (run once, by hand:
/// `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_displaced_attr_v1_2_golden`).
#[test]
#[ignore]
fn write_displaced_attr_v1_2_golden() {
    write_attributed_golden(
        "displaced-attr-v1.2.swm",
        &golden_coloured_ellipsoid(),
        &golden_displaced_attr_options(),
    );
}

/// Must hold forever: a failure means the decoder no longer reads `ATTR`
/// over a mode-2 file as format-spec/08-attributes.md specifies.
#[test]
fn displaced_attr_v1_2_decodes_to_its_test_vector() {
    let info = swm::inspect(DISPLACED_ATTR_V1_2, &Default::default()).unwrap();
    assert_eq!((info.version, info.mode), ((1, 2), swm::Mode::Displaced));
    assert_eq!(info.attributes.len(), 1);
    let m = swm::decode_attributed(DISPLACED_ATTR_V1_2, &DecodeOptions::default())
        .expect("golden file displaced-attr-v1.2.swm must decode");
    assert_eq!(
        attributed_hash(&m),
        DISPLACED_ATTR_V1_2_FNV1A64,
        "decoded mesh differs from format-spec/08-attributes.md's test vector"
    );
    let plain = swm::decode(DISPLACED_ATTR_V1_2, &DecodeOptions::default()).unwrap();
    assert_eq!(plain, m.mesh);
    // Cut to a coarser level: the mesh of that level, no streams.
    let cut = swm::cut_levels(
        DISPLACED_ATTR_V1_2,
        info.levels.len() - 1,
        &Default::default(),
    )
    .unwrap();
    let coarse = swm::decode_attributed(&cut, &DecodeOptions::default()).unwrap();
    assert!(coarse.streams.is_empty());
    assert!(coarse.mesh.triangles.len() * 4 == m.mesh.triangles.len());
}

/// FNV-1a 64 of the bytes today's encoder writes for the coloured
/// ellipsoid at [`golden_displaced_attr_options`]. The golden file itself
/// came from the encoder before bends (2026-12-07) and stays the
/// decoder's test vector; this pins the encoder (since bare bases and
/// passes searched from the last pass's file: 2,524 bytes, within 3% of
/// the 2,500 asked).
const DISPLACED_ATTR_V1_2_REENCODED_FNV1A64: u64 = 0x4E24_5D4F_A184_259D;

/// The encoder still writes the same bytes from the coloured ellipsoid:
/// a mode-2 file with `ATTR`, as the golden file.
#[test]
fn displaced_attr_v1_2_reencodes_to_the_same_bytes() {
    let encoded = swm::encode_attributed(
        &golden_coloured_ellipsoid(),
        &golden_displaced_attr_options(),
    )
    .unwrap();
    assert_eq!(
        (encoded.bytes.len(), fnv1a(FNV_OFFSET, &encoded.bytes)),
        (2524, DISPLACED_ATTR_V1_2_REENCODED_FNV1A64),
        "re-encoding the golden coloured ellipsoid no longer gives the pinned bytes"
    );
    let info = swm::inspect(&encoded.bytes, &Default::default()).unwrap();
    assert_eq!((info.version, info.mode), ((1, 2), swm::Mode::Displaced));
    assert_eq!(info.attributes.len(), 1);
}

/// The coloured ellipsoid coded by SwingWrapper at 2,500 bytes, colours
/// included (resampled at the retiled vertices; no post-processing hint).
fn golden_swing_attr_options() -> EncodeOptions {
    EncodeOptions {
        mode: EncodeMode::Swing {
            target: swm::SwingTarget::Bytes(2500),
            angle_bits: None,
            max_bytes: None,
        },
        ..EncodeOptions::default()
    }
}

const SWING_ATTR_V1_2: &[u8] = include_bytes!("../format-spec/golden/swing-attr-v1.2.swm");

/// The test vector of format-spec/08-attributes.md ("Golden file").
const SWING_ATTR_V1_2_FNV1A64: u64 = 0xD00E_F709_8C07_0DAD;

/// Writes the golden file (run once, by hand:
/// `SWM_WRITE_GOLDEN=1 cargo test --test golden -- --ignored write_swing_attr_v1_2_golden`).
#[test]
#[ignore]
fn write_swing_attr_v1_2_golden() {
    write_attributed_golden(
        "swing-attr-v1.2.swm",
        &golden_coloured_ellipsoid(),
        &golden_swing_attr_options(),
    );
}

/// Must hold forever: a failure means the decoder no longer reads `ATTR`
/// over a mode-1 file as format-spec/08-attributes.md specifies.
#[test]
fn swing_attr_v1_2_decodes_to_its_test_vector() {
    let info = swm::inspect(SWING_ATTR_V1_2, &Default::default()).unwrap();
    assert_eq!((info.version, info.mode), ((1, 2), swm::Mode::Swing));
    assert_eq!(info.attributes.len(), 1);
    assert_eq!(info.post, None, "no post-processing hint beside ATTR");
    let m = swm::decode_attributed(SWING_ATTR_V1_2, &DecodeOptions::default())
        .expect("golden file swing-attr-v1.2.swm must decode");
    assert_eq!(
        attributed_hash(&m),
        SWING_ATTR_V1_2_FNV1A64,
        "decoded mesh differs from format-spec/08-attributes.md's test vector"
    );
    assert_eq!(m.streams[0].value_count(), m.mesh.positions.len());
    let plain = swm::decode(SWING_ATTR_V1_2, &DecodeOptions::default()).unwrap();
    assert_eq!(plain, m.mesh);
}

/// The encoder still writes the golden bytes from the coloured ellipsoid.
#[test]
fn swing_attr_v1_2_reencodes_to_the_same_bytes() {
    let encoded =
        swm::encode_attributed(&golden_coloured_ellipsoid(), &golden_swing_attr_options()).unwrap();
    assert_eq!(
        encoded.bytes, SWING_ATTR_V1_2,
        "re-encoding the golden coloured ellipsoid no longer gives golden/swing-attr-v1.2.swm"
    );
}
