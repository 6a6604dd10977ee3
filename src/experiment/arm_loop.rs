//! `simulate --loop closed`: the learned gesture reproduced in the loop on the simulated arm,
//! the loop study of `cosco heldout --disturb` ([`method_runs`]) on the arm's [`ArmLoop`].
//! Each method's stepper ([`Learned`]: the hierarchy, the DMP on the observed state, GMM/GMR by
//! its clock) drives the arm at 40 Hz from what its encoders read, from the first
//! demonstration's initial posture, undisturbed and then while a hand holds the arm, a force
//! pushes a link or the goal moves (every [`Disturbance`] of the flags at once). What this
//! study keeps of its own: `in_loop.csv` (the hierarchy's run), `in_loop.png`, the report's
//! section, and the clip's marks (the disturbance captioned, a pushed link marked).

use std::path::Path;

use serde::Serialize;

use crate::condition::Conditions;
use crate::demos::{sample_period, Demonstration};
use crate::eval::{method_runs, Against, Learned, LoopRun, Method, GMR_COMPONENTS};
use crate::hsom::Hsom;
use crate::metrics::diagonal;
use crate::plot::{demo_color, panels_png, Band, Panel, Series, BLACK};
use crate::robot::Robot;
use crate::sim::in_loop::ArmLoop;
use crate::sim::{ControllerConfig, NaoArm, Recording};
use crate::stepper::{Disturbance, Kind, Trace};
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

/// The report's section of the loop.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopSection {
    /// The disturbances, described.
    pub disturbances: Vec<String>,
    /// Per method, its run.
    pub methods: Vec<LoopRun>,
}

/// A run as the report's JSON has it.
#[derive(Serialize)]
struct ArmRow<'a> {
    method: &'a str,
    closed_loop: bool,
    error: &'a Option<String>,
    finished: bool,
    replans: usize,
    seconds: f64,
    final_error: f64,
    jump: f64,
    relative_dtw: f64,
    undisturbed_dtw: f64,
    swings: Option<[usize; 2]>,
    displaced: &'a [f64],
}

/// As `{"disturbances": [...], "methods": [...]}`, each run with whether its loop is closed,
/// its duration and its swings disturbed and undisturbed.
impl Serialize for LoopSection {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        #[derive(Serialize)]
        struct Section<'a> {
            disturbances: &'a [String],
            methods: Vec<ArmRow<'a>>,
        }
        let methods = (self.methods.iter())
            .map(|m| ArmRow {
                method: m.method.name(),
                closed_loop: m.closed_loop,
                error: &m.error,
                finished: m.finished,
                replans: m.replans,
                seconds: m.seconds,
                final_error: m.final_error,
                jump: m.jump,
                relative_dtw: m.relative_dtw,
                undisturbed_dtw: m.undisturbed_dtw,
                swings: m.swings.map(|[a, b, _]| [a, b]),
                displaced: &m.displaced,
            })
            .collect();
        let disturbances = &self.disturbances;
        Section {
            disturbances,
            methods,
        }
        .serialize(s)
    }
}

/// The hierarchy's disturbed run, to film and draw.
pub struct HierarchyLoop {
    /// The run.
    pub run: Recording,
    /// Per sample of the run: whether a hold, a move or a push had the arm.
    pub held: Vec<bool>,
    /// Its undisturbed run.
    pub undisturbed: Recording,
    /// The disturbances it ran with.
    pub disturbances: Vec<Disturbance>,
}

/// `trace`'s readings and commands as a recording of `robot` at `rate` Hz.
fn recording(trace: Trace, rate: f64, robot: Robot) -> Recording {
    let mut r = Recording::new(rate, robot);
    r.time = (0..trace.path.len())
        .map(|k| k as f64 * (1.0 / rate))
        .collect();
    r.qpos = trace.path;
    r.target = trace.commanded;
    r
}

/// Every method of [`METHODS`] in the loop on `arm`, learned from `demos` (the hierarchy is
/// `model`), undisturbed and with `disturbances` (seconds, amounts absolute); `in_loop.csv`
/// written into `out` (listed in `files`). The section and the hierarchy's run.
pub fn closed_loop<const N: usize>(
    arm: &NaoArm<N>,
    model: &Hsom,
    demos: &[Demonstration],
    disturbances: &[Disturbance],
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
    let rate = config.record_rate_hz;
    let longest = demos.iter().map(|d| d.rows.len()).max().unwrap_or(1) as f64 * period;
    let limit = ((4.0 * longest + 10.0).min(3600.0) * rate).floor() as usize;
    let robot = arm.robot();
    let against = Against {
        demos,
        diagonal: diagonal(demos).max(f64::MIN_POSITIVE),
        extent: Vec::new(),
        swing_joint: (robot == Robot::LeftArm).then(|| robot.swing_joint().0),
    };
    let plant = ArmLoop { arm, config };
    let sets = [disturbances.to_vec()];
    let mut methods = Vec::new();
    let mut hierarchy = None;
    let shared = std::sync::Arc::new(model.clone());
    for method in METHODS {
        let runs = (|| {
            let hsom = &mut |_| Ok((shared.clone(), 0.0));
            let (learned, _) = Learned::fit(method, demos, period, GMR_COMPONENTS, hsom)?;
            let none = Conditions::default();
            let make = || learned.stepper(method, demos, &initial, &none, period);
            let (plain, mut runs) = method_runs(
                method, &make, &plant, &initial, &against, &sets, limit, period,
            )?;
            Ok::<_, String>((plain, runs.remove(0)?))
        })();
        let (plain, (mut run, trace)) = match runs {
            Ok(r) => r,
            Err(e) => {
                methods.push(LoopRun::failed(method, &first.source, e));
                continue;
            }
        };
        run.seconds = (trace.path.len() - 1) as f64 * (1.0 / rate);
        methods.push(run);
        if method == Method::Hierarchy {
            hierarchy = Some(HierarchyLoop {
                held: trace.held.clone(),
                run: recording(trace, rate, robot),
                undisturbed: recording(plain, rate, robot),
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
    write_loop_csv(&out.join("in_loop.csv"), robot, &hierarchy)?;
    files.push("in_loop.csv".into());
    let section = LoopSection {
        disturbances: disturbances.iter().map(Disturbance::describe).collect(),
        methods,
    };
    Ok((section, hierarchy))
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
    let rec = &h.run;
    for k in 0..rec.len() {
        let row = [
            format!("{:.3}", rec.time[k]),
            u8::from(h.held[k]).to_string(),
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
            m.method.name().to_string(),
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
            m.swings
                .map_or("n/a".into(), |[a, b, _]| format!("{a} / {b}")),
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
        .filter_map(|m| Some((m.method.name(), m.error.as_ref()?)))
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

/// `in_loop.png`: per joint of `robot`'s plot panels, the demonstrations, the hierarchy's
/// undisturbed and disturbed runs, and the disturbances' intervals shaded.
pub fn loop_png(
    path: &Path,
    robot: Robot,
    demos: &[Demonstration],
    h: &HierarchyLoop,
) -> Result<(), ExperimentError> {
    let rec = &h.run;
    let out: Vec<Panel> = (robot.plot_panels().iter().enumerate())
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
                if matches!(d.kind, Kind::Goal(_)) {
                    continue;
                }
                p.bands.push(Band {
                    label: Some(d.describe()).filter(|_| first),
                    color: crate::plot::PALETTE[(j + 3) % crate::plot::PALETTE.len()],
                    points: vec![(d.at, lo, hi), (d.until(), lo, hi)],
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
            let u = &h.undisturbed;
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
    let title = format!(
        "The hierarchy in the loop on the simulated Nao {}, what its encoders read",
        robot.phrase()
    );
    panels_png(path, &title, &out, 2, (620, 380))
        .map_err(|e| ExperimentError::Invalid(format!("drawing {}: {e}", path.display())))
}

/// How long a goal's move stays captioned in the clip, s.
const GOAL_CAPTION_S: f64 = 1.0;

/// When the clip's captions ([`mark_frame`]) say what disturbs the arm, from and to (s): a
/// hold, a move or a push while it acts, a goal's move for [`GOAL_CAPTION_S`].
pub fn marked_windows(h: &HierarchyLoop) -> Vec<(f64, f64)> {
    (h.disturbances.iter())
        .map(|d| match d.kind {
            Kind::Goal(_) => (d.at, d.at + GOAL_CAPTION_S),
            _ => (d.at, d.until()),
        })
        .collect()
}

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
    let t = h.run.time.get(i).copied().unwrap_or(0.0);
    let mut what = Vec::new();
    for d in &h.disturbances {
        match &d.kind {
            Kind::Hold if d.acts_at(t) => what.push("held".to_string()),
            Kind::Move(_) if d.acts_at(t) => what.push("moved, held".to_string()),
            Kind::Push { body, force } if d.acts_at(t) => {
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
            Kind::Goal(_) if t >= d.at && t < d.at + GOAL_CAPTION_S => {
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
