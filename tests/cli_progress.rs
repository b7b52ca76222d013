//! Progress (issue 23, item 2): `swm encode` and `swm rd` draw a spinner
//! or a bar on stderr when it is a terminal and the run takes over a
//! second, and nothing otherwise: not with stderr piped (as here, and in
//! every script), not with `--quiet`, never on stdout, and `--json` stays
//! JSON alone.
//!
//! The runs here set `SWM_PROGRESS_DELAY_MS=0`, so a bar that ignored
//! the pipe would be drawn at once, however fast the machine. Where
//! `script` (util-linux) gives a pseudo-terminal, the same runs on it show
//! the progress, and do not with `--quiet`: the pipe tests are not
//! passing for want of a bar.

mod common;
use common::*;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Progress may appear at once: the tests do not depend on how long a
/// run takes.
const NO_DELAY: (&str, &str) = ("SWM_PROGRESS_DELAY_MS", "0");

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A double torus of 20,000 triangles at 8 bits per vertex in the swing
/// mode: several retilings and the check, about three seconds in a debug
/// build (which this workspace optimizes), well over one in a release
/// one.
fn long_encode(dir: &Path) -> (PathBuf, Vec<String>) {
    let input = dir.join("double-torus.obj");
    let mesh = swm_corpus::double_torus(64);
    swm::io::write_mesh(&input, &mesh).unwrap();
    let output = dir.join("double-torus.swm");
    let args = [
        "encode",
        s(&input),
        "-o",
        s(&output),
        "--mode",
        "swing",
        "--bpv",
        "8",
    ];
    let args = args.map(String::from).to_vec();
    (output, args)
}

/// An rd run of a few cells on generated meshes, over a second.
fn long_rd() -> Vec<String> {
    [
        "rd",
        "generated:double-torus",
        "generated:torus",
        "--rates",
        "2,8",
        "--configs",
        "lossless,swing",
        "--samples",
        "20000",
    ]
    .map(String::from)
    .to_vec()
}

/// Runs swm with stdout and stderr piped and no delay before progress.
fn piped(args: &[String]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swm"))
        .args(args)
        .env(NO_DELAY.0, NO_DELAY.1)
        .output()
        .unwrap()
}

/// No trace of a progress line: no carriage return or escape sequence,
/// no spinner (Braille) or bar character, no `[hh:mm:ss]` elapsed time.
fn assert_no_progress(what: &str, bytes: &[u8]) {
    let text = String::from_utf8_lossy(bytes);
    assert!(!text.contains('\r'), "{what}: a carriage return: {text:?}");
    assert!(!text.contains('\x1b'), "{what}: an escape: {text:?}");
    let drawn =
        |c: char| ('\u{2800}'..='\u{28ff}').contains(&c) || ('\u{2580}'..='\u{259f}').contains(&c);
    assert!(
        !text.chars().any(drawn),
        "{what}: a spinner or bar character: {text:?}"
    );
    assert!(!text.contains("[00:0"), "{what}: an elapsed time: {text:?}");
    assert!(
        !text.contains("swm encode [") && !text.contains("swm rd ["),
        "{what}: a progress prefix: {text:?}"
    );
}

#[test]
fn encode_with_stderr_piped_draws_no_progress() {
    let dir = scratch("progress-encode");
    let (output, args) = long_encode(&dir);
    for extra in [
        &[][..],
        &["--json"][..],
        &["--quiet"][..],
        &["-q", "--json"][..],
    ] {
        let mut args = args.clone();
        args.extend(extra.iter().map(|a| a.to_string()));
        let out = piped(&args);
        let stdout = ok(&out);
        assert_no_progress("stdout", &out.stdout);
        assert_no_progress("stderr", &out.stderr);
        assert!(output.is_file());
        if extra.contains(&"--json") {
            let v: serde_json::Value = serde_json::from_str(&stdout).expect("JSON alone");
            assert!(v["bytes"].as_u64().unwrap() > 0, "{v}");
        } else {
            assert!(stdout.contains(" -> "), "{stdout}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn rd_with_stderr_piped_draws_no_progress() {
    for extra in [&[][..], &["--json"][..], &["--quiet", "--json"][..]] {
        let mut args = long_rd();
        args.extend(extra.iter().map(|a| a.to_string()));
        let out = piped(&args);
        let stdout = ok(&out);
        assert_no_progress("stdout", &out.stdout);
        assert_no_progress("stderr", &out.stderr);
        if extra.contains(&"--json") {
            let v: serde_json::Value = serde_json::from_str(&stdout).expect("JSON alone");
            assert_eq!(v.as_array().map(Vec::len), Some(8), "{v}");
        } else {
            assert_eq!(stdout.lines().count(), 8, "{stdout}");
        }
    }
}

/// `--quiet` and `-q` are options of `encode` and `rd`, and of no other
/// subcommand, and take no value.
#[test]
fn quiet_is_accepted_by_encode_and_rd() {
    let dir = scratch("progress-quiet");
    let input = dir.join("torus.obj");
    swm::io::write_mesh(&input, &swm_corpus::torus(1.0, 0.35, 24, 8)).unwrap();
    let output = dir.join("torus.swm");
    for quiet in ["--quiet", "-q"] {
        let out = swm(&[
            "encode",
            s(&input),
            "-o",
            s(&output),
            quiet,
            "--mode",
            "lossless",
        ]);
        ok(&out);
        let out = swm(&[
            "rd",
            s(&input),
            "--rates",
            "8",
            "--configs",
            "lossless",
            "--samples",
            "100",
            quiet,
        ]);
        ok(&out);
    }
    let out = swm(&["info", s(&input), "--quiet"]);
    assert_eq!(out.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs `command` (a shell command line) under a pseudo-terminal made by
/// `script`, which passes on its exit status (`-e`).
fn script(command: &str) -> std::io::Result<Output> {
    Command::new("script")
        .args(["-qec", command, "/dev/null"])
        .env("TERM", "xterm")
        .env(NO_DELAY.0, NO_DELAY.1)
        .output()
}

/// Whether `script` is here and can make a pseudo-terminal: it runs
/// `true` under one. Only this probe decides a skip.
fn pseudo_terminal() -> bool {
    script("true").is_ok_and(|o| o.status.success())
}

/// Runs swm under a pseudo-terminal made by `script`, whose output is
/// what the terminal showed (stdout and stderr together). A failing swm
/// fails the test (`pseudo_terminal` said `script` works).
fn on_terminal(args: &[String]) -> String {
    let mut command = String::from("exec");
    for a in std::iter::once(env!("CARGO_BIN_EXE_swm")).chain(args.iter().map(String::as_str)) {
        command.push_str(&format!(" '{}'", a.replace('\'', r"'\''")));
    }
    let out = script(&command).expect("run script");
    let shown = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "swm {args:?} failed on a terminal ({}):\n{shown}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    shown
}

/// The control: on a terminal the same long runs show their progress
/// (prefix, elapsed time, phase or count), and with `--quiet` they do
/// not.
#[test]
fn a_terminal_shows_progress_unless_quiet() {
    if !pseudo_terminal() {
        return skip("no pseudo-terminal (`script -qec true /dev/null` failed)");
    }
    let dir = scratch("progress-terminal");
    let (_, encode) = long_encode(&dir);
    for (args, prefix, detail) in [
        (encode, "swm encode [00:00:0", "encoding"),
        (long_rd(), "swm rd [00:00:0", "/8 cells"),
    ] {
        let shown = on_terminal(&args);
        assert!(shown.contains(prefix), "{args:?}: {shown:?}");
        assert!(shown.contains(detail), "{args:?}: {shown:?}");
        let mut quiet = args.clone();
        quiet.push("--quiet".into());
        let shown = on_terminal(&quiet);
        // The terminal turns "\n" into "\r\n": only the progress marks.
        let shown = shown.replace("\r\n", "\n");
        assert_no_progress(&format!("{quiet:?}"), shown.as_bytes());
    }
    let _ = std::fs::remove_dir_all(&dir);
}
