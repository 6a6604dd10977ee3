//! The upper body's two arms in a held-out study: for each gesture where both arms move, the
//! held-out folds whose reproduction's lag between the arms lies within the training
//! demonstrations' own spread of it, per method (docs/METRICS.md, "The two arms' lag"). Only
//! for demonstrations of the upper body's joints: any other data has no such section.

use serde::Serialize;

use crate::metrics::two_arms::{arm_lag, both_arms_move, LagSpread};
use crate::robot::Robot;
use crate::table::Table;

use super::method::Method;
use super::results::GestureLoo;

/// One method's lags over a gesture's held-out folds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MethodLags {
    /// Which method.
    pub method: Method,
    /// Each held-out fold's reproduction's lag, samples (`None`: no reproduction, or arms
    /// that do not move).
    pub lags: Vec<Option<i64>>,
    /// The folds whose lag lies within their training demonstrations' spread.
    pub within: usize,
    /// The held-out folds (a fold without a lag counts as outside).
    pub folds: usize,
}

/// A gesture where both arms move, its demonstrations' lags and every method's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GestureLags {
    /// The gesture.
    pub gesture: String,
    /// Each demonstration's lag, samples.
    pub demo_lags: Vec<Option<i64>>,
    /// Each held-out fold's spread: its training demonstrations' lags.
    pub spreads: Vec<Option<LagSpread>>,
    /// Per method that ran.
    pub methods: Vec<MethodLags>,
}

/// The gestures of `study` recorded on the upper body where both arms move in every
/// demonstration ([`both_arms_move`]), with their lags; empty for any other data.
pub fn two_arms(study: &[GestureLoo]) -> Vec<GestureLags> {
    let upper = |g: &GestureLoo| {
        g.demonstrations
            .first()
            .is_some_and(|d| Robot::of_columns(&d.columns) == Some(Robot::UpperBody))
    };
    study
        .iter()
        .filter(|g| upper(g) && g.demonstrations.iter().all(|d| both_arms_move(&d.rows)))
        .map(|g| {
            let demo_lags: Vec<Option<i64>> =
                g.demonstrations.iter().map(|d| arm_lag(&d.rows)).collect();
            // held-out fold i learned from every demonstration but the i-th
            let spreads: Vec<Option<LagSpread>> = (0..g.held_out.len())
                .map(|i| {
                    let train: Option<Vec<i64>> = (demo_lags.iter().enumerate())
                        .filter(|(j, _)| *j != i)
                        .map(|(_, l)| *l)
                        .collect();
                    LagSpread::of(&train?)
                })
                .collect();
            let methods = Method::ALL
                .into_iter()
                .filter(|&m| g.held_out.iter().any(|f| f.run(m).is_some()))
                .map(|m| {
                    let lags: Vec<Option<i64>> = (g.held_out.iter())
                        .map(|f| f.run(m).and_then(|r| arm_lag(&r.postures)))
                        .collect();
                    let within = (lags.iter().zip(&spreads))
                        .filter(|(l, s)| matches!((l, s), (Some(l), Some(s)) if s.contains(*l)))
                        .count();
                    MethodLags {
                        method: m,
                        within,
                        folds: lags.len(),
                        lags,
                    }
                })
                .collect();
            GestureLags {
                gesture: g.gesture.clone(),
                demo_lags,
                spreads,
                methods,
            }
        })
        .collect()
}

/// The Markdown section of [`two_arms`]; empty when it has no gesture.
pub fn markdown(lags: &[GestureLags]) -> String {
    let Some(first) = lags.first() else {
        return String::new();
    };
    let list = |v: &[Option<i64>]| {
        (v.iter())
            .map(|l| l.map_or("-".to_string(), |l| l.to_string()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut out = String::from(
        "\n## The two arms' lag\n\nThe gestures where both arms move: the lag of the right \
         arm behind the left (the shift that best aligns the mirrored joints, in 40 Hz \
         samples), per method the held-out folds whose reproduction's lag lies within its \
         training demonstrations' lags, widened by one sample (docs/METRICS.md, \"The two \
         arms' lag\"):\n\n",
    );
    let mut table = Table::new(
        ["gesture", "demonstrations' lags", "hierarchy's lags"]
            .into_iter()
            .chain(first.methods.iter().map(|m| m.method.name())),
    );
    for g in lags {
        let hierarchy = g.methods.iter().find(|m| m.method == Method::Hierarchy);
        table.row(
            [
                g.gesture.clone(),
                list(&g.demo_lags),
                hierarchy.map_or("-".to_string(), |m| list(&m.lags)),
            ]
            .into_iter()
            .chain((g.methods.iter()).map(|m| format!("{} of {}", m.within, m.folds))),
        );
    }
    out.push_str(&table.to_string());
    out
}
