//! The paper's experiment (Section IV), made repeatable: the jobs that teach the simulated Nao
//! gestures from demonstrations recorded at 40 Hz, reproduce them from the initial posture
//! alone on the arm and measure how faithful the reproductions are (the main job, `cosco
//! compare`, several gestures, the before/after variants, held out), and their reports,
//! figures and film. Executing and scoring on the arm live in [`crate::sim`], the evaluator
//! in [`crate::eval`]; the arm as the evaluator's executor here ([`executor`]).

pub mod all_gestures;
pub mod arm_loop;
pub mod baseline;
pub mod compare;
pub mod demonstrate;
pub mod executor;
pub mod figures;
pub mod film;
pub mod heldout;
pub mod job;
pub mod output;
pub mod report;
pub mod signature;
pub mod upper_body;
pub mod variants;

pub use crate::sim::Transition;
pub use demonstrate::{record_demonstrations, synthetic_demonstrations, DemoSettings};
pub use executor::{execute_and_score, ArmExecutor};
pub use film::film;
pub use heldout::{folds, leave_one_out};
pub use output::load_arm;

/// What a stage reports to a progress display: (stage, done, total).
pub type Progress<'a> = &'a dyn Fn(&str, usize, usize);

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
    /// A file or directory could not be written or created.
    #[error("{action} {}", path.display())]
    Io {
        /// What was being done ("creating", "writing the report into").
        action: &'static str,
        /// The file or directory.
        path: std::path::PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The arm's model could not be loaded (`path`: its MJCF file, `None` for the default).
    #[error("loading the {}", path.as_ref().map_or("default arm model".to_string(), |p| format!("arm model {}", p.display())))]
    Arm {
        /// The MJCF file given, if any.
        path: Option<std::path::PathBuf>,
        /// The cause.
        source: crate::sim::SimError,
    },
    /// The demonstrations do not fit the configuration's `stateLength`.
    #[error("the configuration's stateLength is {state_length}")]
    StateLength {
        /// The configuration's state length.
        state_length: usize,
        /// What is wrong with the demonstrations.
        source: crate::demos::DemoError,
    },
    /// The configuration was refused.
    #[error(transparent)]
    Config(#[from] crate::config::ConfigError),
    /// A demonstration could not be read, written or used.
    #[error(transparent)]
    Demo(#[from] crate::demos::DemoError),
    /// The GMM/GMR baseline failed, or its model could not be written or read back.
    #[error(transparent)]
    Gmr(#[from] crate::gmr::GmrError),
    /// Per-fold results could not be put together.
    #[error(transparent)]
    Folds(#[from] crate::eval::FoldsError),
    /// A model could not be saved.
    #[error(transparent)]
    Persist(#[from] crate::hsom::PersistError),
    /// A figure could not be drawn or written.
    #[error(transparent)]
    Plot(#[from] crate::plot::PlotError),
}

impl ExperimentError {
    /// An I/O error while `action` (say "creating") on `path`.
    pub fn io(action: &'static str, path: &std::path::Path) -> impl FnOnce(std::io::Error) -> Self {
        let path = path.to_path_buf();
        move |source| ExperimentError::Io {
            action,
            path,
            source,
        }
    }
}
