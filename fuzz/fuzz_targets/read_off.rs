//! Arbitrary bytes as an OFF file (`swm_fuzz::check_reader`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| swm_fuzz::check_reader(data, swm::io::MeshFormat::Off));
