//! `simulate --loop closed`: the learned gesture reproduced in the loop on the simulated arm.
//! Each method's stepper ([`Learned`]: the hierarchy, the DMP on the observed state, GMM/GMR by
//! its clock) drives the arm at 40 Hz from what its encoders read
//! ([`crate::sim::in_loop::run_in_loop`]), from the first demonstration's initial posture,
//! undisturbed and then while a hand holds the arm, a force pushes a link or the goal moves
//! ([`ArmDisturbance`]). Per method: finished or not, the re-plans, the final error, the largest
//! step after the release against the demonstrations' largest, the DTW without the disturbed
//! ticks (disturbed and undisturbed) and the swings. Written into the job's directory:
//! `in_loop.csv` (the hierarchy's run), `in_loop.png` and the report's section; the clip films
//! the hierarchy's disturbed run, the disturbance captioned and a pushed link marked.

use std::path::Path;

use serde::Serialize;

use crate::condition::Conditions;
use crate::demos::{sample_period, Demonstration};
use crate::dtw::{dtw_distance, euclidean, Band as DtwBand};
use crate::eval::{Learned, Method, GMR_COMPONENTS};
use crate::hsom::Hsom;
use crate::metrics::{column_swings, diagonal};
use crate::plot::{demo_color, panels_png, Band, Panel, Series, BLACK};
use crate::robot::Robot;
use crate::sim::in_loop::{run_in_loop, ArmDisturbance, ArmRun};
use crate::sim::{ControllerConfig, NaoArm};
use crate::stepper::kinematic::{free_rows, largest_step};
use crate::table::Table;

use super::ExperimentError;

/// How `simulate` reproduces: `open` (the plan made from the initial posture, then tracked)
/// or `closed` (a stepper in the loop, from the encoders).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum LoopMode {
    /// Plan, then track (the paper's experiment as the main job runs it).
    #[default]
    Open,
    /// A stepper in the loop.
    Closed,
}

/// The methods run in the loop, in the report's order: the hierarchy, its closed-loop peer,
/// and the open-loop control.
const METHODS: [Method; 3] = [Method::Hierarchy, Method::Dmp, Method::GmmGmr];

/// One method's runs in the loop.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LoopMethod {
    /// The method.
    pub method: String,
    /// Whether the reading changes what it commands.
    pub closed_loop: bool,
    /// Why it did not run (it cannot be fitted, or cannot take a disturbance).
    pub error: Option<String>,
    /// Whether it said it was done, the arm free, before the time limit.
    pub finished: bool,
    /// Its re-plans in the disturbed run.
    pub replans: usize,
    /// The disturbed run's duration, s.
    pub seconds: f64,
    /// The disturbed run's end from where it should end (the undisturbed run's end; with a
    /// moved goal, the goal), a share of the demonstrations' diagonal.
    pub final_error: f64,
    /// The largest step after the last release (or the goal's move) over the demonstrations'
    /// largest step (above 2: a jump).
    pub jump: f64,
    /// DTW per step of the disturbed run without its disturbed ticks against the
    /// demonstrations (mean), a share of the diagonal.
    pub relative_dtw: f64,
    /// The same of the undisturbed run.
    pub undisturbed_dtw: f64,
    /// LElbowRoll's swings over the whole run, the disturbed ticks included (the left arm):
    /// disturbed, undisturbed.
    pub swings: Option<[usize; 2]>,
    /// Per disturbance, how far it took the arm from where the undisturbed run had it (rad, the
    /// largest over the joints and the ticks it acted; 0 for a goal's move).
    pub displaced: Vec<f64>,
}

/// The report's section of the loop.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LoopSection {
    /// The disturbances, described.
    pub disturbances: Vec<String>,
    /// Per method, its runs.
    pub methods: Vec<LoopMethod>,
}

/// The hierarchy's disturbed run, to film and draw.
pub struct HierarchyLoop {
    /// The run.
    pub run: ArmRun,
    /// Its undisturbed run.
    pub undisturbed: ArmRun,
    /// The disturbances it ran with.
    pub disturbances: Vec<ArmDisturbance>,
}

/// How far `d` took the arm of `run` from where the undisturbed run `plain` had it: the
/// largest distance over the joints and the ticks it acted.
fn displaced(run: &ArmRun, plain: &[Vec<f64>], d: &ArmDisturbance) -> f64 {
    (run.recording
        .time
        .iter()
        .zip(&run.recording.qpos)
        .zip(plain))
    .filter(|((t, _), _)| d.acts_at(**t))
    .flat_map(|((_, a), b)| a.iter().zip(b).map(|(x, y)| (x - y).abs()))
    .fold(0.0, f64::max)
}

/// Every method of [`METHODS`] in the loop on `arm`, learned from `demos` (the hierarchy is
/// `model`), undisturbed and with `disturbances`; `in_loop.csv` and `in_loop.png` written into
/// `out` (listed in `files`). The section and the hierarchy's run.
pub fn closed_loop<const N: usize>(
    arm: &NaoArm<N>,
    model: &Hsom,
    demos: &[Demonstration],
    disturbances: &[ArmDisturbance],
    out: &Path,
    files: &mut Vec<String>,
) -> Result<(LoopSection, HierarchyLoop), ExperimentError> {
    let first = demos
        .first()
        .ok_or_else(|| ExperimentError::Invalid("no demonstrations to run in the loop".into()))?;
    let initial = first.rows.first().cloned().unwrap_or_default();
    let period = sample_period(first);
    let config = ControllerConfig {
        record_rate_hz: 1.0 / period,
        ..ControllerConfig::default()
    };
    let diag = diagonal(demos).max(f64::MIN_POSITIVE);
    let demo_step = (demos.iter().map(|d| largest_step(&d.rows, 1))).fold(0.0, f64::max);
    let longest = demos.iter().map(|d| d.rows.len()).max().unwrap_or(1) as f64 * period;
    let limit_s = (4.0 * longest + 10.0).min(3600.0);
    let goal = disturbances.iter().rev().find_map(|d| match d {
        ArmDisturbance::Goal { goal, at_s } => Some((goal.clone(), *at_s)),
        _ => None,
    });
    let swing_joint = (arm.robot() == Robot::LeftArm).then(|| arm.robot().swing_joint().0);
    let swings = |rows: &[Vec<f64>]| {
        swing_joint.and_then(|j| column_swings(rows, j, crate::eval::SWING_MIN_AMPLITUDE_RAD).ok())
    };
    let dtw = |rows: &[Vec<f64>]| -> f64 {
        let costs: Vec<f64> = (demos.iter())
            .filter_map(|d| dtw_distance(rows, &d.rows, DtwBand::None).ok())
            .map(|c| c.per_step() / diag)
            .collect();
        costs.iter().sum::<f64>() / costs.len().max(1) as f64
    };
    let mut methods = Vec::new();
    let mut hierarchy = None;
    let shared = std::sync::Arc::new(model.clone());
    for method in METHODS {
        let runs = (|| -> Result<(ArmRun, ArmRun, bool, usize), String> {
            let hsom = &mut |_| Ok((shared.clone(), 0.0));
            let (learned, _) = Learned::fit(method, demos, period, GMR_COMPONENTS, hsom)?;
            let none = Conditions::default();
            let make = || learned.stepper(method, demos, &initial, &none, period);
            let mut plain = make()?;
            let undisturbed = run_in_loop(arm, &config, plain.as_mut(), &initial, &[], limit_s)
                .map_err(|e| e.to_string())?;
            let mut s = make()?;
            let closed = s.closed_loop();
            let disturbed = run_in_loop(arm, &config, s.as_mut(), &initial, disturbances, limit_s)
                .map_err(|e| e.to_string())?;
            Ok((undisturbed, disturbed, closed, s.replans()))
        })();
        let (undisturbed, disturbed, closed, replans) = match runs {
            Ok(r) => r,
            Err(e) => {
                methods.push(LoopMethod::failed(method, e));
                continue;
            }
        };
        let rows = &disturbed.recording.qpos;
        let should_end = match &goal {
            Some((g, _)) => g.clone(),
            None => undisturbed
                .recording
                .qpos
                .last()
                .cloned()
                .unwrap_or_default(),
        };
        let release = disturbed.held.iter().rposition(|h| *h).map_or(1, |k| k + 1);
        let moved = goal
            .as_ref()
            .map_or(1, |(_, at)| (at / period).round() as usize + 1);
        let (free_rows, plain_rows) = (
            free_rows(&disturbed.recording.qpos, &disturbed.held),
            &undisturbed.recording.qpos,
        );
        methods.push(LoopMethod {
            method: method.name().to_string(),
            closed_loop: closed,
            error: None,
            finished: disturbed.finished,
            replans,
            seconds: disturbed.recording.time.last().copied().unwrap_or(0.0),
            final_error: rows
                .last()
                .map_or(f64::NAN, |e| euclidean(e, &should_end) / diag),
            jump: largest_step(rows, release.max(moved)) / demo_step.max(f64::MIN_POSITIVE),
            relative_dtw: dtw(&free_rows),
            undisturbed_dtw: dtw(plain_rows),
            swings: swings(rows).zip(swings(plain_rows)).map(|(a, b)| [a, b]),
            displaced: (disturbances.iter())
                .map(|d| displaced(&disturbed, plain_rows, d))
                .collect(),
        });
        if method == Method::Hierarchy {
            hierarchy = Some(HierarchyLoop {
                run: disturbed,
                undisturbed,
                disturbances: disturbances.to_vec(),
            });
        }
    }
    let hierarchy = hierarchy.ok_or_else(|| {
        let why = methods
            .first()
            .and_then(|m| m.error.clone())
            .unwrap_or_default();
        ExperimentError::Invalid(format!("the hierarchy could not run in the loop: {why}"))
    })?;
    write_loop_csv(&out.join("in_loop.csv"), arm.robot(), &hierarchy)?;
    files.push("in_loop.csv".into());
    let section = LoopSection {
        disturbances: disturbances.iter().map(ArmDisturbance::describe).collect(),
        methods,
    };
    Ok((section, hierarchy))
}

impl LoopMethod {
    fn failed(method: Method, why: String) -> LoopMethod {
        LoopMethod {
            method: method.name().to_string(),
            closed_loop: false,
            error: Some(why),
            finished: false,
            replans: 0,
            seconds: f64::NAN,
            final_error: f64::NAN,
            jump: f64::NAN,
            relative_dtw: f64::NAN,
            undisturbed_dtw: f64::NAN,
            swings: None,
            displaced: Vec::new(),
        }
    }
}

/// `in_loop.csv`: per tick, `time`, `disturbed` (1 while a hold, move or push has the arm),
/// what each joint's encoder read (the joint's name) and what was commanded (`<joint>_command`).
fn write_loop_csv(path: &Path, robot: Robot, h: &HierarchyLoop) -> Result<(), ExperimentError> {
    let names = robot.joint_names();
    let mut w = csv::Writer::from_writer(Vec::new());
    let header = ["time", "disturbed"].into_iter().map(String::from);
    let header = header
        .chain(names.iter().map(|n| n.to_string()))
        .chain(names.iter().map(|n| format!("{n}_command")));
    let werr = |e: csv::Error| ExperimentError::Invalid(format!("writing {}: {e}", path.display()));
    w.write_record(header.collect::<Vec<_>>()).map_err(werr)?;
    let rec = &h.run.recording;
    for k in 0..rec.len() {
        let row = [
            format!("{:.3}", rec.time[k]),
            u8::from(h.run.held[k]).to_string(),
        ];
        let row = row
            .into_iter()
            .chain(rec.qpos[k].iter().map(|v| format!("{v:.6}")));
        let row = row.chain(rec.target[k].iter().map(|v| format!("{v:.6}")));
        w.write_record(row.collect::<Vec<_>>()).map_err(werr)?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| ExperimentError::Invalid(format!("writing {}: {e}", path.display())))?;
    crate::fsutil::write_atomic(path, &bytes).map_err(ExperimentError::io("writing", path))
}

/// The section in Markdown.
pub fn loop_markdown(s: &LoopSection) -> String {
    let mut out = String::from(
        "## In the loop (`--loop closed`)\n\nEach method's stepper drives the simulated arm at \
         40 Hz from what its encoders read, from the first demonstration's initial posture, \
         undisturbed and then disturbed: ",
    );
    match s.disturbances.is_empty() {
        true => out.push_str("no disturbance was given (`--hold`, `--push`, `--goal-at`).\n\n"),
        false => out.push_str(&format!("{}.\n\n", s.disturbances.join("; "))),
    }
    let mut t = Table::new([
        "method",
        "loop",
        "finished",
        "re-plans",
        "final error (share of the diagonal)",
        "largest step after the release / the demonstrations'",
        "relative DTW disturbed (without the disturbed ticks)",
        "relative DTW undisturbed",
        "swings disturbed / undisturbed",
        "displaced from the undisturbed run (rad)",
    ]);
    for m in s.methods.iter().filter(|m| m.error.is_none()) {
        t.row([
            m.method.clone(),
            (if m.closed_loop {
                "closed"
            } else {
                "open (by its clock)"
            })
            .to_string(),
            (if m.finished { "yes" } else { "no" }).to_string(),
            m.replans.to_string(),
            format!("{:.4}", m.final_error),
            format!("{:.2}", m.jump),
            format!("{:.4}", m.relative_dtw),
            format!("{:.4}", m.undisturbed_dtw),
            m.swings.map_or("n/a".into(), |[a, b]| format!("{a} / {b}")),
            match m.displaced.is_empty() {
                true => "n/a".into(),
                false => (m.displaced.iter().map(|d| format!("{d:.3}")))
                    .collect::<Vec<_>>()
                    .join(", "),
            },
        ]);
    }
    out.push_str(&format!("{t}\n"));
    for m in s
        .methods
        .iter()
        .filter_map(|m| Some((&m.method, m.error.as_ref()?)))
    {
        out.push_str(&format!("- {} did not run: {}\n", m.0, m.1));
    }
    out.push_str(
        "\nA step after the release above 2 x the demonstrations' largest is a jump. \
         `in_loop.csv` holds the hierarchy's run (readings, commands, the disturbed ticks); \
         `in_loop.png` draws it.\n\n",
    );
    out
}

/// `in_loop.png`: per joint of `panels`, the demonstrations, the hierarchy's undisturbed and
/// disturbed runs, and the disturbances' intervals shaded.
pub fn loop_png(
    path: &Path,
    panels: &[(usize, &str)],
    demos: &[Demonstration],
    h: &HierarchyLoop,
) -> Result<(), ExperimentError> {
    let rec = &h.run.recording;
    let out: Vec<Panel> = (panels.iter().enumerate())
        .map(|(i, &(k, name))| {
            let mut p = Panel::new(name, "time (s)", crate::robot::axis_label(name));
            let first = i == 0;
            let column = |t: &[f64], rows: &[Vec<f64>]| -> Vec<(f64, f64)> {
                (t.iter().zip(rows))
                    .filter_map(|(t, r)| Some((*t, *r.get(k)?)))
                    .collect()
            };
            let values = (demos.iter().flat_map(|d| d.rows.iter()))
                .chain(&rec.qpos)
                .filter_map(|r| r.get(k).copied());
            let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
            for (j, d) in h.disturbances.iter().enumerate() {
                if matches!(d, ArmDisturbance::Goal { .. }) {
                    continue;
                }
                p.bands.push(Band {
                    label: Some(d.describe()).filter(|_| first),
                    color: crate::plot::PALETTE[(j + 3) % crate::plot::PALETTE.len()],
                    points: vec![(d.at_s(), lo, hi), (d.until_s(), lo, hi)],
                });
            }
            for (j, d) in demos.iter().enumerate() {
                let mut s = Series::new(
                    "demonstrations",
                    demo_color(j),
                    column(d.time.as_deref().unwrap_or(&[]), &d.rows),
                );
                s.width = 1;
                s.label = s.label.filter(|_| first && j == 0);
                p.series.push(s);
            }
            let u = &h.undisturbed.recording;
            let mut s = Series::new(
                "the hierarchy undisturbed",
                plotters::style::RGBColor(150, 150, 150),
                column(&u.time, &u.qpos),
            );
            s.label = s.label.filter(|_| first);
            p.series.push(s);
            let mut s = Series::new(
                "the hierarchy disturbed",
                BLACK,
                column(&rec.time, &rec.qpos),
            );
            s.width = 3;
            s.label = s.label.filter(|_| first);
            p.series.push(s);
            p
        })
        .collect();
    panels_png(
        path,
        "The hierarchy in the loop on the simulated arm, what its encoders read",
        &out,
        2,
        (620, 380),
    )
    .map_err(|e| ExperimentError::Invalid(format!("drawing {}: {e}", path.display())))
}

/// How long a goal's move stays captioned in the clip, s.
const GOAL_CAPTION_S: f64 = 1.0;

/// Mark the clip's frame of sample `i` of the hierarchy's run: a caption with the time and
/// what disturbs the arm then (held, moved, a link pushed, the goal moved), and on a pushed
/// link (seen from `camera`, in a frame of `size` pixels, the state `data`) a ring and an
/// arrow along the force.
pub fn mark_frame(
    h: &HierarchyLoop,
    i: usize,
    data: &crate::mujoco::Data<'_>,
    camera: Option<usize>,
    size: (u32, u32),
    frame: &mut image::RgbImage,
) {
    let t = h.run.recording.time.get(i).copied().unwrap_or(0.0);
    let mut what = Vec::new();
    for d in &h.disturbances {
        match d {
            ArmDisturbance::Hold { .. } if d.acts_at(t) => what.push("held".to_string()),
            ArmDisturbance::Move { .. } if d.acts_at(t) => what.push("moved, held".to_string()),
            ArmDisturbance::Push { body, force, .. } if d.acts_at(t) => {
                let n = force.iter().map(|f| f * f).sum::<f64>().sqrt();
                what.push(format!("{body} pushed, {n:.0} N"));
                let id = data.model().body_id(body);
                if let (Some(c), Some(id)) = (camera, id) {
                    let at = data.body_xpos(id);
                    // the arrow: 6 cm along the force from the link
                    let tip: [f64; 3] =
                        std::array::from_fn(|k| at[k] + 0.06 * force[k] / n.max(1e-9));
                    if let Some(p) = crate::render::project(data, c, at, size) {
                        let q = crate::render::project(data, c, tip, size);
                        crate::plot::mark(frame, p, 14, q);
                    }
                }
            }
            ArmDisturbance::Goal { at_s, .. } if t >= *at_s && t < at_s + GOAL_CAPTION_S => {
                what.push("goal moved".to_string())
            }
            _ => {}
        }
    }
    let text = match what.is_empty() {
        true => format!("in the loop  t = {t:.1} s"),
        false => format!("in the loop  t = {t:.1} s: {}", what.join(", ")),
    };
    crate::plot::caption(frame, &text, 18);
}
