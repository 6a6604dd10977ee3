//! Recognition held out (`eval::recognition`, `cosco recognition`) on small 2-D gestures:
//! each taught demonstration, recognised by the hierarchy trained on all the others, is
//! accepted; untaught gestures are called unknown; the untrained hierarchy (the negative
//! control) fails the gates; bad input is refused naming the label, file or directory.

use std::path::Path;

use assert_cmd::Command;
use predicates::prelude::*;
use rand::{Rng, SeedableRng};

use cosco_hsom::demos::{write_csv, Demonstration};
use cosco_hsom::eval::recognition::{
    recognition_json, recognition_markdown, recognition_study, RecognitionSettings, ACCEPT_GATE,
    UNKNOWN_GATE,
};
use cosco_hsom::eval::LooError;

use crate::hsom_common;
use hsom_common::{apex_config, apex_demo};

/// A LASA-like stroke: hold at a start on the unit circle (at `angle` degrees), move to the
/// origin along a path bent sideways by `bend` (a fraction of the radius), hold; `seed`
/// varies the holds, the speed, the size, the bend and the pen noise.
fn stroke(angle: f64, bend: f64, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let hold = 20 + rng.gen_range(0..10);
    let n = 80 + rng.gen_range(0..20);
    let size = 1.0 + rng.gen_range(-0.05..0.05);
    let bend = bend * (1.0 + rng.gen_range(-0.1..0.1));
    let (c, s) = (angle.to_radians().cos(), angle.to_radians().sin());
    (0..2 * hold + n)
        .map(|i| {
            let u = ((i as f64 - hold as f64) / n as f64).clamp(0.0, 1.0);
            let side = bend * (std::f64::consts::PI * u).sin();
            vec![
                size * (c * (1.0 - u) - s * side) + 0.002 * rng.gen::<f64>(),
                size * (s * (1.0 - u) + c * side) + 0.002 * rng.gen::<f64>(),
            ]
        })
        .collect()
}

/// Taught gestures, two pairs that share their start and end: (label, start angle, bend).
const TAUGHT: [(&str, f64, f64); 4] = [
    ("down", 90.0, 0.0),
    ("down_arc", 90.0, 0.3),
    ("left", 0.0, 0.0),
    ("left_arc", 0.0, -0.3),
];

/// Gestures never taught: the same starts, bent the other way.
const UNTAUGHT: [(&str, f64, f64); 2] =
    [("down_other_arc", 90.0, -0.3), ("left_other_arc", 0.0, 0.3)];

/// `n` demonstrations (seeds 10, 11, ...) of each gesture.
fn labelled(gestures: &[(&str, f64, f64)], n: u64) -> Vec<(String, Vec<Demonstration>)> {
    gestures
        .iter()
        .map(|&(l, angle, bend)| {
            let demos = (10..10 + n)
                .map(|s| apex_demo(&format!("{l}/demo{s}.csv"), stroke(angle, bend, s)))
                .collect();
            (l.to_string(), demos)
        })
        .collect()
}

fn settings() -> RecognitionSettings {
    RecognitionSettings {
        control: true,
        threads: 2,
        ..RecognitionSettings::default()
    }
}

#[test]
fn held_out_demonstrations_are_accepted_untaught_ones_unknown_and_the_untrained_control_fails() {
    let taught = labelled(&TAUGHT, 4);
    let untaught = labelled(&UNTAUGHT, 3);
    let s = recognition_study(&apex_config(), &taught, &untaught, &settings(), None).unwrap();
    assert_eq!(s.taught, ["down", "down_arc", "left", "left_arc"]);
    assert_eq!(s.untaught, ["down_other_arc", "left_other_arc"]);
    let m = &s.model;
    assert_eq!((m.held_out.len(), m.untaught.len()), (16, 6));
    let report = recognition_markdown(&s);
    // every held-out demonstration of a taught gesture: its own label, not unknown
    for a in &m.held_out {
        assert_eq!(
            a.answer.as_deref(),
            Some(a.label.as_str()),
            "{a:?}\n{report}"
        );
        assert!(a.best_score <= a.threshold, "{a:?}");
    }
    // every untaught one: unknown
    for a in &m.untaught {
        assert_eq!(a.answer, None, "{a:?}\n{report}");
    }
    assert!(m.accepted().unwrap() >= ACCEPT_GATE && m.right_by_best() == Some(1.0));
    assert!(m.unknown().unwrap() >= UNKNOWN_GATE);
    assert!(m.passes(), "{report}");
    // the negative control: the untrained hierarchy, calibrated the same way, fails
    let c = s.control.as_ref().unwrap();
    assert_eq!((c.held_out.len(), c.untaught.len()), (16, 6));
    assert!(!c.passes(), "the untrained control passes:\n{report}");
    // the report and the JSON say the same
    assert!(
        report.contains("| trained | 100.0 % (16 of 16) |"),
        "{report}"
    );
    assert!(
        report.contains("| untrained (control, must fail) |"),
        "{report}"
    );
    let doc: serde_json::Value = serde_json::from_str(&recognition_json(&s)).unwrap();
    assert_eq!(doc["summary"]["model"]["passes"], true);
    assert_eq!(doc["summary"]["control"]["passes"], false);
    assert_eq!(
        doc["study"]["model"]["held_out"].as_array().unwrap().len(),
        16
    );
}

#[test]
fn gestures_taught_one_at_a_time_are_recognised_and_not_forgotten_unlike_a_retraining_on_the_new_files_alone(
) {
    use cosco_hsom::eval::recognition::teaching::{forgetting, Reproduced};
    let taught = labelled(&TAUGHT, 4);
    let untaught = labelled(&UNTAUGHT, 3);
    let settings = RecognitionSettings {
        control: false,
        one_at_a_time: true,
        threads: 2,
        stream: false,
    };
    let cfg = apex_config();
    let s = recognition_study(&cfg, &taught, &untaught, &settings, None).unwrap();
    let report = recognition_markdown(&s);
    assert!(s.model.accepted().unwrap() >= ACCEPT_GATE, "{report}");
    assert!(s.model.unknown().unwrap() >= UNKNOWN_GATE, "{report}");
    // every held-out demonstration's gesture reproduced by the three models of its fold
    assert_eq!(s.reproduced.len(), 16);
    let gates = forgetting(&s.taught, &s.reproduced);
    assert_eq!(gates.len(), 4);
    for f in &gates {
        assert!(f.passes, "{f:?}\n{report}");
    }
    assert!(report.contains("| down | 4 |"), "{report}");
    // the negative control: the last "update" a training from scratch on the last gesture's
    // files alone; every earlier gesture, reproduced from its held-out start by what that
    // model knows, is forgotten
    let (last, _) = taught.last().unwrap();
    let alone = cfg
        .fit_model(
            &taught[taught.len() - 1..],
            cosco_hsom::hsom::Fit::default(),
        )
        .unwrap();
    let control: Vec<Reproduced> = (s.reproduced.iter())
        .filter(|r| r.label != *last)
        .map(|r| {
            let (_, demos) = taught.iter().find(|(l, _)| *l == r.label).unwrap();
            let held = demos.iter().find(|d| d.source == r.demonstration).unwrap();
            let rep = alone
                .branch(Some(last))
                .and_then(|b| Ok(b.reproduce(&held.rows[0])?))
                .unwrap();
            let diag = cosco_hsom::eval::diagonal(demos);
            let d = cosco_hsom::dtw::dtw_distance(
                &rep.postures,
                &held.rows,
                cosco_hsom::dtw::Band::None,
            );
            Reproduced {
                after_last: d.unwrap().per_step() / diag,
                ..r.clone()
            }
        })
        .collect();
    let taught_labels: Vec<String> = s.taught.iter().filter(|l| *l != last).cloned().collect();
    for f in forgetting(&taught_labels, &control) {
        assert!(
            !f.passes,
            "retrained on the new files alone, {} is not forgotten: {f:?}",
            f.label
        );
    }
}

#[test]
fn the_study_refuses_bad_input_naming_the_label_or_file() {
    let cfg = apex_config();
    let run = |taught: &[(String, Vec<Demonstration>)],
               untaught: &[(String, Vec<Demonstration>)],
               settings: RecognitionSettings| {
        recognition_study(&cfg, taught, untaught, &settings, None).unwrap_err()
    };
    let no_control = RecognitionSettings {
        control: false,
        threads: 1,
        ..RecognitionSettings::default()
    };
    assert!(matches!(run(&[], &[], no_control), LooError::NoTaught));
    // too few to hold one out and still calibrate held out
    let mut few = labelled(&TAUGHT[..2], 3);
    few[1].1.truncate(2);
    let e = run(&few, &[], no_control).to_string();
    assert!(
        e.contains("'down_arc'") && e.contains("at least 3") && e.contains("got 2"),
        "{e}"
    );
    // a label both taught and untaught
    let taught = labelled(&TAUGHT[..2], 3);
    let e = run(&taught, &labelled(&TAUGHT[1..2], 1), no_control).to_string();
    assert!(
        e.contains("'down_arc'") && e.contains("taught and untaught"),
        "{e}"
    );
    // an untaught demonstration of other columns: named
    let mut wide = labelled(&UNTAUGHT[..1], 1);
    wide[0].1[0].columns.push("x2".into());
    wide[0].1[0].rows.iter_mut().for_each(|r| r.push(0.0));
    let e = run(&taught, &wide, no_control).to_string();
    assert!(
        e.contains("down_other_arc/demo10.csv") && e.contains("x2"),
        "{e}"
    );
    // a label that is not a plain word
    let mut bad = taught.clone();
    bad[0].0 = "two words".into();
    let e = run(&bad, &[], no_control).to_string();
    assert!(
        e.contains("\"two words\"") && e.contains("plain word"),
        "{e}"
    );
    // no threads
    let e = run(
        &taught,
        &[],
        RecognitionSettings {
            control: false,
            threads: 0,
            ..RecognitionSettings::default()
        },
    );
    assert!(e.to_string().contains("threads = 0"), "{e}");
}

fn write_label(root: &Path, (label, angle, bend): (&str, f64, f64), n: u64) {
    let d = root.join(label);
    std::fs::create_dir_all(&d).unwrap();
    for s in 10..10 + n {
        let demo = apex_demo("", stroke(angle, bend, s));
        write_csv(&d.join(format!("demo_{s}.csv")), &demo).unwrap();
    }
}

/// `cosco heldout --recognition` runs the study; `cosco recognition`, its hidden alias for
/// scripts, runs the same code (the bad inputs below) and is not listed in `--help`.
#[test]
fn cosco_heldout_recognition_runs_on_directories_and_names_bad_ones() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("c.xml");
    std::fs::write(&cfg, apex_config().to_xml()).unwrap();
    let taught = dir.path().join("taught");
    write_label(&taught, TAUGHT[0], 3);
    write_label(&taught, TAUGHT[2], 3);
    let other = dir.path().join(UNTAUGHT[0].0);
    write_label(dir.path(), UNTAUGHT[0], 2);
    let json = dir.path().join("r.json");
    let study = |verb: &[&str]| {
        let mut c = Command::cargo_bin("cosco").unwrap();
        c.args(verb).arg("--config").arg(&cfg);
        c
    };
    let cosco = || study(&["recognition"]);
    Command::cargo_bin("cosco")
        .unwrap()
        .arg("--help")
        .assert()
        .success()
        .stdout(predicate::function(|out: &str| {
            let verbs: Vec<&str> = out
                .lines()
                .filter_map(|l| l.split_whitespace().next())
                .collect();
            verbs.contains(&"heldout") && !verbs.contains(&"recognition")
        }));
    // a directory of label subdirectories taught, a directory of CSV files untaught
    study(&["heldout", "--recognition"])
        .arg("--taught")
        .arg(&taught)
        .arg("--untaught")
        .arg(&other)
        .args(["--no-control", "--threads", "2", "--json"])
        .arg(&json)
        .assert()
        .success()
        .stdout(
            predicate::str::contains("2 taught gestures")
                .and(predicate::str::contains("| down_other_arc | no | 2 |"))
                .and(predicate::str::contains("| trained |")),
        );
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(doc["study"]["untaught"][0], "down_other_arc");
    assert!(doc["study"]["control"].is_null());
    // a file where a directory is needed; a directory that does not exist
    let file = other.join("demo_10.csv");
    cosco()
        .arg("--taught")
        .arg(&file)
        .assert()
        .failure()
        .stderr(
            predicate::str::contains("demo_10.csv")
                .and(predicate::str::contains("not a directory")),
        );
    cosco()
        .arg("--taught")
        .arg(dir.path().join("missing"))
        .assert()
        .failure()
        .stderr(predicate::str::contains("missing"));
    // an untaught gesture of two demonstrations is fine, a taught one is too few
    cosco()
        .arg("--taught")
        .arg(&other)
        .assert()
        .failure()
        .stderr(
            predicate::str::contains("'down_other_arc'")
                .and(predicate::str::contains("at least 3")),
        );
}

/// With `stream`: every demonstration is also streamed into the recogniser of the model that
/// answered it; under the rule no taught one is committed to another label, most to their own,
/// and `finish()` is `recognize`; the recogniser that commits at the first sample (the control)
/// fails the wrong-commit gate; the report has the table.
#[test]
fn streamed_the_rule_commits_rightly_and_the_first_sample_control_fails() {
    use cosco_hsom::eval::recognition::stream::StreamSummary;
    let taught = labelled(&TAUGHT, 4);
    let untaught = labelled(&UNTAUGHT, 3);
    let settings = RecognitionSettings {
        control: false,
        threads: 2,
        stream: true,
        ..RecognitionSettings::default()
    };
    let s = recognition_study(&apex_config(), &taught, &untaught, &settings, None).unwrap();
    let all: Vec<_> = s.model.held_out.iter().chain(&s.model.untaught).collect();
    let pick = |i: usize| -> Vec<_> {
        (all.iter())
            .map(|a| a.streamed.as_ref().expect("streamed")[i].clone())
            .collect()
    };
    let (rule, first) = (StreamSummary::of(&pick(0)), StreamSummary::of(&pick(1)));
    assert_eq!((rule.taught, rule.untaught), (16, 6));
    assert_eq!(rule.finish_differs, 0);
    assert_eq!(rule.wrong, 0, "{rule:?}");
    // on these near shapes, which share their start and their end in pairs, it holds until
    // the pair parts (the other of a pair stands in for a shape never seen) and until the
    // stroke is within its label's own held-out prefixes: it commits rightly to 7 of 16,
    // never wrongly, and to no untaught stroke (0 of 6)
    assert!(rule.right * 16 >= rule.taught * 7, "{rule:?}");
    assert_eq!(rule.untaught_committed, 0, "{rule:?}");
    let failed = first.failures();
    assert!(
        failed.iter().any(|f| f.starts_with("wrong commits")),
        "{first:?}"
    );
    let report = recognition_markdown(&s);
    assert!(report.contains("Streamed (`--stream`)"), "{report}");
    assert!(report.contains("| first sample (control) |"), "{report}");
}
