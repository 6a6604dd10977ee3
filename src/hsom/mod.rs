//! The CoSCo-HSOM hierarchy (paper II and III-C): levels of Kohonen maps, short-term memory
//! as activity lists (or, as the baseline, activity levels), sequential training with the
//! exponential update schedule, reproduction from an initial posture, save and load.
//!
//! ```no_run
//! use cosco_hsom::config::load_config;
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let config = load_config(std::path::Path::new("configs/table1.xml"))?;
//! # let demos: Vec<cosco_hsom::demos::Demonstration> = vec![];
//! let model = config.fit(&demos)?;
//! let gesture = model.reproduce(&demos[0].rows[0])?;
//! model.save(std::path::Path::new("model.bin"))?;
//! # Ok(()) }
//! ```

mod algorithm;
mod errors;
mod events;
mod labels;
mod memory;
mod paper;
mod persist;
mod recognize;
mod record;
mod reproduction;

pub use algorithm::{plans_word, Hsom, LevelSummary, ModelSummary};
pub use errors::{HsomError, PersistError};
pub use labels::{is_plain_label, GestureError, GestureModel, GESTURES_FORMAT_VERSION, MAX_LABELS};
pub use memory::{ActivityLevels, ActivityList};
pub use persist::{FilePart, FORMAT_VERSION};
pub use recognize::{Recognition, Scoring, PREFIX_BLEND};
pub use reproduction::{Reproduction, StopReason};
