//! Bare mode-0 bodies (format 1.2, mode 2's `BASE` when its `HEAD` sets
//! bit 6): the writer and parser mirror each other, and every check of a
//! compact file's head and table holds inside the body, with the counts
//! the body does not carry taken from the enclosing file.

use super::*;
use crate::{Error, Limits, Malformed};

/// A mode-2 file's header: its component count and version are what a
/// bare body inherits.
fn enclosing() -> Header {
    let mut h = Header::new(Mode::Displaced, 64, 64, 1).with_framing(Framing::Compact);
    h.minor = 2;
    h
}

fn base_header() -> Header {
    Header::new(Mode::Lossless, 4, 4, 1).with_framing(Framing::Compact)
}

fn sections() -> [(Tag, &'static [u8]); 3] {
    [
        (Tag::HEAD, b"head"),
        (Tag::CLRS, b"clers"),
        (Tag::GEOM, b"geom"),
    ]
}

fn parse(body: &[u8]) -> Result<Container<'_>, Error> {
    parse_bare(body, &enclosing(), &Limits::default())
}

fn malformed(result: Result<Container<'_>, Error>) -> Malformed {
    match result {
        Err(Error::Format(e)) => e.what,
        other => panic!("expected a format error, got {other:?}"),
    }
}

#[test]
fn a_bare_body_is_the_compact_file_without_its_frame() {
    let body = write_bare(&base_header(), &sections()).unwrap();
    let file = write_container(&base_header(), &sections()).unwrap();
    // The file's preamble (8), mode (1), component count (1) and CRC (4).
    assert_eq!(file.len() - body.len(), 14);
    let c = parse(&body).unwrap();
    assert_eq!(c.header.mode, Mode::Lossless);
    assert_eq!((c.header.vertex_count, c.header.triangle_count), (4, 4));
    assert_eq!(c.header.component_count, enclosing().component_count);
    assert_eq!(c.header.minor, 2);
    let got: Vec<(Tag, &[u8])> = c.sections().map(|s| (s.tag, s.bytes)).collect();
    assert_eq!(got, sections().to_vec());
    // The same sections as the whole file's.
    let whole = parse_container(&file, &Limits::default()).unwrap();
    assert!(whole
        .sections()
        .map(|s| s.bytes)
        .eq(c.sections().map(|s| s.bytes)));
}

#[test]
fn every_prefix_of_a_bare_body_is_an_error() {
    let body = write_bare(&base_header(), &sections()).unwrap();
    for n in 0..body.len() {
        assert!(parse(&body[..n]).is_err(), "prefix of {n} bytes parsed");
    }
}

#[test]
fn trailing_bytes_and_overruns_are_malformed() {
    let mut body = write_bare(&base_header(), &sections()).unwrap();
    body.push(0);
    assert_eq!(malformed(parse(&body)), Malformed::TrailingData);
    // GEOM's length (the last entry's, after V, T, n and two entries)
    // one more than its payload.
    let mut body = write_bare(&base_header(), &sections()).unwrap();
    let at = 3 + 2 + 2 + 1;
    assert_eq!(body[at], 4);
    body[at] = 5;
    assert!(matches!(
        malformed(parse(&body)),
        Malformed::SectionOutOfBounds { .. }
    ));
}

#[test]
fn counts_are_checked_against_each_other_and_the_limits() {
    // V above 3T: a triangle's corners cannot hold so many vertices.
    let bad = write_bare(&Header::new(Mode::Lossless, 13, 4, 1), &sections()).unwrap();
    assert!(matches!(malformed(parse(&bad)), Malformed::BadHeader(_)));
    // More triangles than the limits allow, before any allocation.
    let huge = write_bare(&Header::new(Mode::Lossless, 4, u32::MAX, 1), &sections()).unwrap();
    assert!(matches!(parse(&huge), Err(Error::LimitExceeded(_))));
    // A count not in its shortest form.
    let mut long = vec![0x84, 0x00];
    long.extend_from_slice(&write_bare(&base_header(), &sections()).unwrap()[1..]);
    assert_eq!(malformed(parse(&long)), Malformed::BadNumber);
}

#[test]
fn a_critical_section_twice_is_malformed() {
    let mut body = vec![4, 4, 2];
    for _ in 0..2 {
        body.extend_from_slice(&[code_of_geom(), 1]);
    }
    body.extend_from_slice(b"gg");
    assert!(matches!(
        malformed(parse(&body)),
        Malformed::DuplicateSection { .. }
    ));
}

fn code_of_geom() -> u8 {
    super::compact::code_of(Tag::GEOM).unwrap()
}
