//! The map's inner loops, on the blocked weight layout (see [`LANES`]).
//!
//! Each loop is written over the `LANES` nodes of a block, one weight dimension at a time, so
//! the compiler turns it into vector instructions, one lane per node. The summation order of
//! every node's distance is the plain one (dimension 0, 1, 2, ...), without fused
//! multiply-adds, so the results are bit for bit those of a node-by-node loop. The loops run
//! under [`vectorized`], which compiles them a second and third time with AVX2 and AVX-512
//! enabled and picks, at run time, the widest the CPU has (through `pulp`: the run-time
//! feature detection and the `unsafe` it needs live in that crate, none here); a build for the
//! x86-64 baseline stays runnable on any x86-64 machine.

use std::sync::OnceLock;

/// Nodes per block of the weight layout: the weights of nodes `b * LANES .. (b + 1) * LANES`
/// are stored dimension by dimension, `LANES` values (one per node) each, so block `b`,
/// dimension `d` is one `[f64; LANES]`: a 64-byte cache line, one AVX-512 register, two
/// AVX2 registers. Lanes past the last node hold 0 and are never reported.
pub(crate) const LANES: usize = 8;

/// One dimension of one block: the value of `LANES` consecutive nodes.
pub(crate) type Lane = [f64; LANES];

fn arch() -> pulp::Arch {
    static ARCH: OnceLock<pulp::Arch> = OnceLock::new();
    *ARCH.get_or_init(pulp::Arch::new)
}

struct Run<F>(F);

impl<R, F: FnOnce() -> R> pulp::WithSimd for Run<F> {
    type Output = R;
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> R {
        (self.0)()
    }
}

/// Run `f` compiled for the widest vector instruction set this CPU has.
#[inline(always)]
pub(crate) fn vectorized<R>(f: impl FnOnce() -> R) -> R {
    arch().dispatch(Run(f))
}

/// Squared distances of the nodes of `G` consecutive blocks (`G * dim` lanes) to `x`, over
/// the dimensions `dims` yields as `(dimension, x value)`, in that order. The blocks' sums
/// are independent chains the CPU runs side by side (one block alone would wait on the
/// latency of each addition).
#[inline(always)]
fn blocks_dist2<const G: usize>(
    blocks: &[Lane],
    dim: usize,
    dims: impl Iterator<Item = (usize, f64)>,
) -> [Lane; G] {
    let mut acc = [[0.0; LANES]; G];
    for (d, xd) in dims {
        for (g, a) in acc.iter_mut().enumerate() {
            let w = &blocks[g * dim + d];
            for l in 0..LANES {
                let t = w[l] - xd;
                a[l] += t * t;
            }
        }
    }
    acc
}

/// Blocks whose distances are computed together.
const GROUP: usize = 4;

/// Call `visit(block index, distances of its nodes)` for every block of `w` in order; the
/// padding lanes of the last block get infinity (never a match).
#[inline(always)]
fn for_each_block<I, F>(
    w: &[Lane],
    dim: usize,
    nodes: usize,
    dims: F,
    mut visit: impl FnMut(usize, &Lane),
) where
    I: Iterator<Item = (usize, f64)>,
    F: Fn() -> I,
{
    let full = nodes / LANES;
    let mut emit = |b: usize, a: &Lane| {
        if b >= full {
            let first_pad = nodes - b * LANES;
            let mut a = *a;
            for (l, v) in a.iter_mut().enumerate() {
                if l >= first_pad {
                    *v = f64::INFINITY;
                }
            }
            visit(b, &a);
        } else {
            visit(b, a);
        }
    };
    let groups = w.chunks_exact(GROUP * dim);
    let rest = groups.remainder();
    let mut b = 0;
    for group in groups {
        for a in &blocks_dist2::<GROUP>(group, dim, dims()) {
            emit(b, a);
            b += 1;
        }
    }
    for block in rest.chunks_exact(dim) {
        emit(b, &blocks_dist2::<1>(block, dim, dims())[0]);
        b += 1;
    }
}

/// The node nearest to `x` and its squared distance, over the dimensions `dims()` yields;
/// ties go to the lowest index; `(0, inf)` when no distance is below infinity.
#[inline(always)]
pub(crate) fn argmin<I, F>(w: &[Lane], dim: usize, nodes: usize, dims: F) -> (usize, f64)
where
    I: Iterator<Item = (usize, f64)>,
    F: Fn() -> I,
{
    vectorized(
        #[inline(always)]
        || {
            let mut best_d = [f64::INFINITY; LANES];
            let mut best_b = [0usize; LANES];
            for_each_block(w, dim, nodes, dims, |b, acc| {
                for l in 0..LANES {
                    let closer = acc[l] < best_d[l];
                    best_d[l] = if closer { acc[l] } else { best_d[l] };
                    best_b[l] = if closer { b } else { best_b[l] };
                }
            });
            let mut best = (0, f64::INFINITY);
            for l in 0..LANES {
                let i = best_b[l] * LANES + l;
                if best_d[l] < best.1
                    || (best_d[l] == best.1 && best_d[l] < f64::INFINITY && i < best.0)
                {
                    best = (i, best_d[l]);
                }
            }
            best
        },
    )
}

/// The best and second-best matching nodes of `x` over all dimensions, as the sequential
/// scan with strict comparisons finds them: ties go to the lower index, a slot that found
/// nothing below infinity is node 0.
#[inline(always)]
pub(crate) fn best_two(w: &[Lane], dim: usize, nodes: usize, x: &[f64]) -> (usize, usize) {
    vectorized(
        #[inline(always)]
        || {
            let inf = f64::INFINITY;
            let (mut d1, mut d2) = ([inf; LANES], [inf; LANES]);
            let (mut b1, mut b2) = ([0usize; LANES], [0usize; LANES]);
            let dims = || x.iter().copied().take(dim).enumerate();
            for_each_block(w, dim, nodes, dims, |b, acc| {
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
            });
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
        },
    )
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

impl<I, F> pulp::WithSimd for ApplyPlan<'_, F>
where
    I: Iterator<Item = (usize, f64)>,
    F: Fn() -> I,
{
    type Output = ();
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, simd: S) {
        // explicit vectors: left to itself, the compiler vectorises the loop over the
        // dimensions instead, with gathers and scatters
        for (b, k) in self.plan {
            let block = &mut self.w[b * self.dim..(b + 1) * self.dim];
            let (kv, _) = S::as_simd_f64s(k);
            for (d, xd) in (self.dims)() {
                let xs = simd.splat_f64s(xd);
                let (wv, _) = S::as_mut_simd_f64s(&mut block[d]);
                for (w, &k) in wv.iter_mut().zip(kv) {
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
/// exponential (`j <= 2 * 64` for a 64x64 map: under 3e-14 relative).
pub(crate) fn gaussian_table(step: f64, radius: f64, n: usize, out: &mut Vec<f64>) {
    out.clear();
    let c = 1.0 / (2.0 * radius * radius);
    let q = (-step * step * c).exp();
    let q2 = q * q;
    let (mut v, mut ratio) = (1.0, q);
    for _ in 0..n {
        out.push(v);
        v *= ratio;
        ratio *= q2;
    }
}
