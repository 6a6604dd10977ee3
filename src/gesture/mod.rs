//! Synthetic, human-like demonstrations of named gestures.
//!
//! [`library`] holds the gestures (key poses and nominal timing); [`demonstrator`] turns one
//! into the continuous trajectory a person guiding the arm would produce, with a person's
//! variability. Recording it from the simulated joint encoders happens in the simulator
//! (see `crate::sim`), as in kinesthetic teaching.

mod catalog;
pub mod demonstrator;
pub mod library;
pub mod upper_body;

pub use demonstrator::{HumanTrajectory, Variation};
pub use library::{mirror, stand_init, upper, ArmPose, Gesture, Pose, Segment};
