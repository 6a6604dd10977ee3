//! A stepper on the simulated arm, in the loop: at the recording rate (40 Hz) the encoders are
//! read, the [`Stepper`] is given the reading and answers the next posture, and the servos are
//! sent toward it along a straight line over the tick (with its velocity as the feed-forward),
//! as a plan is followed ([`crate::sim::Controller::follow`]). Meanwhile the arm can be
//! disturbed ([`Disturbance`], in seconds): a hand holds it where it is, a force pushes one of
//! its links (MuJoCo's applied forces), or the goal moves.
//!
//! [`ArmLoop`] implements [`Plant`], so held-out studies of the loop
//! ([`crate::eval::in_loop`]) run every method's stepper on the arm as they do in the
//! kinematic loop.
//!
//! ```
//! use cosco_hsom::sim::in_loop::run_in_loop;
//! use cosco_hsom::sim::{ControllerConfig, NaoArm, NamedPosture};
//! use cosco_hsom::stepper::{ByClock, Disturbance};
//! let arm = NaoArm::load_default()?;
//! let start = NamedPosture::Stand.angles().to_vec();
//! let plan: Vec<Vec<f64>> = (0..41)
//!     .map(|k| start.iter().enumerate().map(|(j, v)| v + if j == 3 { -0.5 * k as f64 / 40.0 } else { 0.0 }).collect())
//!     .collect();
//! let columns = arm.robot().joint_names().iter().map(|n| n.to_string()).collect();
//! let mut stepper = ByClock::new(columns, plan, "the replay");
//! let held = [Disturbance::parse("hold", "0.25:0.25", cosco_hsom::stepper::Clock::Seconds)?];
//! let run = run_in_loop(&arm, &ControllerConfig::default(), &mut stepper, &start, &held, 10.0)?;
//! assert!(run.finished);
//! assert_eq!(run.recording.len(), 41); // a reading a tick, the initial one first
//! assert!(run.held[15] && !run.held[25]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use crate::stepper::{Amount, Clock, Disturbance, Kind, Plant, Stepper, StepperError, Trace};

use super::arm::{ArmSim, NaoArm};
use super::controller::ControllerConfig;
use super::recording::Recording;
use super::spec::clamp_posture_of;
use super::{Result, SimError};

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
    Still(&'d Disturbance),
    Push(&'d Disturbance, usize, [f64; 3]),
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
    disturbances: &[Disturbance],
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
    let columns: Vec<String> = robot.joint_names().iter().map(|n| n.to_string()).collect();
    let links: Vec<String> = (1..arm.model().nbody())
        .filter_map(|i| arm.model().body_name(i))
        .collect();
    for d in disturbances {
        let times_ok = d.at.is_finite() && d.at >= 0.0 && d.lasts.is_finite() && d.lasts >= 0.0;
        if d.clock != Clock::Seconds || !times_ok {
            return Err(SimError::Invalid(format!(
                "{}: its start and duration must be finite seconds >= 0",
                d.describe()
            )));
        }
        (d.check(&columns, None, Some(&links), f64::INFINITY)).map_err(SimError::Invalid)?;
        acting.push(match &d.kind {
            Kind::Push { body, force } => {
                let id = arm.model().body_id(body).unwrap_or_default();
                Acting::Push(d, id, *force)
            }
            Kind::Move(Amount::Diagonal(_)) | Kind::Goal(Amount::Diagonal(_)) => {
                return Err(SimError::Invalid(format!(
                    "{}: the simulated arm takes one value per joint, not a share of the diagonal",
                    d.describe()
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
        let pending = acting.iter().any(|a| a.disturbance().until() > t);
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
            if let (Kind::Goal(Amount::Absolute(goal)), false) = (&d.kind, goals_done[i]) {
                if d.at <= t + 1e-9 {
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

/// The largest force along `force` the servos hold the link `body` of `arm` against at
/// `posture`, N, and the joint that gives way first (`None`: no such link, no force, or no
/// servo carries it). Statics, gravity aside: a newton along the force at the link's centre
/// of mass makes about each servo's axis the torque `axis . (r x u)` (`r` from the joint's
/// anchor); the servo holds up to its torque limit (the model's `forcerange`).
pub fn resistible_force<const N: usize>(
    arm: &NaoArm<N>,
    posture: &[f64],
    body: &str,
    force: [f64; 3],
) -> Result<Option<(f64, String)>> {
    let model = arm.model();
    let norm = force.iter().map(|f| f * f).sum::<f64>().sqrt();
    let Some(b) = model.body_id(body).filter(|_| norm > 0.0) else {
        return Ok(None);
    };
    let mut sim = arm.sim()?;
    sim.reset_to(&clamp_posture_of::<N>(arm.robot(), posture)?)?;
    sim.forward()?;
    let data = sim.data();
    let p = data.body_xipos(b);
    let mut weakest: Option<(f64, String)> = None;
    for a in 0..model.nu() {
        let (Some(j), Some((lo, hi))) = (model.actuator_joint(a), model.actuator_force_range(a))
        else {
            continue;
        };
        let carries = std::iter::successors(Some(b), |&k| (k > 0).then(|| model.body_parent(k)))
            .any(|k| k == model.joint_body(j));
        let (o, axis) = (data.xanchor(j), data.xaxis(j));
        let r: [f64; 3] = std::array::from_fn(|k| p[k] - o[k]);
        let u: [f64; 3] = std::array::from_fn(|k| force[k] / norm);
        let per_newton = (axis[0] * (r[1] * u[2] - r[2] * u[1])
            + axis[1] * (r[2] * u[0] - r[0] * u[2])
            + axis[2] * (r[0] * u[1] - r[1] * u[0]))
            .abs();
        if !carries || per_newton < 1e-9 {
            continue;
        }
        let holds = lo.abs().min(hi.abs()) / per_newton;
        if weakest.as_ref().map_or(true, |(f, _)| holds < *f) {
            weakest = Some((holds, model.joint_name(j).unwrap_or_default()));
        }
    }
    Ok(weakest)
}

/// A stepper's refusal of a disturbance, as the simulator's error.
fn stepper_error(d: &Disturbance, e: StepperError) -> SimError {
    SimError::Invalid(format!("{}: {e}", d.describe()))
}

impl Acting<'_> {
    fn disturbance(&self) -> &Disturbance {
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
                    match &d.kind {
                        Kind::Move(Amount::Absolute(by)) => std::array::from_fn(|j| now[j] + by[j]),
                        _ => now,
                    }
                });
                sim.pin(&at);
            }
            Acting::Still(_) => {}
        }
    }
}

/// The simulated arm as a [`Plant`]: each run starts at the stepper's initial posture, a tick
/// is a sample at `config`'s rate, and a disturbance on the phase clock is placed on those
/// ticks (its start, at least the first tick, and its length, at least a tick for a move,
/// rounded to ticks of the duration).
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
        disturbances: &[Disturbance],
        duration: usize,
        limit: usize,
    ) -> std::result::Result<Trace, StepperError> {
        let rate = self.config.record_rate_hz;
        let ticks = |share: f64| (share * duration as f64).round();
        let seconds = |d: &Disturbance| match (d.clock, &d.kind) {
            (Clock::Seconds, _) => d.clone(),
            (Clock::Phase, kind) => {
                let (at, lasts) = match kind {
                    Kind::Goal(_) => (ticks(d.at) / rate, 0.0),
                    Kind::Move(_) => (
                        ticks(d.at).max(1.0) / rate,
                        (ticks(d.lasts) / rate).max(1.0 / rate),
                    ),
                    _ => (ticks(d.at).max(1.0) / rate, ticks(d.lasts) / rate),
                };
                let kind = kind.clone();
                Disturbance {
                    clock: Clock::Seconds,
                    at,
                    lasts,
                    kind,
                }
            }
        };
        let d: Vec<Disturbance> = disturbances.iter().map(seconds).collect();
        let limit_s = limit as f64 / rate;
        let r = run_in_loop(self.arm, &self.config, stepper, initial, &d, limit_s)
            .map_err(|e| StepperError::Plant(Box::new(e)))?;
        let time = &r.recording.time;
        Ok(Trace {
            acting: (d.iter())
                .map(|d| time.iter().map(|t| d.acts_at(*t)).collect())
                .collect(),
            release: r.held.iter().rposition(|h| *h).map(|k| k + 1),
            path: r.recording.qpos,
            commanded: r.recording.target,
            held: r.held,
            finished: r.finished,
        })
    }
}
