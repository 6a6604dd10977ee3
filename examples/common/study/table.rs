//! The study's Markdown tables: one row per (gesture, seed) with the medians per gesture and
//! overall, and the per-level accuracy.

use cosco_hsom::eval::{HeldOutSummary, Method};
use cosco_hsom::table::Table;

use super::{first_seen, median, number, ConfigStudy, StudyRow};

type Value = fn(&StudyRow) -> Option<f64>;

/// A column of the study table: one or more values per cell (joined by " / ").
struct Column {
    header: &'static str,
    values: Vec<Value>,
    digits: usize,
}

fn col(header: &'static str, digits: usize, values: Vec<Value>) -> Column {
    Column {
        header,
        values,
        digits,
    }
}

fn ratio(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) if b != 0.0 => Some(a / b),
        _ => None,
    }
}

fn hsom(r: &StudyRow) -> &HeldOutSummary {
    &r.heldout.hsom
}

fn paired(r: &StudyRow) -> Option<(HeldOutSummary, HeldOutSummary)> {
    r.heldout.paired()
}

/// (CoSCo-HSOM, ProMP) over the folds where ProMP ran.
fn paired_promp(r: &StudyRow) -> Option<(HeldOutSummary, HeldOutSummary)> {
    r.heldout.paired_with(Method::ProMP)
}

fn columns(in_sample: bool) -> Vec<Column> {
    let mut c = vec![
        col(
            "joint DTW (rad/step)",
            4,
            vec![|r| Some(hsom(r).joint_dtw_rad_per_step)],
        ),
        col("wrist DTW (mm/step)", 1, vec![|r| hsom(r).wrist_dtw_mm]),
        col("apex (rad)", 3, vec![|r| Some(hsom(r).apex_error_rad)]),
        col("final (rad)", 3, vec![|r| Some(hsom(r).final_error_rad)]),
        col("duration ratio", 2, vec![|r| Some(hsom(r).duration_ratio)]),
        col(
            "reversals (rep / demos)",
            1,
            vec![|r| Some(hsom(r).velocity_reversals), |r| {
                Some(hsom(r).demo_velocity_reversals)
            }],
        ),
        col(
            "jerk ratio (rep / demos)",
            2,
            vec![|r| ratio(hsom(r).normalized_jerk, hsom(r).demo_normalized_jerk)],
        ),
        col(
            "LElbowRoll swings (rep / demo)",
            1,
            vec![|r| Some(hsom(r).swings), |r| Some(hsom(r).demo_swings)],
        ),
        col(
            "nearest-sequence joint DTW",
            4,
            vec![|r| {
                r.heldout
                    .sequence
                    .as_ref()
                    .map(|s| s.joint_dtw_rad_per_step)
            }],
        ),
        col(
            "nearest-sequence swings",
            1,
            vec![|r| r.heldout.sequence.as_ref().map(|s| s.swings)],
        ),
        col(
            "GMR joint DTW",
            4,
            vec![|r| paired(r).map(|(_, g)| g.joint_dtw_rad_per_step)],
        ),
        col(
            "GMR wrist DTW",
            1,
            vec![|r| paired(r).and_then(|(_, g)| g.wrist_dtw_mm)],
        ),
        col(
            "HSOM/GMR joint",
            2,
            vec![|r| {
                paired(r).and_then(|(h, g)| {
                    ratio(
                        Some(h.joint_dtw_rad_per_step),
                        Some(g.joint_dtw_rad_per_step),
                    )
                })
            }],
        ),
        col(
            "HSOM/GMR wrist",
            2,
            vec![|r| paired(r).and_then(|(h, g)| ratio(h.wrist_dtw_mm, g.wrist_dtw_mm))],
        ),
        col(
            "ProMP joint DTW",
            4,
            vec![|r| paired_promp(r).map(|(_, p)| p.joint_dtw_rad_per_step)],
        ),
        col(
            "HSOM/ProMP joint",
            2,
            vec![|r| {
                paired_promp(r).and_then(|(h, p)| {
                    ratio(
                        Some(h.joint_dtw_rad_per_step),
                        Some(p.joint_dtw_rad_per_step),
                    )
                })
            }],
        ),
        col(
            "ProMP jerk ratio (rep / demos)",
            2,
            vec![|r| {
                paired_promp(r).and_then(|(_, p)| ratio(p.normalized_jerk, p.demo_normalized_jerk))
            }],
        ),
        col(
            "DBA joint DTW",
            4,
            vec![|r| r.heldout.dba.as_ref().map(|d| d.joint_dtw_rad_per_step)],
        ),
        col(
            "DBA swings",
            1,
            vec![|r| r.heldout.dba.as_ref().map(|d| d.swings)],
        ),
    ];
    if in_sample {
        c.push(col(
            "in-sample joint DTW (HSOM / GMR)",
            4,
            vec![
                |r| {
                    r.in_sample
                        .as_ref()
                        .map(|s| s.hsom.joint_dtw_rad_per_step.mean)
                },
                |r| {
                    r.in_sample
                        .as_ref()
                        .and_then(|s| s.gmr.as_ref())
                        .map(|g| g.joint_dtw_rad_per_step.mean)
                },
            ],
        ));
        c.push(col(
            "in-sample wrist DTW (HSOM / GMR)",
            1,
            vec![
                |r| {
                    r.in_sample
                        .as_ref()
                        .and_then(|s| s.hsom.wrist_dtw_mm)
                        .map(|w| w.mean)
                },
                |r| {
                    r.in_sample
                        .as_ref()
                        .and_then(|s| s.gmr.as_ref())
                        .and_then(|g| g.wrist_dtw_mm)
                        .map(|w| w.mean)
                },
            ],
        ));
    }
    c
}

fn cell(c: &Column, rows: &[&StudyRow], median_of: bool) -> String {
    c.values
        .iter()
        .map(|f| {
            let v = if median_of {
                median(rows.iter().filter_map(|r| f(r)))
            } else {
                rows.first().and_then(|r| f(r))
            };
            number(v, c.digits)
        })
        .collect::<Vec<_>>()
        .join(" / ")
}

impl ConfigStudy {
    /// The held-out table: one row per (gesture, seed), the medians per gesture, the overall
    /// medians; CoSCo-HSOM's means over folds, GMM/GMR's and ProMP's on the same folds.
    pub fn table(&self, in_sample: bool) -> String {
        let cols = columns(in_sample);
        let mut t = Table::new(
            ["gesture", "seed"]
                .into_iter()
                .chain(cols.iter().map(|c| c.header)),
        );
        let mut line = |g: String, s: String, rows: &[&StudyRow], med: bool| {
            let cells = cols.iter().map(|c| cell(c, rows, med));
            t.row([g, s].into_iter().chain(cells));
        };
        for r in &self.rows {
            line(r.gesture.clone(), r.seed.to_string(), &[r], false);
        }
        let gestures = first_seen(self.rows.iter().map(|r| r.gesture.as_str()));
        for g in &gestures {
            let rows: Vec<&StudyRow> = self.rows.iter().filter(|r| r.gesture == *g).collect();
            line(format!("**{g}**"), "median".into(), &rows, true);
        }
        let all: Vec<&StudyRow> = self.rows.iter().collect();
        line("**all**".into(), "median".into(), &all, true);
        t.to_string()
    }

    /// Per-level accuracy of the hierarchies trained on the first demonstrations of each set:
    /// prediction accuracy / lookup-table accuracy for every level above the bottom.
    pub fn levels_table(&self) -> String {
        let height = self.rows.iter().map(|r| r.levels.len()).max().unwrap_or(0);
        let mut t = Table::new(
            ["gesture".to_string(), "seed".to_string()]
                .into_iter()
                .chain((1..height).map(|l| format!("L{l} prediction / lookup"))),
        );
        for r in &self.rows {
            let cells = (1..height).map(|l| {
                r.levels.get(l).map_or("n/a".into(), |l| {
                    let off = if l.used_in_reproduction {
                        ""
                    } else {
                        " (not used)"
                    };
                    format!(
                        "{:.2} / {:.2} (held out {:.2} / {:.2}){off}",
                        l.prediction_accuracy,
                        l.lookup_accuracy,
                        l.heldout_prediction_accuracy,
                        l.heldout_lookup_accuracy
                    )
                })
            });
            t.row(
                [r.gesture.clone(), r.seed.to_string()]
                    .into_iter()
                    .chain(cells),
            );
        }
        t.to_string()
    }
}
