//! The algorithm without the simulator: training and reproducing the hierarchy, the
//! labelled model and its recogniser, the held-out studies on synthetic data, the kinematic
//! loop, the loaders under fuzzing and the files the command line writes. Runs in both
//! builds (`cargo test --test algorithm`; one file: `cargo test --test algorithm stepper::`).

#[path = "../common/mod.rs"]
mod common;
#[path = "../hsom_common/mod.rs"]
mod hsom_common;

mod conditioning;
mod file_modes;
mod fuzz_loaders;
mod heldout_loop;
mod hsom_measure;
mod hsom_reproduction;
mod hsom_training;
mod multi_gesture;
mod offline_loo;
mod recognition_heldout;
mod recognizer;
mod stepper;
