//! Value parsers for the command-line options, so that clap refuses a bad
//! value as a usage error (exit 2) with the accepted values in plain
//! words, before any work is done.

/// A positive finite number (`--bpv`, `--edge-length`).
pub fn positive_finite(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err("must be a positive finite number".into()),
    }
}

/// A whole number of bytes, at least 1 (`--size`, `--max-size`).
pub fn positive_bytes(s: &str) -> Result<u64, String> {
    match s.trim().parse::<u64>() {
        Ok(n) if n > 0 => Ok(n),
        _ => Err("must be a whole number of bytes, at least 1".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refusals_and_acceptances() {
        for bad in ["0", "-1", "nan", "NaN", "inf", "-inf", "x", ""] {
            assert!(positive_finite(bad).is_err(), "{bad}");
        }
        assert_eq!(positive_finite("2.5"), Ok(2.5));
        assert_eq!(positive_finite("1e-30"), Ok(1e-30));
        for bad in ["0", "-3", "1.5", "x", "18446744073709551616"] {
            assert!(positive_bytes(bad).is_err(), "{bad}");
        }
        assert_eq!(positive_bytes("1"), Ok(1));
    }
}
