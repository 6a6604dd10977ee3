//! The CoSCo-HSOM hierarchy (paper II and III-C): levels of Kohonen maps, short-term memory
//! as activity lists (or, as the baseline, activity levels), sequential training with the
//! exponential update schedule, reproduction from an initial posture, save and load.
//!
//! Where to look: `model.rs` describes the trained model once (the part both algorithms read,
//! and the paper's or the events extension's own part) with the checks of each part;
//! [`Hsom`] is a model of one algorithm or the other, and `dispatch.rs` hands each operation
//! to it; `algorithm.rs` trains it on what `inputs.rs` checks; `paper.rs` holds the paper's
//! reproduction and the one entry of both algorithms' (the events extension's in `events/`:
//! its plans in `events/plan.rs`, the executed curve in `events/curve.rs`); `summary.rs` is
//! what `cosco inspect` shows; `labels.rs` and `recognize.rs` are several gestures and their
//! recognition; `persist.rs` writes and reads model files of either kind; `stepper.rs` is
//! the hierarchy and the nearest sequence in the loop ([`crate::stepper`]).
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
mod dispatch;
mod errors;
mod events;
mod followers;
mod inputs;
pub(crate) mod kept;
mod labels;
mod memory;
mod model;
mod paper;
mod persist;
mod recognize;
mod recognizer;
mod record;
mod reproduction;
mod stepper;
mod summary;
mod update;

pub use algorithm::Fit;
pub use errors::{GestureError, HsomError, PersistError};
pub(crate) use events::{as_smooth_as, smooth_warp, start_fade};
pub use kept::kept_demonstrations;
pub use kept::{BAND_ROWS, KEPT_DEMONSTRATIONS, MAX_LEARNED};
pub use labels::{Gestures, GESTURES_FORMAT_VERSION, MAX_LABELS};
pub use memory::{ActivityLevels, ActivityList};
pub(crate) use model::DemoSmoothness;
pub use model::{GestureModel, Hsom, Scoring};
pub use persist::{FilePart, FORMAT_VERSION};
pub use recognize::{Recognition, PREFIX_BLEND, WEIGHED_SHOWN};
pub use recognizer::{Commit, Recognizer, StreamCalibration};
pub use reproduction::{Reproduction, StopReason};
pub use stepper::{HsomReplan, HsomStepper, NearestReplan, NearestStepper};
pub use summary::{plans_word, LevelSummary, ModelSummary};

#[cfg(test)]
mod tests;
