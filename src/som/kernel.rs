//! The map's inner loops, on the blocked weight layout (see [`LANES`]).
//!
//! Each loop works on the `LANES` nodes of a block, one weight dimension at a time, one
//! vector lane per node, with `pulp`'s portable vector operations: each kernel is compiled for
//! the x86-64 baseline, AVX2 and AVX-512, and the widest the CPU has is picked at run time
//! (the feature detection and the `unsafe` it needs live in `pulp`, none here), so a build for
//! the x86-64 baseline stays runnable on any x86-64 machine. (Plain loops over the lanes were
//! tried first: the compiler vectorised the update over the dimensions, with gathers and
//! scatters, and split the scan into a mix of 128-, 256- and 512-bit pieces.) Every node's
//! distance is summed in the plain order (dimension 0, 1, 2, ...) with a subtraction, a
//! multiplication and an addition per dimension, no fused multiply-add, so the results are
//! bit for bit those of a node-by-node loop.

use std::sync::OnceLock;

use pulp::{Simd, WithSimd};

/// Nodes per block of the weight layout: the weights of nodes `b * LANES .. (b + 1) * LANES`
/// are stored dimension by dimension, `LANES` values (one per node) each, so block `b`,
/// dimension `d` is one `[f64; LANES]`: a 64-byte cache line, one AVX-512 register, two
/// AVX2 registers. Lanes past the last node hold 0 and are never reported.
pub(crate) const LANES: usize = 8;

/// One dimension of one block: the value of `LANES` consecutive nodes.
pub(crate) type Lane = [f64; LANES];

fn arch() -> pulp::Arch {
    #[cfg(test)]
    if let Some(a) = tests::FORCED.with(|f| f.get()) {
        return a;
    }
    static ARCH: OnceLock<pulp::Arch> = OnceLock::new();
    *ARCH.get_or_init(pulp::Arch::new)
}

/// Squared distances of the nodes of `G` consecutive blocks (`G * dim` lanes) to `x`, over
/// the dimensions `dims` yields as `(dimension, x value)`, in that order. The blocks' sums
/// are independent chains the CPU runs side by side (one block alone would wait on the
/// latency of each addition).
#[inline(always)]
fn blocks_dist2<S: Simd, const G: usize>(
    simd: S,
    blocks: &[Lane],
    dim: usize,
    dims: impl Iterator<Item = (usize, f64)>,
) -> [Lane; G] {
    // vectors per lane: 1 (AVX-512), 2 (AVX2), 8 (scalar)
    let nv = LANES / S::F64_LANES;
    let zero = simd.splat_f64s(0.0);
    let mut acc = [[zero; LANES]; G];
    let (wv, _) = S::as_simd_f64s(blocks[..G * dim].as_flattened());
    for (d, xd) in dims {
        let xs = simd.splat_f64s(xd);
        for (g, a) in acc.iter_mut().enumerate() {
            let at = (g * dim + d) * nv;
            for (a, &w) in a[..nv].iter_mut().zip(&wv[at..at + nv]) {
                let t = simd.sub_f64s(w, xs);
                *a = simd.add_f64s(*a, simd.mul_f64s(t, t));
            }
        }
    }
    let mut out = [[0.0; LANES]; G];
    for (o, a) in out.iter_mut().zip(&acc) {
        let (ov, _) = S::as_mut_simd_f64s(o);
        ov.copy_from_slice(&a[..nv]);
    }
    out
}

/// Blocks whose distances are computed together.
const GROUP: usize = 4;

/// Call `visit(block index, distances of its nodes)` for every block of `w` in order; the
/// padding lanes of the last block get infinity (never a match).
#[inline(always)]
fn for_each_block<S, I, F>(
    simd: S,
    w: &[Lane],
    dim: usize,
    nodes: usize,
    dims: &F,
    mut visit: impl FnMut(usize, &Lane),
) where
    S: Simd,
    I: Iterator<Item = (usize, f64)>,
    F: Fn() -> I,
{
    let full = nodes / LANES;
    let groups = w.chunks_exact(GROUP * dim);
    let rest = groups.remainder();
    let mut b = 0;
    for group in groups {
        for a in &blocks_dist2::<S, GROUP>(simd, group, dim, dims()) {
            visit(b, &padded(a, b, full, nodes));
            b += 1;
        }
    }
    for block in rest.chunks_exact(dim) {
        let [a] = blocks_dist2::<S, 1>(simd, block, dim, dims());
        visit(b, &padded(&a, b, full, nodes));
        b += 1;
    }
}

/// The distances of block `b`, with infinity in its padding lanes if it is the last one.
#[inline(always)]
fn padded(a: &Lane, b: usize, full: usize, nodes: usize) -> Lane {
    let mut a = *a;
    if b >= full {
        let first_pad = nodes - b * LANES;
        for (l, v) in a.iter_mut().enumerate() {
            if l >= first_pad {
                *v = f64::INFINITY;
            }
        }
    }
    a
}

/// The running minimum of each lane over the blocks visited: its smallest distance and the
/// first block where it was found, in vector registers (a compare and two selects a block;
/// written as plain loops over the lanes, the compiler left scalar compares).
struct LaneMin<S: Simd> {
    simd: S,
    d: [S::f64s; LANES],
    b: [S::u64s; LANES],
}

impl<S: Simd> LaneMin<S> {
    #[inline(always)]
    fn new(simd: S) -> Self {
        LaneMin {
            simd,
            d: [simd.splat_f64s(f64::INFINITY); LANES],
            b: [simd.splat_u64s(0); LANES],
        }
    }

    #[inline(always)]
    fn visit(&mut self, b: usize, acc: &Lane) {
        let simd = self.simd;
        let nv = LANES / S::F64_LANES;
        let (av, _) = S::as_simd_f64s(acc);
        let bs = simd.splat_u64s(b as u64);
        for ((d, bb), &a) in self.d[..nv].iter_mut().zip(&mut self.b[..nv]).zip(av) {
            let closer = simd.less_than_f64s(a, *d);
            *d = simd.select_f64s(closer, a, *d);
            *bb = simd.select_u64s(closer, bs, *bb);
        }
    }

    /// The nearest node over all lanes and its distance; ties go to the lowest index.
    #[inline(always)]
    fn best(&self) -> (usize, f64) {
        let nv = LANES / S::F64_LANES;
        let (mut d, mut b) = ([0.0; LANES], [0u64; LANES]);
        S::as_mut_simd_f64s(&mut d).0.copy_from_slice(&self.d[..nv]);
        S::as_mut_simd_u64s(&mut b).0.copy_from_slice(&self.b[..nv]);
        let mut best = (0, f64::INFINITY);
        for l in 0..LANES {
            let (d, i) = (d[l], b[l] as usize * LANES + l);
            if d < best.1 || (d == best.1 && d < f64::INFINITY && i < best.0) {
                best = (i, d);
            }
        }
        best
    }
}

struct ArgMin<'a, F> {
    w: &'a [Lane],
    dim: usize,
    nodes: usize,
    dims: F,
}

impl<I, F> WithSimd for ArgMin<'_, F>
where
    I: Iterator<Item = (usize, f64)>,
    F: Fn() -> I,
{
    type Output = (usize, f64);
    #[inline(always)]
    fn with_simd<S: Simd>(self, simd: S) -> (usize, f64) {
        let mut best = LaneMin::new(simd);
        let visit = |b: usize, acc: &Lane| best.visit(b, acc);
        for_each_block(simd, self.w, self.dim, self.nodes, &self.dims, visit);
        best.best()
    }
}

/// The node nearest to `x` and its squared distance, over the dimensions `dims()` yields;
/// ties go to the lowest index; `(0, inf)` when no distance is below infinity.
pub(crate) fn argmin<I, F>(w: &[Lane], dim: usize, nodes: usize, dims: F) -> (usize, f64)
where
    I: Iterator<Item = (usize, f64)>,
    F: Fn() -> I,
{
    arch().dispatch(ArgMin {
        w,
        dim,
        nodes,
        dims,
    })
}

struct BestTwo<'a> {
    w: &'a [Lane],
    dim: usize,
    nodes: usize,
    x: &'a [f64],
}

impl WithSimd for BestTwo<'_> {
    type Output = (usize, usize);
    #[inline(always)]
    fn with_simd<S: Simd>(self, simd: S) -> (usize, usize) {
        let inf = f64::INFINITY;
        let (mut d1, mut d2) = ([inf; LANES], [inf; LANES]);
        let (mut b1, mut b2) = ([0usize; LANES], [0usize; LANES]);
        let dims = || self.x.iter().copied().take(self.dim).enumerate();
        let visit = |b: usize, acc: &Lane| {
            for l in 0..LANES {
                let a = acc[l];
                let first = a < d1[l];
                let second = a < d2[l];
                d2[l] = if first {
                    d1[l]
                } else if second {
                    a
                } else {
                    d2[l]
                };
                b2[l] = if first {
                    b1[l]
                } else if second {
                    b
                } else {
                    b2[l]
                };
                d1[l] = if first { a } else { d1[l] };
                b1[l] = if first { b } else { b1[l] };
            }
        };
        for_each_block(simd, self.w, self.dim, self.nodes, &dims, visit);
        // the two smallest (distance, index) pairs among the lanes' two best
        let mut top = [(inf, usize::MAX); 2];
        for l in 0..LANES {
            for (d, b) in [(d1[l], b1[l]), (d2[l], b2[l])] {
                if d < inf {
                    let c = (d, b * LANES + l);
                    if c < top[0] {
                        top[1] = top[0];
                        top[0] = c;
                    } else if c < top[1] {
                        top[1] = c;
                    }
                }
            }
        }
        let pick = |c: (f64, usize)| if c.0 < inf { c.1 } else { 0 };
        (pick(top[0]), pick(top[1]))
    }
}

/// The best and second-best matching nodes of `x` over all dimensions, as the sequential
/// scan with strict comparisons finds them: ties go to the lower index, a slot that found
/// nothing below infinity is node 0.
pub(crate) fn best_two(w: &[Lane], dim: usize, nodes: usize, x: &[f64]) -> (usize, usize) {
    arch().dispatch(BestTwo { w, dim, nodes, x })
}

/// The blocks an update moves and the factor `alpha h` of each of their nodes (0: the node
/// keeps its weights).
pub(crate) type Plan = Vec<(usize, Lane)>;

struct ApplyPlan<'a, F> {
    w: &'a mut [Lane],
    dim: usize,
    plan: &'a [(usize, Lane)],
    dims: F,
}

impl<I, F> WithSimd for ApplyPlan<'_, F>
where
    I: Iterator<Item = (usize, f64)>,
    F: Fn() -> I,
{
    type Output = ();
    #[inline(always)]
    fn with_simd<S: Simd>(self, simd: S) {
        // explicit vectors: left to itself, the compiler vectorises the loop over the
        // dimensions instead, with gathers and scatters
        let nv = LANES / S::F64_LANES;
        let (wv, _) = S::as_mut_simd_f64s(self.w.as_flattened_mut());
        for (b, k) in self.plan {
            let (kv, _) = S::as_simd_f64s(k);
            let block = &mut wv[b * self.dim * nv..(b + 1) * self.dim * nv];
            for (d, xd) in (self.dims)() {
                let xs = simd.splat_f64s(xd);
                for (w, &k) in block[d * nv..(d + 1) * nv].iter_mut().zip(kv) {
                    // w + k (x - w), the scalar rule's operations in its order
                    *w = simd.add_f64s(*w, simd.mul_f64s(k, simd.sub_f64s(xs, *w)));
                }
            }
        }
    }
}

/// `w += k (x - w)` on every block of `plan`, lane by lane, over the dimensions `dims()`
/// yields as `(dimension, x value)`.
pub(crate) fn apply_plan<I, F>(w: &mut [Lane], dim: usize, plan: &[(usize, Lane)], dims: F)
where
    I: Iterator<Item = (usize, f64)>,
    F: Fn() -> I,
{
    arch().dispatch(ApplyPlan { w, dim, plan, dims })
}

/// `v[j] = exp(-(j step)^2 / (2 r^2))` for `j = 0..n`, by a recurrence of products (one
/// exponential whatever `n`): `v[j + 1] = v[j] q^(2j + 1)` with `q = exp(-step^2 / (2 r^2))`.
/// Each product adds at most one rounding, so `v[j]` is within about `2j` ulps of the
/// exponential (`j <= 2 * 64` for a 64x64 map: under 3e-14 relative). Once the values fall
/// below `h_min / 1000` the rest (smaller still) are 0: the cut leaves them out either way.
/// Returns how many entries are not 0.
pub(crate) fn gaussian_table(
    step: f64,
    radius: f64,
    n: usize,
    h_min: f64,
    out: &mut Vec<f64>,
) -> usize {
    out.clear();
    out.resize(n, 0.0);
    let c = 1.0 / (2.0 * radius * radius);
    let q = (-step * step * c).exp();
    let q2 = q * q;
    let (mut v, mut ratio) = (1.0, q);
    for (j, o) in out.iter_mut().enumerate() {
        if v < h_min * 1e-3 {
            return j;
        }
        *o = v;
        v *= ratio;
        ratio *= q2;
    }
    n
}

#[cfg(test)]
pub(crate) mod tests;
