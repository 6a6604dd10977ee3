//! The Nao's upper body (head and both arms, 14 joints): its model against the published
//! tables, its demonstrations, the held-out clap, `simulate --robot upper-body` and its ROS 2
//! export (`cargo test --test upper_body`).
#![cfg(feature = "sim")] // needs MuJoCo

#[path = "../common/mod.rs"]
mod common;

mod nao_tables;
mod pointing;
mod simulate_upper_body;
mod upper_body_demos;
mod upper_body_heldout;
mod upper_body_model;
mod upper_body_ros2;
