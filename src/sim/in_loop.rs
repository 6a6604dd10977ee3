//! A stepper on the simulated arm, in the loop: at the recording rate (40 Hz) the encoders are
//! read, the [`Stepper`] is given the reading and answers the next posture, and the servos are
//! sent toward it along a straight line over the tick (with its velocity as the feed-forward),
//! as a plan is followed ([`crate::sim::Controller::follow`]). Meanwhile the arm can be
//! disturbed ([`ArmDisturbance`]): a hand holds it where it is, a force pushes one of its
//! links (MuJoCo's applied forces), or the goal moves.
//!
//! [`ArmLoop`] implements [`Plant`], so held-out studies of the loop
//! ([`crate::eval::in_loop`]) run every method's stepper on the arm as they do in the
//! kinematic loop.
//!
//! ```
//! use cosco_hsom::sim::in_loop::{run_in_loop, ArmDisturbance};
//! use cosco_hsom::sim::{ControllerConfig, NaoArm, NamedPosture};
//! use cosco_hsom::stepper::ByClock;
//! let arm = NaoArm::load_default()?;
//! let start = NamedPosture::Stand.angles().to_vec();
//! let plan: Vec<Vec<f64>> = (0..41)
//!     .map(|k| start.iter().enumerate().map(|(j, v)| v + if j == 3 { -0.5 * k as f64 / 40.0 } else { 0.0 }).collect())
//!     .collect();
//! let columns = arm.robot().joint_names().iter().map(|n| n.to_string()).collect();
//! let mut stepper = ByClock::new(columns, plan, "the replay");
//! let held = [ArmDisturbance::Hold { at_s: 0.25, seconds: 0.25 }];
//! let run = run_in_loop(&arm, &ControllerConfig::default(), &mut stepper, &start, &held, 10.0)?;
//! assert!(run.finished);
//! assert_eq!(run.recording.len(), 41); // a reading a tick, the initial one first
//! assert!(run.held[15] && !run.held[25]);
//! # Ok::<(), cosco_hsom::sim::SimError>(())
//! ```

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use crate::stepper::kinematic::{Disturbance, Trace};
use crate::stepper::{Plant, Stepper, StepperError};

use super::arm::{ArmSim, NaoArm};
use super::controller::ControllerConfig;
use super::recording::Recording;
use super::spec::clamp_posture_of;
use super::{Result, SimError};

/// What happens to the arm while a stepper drives it, in seconds from the start.
#[derive(Debug, Clone, PartialEq)]
pub enum ArmDisturbance {
    /// From `at_s`, for `seconds`, a hand holds every joint where it was when grabbed (the
    /// servos keep pushing; the encoders read the held posture).
    Hold {
        /// When the hand takes hold, s.
        at_s: f64,
        /// How long it holds, s.
        seconds: f64,
    },
    /// From `at_s`, for `seconds`, the hand holds the arm displaced by `by` (rad per joint)
    /// from where it was.
    Move {
        /// When, s.
        at_s: f64,
        /// The displacement, one value per joint.
        by: Vec<f64>,
        /// How long it is held there, s (at least a physics step).
        seconds: f64,
    },
    /// From `at_s`, for `seconds`, the force `force` (N, world frame = the torso's) pushes
    /// the body `body` (a link of the model: `LForeArm`, `LBicep`, ...) at its centre of mass.
    Push {
        /// When, s.
        at_s: f64,
        /// The link pushed (MuJoCo's body name).
        body: String,
        /// The force, N.
        force: [f64; 3],
        /// How long, s.
        seconds: f64,
    },
    /// At `at_s` the stepper's goal moves to `goal` ([`Stepper::set_goal`]).
    Goal {
        /// When, s.
        at_s: f64,
        /// The new goal, one value per joint.
        goal: Vec<f64>,
    },
}

/// `T` of a flag's value: seconds, finite and >= 0.
fn seconds(what: &str, text: &str) -> std::result::Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!("{what} `{text}` is not a time: need seconds >= 0")),
    }
}

/// Comma-separated finite numbers.
fn numbers(what: &str, text: &str) -> std::result::Result<Vec<f64>, String> {
    (text.split(','))
        .map(|v| match v.trim().parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(format!("{what}: `{v}` is not a finite number")),
        })
        .collect()
}

impl ArmDisturbance {
    /// `T:SECONDS`: a hand holds the arm at `T` s for `SECONDS`.
    pub fn parse_hold(s: &str) -> std::result::Result<ArmDisturbance, String> {
        match s.split(':').collect::<Vec<_>>()[..] {
            [t, d] => Ok(ArmDisturbance::Hold {
                at_s: seconds("the hold's start", t)?,
                seconds: seconds("the hold's duration", d)?,
            }),
            _ => Err(format!("hold `{s}`: expected T:SECONDS (e.g. 1.0:0.5)")),
        }
    }

    /// `T:BODY:FX,FY,FZ:SECONDS`: a force (N, torso frame) on the link `BODY` at `T` s for
    /// `SECONDS`.
    pub fn parse_push(s: &str) -> std::result::Result<ArmDisturbance, String> {
        let usage = || {
            format!("push `{s}`: expected T:BODY:FX,FY,FZ:SECONDS (e.g. 1.0:LForeArm:0,0,-8:0.3)")
        };
        match s.split(':').collect::<Vec<_>>()[..] {
            [t, body, f, d] if !body.trim().is_empty() => {
                let force = numbers("the push's force", f)?;
                let force: [f64; 3] = force.try_into().map_err(|_| usage())?;
                Ok(ArmDisturbance::Push {
                    at_s: seconds("the push's start", t)?,
                    body: body.trim().to_string(),
                    force,
                    seconds: seconds("the push's duration", d)?,
                })
            }
            _ => Err(usage()),
        }
    }

    /// `T:V1,...`: the goal moves to the posture `V1,...` at `T` s.
    pub fn parse_goal(s: &str) -> std::result::Result<ArmDisturbance, String> {
        match s.split_once(':') {
            Some((t, v)) => Ok(ArmDisturbance::Goal {
                at_s: seconds("the goal's time", t)?,
                goal: numbers("the goal", v)?,
            }),
            None => Err(format!(
                "goal `{s}`: expected T:V1,V2,... (one value per joint)"
            )),
        }
    }

    /// When it starts, s.
    pub fn at_s(&self) -> f64 {
        match self {
            ArmDisturbance::Hold { at_s, .. }
            | ArmDisturbance::Move { at_s, .. }
            | ArmDisturbance::Push { at_s, .. }
            | ArmDisturbance::Goal { at_s, .. } => *at_s,
        }
    }

    /// When it ends, s (a goal's move: when it is made).
    pub fn until_s(&self) -> f64 {
        match self {
            ArmDisturbance::Hold { at_s, seconds }
            | ArmDisturbance::Move { at_s, seconds, .. }
            | ArmDisturbance::Push { at_s, seconds, .. } => at_s + seconds,
            ArmDisturbance::Goal { at_s, .. } => *at_s,
        }
    }

    /// Whether it has the arm (holds, moves or pushes it) at `t` s.
    pub fn acts_at(&self, t: f64) -> bool {
        !matches!(self, ArmDisturbance::Goal { .. }) && t >= self.at_s() && t < self.until_s()
    }

    /// One line for people: `held at 1.00 s for 0.50 s`, `LForeArm pushed with (0, 0, -8) N
    /// at 1.00 s for 0.30 s`, `goal moved at 1.50 s`.
    pub fn describe(&self) -> String {
        match self {
            ArmDisturbance::Hold { at_s, seconds } => {
                format!("held at {at_s:.2} s for {seconds:.2} s")
            }
            ArmDisturbance::Move { at_s, seconds, .. } => {
                format!("moved at {at_s:.2} s and held for {seconds:.2} s")
            }
            ArmDisturbance::Push {
                at_s,
                body,
                force,
                seconds,
            } => format!(
                "{body} pushed with ({}, {}, {}) N at {at_s:.2} s for {seconds:.2} s",
                force[0], force[1], force[2]
            ),
            ArmDisturbance::Goal { at_s, .. } => format!("goal moved at {at_s:.2} s"),
        }
    }
}

/// A stepper's run on the simulated arm.
#[derive(Debug, Clone, PartialEq)]
pub struct ArmRun {
    /// A sample a tick (at `k / rate`): what the encoders read (`qpos`, what the stepper was
    /// given), the posture commanded at that tick (`target`; the last reading's: the last
    /// command), the hand's sites.
    pub recording: Recording,
    /// Per sample: whether a hold, a move or a push had the arm.
    pub held: Vec<bool>,
    /// Whether the stepper said it was done (and the arm was free) before the time limit.
    pub finished: bool,
    /// Values commanded outside the joint ranges, clamped to the nearest limit.
    pub clamped_values: usize,
}

/// A disturbance checked against the arm: a pushed link's body id, widths.
enum Acting<'d> {
    Still(&'d ArmDisturbance),
    Push(&'d ArmDisturbance, usize, [f64; 3]),
}

/// `stepper` (made from `initial`) drives a simulation of `arm` from `initial` until it is done
/// and the arm is free, or for `limit_s` seconds (`finished` false): each tick (`config`'s
/// recording rate) the encoders are read (with `config`'s noise), and the servos are sent from
/// the last command toward the stepper's next one over the tick, with `config`'s gravity
/// compensation, while `disturbances` act. Commands outside the joint ranges are clamped
/// (counted).
pub fn run_in_loop<const N: usize>(
    arm: &NaoArm<N>,
    config: &ControllerConfig,
    stepper: &mut dyn Stepper,
    initial: &[f64],
    disturbances: &[ArmDisturbance],
    limit_s: f64,
) -> Result<ArmRun> {
    let robot = arm.robot();
    if stepper.width() != N {
        return Err(SimError::Invalid(format!(
            "the stepper's postures have {} values; the {} has {N} joints",
            stepper.width(),
            robot.name()
        )));
    }
    let rate = config.record_rate_hz;
    if !(rate.is_finite() && rate > 0.0 && rate <= 10_000.0) {
        return Err(SimError::InvalidParameter {
            name: "record_rate_hz",
            value: rate,
            reason: "expected a rate in (0, 10000] Hz",
        });
    }
    if !(limit_s.is_finite() && (0.0..=3600.0).contains(&limit_s)) {
        return Err(SimError::InvalidParameter {
            name: "the loop's time limit",
            value: limit_s,
            reason: "0 to 3600 s",
        });
    }
    let noise =
        Normal::new(0.0, config.encoder_noise_std).map_err(|_| SimError::InvalidParameter {
            name: "encoder_noise_std",
            value: config.encoder_noise_std,
            reason: "expected a finite number >= 0",
        })?;
    let mut acting = Vec::with_capacity(disturbances.len());
    for d in disturbances {
        let times_ok = d.at_s().is_finite() && d.at_s() >= 0.0 && d.until_s().is_finite();
        if !times_ok || d.until_s() < d.at_s() {
            return Err(SimError::Invalid(format!(
                "{}: its start and duration must be finite seconds >= 0",
                d.describe()
            )));
        }
        acting.push(match d {
            ArmDisturbance::Push { body, force, .. } => {
                let Some(id) = arm.model().body_id(body).filter(|&id| id > 0) else {
                    let links: Vec<String> = (1..arm.model().nbody())
                        .filter_map(|i| arm.model().body_name(i))
                        .collect();
                    return Err(SimError::Invalid(format!(
                        "a push on `{body}`: the {} has no such link; allowed {}",
                        robot.name(),
                        links.join(", ")
                    )));
                };
                if force.iter().any(|v| !v.is_finite()) {
                    return Err(SimError::Invalid(format!(
                        "{}: the force must be finite",
                        d.describe()
                    )));
                }
                Acting::Push(d, id, *force)
            }
            ArmDisturbance::Move { by, .. } | ArmDisturbance::Goal { goal: by, .. }
                if by.len() != N =>
            {
                return Err(SimError::Invalid(format!(
                    "{}: {} values given; the {} has {N} joints ({})",
                    d.describe(),
                    by.len(),
                    robot.name(),
                    robot.joint_names().join(", ")
                )));
            }
            _ => Acting::Still(d),
        });
    }
    let mut sim = arm.sim()?;
    sim.reset_to(&clamp_posture_of::<N>(robot, initial)?)?;
    let mut rng = ChaCha8Rng::seed_from_u64(config.seed);
    let dt = arm.timestep();
    let period = 1.0 / rate;
    let max_ticks = (limit_s * rate).floor() as usize;
    let mut run = ArmRun {
        recording: Recording::new(rate, robot),
        held: Vec::new(),
        finished: false,
        clamped_values: 0,
    };
    let mut last: [f64; N] = sim.posture();
    let mut goals_done = vec![false; disturbances.len()];
    // where a hand holds the arm, per disturbance, once it has taken hold
    let mut grips: Vec<Option<[f64; N]>> = vec![None; disturbances.len()];
    let mut n = 0usize;
    for k in 0..=max_ticks {
        let t = k as f64 * period;
        hand(&mut sim, &acting, &mut grips, t);
        sim.forward()?;
        let exact = sim.posture();
        let reading: Vec<f64> = exact
            .iter()
            .map(|q| match config.encoder_noise_std > 0.0 {
                true => q + noise.sample(&mut rng),
                false => *q,
            })
            .collect();
        let held = acting.iter().any(|a| a.disturbance().acts_at(t));
        run.recording.time.push(t);
        run.recording.qpos.push(reading.clone());
        run.recording.wrist.push(sim.wrist_position());
        run.recording.gripper.push(sim.gripper_position());
        run.held.push(held);
        let pending = acting.iter().any(|a| a.disturbance().until_s() > t);
        if stepper.done() && !held && !pending {
            run.recording.target.push(last.to_vec());
            run.finished = true;
            break;
        }
        if k == max_ticks {
            run.recording.target.push(last.to_vec());
            break;
        }
        for (i, d) in disturbances.iter().enumerate() {
            if let (ArmDisturbance::Goal { at_s, goal }, false) = (d, goals_done[i]) {
                if *at_s <= t + 1e-9 {
                    stepper.set_goal(goal).map_err(|e| stepper_error(d, e))?;
                    goals_done[i] = true;
                }
            }
        }
        let replans = stepper.replans();
        let asked = stepper
            .step(&reading)
            .map_err(|e| SimError::Invalid(format!("the stepper at {t:.3} s: {e}")))?;
        // a re-plan starts from the posture read: the servos go from there, at its speed
        let from: [f64; N] = match stepper.replans() > replans {
            true => clamp_posture_of(robot, &reading)?,
            false => last,
        };
        let next: [f64; N] = clamp_posture_of(robot, &asked)?;
        run.clamped_values += (asked.iter().zip(&next))
            .filter(|(a, b)| **a != **b)
            .count();
        run.recording.target.push(next.to_vec());
        let velocity: [f64; N] = std::array::from_fn(|j| (next[j] - from[j]) / period);
        while (n as f64) * dt < t + period - 1e-9 {
            let ts = n as f64 * dt;
            hand(&mut sim, &acting, &mut grips, ts);
            let u = ((ts - t) / period).clamp(0.0, 1.0);
            let q: [f64; N] = std::array::from_fn(|j| from[j] + u * (next[j] - from[j]));
            sim.command(&q, &velocity, config.gravity_compensation);
            sim.step()?;
            n += 1;
        }
        last = next;
    }
    Ok(run)
}

/// A stepper's refusal of a disturbance, as the simulator's error.
fn stepper_error(d: &ArmDisturbance, e: StepperError) -> SimError {
    SimError::Invalid(format!("{}: {e}", d.describe()))
}

impl Acting<'_> {
    fn disturbance(&self) -> &ArmDisturbance {
        match self {
            Acting::Still(d) | Acting::Push(d, ..) => d,
        }
    }
}

/// Before a physics step at `t`: every hold and move pins the arm where its hand has it;
/// every push sets its link's force (none outside its interval).
fn hand<const N: usize>(
    sim: &mut ArmSim<'_, N>,
    acting: &[Acting<'_>],
    grips: &mut [Option<[f64; N]>],
    t: f64,
) {
    for (a, grip) in acting.iter().zip(grips.iter_mut()) {
        match a {
            Acting::Push(d, body, force) => {
                let f = if d.acts_at(t) { *force } else { [0.0; 3] };
                sim.apply_force(*body, f);
            }
            Acting::Still(d) if d.acts_at(t) => {
                let at = *grip.get_or_insert_with(|| {
                    let now = sim.posture();
                    match d {
                        ArmDisturbance::Move { by, .. } => std::array::from_fn(|j| now[j] + by[j]),
                        _ => now,
                    }
                });
                sim.pin(&at);
            }
            Acting::Still(_) => {}
        }
    }
}

/// The simulated arm as a [`Plant`] for held-out studies of the loop: each run starts at the
/// stepper's initial posture, a tick is a sample at `config`'s rate, and a disturbance's
/// phases are shares of the duration given in ticks. A push on `body` given by the study
/// acts as its force for its share of the duration.
pub struct ArmLoop<'a, const N: usize> {
    /// The arm.
    pub arm: &'a NaoArm<N>,
    /// The controller's settings (rate, encoder noise, gravity compensation).
    pub config: ControllerConfig,
}

impl<const N: usize> Plant for ArmLoop<'_, N> {
    fn run(
        &self,
        stepper: &mut dyn Stepper,
        initial: &[f64],
        disturbance: &Disturbance,
        duration: usize,
        limit: usize,
    ) -> std::result::Result<Trace, StepperError> {
        let rate = self.config.record_rate_hz;
        let secs = |share: f64| (share * duration as f64).round() / rate;
        let at = |phase: f64| (phase * duration as f64).round().max(1.0) / rate;
        let d = match disturbance {
            Disturbance::None => None,
            Disturbance::Hold { at: p, share } => Some(ArmDisturbance::Hold {
                at_s: at(*p),
                seconds: secs(*share),
            }),
            Disturbance::Move { at: p, by, share } => Some(ArmDisturbance::Move {
                at_s: at(*p),
                by: by.clone(),
                seconds: secs(*share).max(1.0 / rate),
            }),
            Disturbance::Push {
                at: p,
                body,
                force,
                share,
            } => Some(ArmDisturbance::Push {
                at_s: at(*p),
                body: body.clone(),
                force: *force,
                seconds: secs(*share),
            }),
            Disturbance::Goal { at: p, goal } => Some(ArmDisturbance::Goal {
                at_s: (p * duration as f64).round() / rate,
                goal: goal.clone(),
            }),
        };
        let limit_s = limit as f64 / rate;
        let r = run_in_loop(
            self.arm,
            &self.config,
            stepper,
            initial,
            d.as_slice(),
            limit_s,
        )
        .map_err(|e| StepperError::method("the simulated arm", e))?;
        let release = match &d {
            Some(d) if !matches!(d, ArmDisturbance::Goal { .. }) => {
                r.held.iter().rposition(|h| *h).map(|k| k + 1)
            }
            _ => None,
        };
        Ok(Trace {
            path: r.recording.qpos,
            commanded: r.recording.target,
            held: r.held,
            release,
            finished: r.finished,
        })
    }
}
