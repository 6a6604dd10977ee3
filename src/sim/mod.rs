//! The Nao H25 V5 left arm in MuJoCo (models/nao_left_arm.xml) and its position controller
//! with encoder recording (40 Hz by default).
//!
//! - [`spec`]: the left arm's joint table ([`crate::robot`]'s, as fixed-size postures),
//!   [`JOINT_NAMES`], named postures, posture checks.
//! - [`arm`]: [`NaoArm`] (the checked model) and [`ArmSim`] (one simulation of it).
//! - [`interp`]: transition profiles ([`Interpolation`]).
//! - [`controller`]: [`Controller`] for key-pose sequences and dense target trajectories.
//! - [`recording`]: [`Recording`], what the controller records.
//! - [`execute`]: postures executed on the arm ([`execute_postures`]), their [`Transition`].
//! - [`in_loop`]: a stepper driving the arm at 40 Hz from its encoders, held, pushed or
//!   given a new goal ([`in_loop::run_in_loop`], [`in_loop::ArmLoop`]).
//! - [`score`]: scoring on the arm with wrist paths ([`evaluate`]).
//! - [`error`]: [`SimError`], the room's error type.

pub mod arm;
pub mod controller;
pub mod error;
pub mod execute;
pub mod in_loop;
pub mod interp;
pub mod recording;
pub mod score;
pub mod spec;

pub use arm::{ArmSim, NaoArm, ServoGains, DEFAULT_MODEL_PATH, GRIPPER_SITE, WRIST_SITE};
pub use controller::{
    Controller, ControllerConfig, Grab, KeyPose, TargetTrajectory, DEFAULT_RECORD_RATE_HZ,
};
pub use error::{Result, SimError};
pub use execute::{
    clamp_to_ranges, clamp_to_ranges_of, execute_postures, key_pose_indices, Transition,
};
pub use interp::Interpolation;
pub use recording::{limb, own_contacts, Recording, Touch};
pub use score::{
    check_reachable, check_reachable_of, demo_wrist_paths, evaluate, site_path, trajectory,
    wrist_path, LEAD_IN_PEAK_SPEED, RIGHT_WRIST_SITE, SWING_JOINT,
};
pub use spec::{
    check_joint, check_posture, clamp_joint, clamp_posture, JointSpec, NamedPosture, Posture,
    JOINT_NAMES, JOINT_SPECS, NJ,
};
