//! The largest single allocation a piece of test code asks for, on its
//! own thread: tests that say a decoder refuses absurd counts "before
//! allocating" check it with [`largest_allocation`] instead of trusting
//! that an error came back (an error after reserving gigabytes passes
//! `is_err` too, on a machine that overcommits memory).
//!
//! The test binary's global allocator is the system's, with one
//! thread-local maximum kept on the side.
#![allow(unsafe_code)]

extern crate std;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

std::thread_local! {
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

fn note(size: usize) {
    // `try_with`: the slot may be gone while the thread exits.
    let _ = LARGEST.try_with(|l| l.set(l.get().max(size)));
}

struct Watch;

// SAFETY: every call is passed on to `System` unchanged; the bookkeeping
// touches a const-initialized thread-local `Cell`, which never allocates.
unsafe impl GlobalAlloc for Watch {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        System.alloc(layout)
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        System.alloc_zeroed(layout)
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note(new_size);
        System.realloc(ptr, layout, new_size)
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
}

#[global_allocator]
static WATCH: Watch = Watch;

/// `f`'s result and the largest single allocation (bytes) it made on this
/// thread.
pub fn largest_allocation<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let before = LARGEST.with(|l| l.replace(0));
    let out = f();
    let largest = LARGEST.with(|l| l.replace(before.max(l.get())));
    (out, largest)
}

#[test]
fn the_largest_allocation_is_seen() {
    let (v, largest) = largest_allocation(|| std::vec![0u8; 3 << 20]);
    assert_eq!(v.len(), 3 << 20);
    assert!(largest >= 3 << 20, "{largest}");
    let ((), small) = largest_allocation(|| drop(std::vec![0u8; 10]));
    assert!(small < 1 << 10, "{small}");
}
