//! Lossless coding of quantized positions given their predictions.
//! EXPERIMENTAL VERSION (knobs for measurement).

use super::predict::Prediction;
use super::quantize::max_value;
use crate::entropy::{AdaptiveModel, ContextModel, Decoder, Encoder};
use crate::{Error, FormatError, Malformed};

/// Knobs (for measurement only).
#[derive(Clone, Copy, Debug)]
pub struct Config {
    /// 0 axis, 1 axis×prevL(same axis), 2 axis×neighbourL, 3 = 2 + class.
    pub ctx_mode: u8,
    /// Adaptive mantissa bits below the leading one.
    pub adaptive_top: u8,
    /// 0 none, 1 min L1, 2 min estimated rate.
    pub select: u8,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            ctx_mode: 3,
            adaptive_top: 1,
            select: 0,
        }
    }
}

const CLASSES: usize = 3;
const MAXP: usize = 4;

/// Average of the parallelograms of `list` selected by `mask`.
fn average(decoded: &[[u32; 3]], list: &[[u32; 3]], mask: u32, bits: u8) -> [u32; 3] {
    let max = max_value(bits) as i64;
    let mut sum = [0i64; 3];
    let mut n = 0i64;
    for (i, &[a, b, o]) in list.iter().enumerate() {
        if mask >> i & 1 == 0 {
            continue;
        }
        n += 1;
        let (a, b, o) = (
            decoded[a as usize],
            decoded[b as usize],
            decoded[o as usize],
        );
        for k in 0..3 {
            sum[k] += a[k] as i64 + b[k] as i64 - o[k] as i64;
        }
    }
    let n = n.max(1);
    core::array::from_fn(|k| (2 * sum[k] + n).div_euclid(2 * n).clamp(0, max) as u32)
}

fn zig(q: u32, pred: u32, bits: u8) -> u32 {
    let mask = max_value(bits);
    let half = 1u32 << (bits - 1);
    let r = q.wrapping_sub(pred) & mask;
    let s = if r >= half {
        r as i32 - (mask as i32 + 1)
    } else {
        r as i32
    };
    ((s << 1) ^ (s >> 31)) as u32
}

struct Models {
    cfg: Config,
    bits: u8,
    lengths: ContextModel,
    tops: Vec<AdaptiveModel>,
    prev: [u32; 3],
    cur: [u32; 3],
    class: usize,
    lens: Vec<[u8; 3]>,
    nbr: [u32; 3],
    sel: Vec<AdaptiveModel>,
}

impl Models {
    fn new(bits: u8, cfg: Config) -> Self {
        let b1 = bits as usize + 1;
        Models {
            cfg,
            bits,
            lengths: ContextModel::new(CLASSES * 3 * b1, bits as u32 + 1),
            tops: vec![AdaptiveModel::new(2); b1 * 3 * 4],
            prev: [0; 3],
            cur: [0; 3],
            class: 0,
            lens: Vec::new(),
            nbr: [0; 3],
            sel: (0..=MAXP)
                .map(|m| AdaptiveModel::new(((1u32 << m) - 1).max(2)))
                .collect(),
        }
    }

    fn start_vertex(&mut self, p: &Prediction, paras: &[[u32; 3]]) {
        let mut sum = [0u32; 3];
        let mut n = 0u32;
        let mut add = |v: u32, sum: &mut [u32; 3]| {
            let l = self.lens[v as usize];
            for k in 0..3 {
                sum[k] += l[k] as u32;
            }
            n += 1;
        };
        match *p {
            Prediction::None => {}
            Prediction::Delta { from } => add(from, &mut sum),
            Prediction::Parallelogram { a, b, opposite } => {
                add(a, &mut sum);
                add(b, &mut sum);
                if self.cfg.ctx_mode >= 6 {
                    add(opposite, &mut sum);
                }
            }
            Prediction::Multi { first, count } => {
                for t in &paras[first as usize..(first + count) as usize] {
                    add(t[0], &mut sum);
                    add(t[1], &mut sum);
                    if self.cfg.ctx_mode >= 6 {
                        add(t[2], &mut sum);
                    }
                }
            }
        }
        self.nbr = if n == 0 {
            [self.bits as u32 / 2; 3]
        } else {
            sum.map(|s| (s + n / 2) / n)
        };
        self.class = match p {
            Prediction::None | Prediction::Delta { .. } => 0,
            Prediction::Parallelogram { .. } => 1,
            Prediction::Multi { count, .. } => {
                if *count >= 2 {
                    2
                } else {
                    1
                }
            }
        };
    }

    fn context(&self, axis: usize) -> usize {
        let b1 = self.bits as usize + 1;
        let n = match self.cfg.ctx_mode {
            0 => 0,
            1 => self.prev[axis] as usize,
            4 => self.nbr[axis] as usize,
            5 | 6 => match axis {
                0 => self.nbr[0] as usize,
                1 => ((self.nbr[1] + self.cur[0] + 1) / 2) as usize,
                _ => ((self.nbr[2] + self.cur[0] + self.cur[1] + 1) / 3) as usize,
            },
            7 => match axis {
                0 => self.nbr[0] as usize,
                1 => ((2 * self.nbr[1] + self.cur[0] + 1) / 3) as usize,
                _ => ((2 * self.nbr[2] + self.cur[0] + self.cur[1] + 2) / 4) as usize,
            },
            _ => match axis {
                0 => ((self.prev[0] + self.prev[1] + self.prev[2] + 1) / 3) as usize,
                1 => self.cur[0] as usize,
                _ => ((self.cur[0] + self.cur[1] + 1) / 2) as usize,
            },
        };
        let class = if self.cfg.ctx_mode == 3 {
            self.class
        } else {
            0
        };
        (class * 3 + axis) * b1 + n
    }

    fn record(&mut self, axis: usize, len: u32) {
        self.cur[axis] = len;
        if axis == 2 {
            self.prev = self.cur;
            self.lens.push(self.cur.map(|l| l as u8));
        }
    }
}

fn length(z: u32) -> u32 {
    u32::BITS - z.leading_zeros()
}

/// Encodes.
pub fn encode_positions_cfg(
    quantized: &[[u32; 3]],
    predictions: &[Prediction],
    parallelograms: &[[u32; 3]],
    bits: u8,
    enc: &mut Encoder,
    cfg: Config,
) {
    assert_eq!(quantized.len(), predictions.len());
    let mask = max_value(bits);
    let half = 1u32 << (bits - 1);
    let mut m = Models::new(bits, cfg);
    for (k, (q, p)) in quantized.iter().zip(predictions).enumerate() {
        p.check(k, parallelograms).expect("valid prediction");
        m.start_vertex(p, parallelograms);
        let mut pred = p.predict(&quantized[..k], parallelograms, bits);
        if let (Prediction::Multi { first, count }, true) = (*p, cfg.select > 0) {
            let cnt = (count as usize).min(MAXP);
            if cnt >= 2 {
                let list = &parallelograms[first as usize..first as usize + cnt];
                let mut best = (f64::INFINITY, 0u32);
                for mask in 1u32..(1 << cnt) {
                    let pr = average(&quantized[..k], list, mask, bits);
                    let cost = if cfg.select == 1 {
                        (0..3)
                            .map(|a| (q[a] as i64 - pr[a] as i64).abs() as f64)
                            .sum::<f64>()
                    } else {
                        let t = m.sel[cnt].table();
                        let mut c = (65536.0 / t.frequency(mask - 1) as f64).log2();
                        let saved = m.cur;
                        for a in 0..3 {
                            let z = zig(q[a], pr[a], bits);
                            let len = length(z);
                            let ctx = m.context(a);
                            let f = m.lengths.get(ctx).table().frequency(len) as f64;
                            c += (65536.0 / f).log2() + len.saturating_sub(1) as f64;
                            m.cur[a] = len;
                        }
                        m.cur = saved;
                        c
                    };
                    if cost < best.0 {
                        best = (cost, mask);
                    }
                }
                enc.encode(&mut m.sel[cnt], best.1 - 1);
                pred = average(&quantized[..k], list, best.1, bits);
            }
        }
        for axis in 0..3 {
            let r = q[axis].wrapping_sub(pred[axis]) & mask;
            // signed in [−half, half)
            let s = if r >= half {
                r as i32 - (mask as i32 + 1)
            } else {
                r as i32
            };
            let z = ((s << 1) ^ (s >> 31)) as u32;
            let len = length(z);
            let ctx = m.context(axis);
            enc.encode(m.lengths.get(ctx), len);
            if len >= 2 {
                let mant_bits = len - 1;
                let top = (cfg.adaptive_top as u32).min(mant_bits);
                let mut rem = mant_bits;
                for t in 0..top {
                    rem -= 1;
                    let bit = (z >> rem) & 1;
                    let mi = (len as usize * 3 + axis) * 4 + t as usize;
                    let _ = mi;
                    enc.encode(&mut m.tops[(len as usize * 3 + axis) * 4 + t as usize], bit);
                }
                enc.encode_bits(z & ((1 << rem) - 1), rem);
            }
            m.record(axis, len);
        }
    }
}

/// Decodes.
pub fn decode_positions_cfg(
    predictions: &[Prediction],
    parallelograms: &[[u32; 3]],
    bits: u8,
    dec: &mut Decoder,
    out: &mut Vec<[u32; 3]>,
    cfg: Config,
) -> Result<(), Error> {
    if !(1..=24).contains(&bits) {
        return Err(Error::Format(FormatError::new(
            "SWM",
            Malformed::BadHeader("quantization bits out of range"),
        )));
    }
    out.clear();
    out.reserve(predictions.len());
    let mask = max_value(bits);
    let mut m = Models::new(bits, cfg);
    for (k, p) in predictions.iter().enumerate() {
        p.check(k, parallelograms)?;
        m.start_vertex(p, parallelograms);
        let mut pred = p.predict(out, parallelograms, bits);
        if let (Prediction::Multi { first, count }, true) = (*p, cfg.select > 0) {
            let cnt = (count as usize).min(MAXP);
            if cnt >= 2 {
                let list = &parallelograms[first as usize..first as usize + cnt];
                let mask = dec.decode(&mut m.sel[cnt])? + 1;
                pred = average(out, list, mask, bits);
            }
        }
        let mut q = [0u32; 3];
        for axis in 0..3 {
            let ctx = m.context(axis);
            let len = dec.decode(m.lengths.get(ctx))?;
            let z = if len == 0 {
                0
            } else {
                let mant_bits = len - 1;
                let top = (cfg.adaptive_top as u32).min(mant_bits);
                let mut v = 1u32;
                for t in 0..top {
                    let bit =
                        dec.decode(&mut m.tops[(len as usize * 3 + axis) * 4 + t as usize])?;
                    v = (v << 1) | bit;
                }
                let rem = mant_bits - top;
                (v << rem) | dec.decode_bits(rem)?
            };
            let s = ((z >> 1) as i32) ^ -((z & 1) as i32);
            q[axis] = pred[axis].wrapping_add(s as u32) & mask;
            m.record(axis, len);
        }
        out.push(q);
    }
    Ok(())
}
