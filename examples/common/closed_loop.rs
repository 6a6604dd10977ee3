//! A hand grabs the arm during execution, held out ([`closed_loop_folds`]): each method
//! undisturbed, grabbed going on by its clock, grabbed then re-planned from the encoders'
//! reading, and re-planned at the same moment without the grab; with its figure.

use std::time::Instant;

use serde::Serialize;

use cosco_hsom::config::HsomConfig;
use cosco_hsom::demos::sample_period;
use cosco_hsom::demos::Demonstration;
use cosco_hsom::eval::{all_but, FoldScores, Swings, SWING_MIN_AMPLITUDE_RAD};
use cosco_hsom::gmr::MIN_DEMONSTRATIONS;
use cosco_hsom::metrics::{column_swings, MetricsParams};
use cosco_hsom::sim::{clamp_to_ranges, evaluate};
use cosco_hsom::sim::{NaoArm, Recording, Transition, JOINT_NAMES, SWING_JOINT};

use cosco_hsom::experiment::baseline::{gmr_params, plan as gmr_plan, DEFAULT_COMPONENTS};
use cosco_hsom::experiment::heldout::{check_demos, demo_trace, joint_trace};
use cosco_hsom::experiment::{execute_and_score, ExperimentError};
use cosco_hsom::sim::{Controller, ControllerConfig, Grab, TargetTrajectory};

/// The large swings of [`SWING_JOINT`] in an executed motion and in the held-out
/// demonstration it is scored against.
fn swings(executed: &Recording, held_out: &Demonstration) -> Result<Swings, ExperimentError> {
    let count = |rows| column_swings(rows, SWING_JOINT, SWING_MIN_AMPLITUDE_RAD);
    Ok(Swings {
        joint: JOINT_NAMES[SWING_JOINT].to_string(),
        min_amplitude_rad: SWING_MIN_AMPLITUDE_RAD,
        reproduction: count(&executed.qpos)?,
        demo: count(&held_out.rows)?,
    })
}

/// One method on one fold of [`closed_loop_folds`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClosedLoopFold {
    /// Its plan from the held-out demonstration's first posture, executed untouched.
    pub undisturbed: FoldScores,
    /// The same plan executed while the arm is grabbed, going on by its clock (no re-plan).
    pub by_clock: FoldScores,
    /// Executed while the arm is grabbed; on release the method continues from what the
    /// encoders read (its own execution and the grab). `None` for a method that cannot
    /// (GMM/GMR: a time-driven regression has no reading to continue from).
    pub replanned: Option<FoldScores>,
    /// Executed untouched, and at the moment the grab would have come the method continues
    /// from what the encoders read of its own execution: whether a re-plan alone, with no
    /// disturbance, keeps the gesture. `None` where `replanned` is.
    pub read_back: Option<FoldScores>,
    /// `(time s, value rad)` of [`SWING_JOINT`] in the run by the clock.
    pub by_clock_trace: Vec<(f64, f64)>,
    /// The same in the re-planned run.
    pub replanned_trace: Option<Vec<(f64, f64)>>,
}

/// [`closed_loop_folds`]: one [`ClosedLoopFold`] per demonstration for each method.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClosedLoop {
    /// CoSCo-HSOM: resumes its own plan with [`Hsom::resume`](cosco_hsom::hsom::Hsom::resume)
    /// (the reading aligned with the plan, the plan's events executed so far pushed up the
    /// lists, the levels plan the rest).
    pub hsom: Vec<ClosedLoopFold>,
    /// CoSCo-HSOM re-planning from the reading encoded again by its bottom, with
    /// [`Hsom::continue_events`](cosco_hsom::hsom::Hsom::continue_events) (as a prefix of a new
    /// demonstration is); its undisturbed and by-the-clock runs are `hsom`'s.
    pub hsom_reencoded: Vec<ClosedLoopFold>,
    /// The nearest-sequence baseline: re-aligns with
    /// [`Hsom::follow_nearest_from`](cosco_hsom::hsom::Hsom::follow_nearest_from).
    pub sequence: Vec<ClosedLoopFold>,
    /// GMM/GMR by its clock (no re-plan), or why the fold could not run it.
    pub gmr: Vec<Result<ClosedLoopFold, String>>,
    /// When the hand held the arm on each fold: (start, end), s from the start of the motion.
    pub grab_s: Vec<(f64, f64)>,
}

/// One fold of [`closed_loop_folds`]: where and how its methods are executed and scored.
struct GrabbedFold<'a> {
    arm: &'a NaoArm,
    held: &'a Demonstration,
    metrics: &'a MetricsParams,
    rate: f64,
    /// The tick the hand takes hold, and for how many.
    grab: (usize, usize),
    /// On what a method reads when it continues.
    noise: ReadingNoise,
    transition: Transition,
}

impl GrabbedFold<'_> {
    /// Scores of an executed run against the held-out demonstration alone.
    fn score(
        &self,
        rec: &Recording,
        clamped_values: usize,
        (train_s, reproduce_s): (f64, f64),
    ) -> Result<FoldScores, ExperimentError> {
        Ok(FoldScores {
            fidelity: evaluate(
                Some(self.arm),
                std::slice::from_ref(self.held),
                &rec.qpos,
                self.metrics,
            )?,
            swings: Some(swings(rec, self.held)?),
            postures: rec.len(),
            clamped_values,
            train_s,
            reproduce_s,
            start_end: None,
            commanded: None,
            conditions: None,
            coverage: None,
            out_of_range: None,
        })
    }

    /// A method's `plan` executed undisturbed, grabbed by its clock, and (with `replan`)
    /// grabbed then continued, and continued at the same moment without the grab.
    fn run(
        &self,
        plan: &[Vec<f64>],
        times: (f64, f64),
        replan: Option<&mut Replan<'_>>,
    ) -> Result<ClosedLoopFold, ExperimentError> {
        let (train_s, reproduce_s) = times;
        let test = std::slice::from_ref(self.held);
        let still = execute_and_score(self.arm, plan, self.transition, test, self.metrics)?;
        let undisturbed = FoldScores {
            fidelity: still.fidelity,
            swings: Some(swings(&still.trace, self.held)?),
            postures: plan.len(),
            clamped_values: still.clamped_values,
            train_s,
            reproduce_s,
            start_end: None,
            commanded: None,
            conditions: None,
            coverage: None,
            out_of_range: None,
        };
        let (rec, c) = self.execute(plan, self.grab.1, None)?;
        let fold = ClosedLoopFold {
            undisturbed,
            by_clock: self.score(&rec, c, times)?,
            replanned: None,
            read_back: None,
            by_clock_trace: joint_trace(&rec),
            replanned_trace: None,
        };
        match replan {
            Some(replan) => self.continued(fold, plan, times, replan),
            None => Ok(fold),
        }
    }

    /// `fold` (a method's runs without a re-plan) with `replan`'s: grabbed then continued, and
    /// continued at the same moment without the grab.
    fn continued(
        &self,
        mut fold: ClosedLoopFold,
        plan: &[Vec<f64>],
        (train_s, reproduce_s): (f64, f64),
        replan: &mut Replan<'_>,
    ) -> Result<ClosedLoopFold, ExperimentError> {
        for ticks in [self.grab.1, 0] {
            let t = Instant::now();
            let (rec, c) = self.execute(plan, ticks, Some(&mut *replan))?;
            let scores = self.score(&rec, c, (train_s, reproduce_s + t.elapsed().as_secs_f64()))?;
            if ticks > 0 {
                fold.replanned = Some(scores);
                fold.replanned_trace = Some(joint_trace(&rec));
            } else {
                fold.read_back = Some(scores);
            }
        }
        Ok(fold)
    }

    /// `plan` executed with a grab of `ticks` at this fold's moment ([`execute_grabbed`]).
    fn execute(
        &self,
        plan: &[Vec<f64>],
        ticks: usize,
        replan: Option<&mut Replan<'_>>,
    ) -> Result<(Recording, usize), ExperimentError> {
        execute_grabbed(
            self.arm,
            plan,
            self.transition,
            self.rate,
            (self.grab.0, ticks),
            replan.map(|r| (r, self.noise)),
        )
    }
}

/// The disturbance of [`closed_loop_folds`]: a hand holds the arm still for `ticks` ticks at
/// the share `at` of the held-out demonstration's duration; a method continuing afterwards
/// reads the encoders with Gaussian noise of `reading_noise` rad (drawn from `seed` and the
/// fold).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosedLoopGrab {
    /// When, as a share of the held-out demonstration, strictly between 0 and 1.
    pub at: f64,
    /// How long, ticks (at least 1).
    pub ticks: usize,
    /// Noise on the readings a method continues from, rad (>= 0).
    pub reading_noise: f64,
    /// Seed of that noise.
    pub seed: u64,
}

impl ClosedLoopGrab {
    /// Half-way, 1 s at 40 Hz, exact readings.
    #[allow(dead_code)] // tests/heldout.rs grabs with it; the example takes its flags
    pub const DEFAULT: ClosedLoopGrab = ClosedLoopGrab {
        at: 0.5,
        ticks: 40,
        reading_noise: 0.0,
        seed: 0,
    };

    /// Refuse a moment outside (0, 1), a grab of no tick and a noise that is not a finite
    /// number >= 0, naming the value and what is allowed.
    pub fn check(&self) -> Result<(), ExperimentError> {
        let at = self.at;
        if !(at > 0.0 && at < 1.0) {
            return Err(ExperimentError::Invalid(format!(
                "grab at {at} of the demonstration: needs a number strictly between 0 and 1"
            )));
        }
        if self.ticks == 0 {
            return Err(ExperimentError::Invalid(
                "a grab of 0 ticks: needs at least 1".into(),
            ));
        }
        ReadingNoise {
            std: self.reading_noise,
            seed: self.seed,
        }
        .check()
    }
}

/// A hand grabs the arm during execution, held out: on fold `i` each method learns from
/// every demonstration but `demos[i]` and plans from `demos[i]`'s first posture; the plan is
/// executed on the simulated arm and at `grab.at` of `demos[i]`'s duration (the same
/// moment for every method) a hand holds the arm still for `grab.ticks` ticks while the servo
/// targets go on ([`execute_grabbed`]). Each method is executed
/// undisturbed; grabbed, its plan going on by the clock; grabbed, then re-planned on release
/// from the encoders' reading of its own execution and the grab (the closed loop); and, as
/// that re-plan's control, re-planned at the same moment from the reading of its undisturbed
/// execution (no grab). CoSCo-HSOM resumes its plan with
/// [`Hsom::resume`](cosco_hsom::hsom::Hsom::resume) (and, measured beside it, re-plans from the
/// reading encoded again with [`Hsom::continue_events`](cosco_hsom::hsom::Hsom::continue_events)),
/// the nearest-sequence baseline re-aligns with
/// [`Hsom::follow_nearest_from`](cosco_hsom::hsom::Hsom::follow_nearest_from);
/// GMM/GMR is time-driven: by its clock only. Every executed motion, the grab included, is
/// scored against `demos[i]` alone.
pub fn closed_loop_folds(
    arm: &NaoArm,
    config: &HsomConfig,
    demos: &[Demonstration],
    grab: ClosedLoopGrab,
    transition: Transition,
) -> Result<ClosedLoop, ExperimentError> {
    check_demos(demos)?;
    grab.check()?;
    let needed = config.params().action_horizon() + 1;
    let mut out = ClosedLoop {
        hsom: Vec::new(),
        sequence: Vec::new(),
        hsom_reencoded: Vec::new(),
        gmr: Vec::new(),
        grab_s: Vec::new(),
    };
    for i in 0..demos.len() {
        let train = all_but(demos, i);
        let held = &demos[i];
        let metrics = MetricsParams {
            sample_period: sample_period(held),
            ..MetricsParams::default()
        };
        let initial = held
            .rows
            .first()
            .ok_or_else(|| ExperimentError::Invalid(format!("{}: no samples", held.source)))?;
        let rate = 1.0 / metrics.sample_period;
        let at = ((held.rows.len() as f64 * grab.at).round() as usize).max(needed);
        out.grab_s
            .push((at as f64 / rate, (at + grab.ticks) as f64 / rate));
        let fold = GrabbedFold {
            arm,
            held,
            metrics: &metrics,
            rate,
            grab: (at, grab.ticks),
            noise: ReadingNoise {
                std: grab.reading_noise,
                seed: grab.seed.wrapping_add(i as u64),
            },
            transition,
        };
        let method = |plan: &[Vec<f64>], train_s, reproduce_s, replan: Option<&mut Replan<'_>>| {
            fold.run(plan, (train_s, reproduce_s), replan)
        };
        let t = Instant::now();
        let model = config.fit(&train)?;
        let train_s = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let plan = model.reproduce(initial)?.postures;
        let reproduce_s = t.elapsed().as_secs_f64();
        let mut replan = |read: &[Vec<f64>]| Ok(model.resume(initial, read)?.postures);
        let hsom = method(&plan, train_s, reproduce_s, Some(&mut replan))?;
        // the same plan: its undisturbed and by-the-clock runs are the ones above
        let mut replan = |read: &[Vec<f64>]| Ok(model.continue_events(read)?.postures);
        let without = ClosedLoopFold {
            replanned: None,
            read_back: None,
            replanned_trace: None,
            ..hsom.clone()
        };
        out.hsom_reencoded.push(fold.continued(
            without,
            &plan,
            (train_s, reproduce_s),
            &mut replan,
        )?);
        out.hsom.push(hsom);
        let t = Instant::now();
        let plan = model.follow_nearest(&train, initial)?.postures;
        let reproduce_s = t.elapsed().as_secs_f64();
        let mut replan = |read: &[Vec<f64>]| Ok(model.follow_nearest_from(&train, read)?.postures);
        out.sequence
            .push(method(&plan, train_s, reproduce_s, Some(&mut replan))?);
        if train.len() < MIN_DEMONSTRATIONS {
            out.gmr.push(Err(format!(
                "fold {}: GMM/GMR needs at least {MIN_DEMONSTRATIONS} demonstrations to learn \
                 from, this fold has {}",
                i + 1,
                train.len()
            )));
            continue;
        }
        let gmr = (|| {
            let params = gmr_params(DEFAULT_COMPONENTS, metrics.sample_period)?;
            let t = Instant::now();
            let (model, _, _) = params.fit_with_details(&train)?;
            let train_s = t.elapsed().as_secs_f64();
            let t = Instant::now();
            let plan = gmr_plan(&model, initial, rate)?;
            Ok::<_, ExperimentError>((plan, train_s, t.elapsed().as_secs_f64()))
        })();
        out.gmr.push(match gmr {
            Ok((plan, train_s, reproduce_s)) => {
                Ok(method(&plan.postures, train_s, reproduce_s, None)?)
            }
            Err(e) => Err(format!("fold {}: {e}", i + 1)),
        });
    }
    Ok(out)
}

/// One panel per fold of [`closed_loop_folds`] (`c`, on `demos`): [`SWING_JOINT`] against
/// time in the held-out demonstration (grey), the hierarchy resumed after the grab (black),
/// the nearest sequence re-aligned, GMM/GMR and the hierarchy's plan by their clocks, the
/// grab shaded; each panel's title has the runs' joint DTW. Written atomically to `path`.
pub fn closed_loop_png(
    path: &std::path::Path,
    title: &str,
    demos: &[Demonstration],
    c: &ClosedLoop,
) -> Result<(), cosco_hsom::plot::PlotError> {
    use cosco_hsom::plot::{Band, Panel, Series, BLACK, PALETTE};
    use plotters::style::RGBColor;
    let joint = JOINT_NAMES[SWING_JOINT];
    let cost = |f: Option<&FoldScores>| {
        f.map_or("-".to_string(), |f| {
            format!("{:.3}", f.fidelity.joint_dtw_rad_per_step.mean)
        })
    };
    // the legend once, in the first panel
    let line = |i: usize, label: &str, color: RGBColor, width: u32, points: &[(f64, f64)]| {
        let mut s = Series::new(label, color, points.to_vec());
        s.width = width;
        s.label = s.label.filter(|_| i == 0);
        s
    };
    let n = c
        .hsom
        .len()
        .min(c.sequence.len())
        .min(demos.len())
        .min(c.grab_s.len());
    let panels: Vec<Panel> = (0..n)
        .map(|i| {
            let (h, s) = (&c.hsom[i], &c.sequence[i]);
            let g = c.gmr.get(i).and_then(|g| g.as_ref().ok());
            let mut p = Panel::new(
                format!(
                    "demonstration {} held out: DTW resumed {}, re-aligned {}, GMM/GMR {}",
                    i + 1,
                    cost(h.replanned.as_ref()),
                    cost(s.replanned.as_ref()),
                    cost(g.map(|g| &g.by_clock)),
                ),
                "time (s)",
                format!("{joint} (rad)"),
            );
            let demo = demo_trace(&demos[i]);
            let (lo, hi) = demo
                .iter()
                .chain(&h.by_clock_trace)
                .chain(h.replanned_trace.iter().flatten())
                .chain(s.replanned_trace.iter().flatten())
                .chain(g.iter().flat_map(|g| &g.by_clock_trace))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                    (a.min(p.1), b.max(p.1))
                });
            let (t0, t1) = c.grab_s[i];
            p.bands.push(Band {
                label: Some("a hand holds the arm (the executed runs)".to_string())
                    .filter(|_| i == 0),
                color: RGBColor(190, 190, 190),
                points: vec![(t0, lo, hi), (t1, lo, hi)],
            });
            let held = "the held-out demonstration";
            p.series
                .push(line(i, held, RGBColor(160, 160, 160), 5, &demo));
            if let Some(g) = g {
                p.series.push(line(
                    i,
                    "GMM/GMR by its clock",
                    PALETTE[3],
                    1,
                    &g.by_clock_trace,
                ));
            }
            p.series.push(line(
                i,
                "hierarchy by its clock",
                PALETTE[4],
                1,
                &h.by_clock_trace,
            ));
            if let Some(t) = &s.replanned_trace {
                p.series
                    .push(line(i, "nearest sequence re-aligned", PALETTE[1], 2, t));
            }
            if let Some(t) = &h.replanned_trace {
                p.series.push(line(i, "hierarchy resumed", BLACK, 2, t));
            }
            p
        })
        .collect();
    cosco_hsom::plot::panels_png(path, title, &panels, 2, (760, 420))
}

/// A method's continuation after a grab: given what the encoders read so far (one row per
/// tick, ending at the release), the postures to go on with, the first being the last read.
pub type Replan<'a> = dyn FnMut(&[Vec<f64>]) -> Result<Vec<Vec<f64>>, ExperimentError> + 'a;

/// Gaussian noise on what a method reads of the encoders when it continues after a grab
/// (rad; not on the recording that is scored), drawn from `seed`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ReadingNoise {
    /// Standard deviation, rad (0: exact readings).
    pub std: f64,
    /// Seed of the noise stream (ChaCha8).
    pub seed: u64,
}

impl ReadingNoise {
    /// Refuse a standard deviation that is not a finite number >= 0, naming it.
    pub fn check(&self) -> Result<(), ExperimentError> {
        if self.std.is_finite() && self.std >= 0.0 {
            Ok(())
        } else {
            Err(ExperimentError::Invalid(format!(
                "reading noise {}: needs a finite standard deviation >= 0 (rad)",
                self.std
            )))
        }
    }

    /// `rows` as read with this noise ([`ReadingNoise::check`]ed).
    pub fn apply(&self, rows: &[Vec<f64>]) -> Result<Vec<Vec<f64>>, ExperimentError> {
        use rand::SeedableRng;
        use rand_distr::Distribution;
        self.check()?;
        if self.std == 0.0 {
            return Ok(rows.to_vec());
        }
        let normal = rand_distr::Normal::new(0.0, self.std)
            .map_err(|e| ExperimentError::Invalid(format!("reading noise {}: {e}", self.std)))?;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(self.seed);
        Ok(rows
            .iter()
            .map(|r| r.iter().map(|v| v + normal.sample(&mut rng)).collect())
            .collect())
    }
}

/// Execute `postures` (one per tick of `rate_hz`, the first the initial posture; clamped into
/// the joint ranges and shaped by `transition`) on the simulated arm while a hand grabs it
/// at tick `from` and holds it still for `ticks` ticks ([`Controller::follow_grabbed`](cosco_hsom::sim::Controller::follow_grabbed); the
/// servo targets go on meanwhile). Without `replan` the plan simply goes on by its clock: on
/// release the servos pull the arm to wherever the plan has got to. With `replan` the plan
/// stops at the release and the method is given what the encoders read so far (with the
/// reading `noise`); its postures (clamped and shaped likewise) are executed from where the
/// arm is. Returns the recording of the whole motion and the number of posture values
/// clamped.
pub fn execute_grabbed(
    arm: &NaoArm,
    postures: &[Vec<f64>],
    transition: Transition,
    rate_hz: f64,
    (from, ticks): (usize, usize),
    replan: Option<(&mut Replan<'_>, ReadingNoise)>,
) -> Result<(Recording, usize), ExperimentError> {
    let (postures, mut clamped) = clamp_to_ranges(postures)?;
    let mut postures = transition.shape(&postures);
    let Some(first) = postures.first().cloned() else {
        return Err(ExperimentError::Invalid("no postures to execute".into()));
    };
    let controller = Controller::new(ControllerConfig {
        record_rate_hz: rate_hz,
        ..ControllerConfig::default()
    })?;
    let grab = Grab {
        start_s: from as f64 / rate_hz,
        seconds: ticks as f64 / rate_hz,
    };
    let release = from + ticks;
    if release == 0 && replan.is_some() {
        return Err(ExperimentError::Invalid(
            "a re-plan after a grab needs at least one tick read before it (grab of 0 ticks \
             at tick 0)"
                .into(),
        ));
    }
    // the plan holds its last posture until the release at least
    if let Some(last) = postures.last().cloned() {
        postures.resize(postures.len().max(release + 1), last);
    }
    let mut sim = arm.sim()?;
    sim.set_posture(&first)?;
    let Some((replan, noise)) = replan else {
        let trajectory = TargetTrajectory::at_rate(rate_hz, &postures)?;
        return Ok((
            controller.follow_grabbed(&mut sim, &trajectory, grab)?,
            clamped,
        ));
    };
    let trajectory = TargetTrajectory::at_rate(rate_hz, &postures[..release])?;
    let mut recording = controller.follow_grabbed(&mut sim, &trajectory, grab)?;
    let next = replan(&noise.apply(&recording.qpos)?)?;
    let (next, c) = clamp_to_ranges(&next)?;
    clamped += c;
    let targets: Vec<Vec<f64>> = std::iter::once(sim.posture().to_vec())
        .chain(transition.shape(&next).into_iter().skip(1))
        .collect();
    let trajectory = TargetTrajectory::at_rate(rate_hz, &targets)?;
    recording.append(controller.follow(&mut sim, &trajectory)?)?;
    Ok((recording, clamped))
}
