//! Arbitrary bytes as a glTF file, JSON or GLB (`swm_fuzz::check_reader`;
//! the reader tells them apart by the GLB magic).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| swm_fuzz::check_reader(data, swm::io::MeshFormat::Glb));
