//! Pointing and gaze at targets no demonstration pointed at (`cosco reproduce --point-at
//! --look-at`), held out: for every leave-one-out fold of each pointing gesture and seed, the
//! hierarchy learns from the other demonstrations and reproduces from the held-out one's
//! first posture, aimed at a seeded target 0.5 to 3 m away whose direction from the shoulder
//! lies within 25 degrees of azimuth and 20 of elevation of the gesture's nominal pointing
//! direction, and more than 3 degrees from every demonstration's. Measured: how long the held
//! part points within 2 degrees of the target (the kinematics), and within 3 degrees once
//! executed on the simulated robot; the joint ranges; the contacts; the reproduction's DTW to
//! the same fold's unconditioned reproduction over the median DTW of the demonstrations among
//! themselves. Beside it, ProMP conditioned on the same solved posture, and the unconditioned
//! reproduction (the control). On the upper body, the gaze (`--look-at`) the same way.
//!
//! ```sh
//! cargo run --release --example pointing -- --seeds 41-45 --left-seeds 11-20
//! ```

mod common;

use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Parser;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use cosco_hsom::aim::{
    self, aim_conditions, azimuth_elevation, gaze_errors, longest_within, pointing_errors, Aim,
    Arm, Point,
};
use cosco_hsom::condition::Conditions;
use cosco_hsom::config::{load_config, HsomConfig};
use cosco_hsom::demos::Demonstration;
use cosco_hsom::dtw::{dtw_distance, Band};
use cosco_hsom::experiment::demonstrate::parse_seeds;
use cosco_hsom::experiment::record_demonstrations;
use cosco_hsom::gesture::Gesture;
use cosco_hsom::promp::PrompSettings;
use cosco_hsom::robot::Robot;
use cosco_hsom::sim::{execute_postures, NaoArm};
use cosco_hsom::table::Table;

/// Held-out reproductions aimed at targets.
#[derive(Parser, Debug)]
struct Args {
    /// Seeds of the upper body's demonstrations (`point-left` and `point-right`).
    #[arg(long, default_value = "41-45")]
    seeds: String,
    /// Seeds of the left arm's demonstrations (`point-left`).
    #[arg(long, default_value = "11-20")]
    left_seeds: String,
    /// Demonstrations per (gesture, seed): one held out in turn.
    #[arg(long, default_value_t = 5)]
    count: usize,
    /// Upper-body configuration (XML).
    #[arg(long, default_value = "configs/nao-upper-body.xml")]
    upper_config: std::path::PathBuf,
    /// Left-arm configuration (XML).
    #[arg(long, default_value = "configs/nao-gestures.xml")]
    left_config: std::path::PathBuf,
}

fn main() -> ExitCode {
    common::exit(run(Args::parse()))
}

/// Rows a second: the reproductions' rate.
const RATE: f64 = 40.0;
/// The kinematic gate: the held part within this many degrees ...
const POINT_DEG: f64 = 2.0;
/// ... for at least this long, s.
const HOLD_S: f64 = 0.5;
/// After execution on the simulated robot.
const EXECUTED_DEG: f64 = 3.0;
/// Gaze in the kinematics, and executed.
const GAZE_DEG: f64 = 1.0;
const GAZE_EXECUTED_DEG: f64 = 2.0;

/// One fold's measures.
#[derive(Debug, Default, Clone)]
struct Fold {
    /// Seconds the hierarchy's aimed reproduction points within [`POINT_DEG`].
    held_s: f64,
    /// Seconds the executed one points within [`EXECUTED_DEG`].
    executed_s: f64,
    in_ranges: bool,
    contacts: Option<usize>,
    dtw_ratio: f64,
    promp_held_s: f64,
    promp_ratio: f64,
    control_held_s: f64,
    /// Seconds the aimed gaze is within [`GAZE_DEG`], and executed within
    /// [`GAZE_EXECUTED_DEG`] (the upper body).
    gaze: Option<(f64, f64)>,
    refused: Option<String>,
}

fn per_step(a: &[Vec<f64>], b: &[Vec<f64>]) -> Result<f64> {
    Ok(dtw_distance(a, b, Band::None)?.per_step())
}

/// The median DTW of the demonstrations among themselves.
fn spread(demos: &[Demonstration]) -> Result<f64> {
    let mut d = Vec::new();
    for (i, a) in demos.iter().enumerate() {
        for b in &demos[i + 1..] {
            d.push(per_step(&a.rows, &b.rows)?);
        }
    }
    Ok(cosco_hsom::stats::median(d).unwrap_or(f64::NAN))
}

/// The unit direction of `(azimuth, elevation)` degrees.
fn direction(az: f64, el: f64) -> Point {
    let (az, el) = (az.to_radians(), el.to_radians());
    [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()]
}

/// The held pointing direction of each demonstration (its held part's mean posture).
fn demonstrated(robot: Robot, arm: Arm, demos: &[Demonstration]) -> Result<Vec<Point>> {
    let at = arm.offset(robot).context("the robot's arm")?;
    demos
        .iter()
        .map(|d| {
            let held = aim::held_posture(&d.rows, aim::held_span(&d.rows, at..at + 4));
            Ok(arm.pointing(&held[at..at + 5]))
        })
        .collect()
}

/// A seeded target 0.5 to 3 m from the shoulder, within the region about `nominal`
/// (azimuth, elevation), more than 3 degrees from each of `avoid`.
fn target(rng: &mut ChaCha8Rng, arm: Arm, nominal: (f64, f64), avoid: &[Point]) -> Point {
    loop {
        let az = nominal.0 + rng.gen_range(-25.0..25.0);
        let el = nominal.1 + rng.gen_range(-20.0..20.0);
        let u = direction(az, el);
        let far = avoid
            .iter()
            .all(|d| aim::angle_to([0.0; 3], *d, u).to_degrees() > 3.0);
        let r = rng.gen_range(0.5..3.0);
        if far {
            let s = arm.shoulder();
            return [s[0] + r * u[0], s[1] + r * u[1], s[2] + r * u[2]];
        }
    }
}

/// Every fold of `gesture` (pointing with `arm`) on `robot`, over `seeds`.
fn folds<const N: usize>(
    robot: Robot,
    gesture: &Gesture,
    arm: Arm,
    cfg: &HsomConfig,
    seeds: &[u64],
    count: usize,
) -> Result<Vec<Fold>> {
    let model = NaoArm::<N>::load_shipped(robot)?;
    let at = arm.offset(robot).context("the robot's arm")?;
    let nominal_pose = gesture.apex();
    let nominal = azimuth_elevation(arm.pointing(&nominal_pose[at..at + 5]));
    let settings = cosco_hsom::experiment::DemoSettings::default();
    let mut jobs = Vec::new();
    for &seed in seeds {
        let demos: Vec<Demonstration> =
            record_demonstrations(&model, gesture, count, seed, &settings, |_| {})?
                .iter()
                .map(|r| r.to_demonstration(gesture.name))
                .collect();
        let pointed = demonstrated(robot, arm, &demos)?;
        let mut rng = ChaCha8Rng::seed_from_u64(seed * 1000 + at as u64);
        for i in 0..demos.len() {
            jobs.push((demos.clone(), i, target(&mut rng, arm, nominal, &pointed)));
        }
    }
    jobs.par_iter()
        .map(|(demos, i, t)| fold(&model, robot, arm, cfg, demos, *i, *t))
        .collect()
}

/// One fold: demonstration `i` held out, the others learned; aimed at `t`.
fn fold<const N: usize>(
    model: &NaoArm<N>,
    robot: Robot,
    arm: Arm,
    cfg: &HsomConfig,
    demos: &[Demonstration],
    i: usize,
    t: Point,
) -> Result<Fold> {
    let train: Vec<Demonstration> = (demos.iter().enumerate())
        .filter(|&(k, _)| k != i)
        .map(|(_, d)| d.clone())
        .collect();
    let initial = &demos[i].rows[0];
    let hsom = cfg.fit(&train)?;
    let ranges = robot.ranges();
    let plain = hsom.reproduce(initial)?.postures;
    let secs = |errors: &[f64], tol: f64| longest_within(errors, tol) as f64 / RATE;
    let mut f = Fold {
        control_held_s: secs(&pointing_errors(robot, arm, &plain, t), POINT_DEG),
        ..Fold::default()
    };
    let point = Aim {
        point_at: Some(t),
        look_at: None,
    };
    let (conditions, solved) = match aim_conditions(robot, &plain, &Conditions::default(), &point) {
        Ok(c) => c,
        Err(e) => {
            f.refused = Some(e.to_string());
            return Ok(f);
        }
    };
    let rows = hsom
        .reproduce_conditioned(initial, &conditions, Some(&ranges))?
        .postures;
    f.held_s = secs(&pointing_errors(robot, arm, &rows, t), POINT_DEG);
    f.in_ranges = rows.iter().all(|r| {
        r.iter()
            .zip(&ranges)
            .all(|(v, (lo, hi))| (lo..=hi).contains(&v))
    });
    let executed = execute_postures(model, &rows, RATE)?;
    f.executed_s = secs(
        &pointing_errors(robot, arm, &executed.qpos, t),
        EXECUTED_DEG,
    );
    f.contacts = robot
        .has_collision_shapes()
        .then_some(executed.contacts.len());
    let among = spread(&train)?;
    f.dtw_ratio = per_step(&rows, &plain)? / among;
    // ProMP, conditioned on the hierarchy's solved posture over its own held part
    let promp = PrompSettings::default().fit(&train)?;
    let promp_plain = promp.reproduce(initial)?;
    let own = aim::solve(robot, &promp_plain, &point)?;
    let same = aim::Aimed {
        posture: solved.posture.clone(),
        ..own
    };
    let points: Vec<(f64, Vec<f64>)> = aim::via_points(robot, &promp_plain, &same, &point)
        .into_iter()
        .map(|v| (v.phase, v.posture))
        .collect();
    let (promp_rows, _) = promp.conditioned(initial, &points)?;
    f.promp_held_s = secs(&pointing_errors(robot, arm, &promp_rows, t), POINT_DEG);
    f.promp_ratio = per_step(&promp_rows, &promp_plain)? / among;
    if robot == Robot::UpperBody {
        let look = Aim {
            point_at: None,
            look_at: Some(t),
        };
        let (c, _) = aim_conditions(robot, &plain, &Conditions::default(), &look)?;
        let rows = hsom
            .reproduce_conditioned(initial, &c, Some(&ranges))?
            .postures;
        let executed = execute_postures(model, &rows, RATE)?;
        f.gaze = Some((
            secs(&gaze_errors(&rows, t), GAZE_DEG),
            secs(&gaze_errors(&executed.qpos, t), GAZE_EXECUTED_DEG),
        ));
    }
    Ok(f)
}

fn run(a: Args) -> Result<()> {
    anyhow::ensure!(a.count >= 3, "--count must be at least 3, got {}", a.count);
    let upper = load_config(&a.upper_config)?;
    let left = load_config(&a.left_config)?;
    let seeds = parse_seeds(&a.seeds)?;
    let left_seeds = parse_seeds(&a.left_seeds)?;
    let named = |r: Robot, n: &str| Gesture::by_name(r, n).context("a pointing gesture");
    let groups: Vec<(String, Vec<Fold>)> = vec![
        (
            format!("upper body, point-left, seeds {}", a.seeds),
            folds::<14>(
                Robot::UpperBody,
                &named(Robot::UpperBody, "point-left")?,
                Arm::Left,
                &upper,
                &seeds,
                a.count,
            )?,
        ),
        (
            format!("upper body, point-right, seeds {}", a.seeds),
            folds::<14>(
                Robot::UpperBody,
                &named(Robot::UpperBody, "point-right")?,
                Arm::Right,
                &upper,
                &seeds,
                a.count,
            )?,
        ),
        (
            format!("left arm, point-left, seeds {}", a.left_seeds),
            folds::<6>(
                Robot::LeftArm,
                &named(Robot::LeftArm, "point-left")?,
                Arm::Left,
                &left,
                &left_seeds,
                a.count,
            )?,
        ),
    ];
    print!("{}", markdown(&groups));
    Ok(())
}

fn count(folds: &[Fold], f: impl Fn(&Fold) -> bool) -> String {
    format!("{}/{}", folds.iter().filter(|x| f(x)).count(), folds.len())
}

fn median(folds: &[Fold], f: impl Fn(&Fold) -> f64) -> f64 {
    let v: Vec<f64> = folds
        .iter()
        .filter(|x| x.refused.is_none())
        .map(f)
        .collect();
    cosco_hsom::stats::median(v).unwrap_or(f64::NAN)
}

fn markdown(groups: &[(String, Vec<Fold>)]) -> String {
    let mut table = Table::new([
        "folds (one target each)",
        "refused",
        "hierarchy: within 2 deg >= 0.5 s",
        "executed: within 3 deg >= 0.5 s",
        "median s within 2 deg",
        "joint ranges kept",
        "contacts",
        "DTW to unconditioned / demonstrations' (median, worst)",
        "DTW ratio at most 1.3",
        "ProMP: within 2 deg >= 0.5 s",
        "ProMP: DTW ratio (median)",
        "unconditioned (control): within 2 deg >= 0.5 s",
    ]);
    for (name, folds) in groups {
        let ok: Vec<&Fold> = folds.iter().filter(|f| f.refused.is_none()).collect();
        let worst = ok.iter().map(|f| f.dtw_ratio).fold(0.0, f64::max);
        table.row([
            format!("{name}: {}", folds.len()),
            count(folds, |f| f.refused.is_some()),
            count(folds, |f| f.held_s >= HOLD_S),
            count(folds, |f| f.executed_s >= HOLD_S),
            format!("{:.2}", median(folds, |f| f.held_s)),
            count(folds, |f| f.in_ranges),
            match ok
                .iter()
                .map(|f| f.contacts)
                .collect::<Option<Vec<usize>>>()
            {
                Some(c) => format!("{}", c.iter().sum::<usize>()),
                None => "n/a (no collision shapes)".into(),
            },
            format!("{:.2}, {:.2}", median(folds, |f| f.dtw_ratio), worst),
            count(folds, |f| f.refused.is_none() && f.dtw_ratio <= 1.3),
            count(folds, |f| f.promp_held_s >= HOLD_S),
            format!("{:.2}", median(folds, |f| f.promp_ratio)),
            count(folds, |f| f.control_held_s >= HOLD_S),
        ]);
    }
    let mut out = table.to_string();
    let gaze: Vec<&Fold> = (groups.iter())
        .flat_map(|(_, f)| f)
        .filter(|f| f.gaze.is_some())
        .collect();
    if !gaze.is_empty() {
        let mut t = Table::new([
            "gaze (--look-at, the upper body): folds",
            "within 1 deg >= 0.5 s (kinematics)",
            "executed: within 2 deg >= 0.5 s",
        ]);
        let g = |f: &Fold| f.gaze.unwrap_or_default();
        let n = gaze.len();
        t.row([
            format!("{n}"),
            format!("{}/{n}", gaze.iter().filter(|f| g(f).0 >= HOLD_S).count()),
            format!("{}/{n}", gaze.iter().filter(|f| g(f).1 >= HOLD_S).count()),
        ]);
        out += "\n";
        out += &t.to_string();
    }
    for (name, folds) in groups {
        for f in folds.iter().filter_map(|f| f.refused.as_ref()) {
            out += &format!("\nrefused ({name}): {f}\n");
        }
    }
    out
}
