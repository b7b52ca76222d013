//! The compact framing's malformed-input matrix (format 1.1, flag bit 0):
//! the same checks as the fixed framing's (`tests.rs`), plus what varints
//! and tag codes add: shortest forms, reserved codes, literal tags, a
//! table whose end is known only once read; and the 1.1 golden frame.

use super::compact::{code_of, varu_len, CODES};
use super::*;
use crate::{Error, LimitError, Limited, Limits, Location, Malformed};

/// The golden compact frame of format 1.1. Never regenerate it.
const GOLDEN_V1_1: &[u8] = include_bytes!("../../../format-spec/golden/container-v1.1.bin");

fn golden_meta() -> Vec<u8> {
    write_meta(&[("generator", b"swm")])
}

/// The golden file's sections (placeholders, as in 1.0's golden frame).
fn sections(meta: &[u8]) -> [(Tag, &[u8]); 5] {
    [
        (Tag::HEAD, b"head"),
        (Tag::CLRS, b"clers"),
        (Tag::TOPO, b""),
        (Tag::GEOM, b"geom"),
        (Tag::META, meta),
    ]
}

fn header() -> Header {
    Header::new(Mode::Swing, 4, 4, 1).with_framing(Framing::Compact)
}

/// A tetrahedron's counts, swing mode, the golden sections, compact.
fn sample() -> Vec<u8> {
    write_container(&header(), &sections(&golden_meta())).unwrap()
}

fn parse(bytes: &[u8]) -> Result<Container<'_>, Error> {
    parse_container(bytes, &Limits::default())
}

fn malformed(result: Result<Container<'_>, Error>) -> (Malformed, Option<Location>) {
    match result {
        Err(Error::Format(e)) => (e.what, e.at),
        other => panic!("expected a format error, got {other:?}"),
    }
}

fn refresh_crc(bytes: &mut [u8]) {
    let n = bytes.len() - 4;
    let crc = crc32(&bytes[..n]);
    bytes[n..].copy_from_slice(&crc.to_le_bytes());
}

/// A compact file assembled by hand from its framing bytes and payloads
/// (so tests can write what the writer never would), CRC appended.
fn forge(frame: &[u8], payload: &[u8]) -> Vec<u8> {
    let mut b = b"SWM\x00\x01\x01\x01\x00".to_vec();
    b.extend_from_slice(frame);
    b.extend_from_slice(payload);
    b.extend_from_slice(&[0; 4]);
    refresh_crc(&mut b);
    b
}

#[test]
fn round_trip_and_the_bytes_it_saves() {
    let meta = golden_meta();
    let s = sections(&meta);
    let bytes = sample();
    assert_eq!(bytes.len(), container_len(&header(), &s));
    let c = parse(&bytes).unwrap();
    assert_eq!(c.header, header());
    assert_eq!((c.header.minor, c.header.flags), (1, FLAG_COMPACT));
    assert_eq!(c.header.framing(), Framing::Compact);
    let got: Vec<_> = c.sections().map(|s| (s.tag, s.bytes)).collect();
    assert_eq!(got, s);
    assert_eq!(c.sections().len(), 5);
    for s in c.sections() {
        assert_eq!(&bytes[s.offset..s.offset + s.bytes.len()], s.bytes);
    }
    // Preamble 8, mode and three counts 4, section count 1, five entries
    // of 2: 23 bytes of frame where the fixed framing has 63.
    assert_eq!(c.frame_len(), 23);
    let fixed = write_container(&Header::new(Mode::Swing, 4, 4, 1), &s).unwrap();
    assert_eq!(fixed.len() - bytes.len(), 40);
    // The same file in either framing, both ways.
    assert_eq!(reframe(&fixed, Framing::Compact), bytes);
    let back = reframe(&bytes, Framing::Fixed);
    assert_eq!(parse(&back).unwrap().header.framing(), Framing::Fixed);
    let n = fixed.len() - 4;
    assert_eq!(&back[8..n], &fixed[8..n], "only the minor version differs");
}

#[test]
fn varint_lengths_and_counts_at_their_limits() {
    for v in [0u64, 1, 127, 128, 16_383, 16_384, u32::MAX as u64] {
        let mut b = Vec::new();
        crate::varint::put(&mut b, v);
        assert_eq!(b.len(), varu_len(v), "{v}");
    }
    // u32::MAX counts (UNLIMITED), 65,535 sections, a 300-byte payload.
    let h = Header::new(Mode::Lossless, u32::MAX, u32::MAX, 7).with_framing(Framing::Compact);
    let payload = [7u8; 300];
    let mut many: Vec<(Tag, &[u8])> = vec![(Tag(*b"xbig"), &payload[..])];
    many.extend((1..65_535).map(|_| (Tag(*b"xnil"), &[][..])));
    let bytes = write_container(&h, &many).unwrap();
    assert_eq!(bytes.len(), container_len(&h, &many));
    let c = parse_container(&bytes, &Limits::UNLIMITED).unwrap();
    assert_eq!(c.header, h);
    assert_eq!(c.section_count(), 65_535);
    assert_eq!(c.sections().next().unwrap().bytes, payload);
    assert!(matches!(parse(&bytes), Err(Error::LimitExceeded(_))));
}

#[test]
fn every_registered_tag_has_one_code_and_others_are_literal() {
    for (k, t) in CODES.iter().enumerate() {
        assert_eq!(code_of(*t), Some(k as u8 + 1));
        assert!(t.is_known());
    }
    // An ancillary tag of an application travels literally and is skipped.
    let s: [(Tag, &[u8]); 2] = [(Tag::HEAD, b"h"), (Tag(*b"xApp"), b"data")];
    let bytes = write_container(&header(), &s).unwrap();
    let c = parse(&bytes).unwrap();
    let got: Vec<_> = c.sections().map(|s| (s.tag, s.bytes)).collect();
    assert_eq!(got, s);
    // An unknown critical tag written literally is unsupported, as in 1.0.
    let s: [(Tag, &[u8]); 1] = [(Tag(*b"XTRA"), b"x")];
    let bytes = write_container(&header(), &s).unwrap();
    match parse(&bytes) {
        Err(Error::Unsupported(e)) => {
            assert_eq!(e.feature, UnsupportedFeature::CriticalSection(*b"XTRA"))
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn reserved_codes_are_unsupported_and_bad_literals_malformed() {
    // mode 1, V 4, T 4, C 1, one section with code 18 (the first
    // reserved one; 17 is `ATTR`).
    let b = forge(&[1, 4, 4, 1, 1, 18, 0], &[]);
    match parse(&b) {
        Err(Error::Unsupported(e)) => {
            assert_eq!(e.feature, UnsupportedFeature::SectionCode(18));
            assert!(e.to_string().contains("tag code 18"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    let b = forge(&[1, 4, 4, 1, 1, 0, b'H', b'E', b'1', b'D', 0], &[]);
    assert_eq!(
        malformed(parse(&b)),
        (
            Malformed::BadSectionTag { tag: *b"HE1D" },
            Some(Location::Byte(14))
        )
    );
}

#[test]
fn only_shortest_varints_and_values_in_range() {
    // V = 4 written in two bytes.
    let b = forge(&[1, 0x84, 0x00, 4, 1, 0], &[]);
    assert_eq!(
        malformed(parse(&b)),
        (Malformed::BadNumber, Some(Location::Byte(9)))
    );
    // T = 2^32.
    let b = forge(&[1, 4, 0x80, 0x80, 0x80, 0x80, 0x10, 1, 0], &[]);
    assert_eq!(malformed(parse(&b)).0, Malformed::BadNumber);
    // 65,536 sections.
    let b = forge(&[1, 4, 4, 1, 0x80, 0x80, 0x04], &[]);
    assert_eq!(malformed(parse(&b)).0, Malformed::BadNumber);
    // A length of 2^32.
    let b = forge(&[1, 4, 4, 1, 1, 1, 0x80, 0x80, 0x80, 0x80, 0x10], &[]);
    assert_eq!(malformed(parse(&b)).0, Malformed::BadNumber);
    // The same file with its numbers in shortest form parses.
    assert!(parse(&forge(&[1, 4, 4, 1, 1, 1, 2], b"hd")).is_ok());
}

#[test]
fn lying_lengths_counts_and_tables() {
    // A length past the CRC, named at its entry.
    let b = forge(&[1, 4, 4, 1, 1, 1, 3], b"hd");
    assert_eq!(
        malformed(parse(&b)),
        (
            Malformed::SectionOutOfBounds {
                tag: *b"HEAD",
                end: 18,
                limit: 17
            },
            Some(Location::Byte(14))
        )
    );
    // The first of two sections runs past the CRC only once the whole
    // table is counted: still the one named.
    let b = forge(&[1, 4, 4, 1, 2, 1, 3, 4, 0], b"hg");
    assert_eq!(
        malformed(parse(&b)),
        (
            Malformed::SectionOutOfBounds {
                tag: *b"HEAD",
                end: 20,
                limit: 19
            },
            Some(Location::Byte(14))
        )
    );
    // A payload shorter than the bytes left: trailing data.
    let b = forge(&[1, 4, 4, 1, 1, 1, 1], b"hd");
    assert_eq!(malformed(parse(&b)).0, Malformed::TrailingData);
    // More entries than the bytes hold.
    let b = forge(&[1, 4, 4, 1, 9, 1, 0], &[]);
    assert_eq!(malformed(parse(&b)).0, Malformed::Truncated);
    // A header that runs into the CRC.
    let b = forge(&[1, 0x84], &[]);
    assert_eq!(malformed(parse(&b)).0, Malformed::Truncated);
    // A critical code twice.
    let b = forge(&[1, 4, 4, 1, 2, 1, 0, 1, 0], &[]);
    assert_eq!(
        malformed(parse(&b)),
        (
            Malformed::DuplicateSection { tag: *b"HEAD" },
            Some(Location::Byte(15))
        )
    );
    // Counts that break the header's rules, located at the count.
    let b = forge(&[1, 4, 4, 5, 0], &[]);
    assert_eq!(
        malformed(parse(&b)),
        (
            Malformed::BadHeader("more components than triangles"),
            Some(Location::Byte(11))
        )
    );
    // Limits, as soon as the count is read.
    let tight = Limits {
        max_faces: 3,
        ..Limits::default()
    };
    assert!(matches!(
        parse_container(&sample(), &tight),
        Err(Error::LimitExceeded(LimitError {
            what: Limited::Faces,
            requested: 4,
            limit: 3
        }))
    ));
}

#[test]
fn every_truncation_and_bit_flip_is_an_error() {
    let bytes = sample();
    for n in 0..bytes.len() {
        assert!(parse(&bytes[..n]).is_err(), "prefix of {n} bytes");
    }
    for i in 4..bytes.len() {
        for bit in 0..8 {
            let mut damaged = bytes.clone();
            damaged[i] ^= 1 << bit;
            assert!(
                matches!(
                    malformed(parse(&damaged)).0,
                    Malformed::ChecksumMismatch { .. }
                ),
                "byte {i} bit {bit}"
            );
        }
    }
    // A good file followed by garbage says so.
    let mut long = bytes.clone();
    long.extend_from_slice(b"junk");
    assert_eq!(
        malformed(parse(&long)),
        (
            Malformed::TrailingData,
            Some(Location::Byte(bytes.len() as u64))
        )
    );
}

#[test]
fn random_overwrites_never_panic() {
    let bytes = sample();
    let mut rng = crate::mesh::test_rng::Rng(0x5EED_C0DE_0000_0011);
    let mut accepted = 0;
    for round in 0..20_000 {
        let mut b = bytes.clone();
        for _ in 0..1 + rng.next_u64() % 4 {
            let i = 4 + (rng.next_u64() % (b.len() as u64 - 4)) as usize;
            b[i] = rng.next_u64() as u8;
        }
        if round % 8 != 0 {
            refresh_crc(&mut b);
        }
        if let Ok(c) = parse(&b) {
            accepted += 1;
            let mut end = c.frame_len();
            for s in c.sections() {
                assert_eq!(s.offset, end);
                end += s.bytes.len();
            }
            assert_eq!(end + 4, b.len());
            assert_eq!(c.sections().count(), c.section_count());
        }
    }
    assert!(accepted > 0);
}

#[test]
fn golden_v1_1() {
    assert_eq!(sample(), GOLDEN_V1_1, "the compact writer changed");
    let c = parse(GOLDEN_V1_1).unwrap();
    assert_eq!(
        c.header,
        Header {
            major: 1,
            minor: 1,
            flags: 1,
            mode: Mode::Swing,
            vertex_count: 4,
            triangle_count: 4,
            component_count: 1,
        }
    );
    let meta = golden_meta();
    let got: Vec<_> = c.sections().map(|s| (s.tag, s.offset, s.bytes)).collect();
    let want: Vec<_> = sections(&meta)
        .iter()
        .zip([23, 27, 32, 32, 36])
        .map(|(&(t, b), o)| (t, o, b))
        .collect();
    assert_eq!(got, want);
    assert_eq!(GOLDEN_V1_1.len(), 57);
}
