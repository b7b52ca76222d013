//! Structured mutations of small valid `.swm` files of every kind the
//! encoder writes (lossless, swing, swing with a `HOLE` section, swing
//! with a `REST` section), decoded through the library.
//!
//! Two families, because the CRC-32 decides which code a mutation reaches:
//! - mutations that leave the CRC alone (truncation, bit flips, appended
//!   bytes, a new magic) must stop at the frame, with the frame's own
//!   error kind: the decoders proper never see a damaged byte;
//! - mutations whose CRC is fixed afterwards (lying header fields and
//!   section lengths, overwritten payload bytes) reach the header, table
//!   and mode decoders, which must refuse them or decode a valid mesh,
//!   and never panic.

mod common;
use common::{samples, samples_in_both_framings, Frame};

use std::panic::{catch_unwind, AssertUnwindSafe};
use swm::container::crc32;
use swm::{DecodeOptions, Error, Malformed, TriMesh};

/// Offsets of the preamble, the same in every framing
/// (format-spec/01-container.md).
const MAJOR: usize = 4;
const MINOR: usize = 5;
const FLAGS: usize = 6;

/// Where a valid file's first payload starts (its frame's length).
fn table_end(b: &[u8]) -> usize {
    swm::container::parse_container(b, &Default::default())
        .unwrap()
        .frame_len()
}

fn fix_crc(b: &mut [u8]) {
    let n = b.len() - 4;
    let crc = crc32(&b[..n]);
    b[n..].copy_from_slice(&crc.to_le_bytes());
}

/// Decodes, turning a panic into a test failure that names the case.
fn try_decode(bytes: &[u8], options: &DecodeOptions, what: &str) -> Result<TriMesh, Error> {
    let decoded = catch_unwind(AssertUnwindSafe(|| swm::decode(bytes, options)));
    let inspected = catch_unwind(AssertUnwindSafe(|| swm::inspect(bytes, &options.limits)));
    match (decoded, inspected) {
        (Ok(d), Ok(i)) => {
            // `inspect` reads a subset of what `decode` reads: it may not
            // refuse a file that decodes.
            if d.is_ok() {
                assert!(i.is_ok(), "{what}: decodes but inspect fails: {i:?}");
            }
            d
        }
        _ => panic!("{what}: the decoder panicked"),
    }
}

/// A mutated file whose CRC still holds must be refused or decode to a
/// valid mesh.
fn refused_or_valid(bytes: &[u8], what: &str) -> Outcome {
    let Ok(mesh) = try_decode(bytes, &DecodeOptions::default(), what) else {
        return Outcome::Refused;
    };
    {
        assert!(
            mesh.validate().is_ok(),
            "{what}: decodes to an invalid mesh"
        );
        // Whatever mesh a mutated file gives goes through Sharpen&Bend
        // too; it may refuse it, but not panic.
        let post = DecodeOptions {
            sharpen: Some(true),
            bend_steps: Some(1),
            ..Default::default()
        };
        if let Ok(mesh) = try_decode(bytes, &post, what) {
            assert!(
                mesh.validate().is_ok(),
                "{what}: sharpened and bent into an invalid mesh"
            );
        }
    }
    Outcome::Decoded
}

/// What became of a mutated file.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Outcome {
    Refused,
    Decoded,
}

/// How many mutated files of a test were refused and how many decoded
/// (to valid meshes): a test whose mutations were all refused, or all
/// decoded, exercised only one side of the decoder's checks.
#[derive(Default, Debug)]
struct Tally {
    refused: u64,
    decoded: u64,
}

impl Tally {
    fn add(&mut self, outcome: Outcome) {
        match outcome {
            Outcome::Refused => self.refused += 1,
            Outcome::Decoded => self.decoded += 1,
        }
    }

    /// Fails the test unless both outcomes occurred.
    fn both(&self, what: &str) {
        println!("{what}: {self:?}");
        assert!(
            self.refused > 0,
            "{what}: no mutation was refused ({self:?})"
        );
        assert!(self.decoded > 0, "{what}: no mutation decoded ({self:?})");
    }
}

fn format_error(e: &Error) -> Option<&Malformed> {
    match e {
        Error::Format(f) => Some(&f.what),
        _ => None,
    }
}

/// How long one refused decode may take before a test calls it hung: a
/// guard against allocating or looping through what a header declares,
/// generous so that a loaded machine passes (speed is BENCHMARKS.md's).
const HANG_GUARD: std::time::Duration = std::time::Duration::from_secs(30);
#[test]
fn samples_decode_and_are_small() {
    for s in samples() {
        println!("{}: {} bytes", s.name, s.bytes.len());
        assert!(
            (100..8000).contains(&s.bytes.len()),
            "{}: {} bytes",
            s.name,
            s.bytes.len()
        );
        let mesh = try_decode(&s.bytes, &DecodeOptions::default(), s.name).unwrap();
        assert!(
            mesh.face_count() > 0 && mesh.validate().is_ok(),
            "{}",
            s.name
        );
    }
}

#[test]
fn sharpen_and_bend_on_valid_files() {
    let options = DecodeOptions {
        sharpen: Some(true),
        bend_steps: Some(1),
        ..Default::default()
    };
    for s in samples() {
        // EdgeSharpener may add triangles; each Bender step quadruples.
        let sharpened = DecodeOptions {
            sharpen: Some(true),
            ..Default::default()
        };
        let plain = swm::decode(&s.bytes, &sharpened).unwrap();
        let mesh = try_decode(&s.bytes, &options, s.name).unwrap();
        mesh.validate().unwrap();
        assert_eq!(mesh.face_count(), 4 * plain.face_count(), "{}", s.name);
    }
}

#[test]
fn every_truncation_is_a_format_error() {
    for s in samples() {
        for n in 0..s.bytes.len() {
            let what = format!("{} cut to {n} bytes", s.name);
            let e = try_decode(&s.bytes[..n], &DecodeOptions::default(), &what).expect_err(&what);
            let kind = format_error(&e);
            assert!(
                matches!(
                    kind,
                    Some(
                        Malformed::Empty
                            | Malformed::Truncated
                            | Malformed::ChecksumMismatch { .. }
                    )
                ),
                "{what}: {e:?}"
            );
        }
    }
}

#[test]
fn every_single_bit_flip_is_caught_by_the_checksum() {
    for s in samples() {
        for bit in 0..8 * s.bytes.len() {
            let mut b = s.bytes.clone();
            b[bit / 8] ^= 1 << (bit % 8);
            let what = format!("{} with bit {bit} flipped", s.name);
            let e = try_decode(&b, &DecodeOptions::default(), &what).expect_err(&what);
            // CRC-32 detects every single-bit error; the magic is checked
            // first so that "not an .swm file" wins over "damaged".
            let kind = format_error(&e);
            let expected = if bit / 8 < 4 {
                matches!(kind, Some(Malformed::BadMagic))
            } else {
                matches!(kind, Some(Malformed::ChecksumMismatch { .. }))
            };
            assert!(expected, "{what}: {e:?}");
        }
    }
}

#[test]
fn trailing_garbage_is_refused() {
    for s in samples() {
        for extra in [&b"\0"[..], b"garbage", &s.bytes[..], &[0xFF; 300]] {
            let mut b = s.bytes.clone();
            b.extend_from_slice(extra);
            let what = format!("{} + {} bytes", s.name, extra.len());
            let e = try_decode(&b, &DecodeOptions::default(), &what).expect_err(&what);
            assert!(
                matches!(format_error(&e), Some(Malformed::TrailingData)),
                "{what}: {e:?}"
            );
        }
    }
}

#[test]
fn wrong_magic_is_not_an_swm_file() {
    for s in samples() {
        for magic in [b"SWM\x01", b"swm\0", b"PLY\n", b"\0\0\0\0"] {
            let mut b = s.bytes.clone();
            b[..4].copy_from_slice(magic);
            for fixed in [false, true] {
                if fixed {
                    fix_crc(&mut b);
                }
                let what = format!("{} with magic {magic:?}", s.name);
                let e = try_decode(&b, &DecodeOptions::default(), &what).expect_err(&what);
                assert!(
                    matches!(format_error(&e), Some(Malformed::BadMagic)),
                    "{what}: {e:?}"
                );
            }
        }
    }
}

#[test]
fn other_versions() {
    for s in samples() {
        let plain = swm::decode(&s.bytes, &DecodeOptions::default()).unwrap();
        for major in [0u8, 2, 255] {
            let mut b = s.bytes.clone();
            b[MAJOR] = major;
            fix_crc(&mut b);
            let what = format!("{} as version {major}.x", s.name);
            let e = try_decode(&b, &DecodeOptions::default(), &what).expect_err(&what);
            assert!(matches!(e, Error::Unsupported(_)), "{what}: {e:?}");
        }
        // A newer minor version that sets only optional flags decodes to
        // the same mesh; an unknown required flag is unsupported.
        let mut b = s.bytes.clone();
        b[MINOR] = 9;
        b[FLAGS + 1] = 0x80;
        fix_crc(&mut b);
        let mesh = try_decode(&b, &DecodeOptions::default(), s.name).unwrap();
        assert_eq!(mesh, plain, "{}: minor 9", s.name);
        // Bit 0 is 1.1's compact framing; bit 1 is nobody's.
        b[FLAGS] |= 0x02;
        fix_crc(&mut b);
        let e = try_decode(&b, &DecodeOptions::default(), s.name).unwrap_err();
        assert!(matches!(e, Error::Unsupported(_)), "{}: {e:?}", s.name);
    }
}

#[test]
fn overwritten_header_bytes() {
    for s in samples_in_both_framings() {
        let mut tally = Tally::default();
        // The whole header and section table, each byte set to a few
        // values, first with the CRC left alone (caught by it), then fixed
        // (reaches the header, table and mode decoders).
        for at in 4..table_end(&s.bytes) {
            for v in [0x00, 0x01, 0x7F, 0x80, 0xFF, s.bytes[at].wrapping_add(1)] {
                if v == s.bytes[at] {
                    continue;
                }
                let mut b = s.bytes.clone();
                b[at] = v;
                let what = format!("{} with byte {at} = {v:#x}", s.name);
                let e = try_decode(&b, &DecodeOptions::default(), &what).expect_err(&what);
                assert!(
                    matches!(format_error(&e), Some(Malformed::ChecksumMismatch { .. })),
                    "{what}: {e:?}"
                );
                fix_crc(&mut b);
                tally.add(refused_or_valid(&b, &format!("{what}, CRC fixed")));
            }
        }
        tally.both(&format!("{} header bytes", s.name));
    }
}

#[test]
fn overwritten_payload_bytes_with_the_crc_fixed() {
    for s in samples() {
        let mut tally = Tally::default();
        for at in table_end(&s.bytes)..s.bytes.len() - 4 {
            for v in [0x00, 0xFF, s.bytes[at] ^ 0x10] {
                if v == s.bytes[at] {
                    continue;
                }
                let mut b = s.bytes.clone();
                b[at] = v;
                fix_crc(&mut b);
                tally.add(refused_or_valid(
                    &b,
                    &format!("{} with byte {at} = {v:#x}", s.name),
                ));
            }
        }
        tally.both(&format!("{} payload bytes", s.name));
    }
}

/// The file with section `i`'s length (and so its frame) rewritten.
fn with_length(frame: &Frame, i: usize, len: u64) -> Vec<u8> {
    let mut f = frame.clone();
    f.entries[i].1 = len;
    f.bytes()
}

#[test]
fn sections_with_lying_lengths() {
    for s in samples_in_both_framings() {
        let frame = Frame::of(&s.bytes);
        let n = frame.entries.len();
        for i in 0..n {
            let len = frame.entries[i].1;
            // Too long: runs into the CRC or past the end of the file.
            for longer in [len + 1, len + 4, len + 1000, u64::from(u32::MAX)] {
                let b = with_length(&frame, i, longer);
                let what = format!("{} section {i} length {len} -> {longer}", s.name);
                let e = try_decode(&b, &DecodeOptions::default(), &what).expect_err(&what);
                // A compact entry's length may grow a varint byte, which
                // moves the table's end: still out of bounds.
                assert!(
                    matches!(format_error(&e), Some(Malformed::SectionOutOfBounds { .. })),
                    "{what}: {e:?}"
                );
            }
            // Too short: the payloads stop before the CRC.
            for shorter in [0, len / 2, len.saturating_sub(1)] {
                if shorter == len {
                    continue;
                }
                let b = with_length(&frame, i, shorter);
                let what = format!("{} section {i} length {len} -> {shorter}", s.name);
                let e = try_decode(&b, &DecodeOptions::default(), &what).expect_err(&what);
                assert!(
                    matches!(format_error(&e), Some(Malformed::TrailingData)),
                    "{what}: {e:?}"
                );
            }
            // Overlapping: the boundary with the next section moves, so
            // the frame holds and each section starts inside the other.
            if i + 1 < n {
                let next = frame.entries[i + 1].1;
                for shift in [-3i64, -1, 1, 3, len as i64, -(next as i64)] {
                    let (a, c) = (len as i64 + shift, next as i64 - shift);
                    if a < 0 || c < 0 || shift == 0 {
                        continue;
                    }
                    let mut f = frame.clone();
                    f.entries[i].1 = a as u64;
                    f.entries[i + 1].1 = c as u64;
                    let b = f.bytes();
                    let what = format!("{} boundary {i}/{} moved by {shift}", s.name, i + 1);
                    refused_or_valid(&b, &what);
                }
            }
        }
        // A section count that lies: one more or one fewer entry.
        for count in [n + 1, n - 1, 0, 0xFFFF] {
            let mut f = frame.clone();
            f.count = count as u64;
            let b = f.bytes();
            let what = format!("{} with {count} sections", s.name);
            // Refused as malformed, or as unsupported when payload bytes
            // read as an entry make an unknown critical tag (or, compact,
            // a reserved tag code).
            let e = try_decode(&b, &DecodeOptions::default(), &what).expect_err(&what);
            assert!(
                format_error(&e).is_some() || matches!(e, Error::Unsupported(_)),
                "{what}: {e:?}"
            );
        }
    }
}

fn header_counts(b: &[u8]) -> (u64, u64) {
    let c = Frame::of(b).counts;
    (c[0], c[1])
}

#[test]
fn huge_declared_counts_in_a_small_file_are_refused_quickly() {
    for s in samples_in_both_framings() {
        // Within the default limits, consistent with each other, and far
        // more than the sections could code; then beyond the limits.
        for (v, t) in [
            (1u32 << 28, 1u32 << 28),
            (3 << 27, 1 << 29),
            (u32::MAX, u32::MAX),
        ] {
            let mut f = Frame::of(&s.bytes);
            f.counts[0] = v.into();
            f.counts[1] = t.into();
            let b = f.bytes();
            let what = format!("{} declaring {v} vertices, {t} triangles", s.name);
            let start = std::time::Instant::now();
            let e = try_decode(&b, &DecodeOptions::default(), &what).expect_err(&what);
            assert!(
                matches!(e, Error::Format(_) | Error::LimitExceeded(_)),
                "{what}: {e:?}"
            );
            assert!(
                start.elapsed() < HANG_GUARD,
                "{what}: took {:?}",
                start.elapsed()
            );
        }
    }
}

#[test]
fn tight_limits_refuse_a_valid_file() {
    for s in samples_in_both_framings() {
        let mesh = swm::decode(&s.bytes, &DecodeOptions::default()).unwrap();
        // A hole-masked mesh has fewer faces than its header declares, and
        // the limits bound the header; REST adds faces the header does not
        // count, and the limits bound those too. The larger of the two is
        // the tightest limit the file passes.
        // The limits also bound the CLERS symbol count S, which in the
        // lossless mode exceeds the output's triangles by one per boundary
        // edge (the decoder closes holes; format-spec/04-lossless.md).
        let (hv, ht) = header_counts(&s.bytes);
        let info = swm::inspect(&s.bytes, &Default::default()).unwrap();
        let symbols = info.stats.clers.iter().sum::<u64>();
        let v = (mesh.vertex_count() as u64).max(hv);
        let t = (mesh.face_count() as u64).max(ht).max(symbols);
        let exact = swm::Limits {
            max_vertices: v,
            max_faces: t,
            ..Default::default()
        };
        let options = |limits| DecodeOptions {
            limits,
            ..Default::default()
        };
        assert!(swm::decode(&s.bytes, &options(exact)).is_ok(), "{}", s.name);
        for (limits, what) in [
            (
                swm::Limits {
                    max_vertices: v - 1,
                    ..exact
                },
                "one vertex less",
            ),
            (
                swm::Limits {
                    max_faces: t - 1,
                    ..exact
                },
                "one face less",
            ),
            (
                swm::Limits {
                    max_alloc_bytes: 100,
                    ..exact
                },
                "100 bytes",
            ),
        ] {
            let what = format!("{} with limits of {what}", s.name);
            let e = try_decode(&s.bytes, &options(limits), &what).expect_err(&what);
            assert!(matches!(e, Error::LimitExceeded(_)), "{what}: {e:?}");
        }
        // Bender quadruples the faces: the limits cover its output too.
        let bent = DecodeOptions {
            limits: exact,
            sharpen: Some(true),
            bend_steps: Some(1),
            max_level: None,
        };
        let what = format!("{} bent within limits of its own size", s.name);
        let e = try_decode(&s.bytes, &bent, &what).expect_err(&what);
        assert!(matches!(e, Error::LimitExceeded(_)), "{what}: {e:?}");
    }
}

/// A deterministic xorshift generator, so that failures repeat.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
}

#[test]
fn random_multi_byte_overwrites_with_the_crc_fixed() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for s in samples() {
        let mut tally = Tally::default();
        for case in 0..2000 {
            let mut b = s.bytes.clone();
            for _ in 0..1 + rng.next() % 4 {
                let at = 4 + (rng.next() as usize) % (b.len() - 8);
                b[at] = rng.next() as u8;
            }
            fix_crc(&mut b);
            tally.add(refused_or_valid(
                &b,
                &format!("{} random case {case}", s.name),
            ));
        }
        tally.both(&format!("{} random overwrites", s.name));
    }
}

#[test]
fn mutations_inside_rest_reach_the_nested_decoder() {
    // REST holds a whole lossless file with its own CRC: fixing both CRCs
    // lets a mutation reach the nested file's header and sections.
    let s = samples().iter().find(|s| s.name == "swing+REST").unwrap();
    let file = swm::container::parse_container(&s.bytes, &Default::default()).unwrap();
    let rest = file.find(swm::container::Tag::REST).unwrap();
    let (start, len) = (rest.offset, rest.bytes.len());
    let mut tally = Tally::default();
    for at in start + 4..start + len - 4 {
        for v in [0x00, 0xFF, s.bytes[at] ^ 0x01] {
            if v == s.bytes[at] {
                continue;
            }
            let mut b = s.bytes.clone();
            b[at] = v;
            fix_crc(&mut b[start..start + len]);
            fix_crc(&mut b);
            tally.add(refused_or_valid(
                &b,
                &format!("REST byte {} = {v:#x}", at - start),
            ));
        }
    }
    tally.both("REST bytes");
}

#[test]
fn too_many_bender_steps_are_refused_by_the_limits() {
    for s in samples() {
        for steps in [20, 40, u32::MAX] {
            let options = DecodeOptions {
                sharpen: Some(true),
                bend_steps: Some(steps),
                ..Default::default()
            };
            let what = format!("{} with {steps} Bender steps", s.name);
            let start = std::time::Instant::now();
            let e = try_decode(&s.bytes, &options, &what).expect_err(&what);
            assert!(matches!(e, Error::LimitExceeded(_)), "{what}: {e:?}");
            assert!(
                start.elapsed() < HANG_GUARD,
                "{what}: took {:?}",
                start.elapsed()
            );
        }
    }
}
