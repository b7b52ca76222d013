//! A deliberately simple reference decoder for tests: Wrap&Zip
//! (Rossignac and Szymczak, CGTA 1999) in the corner-table form of SMI
//! 2001, for one closed genus-0 component. It numbers vertices as they
//! appear, like the encoder, so its output must equal the fast decoder's.
//!
//! Sentinels in O: UNSET (not yet known), FREE_C (left edge of a C,
//! waiting), FREE (free edge waiting to be zipped).

use super::shared::Symbol;

const UNSET: i64 = -3;
const FREE_C: i64 = -1;
const FREE: i64 = -2;

fn n(c: i64) -> i64 {
    3 * (c / 3) + (c + 1) % 3
}
fn p(c: i64) -> i64 {
    n(n(c))
}

/// Returns the triangles (V) of a single genus-0 component.
pub fn wrap_and_zip(symbols: &[Symbol]) -> Vec<[u32; 3]> {
    let nt = symbols.len() + 1;
    let mut v = vec![-1i64; 3 * nt];
    let mut o = vec![UNSET; 3 * nt];
    v[0] = 0;
    v[1] = 1;
    v[2] = 2;
    o[0] = FREE_C;
    o[2] = FREE_C;
    let mut nv = 2;
    let mut t = 0i64;
    let mut stack = vec![1i64];
    let mut s = symbols.iter();
    'outer: while let Some(mut c) = stack.pop() {
        for &sym in s.by_ref() {
            t += 1;
            let tc = 3 * t;
            o[c as usize] = tc;
            o[tc as usize] = c;
            v[(tc + 1) as usize] = v[p(c) as usize];
            v[(tc + 2) as usize] = v[n(c) as usize];
            c = tc + 1;
            match sym {
                Symbol::C => {
                    o[n(c) as usize] = FREE_C;
                    nv += 1;
                    v[tc as usize] = nv;
                }
                Symbol::L => {
                    o[n(c) as usize] = FREE;
                    zip(&mut o, &mut v, n(c));
                }
                Symbol::R => {
                    o[c as usize] = FREE;
                    c = n(c);
                }
                Symbol::S => stack.push(n(c)),
                Symbol::E => {
                    o[c as usize] = FREE;
                    o[n(c) as usize] = FREE;
                    zip(&mut o, &mut v, n(c));
                    continue 'outer;
                }
            }
        }
    }
    v.chunks(3)
        .map(|t| [t[0] as u32, t[1] as u32, t[2] as u32])
        .collect()
}

fn zip(o: &mut [i64], v: &mut [i64], mut c: i64) {
    loop {
        // Turn round the pivot V[p(c)] to the next free edge.
        let mut b = n(c);
        while o[b as usize] >= 0 {
            b = n(o[b as usize]);
        }
        if o[b as usize] != FREE_C {
            return;
        }
        o[c as usize] = b;
        o[b as usize] = c;
        // c's edge runs X -> pivot and b's runs pivot -> V[p(b)], so the
        // unknown X is V[p(b)]: write it on every corner of X's fan.
        let target = v[p(b) as usize];
        v[n(c) as usize] = target;
        let first = p(c);
        let mut a = first;
        while o[a as usize] >= 0 {
            let d = o[a as usize];
            v[n(d) as usize] = target;
            a = p(d);
            if a == first {
                break; // the fan closed up
            }
        }
        c = p(c);
        while o[c as usize] >= 0 && c != b {
            c = p(o[c as usize]);
        }
        if o[c as usize] != FREE {
            return;
        }
    }
}
