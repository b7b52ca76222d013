//! `swm::StreamDecoder`: the outcome must not depend on how the file was
//! cut into pieces (as image-png's `buf_independent` target checks for
//! PNG), and must agree with decoding the whole file.
//!
//! The first four bytes are the piece lengths (1..=256, cycled), the rest
//! is the file. The file is streamed twice, whole and in those pieces:
//! both give the same mesh or the same error message; a file `decode`
//! accepts whole streams to the same mesh, and a streamed mesh is one
//! `decode` accepts.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swm::{DecodeOptions, Limits, StreamDecoder, TriMesh};

const OPTIONS: DecodeOptions = DecodeOptions {
    limits: Limits {
        max_vertices: 1 << 16,
        max_faces: 1 << 17,
        max_alloc_bytes: 64 << 20,
        ..Limits::UNLIMITED
    },
    sharpen: Some(false),
    bend_steps: Some(0),
};

fn stream(file: &[u8], cuts: &[usize]) -> Result<TriMesh, String> {
    let mut s = StreamDecoder::new(OPTIONS);
    let mut rest = file;
    for &n in cuts.iter().cycle() {
        if rest.is_empty() {
            break;
        }
        let n = n.min(rest.len());
        s = s.push(&rest[..n]).map_err(|e| e.to_string())?;
        rest = &rest[n..];
    }
    s.finish().map_err(|e| e.to_string())
}

fuzz_target!(|data: &[u8]| {
    if data.len() < 4 {
        return;
    }
    let (head, file) = data.split_at(4);
    let cuts: Vec<usize> = head.iter().map(|&b| usize::from(b) + 1).collect();
    let whole = stream(file, &[usize::MAX]);
    let cut = stream(file, &cuts);
    assert_eq!(whole, cut, "the outcome depends on the cuts {cuts:?}");
    match (swm::decode(file, &OPTIONS), whole) {
        (Ok(a), Ok(b)) => assert!(a == b, "stream and decode give different meshes"),
        (Ok(_), Err(e)) => panic!("decode accepts the file, the stream refuses it: {e}"),
        (Err(e), Ok(_)) => panic!("the stream accepts a file decode refuses: {e}"),
        (Err(_), Err(_)) => {}
    }
});
