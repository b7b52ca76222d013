//! The web front door (issue 24): builds `web/`'s WebAssembly package
//! (`npm run build`: cargo for wasm32, then wasm-opt) and runs its Node
//! test and its headless-Chromium test (`web/test/`) on `.swm` files of
//! every mode, which must decode bit for bit as `swm decode` decodes them;
//! and type-checks the TypeScript declarations.
//!
//! Needs Node with `npm ci` done in `web/`, the `wasm32-unknown-unknown`
//! Rust target and, for the browser test, Chromium (`/usr/bin/chromium`
//! or `$SWM_CHROMIUM`); `.ci/setup-web` installs them all. Without them
//! the tests report a skip (`common::skip`: on the terminal and in
//! `tests/run`'s summary) and pass, unless `SWM_CI=1`.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

fn web_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../web")
}

/// Whether a toolchain piece is present; reports the skip (a failure
/// under `SWM_CI=1`) when it is not.
fn present(found: bool, what: &str, how: &str) -> bool {
    if !found {
        common::skip(&format!("{what} not found ({how})"));
    }
    found
}

fn node_ready() -> bool {
    let node = Command::new("node").arg("--version").output();
    present(
        node.is_ok_and(|o| o.status.success()),
        "node",
        "apt-get install nodejs, or .ci/setup-web",
    ) && present(
        web_dir().join("node_modules/binaryen").is_dir(),
        "web/node_modules",
        "run `npm ci` in web/, or .ci/setup-web",
    ) && present(
        wasm_target_installed(),
        "the wasm32-unknown-unknown Rust target",
        "rustup target add wasm32-unknown-unknown",
    )
}

fn wasm_target_installed() -> bool {
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    Command::new(rustc)
        .args(["--print", "sysroot"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| {
            Path::new(String::from_utf8_lossy(&o.stdout).trim())
                .join("lib/rustlib/wasm32-unknown-unknown/lib")
                .is_dir()
        })
        .unwrap_or(false)
}

fn chromium() -> Option<PathBuf> {
    let path = std::env::var_os("SWM_CHROMIUM")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/usr/bin/chromium"));
    present(
        path.is_file(),
        "chromium",
        "apt-get install chromium, or set SWM_CHROMIUM",
    )
    .then_some(path)
}

/// Runs a command in `web/`, failing the test with its output unless it
/// succeeds; returns its stdout.
fn run_in_web(program: &str, args: &[&str], cases: Option<&Path>) -> String {
    let mut command = Command::new(program);
    command.args(args).current_dir(web_dir());
    if let Some(dir) = cases {
        command.env("SWM_WEB_CASES", dir);
    }
    let out = command
        .output()
        .unwrap_or_else(|e| panic!("cannot run {program}: {e}"));
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{program} {args:?} failed: {}\n--- stdout\n{stdout}\n--- stderr\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    stdout
}

/// `npm run build` once per test binary: cargo is incremental and the
/// build script skips wasm-opt when its output is newer.
fn build() {
    static BUILT: OnceLock<()> = OnceLock::new();
    BUILT.get_or_init(|| {
        run_in_web("node", &["scripts/build.mjs"], None);
    });
}

/// The test files: every sample `common::samples` encodes (lossless, with
/// a hole and with handles; swing, with `HOLE` and with `REST`) and the
/// golden files, each with what `swm decode` writes for it (PLY, PLY after
/// `--sharpen --bend 1`, PLY after `--max-level 1`, GLB for the normals), and a damaged file with the
/// message `swm decode` gives for it. Made once per test binary, in a
/// scratch folder or the one `SWM_WEB_CASES_OUT` names (`npm test` in
/// `web/` asks for `web/test/cases/` through `web_cases_are_made`).
fn cases() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = match std::env::var_os("SWM_WEB_CASES_OUT") {
            Some(dir) => {
                let dir = PathBuf::from(dir);
                let _ = std::fs::remove_dir_all(&dir);
                std::fs::create_dir_all(&dir).expect("create SWM_WEB_CASES_OUT");
                dir
            }
            None => common::scratch("web_cases"),
        };
        let mut files: Vec<(String, Vec<u8>)> = common::samples()
            .iter()
            .map(|s| (s.name.replace([' ', '+'], "-"), s.bytes.clone()))
            .collect();
        for name in [
            "lossless-v1.0",
            "swing-v1.0",
            "swing-v1.1",
            "swing-front-v1.1",
            "lossless-compact-v1.1",
            "lossless-dense-v1.1",
            "displaced-v1.2",
        ] {
            let path = Path::new(env!("CARGO_MANIFEST_DIR"))
                .join(format!("../format-spec/golden/{name}.swm"));
            files.push((format!("golden-{name}"), std::fs::read(path).unwrap()));
        }
        let mut entries = Vec::new();
        for (name, bytes) in &files {
            let swm = dir.join(format!("{name}.swm"));
            std::fs::write(&swm, bytes).unwrap();
            let decode = |out: &str, extra: &[&str]| {
                let mut args = vec!["decode", swm.to_str().unwrap(), "-o"];
                let out = dir.join(out);
                args.push(out.to_str().unwrap());
                args.extend_from_slice(extra);
                common::ok(&common::swm(&args));
            };
            decode(&format!("{name}.ply"), &[]);
            decode(&format!("{name}.sb.ply"), &["--sharpen", "--bend", "1"]);
            decode(&format!("{name}.glb"), &[]);
            let header = swm::container::parse_container(bytes, &swm::Limits::default())
                .unwrap()
                .header;
            let mode = match header.mode {
                swm::Mode::Lossless => "lossless",
                swm::Mode::Displaced => "displaced",
                _ => "swing",
            };
            // A displaced file cut at its first level, as `--max-level 1`
            // decodes it (other modes ignore the option: the plain PLY).
            decode(&format!("{name}.l1.ply"), &["--max-level", "1"]);
            // Attribute streams the file holds (a displaced file's `ATTR`).
            let streams = swm::decode_attributed(bytes, &Default::default())
                .unwrap()
                .streams
                .len();
            entries.push(serde_json::json!({
                "name": name,
                "mode": mode,
                "streams": streams,
                "version": format!("{}.{}", header.major, header.minor),
                "swm": format!("{name}.swm"),
                "ply": format!("{name}.ply"),
                "sharpened_ply": format!("{name}.sb.ply"),
                "level1_ply": format!("{name}.l1.ply"),
                "glb": format!("{name}.glb"),
            }));
        }
        // One flipped bit in the middle of a swing file: the checksum
        // catches it, and the message names the byte.
        let (_, bytes) = files.iter().find(|(n, _)| n == "swing-HOLE-LOOP").unwrap();
        let mut damaged = bytes.clone();
        let middle = damaged.len() / 2;
        damaged[middle] ^= 0x10;
        let corrupt = dir.join("damaged.swm");
        std::fs::write(&corrupt, &damaged).unwrap();
        let out = common::swm(&[
            "decode",
            corrupt.to_str().unwrap(),
            "-o",
            dir.join("damaged.ply").to_str().unwrap(),
        ]);
        assert!(!out.status.success(), "the damaged file decoded");
        let stderr = String::from_utf8_lossy(&out.stderr);
        let prefix = format!("swm: error: {}: ", corrupt.display());
        let message = stderr
            .trim_end()
            .strip_prefix(&prefix)
            .unwrap_or_else(|| panic!("unexpected error line: {stderr}"));
        let manifest = serde_json::json!({
            "cases": entries,
            "corrupt": { "swm": "damaged.swm", "message": message },
            "attributed": attributed_case(&dir),
            "scene": scene_case(&dir),
        });
        std::fs::write(dir.join("manifest.json"), manifest.to_string()).unwrap();
        dir
    })
}

/// A lossless file with texture coordinates (a seam: every corner its
/// own value), normals and an RGBA colour set, and what the Rust API
/// decodes it to in the split form (`decode_attributed(..)
/// .split_vertices()`) as raw little-endian arrays, for the package to
/// match bit for bit.
fn attributed_case(dir: &Path) -> serde_json::Value {
    let mesh = swm_corpus::icosphere(1.0, 2);
    let tris = mesh.triangles.clone();
    let uv: Vec<f32> = tris
        .iter()
        .flatten()
        .flat_map(|&v| [mesh.positions[v as usize][0], mesh.positions[v as usize][2]])
        .collect();
    let uv_corners: Vec<[u32; 3]> = (0..tris.len() as u32)
        .map(|f| [3 * f, 3 * f + 1, 3 * f + 2])
        .collect();
    let normals: Vec<f32> = mesh.positions.iter().flatten().copied().collect();
    let colors: Vec<f32> = mesh
        .positions
        .iter()
        .flat_map(|p| [p[0] * 0.5 + 0.5, p[1] * 0.5 + 0.5, p[2] * 0.5 + 0.5, 1.0])
        .collect();
    let streams = vec![
        swm::AttributeStream::new(swm::AttributeKind::Normal, 3, normals, tris.clone()),
        swm::AttributeStream::new(swm::AttributeKind::TexCoord(0), 2, uv, uv_corners),
        swm::AttributeStream::new(swm::AttributeKind::Color(0), 4, colors, tris),
    ];
    let options = swm::EncodeOptions {
        mode: swm::EncodeMode::Lossless { qp: 12 },
        ..Default::default()
    };
    let bytes = swm::encode_attributed(&swm::AttributedMesh::new(mesh, streams), &options)
        .unwrap()
        .bytes;
    std::fs::write(dir.join("attributed.swm"), &bytes).unwrap();
    let want = swm::decode_attributed(&bytes, &Default::default())
        .unwrap()
        .split_vertices();
    let raw = |name: &str, words: Vec<[u8; 4]>| {
        std::fs::write(dir.join(name), words.concat()).unwrap();
        name.to_string()
    };
    let floats = |v: &[f32]| v.iter().map(|x| x.to_le_bytes()).collect::<Vec<_>>();
    let streams: Vec<serde_json::Value> = want
        .streams
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let (kind, set) = match s.kind {
                swm::AttributeKind::Normal => ("normal", 0),
                swm::AttributeKind::TexCoord(n) => ("texcoord", n),
                swm::AttributeKind::Color(n) => ("color", n),
                other => panic!("unexpected stream {other:?}"),
            };
            serde_json::json!({
                "kind": kind, "set": set, "dims": s.dims,
                "values": raw(&format!("attributed.{k}.f32"), floats(&s.values)),
            })
        })
        .collect();
    let indices = want
        .mesh
        .triangles
        .as_flattened()
        .iter()
        .map(|i| i.to_le_bytes());
    serde_json::json!({
        "swm": "attributed.swm",
        "positions": raw("attributed.positions.f32", floats(want.mesh.positions.as_flattened())),
        "indices": raw("attributed.indices.u32", indices.collect()),
        "streams": streams,
    })
}

/// A 16×16 RGB checker of 4-pixel cells as a PNG: zlib's stored
/// blocks (no compression), so that no image crate is needed.
fn checker_png() -> Vec<u8> {
    const SIDE: usize = 16;
    let mut raw = Vec::new();
    for y in 0..SIDE {
        raw.push(0); // filter: none
        for x in 0..SIDE {
            let light = (x / 4 + y / 4) % 2 == 0;
            raw.extend(if light {
                [230, 200, 120]
            } else {
                [40, 90, 160]
            });
        }
    }
    let crc32 = |bytes: &[u8]| {
        let mut c = !0u32;
        for &b in bytes {
            c ^= u32::from(b);
            for _ in 0..8 {
                c = if c & 1 == 1 {
                    (c >> 1) ^ 0xedb8_8320
                } else {
                    c >> 1
                };
            }
        }
        !c
    };
    let (mut a, mut b) = (1u32, 0u32);
    for &x in &raw {
        a = (a + u32::from(x)) % 65_521;
        b = (b + a) % 65_521;
    }
    // One stored block: the image is under 65,535 bytes.
    let len = raw.len() as u16;
    let mut zlib = vec![0x78, 0x01, 1];
    zlib.extend(len.to_le_bytes());
    zlib.extend((!len).to_le_bytes());
    zlib.extend(&raw);
    zlib.extend(((b << 16) | a).to_be_bytes());
    let mut ihdr = Vec::new();
    ihdr.extend((SIDE as u32).to_be_bytes());
    ihdr.extend((SIDE as u32).to_be_bytes());
    ihdr.extend([8, 2, 0, 0, 0]); // 8-bit RGB
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    for (kind, data) in [(b"IHDR", ihdr), (b"IDAT", zlib), (b"IEND", Vec::new())] {
        png.extend((data.len() as u32).to_be_bytes());
        let body = [&kind[..], &data].concat();
        png.extend(&body);
        png.extend(crc32(&body).to_be_bytes());
    }
    png
}

/// The BIN chunk and the bufferViews and accessors of a GLB being built:
/// one tightly packed bufferView per accessor.
#[derive(Default)]
struct SceneBuilder {
    bin: Vec<u8>,
    views: Vec<serde_json::Value>,
    accessors: Vec<serde_json::Value>,
}

impl SceneBuilder {
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        self.bin.resize(self.bin.len().div_ceil(4) * 4, 0);
        let mut v = serde_json::json!({ "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len() });
        if let Some(t) = target {
            v["target"] = t.into();
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    /// A float accessor of `dims` components (VEC3s with their bounds).
    fn floats(&mut self, values: &[f32], dims: usize) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|x| x.to_le_bytes()).collect();
        let v = self.view(&bytes, Some(34962));
        let ty = ["SCALAR", "VEC2", "VEC3", "VEC4"][dims - 1];
        let mut a = serde_json::json!({ "bufferView": v, "componentType": 5126, "count": values.len() / dims, "type": ty });
        if dims == 3 {
            let bound = |f: fn(f32, f32) -> f32, start: f32| {
                (0..3)
                    .map(|k| values.iter().skip(k).step_by(3).copied().fold(start, f))
                    .collect::<Vec<_>>()
            };
            a["min"] = bound(f32::min, f32::INFINITY).into();
            a["max"] = bound(f32::max, f32::NEG_INFINITY).into();
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    /// An unsigned-short index accessor.
    fn indices(&mut self, triangles: &[[u32; 3]]) -> usize {
        let bytes: Vec<u8> = triangles
            .iter()
            .flatten()
            .flat_map(|&i| u16::try_from(i).unwrap().to_le_bytes())
            .collect();
        let v = self.view(&bytes, Some(34963));
        self.accessors.push(serde_json::json!({ "bufferView": v, "componentType": 5123, "count": triangles.len() * 3, "type": "SCALAR" }));
        self.accessors.len() - 1
    }
}

/// A textured glTF scene (issue 47, item 5: the glTF plugin of `web/`)
/// and what the CLI makes of it: `scene.glb`, plain; `scene.swm.glb`,
/// `swm encode` with `SWM_mesh_compression` required;
/// `scene.fallback.glb`, the same with `--gltf-fallback`;
/// `scene.decoded.glb`, `swm decode` of the coded scene. The scene: a box
/// with per-face normals and UVs (24 vertices, seams) and a checker PNG
/// as its material's base colour texture, drawn by two nodes; a sphere
/// with normals, two UV sets and RGBA vertex colours under a transformed
/// parent; a torus of positions only (coded lossy, the others
/// losslessly).
fn scene_case(dir: &Path) -> serde_json::Value {
    use serde_json::json;
    let mut b = SceneBuilder::default();
    let mut primitives = Vec::new();
    // The box: per face, four corners n + s·u + t·v with u × v = n.
    let mut box_pos = Vec::new();
    let mut box_nrm = Vec::new();
    let mut box_uv = Vec::new();
    let mut box_tris: Vec<[u32; 3]> = Vec::new();
    let axes: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
        ([1., 0., 0.], [0., 1., 0.], [0., 0., 1.]),
        ([-1., 0., 0.], [0., 0., 1.], [0., 1., 0.]),
        ([0., 1., 0.], [0., 0., 1.], [1., 0., 0.]),
        ([0., -1., 0.], [1., 0., 0.], [0., 0., 1.]),
        ([0., 0., 1.], [1., 0., 0.], [0., 1., 0.]),
        ([0., 0., -1.], [0., 1., 0.], [1., 0., 0.]),
    ];
    for (f, (n, u, v)) in axes.iter().enumerate() {
        for (s, t) in [(-1., -1.), (1., -1.), (1., 1.), (-1., 1.)] {
            box_pos.extend((0..3).map(|k| 0.5 * (n[k] + s * u[k] + t * v[k])));
            box_nrm.extend(n);
            box_uv.extend([(s + 1.) / 2., (t + 1.) / 2.]);
        }
        let o = 4 * f as u32;
        box_tris.extend([[o, o + 1, o + 2], [o, o + 2, o + 3]]);
    }
    // The sphere and the torus, from the project's generated meshes.
    let ball = swm_corpus::icosphere(0.8, 3);
    let ball_pos: Vec<f32> = ball.positions.iter().flatten().copied().collect();
    let ball_nrm: Vec<f32> = ball_pos.iter().map(|x| x / 0.8).collect();
    let planar = |a: usize, b: usize| -> Vec<f32> {
        ball.positions
            .iter()
            .flat_map(|p| [0.5 + 0.6 * p[a], 0.5 + 0.6 * p[b]])
            .collect()
    };
    let ball_color: Vec<f32> = ball
        .positions
        .iter()
        .flat_map(|p| [0.6 + 0.4 * p[0], 0.6 + 0.4 * p[1], 0.6 + 0.4 * p[2], 1.0])
        .collect();
    let ring = swm_corpus::torus(1.0, 0.25, 48, 16);
    let ring_pos: Vec<f32> = ring.positions.iter().flatten().copied().collect();
    let p = b.floats(&box_pos, 3);
    let n = b.floats(&box_nrm, 3);
    let t = b.floats(&box_uv, 2);
    let i = b.indices(&box_tris);
    primitives.push(json!({ "attributes": { "POSITION": p, "NORMAL": n, "TEXCOORD_0": t }, "indices": i, "material": 0 }));
    let p = b.floats(&ball_pos, 3);
    let n = b.floats(&ball_nrm, 3);
    let t0 = b.floats(&planar(0, 1), 2);
    let t1 = b.floats(&planar(2, 1), 2);
    let c = b.floats(&ball_color, 4);
    let i = b.indices(&ball.triangles);
    primitives.push(json!({ "attributes": { "POSITION": p, "NORMAL": n, "TEXCOORD_0": t0, "TEXCOORD_1": t1, "COLOR_0": c }, "indices": i, "material": 0 }));
    let p = b.floats(&ring_pos, 3);
    let i = b.indices(&ring.triangles);
    primitives.push(json!({ "attributes": { "POSITION": p }, "indices": i, "material": 1 }));
    let image = b.view(&checker_png(), None);
    // A quarter turn about x.
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let doc = json!({
        "asset": { "version": "2.0", "generator": "swm tests/web.rs" },
        "scene": 0,
        "scenes": [{ "name": "table", "nodes": [0] }],
        "nodes": [
            { "name": "world", "children": [1, 2, 3, 5] },
            { "name": "crate", "mesh": 0, "translation": [-1.6, 0.0, 0.0], "rotation": [0.0, 0.258819, 0.0, 0.9659258] },
            { "name": "arm", "translation": [1.6, 0.0, 0.0], "scale": [0.75, 0.75, 0.75], "children": [4] },
            { "name": "ring", "mesh": 2, "translation": [0.0, -1.1, 0.0], "rotation": [h, 0.0, 0.0, h] },
            { "name": "ball", "mesh": 1, "translation": [0.0, 0.5, 0.0] },
            { "name": "small crate", "mesh": 0, "translation": [0.0, 1.1, 0.0], "scale": [0.5, 0.5, 0.5] }
        ],
        "meshes": [
            { "name": "crate", "primitives": [primitives[0]] },
            { "name": "ball", "primitives": [primitives[1]] },
            { "name": "ring", "primitives": [primitives[2]] }
        ],
        "materials": [
            { "name": "checker", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 }, "metallicFactor": 0.0, "roughnessFactor": 0.7 } },
            { "name": "red", "pbrMetallicRoughness": { "baseColorFactor": [0.9, 0.2, 0.15, 1.0], "metallicFactor": 0.0 } }
        ],
        "textures": [{ "sampler": 0, "source": 0 }],
        "samplers": [{ "magFilter": 9728, "minFilter": 9728, "wrapS": 10497, "wrapT": 10497 }],
        "images": [{ "bufferView": image, "mimeType": "image/png", "name": "checker" }],
        "accessors": b.accessors,
        "bufferViews": b.views,
        "buffers": [{ "byteLength": b.bin.len().div_ceil(4) * 4 }]
    });
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    std::fs::write(path("scene.glb"), common::glb(&doc, &b.bin)).unwrap();
    common::ok(&common::swm(&[
        "encode",
        &path("scene.glb"),
        "-o",
        &path("scene.swm.glb"),
    ]));
    common::ok(&common::swm(&[
        "encode",
        &path("scene.glb"),
        "-o",
        &path("scene.fallback.glb"),
        "--gltf-fallback",
    ]));
    common::ok(&common::swm(&[
        "decode",
        &path("scene.swm.glb"),
        "-o",
        &path("scene.decoded.glb"),
    ]));
    json!({
        "plain": "scene.glb",
        "coded": "scene.swm.glb",
        "fallback": "scene.fallback.glb",
        "decoded": "scene.decoded.glb",
    })
}

/// The test files are made, each named in the manifest and present (no
/// Node needed); `npm test` in `web/` runs this test to make its files.
#[test]
fn web_cases_are_made() {
    let dir = cases();
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("manifest.json")).unwrap()).unwrap();
    let cases = manifest["cases"].as_array().expect("a list of cases");
    let modes: std::collections::BTreeSet<_> = cases.iter().map(|c| c["mode"].as_str()).collect();
    assert_eq!(modes.len(), 3, "every mode: {modes:?}");
    for c in cases {
        for key in ["swm", "ply", "sharpened_ply", "level1_ply", "glb"] {
            let file = dir.join(c[key].as_str().unwrap());
            assert!(
                std::fs::metadata(&file).is_ok_and(|m| m.len() > 0),
                "{}",
                file.display()
            );
        }
    }
    assert!(dir
        .join(manifest["corrupt"]["swm"].as_str().unwrap())
        .is_file());
}

#[test]
fn node_package_decodes_as_the_cli() {
    if !node_ready() {
        return;
    }
    build();
    let out = run_in_web(
        "node",
        &[
            "--test",
            "--test-reporter=spec",
            "test/node.test.mjs",
            "test/gltf.test.mjs",
        ],
        Some(cases()),
    );
    println!("{out}");
}

/// The module's size that README.md gives ("the decoder compiled to
/// WebAssembly (NN KB gzipped)", KB of 1000 bytes, `gzip -9`) is within 5%
/// of what `npm run build` makes now, so that the figure follows the code.
#[test]
fn readme_gives_the_built_module_size() {
    if !node_ready() {
        return;
    }
    build();
    let readme = std::fs::read_to_string(web_dir().join("../README.md")).unwrap();
    let marker = "the decoder compiled to WebAssembly (";
    let at = readme.find(marker).expect("README gives the module's size") + marker.len();
    let figure: f64 = readme[at..]
        .split(" KB gzipped")
        .next()
        .and_then(|n| n.trim().parse().ok())
        .expect("a size in KB");
    let gzip = Command::new("gzip")
        .args(["-9c"])
        .arg(web_dir().join("dist/swm.wasm"))
        .output()
        .ok()
        .filter(|o| o.status.success());
    let Some(gzip) = gzip else {
        return common::skip("gzip not found");
    };
    let built = gzip.stdout.len() as f64 / 1000.0;
    assert!(
        (figure / built - 1.0).abs() <= 0.05,
        "README says {figure} KB gzipped, the build gives {built:.1} KB: update README.md and BENCHMARKS.md (\"Web\")"
    );
}

/// The hand-written TypeScript declarations accept the README's usage and
/// reject misuse (`web/test/types/usage.ts`, compiled with the lock
/// file's TypeScript, never run).
#[test]
fn typescript_declarations_check() {
    if !node_ready() {
        return;
    }
    let tsc = web_dir().join("node_modules/typescript/bin/tsc");
    assert!(
        tsc.is_file(),
        "{} missing: run `npm ci` in web/",
        tsc.display()
    );
    run_in_web("node", &[tsc.to_str().unwrap(), "-p", "test/types"], None);
}

#[test]
fn browser_page_decodes_and_shows_every_mode() {
    if !node_ready() {
        return;
    }
    let Some(chromium) = chromium() else {
        return;
    };
    build();
    let out = run_in_web(
        "node",
        &["test/browser.mjs", "--chromium", chromium.to_str().unwrap()],
        Some(cases()),
    );
    println!("{out}");
}
