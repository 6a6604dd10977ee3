//! The recognition study as Markdown and JSON (`cosco recognition`).

use std::fmt::Write as _;

use serde::Serialize;

use crate::eval::report::json_text;
use crate::table::Table;

use super::teaching::Forgetting;

use super::{fraction, Answer, Answers, RecognitionStudy, ACCEPT_GATE, UNKNOWN_GATE};

/// A fraction as a percentage, `-` when there is nothing to count.
fn pct(v: Option<f64>) -> String {
    v.map_or("-".to_string(), |v| format!("{:.1} %", 100.0 * v))
}

/// A fraction with its counts: `97.9 % (47 of 48)`.
fn counted(v: Option<f64>, n: usize) -> String {
    match v {
        Some(v) => format!(
            "{:.1} % ({} of {n})",
            100.0 * v,
            (v * n as f64).round() as usize
        ),
        None => "-".to_string(),
    }
}

/// The summary of one model's answers (what `--json` holds beside every answer).
#[derive(Debug, Serialize)]
struct AnswersSummary {
    accepted: Option<f64>,
    right_by_best: Option<f64>,
    unknown: Option<f64>,
    held_out: usize,
    untaught: usize,
    passes: bool,
}

impl AnswersSummary {
    fn of(a: &Answers) -> Self {
        AnswersSummary {
            accepted: a.accepted(),
            right_by_best: a.right_by_best(),
            unknown: a.unknown(),
            held_out: a.held_out.len(),
            untaught: a.untaught.len(),
            passes: a.passes(),
        }
    }
}

/// The recognition study's JSON document: the gates, each model's summary, what teaching one
/// gesture at a time forgot, and every answer.
#[derive(Debug, Serialize)]
struct RecognitionDocument<'a> {
    gates: Gates,
    summary: Summaries,
    forgetting: Vec<Forgetting>,
    study: &'a RecognitionStudy,
}

/// The gates the trained model must pass ([`ACCEPT_GATE`], [`UNKNOWN_GATE`]).
#[derive(Debug, Serialize)]
struct Gates {
    accepted: f64,
    unknown: f64,
}

/// The trained model's summary and the control's.
#[derive(Debug, Serialize)]
struct Summaries {
    model: AnswersSummary,
    control: Option<AnswersSummary>,
}

/// The study as a JSON document: the gates, each model's summary and every answer.
pub fn recognition_json(study: &RecognitionStudy) -> String {
    json_text(&RecognitionDocument {
        gates: Gates {
            accepted: ACCEPT_GATE,
            unknown: UNKNOWN_GATE,
        },
        summary: Summaries {
            model: AnswersSummary::of(&study.model),
            control: study.control.as_ref().map(AnswersSummary::of),
        },
        forgetting: super::teaching::forgetting(&study.taught, &study.reproduced),
        study,
    })
}

fn model_row(table: &mut Table, name: &str, a: &Answers) {
    table.row([
        name.to_string(),
        counted(a.accepted(), a.held_out.len()),
        pct(a.right_by_best()),
        counted(a.unknown(), a.untaught.len()),
        if a.passes() { "pass" } else { "fail" }.to_string(),
    ]);
}

/// The study as Markdown: the trained model beside the control against the gates, then per
/// gesture.
pub fn recognition_markdown(study: &RecognitionStudy) -> String {
    let mut out = String::new();
    let (m, c) = (&study.model, study.control.as_ref());
    let _ = writeln!(
        out,
        "Recognition held out: {} taught gestures (each demonstration recognised by the model \
         trained on all the others), {} untaught (recognised by the model trained on every \
         taught demonstration).{}\n",
        study.taught.len(),
        study.untaught.len(),
        if study.reproduced.is_empty() {
            ""
        } else {
            " Every trained model was taught one gesture after another, each update with that \
             gesture's demonstrations alone."
        }
    );
    let mut table = Table::new([
        "model".to_string(),
        format!("held-out accepted (gate {:.0} %)", 100.0 * ACCEPT_GATE),
        "lowest score right".to_string(),
        format!(
            "untaught called unknown (gate {:.0} %)",
            100.0 * UNKNOWN_GATE
        ),
        "gates".to_string(),
    ]);
    model_row(&mut table, "trained", m);
    if let Some(c) = c {
        model_row(&mut table, "untrained (control, must fail)", c);
    }
    let _ = writeln!(out, "{table}");
    let streams = |pick: usize| -> Vec<super::stream::Streamed> {
        (m.held_out.iter().chain(&m.untaught))
            .filter_map(|a| Some(a.streamed.as_ref()?[pick].clone()))
            .collect()
    };
    let rule = streams(0);
    if !rule.is_empty() {
        use super::stream::{StreamSummary, MARKDOWN_HEADER};
        let _ = writeln!(
            out,
            "Streamed (`--stream`): each demonstration above pushed a sample at a time into the \
             recogniser of the model that answered it (docs/ALGORITHM.md, section 4, item 7), \
             beside a recogniser that commits at the first sample (the control: it must fail \
             the wrong-commit gate).\n\n{MARKDOWN_HEADER}\n{}\n{}\n",
            StreamSummary::of(&rule).markdown_row("the rule"),
            StreamSummary::of(&streams(1)).markdown_row("first sample (control)"),
        );
    }
    let mut table = Table::new([
        "gesture",
        "taught",
        "demos",
        "accepted",
        "lowest score right",
        "called unknown",
        "another label",
        "control: accepted",
        "control: unknown",
    ]);
    // the answers of label `l` among `a`, and the percentage of them that are `right`
    let of = |a: &[Answer], l: &str| -> Vec<Answer> {
        a.iter().filter(|x| x.label == l).cloned().collect()
    };
    let share = |a: &[Answer], l: &str, right| pct(fraction(&of(a, l), right));
    let control = |f: &dyn Fn(&Answers) -> String| c.map_or("-".to_string(), f);
    for l in &study.taught {
        table.row([
            l.clone(),
            "yes".into(),
            of(&m.held_out, l).len().to_string(),
            share(&m.held_out, l, Answer::accepted),
            share(&m.held_out, l, Answer::right_by_best),
            share(&m.held_out, l, Answer::unknown),
            share(&m.held_out, l, Answer::other_label),
            control(&|c| share(&c.held_out, l, Answer::accepted)),
            control(&|c| share(&c.held_out, l, Answer::unknown)),
        ]);
    }
    for l in &study.untaught {
        table.row([
            l.clone(),
            "no".into(),
            of(&m.untaught, l).len().to_string(),
            "-".into(),
            "-".into(),
            share(&m.untaught, l, Answer::unknown),
            share(&m.untaught, l, Answer::other_label),
            "-".into(),
            control(&|c| share(&c.untaught, l, Answer::unknown)),
        ]);
    }
    out.push_str(&table.to_string());
    if !study.reproduced.is_empty() {
        forgetting_table(&mut out, study);
    }
    out
}

/// Taught one gesture at a time: per gesture, its held-out reproduction by the three models
/// of each fold and the forgetting gate.
fn forgetting_table(out: &mut String, study: &RecognitionStudy) {
    use super::teaching::{forgetting, FORGETTING_GATE};
    let r = &study.reproduced;
    let accepted = r.iter().filter(|x| x.at_once_accepted).count();
    let _ = writeln!(
        out,
        "\nTaught one at a time against taught at once: the held-out demonstrations' own \
         gesture reproduced from their first posture (relative DTW, median over the folds) by \
         the model taught every gesture at once, the model right after the gesture was taught \
         and the model after the last one (gate: after the last at most {FORGETTING_GATE} x \
         each of the others). The model taught at once accepted {}.\n",
        counted(Some(accepted as f64 / r.len() as f64), r.len())
    );
    let mut table = Table::new([
        "gesture",
        "folds",
        "at once",
        "right after taught",
        "after the last",
        "last / at once",
        "last / right after",
        "gate",
    ]);
    for f in forgetting(&study.taught, r) {
        table.row([
            f.label.to_string(),
            f.folds.to_string(),
            format!("{:.4}", f.at_once),
            format!("{:.4}", f.after_taught),
            format!("{:.4}", f.after_last),
            format!("{:.3}", f.against_at_once),
            format!("{:.3}", f.against_taught),
            if f.passes { "pass" } else { "fail" }.to_string(),
        ]);
    }
    out.push_str(&table.to_string());
}
