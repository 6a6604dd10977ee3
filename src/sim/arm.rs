//! The arm model ([`NaoArm`]) and one simulation of it ([`ArmSim`]).

use std::path::{Path, PathBuf};

use super::error::{Result, SimError};
use super::spec::{check_posture_of, clamp_posture_of, NJ};
use crate::mujoco::{Data, Model};
use crate::robot::Robot;

/// Path of the shipped model, models/nao_left_arm.xml in the crate.
pub const DEFAULT_MODEL_PATH: &str = crate::robot::Robot::LeftArm.model_path();

/// Name of the site at the LWristYaw joint origin.
pub const WRIST_SITE: &str = "l_wrist";
/// Name of the site at the hand point (HandOffsetX/Z beyond the wrist).
pub const GRIPPER_SITE: &str = "l_gripper";

/// Smallest physics time step accepted, s (bounds the steps of a simulated second).
pub const MIN_TIMESTEP_S: f64 = 1e-5;
/// Largest physics time step accepted, s: several steps per 40 Hz sample, and inside the
/// servos' stability margin (docs in models/nao_left_arm.xml).
pub const MAX_TIMESTEP_S: f64 = 0.005;

/// When MuJoCo refused an MJCF document: the arm's first joint that no actuator element of
/// the document drives, as [`SimError::Missing`] (None when every joint has one, or the
/// document is not XML we can read: MuJoCo's own message stands then).
fn missing_actuator(robot: Robot, xml: &str) -> Option<SimError> {
    use quick_xml::events::Event;
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut in_actuator = 0usize;
    let mut driven: Vec<String> = Vec::new();
    let mut saw_actuator_block = false;
    loop {
        match reader.read_event() {
            Ok(Event::Start(e)) => {
                if e.name().as_ref() == b"actuator" {
                    in_actuator += 1;
                    saw_actuator_block = true;
                } else if in_actuator > 0 {
                    driven.extend(joint_attr(&e));
                }
            }
            Ok(Event::Empty(e)) if in_actuator > 0 => driven.extend(joint_attr(&e)),
            Ok(Event::End(e)) if e.name().as_ref() == b"actuator" => {
                in_actuator = in_actuator.saturating_sub(1)
            }
            Ok(Event::Eof) => break,
            Err(_) => return None,
            _ => {}
        }
    }
    if !saw_actuator_block {
        return None;
    }
    robot
        .joint_names()
        .iter()
        .find(|j| !driven.iter().any(|d| d == *j))
        .map(|j| SimError::Missing {
            kind: "actuator",
            name: j.to_string(),
        })
}

fn joint_attr(e: &quick_xml::events::BytesStart<'_>) -> Option<String> {
    e.attributes()
        .flatten()
        .find(|a| a.key.as_ref() == b"joint")
        .and_then(|a| a.unescape_value().ok().map(|v| v.into_owned()))
}

/// Servo gains of one joint, as identified from the model: the actuator force is
/// `kp (ctrl - q) - kv qdot`, clipped to the joint's maximum torque.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServoGains {
    /// Position gain, N m / rad.
    pub kp: f64,
    /// Velocity gain, N m s / rad.
    pub kv: f64,
}

#[derive(Debug, Clone, Copy)]
struct JointIndex {
    qpos: usize,
    dof: usize,
    actuator: usize,
}

/// A Nao model with `N` actuated joints (the left arm's six by default, the upper body's 14),
/// checked against its robot's description ([`crate::robot`]).
///
/// ```
/// let arm = cosco_hsom::sim::NaoArm::load_default()?;
/// let mut sim = arm.sim()?;
/// sim.set_posture(&cosco_hsom::sim::NamedPosture::StandInit.angles())?;
/// assert!(sim.gripper_position()[2] < 0.0); // the hand hangs below the shoulder
/// # Ok::<(), cosco_hsom::sim::SimError>(())
/// ```
pub struct NaoArm<const N: usize = NJ> {
    robot: Robot,
    model: Model,
    joints: [JointIndex; N],
    wrist_site: usize,
    gripper_site: usize,
    gains: [ServoGains; N],
}

impl<const N: usize> std::fmt::Debug for NaoArm<N> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NaoArm")
            .field("gains", &self.gains)
            .finish_non_exhaustive()
    }
}

impl NaoArm {
    /// Load and check an MJCF file of the left arm ([`NaoArm::load_robot`]).
    pub fn load(path: impl AsRef<Path>) -> Result<NaoArm> {
        Self::load_robot(Robot::LeftArm, path)
    }

    /// Load the shipped model ([`DEFAULT_MODEL_PATH`]).
    pub fn load_default() -> Result<NaoArm> {
        Self::load(DEFAULT_MODEL_PATH)
    }

    /// The shipped model's path.
    pub fn default_model_path() -> PathBuf {
        PathBuf::from(DEFAULT_MODEL_PATH)
    }

    /// Load and check a left-arm MJCF document given as a string (a missing actuator reported
    /// as in [`NaoArm::load_robot`]).
    pub fn from_xml_str(xml: &str) -> Result<NaoArm> {
        match Model::from_xml_str(xml) {
            Ok(model) => Self::from_model(Robot::LeftArm, model),
            Err(e) => Err(missing_actuator(Robot::LeftArm, xml).unwrap_or(SimError::Mujoco(e))),
        }
    }
}

impl<const N: usize> NaoArm<N> {
    /// Load and check an MJCF file of `robot` (whose joints must number `N`). When MuJoCo
    /// refuses it, a file that lacks one of the robot's actuators is reported as such
    /// (MuJoCo's own message is then about the keyframes' control vectors).
    pub fn load_robot(robot: Robot, path: impl AsRef<Path>) -> Result<NaoArm<N>> {
        let path = path.as_ref();
        match Model::from_xml_path(path) {
            Ok(model) => Self::from_model(robot, model),
            Err(e) => Err(std::fs::read_to_string(path)
                .ok()
                .and_then(|text| missing_actuator(robot, &text))
                .unwrap_or(SimError::Mujoco(e))),
        }
    }

    /// Load `robot`'s shipped model.
    pub fn load_shipped(robot: Robot) -> Result<NaoArm<N>> {
        Self::load_robot(robot, robot.model_path())
    }

    /// The robot this model is.
    pub fn robot(&self) -> Robot {
        self.robot
    }

    /// Check a loaded model of `robot`: its named joints with the documented ranges, one
    /// actuator per joint (named after it, driving it, with the joint's range as control range
    /// and the documented torque limit), the wrist and gripper sites; then identify each
    /// servo's gains.
    pub fn from_model(robot: Robot, model: Model) -> Result<NaoArm<N>> {
        let specs = robot.joints();
        if specs.len() != N {
            return Err(SimError::WrongJointCount {
                expected: N,
                got: specs.len(),
            });
        }
        let dt = model.timestep();
        if !(dt.is_finite() && (MIN_TIMESTEP_S..=MAX_TIMESTEP_S).contains(&dt)) {
            return Err(SimError::BadOption {
                name: "option/@timestep",
                value: dt,
                allowed: "a time step from 1e-5 to 0.005 s (the controller records at 40 Hz and \
                          runs the servos at every physics step; the shipped model uses 0.002)",
            });
        }
        let mut joints = [JointIndex {
            qpos: 0,
            dof: 0,
            actuator: 0,
        }; N];
        for (k, spec) in specs.iter().enumerate() {
            let missing = |kind| SimError::Missing {
                kind,
                name: spec.name.to_string(),
            };
            let j = model.joint_id(spec.name).ok_or_else(|| missing("joint"))?;
            let a = model
                .actuator_id(spec.name)
                .ok_or_else(|| missing("actuator"))?;
            let range = model.joint_range(j);
            check_range(spec.name, "joint range", range, spec.range)?;
            check_range(
                spec.name,
                "actuator control range",
                model.actuator_ctrl_range(a),
                spec.range,
            )?;
            check_range(
                spec.name,
                "actuator force range",
                model.actuator_force_range(a),
                (-spec.max_torque, spec.max_torque),
            )?;
            if model.actuator_joint(a) != Some(j) {
                return Err(SimError::ModelMismatch {
                    name: spec.name.to_string(),
                    what: "actuator's joint",
                    found: format!(
                        "{:?}",
                        model.actuator_joint(a).and_then(|i| model.joint_name(i))
                    ),
                    expected: spec.name.to_string(),
                });
            }
            joints[k] = JointIndex {
                qpos: model.joint_qpos_adr(j),
                dof: model.joint_dof_adr(j),
                actuator: a,
            };
        }
        let site = |name: &str| {
            model.site_id(name).ok_or_else(|| SimError::Missing {
                kind: "site",
                name: name.to_string(),
            })
        };
        let wrist_site = site(WRIST_SITE)?;
        let gripper_site = site(GRIPPER_SITE)?;
        let gains = identify_gains(robot, &model, &joints)?;
        Ok(NaoArm {
            robot,
            model,
            joints,
            wrist_site,
            gripper_site,
            gains,
        })
    }

    /// The MuJoCo model (for rendering or inspection).
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The servo gains identified from the model, in [`JOINT_NAMES`] order.
    pub fn servo_gains(&self) -> [ServoGains; N] {
        self.gains
    }

    /// Physics time step, seconds.
    pub fn timestep(&self) -> f64 {
        self.model.timestep()
    }

    /// Start a simulation, at StandInit (teleported, at rest, servos holding it).
    pub fn sim(&self) -> Result<ArmSim<'_, N>> {
        let mut sim = ArmSim {
            arm: self,
            data: Data::new(&self.model)?,
            targets: [0.0; N],
        };
        let stand_init = self.robot.posture("StandInit");
        sim.set_posture(stand_init.expect("every shipped model has StandInit"))?;
        Ok(sim)
    }
}

fn check_range(
    name: &str,
    what: &'static str,
    found: Option<(f64, f64)>,
    expected: (f64, f64),
) -> Result<()> {
    let ok = matches!(found, Some((lo, hi)) if (lo - expected.0).abs() < 1e-9 && (hi - expected.1).abs() < 1e-9);
    if ok {
        Ok(())
    } else {
        Err(SimError::ModelMismatch {
            name: name.to_string(),
            what,
            found: match found {
                Some(r) => format!("[{}, {}]", r.0, r.1),
                None => "unlimited".to_string(),
            },
            expected: format!("[{}, {}]", expected.0, expected.1),
        })
    }
}

/// Identify kp and kv of each servo by probing: with the arm at rest at mid-range, a small
/// control offset gives `kp * offset`; with the target at the posture, a small joint velocity
/// gives `-kv * velocity`. Both probes stay far below the torque limits.
fn identify_gains<const N: usize>(
    robot: Robot,
    model: &Model,
    joints: &[JointIndex; N],
) -> Result<[ServoGains; N]> {
    const DQ: f64 = 1e-3;
    const DV: f64 = 1e-3;
    let mut data = Data::new(model)?;
    let mut mid = [0.0; N];
    for (m, s) in mid.iter_mut().zip(robot.joints()) {
        *m = 0.5 * (s.range.0 + s.range.1);
    }
    let mut gains = [ServoGains { kp: 0.0, kv: 0.0 }; N];
    for (k, ji) in joints.iter().enumerate() {
        for (i, j) in joints.iter().enumerate() {
            data.qpos_mut()[j.qpos] = mid[i];
            data.qvel_mut()[j.dof] = 0.0;
            data.ctrl_mut()[j.actuator] = mid[i];
        }
        data.ctrl_mut()[ji.actuator] = mid[k] + DQ;
        data.forward()?;
        let kp = data.actuator_force()[ji.actuator] / DQ;
        data.ctrl_mut()[ji.actuator] = mid[k];
        data.qvel_mut()[ji.dof] = DV;
        data.forward()?;
        let kv = -data.actuator_force()[ji.actuator] / DV;
        if !(kp.is_finite() && kp > 0.0 && kv.is_finite() && kv >= 0.0) {
            return Err(SimError::ModelMismatch {
                name: robot.joint_names()[k].to_string(),
                what: "actuator (expected a position servo, force = kp (ctrl - q) - kv qdot)",
                found: format!("kp = {kp}, kv = {kv}"),
                expected: "kp > 0, kv >= 0".to_string(),
            });
        }
        gains[k] = ServoGains { kp, kv };
    }
    Ok(gains)
}

/// One running simulation of the arm: owns MuJoCo's `Data`, borrows the [`NaoArm`].
///
/// Positions are in the torso frame (the model welds the torso to the world at the origin with
/// the world's axes), metres.
pub struct ArmSim<'a, const N: usize = NJ> {
    arm: &'a NaoArm<N>,
    data: Data<'a>,
    targets: [f64; N],
}

impl<'a, const N: usize> ArmSim<'a, N> {
    /// The arm this simulation runs.
    pub fn arm(&self) -> &'a NaoArm<N> {
        self.arm
    }

    /// MuJoCo's data (for rendering or inspection).
    pub fn data(&self) -> &Data<'a> {
        &self.data
    }

    /// Simulated time, seconds.
    pub fn time(&self) -> f64 {
        self.data.time()
    }

    /// Reset the simulation (time 0, MuJoCo's data cleared) and teleport to a posture (checked).
    pub fn reset_to(&mut self, posture: &[f64]) -> Result<()> {
        let p = check_posture_of(self.arm.robot, posture)?;
        self.data.reset();
        self.teleport(p)
    }

    /// Teleport to a posture (checked): joint positions set, velocities zeroed, servo targets set
    /// to the posture, kinematics recomputed. Time is not reset.
    pub fn set_posture(&mut self, posture: &[f64]) -> Result<()> {
        let p = check_posture_of(self.arm.robot, posture)?;
        self.teleport(p)
    }

    /// [`ArmSim::set_posture`], with out-of-range values clamped to the joint limits
    /// (wrong joint count and NaN are still errors).
    pub fn set_posture_clamped(&mut self, posture: &[f64]) -> Result<()> {
        let p = clamp_posture_of(self.arm.robot, posture)?;
        self.teleport(p)
    }

    /// Hold the joints at `posture` from outside (a hand on the arm): positions set,
    /// velocities zeroed; the servo targets are not touched (the servos keep pushing) and
    /// the next physics step moves the arm again.
    pub(crate) fn pin(&mut self, posture: &[f64; N]) {
        for (k, j) in self.arm.joints.iter().enumerate() {
            self.data.qpos_mut()[j.qpos] = posture[k];
            self.data.qvel_mut()[j.dof] = 0.0;
        }
    }

    /// A force from outside on the body `body` (MuJoCo's body id), newtons, world frame, at the
    /// body's centre of mass, acting from the next physics step until changed (`[0; 3]`: none).
    pub(crate) fn apply_force(&mut self, body: usize, force: [f64; 3]) {
        let f = self.data.xfrc_applied_mut();
        if let Some(slot) = f.get_mut(6 * body..6 * body + 3) {
            slot.copy_from_slice(&force);
        }
    }

    fn teleport(&mut self, p: [f64; N]) -> Result<()> {
        self.pin(&p);
        self.targets = p;
        self.write_ctrl(&p, &[0.0; N], false);
        self.data.forward()?;
        Ok(())
    }

    /// Joint positions (the encoders), [`JOINT_NAMES`] order.
    pub fn posture(&self) -> [f64; N] {
        let q = self.data.qpos();
        std::array::from_fn(|k| q[self.arm.joints[k].qpos])
    }

    /// Joint velocities, rad/s.
    pub fn velocities(&self) -> [f64; N] {
        let v = self.data.qvel();
        std::array::from_fn(|k| v[self.arm.joints[k].dof])
    }

    /// The current servo targets (last checked targets given).
    pub fn targets(&self) -> [f64; N] {
        self.targets
    }

    /// Position of the `l_wrist` site (LWristYaw joint origin), torso frame, m.
    pub fn wrist_position(&self) -> [f64; 3] {
        self.data.site_xpos(self.arm.wrist_site)
    }

    /// Position of the `l_gripper` site (hand point), torso frame, m.
    pub fn gripper_position(&self) -> [f64; 3] {
        self.data.site_xpos(self.arm.gripper_site)
    }

    /// Set the servo targets (checked); they hold until changed.
    pub fn set_targets(&mut self, targets: &[f64]) -> Result<()> {
        let p = check_posture_of(self.arm.robot, targets)?;
        self.command(&p, &[0.0; N], false);
        Ok(())
    }

    /// Set the servo targets (checked) and advance the physics by one time step.
    pub fn step_with_targets(&mut self, targets: &[f64]) -> Result<()> {
        self.set_targets(targets)?;
        self.step()
    }

    /// Recompute kinematics and forces for the current state without advancing time. After
    /// [`ArmSim::step`], site positions belong to the state before the step (MuJoCo's Euler
    /// step computes them, then integrates); call this to bring them up to date.
    pub fn forward(&mut self) -> Result<()> {
        self.data.forward()?;
        Ok(())
    }

    /// Advance the physics by one time step with the current servo commands.
    pub fn step(&mut self) -> Result<()> {
        self.data.step()?;
        Ok(())
    }

    /// Command a checked posture `q` with desired velocity `qd`: the servo target gets the
    /// velocity feed-forward `(kv / kp) qd` and, with `gravity_compensation`, the static
    /// feed-forward `bias / kp` (MuJoCo's gravity and Coriolis forces at the current state), so
    /// that the servo's force is `kp (q - q_now) + kv (qd - qd_now) + bias`. MuJoCo clips the
    /// command to the control range (the joint range) and the force to the torque limit.
    pub(crate) fn command(&mut self, q: &[f64; N], qd: &[f64; N], gravity_compensation: bool) {
        self.targets = *q;
        self.write_ctrl(q, qd, gravity_compensation);
    }

    fn write_ctrl(&mut self, q: &[f64; N], qd: &[f64; N], gravity_compensation: bool) {
        let mut ctrl = [0.0; N];
        for k in 0..N {
            let g = self.arm.gains[k];
            let j = self.arm.joints[k];
            let bias = if gravity_compensation {
                self.data.qfrc_bias()[j.dof]
            } else {
                0.0
            };
            ctrl[k] = q[k] + (g.kv * qd[k] + bias) / g.kp;
        }
        let c = self.data.ctrl_mut();
        for k in 0..N {
            c[self.arm.joints[k].actuator] = ctrl[k];
        }
    }
}
