//! xorshift64: a small deterministic generator shared by the codec's unit
//! tests, so they need no crate.

pub(crate) struct Rng(pub u64);

impl Rng {
    /// The next state.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A value in `0..n`.
    pub fn below(&mut self, n: u64) -> u32 {
        (self.next_u64() % n) as u32
    }

    /// A value in `[0, 1)`, from the top 53 bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}
