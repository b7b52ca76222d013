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

/// Issue 46, item 4: a displaced-subdivision file (the golden one, two
/// levels) fed in pieces hands out its base as soon as `HEAD` and `BASE`
/// are in and each finer level as soon as its chunk is, each bit for bit
/// what `decode` gives with that `max_level`, whatever the cuts.
#[test]
fn a_displaced_file_hands_out_each_level_as_its_bytes_arrive() {
    let bytes: &[u8] = include_bytes!("../format-spec/golden/displaced-v1.2.swm");
    let file = swm::container::parse_container(bytes, &Limits::default()).unwrap();
    let section = |tag: &[u8; 4]| file.find(swm::container::Tag(*tag)).unwrap();
    let (head, base, disp) = (section(b"HEAD"), section(b"BASE"), section(b"DISP"));
    // Where each level is complete: the base, then each chunk's end
    // (a `varu` length, then that many bytes).
    let mut ends = vec![(head.offset + head.bytes.len()).max(base.offset + base.bytes.len())];
    let mut at = 0;
    while at < disp.bytes.len() {
        let (mut len, mut shift) = (0usize, 0);
        loop {
            let b = disp.bytes[at];
            at += 1;
            len |= usize::from(b & 0x7f) << shift;
            shift += 7;
            if b < 0x80 {
                break;
            }
        }
        at += len;
        ends.push(disp.offset + at);
    }
    assert_eq!(ends.len(), 3, "the golden file has two levels");
    let want: Vec<TriMesh> = (0..3)
        .map(|l| {
            let options = DecodeOptions {
                max_level: Some(l),
                ..Default::default()
            };
            swm::decode(bytes, &options).unwrap()
        })
        .collect();

    // Byte by byte: each level appears exactly when its last byte does.
    let mut s = StreamDecoder::new(DecodeOptions::default());
    let mut seen = None;
    for (n, b) in bytes.iter().enumerate() {
        s = s.push(std::slice::from_ref(b)).unwrap();
        let level = s.level().map(|(l, _)| l);
        if level != seen {
            let l = level.unwrap();
            assert_eq!(n + 1, ends[l], "level {l} after {} bytes", n + 1);
            assert!(s.level().unwrap().1 == &want[l], "level {l}");
            seen = level;
        }
    }
    assert_eq!(seen, Some(2));
    assert!(s.finish().unwrap() == want[2]);

    // Any cuts: the levels come in order, each the same mesh.
    for cuts in CUTS {
        let mut s = StreamDecoder::new(DecodeOptions::default());
        let (mut rest, mut k, mut last) = (bytes, 0, None);
        while !rest.is_empty() {
            let n = cuts[k % cuts.len()].clamp(1, rest.len());
            k += 1;
            s = s.push(&rest[..n]).unwrap();
            rest = &rest[n..];
            if let Some((l, mesh)) = s.level() {
                assert!(last.is_none_or(|p| p <= l), "cut {cuts:?}");
                assert!(mesh == &want[l], "cut {cuts:?} level {l}");
                last = Some(l);
            }
        }
        assert_eq!(last, Some(2), "cut {cuts:?}");
    }

    // `max_level` stops the stream as it stops `decode`.
    for max in 0..3u8 {
        let options = DecodeOptions {
            max_level: Some(max),
            ..Default::default()
        };
        let s = StreamDecoder::new(options).push(bytes).unwrap();
        let (l, mesh) = s.level().unwrap();
        assert_eq!(l, usize::from(max));
        assert!(mesh == &want[l]);
        assert!(s.finish().unwrap() == want[l]);
    }

    // Other modes have no levels.
    let lossless = &common::samples()[0].bytes;
    let s = StreamDecoder::new(DecodeOptions::default())
        .push(lossless)
        .unwrap();
    assert!(s.level().is_none());
}
