//! The large swings of a held-out fold, to look at ([`swing_folds`], [`swing_folds_png`]):
//! the executed reproduction's trace of the swing joint beside the held-out demonstration's.

use serde::Serialize;

use cosco_hsom::config::HsomConfig;
use cosco_hsom::demos::Demonstration;
use cosco_hsom::eval::{fold_scores, loo_map, run_fold, FoldInput, Method, Pool, Split, Swings};
use cosco_hsom::experiment::heldout::{check_demos, demo_trace, joint_trace};
use cosco_hsom::experiment::{ArmExecutor, ExperimentError};
use cosco_hsom::sim::{NaoArm, Transition, JOINT_NAMES, SWING_JOINT};

/// One fold of [`swing_folds`]: the large swings of [`SWING_JOINT`] in the executed
/// reproduction and in the held-out demonstration, and both traces to draw.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SwingFold {
    /// 0-based index of the held-out demonstration.
    pub held_out: usize,
    /// The swings counted.
    pub swings: Swings,
    /// Joint DTW of the fold, rad per step.
    pub joint_dtw: f64,
    /// Duration ratio of the fold (reproduction / demonstration, active parts).
    pub duration_ratio: f64,
    /// `(time s, value rad)` of [`SWING_JOINT`] in the executed reproduction.
    pub reproduction: Vec<(f64, f64)>,
    /// `(time s, value rad)` of [`SWING_JOINT`] in the held-out demonstration.
    pub demo: Vec<(f64, f64)>,
}

/// CoSCo-HSOM's leave-one-out folds on the arm (learned with `config`, executed with
/// `transition`), keeping for each the trace of [`SWING_JOINT`] beside the held-out
/// demonstration's: what a swing count means, to look at ([`swing_folds_png`]).
pub fn swing_folds(
    arm: &NaoArm,
    config: &HsomConfig,
    demos: &[Demonstration],
    transition: Transition,
) -> Result<Vec<SwingFold>, ExperimentError> {
    check_demos(demos)?;
    let executor = ArmExecutor { arm, transition };
    let pool = Pool::new(1).map_err(ExperimentError::Invalid)?;
    let fold = |split: Split| {
        let Split::HeldOut(i) = split else {
            return Err(ExperimentError::Invalid(format!("{split:?}: not held out")));
        };
        let (train, held) = split.of(demos);
        let demo = &held[0];
        let input = FoldInput {
            config: Some(config),
            ..FoldInput::new(&train, held)
        };
        let run = run_fold(&[Method::Hierarchy], &input, &executor)
            .pop()
            .map_or_else(|| Err("no run".to_string()), |(_, r)| r)
            .map_err(ExperimentError::Invalid)?;
        let scores =
            fold_scores(&run, &executor, &train, demo, 0.0).map_err(ExperimentError::Invalid)?;
        Ok(SwingFold {
            held_out: i,
            swings: scores
                .swings
                .ok_or_else(|| ExperimentError::Invalid("no swings".into()))?,
            joint_dtw: run.executed.fidelity.joint_dtw_rad_per_step.mean,
            duration_ratio: run.executed.fidelity.duration_ratio.mean,
            reproduction: joint_trace(&run.executed.trace),
            demo: demo_trace(demo),
        })
    };
    (loo_map(&[demos], false, &pool, None, |_, split| fold(split)).into_iter())
        .flat_map(|(held_out, _)| held_out)
        .collect()
}

/// One panel per fold of [`swing_folds`]: the held-out demonstration (in the palette's
/// colour of its index) and the executed reproduction (black), [`SWING_JOINT`] against time,
/// the counts and the fold's joint DTW in each panel's title. Written atomically to `path`.
pub fn swing_folds_png(
    path: &std::path::Path,
    title: &str,
    folds: &[SwingFold],
) -> Result<(), cosco_hsom::plot::PlotError> {
    use cosco_hsom::plot::{demo_color, Panel, Series};
    let joint = JOINT_NAMES[SWING_JOINT];
    let panels: Vec<Panel> = folds
        .iter()
        .map(|f| {
            let mut p = Panel::new(
                format!(
                    "demonstration {} held out: {} of {} swings, {:.3} rad/step, duration {:.2}",
                    f.held_out + 1,
                    f.swings.reproduction,
                    f.swings.demo,
                    f.joint_dtw,
                    f.duration_ratio
                ),
                "time (s)",
                format!("{joint} (rad)"),
            );
            p.series.push(Series::new(
                format!("demonstration {}", f.held_out + 1),
                demo_color(f.held_out),
                f.demo.clone(),
            ));
            let mut r = Series::new(
                "reproduction",
                cosco_hsom::plot::BLACK,
                f.reproduction.clone(),
            );
            r.width = 3;
            p.series.push(r);
            p
        })
        .collect();
    cosco_hsom::plot::panels_png(path, title, &panels, 2, (620, 380))
}
