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
            entries.push(serde_json::json!({
                "name": name,
                "mode": mode,
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
        &["--test", "--test-reporter=spec", "test/node.test.mjs"],
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
