//! The CoSCo-HSOM configuration (the paper's III-D): one XML file holds every setting;
//! it is parsed and validated once, up front, into a [`HsomConfig`] that only valid values
//! can reach. The schema is documented in `docs/CONFIG.md`.

mod errors;
mod hyperparams;
mod xml;

pub use errors::ConfigError;
pub use hyperparams::{
    Algorithm, AlgorithmParams, EventsParams, HsomConfig, HsomParams, IdDecoding, LevelParams,
    MemoryMode, Normalisation, PaperParams, ReproductionParams, StopRule,
    PAPER_MIN_LENGTH_FRACTION, PAPER_STATIONARY_STEPS, PAPER_STATIONARY_TOLERANCE,
};
pub(crate) use xml::Text;
pub use xml::{
    load_config, load_config_or_default, load_config_or_robots, parse_config, DEFAULT_CONFIG_NAME,
    NAO_GESTURES_XML,
};

#[cfg(test)]
mod tests;
