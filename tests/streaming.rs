//! `StreamDecoder` (issue 8's "decode output independent of how the input
//! was sliced"): every way of cutting a file gives the same outcome, the
//! same mesh as decoding it whole, and a bad frame stops it early.

mod common;

use swm::{DecodeOptions, Error, Limits, StreamDecoder, TriMesh};

/// Feeds `bytes` in pieces of the given lengths (cycled), then finishes.
/// The outcome as a comparable value: the mesh, or the error's text.
fn stream(bytes: &[u8], cuts: &[usize], options: &DecodeOptions) -> Result<TriMesh, String> {
    let mut s = StreamDecoder::new(options.clone());
    let mut rest = bytes;
    let mut k = 0;
    while !rest.is_empty() {
        let n = cuts[k % cuts.len()].clamp(1, rest.len());
        k += 1;
        s = s.push(&rest[..n]).map_err(|e| e.to_string())?;
        rest = &rest[n..];
    }
    s.finish().map_err(|e| e.to_string())
}

/// Cuts: whole, byte by byte, and uneven pieces that straddle the
/// checks at 4 and 27 bytes and the end of the section table.
const CUTS: &[&[usize]] = &[
    &[usize::MAX],
    &[1],
    &[3, 5, 19, 2],
    &[26, 1, 1, 9],
    &[4, 23, 64],
];

#[test]
fn every_cut_decodes_to_the_whole_file_mesh() {
    for s in common::samples_in_both_framings() {
        for options in [
            DecodeOptions::default(),
            DecodeOptions {
                sharpen: Some(true),
                bend_steps: Some(1),
                ..Default::default()
            },
        ] {
            let whole = swm::decode(&s.bytes, &options).unwrap();
            for cuts in CUTS {
                let got = stream(&s.bytes, cuts, &options).unwrap();
                assert!(got == whole, "{} cut {cuts:?}", s.name);
            }
        }
    }
}

/// Damage of every kind (each truncation, each bit flip, a trailing byte)
/// gives one outcome whatever the cuts, and never a mesh that decoding the
/// whole bytes would refuse.
#[test]
fn damaged_files_fail_the_same_way_for_every_cut() {
    let options = DecodeOptions::default();
    let base = &common::samples()[0].bytes;
    let mut variants: Vec<Vec<u8>> = (0..base.len()).map(|n| base[..n].to_vec()).collect();
    for bit in 0..8 * base.len() {
        let mut b = base.clone();
        b[bit / 8] ^= 1 << (bit % 8);
        variants.push(b);
    }
    let mut longer = base.clone();
    longer.push(0);
    variants.push(longer);
    for bytes in &variants {
        let first = stream(bytes, CUTS[0], &options);
        for cuts in &CUTS[1..] {
            assert_eq!(stream(bytes, cuts, &options), first, "cut {cuts:?}");
        }
        assert!(
            first.is_err(),
            "a damaged file decoded ({} bytes)",
            bytes.len()
        );
        assert!(swm::decode(bytes, &options).is_err());
    }
}

#[test]
fn a_bad_frame_stops_the_stream_early() {
    let compact = &common::samples()[3].bytes;
    let fixed = &common::reframed(compact, swm::Framing::Fixed);
    // The header's counts above the limits: refused at byte 27 in the
    // fixed framing, as soon as the vertex count's varint is in in the
    // compact one (byte 9 is its first).
    let tight = DecodeOptions {
        limits: Limits {
            max_vertices: 3,
            ..Default::default()
        },
        ..Default::default()
    };
    let v = common::Frame::of(compact).counts[0];
    let v_len = (64 - (v | 1).leading_zeros() as usize).div_ceil(7);
    for (bytes, at) in [(fixed, 27), (compact, 9 + v_len)] {
        let s = StreamDecoder::new(tight.clone())
            .push(&bytes[..at - 1])
            .unwrap();
        assert!(matches!(
            s.push(&bytes[at - 1..at]),
            Err(Error::LimitExceeded(_))
        ));
    }
    let bytes = compact;

    // A file longer than the allocation limit: refused once the section
    // table is in, before anything is reserved for it.
    let small = DecodeOptions {
        limits: Limits {
            max_alloc_bytes: bytes.len() as u64 - 1,
            ..Default::default()
        },
        ..Default::default()
    };
    assert!(matches!(
        StreamDecoder::new(small).push(bytes),
        Err(Error::LimitExceeded(_))
    ));

    // Not an .swm file: refused at byte 4.
    let s = StreamDecoder::new(DecodeOptions::default())
        .push(b"SWM")
        .unwrap();
    assert!(matches!(s.push(b"!"), Err(Error::Format(_))));

    // The length is known from the table, and a byte past it is refused.
    let s = StreamDecoder::new(DecodeOptions::default())
        .push(&bytes[..bytes.len() - 1])
        .unwrap();
    assert_eq!(s.expected_len(), Some(bytes.len()));
    let s = s.push(&bytes[bytes.len() - 1..]).unwrap();
    let err = s.push(&[0]).unwrap_err().to_string();
    assert!(
        err.contains("after") || err.contains("trailing") || err.contains("extra"),
        "{err}"
    );
}
