//! No lost output: `swm encode`, `decode` and `sharpen` write through a
//! temporary file and a rename, so a failing run leaves neither a partial
//! output nor a temporary file behind, keeps an existing output as it
//! was, and a command never overwrites its own input (whatever its name:
//! another spelling, a symbolic link, a hard link). The temporary file is
//! created exclusively under an unpredictable name, so symbolic links
//! planted where it or the output will be are never followed; SIGINT and
//! SIGTERM remove it and exit 130 and 143.

mod common;
use common::*;
use std::path::{Path, PathBuf};

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Runs `swm args` and checks it fails with one error line naming `file`.
fn fails(args: &[&str], file: &Path) -> String {
    let out = swm(args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
    assert!(stderr.starts_with("swm: error:"), "{args:?}: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: {stderr}");
    assert!(
        stderr.contains(s(file)),
        "{args:?}: does not name {file:?}: {stderr}"
    );
    stderr
}

/// A valid small mesh file and its `.swm` encoding in `dir`.
fn good_files(dir: &Path) -> (PathBuf, PathBuf) {
    let mesh = dir.join("good.obj");
    swm::io::write_mesh(&mesh, &swm_corpus::icosphere(1.0, 1)).unwrap();
    let swm_file = dir.join("good.swm");
    ok(&swm(&[
        "encode",
        s(&mesh),
        "-o",
        s(&swm_file),
        "--mode",
        "lossless",
    ]));
    (mesh, swm_file)
}

#[test]
fn failing_runs_leave_no_file_behind() {
    let dir = scratch("lost-none");
    let bad_mesh = write(&dir, "bad.obj", b"v 0 0 0\nf 1 2 3\n");
    let bad_swm = write(&dir, "bad.swm", b"SWM\0\x01\0 certainly not a valid file");
    let before = listing(&dir);
    fails(
        &["encode", s(&bad_mesh), "-o", s(&dir.join("out.swm"))],
        &bad_mesh,
    );
    fails(
        &[
            "encode",
            s(&bad_mesh),
            "-o",
            s(&dir.join("out.swm")),
            "--mode",
            "lossless",
        ],
        &bad_mesh,
    );
    fails(
        &["decode", s(&bad_swm), "-o", s(&dir.join("out.obj"))],
        &bad_swm,
    );
    fails(
        &["sharpen", s(&bad_mesh), "-o", s(&dir.join("out.ply"))],
        &bad_mesh,
    );
    assert_eq!(listing(&dir), before, "a failing run left a file behind");
}

#[test]
fn an_existing_output_survives_a_failure() {
    let dir = scratch("lost-existing");
    let (good_mesh, good_swm) = good_files(&dir);
    let bad_mesh = write(&dir, "bad.obj", b"v 0 0 0\nf 1 2 3\n");
    let mut damaged = std::fs::read(&good_swm).unwrap();
    let mid = damaged.len() / 2;
    damaged[mid] ^= 0x40;
    let bad_swm = write(&dir, "damaged.swm", &damaged);
    let old_swm = write(&dir, "old.swm", b"previous contents");
    let old_obj = write(&dir, "old.obj", b"# previous contents\n");
    let before = listing(&dir);
    fails(&["encode", s(&bad_mesh), "-o", s(&old_swm)], &bad_mesh);
    fails(&["decode", s(&bad_swm), "-o", s(&old_obj)], &bad_swm);
    fails(&["sharpen", s(&bad_mesh), "-o", s(&old_obj)], &bad_mesh);
    // A valid file refused by a limit: the failure comes after reading.
    fails(
        &[
            "decode",
            s(&good_swm),
            "-o",
            s(&old_obj),
            "--max-faces",
            "10",
        ],
        &good_swm,
    );
    assert_eq!(std::fs::read(&old_swm).unwrap(), b"previous contents");
    assert_eq!(std::fs::read(&old_obj).unwrap(), b"# previous contents\n");
    assert_eq!(listing(&dir), before);
    // And the same commands succeed on good input, replacing the file.
    ok(&swm(&[
        "decode",
        s(&good_swm),
        "-o",
        s(&old_obj),
        "--max-faces",
        "80",
    ]));
    assert!(swm::io::read_mesh(&old_obj).is_ok());
    let _ = good_mesh;
}

#[test]
fn the_output_may_not_be_the_input() {
    let dir = scratch("lost-same");
    let (mesh, swm_file) = good_files(&dir);
    let mesh_bytes = std::fs::read(&mesh).unwrap();
    let swm_bytes = std::fs::read(&swm_file).unwrap();
    // Spelled differently, so that only a comparison of the files (not of
    // the strings) catches it.
    let other_spelling = dir.join(".").join("good.obj");
    for (args, named) in [
        (vec!["sharpen", s(&mesh), "-o", s(&mesh)], &mesh),
        (
            vec!["sharpen", s(&mesh), "-o", s(&other_spelling)],
            &other_spelling,
        ),
        // --force: past the refusal of a mesh-named output, to the
        // same-file check itself.
        (vec!["encode", s(&mesh), "-o", s(&mesh), "--force"], &mesh),
        (vec!["decode", s(&swm_file), "-o", s(&swm_file)], &swm_file),
    ] {
        let stderr = fails(&args, named);
        assert!(stderr.contains("input"), "{args:?}: {stderr}");
    }
    assert_eq!(std::fs::read(&mesh).unwrap(), mesh_bytes);
    assert_eq!(std::fs::read(&swm_file).unwrap(), swm_bytes);
    assert_eq!(listing(&dir), ["good.obj", "good.swm"]);
}

/// The input under another name: a hard link (same device and inode, a
/// different directory entry) or a symbolic link, with the output's
/// extension.
#[cfg(unix)]
#[test]
fn the_output_may_not_be_the_input_through_a_link() {
    let dir = scratch("lost-linked");
    let (mesh, swm_file) = good_files(&dir);
    let mesh_bytes = std::fs::read(&mesh).unwrap();
    let swm_bytes = std::fs::read(&swm_file).unwrap();
    let hard_obj = dir.join("hard.obj");
    let hard_swm = dir.join("hard.swm");
    let hard_swm_as_obj = dir.join("hard-swm.obj");
    let soft_obj = dir.join("soft.obj");
    std::fs::hard_link(&mesh, &hard_obj).unwrap();
    std::fs::hard_link(&mesh, &hard_swm).unwrap();
    std::fs::hard_link(&swm_file, &hard_swm_as_obj).unwrap();
    std::os::unix::fs::symlink(&mesh, &soft_obj).unwrap();
    let before = listing(&dir);
    for (args, named) in [
        (vec!["sharpen", s(&mesh), "-o", s(&hard_obj)], &hard_obj),
        (vec!["encode", s(&mesh), "-o", s(&hard_swm)], &hard_swm),
        (
            vec!["encode", s(&mesh), "-o", s(&hard_swm), "--mode", "lossless"],
            &hard_swm,
        ),
        (
            vec!["decode", s(&swm_file), "-o", s(&hard_swm_as_obj)],
            &hard_swm_as_obj,
        ),
        (vec!["sharpen", s(&mesh), "-o", s(&soft_obj)], &soft_obj),
        // The input named through the link, the output directly.
        (vec!["sharpen", s(&hard_obj), "-o", s(&mesh)], &mesh),
    ] {
        let stderr = fails(&args, named);
        assert!(
            stderr.contains("the output is the input"),
            "{args:?}: {stderr}"
        );
    }
    assert_eq!(std::fs::read(&mesh).unwrap(), mesh_bytes);
    assert_eq!(std::fs::read(&swm_file).unwrap(), swm_bytes);
    assert_eq!(listing(&dir), before);
    // A copy is another file: writing over it is allowed.
    let copy = dir.join("copy.obj");
    std::fs::copy(&mesh, &copy).unwrap();
    ok(&swm(&["sharpen", s(&mesh), "-o", s(&copy)]));
}

/// Symbolic links planted where the writer of an older version put its
/// temporary file (`.NAME.tmp-PID`, predictable) and at the output's own
/// name: the files they point to are left untouched, the planted links
/// stay as they were, and the output becomes a regular file (the rename
/// replaces a link at the output's name instead of following it).
#[cfg(unix)]
#[test]
fn planted_symlinks_are_left_untouched() {
    use std::os::unix::fs::symlink;
    let dir = scratch("lost-planted");
    let (mesh, swm_file) = good_files(&dir);
    let runs: [(&str, Vec<&str>); 4] = [
        ("out.swm", vec!["encode", s(&mesh), "--mode", "lossless"]),
        (
            "swing.swm",
            vec!["encode", s(&mesh), "--edge-length", "0.4"],
        ),
        ("out.ply", vec!["decode", s(&swm_file)]),
        ("out.off", vec!["sharpen", s(&mesh)]),
    ];
    for (name, args) in runs {
        let victim_temp = write(&dir, &format!("victim-temp-{name}"), b"temp victim\n");
        let victim_out = write(&dir, &format!("victim-out-{name}"), b"output victim\n");
        let out = dir.join(name);
        symlink(&victim_out, &out).unwrap();
        // `$$` is the shell's process id, which `exec` hands to `swm`:
        // the link sits at the exact name `.NAME.tmp-PID` of that run.
        let script = r#"v=$1; d=$2; n=$3; shift 3
ln -s "$v" "$d/.$n.tmp-$$" && exec "$0" "$@""#;
        let run = std::process::Command::new("sh")
            .args(["-c", script, env!("CARGO_BIN_EXE_swm")])
            .args([s(&victim_temp), s(&dir), name])
            .args(&args)
            .args(["-o", s(&out)])
            .output()
            .unwrap();
        ok(&run);
        assert_eq!(
            std::fs::read(&victim_temp).unwrap(),
            b"temp victim\n",
            "{name}"
        );
        assert_eq!(
            std::fs::read(&victim_out).unwrap(),
            b"output victim\n",
            "{name}"
        );
        let meta = std::fs::symlink_metadata(&out).unwrap();
        assert!(meta.file_type().is_file(), "{name}: not a regular file");
        let planted: Vec<_> = listing(&dir)
            .into_iter()
            .filter(|n| n.starts_with(&format!(".{name}.")))
            .collect();
        assert_eq!(planted.len(), 1, "{name}: {planted:?}");
        assert_eq!(
            std::fs::read_link(dir.join(&planted[0])).unwrap(),
            victim_temp,
            "{name}: the planted link changed"
        );
    }
    assert!(swm::io::read_mesh(&dir.join("out.ply")).is_ok());
    assert!(swm::io::read_mesh(&dir.join("out.off")).is_ok());
}

/// Runs `swm decode` of a file that takes a while (`bend` Bender steps
/// multiply the triangles by 4^bend), sends `signal` once `ready` says so, and checks
/// the exit status and that nothing but `existing` (unchanged) is left
/// beside the input. A run that finished before the signal reached it
/// (a fast machine can write and rename the output between `ready` and
/// the signal) says nothing either way: it is run again with one more
/// Bender step (four times the output), while that stays under 5.2
/// million triangles.
#[cfg(unix)]
fn interrupted(
    name: &str,
    (signal, code): (&str, i32),
    bend: u32,
    existing: Option<&[u8]>,
    ready: impl Fn(&Path, u32) -> bool,
) {
    for steps in bend..=bend.max(6) {
        if interrupted_once(name, (signal, code), steps, existing, &ready) {
            return;
        }
        println!("{name}: swm finished before the signal at --bend {steps}");
    }
    panic!("{name}: swm finished before the signal every time");
}

/// One run of [`interrupted`]: false when swm finished before the signal.
#[cfg(unix)]
fn interrupted_once(
    name: &str,
    (signal, code): (&str, i32),
    bend: u32,
    existing: Option<&[u8]>,
    ready: &impl Fn(&Path, u32) -> bool,
) -> bool {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let dir = scratch(name);
    let input = dir.join("in.swm");
    let options = swm::EncodeOptions {
        mode: swm::EncodeMode::Lossless { qp: 12 },
        ..Default::default()
    };
    let sphere = swm_corpus::icosphere(1.0, 3);
    std::fs::write(&input, swm::encode(&sphere, &options).unwrap().bytes).unwrap();
    let out = dir.join("out.obj");
    if let Some(bytes) = existing {
        std::fs::write(&out, bytes).unwrap();
    }
    let before = listing(&dir);
    let bend = bend.to_string();
    let mut child = Command::new(env!("CARGO_BIN_EXE_swm"))
        .args(["decode", s(&input), "-o", s(&out), "--bend", &bend])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !ready(&dir, child.id()) {
        if child.try_wait().unwrap().is_some() {
            return false;
        }
        // A hang guard: the output starts within seconds.
        assert!(
            start.elapsed() < Duration::from_secs(300),
            "{name}: never ready"
        );
        std::thread::sleep(Duration::from_millis(1));
    }
    let kill = Command::new("sh")
        .args(["-c", "kill -s \"$1\" \"$2\"", "sh", signal])
        .arg(child.id().to_string())
        .status()
        .unwrap();
    assert!(kill.success());
    let status = child.wait().unwrap();
    let mut stderr = String::new();
    std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut stderr).unwrap();
    if status.success() {
        // Done and renamed before the signal arrived.
        return false;
    }
    assert_eq!(status.code(), Some(code), "{name}: {status}: {stderr}");
    assert_eq!(listing(&dir), before, "{name}: a file was left behind");
    if let Some(bytes) = existing {
        assert_eq!(std::fs::read(&out).unwrap(), bytes, "{name}");
    }
    true
}

/// Whether the temporary file of `out.obj` exists yet: the signal then
/// comes while the output is being written.
#[cfg(unix)]
fn writing(dir: &Path, _pid: u32) -> bool {
    listing(dir).iter().any(|n| n.starts_with(".out.obj."))
}

#[cfg(unix)]
#[test]
fn sigterm_while_writing_leaves_no_file_and_exits_143() {
    let existing: &[u8] = b"# previous contents\n";
    interrupted("lost-sigterm", ("TERM", 143), 5, Some(existing), writing);
}

#[cfg(unix)]
#[test]
fn sigint_while_writing_leaves_no_file_and_exits_130() {
    interrupted("lost-sigint", ("INT", 130), 5, None, writing);
}

/// A signal while decoding, before any output exists: once the process
/// has used a tenth of a second of CPU time (long after it started), a
/// tenth of what decoding and six Bender steps take.
#[cfg(target_os = "linux")]
#[test]
fn sigterm_while_decoding_exits_143() {
    fn cpu_ticks(pid: u32) -> u64 {
        let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap_or_default();
        // After the command name's closing parenthesis: fields 3 on;
        // utime and stime are fields 14 and 15.
        let rest = stat.rsplit_once(')').map_or("", |r| r.1);
        let fields: Vec<&str> = rest.split_whitespace().collect();
        let field = |i: usize| fields.get(i - 3).and_then(|f| f.parse::<u64>().ok());
        field(14).unwrap_or(0) + field(15).unwrap_or(0)
    }
    interrupted(
        "lost-sigterm-decoding",
        ("TERM", 143),
        6,
        None,
        |dir, pid| {
            let ready = cpu_ticks(pid) >= 10;
            assert!(
                !(ready && writing(dir, pid)),
                "the output was started already"
            );
            ready
        },
    );
}
