//! CoSCo-HSOM: Compressed Sparse Code Hierarchical Self-Organizing Map (Pierris & Dahl),
//! with a MuJoCo-simulated Nao left arm to teach it gestures and reproduce them.
//!
//! Rooms:
//! - [`mujoco`]: bindings to Debian's MuJoCo 2.2.2 and a safe layer; with [`render`], the only
//!   places with `unsafe`.
//! - [`render`]: off-screen rendering with OSMesa, PNG frames, GIF clips, contact sheets.
//! - [`robot`]: the Nao as one description: joints (ranges, velocity and torque limits),
//!   named postures and the MJCF model they are read from.
//! - [`sim`]: the Nao left arm model, its position controller with 40 Hz encoder recording,
//!   and executing and scoring a reproduction on it.
//! - [`som`]: a Kohonen map.
//! - [`hsom`]: the CoSCo-HSOM hierarchy: activity lists, training, reproduction, save/load.
//! - [`aim`]: pointing and gaze at a point in space through the Nao's kinematics, and the
//!   via-points that carry a reproduction's held part through the aimed posture.
//! - [`condition`]: a goal and via-points beyond the initial posture, and bending a trajectory
//!   onto them exactly.
//! - [`config`]: the XML configuration, validated once into a checked type.
//! - [`demos`]: demonstration CSV files, and the rules of a set of them.
//! - [`demo_sets`]: demonstration sets as the commands read them from paths: one gesture, or
//!   labelled directories.
//! - [`dtw`]: dynamic time warping.
//! - [`gmr`]: the baseline, GMM/GMR.
//! - [`promp`]: a second baseline, ProMP conditioned on the initial posture.
//! - [`dmp`]: a third baseline, the dynamic movement primitive, conditioned on start and goal.
//! - [`stepper`]: a reproduction in the loop: given the posture the encoders read, the next
//!   posture to command; one trait for every method, and a kinematic loop with disturbances.
//! - [`gesture`]: synthetic human-like demonstrations.
//! - [`metrics`]: fidelity metrics.
//! - [`plot`]: PNG plots.
//! - [`experiment`]: the jobs on the simulated arm (the paper's experiment end to end, compare,
//!   several gestures, variants, held out), the arm as the evaluator's executor, and their
//!   reports, figures and film.
//! - [`sweep`]: grids of runs from a TOML spec, on a thread pool or a cluster's job arrays,
//!   merged into tables and box plots.
//! - [`app`]: one way in: train, reproduce, recognize, evaluate, inspect, export, import,
//!   each one function the `cosco` binary and the Python package call (same checks, same
//!   messages), with one error type; no room of the library calls it.
//! - [`eval`]: one evaluator (methods x an executor; in-sample and leave-one-out as two splits
//!   of one fold; one result family; one worker pool).
//! - [`fsutil`]: atomic file writes, and the check that an output can be written.
//! - [`errors`]: an error and its causes on one line.
//! - [`table`]: Markdown tables, as the reports print them.
//! - [`stats`]: order statistics (median, quantiles, upper median).
//! - [`export`]: a reproduction to a robot: time scaling, the robot's limits, NAOqi JSON,
//!   ROS 2 MCAP ([`ros2`], feature `ros2`, on by default, which also imports bags) and CSV.
//! - [`resample`]: demonstrations at different sampling rates brought to one.
//! - `trajectory`: a joint trajectory and the export's errors, below both [`export`] and
//!   [`ros2`], which write it.
//!
//! Feature `sim` (on by default) holds everything that needs MuJoCo or OSMesa: [`mujoco`],
//! [`render`], [`sim`], [`experiment`] and [`sweep`], and turns on `plot` ([`plot`]: PNG
//! plots, whose only users are the simulator's reports). Without it (`--no-default-features`) the
//! crate is the algorithm, configuration, persistence, GMM/GMR, DTW and metrics (with no
//! wrist paths: those need the arm's kinematics), and builds without libmujoco-dev.
#![warn(missing_docs)]

pub mod aim;
pub mod app;
pub mod condition;
pub mod config;
pub mod curve;
pub mod dba;
pub mod demo_sets;
pub mod demos;
pub mod dmp;
pub mod dtw;
pub mod errors;
pub mod eval;
#[cfg(feature = "sim")]
pub mod experiment;
pub mod export;
pub mod fsutil;
pub mod gesture;
pub mod gmr;
pub mod hsom;
pub mod metrics;
#[cfg(feature = "sim")]
pub mod mujoco;
pub mod nearest;
pub mod promp;

#[cfg(feature = "plot")]
pub mod plot;
#[cfg(feature = "sim")]
pub mod render;
pub mod resample;
pub mod robot;
#[cfg(feature = "ros2")]
pub mod ros2;
#[cfg(feature = "sim")]
pub mod sim;
pub mod som;
pub mod stats;
pub mod stepper;
#[cfg(feature = "sim")]
pub mod sweep;
pub mod table;
pub(crate) mod trajectory;

// The unit tests share the synthetic data of the integration tests (tests/hsom_common), which
// name this crate `cosco_hsom`.
#[cfg(test)]
extern crate self as cosco_hsom;
