//! The bytes of an input file: memory-mapped when large, read into memory
//! when small; bounded in both cases.
//!
//! Mapping saves the copy of a multi-hundred-megabyte scan into the heap
//! and lets the readers treat every file as one `&[u8]`. Small files are
//! read instead: a map costs a few system calls and page faults that a
//! single `read` beats, and mapping an empty file fails on most systems.
//!
//! Invariants:
//! - only regular files are read (symbolic links are followed and their
//!   target judged): a FIFO, a device such as `/dev/zero` or a directory
//!   is refused with [`InputError::NotARegularFile`], since its length is
//!   unknown or unbounded;
//! - opening cannot block: on Unix the file is opened with `O_NONBLOCK`
//!   (no effect on regular files), so a FIFO swapped in after any check
//!   is still refused at once, and the kind is taken from the open file
//!   (`fstat`), not from the path;
//! - no more than [`Limits::max_input_bytes`] bytes are mapped or read: a
//!   longer file is refused by its length before anything is read, and a
//!   file that holds more than its length said (files under `/proc`
//!   report 0; a file may grow while read) is cut off one byte past the
//!   limit and refused.
//!
//! This is the only `unsafe` in the crate (see the safety comment below).

use crate::{Error, FileKind, InputError, LimitError, Limited, Limits};
use std::fs::{File, FileType, OpenOptions};
use std::io::Read;
use std::ops::Deref;
use std::path::Path;

/// Files at least this large are mapped rather than read.
const MAP_THRESHOLD: u64 = 1 << 20;

/// The whole content of an input file.
pub(super) enum Source {
    /// Read into memory.
    Owned(Vec<u8>),
    /// Mapped read-only.
    Mapped(memmap2::Mmap),
}

impl Source {
    /// Opens `path` and maps or reads it, within `limits.max_input_bytes`.
    pub(super) fn open(path: &Path, limits: &Limits) -> Result<Source, Error> {
        let file = open_nonblocking(path)?;
        let meta = file.metadata()?;
        if !meta.is_file() {
            let kind = kind_of(meta.file_type());
            return Err(Error::Input(InputError::NotARegularFile { kind }));
        }
        let len = meta.len();
        limits.check_input(len)?;
        if len < MAP_THRESHOLD {
            return read_bounded(file, len, limits.max_input_bytes).map(Source::Owned);
        }
        let len = usize::try_from(len).map_err(|_| too_long(len, limits.max_input_bytes))?;
        // SAFETY: `Mmap::map` is unsafe because the mapped bytes can change
        // under us if another process writes to or truncates the file while
        // it is mapped, which Rust's aliasing rules for `&[u8]` do not allow.
        // We accept that risk for input files, as every mmap-based reader
        // does, for these reasons:
        // - the map is read-only and private, so this process never writes
        //   through it, and it lives only for the duration of one read call;
        // - every reader treats the bytes as untrusted and re-checks every
        //   length and index it uses, so bytes that change mid-parse give
        //   wrong data or an error, never an out-of-bounds access;
        // - the remaining failure is a file truncated by someone else while
        //   we read it, which makes the OS kill the process with SIGBUS.
        //   Callers that read files other users may modify concurrently
        //   should copy them first or use `read_mesh_bytes`.
        // The map covers the length checked above, not whatever the file
        // has grown to since.
        #[allow(unsafe_code)]
        let map = unsafe { memmap2::MmapOptions::new().len(len).map(&file)? };
        #[cfg(unix)]
        {
            // Only a hint: the readers scan front to back.
            let _ = map.advise(memmap2::Advice::Sequential);
        }
        Ok(Source::Mapped(map))
    }
}

/// Opens `path` for reading without waiting for a FIFO's writer.
fn open_nonblocking(path: &Path) -> std::io::Result<File> {
    let mut options = OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    options.open(path)
}

/// Reads a regular file of `len` bytes (as its metadata says), refusing
/// it once it turns out to hold more than `limit`.
fn read_bounded(file: File, len: u64, limit: u64) -> Result<Vec<u8>, Error> {
    let mut bytes = Vec::new();
    bytes
        .try_reserve_exact(len as usize)
        .map_err(|_| Error::Io(std::io::Error::from(std::io::ErrorKind::OutOfMemory)))?;
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    let read = bytes.len() as u64;
    if read > limit {
        return Err(too_long(read, limit));
    }
    Ok(bytes)
}

fn too_long(bytes: u64, limit: u64) -> Error {
    Error::LimitExceeded(LimitError {
        what: Limited::InputBytes,
        requested: bytes,
        limit,
    })
}

/// The kind of a file that is not a regular file.
fn kind_of(t: FileType) -> FileKind {
    if t.is_dir() {
        return FileKind::Directory;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return FileKind::Fifo;
        }
        if t.is_char_device() {
            return FileKind::CharDevice;
        }
        if t.is_block_device() {
            return FileKind::BlockDevice;
        }
        if t.is_socket() {
            return FileKind::Socket;
        }
    }
    FileKind::Other
}

impl Deref for Source {
    type Target = [u8];

    fn deref(&self) -> &[u8] {
        match self {
            Source::Owned(bytes) => bytes,
            Source::Mapped(map) => map,
        }
    }
}
