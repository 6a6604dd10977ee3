//! The position controller: key-pose sequences and dense target trajectories, executed on
//! [`ArmSim`] at the physics rate and recorded at a fixed rate (40 Hz by default).

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use super::arm::ArmSim;
use super::error::{Result, SimError};
use super::interp::Interpolation;
use super::recording::{Recording, Touches};
use super::spec::{check_posture, check_posture_of, clamp_posture, Posture, JOINT_SPECS, NJ};
use crate::robot::Robot;

/// The paper's recording rate, Hz.
pub const DEFAULT_RECORD_RATE_HZ: f64 = 40.0;

/// The longest motion one controller call simulates, s.
pub const MAX_DURATION_S: f64 = 3600.0;
/// A contact seen again within this long of its last sighting is the same contact, s.
const TOUCH_GAP_S: f64 = 0.05;
/// The most physics steps one controller call runs (a bound no input can exceed).
pub const MAX_STEPS_PER_CALL: u64 = 100_000_000;

/// A key pose of a motion: where to go, at least how long the transition takes, how long to
/// stay there afterwards.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KeyPose {
    posture: Posture,
    min_duration: f64,
    hold: f64,
}

impl KeyPose {
    /// A key pose (checked): six finite values within the joint ranges; no minimum duration,
    /// no hold.
    pub fn new(posture: &[f64]) -> Result<KeyPose> {
        Ok(KeyPose {
            posture: check_posture(posture)?,
            min_duration: 0.0,
            hold: 0.0,
        })
    }

    /// [`KeyPose::new`] with out-of-range values clamped to the joint limits.
    pub fn new_clamped(posture: &[f64]) -> Result<KeyPose> {
        Ok(KeyPose {
            posture: clamp_posture(posture)?,
            min_duration: 0.0,
            hold: 0.0,
        })
    }

    /// The transition to this pose lasts at least `seconds` (finite, >= 0); it lasts longer when
    /// the velocity limits need it.
    pub fn with_min_duration(mut self, seconds: f64) -> Result<KeyPose> {
        self.min_duration = non_negative("min_duration", seconds)?;
        Ok(self)
    }

    /// Stay at this pose for `seconds` (finite, >= 0) after reaching it.
    pub fn with_hold(mut self, seconds: f64) -> Result<KeyPose> {
        self.hold = non_negative("hold", seconds)?;
        Ok(self)
    }

    /// The target posture.
    pub fn posture(&self) -> Posture {
        self.posture
    }

    /// Minimum transition duration, s.
    pub fn min_duration(&self) -> f64 {
        self.min_duration
    }

    /// Hold time, s.
    pub fn hold(&self) -> f64 {
        self.hold
    }
}

fn non_negative(name: &'static str, v: f64) -> Result<f64> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(SimError::InvalidParameter {
            name,
            value: v,
            reason: "expected a finite number >= 0",
        })
    }
}

/// A dense target trajectory: postures at strictly increasing times (s, relative to the start),
/// followed piecewise-linearly (with the segment's slope as velocity feed-forward) and held at
/// the last target until `duration`.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetTrajectory<const N: usize = NJ> {
    robot: Robot,
    times: Vec<f64>,
    targets: Vec<[f64; N]>,
    duration: f64,
}

impl TargetTrajectory {
    /// Targets of the left arm at given times ([`TargetTrajectory::new_for`]).
    pub fn new(times: &[f64], targets: &[Vec<f64>]) -> Result<TargetTrajectory> {
        Self::new_for(Robot::LeftArm, times, targets)
    }

    /// One left-arm target per tick of a clock at `rate_hz` ([`TargetTrajectory::at_rate_for`]).
    pub fn at_rate(rate_hz: f64, targets: &[Vec<f64>]) -> Result<TargetTrajectory> {
        Self::at_rate_for(Robot::LeftArm, rate_hz, targets)
    }
}

impl<const N: usize> TargetTrajectory<N> {
    /// Targets of `robot` at given times (checked: same lengths, at least one target, times
    /// finite, first time >= 0, strictly increasing; every target a valid posture). The motion
    /// lasts until the last time.
    pub fn new_for(robot: Robot, times: &[f64], targets: &[Vec<f64>]) -> Result<Self> {
        if times.len() != targets.len() {
            return Err(SimError::InvalidTrajectory(format!(
                "{} times for {} targets",
                times.len(),
                targets.len()
            )));
        }
        if targets.is_empty() {
            return Err(SimError::InvalidTrajectory("no targets".into()));
        }
        for (i, &t) in times.iter().enumerate() {
            let bad = !t.is_finite() || t < 0.0 || (i > 0 && t <= times[i - 1]);
            if bad {
                return Err(SimError::InvalidTrajectory(format!(
                    "time {i} = {t}: times must be finite, >= 0 and strictly increasing"
                )));
            }
        }
        let targets = targets
            .iter()
            .map(|t| check_posture_of(robot, t))
            .collect::<Result<Vec<_>>>()?;
        Ok(TargetTrajectory {
            robot,
            duration: *times.last().unwrap_or(&0.0),
            times: times.to_vec(),
            targets,
        })
    }

    /// One target per tick of a clock at `rate_hz` (target k at time k / rate_hz); the motion
    /// lasts `targets.len() / rate_hz`, so recording at the same rate yields one sample per target.
    pub fn at_rate_for(robot: Robot, rate_hz: f64, targets: &[Vec<f64>]) -> Result<Self> {
        check_rate("rate_hz", rate_hz)?;
        let times: Vec<f64> = (0..targets.len()).map(|k| k as f64 / rate_hz).collect();
        let mut t = Self::new_for(robot, &times, targets)?;
        t.duration = targets.len() as f64 / rate_hz;
        Ok(t)
    }

    /// Hold the last target for `seconds` more (finite, >= 0).
    pub fn with_hold(mut self, seconds: f64) -> Result<Self> {
        self.duration += non_negative("hold", seconds)?;
        Ok(self)
    }

    /// Peak velocity of the piecewise-linear targets of each joint as a fraction of the joint's
    /// maximum velocity ([`JOINT_NAMES`](super::JOINT_NAMES) order). Values above 1 mean the
    /// servos cannot follow exactly (the controller still runs; the torque limits decide).
    pub fn peak_velocity_fractions(&self) -> [f64; N] {
        let mut peak = [0.0f64; N];
        let joints = self.robot.joints();
        for (w, t) in self.targets.windows(2).zip(self.times.windows(2)) {
            for k in 0..N {
                let v = (w[1][k] - w[0][k]).abs() / (t[1] - t[0]) / joints[k].max_velocity;
                peak[k] = peak[k].max(v);
            }
        }
        peak
    }

    /// Total duration, s.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Number of targets.
    pub fn len(&self) -> usize {
        self.targets.len()
    }

    /// Always false (a trajectory has at least one target).
    pub fn is_empty(&self) -> bool {
        self.targets.is_empty()
    }

    /// Target posture and velocity at time `t` (before the first time: the first target).
    fn sample(&self, t: f64) -> ([f64; N], [f64; N]) {
        let n = self.times.len();
        if t <= self.times[0] {
            return (self.targets[0], [0.0; N]);
        }
        if t >= self.times[n - 1] {
            return (self.targets[n - 1], [0.0; N]);
        }
        let i = self.times.partition_point(|&x| x <= t) - 1;
        let (t0, t1) = (self.times[i], self.times[i + 1]);
        let (a, b) = (&self.targets[i], &self.targets[i + 1]);
        let u = (t - t0) / (t1 - t0);
        (
            std::array::from_fn(|k| a[k] + u * (b[k] - a[k])),
            std::array::from_fn(|k| (b[k] - a[k]) / (t1 - t0)),
        )
    }
}

fn check_rate(name: &'static str, rate: f64) -> Result<f64> {
    if rate.is_finite() && rate > 0.0 && rate <= 10_000.0 {
        Ok(rate)
    } else {
        Err(SimError::InvalidParameter {
            name,
            value: rate,
            reason: "expected a rate in (0, 10000] Hz",
        })
    }
}

/// Controller settings; check them with [`Controller::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ControllerConfig {
    /// Transition profile between key poses (default minimum jerk).
    pub interpolation: Interpolation,
    /// Fraction of each joint's maximum velocity a transition may reach, in (0, 1] (default 0.5).
    pub speed_fraction: f64,
    /// Recording rate, Hz (default 40, the paper's).
    pub record_rate_hz: f64,
    /// Standard deviation of the Gaussian noise added to recorded encoder values, rad
    /// (default 0: exact encoders). Targets and hand positions are recorded without noise.
    pub encoder_noise_std: f64,
    /// Seed of the noise stream (ChaCha8).
    pub seed: u64,
    /// Add MuJoCo's gravity/Coriolis forces as a feed-forward to the servo targets (default
    /// true): the arm holds postures without the static sag `tau_gravity / kp`.
    pub gravity_compensation: bool,
}

impl Default for ControllerConfig {
    fn default() -> Self {
        ControllerConfig {
            interpolation: Interpolation::MinimumJerk,
            speed_fraction: 0.5,
            record_rate_hz: DEFAULT_RECORD_RATE_HZ,
            encoder_noise_std: 0.0,
            seed: 0,
            gravity_compensation: true,
        }
    }
}

/// A checked position controller.
///
/// ```
/// use cosco_hsom::sim::{Controller, ControllerConfig, KeyPose, NaoArm, NamedPosture};
/// let arm = NaoArm::load_default()?;
/// let mut sim = arm.sim()?; // at StandInit
/// let ctl = Controller::new(ControllerConfig::default())?;
/// let poses = [KeyPose::new(&NamedPosture::Stand.angles())?.with_hold(0.5)?];
/// let rec = ctl.execute(&mut sim, &poses)?;
/// assert_eq!(rec.joint_names[0], "LShoulderPitch");
/// assert!(rec.len() > 20); // 40 samples per second
/// # Ok::<(), cosco_hsom::sim::SimError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Controller {
    config: ControllerConfig,
}

/// An external hand holding the arm still during a motion ([`Controller::follow_grabbed`]):
/// from `start_s` (s from the motion's start) for `seconds`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grab {
    /// When the hand takes hold, s from the start of the motion (>= 0).
    pub start_s: f64,
    /// How long it holds, s (>= 0; 0: no grab).
    pub seconds: f64,
}

/// No hand on the arm.
fn no_hand<const N: usize>(_: f64, _: &mut ArmSim<'_, N>) {}

struct Segment {
    start: Posture,
    end: Posture,
    t0: f64,
    duration: f64,
}

impl Controller {
    /// Check the settings: speed fraction in (0, 1], rate in (0, 10000] Hz, noise finite >= 0.
    pub fn new(config: ControllerConfig) -> Result<Controller> {
        let f = config.speed_fraction;
        if !(f.is_finite() && f > 0.0 && f <= 1.0) {
            return Err(SimError::InvalidParameter {
                name: "speed_fraction",
                value: f,
                reason: "expected a fraction of the maximum velocity in (0, 1]",
            });
        }
        check_rate("record_rate_hz", config.record_rate_hz)?;
        non_negative("encoder_noise_std", config.encoder_noise_std)?;
        Ok(Controller { config })
    }

    /// The checked settings.
    pub fn config(&self) -> &ControllerConfig {
        &self.config
    }

    /// Duration of a transition from `from` to `to`: the shortest time in which no joint
    /// exceeds `speed_fraction` of its maximum velocity under the chosen profile, at least
    /// `min_duration`.
    pub fn transition_duration(&self, from: &Posture, to: &Posture, min_duration: f64) -> f64 {
        let peak = self.config.interpolation.peak_velocity_factor();
        let t = (0..NJ)
            .map(|k| {
                (to[k] - from[k]).abs() * peak
                    / (self.config.speed_fraction * JOINT_SPECS[k].max_velocity)
            })
            .fold(0.0, f64::max);
        t.max(min_duration)
    }

    /// Execute key poses from the current posture: one smooth transition per pose (timed by
    /// [`Controller::transition_duration`]), then its hold. Servo commands are updated at every
    /// physics step; the recording starts at time 0 (the initial state) and has one sample per
    /// tick `k / record_rate_hz` before the end of the motion.
    pub fn execute(&self, sim: &mut ArmSim<'_>, poses: &[KeyPose]) -> Result<Recording> {
        let mut segments = Vec::with_capacity(2 * poses.len());
        let mut from = sim.targets();
        let mut t = 0.0;
        for pose in poses {
            let d = self.transition_duration(&from, &pose.posture, pose.min_duration);
            segments.push(Segment {
                start: from,
                end: pose.posture,
                t0: t,
                duration: d,
            });
            t += d;
            if pose.hold > 0.0 {
                segments.push(Segment {
                    start: pose.posture,
                    end: pose.posture,
                    t0: t,
                    duration: pose.hold,
                });
                t += pose.hold;
            }
            from = pose.posture;
        }
        let interp = self.config.interpolation;
        let start = sim.targets();
        self.run(sim, t, no_hand, |time| {
            let i = segments.partition_point(|s| s.t0 <= time);
            let Some(s) = i.checked_sub(1).map(|i| &segments[i]) else {
                return (start, [0.0; NJ]);
            };
            if s.duration <= 0.0 || time >= s.t0 + s.duration {
                return (s.end, [0.0; NJ]);
            }
            let (p, dp) = interp.profile((time - s.t0) / s.duration);
            (
                std::array::from_fn(|k| s.start[k] + p * (s.end[k] - s.start[k])),
                std::array::from_fn(|k| dp * (s.end[k] - s.start[k]) / s.duration),
            )
        })
    }

    /// Hold the current targets for `seconds`, recording.
    pub fn hold(&self, sim: &mut ArmSim<'_>, seconds: f64) -> Result<Recording> {
        let pose = KeyPose::new(&sim.targets())?.with_hold(seconds)?;
        self.execute(sim, &[pose])
    }

    /// Follow a dense target trajectory (e.g. a demonstration replayed, or a learner's
    /// predicted postures) from time 0 to its duration. The speed fraction is not applied: the
    /// servos follow as fast as their torque limits allow. Start from the trajectory's first
    /// posture (e.g. with [`ArmSim::set_posture`] or [`Controller::execute`]) to avoid a jump.
    pub fn follow<const N: usize>(
        &self,
        sim: &mut ArmSim<'_, N>,
        trajectory: &TargetTrajectory<N>,
    ) -> Result<Recording> {
        self.run(sim, trajectory.duration, no_hand, |t| trajectory.sample(t))
    }

    /// [`Controller::follow`] while an external hand grabs the arm ([`Grab`]): from
    /// `grab.start_s`, for `grab.seconds`, every joint stays where it was when grabbed
    /// (position pinned, velocity zero, at every physics step) while the servo targets go on
    /// along the trajectory; then the hand lets go and the servos pull the arm on. The
    /// encoders read the held posture meanwhile. A grab outside the motion does nothing.
    pub fn follow_grabbed<const N: usize>(
        &self,
        sim: &mut ArmSim<'_, N>,
        trajectory: &TargetTrajectory<N>,
        grab: Grab,
    ) -> Result<Recording> {
        non_negative("grab start", grab.start_s)?;
        non_negative("grab duration", grab.seconds)?;
        let mut held: Option<[f64; N]> = None;
        let hand = |t: f64, sim: &mut ArmSim<'_, N>| {
            if t >= grab.start_s && t < grab.start_s + grab.seconds {
                let p = *held.get_or_insert_with(|| sim.posture());
                sim.pin(&p);
            }
        };
        self.run(sim, trajectory.duration, hand, |t| trajectory.sample(t))
    }

    /// Run the servos along `desired` for `duration`, recording; `hand(t, sim)` acts on the
    /// arm from outside before each physics step at time `t` ([`no_hand`]: nothing).
    fn run<const N: usize>(
        &self,
        sim: &mut ArmSim<'_, N>,
        duration: f64,
        mut hand: impl FnMut(f64, &mut ArmSim<'_, N>),
        desired: impl Fn(f64) -> ([f64; N], [f64; N]),
    ) -> Result<Recording> {
        let dt = sim.arm().timestep();
        let rate = self.config.record_rate_hz;
        let gc = self.config.gravity_compensation;
        let mut rng = ChaCha8Rng::seed_from_u64(self.config.seed);
        let noise = Normal::new(0.0, self.config.encoder_noise_std).map_err(|_| {
            SimError::InvalidParameter {
                name: "encoder_noise_std",
                value: self.config.encoder_noise_std,
                reason: "expected a finite number >= 0",
            }
        })?;
        // a hard bound on the work of one call, whatever the model or the trajectory says
        if !(duration.is_finite() && (0.0..=MAX_DURATION_S).contains(&duration)) {
            return Err(SimError::InvalidParameter {
                name: "duration",
                value: duration,
                reason: "a motion of 0 to 3600 s can be simulated in one call",
            });
        }
        if !(dt.is_finite() && dt > 0.0 && duration / dt <= MAX_STEPS_PER_CALL as f64) {
            return Err(SimError::InvalidParameter {
                name: "timestep",
                value: dt,
                reason: "a positive time step with at most 1e8 physics steps per call",
            });
        }
        let n_samples = ((duration * rate) - 1e-9).ceil().max(0.0) as usize;
        let n_steps = ((duration / dt) - 1e-9).ceil().max(0.0) as usize;
        let mut rec = Recording::new(rate, sim.arm().robot());
        rec.time.reserve(n_samples);

        // After mj_step (Euler), MuJoCo's positions-dependent quantities (site positions) belong
        // to the state *before* the integration: the encoders read before a step and the sites
        // read after it form a consistent state. A final forward() completes the last one.
        sim.forward()?;
        let mut prev: State<N> = (sim.posture(), sim.wrist_position(), sim.gripper_position());
        let mut t_prev = 0.0;
        let mut push = |rec: &mut Recording, k: usize, a: &State<N>, b: &State<N>, alpha: f64| {
            let tk = k as f64 / rate;
            let lerp = |x: f64, y: f64| x + alpha * (y - x);
            rec.time.push(tk);
            rec.qpos.push(
                (0..N)
                    .map(|j| {
                        let e = if self.config.encoder_noise_std > 0.0 {
                            noise.sample(&mut rng)
                        } else {
                            0.0
                        };
                        lerp(a.0[j], b.0[j]) + e
                    })
                    .collect(),
            );
            rec.target.push(desired(tk).0.to_vec());
            rec.wrist
                .push(std::array::from_fn(|i| lerp(a.1[i], b.1[i])));
            rec.gripper
                .push(std::array::from_fn(|i| lerp(a.2[i], b.2[i])));
        };
        let mut next = 0usize;
        let mut record_until = |rec: &mut Recording,
                                next: &mut usize,
                                prev: &State<N>,
                                now: &State<N>,
                                t_prev: f64,
                                t_now: f64| {
            while *next < n_samples && (*next as f64 / rate) <= t_now + 1e-12 {
                let alpha = if t_now > t_prev {
                    ((*next as f64 / rate) - t_prev) / (t_now - t_prev)
                } else {
                    1.0
                };
                push(rec, *next, prev, now, alpha.clamp(0.0, 1.0));
                *next += 1;
            }
        };
        record_until(&mut rec, &mut next, &prev, &prev, 0.0, 0.0);
        let mut touches = Touches::default();
        for n in 0..n_steps {
            let t = n as f64 * dt;
            hand(t, sim);
            let (q, qd) = desired(t);
            sim.command(&q, &qd, gc);
            let q_before = sim.posture();
            sim.step()?;
            // the contacts MuJoCo found for the state at time t
            touches.see(t, TOUCH_GAP_S, &sim.data().contacts());
            // consistent state at time t (n > 0; at n = 0 it is `prev` again)
            if n > 0 {
                let now: State<N> = (q_before, sim.wrist_position(), sim.gripper_position());
                record_until(&mut rec, &mut next, &prev, &now, t_prev, t);
                prev = now;
                t_prev = t;
            }
        }
        sim.forward()?;
        let t_end = n_steps as f64 * dt;
        let now: State<N> = (sim.posture(), sim.wrist_position(), sim.gripper_position());
        record_until(&mut rec, &mut next, &prev, &now, t_prev, t_end);
        // leave the servos at the final target, at rest
        let (q, _) = desired(duration);
        sim.command(&q, &[0.0; N], gc);
        rec.contacts = touches.into_vec();
        Ok(rec)
    }
}

type State<const N: usize> = ([f64; N], [f64; 3], [f64; 3]);
