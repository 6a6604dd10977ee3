//! A Kohonen self-organizing map: a 2-D grid of nodes (orthogonal or hexagonal topology),
//! seeded random initial weights, best-matching-unit search (optionally on a subset of the
//! input's dimensions), a neighbourhood update with decaying learning factor and radius,
//! and the two usual quality measures (quantization and topographic error).
//!
//! A node's ID is its `(x, y)` grid position: `x` the column, `y` the row.

mod algorithm;
mod hyperparams;
mod kernel;
pub mod reference;

pub use algorithm::{NodeId, NodeWeights, Reach, SelfOrganizingMap, SomError, DEFAULT_H_MIN};
pub(crate) use hyperparams::word;
pub use hyperparams::{Decay, Neighbourhood, Schedule, SomParams, Topology};
