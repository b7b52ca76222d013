//! Peak memory of the decoder on hostile input: whatever a small file
//! says, decoding it may allocate at most a small multiple of the larger
//! of the file's size and the mesh its header declares (which `Limits`
//! bound), plus a fixed allowance for the entropy models.
//!
//! Measured with a counting global allocator. The counters are per
//! thread, so the test harness's other threads do not disturb them.

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use swm::container::{crc32, parse_container, write_container, Tag};
use swm::{DecodeOptions, Limits};

struct Counting;

thread_local! {
    static CURRENT: Cell<usize> = const { Cell::new(0) };
    static PEAK: Cell<usize> = const { Cell::new(0) };
}

fn grow(n: usize) {
    // `try_with`: the thread-local may be gone while a thread exits.
    let _ = CURRENT.try_with(|c| {
        let now = c.get() + n;
        c.set(now);
        let _ = PEAK.try_with(|p| p.set(p.get().max(now)));
    });
}

fn shrink(n: usize) {
    let _ = CURRENT.try_with(|c| c.set(c.get().saturating_sub(n)));
}

// SAFETY: every call forwards to `System` unchanged; the bookkeeping
// touches only const-initialised thread-locals, which never allocate.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = System.alloc(layout);
        if !p.is_null() {
            grow(layout.size());
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = System.alloc_zeroed(layout);
        if !p.is_null() {
            grow(layout.size());
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout);
        shrink(layout.size());
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = System.realloc(ptr, layout, new_size);
        if !p.is_null() {
            shrink(layout.size());
            grow(new_size);
        }
        p
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Bytes per declared vertex or triangle of output that the decoder may
/// use at its peak (output, corner table and working buffers).
const PER_ELEMENT: usize = 256;
/// Bytes per byte of input.
const PER_FILE_BYTE: usize = 64;
/// Entropy models, small tables and the like.
const ALLOWANCE: usize = 64 << 10;

/// Peak bytes allocated by this thread while decoding `bytes`, beyond
/// what was live before.
fn peak_of(bytes: &[u8]) -> (usize, bool) {
    let base = CURRENT.with(Cell::get);
    PEAK.with(|p| p.set(base));
    let ok = swm::decode(bytes, &DecodeOptions::default()).is_ok();
    (PEAK.with(Cell::get) - base, ok)
}

/// The mesh size the header declares, in vertices plus triangles.
fn declared(bytes: &[u8]) -> usize {
    match parse_container(bytes, &Limits::UNLIMITED) {
        Ok(file) => {
            let h = file.header;
            let mut n = h.vertex_count as usize + h.triangle_count as usize;
            if let Some(rest) = file.section(Tag::REST) {
                n += declared(rest);
            }
            n
        }
        Err(_) => 0,
    }
}

/// Checks the decoder's peak on `bytes` against `elements` vertices and
/// triangles of output.
fn check(bytes: &[u8], what: &str, elements: usize) {
    let (peak, ok) = peak_of(bytes);
    let bound = PER_FILE_BYTE * bytes.len() + PER_ELEMENT * elements + ALLOWANCE;
    assert!(
        peak <= bound,
        "{what}: peak {peak} bytes > bound {bound} (file {} bytes, {elements} elements, decoded: {ok})",
        bytes.len(),
    );
}

fn fix_crc(b: &mut [u8]) {
    let n = b.len() - 4;
    let crc = crc32(&b[..n]);
    b[n..].copy_from_slice(&crc.to_le_bytes());
}

fn varu(mut v: u64) -> Vec<u8> {
    let mut out = Vec::new();
    while v >= 0x80 {
        out.push(v as u8 | 0x80);
        v >>= 7;
    }
    out.push(v as u8);
    out
}

/// `bytes` with one section's payload replaced, frame and CRC valid.
fn with_section(bytes: &[u8], tag: Tag, payload: &[u8]) -> Vec<u8> {
    let file = parse_container(bytes, &Limits::UNLIMITED).unwrap();
    let sections: Vec<(Tag, &[u8])> = file
        .sections()
        .map(|s| (s.tag, if s.tag == tag { payload } else { s.bytes }))
        .collect();
    write_container(&file.header, &sections).unwrap()
}

#[test]
fn decoding_hostile_input_stays_within_a_multiple_of_its_size() {
    for sample in common::samples() {
        let (name, good) = (sample.name, &sample.bytes);
        // The bound for every mutation below: the *valid* file's mesh. A
        // mutated file may declare more, but its sections still code no
        // more than the original's, and the decoder must find that out
        // before it allocates for what the header says.
        let elements = declared(good);
        check(good, name, elements);
        // Lying counts in the header (CRC fixed), within the default
        // limits and consistent with each other, then at the maximum.
        for (v, t) in [
            (3u32 << 20, 1u32 << 20),
            (1 << 28, 1 << 28),
            (u32::MAX, u32::MAX / 3 + 1),
        ] {
            let mut b = good.clone();
            b[9..13].copy_from_slice(&v.to_le_bytes());
            b[13..17].copy_from_slice(&t.to_le_bytes());
            fix_crc(&mut b);
            check(
                &b,
                &format!("{name} declaring {v} vertices, {t} triangles"),
                elements,
            );
        }
        // Lying symbol counts in TOPO: as many as CLRS could hold at the
        // coder's best rate, far more than the header's triangles (a
        // displaced file has its TOPO inside BASE, whose bytes the
        // overwrites below reach).
        let file = parse_container(good, &Limits::UNLIMITED).unwrap();
        let topo = file
            .section(Tag::TOPO)
            .map(<[u8]>::to_vec)
            .unwrap_or_default();
        for symbols in [1u64 << 16, 1 << 20, 1 << 24, 1 << 30] {
            if topo.is_empty() {
                break;
            }
            let mut payload = varu(symbols);
            // Skip the true count's varu and keep the rest.
            let skip = topo.iter().position(|&b| b < 0x80).unwrap() + 1;
            payload.extend_from_slice(&topo[skip..]);
            let b = with_section(good, Tag::TOPO, &payload);
            check(
                &b,
                &format!("{name} with {symbols} symbols in TOPO"),
                elements,
            );
        }
        // Every byte overwritten, CRC fixed: what reaches the decoders.
        for at in 4..good.len() - 4 {
            for v in [0x00, 0x7F, 0xFF] {
                let mut b = good.clone();
                b[at] = v;
                fix_crc(&mut b);
                check(&b, &format!("{name} with byte {at} = {v:#x}"), elements);
            }
        }
        // Every truncation (stopped by the frame, but the frame must not
        // allocate either).
        for n in 0..good.len() {
            check(&good[..n], &format!("{name} cut to {n} bytes"), 0);
        }
    }
}
