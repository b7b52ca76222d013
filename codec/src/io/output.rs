//! Output files that are either complete or absent: the data goes to a
//! temporary file beside the target, reaches the disk, and is renamed
//! over the target in one step.
//!
//! Invariants:
//! - the temporary file is created exclusively (`O_CREAT | O_EXCL`)
//!   under an unpredictable name `.{name}.XXXXXX.tmp` in the target's
//!   directory (the `tempfile` crate draws the name, retries on a
//!   collision and removes the file when dropped): it never opens,
//!   follows or replaces anything that was there, symbolic links
//!   included, and nobody can plant a file at a name it will use;
//! - it gets the permissions `File::create` would give (`0o666` less the
//!   umask on Unix), not `tempfile`'s private `0o600`;
//! - its data is synced before the rename, so `path` never names a file
//!   whose blocks were not written; the rename replaces the directory
//!   entry at `path`, so a symbolic link at `path` is itself replaced by
//!   the new file, never followed;
//! - it is removed on every error (dropping the `NamedTempFile` removes
//!   it) and, while the write is in progress, its path is listed in a
//!   process-wide registry that [`discard_unfinished`] empties, so that a
//!   program ending on a signal leaves no hidden partial file behind.
//!
//! - a target that exists and is neither a regular file nor a symbolic
//!   link (a device such as `/dev/null`, a FIFO, a socket) is written to
//!   in place, with no temporary file: renaming over it would replace
//!   the device node with a plain file (`-o /dev/null` once turned the
//!   machine's `/dev/null` into a file that every later reader saw
//!   filled with other programs' output). Such a target receives the
//!   data as it is produced, so an error can leave part of it there, as
//!   with standard output.
//!
//! Someone who may write to the target's directory can still replace the
//! temporary file between its creation and the rename, as they can
//! replace the target itself; the guarantees are against everyone else.

use crate::Error;
use std::ffi::OsString;
use std::fs::{File, OpenOptions};
use std::io;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};
use tempfile::NamedTempFile;

/// Paths of temporary files of writes in progress.
struct Registry(Mutex<Vec<PathBuf>>);

/// The registry of every write of this process; tests make their own, so
/// that discarding in one test cannot break another's writes.
static UNFINISHED: Registry = Registry(Mutex::new(Vec::new()));

impl Registry {
    /// The list, even if a thread panicked while holding it: it is a plain
    /// list of paths, valid at every step.
    fn lock(&self) -> MutexGuard<'_, Vec<PathBuf>> {
        self.0
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    fn discard<R>(&self, then: impl FnOnce() -> R) -> R {
        let mut live = self.lock();
        for path in live.drain(..) {
            // Already gone is fine: the goal is that it does not exist.
            let _ = std::fs::remove_file(&path);
        }
        then()
    }
}

/// Removes the temporary files of the writes still in progress in this
/// process ([`write_mesh`](super::write_mesh), [`write_bytes`](super::write_bytes)),
/// then runs `then` while holding every writer off: until `then` returns,
/// no writer creates a temporary file or renames one into place.
///
/// This is for programs that end on a signal. The crate installs no signal
/// handler; a program does, and its handler thread calls, e.g.,
/// `discard_unfinished(|| std::process::exit(130))`: the process then
/// ends leaving every output either as it was or complete, and no
/// temporary file behind. If `then` returns, the writes whose files were
/// removed fail with an I/O error when they try to finish; later writes
/// work as usual. Returns what `then` returns.
pub fn discard_unfinished<R>(then: impl FnOnce() -> R) -> R {
    UNFINISHED.discard(then)
}

/// A temporary file listed in a registry; dropped unfinished, it is
/// removed and unlisted.
struct Unfinished<'r> {
    file: Option<NamedTempFile>,
    registry: &'r Registry,
}

impl<'r> Unfinished<'r> {
    /// Creates `.{name}.XXXXXX.tmp` beside `path` and lists it.
    fn create(path: &Path, registry: &'r Registry) -> Result<Self, Error> {
        let name = path
            .file_name()
            .ok_or_else(|| Error::Io(io::Error::from(io::ErrorKind::InvalidInput)))?;
        let dir = match path.parent() {
            Some(dir) if !dir.as_os_str().is_empty() => dir,
            _ => Path::new("."),
        };
        let mut prefix = OsString::from(".");
        prefix.push(name);
        prefix.push(".");
        // Opened here rather than by `Builder::tempfile_in`, which would
        // add its hidden name to every error message (the caller names
        // the output) and give the file mode 0o600.
        let open = |name: &Path| {
            let mut options = OpenOptions::new();
            // `create_new` is `O_CREAT | O_EXCL`: never an existing entry,
            // never through a symbolic link.
            options.write(true).create_new(true);
            #[cfg(unix)]
            {
                use std::os::unix::fs::OpenOptionsExt;
                options.mode(0o666);
            }
            options.open(name)
        };
        // Created and listed under the lock, so that `discard` sees every
        // file that exists.
        let mut live = registry.lock();
        let file = tempfile::Builder::new()
            .prefix(&prefix)
            .suffix(".tmp")
            .make_in(dir, open)?;
        live.push(file.path().to_owned());
        Ok(Unfinished {
            file: Some(file),
            registry,
        })
    }

    fn file(&mut self) -> &mut File {
        self.file
            .as_mut()
            .expect("only `persist` takes the file, and it consumes self")
            .as_file_mut()
    }

    /// Syncs the file and renames it to `path`.
    fn persist(mut self, path: &Path) -> Result<(), Error> {
        let file = self
            .file
            .take()
            .expect("only `persist` takes the file, and it consumes self");
        file.as_file().sync_all()?;
        // Unlisted and renamed under the lock: `discard` either removes
        // the file before the rename (which then fails) or finds it
        // renamed and no longer listed.
        let mut live = self.registry.lock();
        unlist(&mut live, file.path());
        // On failure the error holds the file, and dropping it removes it.
        file.persist(path).map_err(|e| Error::Io(e.error))?;
        Ok(())
    }
}

impl Drop for Unfinished<'_> {
    fn drop(&mut self) {
        if let Some(file) = self.file.take() {
            let mut live = self.registry.lock();
            unlist(&mut live, file.path());
            drop(file);
        }
    }
}

fn unlist(live: &mut Vec<PathBuf>, path: &Path) {
    if let Some(i) = live.iter().position(|p| p == path) {
        live.swap_remove(i);
    }
}

/// Runs `fill` on a new temporary file beside `path` and renames it over
/// `path` only if `fill` succeeded and the data reached the disk.
pub(super) fn write_atomic(
    path: &Path,
    fill: impl FnOnce(&mut File) -> Result<(), Error>,
) -> Result<(), Error> {
    write_listed(path, &UNFINISHED, fill)
}

fn write_listed(
    path: &Path,
    registry: &Registry,
    fill: impl FnOnce(&mut File) -> Result<(), Error>,
) -> Result<(), Error> {
    if is_special(path) {
        // Opened without `create` or `truncate`: it exists and is not a
        // file, so there is nothing to create, and truncating a device
        // means nothing (a FIFO refuses it).
        let mut file = OpenOptions::new().write(true).open(path)?;
        return fill(&mut file);
    }
    let mut temp = Unfinished::create(path, registry)?;
    fill(temp.file())?;
    temp.persist(path)
}

/// Whether `path` names an existing entry that is not a regular file, a
/// symbolic link or a directory: a device, a FIFO or a socket, which a
/// rename must not replace. A directory is left to the rename, which
/// refuses it.
fn is_special(path: &Path) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|meta| {
        let kind = meta.file_type();
        !(kind.is_file() || kind.is_symlink() || kind.is_dir())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;
    use std::sync::mpsc;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("swm-output-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn listing(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_missing_directory_is_reported_without_the_temporary_name() {
        let dir = scratch("missing");
        let e = write_atomic(&dir.join("no/out.bin"), |_| Ok(())).unwrap_err();
        let Error::Io(io) = &e else { panic!("{e:?}") };
        assert_eq!(io.kind(), io::ErrorKind::NotFound);
        assert!(!e.to_string().contains(".tmp"), "{e}");
    }

    #[test]
    fn a_failed_fill_leaves_nothing_and_unlists_its_file() {
        let dir = scratch("fail");
        let target = dir.join("out.bin");
        let result = write_atomic(&target, |f| {
            f.write_all(b"partial")?;
            Err(Error::Io(io::Error::other("fill failed")))
        });
        assert!(result.is_err());
        assert!(listing(&dir).is_empty(), "{:?}", listing(&dir));
        assert!(!UNFINISHED.lock().iter().any(|p| p.starts_with(&dir)));
    }

    #[test]
    fn the_temporary_file_is_hidden_beside_the_target_and_unpredictable() {
        let dir = scratch("names");
        let target = dir.join("out.bin");
        let mut names = Vec::new();
        for _ in 0..2 {
            write_atomic(&target, |_| {
                names.extend(listing(&dir).into_iter().filter(|n| n != "out.bin"));
                Ok(())
            })
            .unwrap();
        }
        assert_eq!(names.len(), 2, "{names:?}");
        for n in &names {
            assert!(n.starts_with(".out.bin.") && n.ends_with(".tmp"), "{n}");
        }
        assert_ne!(names[0], names[1], "two writes used the same name");
        assert_eq!(listing(&dir), ["out.bin"]);
    }

    #[cfg(unix)]
    #[test]
    fn a_symlink_at_the_target_is_replaced_not_followed() {
        let dir = scratch("symlink");
        let victim = dir.join("victim");
        std::fs::write(&victim, b"keep me").unwrap();
        let target = dir.join("out.bin");
        std::os::unix::fs::symlink(&victim, &target).unwrap();
        write_atomic(&target, |f| Ok(f.write_all(b"new")?)).unwrap();
        assert_eq!(std::fs::read(&victim).unwrap(), b"keep me");
        let meta = std::fs::symlink_metadata(&target).unwrap();
        assert!(meta.file_type().is_file());
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
    }

    #[cfg(unix)]
    #[test]
    fn the_file_gets_the_permissions_of_a_created_file() {
        use std::os::unix::fs::PermissionsExt;
        let dir = scratch("mode");
        let created = dir.join("created");
        File::create(&created).unwrap();
        let target = dir.join("out.bin");
        write_atomic(&target, |_| Ok(())).unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode(&target), mode(&created));
    }

    #[cfg(unix)]
    #[test]
    fn a_device_is_written_to_not_replaced() {
        use std::os::unix::fs::FileTypeExt;
        let null = Path::new("/dev/null");
        let is_device =
            |p: &Path| std::fs::symlink_metadata(p).is_ok_and(|m| m.file_type().is_char_device());
        if !is_device(null) {
            crate::test_skip::skip("/dev/null is not a character device here");
            return;
        }
        write_atomic(null, |f| Ok(f.write_all(b"gone")?)).unwrap();
        assert!(is_device(null), "/dev/null was replaced");
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_receives_the_data_and_stays_a_fifo() {
        use std::io::Read;
        use std::os::unix::fs::FileTypeExt;
        let dir = scratch("fifo");
        let fifo = dir.join("pipe");
        match std::process::Command::new("mkfifo").arg(&fifo).status() {
            Ok(status) if status.success() => {}
            _ => {
                crate::test_skip::skip("mkfifo is not available");
                return;
            }
        }
        let reader = std::thread::spawn({
            let fifo = fifo.clone();
            move || {
                let mut got = Vec::new();
                File::open(&fifo).unwrap().read_to_end(&mut got).unwrap();
                got
            }
        });
        write_atomic(&fifo, |f| Ok(f.write_all(b"through the pipe")?)).unwrap();
        assert_eq!(reader.join().unwrap(), b"through the pipe");
        let meta = std::fs::symlink_metadata(&fifo).unwrap();
        assert!(meta.file_type().is_fifo());
        assert_eq!(listing(&dir), ["pipe"]);
    }

    #[test]
    fn discarding_removes_a_write_in_progress_and_makes_it_fail() {
        let dir = scratch("discard");
        let target = dir.join("out.bin");
        let (started, wait_started) = mpsc::channel();
        let (go_on, wait_go_on) = mpsc::channel::<()>();
        // Its own registry: discarding this process's would break the
        // writes of tests running beside this one.
        static REGISTRY: Registry = Registry(Mutex::new(Vec::new()));
        let writer = std::thread::spawn({
            let target = target.clone();
            move || {
                write_listed(&target, &REGISTRY, |f| {
                    f.write_all(b"half")?;
                    started.send(()).unwrap();
                    wait_go_on.recv().unwrap();
                    Ok(f.write_all(b" and the rest")?)
                })
            }
        });
        wait_started.recv().unwrap();
        assert_eq!(listing(&dir).len(), 1, "the temporary file exists");
        let seen = REGISTRY.discard(|| listing(&dir));
        assert!(seen.is_empty(), "left behind: {seen:?}");
        go_on.send(()).unwrap();
        assert!(writer.join().unwrap().is_err());
        assert!(listing(&dir).is_empty(), "{:?}", listing(&dir));
    }
}
