//! Arbitrary bytes as a `.swm` file, read without decoding geometry: the
//! container parser and `swm::inspect` (header, sections, connectivity)
//! must return an error or a result, never panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swm::Limits;

fuzz_target!(|data: &[u8]| {
    let limits = Limits::default();
    if let Ok(file) = swm::container::parse_container(data, &limits) {
        // Walking the sections of a parsed container must stay in bounds.
        for s in file.sections() {
            let _ = (s.tag, s.bytes.len());
        }
    }
    let _ = swm::inspect(data, &limits);
});
