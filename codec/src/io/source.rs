//! The bytes of an input file: memory-mapped when large, read into memory
//! when small.
//!
//! Mapping saves the copy of a multi-hundred-megabyte scan into the heap
//! and lets the readers treat every file as one `&[u8]`. Small files are
//! read instead: a map costs a few system calls and page faults that a
//! single `read` beats, and mapping an empty file fails on most systems.
//!
//! This is the only `unsafe` in the crate (see the safety comment below).

use std::fs::File;
use std::io::{self, Read};
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
    /// Opens `path` and maps or reads it.
    pub(super) fn open(path: &Path) -> io::Result<Source> {
        let mut file = File::open(path)?;
        let meta = file.metadata()?;
        // Pipes and special files report a length of 0 and cannot be
        // mapped; reading them works, and reading a directory gives the
        // operating system's own "is a directory" error.
        if !meta.is_file() || meta.len() < MAP_THRESHOLD {
            let mut bytes = Vec::new();
            file.read_to_end(&mut bytes)?;
            return Ok(Source::Owned(bytes));
        }
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
        #[allow(unsafe_code)]
        let map = unsafe { memmap2::Mmap::map(&file)? };
        #[cfg(unix)]
        {
            // Only a hint: the readers scan front to back.
            let _ = map.advise(memmap2::Advice::Sequential);
        }
        Ok(Source::Mapped(map))
    }
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
