//! The map's loops node by node, without the blocked layout: the reference the kernels are
//! tested and benchmarked against.

use super::algorithm::{known, positions};
use super::{Neighbourhood, SelfOrganizingMap};

/// A node-major map with plain loops: the reference the blocked kernels are tested against,
/// and the comparison of the benchmarks.
/// Not for use in the algorithm.
#[derive(Debug, Clone)]
pub struct NodeMajorMap {
    dim: usize,
    weights: Vec<f64>,
    pos: Vec<(f64, f64)>,
}

impl NodeMajorMap {
    /// A copy of `m`.
    pub fn of(m: &SelfOrganizingMap) -> Self {
        NodeMajorMap {
            dim: m.dim(),
            weights: m.all_weights(),
            pos: positions(m.rows(), m.cols(), m.topology()),
        }
    }
    /// Number of nodes.
    pub fn n(&self) -> usize {
        self.weights.len() / self.dim
    }
    /// Best-matching unit over the `(dimension, value)` pairs `pairs` yields (ties to the
    /// lowest index).
    fn argmin<I: Iterator<Item = (usize, f64)>>(&self, pairs: impl Fn() -> I) -> (usize, f64) {
        let mut best = (0, f64::INFINITY);
        for (i, w) in self.weights.chunks_exact(self.dim).enumerate() {
            let mut d = 0.0;
            for (k, v) in pairs() {
                let t = w[k] - v;
                d += t * t;
            }
            if d < best.1 {
                best = (i, d);
            }
        }
        best
    }
    /// Best-matching unit (ties to the lowest index).
    pub fn bmu(&self, x: &[f64]) -> (usize, f64) {
        self.argmin(|| x.iter().copied().take(self.dim).enumerate())
    }
    /// Best-matching unit over the dimensions where `mask` is true.
    pub fn bmu_masked(&self, x: &[f64], mask: &[bool]) -> (usize, f64) {
        self.argmin(|| known(x, mask, self.dim))
    }
    /// Best-matching unit over the dimensions `range`.
    pub fn bmu_range(&self, x: &[f64], range: std::ops::Range<usize>) -> (usize, f64) {
        self.argmin(|| range.clone().zip(x.iter().copied()))
    }
    /// Best and second-best matching units.
    pub fn best_two(&self, x: &[f64]) -> (usize, usize) {
        let mut b1 = (0, f64::INFINITY);
        let mut b2 = (0, f64::INFINITY);
        for (i, w) in self.weights.chunks_exact(self.dim).enumerate() {
            let d: f64 = w.iter().zip(x).map(|(a, b)| (a - b) * (a - b)).sum();
            if d < b1.1 {
                b2 = b1;
                b1 = (i, d);
            } else if d < b2.1 {
                b2 = (i, d);
            }
        }
        (b1.0, b2.0)
    }
    /// The update, one exponential per node; nodes with h < `h_min` are left untouched
    /// (1e-4 was the map's cut, 0 makes it exact).
    #[allow(clippy::too_many_arguments)]
    pub fn update(
        &mut self,
        x: &[f64],
        mask: Option<&[bool]>,
        bmu: usize,
        alpha: f64,
        radius: f64,
        nb: Neighbourhood,
        h_min: f64,
    ) {
        let dim = self.dim;
        for i in 0..self.n() {
            let ((ax, ay), (bx, by)) = (self.pos[bmu], self.pos[i]);
            let h = nb.weight((ax - bx) * (ax - bx) + (ay - by) * (ay - by), radius);
            if h < h_min {
                continue;
            }
            let k = alpha * h;
            let w = &mut self.weights[i * dim..(i + 1) * dim];
            match mask {
                None => {
                    for (wv, xv) in w.iter_mut().zip(x) {
                        *wv += k * (xv - *wv);
                    }
                }
                Some(m) => {
                    for ((wv, xv), &mv) in w.iter_mut().zip(x).zip(m) {
                        if mv {
                            *wv += k * (xv - *wv);
                        }
                    }
                }
            }
        }
    }

    /// All weights, node-major.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }
}
