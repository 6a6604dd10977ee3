//! An evaluation as JSON, Markdown and a figure (`cosco heldout`).

use crate::metrics::registry::{
    Metric, DURATION_RATIO, JERK_RATIO, RELATIVE_DTW, RELATIVE_DTW_IN_SAMPLE, RELATIVE_FINAL_ERROR,
};
use crate::table::Table;

#[cfg(feature = "plot")]
use super::loo::LooError;
use super::method::Method;
use super::results::{failures, passed, summary, GestureLoo, Score};
#[cfg(feature = "plot")]
use crate::demos::sample_period;

/// `doc` as pretty JSON, its keys in alphabetical order at every level (serde_json's map
/// keeps them sorted), non-finite numbers as null: how every study document is written.
pub(super) fn json_text(doc: &impl serde::Serialize) -> String {
    // cannot fail: string keys, plain numbers, strings and enums
    let value = serde_json::to_value(doc).unwrap_or_default();
    serde_json::to_string_pretty(&value).unwrap_or_default()
}

/// The metric columns of the summary table, in order (a [`super::MethodSummary`] field each).
const SUMMARY_METRICS: [Metric; 5] = [
    RELATIVE_DTW,
    RELATIVE_DTW_IN_SAMPLE,
    DURATION_RATIO.to(2),
    RELATIVE_FINAL_ERROR,
    JERK_RATIO.titled("jerk ratio"),
];

/// The study as Markdown: per gesture, each method's mean relative DTW over the folds held
/// out (and in-sample), then the summary over the gestures.
pub fn markdown(study: &[GestureLoo]) -> String {
    use std::fmt::Write as _;
    let summaries = summary(study);
    let methods: Vec<Method> = summaries.iter().map(|s| s.method).collect();
    let cell = |v: Option<f64>| v.map_or("failed".to_string(), |v| format!("{v:.4}"));
    let mut out = String::new();
    let _ = writeln!(
        out,
        "Relative DTW (per-step DTW / the gesture's bounding-box diagonal), mean over the \
         leave-one-out folds, held out (in-sample in brackets where learned from all):\n"
    );
    let mut table = Table::new(
        ["gesture", "demonstrations"]
            .into_iter()
            .chain(methods.iter().map(|m| m.name())),
    );
    for g in study {
        let cells = methods.iter().map(|&m| {
            let h = cell(g.mean(&g.held_out, m, |s| s.relative_dtw));
            match g.mean(&g.in_sample, m, |s| s.relative_dtw) {
                Some(i) => format!("{h} ({i:.4})"),
                None => h,
            }
        });
        table.row(
            [g.gesture.clone(), g.demonstrations.len().to_string()]
                .into_iter()
                .chain(cells),
        );
    }
    out.push_str(&table.to_string());
    let over = match study.len() {
        1 => "The gesture's means over the leave-one-out folds (held out)".to_string(),
        n => format!("Medians over the {n} gestures (held out; per-gesture means over the folds)"),
    };
    let _ = writeln!(
        out,
        "\n{over}; start in range and end within spread count the held-out folds \
         (docs/METRICS.md, \"Start and end\"):\n"
    );
    let columns = SUMMARY_METRICS.map(|m| m.label);
    let mut table = Table::new(["method"].into_iter().chain(columns).chain([
        "band coverage",
        "start in range",
        "end within spread",
        "hierarchy / method",
        "hierarchy closer",
        "failed folds",
    ]));
    let folds = |m: Method, pass: fn(&Score) -> bool| {
        let (k, n) = passed(study, m, pass);
        format!("{k} of {n}")
    };
    let opt = |v: Option<f64>, d: usize| v.map_or("-".to_string(), |v| format!("{v:.d$}"));
    for s in summaries {
        // the hierarchy against itself: nothing to show
        let against = |v: String| {
            if s.method == Method::Hierarchy {
                "-".into()
            } else {
                v
            }
        };
        let figures = [
            s.relative_dtw,
            s.relative_dtw_in_sample,
            s.duration_ratio,
            s.relative_final_error,
            s.jerk_ratio,
        ];
        let cells = (SUMMARY_METRICS.iter().zip(figures)).map(|(m, v)| m.cell(v, "-"));
        let name = s.method.name().to_string();
        table.row(
            std::iter::once(name).chain(cells).chain([
                s.coverage
                    .map_or("-".to_string(), |c| format!("{:.1} %", 100.0 * c)),
                folds(s.method, |s| s.start_in_range),
                folds(s.method, |s| s.end_within_spread),
                against(opt(s.hierarchy_ratio, 3)),
                against(format!(
                    "{} of {}",
                    s.hierarchy_closer.0, s.hierarchy_closer.1
                )),
                format!("{} of {}", s.failed, s.folds),
            ]),
        );
    }
    out.push_str(&table.to_string());
    let outside: Vec<String> = (summary(study).iter())
        .filter_map(|s| Some(format!("{} {}", s.method.name(), s.out_of_range?)))
        .collect();
    if !outside.is_empty() {
        let _ = writeln!(
            out,
            "\nPosture values outside the Nao arm's joint ranges (before execution), over the \
             held-out folds: {}.",
            outside.join(", ")
        );
    }
    if summaries_conditioned(study) {
        let _ = writeln!(
            out,
            "\nConditions met by the postures each method produced (before execution; each \
             read at its phase between two rows), the largest error of any held-out fold over \
             the gesture's diagonal:\n"
        );
        let e = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.1e}"));
        let mut table = Table::new(["method", "goal", "via-point"]);
        for s in summary(study) {
            table.row([
                s.method.name().to_string(),
                e(s.worst_goal_error),
                e(s.worst_via_error),
            ]);
        }
        out.push_str(&table.to_string());
    }
    let failed = failures(study);
    if !failed.is_empty() {
        let _ = writeln!(out, "\nFailed runs (method: reason; where):\n");
        for (m, why, at) in failed {
            let shown = at.iter().take(3).cloned().collect::<Vec<_>>().join("; ");
            let more = match at.len() {
                n if n > 3 => format!("; and {} more", n - 3),
                _ => String::new(),
            };
            let _ = writeln!(out, "- {}: {why}; {shown}{more}", m.name());
        }
    }
    out
}

/// Whether any method's reproductions in `study` were conditioned on a goal or via-point.
fn summaries_conditioned(study: &[GestureLoo]) -> bool {
    summary(study)
        .iter()
        .any(|s| s.worst_goal_error.is_some() || s.worst_via_error.is_some())
}

/// A figure of one fold per gesture: the gesture's demonstrations (thin, grey), the held-out
/// one (black) and the reproductions from its first sample of the hierarchy, the nearest
/// sequence and GMM/GMR (height 1 and the replay are in the tables only), in the plane of the
/// first two variables (against time for data of one variable). `fold` picks the held-out
/// demonstration (0-based; the last one where a gesture has fewer).
#[cfg(feature = "plot")]
pub fn png(path: &std::path::Path, study: &[GestureLoo], fold: usize) -> Result<(), LooError> {
    use crate::plot::{panels_png, Band, Panel, Series, Tube, BLACK, PALETTE};
    use plotters::style::RGBColor;
    let color = |m: Method| match m {
        Method::Hierarchy => PALETTE[3],
        Method::NearestSequence => PALETTE[0],
        Method::Height1 => PALETTE[4],
        Method::GmmGmr => RGBColor(200, 0, 130),
        Method::ProMP => PALETTE[1],
        Method::Dmp => RGBColor(120, 90, 40),
        Method::Dba => RGBColor(0, 150, 150),
        Method::Replay => PALETTE[2],
    };
    let points = |rows: &[Vec<f64>], period: f64| -> Vec<(f64, f64)> {
        rows.iter()
            .enumerate()
            .map(|(k, r)| match r.len() {
                1 => (k as f64 * period, r[0]),
                _ => (r[0], r[1]),
            })
            .collect()
    };
    let mut panels = Vec::new();
    for g in study {
        let k = fold.min(g.held_out.len().saturating_sub(1));
        let (Some(target), Some(f)) = (g.demonstrations.get(k), g.held_out.get(k)) else {
            continue;
        };
        let period = sample_period(target);
        let (x, y) = match target.columns.len() {
            1 => ("time (s)".to_string(), target.columns[0].clone()),
            _ => (target.columns[0].clone(), target.columns[1].clone()),
        };
        let mut panel = Panel::new(format!("{} (fold {})", g.gesture, k + 1), x, y);
        panel.equal_aspect = target.columns.len() > 1;
        for (j, d) in g.demonstrations.iter().enumerate() {
            if j != k {
                let mut s = Series::new("", RGBColor(170, 170, 170), points(&d.rows, period));
                s.label = (j == usize::from(k == 0)).then(|| "training".to_string());
                s.width = 1;
                panel.series.push(s);
            }
        }
        panel
            .series
            .push(Series::new("held out", BLACK, points(&target.rows, period)));
        // the hierarchy's 95 % band under everything
        if let Some(b) = f.run(Method::Hierarchy).and_then(|r| r.band.as_ref()) {
            let label = Some("hierarchy's 95 % band".to_string());
            let color = color(Method::Hierarchy);
            match target.columns.len() {
                1 => panel.bands.push(Band {
                    label,
                    color,
                    points: (b.lo.iter().zip(&b.hi).enumerate())
                        .map(|(k, (lo, hi))| (k as f64 * period, lo[0], hi[0]))
                        .collect(),
                }),
                _ => panel.tubes.push(Tube {
                    label,
                    color,
                    boxes: (b.lo.iter().zip(&b.hi))
                        .map(|(lo, hi)| ((lo[0], lo[1]), (hi[0], hi[1])))
                        .collect(),
                }),
            }
        }
        // GMM/GMR first, the hierarchy last (on top)
        for r in f.runs.iter().rev().filter(|r| !r.postures.is_empty()) {
            if r.method == Method::Height1 || r.method == Method::Replay {
                continue;
            }
            panel.series.push(Series::new(
                r.method.name(),
                color(r.method),
                points(&r.postures, period),
            ));
        }
        panels.push(panel);
    }
    let cols = (panels.len() as f64).sqrt().ceil().max(1.0) as usize;
    panels_png(
        path,
        "Held out (black), reproduced from its first sample",
        &panels,
        cols,
        (420, 360),
    )?;
    Ok(())
}
