//! The error type of the MuJoCo layer.

use thiserror::Error;

/// Everything that can go wrong when loading or running a MuJoCo model.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum MjError {
    /// The linked `libmujoco` is not the version these bindings were generated from.
    #[error(
        "MuJoCo version mismatch: the linked library reports {found}, this crate needs {expected} \
         (Debian's libmujoco-dev 2.2.2; install it with `make deps`)"
    )]
    Version {
        /// `mj_version()` of the linked library.
        found: i32,
        /// The version the bindings were generated from.
        expected: i32,
    },
    /// MuJoCo refused to load an MJCF file or string.
    #[error("cannot load MuJoCo model from {path}: {message}")]
    Load {
        /// The file path, or `<string>` for a model given as text.
        path: String,
        /// MuJoCo's own message (element, attribute, line).
        message: String,
    },
    /// MuJoCo raised an error while running (through `mju_error`).
    #[error("MuJoCo error: {message}")]
    Runtime {
        /// MuJoCo's message.
        message: String,
    },
    /// The simulation became unstable (bad qacc/qpos/qvel): MuJoCo reset the state.
    #[error("simulation unstable at t = {time:.4} s: {message} (MuJoCo reset the state; lower the timestep or the gains)")]
    Unstable {
        /// Simulation time before the failing step.
        time: f64,
        /// MuJoCo's warning text.
        message: String,
    },
    /// A named object does not exist in the model.
    #[error("no {kind} named {name:?} in the model")]
    NotFound {
        /// `joint`, `actuator`, `site`, `body`, `camera`...
        kind: &'static str,
        /// The name asked for.
        name: String,
    },
    /// A string handed to MuJoCo contains a NUL byte.
    #[error("{what} contains a NUL byte, which MuJoCo cannot take")]
    NulByte {
        /// What the string was (a path, a name, the XML text).
        what: &'static str,
    },
    /// The model is larger than MuJoCo's limits (for example its virtual file system).
    #[error("{what} is too large for MuJoCo: {size} bytes")]
    TooLarge {
        /// What was too large.
        what: &'static str,
        /// Its size in bytes.
        size: usize,
    },
    /// A [`crate::mujoco::Data`] that saw a MuJoCo error refuses to run until reset.
    #[error("this simulation state was poisoned by an earlier MuJoCo error ({message}); call reset() first")]
    Poisoned {
        /// The earlier error's message.
        message: String,
    },
}

/// Result of the MuJoCo layer.
pub type Result<T> = std::result::Result<T, MjError>;
