//! The container's malformed-input matrix (STYLE.md items 10 and 11):
//! round trip, every truncation, every bit flip, versions, lying lengths,
//! trailing bytes, limits, random overwrites, and the 1.0 golden file.

use super::*;
use crate::{Error, LimitError, Limited, Limits, Location, Malformed};

/// The golden file of format 1.0. Never regenerate it: a change to these
/// bytes is a format change and needs a new version (format-spec/versions.md).
const GOLDEN_V1_0: &[u8] = include_bytes!("../../../format-spec/golden/container-v1.0.bin");

/// The sections of the golden file. The payloads are placeholders: the
/// container does not look inside them.
fn golden_sections(meta: &[u8]) -> [(Tag, &[u8]); 5] {
    [
        (Tag::HEAD, b"head"),
        (Tag::CLRS, b"clers"),
        (Tag::TOPO, b""),
        (Tag::GEOM, b"geom"),
        (Tag::META, meta),
    ]
}

fn golden_meta() -> Vec<u8> {
    write_meta(&[("generator", b"swm")])
}

/// A tetrahedron's counts, swing mode, the golden sections.
fn sample() -> Vec<u8> {
    let meta = golden_meta();
    write_container(&Header::new(Mode::Swing, 4, 4, 1), &golden_sections(&meta)).unwrap()
}

fn parse(bytes: &[u8]) -> Result<Container<'_>, Error> {
    parse_container(bytes, &Limits::default())
}

/// What a container format error says is wrong, and where.
fn malformed(result: Result<Container<'_>, Error>) -> (Malformed, Option<Location>) {
    match result {
        Err(Error::Format(e)) => {
            assert_eq!(e.format, "SWM");
            (e.what, e.at)
        }
        other => panic!("expected a format error, got {other:?}"),
    }
}

fn unsupported(result: Result<Container<'_>, Error>) -> UnsupportedError {
    match result {
        Err(Error::Unsupported(e)) => e,
        other => panic!("expected an unsupported error, got {other:?}"),
    }
}

/// Recomputes the trailing CRC after a deliberate edit, so the edit reaches
/// the checks behind the checksum.
fn refresh_crc(bytes: &mut [u8]) {
    let n = bytes.len() - 4;
    let crc = crc32(&bytes[..n]);
    bytes[n..].copy_from_slice(&crc.to_le_bytes());
}

/// File offset of section table entry `i`.
fn entry(i: usize) -> usize {
    23 + 8 * i
}

#[test]
fn round_trip() {
    let meta = golden_meta();
    let sections = golden_sections(&meta);
    let header = Header::new(Mode::Swing, 4, 4, 1);
    let bytes = write_container(&header, &sections).unwrap();
    assert_eq!(bytes.len(), container_len(&header, &sections));
    let c = parse(&bytes).unwrap();
    assert_eq!(c.header, header);
    assert_eq!(c.section_count(), 5);
    let got: Vec<_> = c.sections().map(|s| (s.tag, s.bytes)).collect();
    assert_eq!(got, sections);
    assert!(c.sections().all(|s| s.is_known()));
    assert_eq!(c.sections().len(), 5);
    assert_eq!(c.section(Tag::CLRS), Some(&b"clers"[..]));
    assert_eq!(c.section(Tag::TOPO), Some(&b""[..]));
    assert_eq!(c.section(Tag::HOLE), None);
    // Offsets point at the payloads in the file.
    for s in c.sections() {
        assert_eq!(&bytes[s.offset..s.offset + s.bytes.len()], s.bytes);
    }
    let m = c.require(Tag::META).unwrap();
    let entries: Vec<_> = meta_entries(&m).map(Result::unwrap).collect();
    assert_eq!(
        entries,
        [MetaEntry {
            key: "generator",
            value: b"swm"
        }]
    );
}

#[test]
fn write_into_appends() {
    let meta = golden_meta();
    let mut out = b"prefix".to_vec();
    let n = write_container_into(
        &Header::new(Mode::Swing, 4, 4, 1),
        &golden_sections(&meta),
        &mut out,
    )
    .unwrap();
    assert_eq!(&out[..6], b"prefix");
    assert_eq!(out.len(), 6 + n);
    assert_eq!(out[6..], sample());
}

#[test]
fn empty_container() {
    let header = Header::new(Mode::Lossless, 0, 0, 0);
    let bytes = write_container(&header, &[]).unwrap();
    assert_eq!(bytes.len(), 27);
    let c = parse(&bytes).unwrap();
    assert_eq!(c.header, header);
    assert_eq!(c.sections().count(), 0);
}

#[test]
fn require_names_the_missing_section() {
    let bytes = sample();
    let err = parse(&bytes).unwrap().require(Tag::HOLE).unwrap_err();
    assert!(matches!(
        err,
        Error::Format(ref e) if e.what == Malformed::MissingSection { tag: *b"HOLE" }
    ));
}

#[test]
fn every_truncation_is_an_error() {
    let bytes = sample();
    for n in 0..bytes.len() {
        let (what, _) = malformed(parse(&bytes[..n]));
        let expected_kind = match n {
            0 => matches!(what, Malformed::Empty),
            1..=9 => what == Malformed::Truncated,
            _ => matches!(what, Malformed::ChecksumMismatch { .. }),
        };
        assert!(expected_kind, "prefix of {n} bytes: {what:?}");
    }
}

#[test]
fn every_bit_flip_is_a_checksum_error() {
    let bytes = sample();
    for i in 0..bytes.len() {
        for bit in 0..8 {
            let mut damaged = bytes.clone();
            damaged[i] ^= 1 << bit;
            let (what, at) = malformed(parse(&damaged));
            if i < 4 {
                // A file that does not start with the magic is not an .swm
                // file; no decoder can tell a damaged magic from another format.
                assert_eq!(what, Malformed::BadMagic, "byte {i} bit {bit}");
            } else {
                assert!(
                    matches!(what, Malformed::ChecksumMismatch { .. }),
                    "byte {i} bit {bit}: {what:?}"
                );
                assert_eq!(at, Some(Location::Byte(bytes.len() as u64 - 4)));
            }
        }
    }
}

#[test]
fn wrong_magic() {
    for bytes in [
        &b"ply\nformat binary_little_endian 1.0\n"[..],
        b"P",
        b"SWM\x01rest-of-file",
        b"swm\0",
    ] {
        assert_eq!(malformed(parse(bytes)).0, Malformed::BadMagic, "{bytes:?}");
    }
    assert_eq!(
        malformed(parse(b"SW")),
        (Malformed::Truncated, Some(Location::Byte(2)))
    );
}

#[test]
fn other_major_versions_are_unsupported() {
    for major in [0, 2, 255] {
        let mut header = Header::new(Mode::Swing, 4, 4, 1);
        header.major = major;
        header.minor = 3;
        let bytes = write_container(&header, &[]).unwrap();
        let e = unsupported(parse(&bytes));
        assert_eq!(
            e,
            UnsupportedError {
                feature: UnsupportedFeature::Version,
                major,
                minor: 3,
                supported_major: FORMAT_MAJOR,
                supported_minor: FORMAT_MINOR,
            }
        );
        let text = Error::from(e).to_string();
        assert!(
            text.contains(&format!("{major}.3"))
                && text.contains(&format!("{FORMAT_MAJOR}.{FORMAT_MINOR}")),
            "{text}"
        );
    }
}

#[test]
fn newer_minor_skips_unknown_ancillary_sections() {
    let mut header = Header::new(Mode::Swing, 4, 4, 1);
    header.minor = FORMAT_MINOR + 1;
    header.flags = 0x0100; // an optional flag a later minor version might define
    let sections: [(Tag, &[u8]); 3] = [
        (Tag::HEAD, b"h"),
        (Tag(*b"xtra"), b"from the future"),
        (Tag::GEOM, b"g"),
    ];
    let bytes = write_container(&header, &sections).unwrap();
    let c = parse(&bytes).unwrap();
    assert_eq!(c.header, header);
    let known: Vec<_> = c.sections().map(|s| (s.tag, s.is_known())).collect();
    assert_eq!(
        known,
        [(Tag::HEAD, true), (Tag(*b"xtra"), false), (Tag::GEOM, true)]
    );
    assert_eq!(c.section(Tag::GEOM), Some(&b"g"[..]));
}

#[test]
fn unknown_critical_section_is_unsupported() {
    let mut header = Header::new(Mode::Swing, 4, 4, 1);
    header.minor = FORMAT_MINOR + 1;
    let bytes = write_container(&header, &[(Tag::HEAD, b"h"), (Tag(*b"XTRA"), b"x")]).unwrap();
    let e = unsupported(parse(&bytes));
    assert_eq!(e.feature, UnsupportedFeature::CriticalSection(*b"XTRA"));
    assert_eq!((e.major, e.minor), (1, FORMAT_MINOR + 1));
}

#[test]
fn unknown_required_flag_and_mode_are_unsupported() {
    let mut bytes = sample();
    // Bit 0 is 1.1's compact framing; bits 1 and 2 are nobody's.
    bytes[6] = 0x07;
    refresh_crc(&mut bytes);
    assert_eq!(
        unsupported(parse(&bytes)).feature,
        UnsupportedFeature::RequiredFlags(0x0006)
    );
    let mut bytes = sample();
    bytes[8] = 7;
    refresh_crc(&mut bytes);
    assert_eq!(
        unsupported(parse(&bytes)).feature,
        UnsupportedFeature::Mode(7)
    );
}

#[test]
fn lying_section_lengths() {
    let bytes = sample();
    let geom_len = entry(3) + 4;
    let set_len = |len: u32| {
        let mut b = bytes.clone();
        b[geom_len..geom_len + 4].copy_from_slice(&len.to_le_bytes());
        refresh_crc(&mut b);
        b
    };
    let crc_at = bytes.len() as u64 - 4;
    // One byte too long: GEOM would swallow meta's last byte and meta the CRC.
    let (what, at) = malformed(parse(&set_len(5)));
    assert!(
        matches!(what, Malformed::SectionOutOfBounds { tag, end, limit } if &tag == b"meta" && end == crc_at + 1 && limit == crc_at),
        "{what:?}"
    );
    assert_eq!(at, Some(Location::Byte(entry(4) as u64 + 4)));
    // Far too long, on GEOM itself.
    let (what, at) = malformed(parse(&set_len(u32::MAX)));
    assert!(matches!(what, Malformed::SectionOutOfBounds { tag, .. } if &tag == b"GEOM"));
    assert_eq!(at, Some(Location::Byte(geom_len as u64)));
    // One byte too short: a byte belongs to no section.
    let (what, at) = malformed(parse(&set_len(3)));
    assert_eq!(what, Malformed::TrailingData);
    assert_eq!(at, Some(Location::Byte(crc_at - 1)));
    // A section count the table cannot hold.
    let mut b = bytes.clone();
    b[21..23].copy_from_slice(&u16::MAX.to_le_bytes());
    refresh_crc(&mut b);
    assert_eq!(
        malformed(parse(&b)),
        (Malformed::Truncated, Some(Location::Byte(21)))
    );
    // One entry more: the table reads into the payloads, whose bytes make
    // no valid sixth entry.
    let mut b = bytes.clone();
    b[21] += 1;
    refresh_crc(&mut b);
    assert!(parse(&b).is_err());
}

#[test]
fn trailing_bytes() {
    let bytes = sample();
    // Garbage after a valid file: the CRC found where the table says the
    // file ends still verifies, so the error says what happened.
    for extra in [&b"\0"[..], b"junk", &[0xFF; 100]] {
        let mut b = bytes.clone();
        b.extend_from_slice(extra);
        assert_eq!(
            malformed(parse(&b)),
            (
                Malformed::TrailingData,
                Some(Location::Byte(bytes.len() as u64))
            )
        );
    }
    // Extra bytes inside the checksummed area, after the last payload.
    let mut b = bytes[..bytes.len() - 4].to_vec();
    b.extend_from_slice(b"junk\0\0\0\0");
    refresh_crc(&mut b);
    assert_eq!(
        malformed(parse(&b)),
        (
            Malformed::TrailingData,
            Some(Location::Byte(bytes.len() as u64 - 4))
        )
    );
}

#[test]
fn duplicate_and_bad_tags() {
    let bytes = sample();
    // GEOM renamed CLRS: a second critical CLRS.
    let mut b = bytes.clone();
    b[entry(3)..entry(3) + 4].copy_from_slice(b"CLRS");
    refresh_crc(&mut b);
    assert_eq!(
        malformed(parse(&b)),
        (
            Malformed::DuplicateSection { tag: *b"CLRS" },
            Some(Location::Byte(entry(3) as u64))
        )
    );
    // Ancillary sections may repeat; `section` gives the first.
    let two = write_container(
        &Header::new(Mode::Swing, 4, 4, 1),
        &[(Tag::META, b""), (Tag::HEAD, b"h"), (Tag::META, b"x")],
    )
    .unwrap();
    let c = parse(&two).unwrap();
    assert_eq!(c.section(Tag::META), Some(&b""[..]));
    assert_eq!(c.sections().filter(|s| s.tag == Tag::META).count(), 2);
    // A tag that is not four letters.
    let mut b = bytes.clone();
    b[entry(1) + 2] = b'1';
    refresh_crc(&mut b);
    assert_eq!(
        malformed(parse(&b)),
        (
            Malformed::BadSectionTag { tag: *b"CL1S" },
            Some(Location::Byte(entry(1) as u64))
        )
    );
}

#[test]
fn counts_above_limits_are_rejected() {
    let bytes = sample();
    let tight = Limits {
        max_vertices: 3,
        ..Limits::default()
    };
    assert!(matches!(
        parse_container(&bytes, &tight),
        Err(Error::LimitExceeded(LimitError {
            what: Limited::Vertices,
            requested: 4,
            limit: 3
        }))
    ));
    let tight = Limits {
        max_faces: 2,
        ..Limits::default()
    };
    assert!(matches!(
        parse_container(&bytes, &tight),
        Err(Error::LimitExceeded(LimitError {
            what: Limited::Faces,
            requested: 4,
            limit: 2
        }))
    ));
    // u32::MAX triangles pass UNLIMITED but not the default limits.
    let huge = write_container(&Header::new(Mode::Swing, u32::MAX, u32::MAX, 1), &[]).unwrap();
    assert!(matches!(parse(&huge), Err(Error::LimitExceeded(_))));
    assert!(parse_container(&huge, &Limits::UNLIMITED).is_ok());
}

#[test]
fn inconsistent_counts_are_rejected() {
    for (v, t, c) in [
        (4, 4, 5),
        (4, 4, 0),
        (13, 4, 1),
        (2, 1, 1),
        (1, 0, 0),
        (0, 0, 1),
    ] {
        let bytes = write_container(&Header::new(Mode::Swing, v, t, c), &[]).unwrap();
        let (what, _) = malformed(parse(&bytes));
        assert!(
            matches!(what, Malformed::BadHeader(_)),
            "{v} {t} {c}: {what:?}"
        );
    }
}

#[test]
fn writer_rejects_unframeable_input() {
    let many = vec![(Tag::META, &b""[..]); 65_536];
    let header = Header::new(Mode::Swing, 4, 4, 1);
    let mut out = b"kept".to_vec();
    assert!(matches!(
        write_container_into(&header, &many, &mut out),
        Err(Error::Parameter(_))
    ));
    assert_eq!(out, b"kept");
    assert!(write_container(&header, &many[..65_535]).is_ok());
}

#[test]
#[should_panic(expected = "not four ASCII letters")]
fn writer_panics_on_a_bad_tag() {
    let _ = write_container(&Header::new(Mode::Swing, 4, 4, 1), &[(Tag(*b"AB1D"), b"")]);
}

#[test]
#[should_panic(expected = "given twice")]
fn writer_panics_on_a_repeated_critical_tag() {
    let _ = write_container(
        &Header::new(Mode::Swing, 4, 4, 1),
        &[(Tag::GEOM, b""), (Tag::GEOM, b"")],
    );
}

/// xorshift64*: deterministic, dependency-free.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

#[test]
fn random_overwrites_never_panic() {
    let bytes = sample();
    let mut rng = Rng(0x5EED_0F5A_1D00_0001);
    let mut accepted = 0;
    for round in 0..20_000 {
        let mut b = bytes.clone();
        for _ in 0..1 + rng.below(4) {
            let i = 4 + rng.below(b.len() - 4); // keep the magic: reach the checks behind it
            b[i] = rng.next() as u8;
        }
        if rng.below(4) == 0 {
            b.truncate(rng.below(b.len() + 1).max(10));
        }
        // Most rounds re-sign the damage, so it reaches the structural checks.
        if round % 8 != 0 && b.len() >= 4 {
            refresh_crc(&mut b);
        }
        if let Ok(c) = parse(&b) {
            accepted += 1;
            let mut end = 23 + 8 * c.section_count();
            for s in c.sections() {
                assert_eq!(s.offset, end);
                end += s.bytes.len();
            }
            assert_eq!(end + 4, b.len());
            assert!(c.sections().all(|s| s.tag.is_valid()));
        }
    }
    // Some overwrites only touch payload bytes and stay valid files.
    assert!(accepted > 0);
}

#[test]
fn golden_v1_0() {
    // The writer still produces the released bytes.
    assert_eq!(
        sample(),
        GOLDEN_V1_0,
        "the writer changed the 1.0 byte layout"
    );
    let c = parse(GOLDEN_V1_0).unwrap();
    assert_eq!(
        c.header,
        Header {
            major: 1,
            minor: 0,
            flags: 0,
            mode: Mode::Swing,
            vertex_count: 4,
            triangle_count: 4,
            component_count: 1,
        }
    );
    let meta = golden_meta();
    let got: Vec<_> = c.sections().map(|s| (s.tag, s.offset, s.bytes)).collect();
    let want: Vec<_> = golden_sections(&meta)
        .iter()
        .zip([63, 67, 72, 72, 76])
        .map(|(&(t, b), o)| (t, o, b))
        .collect();
    assert_eq!(got, want);
    assert_eq!(GOLDEN_V1_0.len(), 97);
    assert_eq!(&GOLDEN_V1_0[93..], crc32(&GOLDEN_V1_0[..93]).to_le_bytes());
}
