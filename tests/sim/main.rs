//! The simulated Nao arm: the MuJoCo layer, rendering, the arm's regression figures and
//! contacts, the closed loop, `simulate` (one gesture and `--gesture all`), the baseline, the
//! held-out studies and sweeps on recorded demonstrations (`cargo test --test sim`; one
//! file: `cargo test --test sim sim_loop::`).
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

#[path = "../common/mod.rs"]
mod common;
#[path = "../hsom_common/mod.rs"]
mod hsom_common;

mod clip_render;
mod compare_baseline;
mod compare_cli;
mod contacts;
mod fuzz_mjcf;
mod gesture_fidelity;
mod heldout;
mod hierarchy_gates;
mod mujoco_safe_layer;
mod multi_fidelity;
mod render_offscreen;
mod sim_loop;
mod sim_regression;
mod simulate_all;
mod sweep;
