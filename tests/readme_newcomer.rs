//! README.md as a newcomer reads it (issue 23, item 1): the Install
//! section names the package, binary and minimum Rust that the manifests
//! declare; the First steps commands run, as written, in a directory that
//! holds nothing but what they make (a clean checkout without the shared
//! corpus); and the "which mode" table covers every `--mode` value.

mod common;
use common::*;
use std::path::Path;
use std::process::Command;

fn readme() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md"))
        .expect("README.md")
}

/// The README section under `heading` (a `## ` line), up to the next one.
fn section(readme: &str, heading: &str) -> String {
    let start = readme
        .find(&format!("\n## {heading}\n"))
        .unwrap_or_else(|| panic!("README has no section {heading:?}"));
    let rest = &readme[start + 1..];
    let end = rest[3..].find("\n## ").map_or(rest.len(), |e| e + 3);
    rest[..end].to_string()
}

/// The value of `key = "..."` on the first line of `manifest` that sets it.
fn manifest_value(manifest: &str, key: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(manifest);
    let text = std::fs::read_to_string(&path).expect("manifest");
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with(&format!("{key} = \"")))
        .unwrap_or_else(|| panic!("{manifest} sets no {key}"));
    line.split('"').nth(1).expect("a quoted value").to_string()
}

#[test]
fn install_names_what_the_manifests_declare() {
    let install = section(&readme(), "Install");
    let rust = manifest_value("../Cargo.toml", "rust-version");
    // tools/Cargo.toml: the package's name comes first, the binary's second.
    let package = manifest_value("Cargo.toml", "name");
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml")).unwrap();
    let bin = text.split("[[bin]]").nth(1).expect("a [[bin]] table");
    let binary = bin.split('"').nth(1).expect("the binary's name");
    for needle in [
        format!("Rust {rust} or newer"),
        "cargo install --locked --path tools".to_string(),
        format!("package is `{package}`, the binary `{binary}`"),
        format!("target/release/{binary}"),
        "crates.io".to_string(),
    ] {
        let flat = |s: &str| s.split_whitespace().collect::<Vec<_>>().join(" ");
        assert!(
            flat(&install).contains(&flat(&needle)),
            "README Install should say {needle:?}:\n{install}"
        );
    }
}

/// The README's First steps block, run line by line: `cargo run -p
/// swm-corpus` through the library its binary calls (building a second
/// binary here would double the test's build), every `swm` line through
/// the binary this package builds.
#[test]
fn first_steps_run_as_written() {
    let steps = section(&readme(), "First steps");
    let block = steps
        .split("```sh\n")
        .nth(1)
        .and_then(|b| b.split("```").next())
        .expect("a sh block in First steps");
    let dir = scratch("readme-first-steps");
    let mut outputs = Vec::new();
    for line in block.lines() {
        let command = line.split('#').next().unwrap().trim();
        if command.is_empty() {
            continue;
        }
        if command == "cargo run --release -p swm-corpus" {
            // The binary's default output directory.
            let out = dir.join("corpus/generated");
            std::fs::create_dir_all(&out).unwrap();
            for (name, mesh) in swm_corpus::all() {
                swm_corpus::save_obj(&mesh, &out.join(format!("{name}.obj"))).unwrap();
            }
            continue;
        }
        let args: Vec<&str> = match command.strip_prefix("swm ") {
            Some(rest) => rest.split_whitespace().collect(),
            None => panic!("First steps has a line this test cannot run: {line:?}"),
        };
        let out = Command::new(env!("CARGO_BIN_EXE_swm"))
            .args(&args)
            .current_dir(&dir)
            .output()
            .expect("run swm");
        let stdout = ok(&out);
        assert!(!stdout.is_empty(), "`{command}` printed nothing");
        outputs.push((args[0].to_string(), stdout));
    }
    let printed = |sub: &str| -> &str {
        let found = outputs.iter().find(|(s, _)| s == sub);
        &found
            .unwrap_or_else(|| panic!("First steps runs no `swm {sub}`"))
            .1
    };
    // What the prose after the block says of each output.
    let encode = printed("encode");
    assert!(encode.contains("\nmethod: swing "), "{encode}");
    let bytes: u64 = encode
        .split(": ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no byte count in {encode:?}"));
    assert!(
        (1000..=1250).contains(&bytes),
        "README says about 1.1 KB; the file has {bytes} bytes"
    );
    assert!(printed("info").contains("CLERS"));
    assert!(printed("decode").contains("triangles"));
    assert!(printed("distance").contains("1e-4 of the diagonal"));
    assert!(dir.join("double-torus.ply").is_file());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_mode_table_covers_every_mode() {
    let install = section(&readme(), "Install");
    // clap lists the accepted values when it refuses one.
    let refused = swm(&["encode", "in.obj", "-o", "x.swm", "--mode", "none"]);
    let err = String::from_utf8_lossy(&refused.stderr).to_string();
    let values = err
        .split("[possible values: ")
        .nth(1)
        .and_then(|s| s.split(']').next())
        .unwrap_or_else(|| panic!("no possible values in {err:?}"));
    let modes: Vec<&str> = values.split(", ").collect();
    assert!(modes.len() >= 3, "{modes:?}");
    for mode in modes {
        let cell = format!("| `--mode {mode}");
        assert!(install.contains(&cell), "the mode table has no {cell}");
    }
}

/// The README's test command is the one `.ci/run` runs, and it ends with
/// the skip count that the skip helper feeds (issue 48, item 1).
#[test]
fn the_test_command_is_what_ci_runs_and_counts_skips() {
    let readme = readme();
    let at = readme
        .find("Run all tests:")
        .expect("README says how to run all tests");
    let block = readme[at..]
        .split("```")
        .nth(1)
        .expect("a code block after it");
    let command = block.trim_start_matches("sh").trim();
    assert_eq!(command, "tests/run", "README's test command");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let ci = std::fs::read_to_string(root.join(".ci/run")).expect(".ci/run");
    assert!(
        ci.lines().any(|l| l.trim() == command),
        ".ci/run should run {command:?} as a line of its own"
    );
    assert!(ci.contains("export SWM_CI=1"), ".ci/run makes skips fatal");
    let run = std::fs::read_to_string(root.join(command)).expect("tests/run");
    assert!(
        run.contains("cargo test --workspace"),
        "{command} runs cargo test"
    );
    assert!(run.contains("SWM_SKIP_LOG"), "{command} reads the skip log");
}

/// A skip through the helper reaches the log `tests/run` counts, and
/// names the test that skipped.
#[test]
fn a_skip_is_logged_with_its_test() {
    let log = common::scratch("skip-log").join("skips.log");
    // A child process of this very test binary, running only the helper
    // test below, with the log pointed elsewhere so a run's own log holds
    // no entry for it; under SWM_CI=1 the skip fails it instead.
    let exe = std::env::current_exe().unwrap();
    for (ci, expect_ok) in [("0", true), ("1", false)] {
        let out = Command::new(&exe)
            .args(["--exact", "skip_helper_child"])
            .env("SWM_SKIP_LOG", &log)
            .env("SWM_SKIP_CHILD", "1")
            .env("SWM_CI", ci)
            .output()
            .unwrap();
        assert_eq!(out.status.success(), expect_ok, "SWM_CI={ci}: {out:?}");
    }
    let text = std::fs::read_to_string(&log).unwrap();
    assert_eq!(
        text,
        "skipped: readme_newcomer::skip_helper_child: nothing to test here\n"
    );
}

/// Not a test of its own: skips only when `a_skip_is_logged_with_its_test`
/// runs it (`SWM_SKIP_CHILD`), and passes doing nothing otherwise.
#[test]
fn skip_helper_child() {
    if std::env::var_os("SWM_SKIP_CHILD").is_some() {
        common::skip("nothing to test here");
    }
}
