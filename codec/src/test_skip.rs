//! Skipped tests, made visible and, under CI, fatal (issue 48).
//!
//! A test that cannot run here (no `../shared/corpus`, no `mkfifo`, no
//! Python environment, ...) calls [`skip`] and returns. cargo hides what a
//! passing test prints, so a bare `println!("skipped: ...")` never shows:
//! [`skip`] writes its line to the terminal past cargo's capture and
//! appends it to a log that `tests/run` (the README's test command)
//! counts and prints at the end of the run. With `SWM_CI=1`, as `.ci/run`
//! sets, it panics instead: CI installs everything the tests need, so a
//! skip there means something is missing.
//!
//! This one file serves the library's unit tests (`mod test_skip` in
//! `lib.rs`) and the end-to-end tests (`tests/common/mod.rs` includes it
//! by path), so both skip the same way.
#![allow(dead_code)]

extern crate std;

use std::io::Write;
use std::path::PathBuf;
use std::string::{String, ToString};

/// The log a skip is appended to: `$SWM_SKIP_LOG` when set (`tests/run`
/// sets it), else `swm-skipped.log` in cargo's profile folder
/// (`target/debug/`), found from the test binary's own path
/// (`target/debug/deps/NAME-HASH`), so that `CARGO_TARGET_DIR` is
/// followed.
pub fn skip_log() -> Option<PathBuf> {
    if let Some(path) = std::env::var_os("SWM_SKIP_LOG") {
        return Some(PathBuf::from(path));
    }
    let exe = std::env::current_exe().ok()?;
    Some(exe.parent()?.parent()?.join("swm-skipped.log"))
}

/// The test calling: its binary (without cargo's hash) and its name.
fn who() -> String {
    let binary = std::env::current_exe()
        .ok()
        .and_then(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .map(|stem| match stem.rsplit_once('-') {
            Some((name, hash)) if hash.chars().all(|c| c.is_ascii_hexdigit()) => name.to_string(),
            _ => stem,
        })
        .unwrap_or_else(|| "?".into());
    let thread = std::thread::current();
    match thread.name() {
        Some(name) if name != "main" => std::format!("{binary}::{name}"),
        _ => binary,
    }
}

/// Reports that the calling test skips (part of) its work for want of
/// what `reason` names; the caller then returns. Panics instead under
/// `SWM_CI=1`.
pub fn skip(reason: &str) {
    let who = who();
    if std::env::var("SWM_CI").as_deref() == Ok("1") {
        panic!("{who}: {reason}; SWM_CI=1 makes a skipped test a failure");
    }
    let line = std::format!("skipped: {who}: {reason}\n");
    // `io::stderr()` itself, not `eprintln!`: the test harness captures
    // the macros' output, not the stream.
    let _ = std::io::stderr().write_all(line.as_bytes());
    if let Some(path) = skip_log() {
        // One `write` of one line in append mode: lines of tests running
        // at once, in one or several binaries, do not interleave.
        let file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path);
        if let Ok(mut file) = file {
            let _ = file.write_all(line.as_bytes());
        }
    }
}
