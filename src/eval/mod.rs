//! One evaluator, without the simulator: the methods compared on the same folds
//! ([`Method`]: the hierarchy, the nearest sequence, height 1, GMM/GMR, ProMP, the replay of
//! the training demonstration that starts nearest), an [`Executor`] that carries their
//! postures out ([`Kinematic`]: as they are; the simulated arm's is `experiment::ArmExecutor`), one
//! fold ([`run_fold`]) whose held-out and in-sample [`Split`]s make every study
//! ([`leave_one_out`] with the in-sample result beside it), one result family ([`Run`],
//! [`Fold`], [`GestureLoo`], [`HeldOut`] and their summaries), and one worker pool
//! ([`Pool`]).
//!
//! Used by `cosco heldout` (any recorded data), the Python package, `simulate`'s in-sample and
//! held-out results, the sweeps and the examples (with the arm's executor).
//!
//! Reproductions are scored as executed: joint DTW in the data's own units per step and
//! relative to the diagonal of the gesture's bounding box (comparable across gestures and
//! units), final-sample error, duration ratio and normalised jerk over the held-out
//! demonstration's, all after the idle trimming of `docs/METRICS.md`; and the start speed and
//! final error against the training demonstrations' start speeds and end spread.
//!
//! On the upper body's joints, the lag between the two arms of every reproduction against the
//! demonstrations' ([`two_arms`]).
//!
//! Recognition of several gestures, held out likewise: [`recognition`] (`cosco recognition`).

mod executor;
mod far;
mod files;
mod fold;
mod in_loop;
mod learned;
mod loo;
mod method;
mod pool;
pub mod recognition;
mod report;
mod results;
mod study;
mod two_arms;

pub use executor::{Executed, Executor, Kinematic};
pub use far::far_target;
pub use files::{heldout, heldout_with, HeldoutJob};
pub use fold::{
    all_but, diagonal, fold, fold_scores, run_fold, scored, sitting, Conditioning, FoldInput,
    FoldRuns, MethodRun, Split, Training, GMR_UNCONDITIONED, SWING_MIN_AMPLITUDE_RAD,
};
pub use in_loop::{
    in_loop, loop_markdown, method_runs, Against, GestureLoop, LoopRun, Runs, LOOP_METHODS,
};
pub use learned::{Fitted, Kept, Learned, Planned};
pub use loo::{
    leave_one_out, loo_folds, loo_map, read_gestures_at, Gestures, LooError, LooSettings,
    MIN_TAUGHT_DEMOS,
};
pub use method::{peak_speed, Method, GMR_COMPONENTS};
pub use pool::Pool;
pub use report::markdown;
#[cfg(feature = "plot")]
pub use report::png;
pub use results::{
    failures, passed, summary, Commanded, ConditionErrors, Fold, FoldScores, FoldsError,
    GestureLoo, HeldOut, HeldOutSummary, MethodSummary, Run, Score, Swings, MIN_DEMO_JERK,
};
pub use study::{sittings_ratios, study, Extra, Section, SittingsRatio, Study, StudyDocument};
pub use two_arms::{two_arms, GestureLags, MethodLags};
