//! The paper's experiment (Section IV), made repeatable: teach the simulated Nao a gesture from
//! demonstrations recorded at 40 Hz, reproduce it from the initial posture alone on the
//! simulated arm, and measure how faithful the reproduction is.

pub mod all_gestures;
pub mod arm_executor;
pub mod baseline;
pub mod closed_loop;
pub mod compare;
pub mod demonstrate;
pub mod evaluate;
pub mod execute;
pub mod figures;
pub mod film;
pub mod heldout;
pub mod job;
pub mod multi;
pub mod pipeline;
pub mod report;
pub mod study;
pub mod variants;

pub use arm_executor::ArmExecutor;
pub use demonstrate::{
    joint_limits, record_demonstrations, synthetic_demonstrations, DemoSettings,
};
pub use evaluate::{
    are_arm_joints, check_reachable, demo_wrist_paths, evaluate, trajectory, wrist_path,
    RANGE_TOLERANCE_RAD,
};
pub use execute::{
    clamp_to_ranges, execute_grabbed, execute_postures, ReadingNoise, Replan, Transition,
};
pub use film::film;
pub use heldout::{
    continuation_folds, gmr_folds, hsom_and_sequence_folds, hsom_folds, leave_one_out, Fold,
    FoldScores, HeldOut, HeldOutSummary, Swings,
};
pub use pipeline::{
    execute_and_score, learn_and_reproduce, learn_and_score, reproduce_variant, Executed, Outcome,
    Split, Training,
};

/// Errors of the experiment pipeline.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExperimentError {
    /// A setting is out of its allowed range.
    #[error("{0}")]
    Invalid(String),
    /// The simulator refused something.
    #[error(transparent)]
    Sim(#[from] crate::sim::SimError),
    /// Rendering failed.
    #[error(transparent)]
    Render(#[from] crate::render::RenderError),
    /// The metrics refused their input.
    #[error(transparent)]
    Metrics(#[from] crate::metrics::MetricsError),
    /// Training or reproduction failed.
    #[error(transparent)]
    Hsom(#[from] crate::hsom::HsomError),
}
