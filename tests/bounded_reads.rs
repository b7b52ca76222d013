//! Inputs that are not regular files, or longer than the input limit:
//! every command that reads a file refuses them at once with one line
//! naming the file, exit status 1, without reading (a symbolic link to
//! `/dev/zero` as `.obj`, `.ply` or `.swm` was once read until memory ran
//! out, and a FIFO blocked). Each run is address-space capped and stopped
//! after a deadline, so that a regression fails instead of hanging or
//! eating the machine's memory.
#![cfg(unix)]

mod common;
use common::*;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// 1 GiB of address space: plenty to refuse a file, far too little to read
/// `/dev/zero` into memory.
const CAP_KIB: u64 = 1 << 20;

/// Far beyond what refusing a file takes; only a hang reaches it.
const DEADLINE: Duration = Duration::from_secs(20);

/// Runs `swm args` capped to `CAP_KIB`, killed (and the test failed) if it
/// is still running after `DEADLINE`.
fn run(args: &[&str]) -> Output {
    let mut script = format!("ulimit -v {CAP_KIB}; exec \"$0\"");
    for i in 1..=args.len() {
        script.push_str(&format!(" \"${i}\""));
    }
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(env!("CARGO_BIN_EXE_swm"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run swm");
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > DEADLINE {
            let _ = child.kill();
            let _ = child.wait();
            panic!("swm {args:?} still running after {DEADLINE:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    child.wait_with_output().unwrap()
}

/// Checks that `swm args` failed with one line naming `file` and saying
/// `why`.
fn refused(args: &[&str], file: &Path, why: &str) {
    let out = run(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
    assert!(stderr.starts_with("swm: error:"), "{args:?}: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: {stderr}");
    let named = format!("swm: error: {}: ", file.to_str().unwrap());
    assert!(
        stderr.starts_with(&named),
        "{args:?}: not about {file:?}: {stderr}"
    );
    assert!(
        stderr.contains(why),
        "{args:?}: expected \"{why}\": {stderr}"
    );
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A small valid mesh and its `.swm` encoding in `dir`.
fn good_files(dir: &Path) -> (PathBuf, PathBuf) {
    let mesh = dir.join("good.obj");
    swm::io::write_mesh(&mesh, &swm_corpus::icosphere(1.0, 1)).unwrap();
    let bytes = swm::encode(
        &swm::io::read_mesh(&mesh).unwrap(),
        &swm::EncodeOptions {
            mode: swm::EncodeMode::Lossless { qp: 12 },
            ..Default::default()
        },
    )
    .unwrap()
    .bytes;
    let swm_file = dir.join("good.swm");
    std::fs::write(&swm_file, bytes).unwrap();
    (mesh, swm_file)
}

/// Every command that reads a file, with `bad` in each input position
/// (`mesh` fills the others), writing into `dir`.
fn every_reader<'a>(bad: &'a str, mesh: &'a str, dir: &'a Path, is_swm: bool) -> Vec<Vec<String>> {
    let out_mesh = s(&dir.join("out.obj")).to_owned();
    let out_swm = s(&dir.join("out.swm")).to_owned();
    let runs: Vec<Vec<&str>> = if is_swm {
        vec![vec!["info", bad], vec!["decode", bad, "-o", &out_mesh]]
    } else {
        vec![
            vec!["info", bad],
            vec!["encode", bad, "-o", &out_swm],
            vec!["encode", bad, "-o", &out_swm, "--mode", "lossless"],
            vec!["sharpen", bad, "-o", &out_mesh],
            vec!["distance", bad, mesh],
            vec!["distance", mesh, bad],
            vec!["rd", bad, "--rates", "1", "--configs", "lossless"],
        ]
    };
    let owned = |run: Vec<&str>| run.into_iter().map(str::to_owned).collect();
    runs.into_iter().map(owned).collect()
}

/// Runs every reader on `bad` and checks each refuses it for `why`,
/// writing nothing.
fn all_refuse(bad: &Path, mesh: &Path, is_swm: bool, why: &str) {
    let dir = bad.parent().unwrap();
    for args in every_reader(s(bad), s(mesh), dir, is_swm) {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&args, bad, why);
    }
    for out in ["out.obj", "out.swm"] {
        assert!(!dir.join(out).exists(), "{bad:?}: {out} was written");
    }
}

#[test]
fn dev_zero_is_refused_at_once_under_every_name() {
    let dir = scratch("bounded-zero");
    let (mesh, _) = good_files(&dir);
    for ext in ["obj", "ply", "off", "stl", "swm"] {
        let zero = dir.join(format!("zero.{ext}"));
        std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
        all_refuse(
            &zero,
            &mesh,
            ext == "swm",
            "a character device, not a regular file",
        );
    }
    // Named directly, too (`decode` reads its input as `.swm` whatever
    // its name).
    let out = dir.join("out.obj");
    let dev_zero = Path::new("/dev/zero");
    refused(
        &["decode", "/dev/zero", "-o", s(&out)],
        dev_zero,
        "a character device",
    );
    assert!(!out.exists());
}

#[test]
fn a_fifo_is_refused_without_waiting_for_a_writer() {
    let dir = scratch("bounded-fifo");
    let (mesh, _) = good_files(&dir);
    for ext in ["obj", "ply", "swm"] {
        let fifo = dir.join(format!("fifo.{ext}"));
        let made = Command::new("mkfifo").arg(&fifo).status();
        if !made.is_ok_and(|s| s.success()) {
            skip("mkfifo not found");
            return;
        }
        all_refuse(
            &fifo,
            &mesh,
            ext == "swm",
            "a FIFO (named pipe), not a regular file",
        );
        // Through a symbolic link, the target is judged.
        let link = dir.join(format!("link-to-fifo.{ext}"));
        std::os::unix::fs::symlink(&fifo, &link).unwrap();
        refused(&["info", s(&link)], &link, "a FIFO");
    }
}

#[test]
fn a_directory_is_refused() {
    let dir = scratch("bounded-dir");
    let (mesh, _) = good_files(&dir);
    for ext in ["obj", "swm"] {
        let sub = dir.join(format!("sub.{ext}"));
        std::fs::create_dir(&sub).unwrap();
        all_refuse(&sub, &mesh, ext == "swm", "a directory, not a regular file");
    }
}

#[test]
fn a_table_to_check_is_read_the_same_way() {
    let dir = scratch("bounded-table");
    let zero = dir.join("table.csv");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    refused(&["rd", "--check", s(&zero)], &zero, "a character device");
}

#[test]
fn decode_refuses_a_file_longer_than_max_input() {
    let dir = scratch("bounded-max-input");
    let (_, swm_file) = good_files(&dir);
    let len = std::fs::metadata(&swm_file).unwrap().len();
    let out = dir.join("out.obj");
    let exact = len.to_string();
    ok(&run(&[
        "decode",
        s(&swm_file),
        "-o",
        s(&out),
        "--max-input",
        &exact,
    ]));
    std::fs::remove_file(&out).unwrap();
    let less = (len - 1).to_string();
    let why = format!("at least {len} bytes, more than the input limit of {less}");
    refused(
        &["decode", s(&swm_file), "-o", s(&out), "--max-input", &less],
        &swm_file,
        &why,
    );
    assert!(!out.exists());
}

/// The default limit (16 GiB) refuses a longer file by its length, before
/// reading any of it: a sparse file costs nothing to make, and scanning
/// its zeros would take minutes.
#[test]
fn the_default_limit_refuses_a_huge_file_unread() {
    let dir = scratch("bounded-huge");
    for name in ["huge.obj", "huge.swm"] {
        let huge = dir.join(name);
        let file = std::fs::File::create(&huge).unwrap();
        if file.set_len(20 << 30).is_err() {
            skip("this file system has no 20 GiB sparse files");
            return;
        }
        let why = format!(
            "at least {} bytes, more than the input limit of {}",
            20u64 << 30,
            16u64 << 30
        );
        refused(&["info", s(&huge)], &huge, &why);
    }
}
