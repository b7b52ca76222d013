//! Round trips, compression efficiency, hostile input and determinism.

use super::*;
use crate::{Error, FormatError, Malformed};

/// SplitMix64: a tiny deterministic generator, so tests need no crate.
pub(crate) struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    pub fn below(&mut self, n: u32) -> u32 {
        (self.next() % n as u64) as u32
    }

    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// What one step of a test stream codes.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Item {
    /// A symbol of the context model for `context`.
    Symbol { context: usize, symbol: u32 },
    /// Raw bits.
    Bits { value: u32, bits: u32 },
}

fn encode_items(items: &[Item], contexts: usize, symbols: u32) -> Vec<u8> {
    let mut enc = Encoder::new();
    let mut model = ContextModel::new(contexts, symbols);
    for &item in items {
        match item {
            Item::Symbol { context, symbol } => enc.encode(model.get(context), symbol),
            Item::Bits { value, bits } => enc.encode_bits(value, bits),
        }
    }
    enc.finish()
}

fn decode_items(
    bytes: &[u8],
    shape: &[Item],
    contexts: usize,
    symbols: u32,
) -> Result<Vec<Item>, Error> {
    let mut dec = Decoder::new(bytes)?;
    let mut model = ContextModel::new(contexts, symbols);
    let mut out = Vec::with_capacity(shape.len());
    for &item in shape {
        out.push(match item {
            Item::Symbol { context, .. } => Item::Symbol {
                context,
                symbol: dec.decode(model.get(context))?,
            },
            Item::Bits { bits, .. } => Item::Bits {
                value: dec.decode_bits(bits)?,
                bits,
            },
        });
    }
    dec.finish()?;
    Ok(out)
}

/// A stream mixing symbols of skewed, context-dependent distributions with
/// raw bits of every width.
fn random_items(rng: &mut Rng, len: usize, contexts: usize, symbols: u32) -> Vec<Item> {
    let mut items = Vec::with_capacity(len);
    let mut prev = 0u32;
    for _ in 0..len {
        if rng.below(10) == 0 {
            let bits = rng.below(MAX_RAW_BITS + 1);
            let value = (rng.next() as u32) & ((1u64 << bits) - 1) as u32;
            items.push(Item::Bits { value, bits });
        } else {
            let context = prev as usize % contexts;
            // Skewed: small symbols more likely, shifted by the context.
            let r = rng.unit();
            let symbol = ((r * r * r * symbols as f64) as u32 + context as u32) % symbols;
            items.push(Item::Symbol { context, symbol });
            prev = symbol;
        }
    }
    items
}

#[test]
fn random_streams_round_trip() {
    let mut rng = Rng(1);
    for (contexts, symbols) in [(1, 2), (2, 3), (5, 5), (3, 16), (4, 256), (1, 4096)] {
        for len in [0, 1, 2, 7, 100, 5_000, 60_000] {
            let items = random_items(&mut rng, len, contexts, symbols);
            let bytes = encode_items(&items, contexts, symbols);
            assert_eq!(bytes.len() % 4, 0);
            let back = decode_items(&bytes, &items, contexts, symbols)
                .unwrap_or_else(|e| panic!("{contexts}x{symbols}, {len} items: {e}"));
            assert_eq!(back, items, "{contexts}x{symbols}, {len} items");
        }
    }
}

#[test]
fn extreme_symbols_round_trip() {
    // Long runs of one symbol, then every symbol once: exercises halving,
    // the largest and the smallest quantized frequencies.
    for symbols in [2, 5, 4096] {
        let mut items: Vec<Item> = (0..300_000)
            .map(|_| Item::Symbol {
                context: 0,
                symbol: symbols - 1,
            })
            .collect();
        items.extend((0..symbols).map(|symbol| Item::Symbol { context: 0, symbol }));
        let bytes = encode_items(&items, 1, symbols);
        assert_eq!(decode_items(&bytes, &items, 1, symbols).unwrap(), items);
    }
}

/// Empirical order-0 entropy of a sequence, in bits.
fn entropy_bits(symbols: &[u32], n: u32) -> f64 {
    let mut counts = vec![0u64; n as usize];
    for &s in symbols {
        counts[s as usize] += 1;
    }
    let len = symbols.len() as f64;
    counts
        .iter()
        .filter(|&&c| c > 0)
        .map(|&c| -(c as f64) * (c as f64 / len).log2())
        .sum()
}

#[test]
fn skewed_stream_codes_near_its_entropy() {
    let mut rng = Rng(7);
    for n in [2, 4, 16] {
        let stream: Vec<u32> = (0..100_000)
            .map(|_| {
                if rng.unit() < 0.95 {
                    0
                } else {
                    1 + rng.below(n - 1)
                }
            })
            .collect();
        let mut enc = Encoder::new();
        let mut model = AdaptiveModel::new(n);
        for &s in &stream {
            enc.encode(&mut model, s);
        }
        let bytes = enc.finish();
        let coded = bytes.len() as f64 * 8.0;
        let h = entropy_bits(&stream, n);
        assert!(
            coded <= h * 1.03,
            "{n} symbols: {coded} bits coded, entropy {h:.0} bits ({:.2}%)",
            100.0 * (coded / h - 1.0)
        );
        let mut dec = Decoder::new(&bytes).unwrap();
        let mut model = AdaptiveModel::new(n);
        for &s in &stream {
            assert_eq!(dec.decode(&mut model).unwrap(), s);
        }
        dec.finish().unwrap();
    }
}

#[test]
fn raw_bits_round_trip() {
    let mut rng = Rng(3);
    let mut items = Vec::new();
    for bits in 0..=MAX_RAW_BITS {
        let max = ((1u64 << bits) - 1) as u32;
        for value in [0, max, max / 2, (rng.next() as u32) & max] {
            items.push(Item::Bits { value, bits });
        }
    }
    let bytes = encode_items(&items, 1, 2);
    // Raw bits cost what they are, plus at most two words of flush.
    let raw: u32 = items
        .iter()
        .map(|i| match i {
            Item::Bits { bits, .. } => *bits,
            _ => 0,
        })
        .sum();
    assert!(bytes.len() * 8 <= raw as usize + 64 + 8);
    assert_eq!(decode_items(&bytes, &items, 1, 2).unwrap(), items);
}

#[test]
fn encoding_is_deterministic() {
    let mut rng = Rng(11);
    let items = random_items(&mut rng, 20_000, 5, 5);
    let a = encode_items(&items, 5, 5);
    let b = encode_items(&items, 5, 5);
    assert_eq!(a, b);
    // Models that saw the same symbols are identical, whichever side.
    let mut enc = Encoder::new();
    let mut m_enc = AdaptiveModel::new(7);
    for s in 0..5_000u32 {
        enc.encode(&mut m_enc, s * s % 7);
    }
    let bytes = enc.finish();
    let mut dec = Decoder::new(&bytes).unwrap();
    let mut m_dec = AdaptiveModel::new(7);
    for _ in 0..5_000 {
        dec.decode(&mut m_dec).unwrap();
    }
    assert_eq!(m_enc, m_dec);
}

#[test]
fn empty_stream() {
    let bytes = Encoder::new().finish();
    assert!(bytes.is_empty());
    Decoder::new(&bytes).unwrap().finish().unwrap();
    // Decoding from nothing gives symbols (zeros shifted in), not a panic,
    // and `finish` then reports the truncation.
    let mut dec = Decoder::new(&[]).unwrap();
    let mut model = AdaptiveModel::new(5);
    for _ in 0..100 {
        dec.decode(&mut model).unwrap();
    }
    assert!(matches!(
        dec.finish(),
        Err(Error::Format(FormatError {
            what: Malformed::Truncated,
            ..
        }))
    ));
}

fn what(r: Result<(), Error>) -> Option<Malformed> {
    match r {
        Err(Error::Format(FormatError { what, format, .. })) => {
            assert_eq!(format, "SWM");
            Some(what)
        }
        Err(e) => panic!("unexpected error {e}"),
        Ok(()) => None,
    }
}

#[test]
fn framing_errors() {
    let mut rng = Rng(5);
    let items = random_items(&mut rng, 2_000, 5, 5);
    let bytes = encode_items(&items, 5, 5);

    for cut in [1, 2, 3, 5] {
        let r = Decoder::new(&bytes[..bytes.len() - cut]).map(|_| ());
        assert!(
            matches!(what(r), Some(Malformed::BadSyntax(_))),
            "cut {cut}"
        );
    }

    // One word more or less is always noticed, at any stream length.
    for len in (1..=80).chain([100, 2_000]) {
        let items = &items[..len];
        let bytes = encode_items(items, 5, 5);
        let mut longer = bytes.clone();
        longer.extend_from_slice(&[0; 4]);
        let r = decode_items(&longer, items, 5, 5).map(|_| ());
        assert_eq!(what(r), Some(Malformed::TrailingData), "{len} items");
        if bytes.len() >= 4 {
            let r = decode_items(&bytes[..bytes.len() - 4], items, 5, 5).map(|_| ());
            assert!(r.is_err(), "{len} items");
        }
    }

    // Bytes for a stream that encoded nothing.
    let r = Decoder::new(&[1, 2, 3, 4]).unwrap().finish();
    assert_eq!(what(r), Some(Malformed::TrailingData));
}

#[test]
fn garbage_never_panics() {
    let mut rng = Rng(13);
    let mut errors = 0;
    for round in 0..3_000 {
        let len = 4 * rng.below(40) as usize;
        let bytes: Vec<u8> = match round % 4 {
            0 => vec![0xFF; len],
            1 => vec![0x00; len],
            _ => (0..len).map(|_| rng.next() as u8).collect(),
        };
        let symbols = [2, 5, 256, 4096][rng.below(4) as usize];
        let contexts = 1 + rng.below(4) as usize;
        let len = 1 + rng.below(300) as usize;
        let shape = random_items(&mut rng, len, contexts, symbols);
        match decode_items(&bytes, &shape, contexts, symbols) {
            Ok(items) => {
                for item in items {
                    match item {
                        Item::Symbol { symbol, .. } => assert!(symbol < symbols),
                        Item::Bits { value, bits } => assert!(value >> bits == 0),
                    }
                }
            }
            Err(Error::Format(e)) => {
                assert_eq!(e.format, "SWM");
                errors += 1;
            }
            Err(e) => panic!("unexpected error {e}"),
        }
    }
    // All-ones input points past every model: constriction's one error.
    let mut dec = Decoder::new(&[0xFF; 8]).unwrap();
    let mut model = AdaptiveModel::new(5);
    assert!(dec.decode(&mut model).is_err());
    assert!(errors > 0);
}
