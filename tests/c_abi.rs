//! The C interface as a C viewer sees it (issue 9): the example program
//! `codec/ffi/examples/decode.c`, compiled against `include/swm.h` and the
//! static library, decodes to the counts `swm decode` reports (and, with
//! `--attributes`, to the split mesh and streams of the Rust API), and
//! fails with a non-zero status and a message on a damaged buffer.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn ffi_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../codec/ffi")
}

/// `libswm_ffi.a` from this build: cargo puts it beside the test binaries'
/// folder (`target/<profile>/`) when swm-ffi is built as a workspace
/// member, or in `deps/` with a hash when built only as a dependency.
fn static_library() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    let profile = deps.parent().unwrap();
    // The newest of `cargo build`'s copy and the test build's own: a copy
    // left by an earlier `cargo build -p swm-ffi` may be stale.
    let direct = profile.join("libswm_ffi.a");
    std::fs::read_dir(deps)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            name.starts_with("libswm_ffi") && name.ends_with(".a")
        })
        .chain(direct.exists().then_some(direct))
        .max_by_key(|p| p.metadata().and_then(|m| m.modified()).ok())
        .unwrap_or_else(|| panic!("no libswm_ffi.a under {}", profile.display()))
}

/// Compiles the example once per test binary.
fn example() -> &'static Path {
    static EXE: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    EXE.get_or_init(|| {
        let out = common::scratch("c_abi_build").join("decode");
        let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
        let status = Command::new(&cc)
            .args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-O1"])
            .arg(ffi_dir().join("examples/decode.c"))
            .arg("-I")
            .arg(ffi_dir().join("include"))
            .arg(static_library())
            // The decoder is all Rust (`cargo build -p swm-ffi` links
            // with these alone), but the test build's copy carries the
            // features the CLI asks for (cargo unifies them), and the
            // encoder's `fast` effort brings meshoptimizer's C++: its
            // runtime is named here for that copy only.
            .args(["-lpthread", "-ldl", "-lm", "-lstdc++", "-o"])
            .arg(&out)
            .status()
            .unwrap_or_else(|e| panic!("cannot run the C compiler `{cc}`: {e}"));
        assert!(status.success(), "compiling examples/decode.c failed");
        out
    })
}

/// `(vertices, triangles)` from `swm decode`'s summary line.
fn swm_decode_counts(file: &Path, extra: &[&str]) -> (u64, u64) {
    let obj = file.with_extension("obj");
    let mut args = vec![
        "decode",
        file.to_str().unwrap(),
        "-o",
        obj.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let line = common::ok(&common::swm(&args));
    let counts = line.split(": ").nth(1).unwrap();
    let n: Vec<u64> = counts
        .split(", ")
        .take(2)
        .map(|s| s.split(' ').next().unwrap().parse().unwrap())
        .collect();
    (n[0], n[1])
}

fn c_decode(file: &Path, extra: &[&str]) -> std::process::Output {
    Command::new(example())
        .arg(file)
        .args(extra)
        .output()
        .unwrap()
}

#[test]
fn c_example_decodes_to_the_cli_counts() {
    let dir = common::scratch("c_abi_counts");
    for (k, s) in common::samples().iter().enumerate() {
        let file = dir.join(format!("{k}.swm"));
        std::fs::write(&file, &s.bytes).unwrap();
        for (cli, c) in [
            (&[][..], &[][..]),
            (
                &["--sharpen", "--bend", "1"][..],
                &["--sharpen", "--bend", "1", "--normals"][..],
            ),
        ] {
            let (v, t) = swm_decode_counts(&file, cli);
            let out = c_decode(&file, c);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert!(
                out.status.success() && stderr.is_empty(),
                "{}: {stderr}",
                s.name
            );
            assert_eq!(
                String::from_utf8_lossy(&out.stdout).trim(),
                format!("vertices {v} triangles {t}"),
                "{} {cli:?}",
                s.name
            );
        }
    }
}

#[test]
fn c_example_reports_a_damaged_buffer() {
    let mut bytes = common::samples()[3].bytes.clone();
    let k = bytes.len() / 3;
    bytes[k] ^= 0x04;
    let file = common::scratch("c_abi_damaged").join("damaged.swm");
    std::fs::write(&file, &bytes).unwrap();
    let out = c_decode(&file, &[]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.starts_with("decode: error 2: ") && stderr.contains("checksum"),
        "{stderr}"
    );
    assert!(out.stdout.is_empty());
}

/// `--attributes`: the example's `swm_decode_attributed` gives the split
/// mesh and the streams of the Rust API's
/// `decode_attributed(..).split_vertices()`: an icosphere whose texture
/// coordinates follow the longitude, each corner with its own value (as
/// a soup of UVs comes), so every vertex splits per face around it.
#[test]
fn c_example_decodes_attribute_streams() {
    let mesh = swm_corpus::icosphere(1.0, 2);
    let mut uv = Vec::new();
    let mut corners = Vec::new();
    for t in &mesh.triangles {
        let mut c = [0u32; 3];
        let west = t.iter().any(|&v| mesh.positions[v as usize][1] < 0.0);
        for (k, &v) in t.iter().enumerate() {
            let [x, y, z] = mesh.positions[v as usize];
            let mut u = y.atan2(x) / std::f32::consts::TAU;
            // A face across the cut takes the values on its own side.
            if west && u < 0.0 || !west && u < -0.25 {
                u += 1.0;
            }
            c[k] = (uv.len() / 2) as u32;
            uv.extend([u, z * 0.5 + 0.5]);
        }
        corners.push(c);
    }
    let stream = swm::AttributeStream::new(swm::AttributeKind::TexCoord(0), 2, uv, corners);
    let options = swm::EncodeOptions {
        mode: swm::EncodeMode::Lossless { qp: 12 },
        ..Default::default()
    };
    let bytes = swm::encode_attributed(&swm::AttributedMesh::new(mesh, vec![stream]), &options)
        .unwrap()
        .bytes;
    let want = swm::decode_attributed(&bytes, &Default::default())
        .unwrap()
        .split_vertices();
    let plain = swm::decode(&bytes, &Default::default()).unwrap();
    let file = common::scratch("c_abi_attributes").join("uv.swm");
    std::fs::write(&file, &bytes).unwrap();
    let out = c_decode(&file, &["--attributes", "--normals"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && stderr.is_empty(), "{stderr}");
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        format!(
            "vertices {} triangles {}\nsplit vertices {} streams 1\nstream 2 0 2\n",
            plain.positions.len(),
            plain.triangles.len(),
            want.mesh.positions.len()
        )
    );
    assert!(want.mesh.positions.len() > plain.positions.len());
}
