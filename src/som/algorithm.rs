//! The map itself: weights, best-matching-unit search, neighbourhood update, quality.

use rand::Rng;

use super::hyperparams::{Neighbourhood, Topology};

/// A node's ID: its `(x, y)` grid position (`x` the column, `y` the row).
pub type NodeId = (u16, u16);

/// Errors of the stand-alone map trainer.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum SomError {
    /// A setting is out of range.
    #[error("invalid SOM parameter {name} = {value}")]
    InvalidParam {
        /// Parameter name.
        name: &'static str,
        /// Offending value.
        value: String,
    },
    /// No data, or zero-length samples.
    #[error("no training data (or zero-dimensional samples)")]
    EmptyData,
    /// A sample of another length than the first.
    #[error("sample {row} has {found} values, expected {expected}")]
    DimensionMismatch {
        /// Expected length.
        expected: usize,
        /// Found length.
        found: usize,
        /// Sample index.
        row: usize,
    },
    /// A NaN or infinite value.
    #[error("sample {row}, column {column} is not a finite number")]
    NonFinite {
        /// Sample index.
        row: usize,
        /// Column index.
        column: usize,
    },
    /// Weights of the wrong length.
    #[error(
        "weights have {found} values, a {rows}x{cols} map of dimension {dim} needs {expected}"
    )]
    WeightsLength {
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
        /// Dimension.
        dim: usize,
        /// Expected length.
        expected: usize,
        /// Found length.
        found: usize,
    },
}

/// A 2-D Kohonen map of `rows` x `cols` nodes, each with a weight vector of length `dim`.
/// Node index `i = y * cols + x` has ID `(x, y)`.
#[derive(Debug, Clone, PartialEq)]
pub struct SelfOrganizingMap {
    rows: usize,
    cols: usize,
    dim: usize,
    topology: Topology,
    weights: Vec<f64>,
    /// Grid position of every node (for neighbourhood distances).
    pos: Vec<(f64, f64)>,
}

fn positions(rows: usize, cols: usize, topology: Topology) -> Vec<(f64, f64)> {
    let mut pos = Vec::with_capacity(rows * cols);
    for y in 0..rows {
        for x in 0..cols {
            pos.push(match topology {
                Topology::Orthogonal => (x as f64, y as f64),
                Topology::Hexagonal => (
                    x as f64 + 0.5 * (y % 2) as f64,
                    y as f64 * (3f64).sqrt() / 2.0,
                ),
            });
        }
    }
    pos
}

impl SelfOrganizingMap {
    /// A map whose weights are drawn uniformly from `rng`, dimension `d` inside `[lo[d], hi[d]]`.
    /// `lo` and `hi` must have length `dim`, `rows` and `cols` must be >= 1 (checked by callers).
    pub fn new_random<R: Rng>(
        rows: usize,
        cols: usize,
        dim: usize,
        topology: Topology,
        lo: &[f64],
        hi: &[f64],
        rng: &mut R,
    ) -> Self {
        let mut weights = Vec::with_capacity(rows * cols * dim);
        for _ in 0..rows * cols {
            for d in 0..dim {
                let u: f64 = rng.gen();
                weights.push(lo[d] + (hi[d] - lo[d]) * u);
            }
        }
        SelfOrganizingMap {
            rows,
            cols,
            dim,
            topology,
            weights,
            pos: positions(rows, cols, topology),
        }
    }

    /// A map with the given weights (node-major, `rows * cols * dim` values).
    pub fn from_weights(
        rows: usize,
        cols: usize,
        dim: usize,
        topology: Topology,
        weights: Vec<f64>,
    ) -> Result<Self, SomError> {
        let expected = rows * cols * dim;
        if weights.len() != expected {
            return Err(SomError::WeightsLength {
                rows,
                cols,
                dim,
                expected,
                found: weights.len(),
            });
        }
        Ok(SelfOrganizingMap {
            rows,
            cols,
            dim,
            topology,
            weights,
            pos: positions(rows, cols, topology),
        })
    }

    /// Set node `i`'s weights (`dim` values; shorter or longer slices are cut or padded by
    /// what is there already).
    pub fn set_weights(&mut self, i: usize, w: &[f64]) {
        let d = self.dim;
        for (dst, src) in self.weights[i * d..(i + 1) * d].iter_mut().zip(w) {
            *dst = *src;
        }
    }

    /// Number of grid rows.
    pub fn rows(&self) -> usize {
        self.rows
    }
    /// Number of grid columns.
    pub fn cols(&self) -> usize {
        self.cols
    }
    /// Length of each weight vector.
    pub fn dim(&self) -> usize {
        self.dim
    }
    /// Grid topology.
    pub fn topology(&self) -> Topology {
        self.topology
    }
    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.rows * self.cols
    }
    /// True for a map without nodes (never, once checked).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// All weights, node-major.
    pub fn all_weights(&self) -> &[f64] {
        &self.weights
    }
    /// Weight vector of node index `i`.
    #[inline]
    pub fn weights(&self, i: usize) -> &[f64] {
        &self.weights[i * self.dim..(i + 1) * self.dim]
    }
    /// ID `(x, y)` of node index `i`.
    #[inline]
    pub fn id(&self, i: usize) -> NodeId {
        ((i % self.cols) as u16, (i / self.cols) as u16)
    }
    /// Node index of ID `(x, y)` (which must be on the grid).
    #[inline]
    pub fn index(&self, id: NodeId) -> usize {
        id.1 as usize * self.cols + id.0 as usize
    }
    /// Squared distance between two nodes on the grid (topology-aware).
    #[inline]
    pub fn grid_distance2(&self, a: usize, b: usize) -> f64 {
        let (ax, ay) = self.pos[a];
        let (bx, by) = self.pos[b];
        (ax - bx) * (ax - bx) + (ay - by) * (ay - by)
    }
    /// True when nodes `a` and `b` are adjacent (8-neighbourhood on the orthogonal grid,
    /// 6-neighbourhood on the hexagonal one).
    pub fn are_neighbours(&self, a: usize, b: usize) -> bool {
        let d2 = self.grid_distance2(a, b);
        match self.topology {
            Topology::Orthogonal => d2 <= 2.0 + 1e-9,
            Topology::Hexagonal => d2 <= 1.0 + 1e-9,
        }
    }

    /// Best-matching unit of `x` (length `dim`): its index and squared distance. Ties go to
    /// the lowest index.
    #[inline]
    pub fn bmu(&self, x: &[f64]) -> (usize, f64) {
        let mut best = (0, f64::INFINITY);
        for (i, w) in self.weights.chunks_exact(self.dim).enumerate() {
            let mut d = 0.0;
            for (a, b) in w.iter().zip(x) {
                let t = a - b;
                d += t * t;
            }
            if d < best.1 {
                best = (i, d);
            }
        }
        best
    }

    /// Best-matching unit of `x` using only the dimensions where `mask` is true (the unknown
    /// dimensions are ignored): its index and squared distance over the known dimensions.
    pub fn bmu_masked(&self, x: &[f64], mask: &[bool]) -> (usize, f64) {
        let mut best = (0, f64::INFINITY);
        for (i, w) in self.weights.chunks_exact(self.dim).enumerate() {
            let mut d = 0.0;
            for ((a, b), &m) in w.iter().zip(x).zip(mask) {
                if m {
                    let t = a - b;
                    d += t * t;
                }
            }
            if d < best.1 {
                best = (i, d);
            }
        }
        best
    }

    /// Best-matching unit of `x` over the dimension range `range` only (e.g. the state half).
    pub fn bmu_range(&self, x: &[f64], range: std::ops::Range<usize>) -> (usize, f64) {
        let mut best = (0, f64::INFINITY);
        for (i, w) in self.weights.chunks_exact(self.dim).enumerate() {
            let mut d = 0.0;
            for (a, b) in w[range.clone()].iter().zip(x) {
                let t = a - b;
                d += t * t;
            }
            if d < best.1 {
                best = (i, d);
            }
        }
        best
    }

    /// Indices of the best and second-best matching units of `x`.
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

    /// Kohonen update towards `x` around node `bmu`: every node moves by
    /// `alpha * h(grid distance, radius) * (x - w)`, on the dimensions where `mask` is true
    /// (all of them when `mask` is `None`). Nodes with h < 1e-4 are left untouched.
    pub fn update(
        &mut self,
        x: &[f64],
        mask: Option<&[bool]>,
        bmu: usize,
        alpha: f64,
        radius: f64,
        neighbourhood: Neighbourhood,
    ) {
        let dim = self.dim;
        for i in 0..self.rows * self.cols {
            let h = neighbourhood.weight(self.grid_distance2(bmu, i), radius);
            if h < 1e-4 {
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

    /// Mean Euclidean distance from each sample to its best-matching unit (0 for no data).
    pub fn quantization_error(&self, data: &[Vec<f64>]) -> f64 {
        if data.is_empty() {
            return 0.0;
        }
        data.iter().map(|x| self.bmu(x).1.sqrt()).sum::<f64>() / data.len() as f64
    }

    /// Fraction of samples whose best and second-best matching units are not adjacent on the
    /// grid (0 for no data or a single-node map).
    pub fn topographic_error(&self, data: &[Vec<f64>]) -> f64 {
        if data.is_empty() || self.len() < 2 {
            return 0.0;
        }
        let bad = data
            .iter()
            .filter(|x| {
                let (a, b) = self.best_two(x);
                !self.are_neighbours(a, b)
            })
            .count();
        bad as f64 / data.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Decay, Schedule, SomParams};
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn ids_round_trip_through_indices() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let m = SelfOrganizingMap::new_random(
            3,
            5,
            2,
            Topology::Orthogonal,
            &[0.0; 2],
            &[1.0; 2],
            &mut rng,
        );
        for i in 0..15 {
            assert_eq!(m.index(m.id(i)), i);
        }
        assert_eq!(m.id(7), (2, 1));
    }

    #[test]
    fn hexagonal_inner_node_has_six_neighbours() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let m =
            SelfOrganizingMap::new_random(5, 5, 1, Topology::Hexagonal, &[0.0], &[1.0], &mut rng);
        let c = m.index((2, 2));
        let n = (0..25)
            .filter(|&j| j != c && m.are_neighbours(c, j))
            .count();
        assert_eq!(n, 6);
        let o =
            SelfOrganizingMap::new_random(5, 5, 1, Topology::Orthogonal, &[0.0], &[1.0], &mut rng);
        let n = (0..25)
            .filter(|&j| j != c && o.are_neighbours(c, j))
            .count();
        assert_eq!(n, 8);
    }

    #[test]
    fn initial_weights_lie_in_the_given_box() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let m = SelfOrganizingMap::new_random(
            4,
            4,
            2,
            Topology::Orthogonal,
            &[10.0, -5.0],
            &[20.0, -4.0],
            &mut rng,
        );
        for i in 0..m.len() {
            let w = m.weights(i);
            assert!((10.0..=20.0).contains(&w[0]) && (-5.0..=-4.0).contains(&w[1]));
        }
    }

    #[test]
    fn masked_bmu_ignores_unknown_dimensions() {
        let m = SelfOrganizingMap::from_weights(
            1,
            2,
            2,
            Topology::Orthogonal,
            vec![0.0, 100.0, 5.0, 0.0],
        )
        .unwrap();
        assert_eq!(m.bmu(&[0.0, 0.0]).0, 1);
        assert_eq!(m.bmu_masked(&[0.0, 0.0], &[true, false]).0, 0);
    }

    #[test]
    fn schedules_start_and_end_at_their_values() {
        for decay in [Decay::Exponential, Decay::Linear] {
            let s = Schedule {
                initial: 0.5,
                last: 0.01,
                decay,
            };
            assert!((s.at(0.0) - 0.5).abs() < 1e-12 && (s.at(1.0) - 0.01).abs() < 1e-12);
            assert!(s.at(0.5) < 0.5 && s.at(0.5) > 0.01);
        }
    }

    #[test]
    fn training_lowers_quantization_error_and_keeps_topology() {
        // points along a line: a trained 1x10 map orders itself along it
        let data: Vec<Vec<f64>> = (0..200)
            .map(|i| vec![((i * 37) % 200) as f64 / 10.0])
            .collect();
        let mut p = SomParams::new(1, 10);
        p.steps = 2000;
        let m = p.fit(&data).unwrap();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0);
        let untrained = SelfOrganizingMap::new_random(
            1,
            10,
            1,
            Topology::Orthogonal,
            &[0.0],
            &[20.0],
            &mut rng,
        );
        assert!(
            m.quantization_error(&data) < 0.6,
            "{}",
            m.quantization_error(&data)
        );
        assert!(m.quantization_error(&data) < untrained.quantization_error(&data));
        assert!(m.topographic_error(&data) < 0.05);
        let w: Vec<f64> = (0..10).map(|i| m.weights(i)[0]).collect();
        let inc = w.windows(2).all(|p| p[0] < p[1]);
        let dec = w.windows(2).all(|p| p[0] > p[1]);
        assert!(inc || dec, "{w:?}");
    }

    #[test]
    fn invalid_learning_factor_is_rejected() {
        let mut p = SomParams::new(2, 2);
        p.learning_factor.initial = 1.5;
        assert!(matches!(
            p.fit(&[vec![0.0]]),
            Err(SomError::InvalidParam { .. })
        ));
    }
}
