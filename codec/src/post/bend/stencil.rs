//! Bender's stencils: the weights that place a new edge point as an affine
//! combination of old vertices, as pure functions of the layout.
//!
//! Sources: D. Zorin, P. Schröder, W. Sweldens, "Interpolating subdivision
//! for meshes with arbitrary topology", SIGGRAPH 1996 (R1, E1); the
//! four-point scheme of Dyn, Levin and Gregory (R2); M. Attene, *Surface
//! Remeshing and Applications* (2004), §8.4 and Fig. 8.13 (R3–R6, E2), as
//! reconstructed in `../shared/design/ALGORITHMS.md` §8, since the
//! thesis's figure is garbled.
//!
//! Invariants kept: every stencil's weights sum to 1, so a stencil is an
//! affine combination (translations, and planes, are kept exactly); each
//! reproduces the polynomials stated in its comment on the layout drawn
//! there (`tests.rs` checks both). Vertex names: V and W are the edge's
//! ends, p is the new point, `=` marks a sharp (tagged or boundary) edge.

use crate::math;

use glam::DVec3;

/// **R1**, the butterfly (both ends smooth, valence 6). Weights in the
/// order `[V, W, A, B, VA, WA, VB, WB]`, where A and B are the wings and
/// `XY` is the vertex across edge X–Y from the edge V–W:
///
/// ```text
///      VA ----- A ----- WA          V, W     1/2
///        \    /   \    /            A, B     1/8
///         \  /     \  /             far     -1/16
///          V ---p--- W
///         /  \     /  \
///        /    \   /    \
///      VB ----- B ----- WB
/// ```
///
/// This is ZSS96's ten-point stencil with w = 0 (the eight-point butterfly
/// of Dyn, Levin and Gregory); it reproduces cubics on the regular grid.
pub(super) const fn r1() -> [f64; 8] {
    [0.5, 0.5, 0.125, 0.125, -0.0625, -0.0625, -0.0625, -0.0625]
}

/// **R2**, the four-point scheme along a chain of sharp (or boundary)
/// edges. Weights in the order `[V2, V, W, W2]`:
///
/// ```text
///    V2 ===== V ===p=== W ===== W2        -1/16, 9/16, 9/16, -1/16
/// ```
///
/// It ignores everything off the chain, so a sharp edge stays a curve of
/// its own; it reproduces cubics on uniformly spaced points.
pub(super) const fn r2() -> [f64; 4] {
    [-0.0625, 0.5625, 0.5625, -0.0625]
}

/// **R3**, crease–crease rule 1: a non-sharp edge across a strip one
/// triangle wide between two creases, both ends regular crease vertices
/// (K = 3). Weights `[V, W]`; the other four vertices of the figure get 0.
///
/// ```text
///    ======= B ======= W =======
///             \       / \
///              \     p   \
///               \   /     \
///                \ /       \
///    ============ V ======= A ===
/// ```
///
/// The plain midpoint: no stencil on this layout reproduces quadratics,
/// so it keeps linear functions only.
pub(super) const fn r3() -> [f64; 2] {
    [0.5, 0.5]
}

/// **R4**, crease–interior: V a regular crease vertex (K = 3), W an
/// interior vertex of valence 6. A is the wing on V's crease, B the other
/// wing; C1 is across W–A, C2 is V's other crease neighbour (the vertex
/// across V–B), C3 is across W–B. Weights `[V, W, A, B, C1, C2, C3]`:
///
/// ```text
///             C3              V   3/8     W   5/8
///            / \              A   1/16    B   3/16
///           /   \             C1 -1/16    C2 -1/16
///          /     \            C3 -1/8
///         B-------W-------C1
///        / \     / \     /
///       /   \   p   \   /
///      /     \ /     \ /
///     C2======V=======A
/// ```
///
/// Reproduces quadratics on this layout (the only placement of the
/// figure's numbers that does).
pub(super) const fn r4() -> [f64; 7] {
    [0.375, 0.625, 0.0625, 0.1875, -0.0625, -0.0625, -0.125]
}

/// **R5**, crease–crease rule 2: both ends regular crease vertices and
/// the wing A an ear (A–V and A–W both sharp). B is the other wing, VB
/// and WB the vertices across V–B and W–B (V's and W's other crease
/// neighbours); `=` and `#` mark the creases. Weights
/// `[V, W, A, B, VB, WB]`:
///
/// ```text
///               WB            V, W   1/2
///              # \            A      0
///             #   \           B      1/4
///            #     \          VB, WB -1/8
///           W-------B
///          # \     / \
///         #   p   /   \
///        #     \ /     \
///       A=======V=======VB
/// ```
///
/// Reproduces quadratics on this layout (the only weights that do).
pub(super) const fn r5() -> [f64; 6] {
    [0.5, 0.5, 0.0, 0.25, -0.125, -0.125]
}

/// **E1**, weight of V itself when V is an interior vertex of valence
/// `k` ≠ 6 (ZSS96): 3/4. Below valence 3, which no manifold corner table
/// holds (it would take two triangles sharing all three edges), the rule
/// degrades to the midpoint, 1/2, so that the function is total.
pub(super) fn e1_center(k: usize) -> f64 {
    if k >= 3 {
        0.75
    } else {
        0.5
    }
}

/// **E1**, weight of the ring vertex `s_j` of an interior vertex V of
/// valence `k`, where `s_0 = W` and `s_1, s_2, …` follow round V (either
/// way: the weights are symmetric, `s_j = s_{k−j}`):
///
/// ```text
///          s2 ---- s1               k ≥ 5: s_j = (1/4 + cos(2πj/k)
///         /  \    /  \                          + cos(4πj/k)/2) / k
///       s3 --- V --p-- s0 = W       k = 4: 3/8, 0, -1/8, 0
///         \  /    \  /              k = 3: 5/12, -1/12, -1/12
///          s4 ---- s5
/// ```
///
/// On the symmetric fan (ring on the unit circle at angles 2πj/k) it
/// reproduces quadratics for k ≥ 4 and linear functions for k = 3.
pub(super) fn e1(k: usize, j: usize) -> f64 {
    match k {
        0..=2 => {
            if j == 0 {
                0.5
            } else {
                0.0
            }
        }
        3 => [5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0][j % 3],
        4 => [0.375, 0.0, -0.125, 0.0][j % 4],
        _ => {
            let a = core::f64::consts::TAU * j as f64 / k as f64;
            (0.25 + math::cos(a) + 0.5 * math::cos(2.0 * a)) / k as f64
        }
    }
}

/// **E2**, weight of V itself when the edge is the `i`-th inner edge of a
/// sector of `k` triangles at a crease (or boundary, or cut) vertex V:
/// `1 − sin θ · sin iθ / (k (1 − cos θ))`, θ = π/k.
pub(super) fn e2_center(k: usize, i: usize) -> f64 {
    let (kf, t) = sector_angle(k);
    1.0 - math::sin(t) * math::sin(i as f64 * t) / (kf * (1.0 - math::cos(t)))
}

/// **E2**, weight of `s_j` (0 ≤ j ≤ k) for the edge V–s_i of a sector
/// s_0 … s_k of `k` triangles, bounded by the sharp edges V–s_0 and V–s_k
/// (θ = π/k):
///
/// ```text
///            s2 ---- s1             0 < j < k:
///           /  \    /  \              s_j = (sin iθ sin jθ
///          /    \  /    \                    + sin 2iθ sin 2jθ / 2) / k
///   s3 ===== V ===== s0             s_0 = -s_k = cos(iθ)/4
///      (sharp)    (sharp)                 - sin 2θ sin 2iθ / (4k(cos θ - cos 2θ))
/// ```
///
/// For k = 3, i = 1: V 1/2, s_0 1/16, s_1 3/8, s_2 1/8, s_3 -1/16. On the
/// symmetric half-fan (s_j on the unit circle at angles jθ) it reproduces
/// linear functions.
pub(super) fn e2(k: usize, i: usize, j: usize) -> f64 {
    let (kf, t) = sector_angle(k);
    let (i, jf) = (i as f64, j as f64);
    if j == 0 || j == k {
        let s0 = 0.25 * math::cos(i * t)
            - math::sin(2.0 * t) * math::sin(2.0 * i * t)
                / (4.0 * kf * (math::cos(t) - math::cos(2.0 * t)));
        if j == 0 {
            s0
        } else {
            -s0
        }
    } else {
        (math::sin(i * t) * math::sin(jf * t)
            + 0.5 * math::sin(2.0 * i * t) * math::sin(2.0 * jf * t))
            / kf
    }
}

/// `(k, π/k)` as floats; a sector has at least two triangles whenever it
/// holds an inner edge, so `k` below 2 is clamped to keep the weights
/// finite.
fn sector_angle(k: usize) -> (f64, f64) {
    let kf = k.max(2) as f64;
    (kf, core::f64::consts::PI / kf)
}

/// **R6**, the non-manifold crease rule: V is not a 1-manifold sharp
/// vertex, W is, with W2 its other sharp neighbour. The missing V2 is W2
/// reflected across the plane bisecting V–W, so that R2 sees a chain that
/// bends the same way at both ends:
///
/// ```text
///    V2 := W2 + (V−W)·[1 − 2 (V−W)·(W2−W) / ((V−W)·(V−W))]
///
///   (V2) - - - V ===p=== W ====== W2        then R2 on V2, V, W, W2
/// ```
///
/// The plane holding both sharp edges is never needed, so collinear
/// edges are no special case. `None` when V and W coincide (or are not
/// finite), where no bisecting plane exists: the caller takes the
/// midpoint, as for two non-manifold ends.
pub(super) fn r6_mirror(v: DVec3, w: DVec3, w2: DVec3) -> Option<DVec3> {
    let d = v - w;
    let dd = d.dot(d);
    // `!(dd > 0)` also catches NaN.
    if !(dd > 0.0 && dd.is_finite()) {
        return None;
    }
    Some(w2 + d * (1.0 - 2.0 * d.dot(w2 - w) / dd))
}

/// E1 for every edge of one interior vertex at once, in O(k) instead of
/// O(k²): `out[e]` is the E1 point of the edge V–`ring[e]`, with the ring
/// in order round V. For fans too large to sum each stencil directly.
///
/// For k ≥ 5 the weight of `ring[m]` for the edge at `e` is
/// `(1/4 + cos α(m−e) + cos 2α(m−e)/2)/k` with α = 2π/k; expanding the
/// cosines of differences turns the k sums into five shared ones
/// (Σ r, Σ cos αm·r, Σ sin αm·r, and the same at 2α).
pub(super) fn e1_all(center: DVec3, ring: &[DVec3], out: &mut [DVec3]) {
    let k = ring.len();
    if k < 5 {
        for (e, o) in out.iter_mut().enumerate().take(k) {
            *o = center * e1_center(k)
                + (0..k).fold(DVec3::ZERO, |s, j| s + ring[(e + j) % k] * e1(k, j));
        }
        return;
    }
    let a = core::f64::consts::TAU / k as f64;
    let (mut sum, mut c1, mut s1, mut c2, mut s2) = (
        DVec3::ZERO,
        DVec3::ZERO,
        DVec3::ZERO,
        DVec3::ZERO,
        DVec3::ZERO,
    );
    for (m, &r) in ring.iter().enumerate() {
        let x = a * m as f64;
        sum += r;
        c1 += r * math::cos(x);
        s1 += r * math::sin(x);
        c2 += r * math::cos(2.0 * x);
        s2 += r * math::sin(2.0 * x);
    }
    let kf = k as f64;
    for (e, o) in out.iter_mut().enumerate().take(k) {
        let x = a * e as f64;
        let fourier = 0.25 * sum
            + math::cos(x) * c1
            + math::sin(x) * s1
            + 0.5 * (math::cos(2.0 * x) * c2 + math::sin(2.0 * x) * s2);
        *o = 0.75 * center + fourier / kf;
    }
}

/// E2 for every inner edge of one sector at once, in O(k): `out[i]` is
/// the E2 point of the edge V–`sector[i]` for 0 < i < k (`out[0]` and
/// `out[k]`, sharp edges, are left alone), with `sector` = s_0 … s_k.
///
/// The inner weights factor as `sin iθ·sin jθ + sin 2iθ·sin 2jθ/2`, so
/// two shared sums Σ sin jθ·s_j and Σ sin 2jθ·s_j serve every i.
pub(super) fn e2_all(center: DVec3, sector: &[DVec3], out: &mut [DVec3]) {
    let Some(k) = sector.len().checked_sub(1) else {
        return;
    };
    let (kf, t) = sector_angle(k);
    let (mut t1, mut t2) = (DVec3::ZERO, DVec3::ZERO);
    for (j, &s) in sector.iter().enumerate().take(k).skip(1) {
        t1 += s * math::sin(j as f64 * t);
        t2 += s * math::sin(2.0 * j as f64 * t);
    }
    let ends = sector[0] - sector[k];
    for (i, o) in out.iter_mut().enumerate().take(k).skip(1) {
        let x = i as f64 * t;
        *o = center * e2_center(k, i)
            + ends * e2(k, i, 0)
            + (math::sin(x) * t1 + 0.5 * math::sin(2.0 * x) * t2) / kf;
    }
}
