//! The C interface as a C viewer sees it (issue 9): the example program
//! `codec/ffi/examples/decode.c`, compiled against `include/swm.h` and the
//! static library, decodes to the counts `swm decode` reports, and fails
//! with a non-zero status and a message on a damaged buffer.

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
