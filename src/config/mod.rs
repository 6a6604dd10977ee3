//! The CoSCo-HSOM configuration (the paper's III-D): one XML file holds every setting;
//! it is parsed and validated once, up front, into a [`HsomConfig`] that only valid values
//! can reach. The schema is documented in `docs/CONFIG.md`.

mod errors;
mod hyperparams;
mod xml;

pub use errors::ConfigError;
pub use hyperparams::{
    Algorithm, Alignment, Consensus, HsomConfig, HsomParams, IdDecoding, Knots, LevelParams,
    ListUpdate, MemoryMode, Normalisation, PartialTraining, Plan, Reflex, ReproductionMode,
    ReproductionParams, StopRule, Timing,
};
pub use xml::{load_config, parse_config};
