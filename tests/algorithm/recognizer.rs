//! Recognition in the loop (`hsom::Recognizer`, `cosco recognize --stream`) on the small 2-D
//! gestures of tests/multi_gesture.rs: `finish()` is `recognize` on every stream, a committed
//! answer never changes, taught gestures are committed to before their end and rightly,
//! untaught ones are not committed to a label; the negative control (a recogniser that
//! commits at the first sample) fails the wrong-commit gate. Through `cosco`: the commit line
//! and the whole answer from standard input, bad input refused naming its line and column.

use cosco_hsom::demos::write_csv;
use cosco_hsom::eval::recognition::stream::{stream, Policy, StreamSummary, WRONG_COMMIT_GATE};
use cosco_hsom::hsom::GestureModel;

use crate::hsom_common;
use hsom_common::{
    apex_config as config, apex_demo as demo, apex_gesture as gesture, apex_sets as sets, APEXES,
};

/// New demonstrations (seeds 100-107) of each of `labels`, as `(label, rows)`.
fn new_streams(labels: &[(&str, [f64; 2])]) -> Vec<(String, Vec<Vec<f64>>)> {
    labels
        .iter()
        .flat_map(|(l, a)| (100..108).map(move |s| (l.to_string(), gesture(*a, s))))
        .collect()
}

#[test]
fn the_recogniser_commits_early_never_changes_and_finishes_as_recognize() {
    let m = config()
        .fit_model(&sets(&APEXES), cosco_hsom::hsom::Fit::default())
        .unwrap();
    let cal = m.stream_calibration().unwrap();
    assert!(
        cal.rise.iter().all(|r| r.is_finite()) && cal.rise[0] >= 1.0,
        "{cal:?}"
    );
    assert!(cal.rise.windows(2).all(|w| w[0] >= w[1]), "{cal:?}");
    for (label, rows) in new_streams(&APEXES) {
        let mut r = m.recognizer().unwrap();
        let mut first = None;
        for (i, row) in rows.iter().enumerate() {
            let c = r.push(row).unwrap();
            assert_eq!(r.decided(), c.is_some());
            match (&first, c) {
                (None, Some(c)) => {
                    assert_eq!(c.samples, i + 1, "committed on this sample");
                    first = Some(c);
                }
                (Some(f), c) => assert_eq!(c.as_ref(), Some(f), "a commitment never changes"),
                (None, None) => {}
            }
        }
        let c = first.unwrap_or_else(|| panic!("{label}: never committed"));
        assert_eq!(c.label.as_deref(), Some(label.as_str()));
        assert!(c.samples < rows.len(), "{label}: committed at the end");
        assert_eq!(r.finish().unwrap(), m.recognize(&rows).unwrap());
    }
}

#[test]
fn the_prefix_scores_are_recognitions_and_bad_samples_are_refused() {
    let m = config()
        .fit_model(&sets(&APEXES[..2]), cosco_hsom::hsom::Fit::default())
        .unwrap();
    let rows = gesture(APEXES[0].1, 100);
    let mut r = m.recognizer().unwrap();
    // fewer than 2 samples: refused as recognize refuses them
    assert!(r.finish().is_err());
    for row in &rows {
        r.push(row).unwrap();
    }
    // the last prefix's scores are the open-ended scores recognize reads
    let scores = r.prefix_scores();
    assert_eq!(scores.len(), 2);
    assert!(scores.iter().all(|s| s.is_finite()), "{scores:?}");
    // a wrong width or a value that is not finite is refused, naming the sample, and the
    // recogniser goes on as it was
    let e = r.push(&[0.0]).unwrap_err().to_string();
    assert!(
        e.contains("the stream") && e.contains(&rows.len().to_string()),
        "{e}"
    );
    let e = r.push(&[0.0, f64::NAN]).unwrap_err().to_string();
    assert!(e.contains("the stream"), "{e}");
    assert_eq!(r.samples(), rows.len());
    assert_eq!(r.finish().unwrap(), m.recognize(&rows).unwrap());
}

/// The study's figures on `model` for `streams` (`None`: untaught) under `policy`.
fn summary(
    model: &GestureModel,
    streams: &[(Option<String>, Vec<Vec<f64>>)],
    policy: Policy,
) -> StreamSummary {
    let c = model.stream_calibration().unwrap();
    let s: Vec<_> = streams
        .iter()
        .map(|(e, rows)| stream(model, &c, rows, e.as_deref(), policy).unwrap())
        .collect();
    StreamSummary::of(&s)
}

#[test]
fn untaught_gestures_are_not_committed_to_and_committing_at_once_fails_the_gate() {
    let all = config()
        .fit_model(&sets(&APEXES), cosco_hsom::hsom::Fit::default())
        .unwrap();
    let taught: Vec<_> = new_streams(&APEXES)
        .into_iter()
        .map(|(l, r)| (Some(l), r))
        .collect();
    let rule = summary(&all, &taught, Policy::Rule);
    assert_eq!(rule.right, rule.taught, "{rule:?}");
    assert_eq!(rule.wrong, 0, "{rule:?}");
    assert!(rule.median_commit_point < 0.9, "{rule:?}");
    assert_eq!(rule.finish_differs, 0);
    // negative control: committing at the first sample, before the gestures part
    let first = summary(&all, &taught, Policy::FirstSample);
    let wrong = first.wrong as f64 / first.taught as f64;
    assert!(wrong > WRONG_COMMIT_GATE, "{first:?}");
    assert!(first
        .failures()
        .iter()
        .any(|f| f.starts_with("wrong commits")));
    // a gesture never taught: committed to no label
    let two = config()
        .fit_model(&sets(&APEXES[..2]), cosco_hsom::hsom::Fit::default())
        .unwrap();
    let untaught: Vec<_> = new_streams(&APEXES[2..])
        .into_iter()
        .map(|(_, r)| (None, r))
        .collect();
    let u = summary(&two, &untaught, Policy::Rule);
    assert_eq!(u.untaught_committed, 0, "{u:?}");
    assert_eq!(u.finish_differs, 0);
}

use crate::common::cosco;

#[test]
fn cosco_recognize_stream_prints_the_commit_and_the_whole_answer() {
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("m.bin");
    config()
        .fit_model(&sets(&APEXES), cosco_hsom::hsom::Fit::default())
        .unwrap()
        .save(&model)
        .unwrap();
    let mut d = demo("right", gesture(APEXES[1].1, 100));
    d.time = Some((0..d.rows.len()).map(|i| i as f64 * 0.025).collect());
    let file = dir.path().join("right.csv");
    write_csv(&file, &d).unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    let whole = cosco()
        .args(["recognize", "--model"])
        .arg(&model)
        .arg("--demos")
        .arg(&file)
        .output()
        .unwrap();
    let whole = String::from_utf8(whole.stdout).unwrap();
    let out = cosco()
        .args(["recognize", "--model"])
        .arg(&model)
        .arg("--stream")
        .write_stdin(text.clone())
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let out = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}");
    assert!(
        lines[0].starts_with("sample ")
            && lines[0].contains(" time ")
            && lines[0].ends_with(" s: right"),
        "{out}"
    );
    // the whole answer: `cosco recognize`'s line for the file, read from standard input
    let file_line = whole.lines().next().unwrap();
    let name = file.display().to_string();
    assert_eq!(
        lines[1].strip_prefix("standard input"),
        file_line.strip_prefix(name.as_str()),
        "{out}\n{whole}"
    );
    // bad input: named by line and column
    let bad = |input: String, says: &[&str]| {
        let out = cosco()
            .args(["recognize", "--model"])
            .arg(&model)
            .arg("--stream")
            .write_stdin(input)
            .output()
            .unwrap();
        assert!(!out.status.success());
        let err = String::from_utf8(out.stderr).unwrap();
        for s in says {
            assert!(err.contains(s), "{err} should say {s}");
        }
    };
    let mut head = text.lines();
    let header = head.next().unwrap().to_string();
    let row1 = head.next().unwrap().to_string();
    bad(
        format!("{}\n{row1}\n", header.replace("x1", "y")),
        &["line 1", "\"y\""],
    );
    bad(
        format!("{header}\n{row1}\n0.05,1,zz\n"),
        &["line 3", "x1", "zz"],
    );
    bad(
        format!("{header}\n{row1}\n0.05,1\n"),
        &["line 3", "2 cells", "3"],
    );
    bad(format!("{header}\n{row1}\n0,1,1\n"), &["line 3", "time"]);
    bad(format!("{header}\n{row1}\n"), &["at least 2"]);
}

/// A stroke tilted off a taught one follows it far enough for the other label to be ruled
/// out and for its hold to pass; the envelope (how far the label's own held-out
/// demonstrations were from it that far in) keeps the recogniser from committing to it. The
/// negative control: the same calibration with no envelope commits those strokes.
#[test]
fn a_stroke_tilted_off_a_taught_one_is_not_committed_to_it() {
    let two = config()
        .fit_model(&sets(&APEXES[..2]), cosco_hsom::hsom::Fit::default())
        .unwrap();
    let c = two.stream_calibration().unwrap();
    assert!(c.envelope.iter().flatten().all(|e| e.is_finite()), "{c:?}");
    let tilted: Vec<_> = [[0.4, 1.0], [1.0, 0.3]]
        .into_iter()
        .flat_map(|apex| (100..104).map(move |s| gesture(apex, s)))
        .collect();
    let committed = |c: &cosco_hsom::hsom::StreamCalibration| {
        (tilted.iter())
            .map(|rows| stream(&two, c, rows, None, Policy::Rule).unwrap())
            .filter(|s| matches!(s.committed, Some(Some(_))))
            .count()
    };
    assert_eq!(committed(&c), 0);
    let mut open = c.clone();
    open.envelope = vec![vec![f64::INFINITY; c.rise.len()]; 2];
    assert_eq!(committed(&open), tilted.len());
}
