//! Recognition in the loop, held out ([`crate::hsom::Recognizer`]; docs/ALGORITHM.md,
//! section 4, item 7): each held-out demonstration of a taught gesture streamed one sample at
//! a time into a recogniser of the model taught the others, each demonstration of an untaught
//! gesture into the model taught without it; what was committed, when, and whether
//! `finish()` gave `recognize`'s answer. [`Policy::FirstSample`] is the negative control: a
//! recogniser that commits at the first sample, which the wrong-commit gate must refuse.

use serde::Serialize;

use crate::hsom::{GestureError, GestureModel, Recognizer};

/// The gate on taught streams: at least this fraction committed to their own label.
pub const RIGHT_COMMIT_GATE: f64 = 0.95;
/// The gate on the commit point: the median fraction of the gesture seen at the commit (a
/// stream never committed counts as the whole) at most this.
pub const COMMIT_POINT_GATE: f64 = 0.40;
/// The gate on taught streams: at most this fraction committed to another label or unknown.
pub const WRONG_COMMIT_GATE: f64 = 0.02;
/// The gate on untaught streams: at most this fraction committed to a label.
pub const UNTAUGHT_COMMIT_GATE: f64 = 0.05;

/// When a recogniser commits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Policy {
    /// The recogniser's rule ([`Recognizer`]).
    Rule,
    /// The negative control: at the first sample, to the label whose prefix scores lowest.
    FirstSample,
}

/// One stream.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Streamed {
    /// The gesture's label; `None` for an untaught gesture.
    pub expected: Option<String>,
    /// Whether it committed (in JSON, `committed` is null both for unknown and for nothing).
    pub decided: bool,
    /// What was committed (`Some(None)`: unknown), `None` when nothing was.
    pub committed: Option<Option<String>>,
    /// The samples pushed when it committed.
    pub at: Option<usize>,
    /// The samples in the stream.
    pub samples: usize,
    /// `finish()`'s label (`None`: unknown).
    pub finished: Option<String>,
    /// Whether `finish()` equalled `recognize` on the whole sequence.
    pub finish_is_recognize: bool,
}

impl Streamed {
    /// The fraction of the gesture seen at the commit (1 when it never committed).
    pub fn commit_point(&self) -> f64 {
        self.at
            .map_or(1.0, |a| a as f64 / self.samples.max(1) as f64)
    }
}

/// Stream `rows` into a recogniser of `model` (calibrated once: `calibration`) under
/// `policy`; `expected` is the gesture's label (`None`: untaught).
pub fn stream(
    model: &GestureModel,
    calibration: &crate::hsom::StreamCalibration,
    rows: &[Vec<f64>],
    expected: Option<&str>,
    policy: Policy,
) -> Result<Streamed, GestureError> {
    let mut r = Recognizer::new(model, calibration.clone())?;
    let mut committed: Option<Option<String>> = None;
    let mut at = None;
    for (i, row) in rows.iter().enumerate() {
        let c = r.push(row)?;
        if committed.is_some() {
            continue;
        }
        match policy {
            Policy::Rule => {
                if let Some(c) = c {
                    committed = Some(c.label);
                    at = Some(c.samples);
                }
            }
            Policy::FirstSample => {
                let s = r.prefix_scores();
                let best = crate::dtw::argmin(&s);
                let within = s[best] <= model.thresholds()[best];
                committed = Some(within.then(|| model.labels()[best].clone()));
                at = Some(i + 1);
            }
        }
    }
    let fin = r.finish()?;
    let whole = model.recognize(rows)?;
    Ok(Streamed {
        expected: expected.map(str::to_string),
        decided: committed.is_some(),
        committed,
        at,
        samples: rows.len(),
        finished: fin.label.clone(),
        finish_is_recognize: fin == whole,
    })
}

/// The figures of a set of streams against the gates.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StreamSummary {
    /// Streams of taught gestures.
    pub taught: usize,
    /// Of them, committed to their own label.
    pub right: usize,
    /// Of them, committed to another label or to unknown.
    pub wrong: usize,
    /// The median fraction of the gesture seen at the commit, taught streams (a stream never
    /// committed counts as 1).
    pub median_commit_point: f64,
    /// Streams of untaught gestures.
    pub untaught: usize,
    /// Of them, committed to a label.
    pub untaught_committed: usize,
    /// Of them, committed to unknown.
    pub untaught_unknown: usize,
    /// Streams whose `finish()` was not `recognize`'s answer.
    pub finish_differs: usize,
}

impl StreamSummary {
    /// The figures of `streams`.
    pub fn of(streams: &[Streamed]) -> Self {
        let taught: Vec<&Streamed> = streams.iter().filter(|s| s.expected.is_some()).collect();
        let untaught: Vec<&Streamed> = streams.iter().filter(|s| s.expected.is_none()).collect();
        let right = taught
            .iter()
            .filter(|s| s.committed.as_ref() == Some(&s.expected))
            .count();
        let wrong = taught
            .iter()
            .filter(|s| s.committed.as_ref().is_some_and(|c| *c != s.expected))
            .count();
        let mut points: Vec<f64> = taught.iter().map(|s| s.commit_point()).collect();
        points.sort_by(f64::total_cmp);
        let median = match points.len() {
            0 => f64::NAN,
            n if n % 2 == 1 => points[n / 2],
            n => (points[n / 2 - 1] + points[n / 2]) / 2.0,
        };
        StreamSummary {
            taught: taught.len(),
            right,
            wrong,
            median_commit_point: median,
            untaught: untaught.len(),
            untaught_committed: untaught
                .iter()
                .filter(|s| matches!(s.committed, Some(Some(_))))
                .count(),
            untaught_unknown: untaught
                .iter()
                .filter(|s| matches!(s.committed, Some(None)))
                .count(),
            finish_differs: streams.iter().filter(|s| !s.finish_is_recognize).count(),
        }
    }

    /// `part / whole` (0 of none).
    fn rate(part: usize, whole: usize) -> f64 {
        part as f64 / whole.max(1) as f64
    }

    /// The gates that fail, named (empty: all pass).
    pub fn failures(&self) -> Vec<String> {
        let mut f = Vec::new();
        let right = Self::rate(self.right, self.taught);
        if right < RIGHT_COMMIT_GATE {
            f.push(format!("right commits {right:.3} < {RIGHT_COMMIT_GATE}"));
        }
        if self.median_commit_point > COMMIT_POINT_GATE {
            f.push(format!(
                "median commit point {:.3} > {COMMIT_POINT_GATE}",
                self.median_commit_point
            ));
        }
        let wrong = Self::rate(self.wrong, self.taught);
        if wrong > WRONG_COMMIT_GATE {
            f.push(format!("wrong commits {wrong:.3} > {WRONG_COMMIT_GATE}"));
        }
        let untaught = Self::rate(self.untaught_committed, self.untaught);
        if untaught > UNTAUGHT_COMMIT_GATE {
            f.push(format!(
                "untaught committed to a label {untaught:.3} > {UNTAUGHT_COMMIT_GATE}"
            ));
        }
        if self.finish_differs > 0 {
            f.push(format!(
                "finish() differs from recognize on {} streams",
                self.finish_differs
            ));
        }
        f
    }

    /// One Markdown table row: `name`, then the figures.
    pub fn markdown_row(&self, name: &str) -> String {
        format!(
            "| {name} | {:.1} % ({} of {}) | {:.3} | {:.1} % ({}) | {:.1} % ({} of {}) | {} |",
            100.0 * Self::rate(self.right, self.taught),
            self.right,
            self.taught,
            self.median_commit_point,
            100.0 * Self::rate(self.wrong, self.taught),
            self.wrong,
            100.0 * Self::rate(self.untaught_committed, self.untaught),
            self.untaught_committed,
            self.untaught,
            self.finish_differs,
        )
    }
}

/// The header of [`StreamSummary::markdown_row`]'s table.
pub const MARKDOWN_HEADER: &str = "| recogniser | committed right (gate 95 %) | median commit point (gate 0.40) | wrong commits (gate 2 %) | untaught committed to a label (gate 5 %) | finish() not recognize |\n|---|---|---|---|---|---|";
