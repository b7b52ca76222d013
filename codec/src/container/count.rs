//! The "count cannot fit" rule: a count a file declares must be one its
//! bytes could possibly encode.
//!
//! [`Limits`](crate::Limits) cap what a file may ask for; this rule caps it
//! further by the file's own size, so that a 100-byte file cannot make a
//! decoder allocate for a million elements even when the limits would
//! allow a million. The caller states the fewest bits any element can
//! cost in its section's coding (for entropy-coded symbols, what the
//! coder's smallest probability allows); the container does the
//! arithmetic, exactly and without overflow.

use super::header::FORMAT_NAME;
use crate::{FormatError, Malformed};

/// Checks that `count` elements of at least `min_bits_num / min_bits_den`
/// bits each fit in `section_len` bytes.
///
/// Fails with [`Malformed::CountTooLarge`] (naming `element`, the count and
/// the most the section could hold) when `count × min_bits > 8 ×
/// section_len`. A zero `min_bits_num` means elements can be free, and
/// every count passes. The error is not located; callers add the section's
/// offset with [`FormatError::at`].
///
/// # Panics
/// If `min_bits_den` is zero: the bound is the caller's constant, never
/// the file's.
pub fn check_count_fits(
    element: &'static str,
    count: u64,
    section_len: usize,
    min_bits_num: u64,
    min_bits_den: u64,
) -> Result<(), FormatError> {
    assert!(
        min_bits_den > 0,
        "check_count_fits: min_bits_den must be positive"
    );
    if min_bits_num == 0 {
        return Ok(());
    }
    // count ≤ floor(8 · len · den / num), exactly, in u128. 8 · len < 2^67;
    // if the product with den overflows, `possible` ≥ 2^128 / 2^64 exceeds
    // every u64 count.
    let Some(scaled) = (section_len as u128 * 8).checked_mul(u128::from(min_bits_den)) else {
        return Ok(());
    };
    let possible = scaled / u128::from(min_bits_num);
    if u128::from(count) > possible {
        return Err(FormatError::new(
            FORMAT_NAME,
            Malformed::CountTooLarge {
                element,
                declared: count,
                possible: possible.min(u64::MAX as u128) as u64,
            },
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds() {
        // 2 bytes at 1/2 bit per element: 32 elements fit, 33 do not.
        assert!(check_count_fits("symbol", 32, 2, 1, 2).is_ok());
        let err = check_count_fits("symbol", 33, 2, 1, 2).unwrap_err();
        assert_eq!(
            err.what,
            Malformed::CountTooLarge {
                element: "symbol",
                declared: 33,
                possible: 32
            }
        );
        // 96 bits per vertex (three f32): 12 bytes hold one vertex.
        assert!(check_count_fits("vertex", 1, 12, 96, 1).is_ok());
        assert!(check_count_fits("vertex", 2, 23, 96, 1).is_err());
        // Empty section: nothing fits unless elements are free.
        assert!(check_count_fits("vertex", 0, 0, 1, 1).is_ok());
        assert!(check_count_fits("vertex", 1, 0, 1, 1).is_err());
        assert!(check_count_fits("vertex", u64::MAX, 0, 0, 1).is_ok());
    }

    #[test]
    fn no_overflow() {
        assert!(check_count_fits("x", u64::MAX, usize::MAX, 1, u64::MAX).is_ok());
        assert!(check_count_fits("x", u64::MAX, 1, u64::MAX, 1).is_err());
    }
}
