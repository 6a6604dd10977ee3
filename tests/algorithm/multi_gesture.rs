//! Several gestures in one hierarchy, on small 2-D gestures that train in well
//! under a second: recognition held out beside its negative controls (shuffled labels, an
//! unknown gesture), reproduction on cue, save and load (a single-gesture file still loads
//! as one gesture), and bad input through `cosco` with errors naming the directory or label.

use std::path::Path;

use cosco_hsom::demos::{write_csv, Demonstration};
use cosco_hsom::hsom::{GestureError, GestureModel, Scoring, GESTURES_FORMAT_VERSION};
use predicates::prelude::*;

use crate::hsom_common;
use hsom_common::{
    apex_config as config, apex_demo as demo, apex_gesture as gesture, apex_sets as sets, APEXES,
};

/// Held-out accuracy of `model` over 4 new demonstrations of each of `labels`.
fn accuracy(model: &GestureModel, labels: &[(&str, [f64; 2])]) -> f64 {
    let mut ok = 0;
    for (l, a) in labels {
        for s in 100..104 {
            let r = model.recognize(&gesture(*a, s)).unwrap();
            ok += usize::from(r.label.as_deref() == Some(*l));
        }
    }
    ok as f64 / (4 * labels.len()) as f64
}

#[test]
fn held_out_gestures_are_recognised_and_shuffled_labels_are_not() {
    let m = config()
        .fit_model(&sets(&APEXES), cosco_hsom::hsom::Fit::default())
        .unwrap();
    assert_eq!(m.labels(), ["up", "right", "diag"]);
    let acc = accuracy(&m, &APEXES);
    assert!(acc >= 0.95, "held-out accuracy {acc}");
    // early: the decision is final before the end of the gesture
    let r = m.recognize(&gesture(APEXES[1].1, 200)).unwrap();
    assert!(r.decided_fraction() < 0.9, "{r:?}");
    // negative control: the same demonstrations with their labels shuffled
    // (each label gets one demonstration of every gesture)
    let all: Vec<Demonstration> = sets(&APEXES).into_iter().flat_map(|(_, d)| d).collect();
    let shuffled: Vec<(String, Vec<Demonstration>)> = APEXES
        .iter()
        .enumerate()
        .map(|(i, (l, _))| {
            (
                l.to_string(),
                (0..3).map(|j| all[j * 3 + i].clone()).collect(),
            )
        })
        .collect();
    let ms = config()
        .fit_model(&shuffled, cosco_hsom::hsom::Fit::default())
        .unwrap();
    let acc = accuracy(&ms, &APEXES);
    assert!(acc < 0.95, "shuffled labels: {acc}");
}

#[test]
fn a_gesture_never_taught_is_unknown_and_the_taught_ones_are_not() {
    let taught = &APEXES[..2];
    let m = config()
        .fit_model(&sets(taught), cosco_hsom::hsom::Fit::default())
        .unwrap();
    for s in 100..104 {
        let r = m.recognize(&gesture(APEXES[2].1, s)).unwrap();
        assert_eq!(r.label, None, "{r:?}");
    }
    assert!(accuracy(&m, taught) >= 0.95);
}

/// A gesture that only goes part of the way along a taught one's path (up to half the apex
/// and back, or up and staying there) is not that gesture: the reproduction from its start
/// goes all the way, so it scores far above new demonstrations of the taught one and is
/// `unknown`. The control: the nearest-posture score cannot tell them apart, since every
/// sample lies on the taught path.
#[test]
fn part_of_a_taught_path_is_unknown() {
    let taught = &APEXES[..2];
    let m = config()
        .fit_model(&sets(taught), cosco_hsom::hsom::Fit::default())
        .unwrap();
    let by_postures = m.clone().with_scoring(Scoring::Postures);
    let up = |model: &GestureModel, rows: &[Vec<f64>]| model.scores(rows).unwrap()[0];
    let new_up: Vec<Vec<Vec<f64>>> = (100..104).map(|s| gesture(APEXES[0].1, s)).collect();
    let worst = |model: &GestureModel| new_up.iter().map(|g| up(model, g)).fold(0.0, f64::max);
    let half = gesture([0.0, 0.5], 7);
    let mut one_way = gesture(APEXES[0].1, 8);
    let back = one_way.len() - (one_way.len() - 40) / 3 - 40;
    let top = one_way[back - 1].clone();
    one_way[back..].iter_mut().for_each(|r| *r = top.clone());
    for part in [&half, &one_way] {
        let r = m.recognize(part).unwrap();
        assert_eq!(r.label, None, "{r:?}");
        assert!(
            up(&m, part) > 3.0 * worst(&m),
            "{} vs {}",
            up(&m, part),
            worst(&m)
        );
        assert!(
            up(&by_postures, part) < 1.5 * worst(&by_postures),
            "the control: {} vs {}",
            up(&by_postures, part),
            worst(&by_postures)
        );
    }
    for g in &new_up {
        assert_eq!(m.recognize(g).unwrap().label.as_deref(), Some("up"));
    }
}

#[test]
fn the_label_chooses_the_gesture_reproduced_and_is_required() {
    let m = config()
        .fit_model(&sets(&APEXES), cosco_hsom::hsom::Fit::default())
        .unwrap();
    for (l, a) in APEXES {
        let rep = m
            .branch(Some(l))
            .and_then(|b| Ok(b.reproduce(&[0.0, 0.0])?))
            .unwrap();
        let far = rep
            .postures
            .iter()
            .max_by(|p, q| (p[0].hypot(p[1])).total_cmp(&q[0].hypot(q[1])))
            .unwrap();
        let d = (far[0] - a[0]).hypot(far[1] - a[1]);
        assert!(d < 0.25, "{l}: apex {far:?} vs {a:?}");
    }
    match m.branch(None).and_then(|b| Ok(b.reproduce(&[0.0, 0.0])?)) {
        Err(e @ GestureError::LabelNeeded { .. }) => {
            let t = e.to_string();
            assert!(t.contains("up, right, diag"), "{t}");
        }
        other => panic!("{other:?}"),
    }
    match m
        .branch(Some("wave"))
        .and_then(|b| Ok(b.reproduce(&[0.0, 0.0])?))
    {
        Err(e @ GestureError::UnknownLabel { .. }) => assert!(e.to_string().contains("\"wave\"")),
        other => panic!("{other:?}"),
    }
    // continuing a prefix: the hierarchy tells which gesture it is
    let g = gesture(APEXES[1].1, 300);
    let (label, rep) = m.continue_prefix(&g[..60]).unwrap();
    assert_eq!(label, "right");
    assert_eq!(rep.postures[..60], g[..60]);
    assert!(rep.postures.len() > 80);
}

#[test]
fn save_and_load_keep_the_model_and_its_size_does_not_grow_with_the_demonstrations() {
    let dir = tempfile::tempdir().unwrap();
    let m = config()
        .fit_model(&sets(&APEXES), cosco_hsom::hsom::Fit::default())
        .unwrap();
    for ext in ["bin", "txt"] {
        let p = dir.path().join(format!("m.{ext}"));
        m.save(&p).unwrap();
        assert_eq!(GestureModel::load(&p).unwrap(), m, "{ext}");
    }
    let bytes = std::fs::read(dir.path().join("m.bin")).unwrap();
    assert_eq!(bytes[8..12], GESTURES_FORMAT_VERSION.to_le_bytes());
    // the header says the kind: a file of several gestures is not one gesture's
    for ext in ["bin", "txt"] {
        let e = cosco_hsom::hsom::Hsom::load(&dir.path().join(format!("m.{ext}")))
            .unwrap_err()
            .to_string();
        assert!(e.contains("several-gestures"), "{ext}: {e}");
    }
    // a model of an older format (6, before the branches' own postures; 9, before the
    // levels' held-out accuracies, the number the single-gesture format now skips):
    // "retrain", both forms
    let fnv1a = |b: &[u8]| {
        b.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &x| {
            (h ^ x as u64).wrapping_mul(0x0100_0000_01b3)
        })
    };
    let text = std::fs::read_to_string(dir.path().join("m.txt")).unwrap();
    // the lines before the final checksum (each branch's text keeps its own)
    let text = &text[..text.trim_end().rfind('\n').unwrap() + 1];
    for version in [6u32, 9] {
        let mut old = bytes[..bytes.len() - 8].to_vec();
        old[8..12].copy_from_slice(&version.to_le_bytes());
        let sum = fnv1a(&old);
        old.extend_from_slice(&sum.to_le_bytes());
        let body = text.replacen(
            &format!("\nversion {GESTURES_FORMAT_VERSION}\n"),
            &format!("\nversion {version}\n"),
            1,
        );
        assert_ne!(body, text);
        let old_text = format!("{body}checksum {:016x}\n", fnv1a(body.as_bytes()));
        for (ext, content) in [("bin", old), ("txt", old_text.into_bytes())] {
            let p = dir.path().join(format!("old.{ext}"));
            std::fs::write(&p, content).unwrap();
            let e = GestureModel::load(&p).unwrap_err().to_string();
            assert!(
                e.contains(&format!("version {version}")) && e.contains("retrain"),
                "{ext}: {e}"
            );
        }
    }
    // stored postures of the wrong size (with a valid checksum): refused, named
    let single_text = config()
        .fit(&cosco_hsom::demos::Demonstration::from_series(&[
            gesture([1.0, 0.0], 1),
            gesture([1.0, 0.0], 2),
        ]))
        .unwrap()
        .to_text();
    // `single_text` with its model edited by `edit`, written with a valid checksum
    let tampered = |edit: &dyn Fn(&mut serde_json::Value), name: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, hsom_common::edit_model_text(&single_text, edit)).unwrap();
        p
    };
    let p = tampered(
        &|m| m["algo"]["Events"]["knots"] = vec![1.0, 2.0, 3.0].into(),
        "short.txt",
    );
    let e = GestureModel::load(&p).unwrap_err().to_string();
    assert!(e.contains("3 posture values"), "{e}");
    // a held-out accuracy above 1 (with a valid checksum): refused
    let p = tampered(
        &|m| m["algo"]["Events"]["heldout_accuracy"][1] = 1.5.into(),
        "accuracy.txt",
    );
    assert!(GestureModel::load(&p).is_err());
    let e = cosco_hsom::hsom::Hsom::load(&p).unwrap_err().to_string();
    assert!(e.contains("accuracy outside [0, 1]"), "{e}");
    // a follower position that is negative (valid checksum): refused
    let p = tampered(
        &|m| m["algo"]["Events"]["follower_at"][0] = (-1.0).into(),
        "position.txt",
    );
    let e = cosco_hsom::hsom::Hsom::load(&p).unwrap_err().to_string();
    assert!(e.contains("position negative or non-finite"), "{e}");
    // a corrupted byte is refused
    let mut bad = bytes.clone();
    let mid = bad.len() / 2;
    bad[mid] ^= 1;
    assert!(GestureModel::from_bytes(&bad, Path::new("x.bin")).is_err());
    // demonstrations twice as long: the same size
    let long: Vec<(String, Vec<Demonstration>)> = sets(&APEXES)
        .into_iter()
        .map(|(l, ds)| {
            let ds = ds
                .into_iter()
                .map(|d| {
                    let rows = d.rows.iter().flat_map(|r| [r.clone(), r.clone()]).collect();
                    demo(&d.source, rows)
                })
                .collect();
            (l, ds)
        })
        .collect();
    let ml = config()
        .fit_model(&long, cosco_hsom::hsom::Fit::default())
        .unwrap();
    // every part of every branch the same size but the traced chunks, which the file keeps
    // only where a node has them, within a ceiling set by the configuration alone
    for (a, b) in m.branches().iter().zip(ml.branches()) {
        let (pa, pb) = (a.file_parts(), b.file_parts());
        for (x, y) in pa.iter().zip(&pb) {
            if x.part == "traced chunks" {
                assert!(x.bytes <= a.traced_ceiling() && y.bytes <= b.traced_ceiling());
                assert_eq!(a.traced_ceiling(), b.traced_ceiling());
            } else {
                assert_eq!(x, y);
            }
        }
        let total: usize = pa.iter().map(|p| p.bytes).sum();
        assert_eq!(total, a.to_bytes().len());
    }
    // a single-gesture model loads as one unlabelled gesture, byte for byte
    let single = config()
        .fit(&cosco_hsom::demos::Demonstration::from_series(&[gesture(
            [1.0, 0.0],
            1,
        )]))
        .unwrap();
    let p = dir.path().join("single.bin");
    single.save(&p).unwrap();
    let g = GestureModel::load(&p).unwrap();
    assert!(g.labels().is_empty());
    assert_eq!(g.branches()[0], single);
    g.save(&dir.path().join("again.bin")).unwrap();
    assert_eq!(
        std::fs::read(&p).unwrap(),
        std::fs::read(dir.path().join("again.bin")).unwrap()
    );
}

fn write_label(root: &Path, label: &str, apex: [f64; 2], width3: bool) {
    let d = root.join(label);
    std::fs::create_dir_all(&d).unwrap();
    for i in 0..2 {
        let mut rows = gesture(apex, i);
        let mut columns = vec!["x0".to_string(), "x1".to_string()];
        if width3 {
            rows.iter_mut().for_each(|r| r.push(0.0));
            columns.push("x2".into());
        }
        let demo = Demonstration {
            source: String::new(),
            columns,
            time: None,
            rows,
        };
        write_csv(&d.join(format!("demo_{i}.csv")), &demo).unwrap();
    }
}

use crate::common::cosco;

#[test]
fn bad_labelled_directories_are_refused_naming_the_directory_or_label() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("c.xml");
    std::fs::write(&cfg, config().to_xml()).unwrap();
    let out = dir.path().join("m.bin");
    let train = |demos: &Path| {
        let mut c = cosco();
        c.args(["train", "--config"])
            .arg(&cfg)
            .arg("--demos")
            .arg(demos)
            .arg("--out")
            .arg(&out);
        c
    };
    // a label directory with no CSV
    let empty = dir.path().join("empty");
    write_label(&empty, "up", [0.0, 1.0], false);
    std::fs::create_dir_all(empty.join("nothing")).unwrap();
    train(&empty)
        .assert()
        .failure()
        .stderr(predicate::str::contains("nothing"));
    // a label that is not a plain word
    let badname = dir.path().join("badname");
    write_label(&badname, "up", [0.0, 1.0], false);
    write_label(&badname, "two words", [1.0, 0.0], false);
    train(&badname).assert().failure().stderr(
        predicate::str::contains("\"two words\"").and(predicate::str::contains("plain word")),
    );
    // mixed widths across labels
    let mixed = dir.path().join("mixed");
    write_label(&mixed, "up", [0.0, 1.0], false);
    write_label(&mixed, "wide", [1.0, 0.0], true);
    train(&mixed)
        .assert()
        .failure()
        .stderr(predicate::str::contains("wide"));
    // a good set trains; an unknown label, or none, is refused listing the labels
    let good = dir.path().join("good");
    write_label(&good, "up", [0.0, 1.0], false);
    write_label(&good, "right", [1.0, 0.0], false);
    train(&good)
        .assert()
        .success()
        .stdout(predicate::str::contains("2 gestures"));
    let rep = dir.path().join("rep.csv");
    let reproduce = |extra: &[&str]| {
        let mut c = cosco();
        c.arg("reproduce")
            .arg("--model")
            .arg(&out)
            .args(["--initial", "0,0"])
            .arg("--out")
            .arg(&rep)
            .args(extra);
        c
    };
    reproduce(&["--gesture", "wave"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("\"wave\"").and(predicate::str::contains("right, up")));
    reproduce(&[])
        .assert()
        .failure()
        .stderr(predicate::str::contains("right, up"));
    reproduce(&["--gesture", "up"]).assert().success();
    cosco()
        .args(["recognize", "--model"])
        .arg(&out)
        .arg("--demos")
        .arg(&good)
        .assert()
        .success()
        .stdout(predicate::str::contains("4 of 4 recognised"));
}

#[test]
fn a_label_without_demonstrations_is_named_by_the_library_step() {
    // `app::train` (what the Python package calls): a label with no
    // demonstrations is refused naming it, not as "no demonstrations" of no one
    let mut s = sets(&APEXES[..2]);
    s[1].1.clear();
    let e = cosco_hsom::app::train(&config(), &s, None).unwrap_err();
    assert_eq!(e.to_string(), "gesture \"right\" has no demonstrations");
}
