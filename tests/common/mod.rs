//! Helpers shared by the end-to-end tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;
use swm::{EncodeMode, EncodeOptions, SwingTarget, TriMesh};

/// The library's skip helper, the same file: every skip of every test goes
/// through [`skip`] (visible, logged for `tests/run`'s summary, fatal
/// under `SWM_CI=1`).
#[path = "../../codec/src/test_skip.rs"]
mod test_skip;
pub use test_skip::skip;

/// The shared reference corpus (`../shared/corpus` next to the repository),
/// or `None` after reporting the skip (a failure under `SWM_CI=1`).
pub fn shared_corpus() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/corpus");
    if dir.join("README.md").is_file() {
        Some(dir)
    } else {
        skip("../shared/corpus not found");
        None
    }
}

/// Whether a file name is that of an output's temporary file,
/// `.NAME.XXXXXX.tmp` (see `swm::io::write_mesh`).
pub fn is_temporary(name: &str) -> bool {
    name.starts_with('.') && name.ends_with(".tmp")
}

/// A fresh, empty scratch directory for one test.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("swm-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create scratch directory");
    dir
}

/// Runs the `swm` binary built by this package.
pub fn swm(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swm"))
        .args(args)
        .output()
        .expect("run swm")
}

/// Runs `swm` with its address space capped (in KiB), so that an attempt to
/// allocate what a lying header declares fails loudly instead of passing.
pub fn swm_capped(args: &[&str], max_kib: u64) -> Output {
    let mut script = format!("ulimit -v {max_kib}; exec \"$0\"");
    for i in 1..=args.len() {
        script.push_str(&format!(" \"${i}\""));
    }
    Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(env!("CARGO_BIN_EXE_swm"))
        .args(args)
        .output()
        .expect("run swm under ulimit")
}

/// Parses `swm ... --json` output, failing the test with stderr on error.
pub fn json(out: &Output) -> serde_json::Value {
    ok(out);
    serde_json::from_slice(&out.stdout).expect("valid JSON on stdout")
}

/// The stdout of a successful run, failing the test with stderr otherwise.
pub fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "swm failed: {}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Meshes of the shared corpus that the README lists as manifold, with the
/// counts it gives: (file, vertices, faces, components, boundary loops, genus).
pub const MANIFOLD_CORPUS: &[(&str, u64, u64, u64, u64, i64)] = &[
    ("fandisk.obj", 6475, 12946, 1, 0, 0),
    ("stanford-bunny.obj", 35947, 69451, 1, 5, 0),
    ("horse.ply", 48485, 96966, 1, 0, 0),
    ("spot.obj", 2930, 5856, 1, 0, 0),
    ("homer.obj", 6002, 12000, 1, 0, 0),
    ("cheburashka.obj", 6669, 13334, 1, 0, 0),
    ("alligator.obj", 3208, 5981, 1, 1, 0),
    ("woody.obj", 694, 1267, 1, 1, 0),
    ("bunny-1m.ply", 557164, 1111216, 1, 5, 0),
];

/// The non-manifold meshes of the shared corpus: (file, vertices, faces).
pub const NON_MANIFOLD_CORPUS: &[(&str, u64, u64)] = &[
    ("cow.obj", 2903, 5804),
    ("teapot.obj", 3241, 6320),
    ("suzanne.obj", 505, 968),
    ("beetle.obj", 1148, 2053),
];

/// A small valid `.swm` file.
#[derive(Clone, Debug)]
pub struct Sample {
    /// What kind of file it is.
    pub name: &'static str,
    /// The file.
    pub bytes: Vec<u8>,
}

/// A sphere of radius 1 without the faces whose centroid lies above
/// z = 0.6 or below z = −0.8: two boundary loops; the swing encoder
/// starts on the larger (`LOOP`, its fan dropped without a bit) and
/// closes the other with a patch it masks out again (`HOLE`).
pub fn capped_sphere() -> TriMesh {
    let m = swm_corpus::icosphere(1.0, 3);
    let keep = m
        .triangles
        .iter()
        .copied()
        .filter(|t| {
            let z = t.iter().map(|&v| m.positions[v as usize][2]).sum::<f32>() / 3.0;
            // Two caps: the larger hole starts the retiling (LOOP), the
            // smaller is masked over its patch (HOLE).
            z < 0.6 && z > -0.8
        })
        .collect();
    TriMesh::new(m.positions.clone(), keep)
}

/// A sphere and a far smaller one beside it: the small one is below the
/// edge length, so the swing encoder keeps it losslessly in `REST`.
pub fn sphere_and_speck() -> TriMesh {
    let a = swm_corpus::icosphere(1.0, 3);
    let b = swm_corpus::icosphere(1.0, 1);
    let mut m = a.clone();
    let base = m.positions.len() as u32;
    m.positions.extend(
        b.positions
            .iter()
            .map(|p| [p[0] * 0.02 + 3.0, p[1] * 0.02, p[2] * 0.02]),
    );
    m.triangles
        .extend(b.triangles.iter().map(|t| t.map(|v| v + base)));
    m
}

fn encode(mesh: &TriMesh, mode: EncodeMode) -> Vec<u8> {
    let options = EncodeOptions {
        mode,
        ..Default::default()
    };
    swm::encode(mesh, &options).expect("encode").bytes
}

fn swing(l: f64) -> EncodeMode {
    EncodeMode::Swing {
        target: SwingTarget::EdgeLength(l),
        angle_bits: Some(8),
        max_bytes: None,
    }
}

fn tag_present(bytes: &[u8], tag: &[u8; 4]) -> bool {
    let file = swm::container::parse_container(bytes, &swm::Limits::default()).unwrap();
    file.sections().any(|s| &s.tag.0 == tag)
}

/// Small files of every kind the encoder writes (lossless, with holes and
/// handles too, and dense: `CLRD` and `GEOF`; swing, with `HOLE` and
/// with `REST`), encoded once per test binary.
pub fn samples() -> &'static [Sample] {
    static SAMPLES: OnceLock<Vec<Sample>> = OnceLock::new();
    SAMPLES.get_or_init(|| {
        let lossless = encode(
            &swm_corpus::icosphere(1.0, 1),
            EncodeMode::Lossless { qp: 10 },
        );
        // Dummy vertices (one per hole) and handle events in TOPO.
        let mut open = swm_corpus::icosphere(1.0, 1);
        open.triangles.retain(|t| {
            t.iter()
                .map(|&v| open.positions[v as usize][2])
                .sum::<f32>()
                < 1.5
        });
        let lossless_hole = encode(&open, EncodeMode::Lossless { qp: 10 });
        let lossless_torus = encode(
            &swm_corpus::torus(1.0, 0.4, 8, 6),
            EncodeMode::Lossless { qp: 10 },
        );
        // Vertices about four grid steps apart, nearly all of valence 6:
        // the format 1.1 sections CLRD and GEOF.
        let lossless_dense = encode(
            &swm_corpus::icosphere(1.0, 3),
            EncodeMode::Lossless { qp: 6 },
        );
        assert!(
            tag_present(&lossless_dense, b"CLRD") && tag_present(&lossless_dense, b"GEOF"),
            "the dense icosphere has no CLRD or no GEOF section"
        );
        let swing_file = encode(&swm_corpus::torus(1.0, 0.4, 16, 8), swing(0.35));
        let hole = encode(&capped_sphere(), swing(0.3));
        let rest = encode(&sphere_and_speck(), swing(0.3));
        assert!(
            tag_present(&hole, b"HOLE") && tag_present(&hole, b"LOOP"),
            "the capped sphere has no HOLE or no LOOP section"
        );
        assert!(
            tag_present(&rest, b"REST"),
            "the two spheres have no REST section"
        );
        vec![
            Sample {
                name: "lossless",
                bytes: lossless,
            },
            Sample {
                name: "lossless with a hole",
                bytes: lossless_hole,
            },
            Sample {
                name: "lossless torus",
                bytes: lossless_torus,
            },
            Sample {
                name: "swing",
                bytes: swing_file,
            },
            Sample {
                name: "swing+HOLE+LOOP",
                bytes: hole,
            },
            Sample {
                name: "swing+REST",
                bytes: rest,
            },
            Sample {
                name: "lossless dense (CLRD, GEOF)",
                bytes: lossless_dense,
            },
            Sample {
                name: "displaced+ATTR",
                bytes: include_bytes!("../../format-spec/golden/displaced-attr-v1.2.swm").to_vec(),
            },
            Sample {
                name: "displaced with bends",
                bytes: include_bytes!("../../format-spec/golden/displaced-bend-v1.2.swm").to_vec(),
            },
            Sample {
                name: "displaced with a bare base",
                bytes: include_bytes!("../../format-spec/golden/displaced-bare-v1.2.swm").to_vec(),
            },
            Sample {
                name: "swing+ATTR",
                bytes: include_bytes!("../../format-spec/golden/swing-attr-v1.2.swm").to_vec(),
            },
        ]
    })
}

/// A GLB file (glTF 2.0 binary): the JSON chunk of `doc`, padded with
/// spaces, and a BIN chunk of `bin`, padded with zeros.
pub fn glb(doc: &serde_json::Value, bin: &[u8]) -> Vec<u8> {
    let mut json = serde_json::to_vec(doc).unwrap();
    json.resize(json.len().div_ceil(4) * 4, b' ');
    let mut bin = bin.to_vec();
    bin.resize(bin.len().div_ceil(4) * 4, 0);
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out
}

/// A valid file in the other framing (format-spec/01-container.md): the
/// same header fields and sections, the header's framing flag changed.
pub fn reframed(bytes: &[u8], framing: swm::Framing) -> Vec<u8> {
    let file = swm::container::parse_container(bytes, &Default::default()).unwrap();
    let sections: Vec<(swm::container::Tag, &[u8])> =
        file.sections().map(|s| (s.tag, s.bytes)).collect();
    swm::container::write_container(&file.header.with_framing(framing), &sections).unwrap()
}

/// Every sample in both framings: as the encoder writes it (compact) and
/// in the fixed framing of format 1.0.
pub fn samples_in_both_framings() -> &'static [Sample] {
    static BOTH: OnceLock<Vec<Sample>> = OnceLock::new();
    BOTH.get_or_init(|| {
        let mut all = samples().to_vec();
        for s in samples() {
            let name: &'static str = Box::leak(format!("{} (fixed framing)", s.name).into());
            all.push(Sample {
                name,
                bytes: reframed(&s.bytes, swm::Framing::Fixed),
            });
        }
        all
    })
}

/// A file's frame taken apart so that tests can make it lie: counts,
/// section count and lengths are written as given, in the file's own
/// framing, over the same payloads, with a fresh CRC.
#[derive(Clone, Debug)]
pub struct Frame {
    pub header: swm::container::Header,
    /// Vertex, triangle and component counts.
    pub counts: [u64; 3],
    /// The section count written (may differ from `entries.len()`).
    pub count: u64,
    /// Each entry's tag and written length.
    pub entries: Vec<(swm::container::Tag, u64)>,
    /// All payloads, back to back.
    pub payload: Vec<u8>,
}

/// The compact framing's registered tags, code k at index k - 1.
const CODES: [&[u8; 4]; 9] = [
    b"HEAD", b"CLRS", b"TOPO", b"GEOM", b"HOLE", b"REST", b"DENS", b"CLRF", b"meta",
];

impl Frame {
    pub fn of(bytes: &[u8]) -> Frame {
        let file = swm::container::parse_container(bytes, &Default::default()).unwrap();
        let h = file.header;
        Frame {
            header: h,
            counts: [h.vertex_count, h.triangle_count, h.component_count].map(u64::from),
            count: file.section_count() as u64,
            entries: file
                .sections()
                .map(|s| (s.tag, s.bytes.len() as u64))
                .collect(),
            payload: file.sections().flat_map(|s| s.bytes.to_vec()).collect(),
        }
    }

    pub fn compact(&self) -> bool {
        self.header.framing() == swm::Framing::Compact
    }

    pub fn bytes(&self) -> Vec<u8> {
        let mut b = Vec::new();
        let h = &self.header;
        b.extend_from_slice(b"SWM\0");
        b.extend_from_slice(&[h.major, h.minor]);
        b.extend_from_slice(&h.flags.to_le_bytes());
        b.push(h.mode.code());
        let varu = |b: &mut Vec<u8>, mut v: u64| {
            while v >= 0x80 {
                b.push(v as u8 | 0x80);
                v >>= 7;
            }
            b.push(v as u8);
        };
        if self.compact() {
            for c in self.counts {
                varu(&mut b, c);
            }
            varu(&mut b, self.count);
            for (tag, len) in &self.entries {
                match CODES.iter().position(|c| **c == tag.0) {
                    Some(k) => b.push(k as u8 + 1),
                    None => {
                        b.push(0);
                        b.extend_from_slice(&tag.0);
                    }
                }
                varu(&mut b, *len);
            }
        } else {
            for c in self.counts {
                b.extend_from_slice(&(c as u32).to_le_bytes());
            }
            b.extend_from_slice(&(self.count as u16).to_le_bytes());
            for (tag, len) in &self.entries {
                b.extend_from_slice(&tag.0);
                b.extend_from_slice(&(*len as u32).to_le_bytes());
            }
        }
        b.extend_from_slice(&self.payload);
        let crc = swm::container::crc32(&b);
        b.extend_from_slice(&crc.to_le_bytes());
        b
    }
}
