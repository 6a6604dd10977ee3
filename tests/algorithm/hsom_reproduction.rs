//! Reproduction fidelity (with an untrained negative control) and persistence round trips.

use crate::hsom_common;

use cosco_hsom::demos::Demonstration;
use cosco_hsom::hsom::{Hsom, PersistError};
use hsom_common::*;

/// A deterministic gesture through five key postures (3-D), ramps of 12 samples and holds of
/// 4, the same in every demonstration.
fn key_postures() -> Vec<Demonstration> {
    let keys = [
        [0.0, 0.0, 0.0],
        [1.0, 0.2, 0.5],
        [1.5, 1.0, 0.0],
        [0.5, 1.5, -0.5],
        [-0.5, 0.8, 0.2],
    ];
    let mut rows = Vec::new();
    for w in keys.windows(2) {
        for _ in 0..4 {
            rows.push(w[0].to_vec());
        }
        for j in 0..12 {
            let t = j as f64 / 12.0;
            rows.push((0..3).map(|d| w[0][d] + (w[1][d] - w[0][d]) * t).collect());
        }
    }
    for _ in 0..4 {
        rows.push(keys[4].to_vec());
    }
    (0..3)
        .map(|i| Demonstration {
            source: format!("keys{i}"),
            columns: vec!["a".into(), "b".into(), "c".into()],
            time: None,
            rows: rows.clone(),
        })
        .collect()
}

/// Threshold of the fidelity check: mean DTW distance below 6 % of the data's diagonal.
const FIDELITY: f64 = 0.06;

#[test]
fn trained_hierarchy_reproduces_the_key_posture_gesture_and_untrained_does_not() {
    let demos = key_postures();
    let cfg = table1_for(3);
    let model = cfg.fit(&demos).unwrap();
    let rep = model.reproduce(&demos[0].rows[0]).unwrap();
    let e = relative_dtw(&rep.postures, &demos);
    let untrained = cfg
        .fit_model(&demos, cosco_hsom::hsom::Fit::UNTRAINED)
        .map(|m| m.branches()[0].clone())
        .unwrap();
    let rep_u = untrained.reproduce(&demos[0].rows[0]).unwrap();
    let e_u = relative_dtw(&rep_u.postures, &demos);
    println!(
        "trained {e:.4} ({} postures, {:?}), untrained {e_u:.4}",
        rep.postures.len(),
        rep.stop
    );
    assert!(e < FIDELITY, "trained relative DTW {e}");
    assert!(
        e_u >= FIDELITY,
        "untrained relative DTW {e_u} passes the check: the check is too weak"
    );
    // it starts where it was asked to and leaves the initial posture
    assert_eq!(rep.postures[0], demos[0].rows[0]);
    assert!(rep.postures.len() > 10);
    assert_eq!(rep.steps, (0..rep.postures.len()).collect::<Vec<_>>());
}

#[test]
fn literal_mode_also_runs_and_respects_max_length() {
    let demos = key_postures();
    let model = table1_for(3).fit(&demos).unwrap();
    let mut p = model.config().params().clone();
    p.reproduction.max_length = 37;
    p.paper_mut().unwrap().stop = cosco_hsom::config::StopRule::MaxLength;
    let model = p.check("t").unwrap().fit(&demos).unwrap();
    let rep = model.reproduce(&demos[0].rows[0]).unwrap();
    assert_eq!(rep.postures.len(), 37);
    assert!(
        rep.predicted_by.iter().any(|&l| l >= 1),
        "higher levels never used"
    );
}

fn trained() -> (Hsom, Vec<f64>) {
    let demos = stroke(3, 5);
    let init = demos[0].rows[0].clone();
    (table1_for(2).fit(&demos).unwrap(), init)
}

#[test]
fn save_load_gives_an_identical_model_and_reproduction_in_both_formats() {
    let (m, init) = trained();
    let dir = tempfile::tempdir().unwrap();
    let before = m.reproduce(&init).unwrap();
    for name in ["m.bin", "m.txt"] {
        let p = dir.path().join(name);
        m.save(&p).unwrap();
        let back = Hsom::load(&p).unwrap();
        assert_eq!(back, m, "{name}");
        assert_eq!(back.reproduce(&init).unwrap(), before, "{name}");
    }
    assert!(matches!(
        m.save(&dir.path().join("m.json")),
        Err(PersistError::UnknownExtension { .. })
    ));
}

#[test]
fn model_size_depends_on_the_configuration_not_on_the_data_length() {
    let short = stroke(2, 11);
    let long: Vec<Demonstration> = short
        .iter()
        .map(|d| {
            let mut d = d.clone();
            // 100x longer: the same stroke sampled 100 times more densely
            let n = d.rows.len();
            d.rows = (0..n * 100)
                .map(|i| {
                    let t = i as f64 / 100.0;
                    let (a, b) = (t.floor() as usize, (t.floor() as usize + 1).min(n - 1));
                    let f = t - t.floor();
                    (0..2)
                        .map(|k| d.rows[a][k] * (1.0 - f) + d.rows[b][k] * f)
                        .collect()
                })
                .collect();
            d
        })
        .collect();
    let cfg = table1_for(2);
    let a = cfg.fit(&short).unwrap();
    let b = cfg.fit(&long).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let (pa, pb) = (dir.path().join("a.bin"), dir.path().join("b.bin"));
    a.save(&pa).unwrap();
    b.save(&pb).unwrap();
    let (sa, sb) = (
        std::fs::metadata(&pa).unwrap().len(),
        std::fs::metadata(&pb).unwrap().len(),
    );
    assert_eq!(sa, sb);
    // the text form's structure: its lines and the values of its JSON
    let count = |m: &Hsom| {
        let t = m.to_text();
        (t.lines().count(), t.matches(',').count())
    };
    assert_eq!(count(&a), count(&b));
}

#[test]
fn corrupted_truncated_and_other_version_files_are_refused() {
    let (m, _) = trained();
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("x.bin");
    let bytes = m.to_bytes();
    // truncated
    std::fs::write(&p, &bytes[..bytes.len() / 2]).unwrap();
    let e = Hsom::load(&p).unwrap_err();
    assert!(matches!(e, PersistError::Truncated { .. }), "{e}");
    assert!(e.to_string().contains("truncated") && e.to_string().contains("x.bin"));
    // a flipped bit in the weights
    let mut b = bytes.clone();
    let k = b.len() - 100;
    b[k] ^= 0x10;
    std::fs::write(&p, &b).unwrap();
    assert!(matches!(
        Hsom::load(&p),
        Err(PersistError::Corrupted { .. })
    ));
    // another version
    let mut b = bytes.clone();
    b[8] = 1;
    std::fs::write(&p, &b).unwrap();
    let e = Hsom::load(&p).unwrap_err();
    assert!(
        matches!(
            e,
            PersistError::Version {
                found: 1,
                expected: cosco_hsom::hsom::FORMAT_VERSION,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("retrain"), "{e}");
    // a newer version: said so, before the checksum (left as it was)
    let mut b = bytes.clone();
    b[8..12].copy_from_slice(&(cosco_hsom::hsom::FORMAT_VERSION + 1).to_le_bytes());
    std::fs::write(&p, &b).unwrap();
    let e = Hsom::load(&p).unwrap_err();
    assert!(matches!(e, PersistError::Newer { .. }), "{e}");
    assert!(e.to_string().contains("written by a newer version"), "{e}");
    let t = dir.path().join("x.txt");
    let newer = m.to_text().replacen(
        &format!("version {}", cosco_hsom::hsom::FORMAT_VERSION),
        &format!("version {}", cosco_hsom::hsom::FORMAT_VERSION + 1),
        1,
    );
    std::fs::write(&t, newer).unwrap();
    let e = Hsom::load(&t).unwrap_err();
    assert!(matches!(e, PersistError::Newer { .. }), "{e}");
    // not a model
    std::fs::write(&p, b"hello world, not a model").unwrap();
    assert!(matches!(Hsom::load(&p), Err(PersistError::BadMagic { .. })));
    // a huge configuration length: refused without allocating
    let mut b = bytes.clone();
    b[12..20].copy_from_slice(&u64::MAX.to_le_bytes());
    std::fs::write(&p, &b).unwrap();
    assert!(matches!(
        Hsom::load(&p),
        Err(PersistError::Corrupted { .. })
    ));
    // inconsistent sizes: the embedded configuration says 11 rows where the data hold 10
    let mut b = bytes.clone();
    let at = b.windows(15).position(|w| w == b"<rows>10</rows>").unwrap();
    b[at + 7] = b'1';
    std::fs::write(&p, &b).unwrap();
    let e = Hsom::load(&p).unwrap_err();
    assert!(
        matches!(e, PersistError::Corrupted { .. }) && e.to_string().contains("11x10"),
        "{e}"
    );
    // empty file
    std::fs::write(&p, b"").unwrap();
    assert!(Hsom::load(&p).is_err());
}

#[test]
fn corrupted_truncated_and_other_version_text_files_are_refused() {
    let (m, _) = trained();
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("x.txt");
    let text = m.to_text();
    std::fs::write(&p, &text[..text.len() / 2]).unwrap();
    assert!(matches!(
        Hsom::load(&p),
        Err(PersistError::Truncated { .. })
    ));
    std::fs::write(
        &p,
        text.replacen(
            &format!("version {}", cosco_hsom::hsom::FORMAT_VERSION),
            "version 7",
            1,
        ),
    )
    .unwrap();
    assert!(matches!(
        Hsom::load(&p),
        Err(PersistError::Version { found: 7, .. })
    ));
    // a changed digit in the weights
    let i = text.find("\"weights\":[").unwrap();
    let i = i + text[i..].find(|c: char| c.is_ascii_digit()).unwrap();
    let mut t = text.clone();
    let digit = if &t[i..i + 1] == "9" { "8" } else { "9" };
    t.replace_range(i..i + 1, digit);
    std::fs::write(&p, &t).unwrap();
    let e = Hsom::load(&p).unwrap_err();
    assert!(matches!(e, PersistError::Corrupted { .. }), "{e}");
    // a map with a missing value
    let shorter = edit_model_text(&text, |m| {
        m["maps"][0]["weights"].as_array_mut().unwrap().pop();
    });
    std::fs::write(&p, shorter).unwrap();
    let e = Hsom::load(&p).unwrap_err();
    assert!(
        matches!(e, PersistError::Corrupted { .. }) && e.to_string().contains("values"),
        "{e}"
    );
    std::fs::write(&p, "something else\n").unwrap();
    assert!(matches!(Hsom::load(&p), Err(PersistError::BadMagic { .. })));
}

/// Seven handwriting-like drawings, each shifted 6 units further along y than the last
/// (nested curves: where a drawing starts tells where it goes).
fn nested() -> Vec<Demonstration> {
    let mut demos = handwriting(7, 9);
    for (i, d) in demos.iter_mut().enumerate() {
        for r in &mut d.rows {
            r[1] += 6.0 * i as f64;
        }
    }
    demos
}

#[test]
fn start_weighted_postures_survive_save_and_load_in_both_formats() {
    // the consensus weighed by the starts, on drawings whose start predicts their route,
    // keeps each demonstration's placement and start in the model (the width is stored)
    let demos = nested();
    let m = recommended_for(2).fit(&demos).unwrap();
    let init = demos[6].rows[0].clone();
    let before = m.reproduce(&init).unwrap();
    let dir = tempfile::tempdir().unwrap();
    for name in ["m.bin", "m.txt"] {
        let path = dir.path().join(name);
        m.save(&path).unwrap();
        let back = Hsom::load(&path).unwrap();
        assert_eq!(back, m, "{name}");
        assert_eq!(back.reproduce(&init).unwrap(), before, "{name}");
    }
    // a corrupted width is refused, naming the start-weighted postures
    let path = dir.path().join("m.txt");
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("\"width\":"));
    let bad = edit_model_text(&text, |m| {
        m["algo"]["Events"]["start_knots"]["width"] = (-1.0).into()
    });
    std::fs::write(&path, bad).unwrap();
    let e = Hsom::load(&path).unwrap_err().to_string();
    assert!(e.contains("start-weighted postures"), "{e}");
    // so is an end posture of another width, and a negative demonstrations' jerk
    let bad = edit_model_text(&text, |m| {
        m["algo"]["Events"]["end_posture"]
            .as_array_mut()
            .unwrap()
            .push(0.0.into())
    });
    std::fs::write(&path, bad).unwrap();
    let e = Hsom::load(&path).unwrap_err().to_string();
    assert!(e.contains("end-posture values"), "{e}");
    let bad = edit_model_text(&text, |m| {
        m["algo"]["Events"]["demo_smoothness"]["jerk"] = (-1.0).into()
    });
    std::fs::write(&path, bad).unwrap();
    let e = Hsom::load(&path).unwrap_err().to_string();
    assert!(e.contains("demonstrations' jerk"), "{e}");
    // the model keeps its traced chunks (seven places per event: the event, its halves, each
    // half's extremes) in both forms (above); a chunk one word short is refused
    let chunk = |m: &mut serde_json::Value| -> Vec<serde_json::Value> {
        m["algo"]["Events"]["traces"]["levels"][1][0]["words"]
            .as_array()
            .unwrap()
            .clone()
    };
    let short = edit_model_text(&text, |m| {
        let mut words = chunk(m);
        words.pop();
        m["algo"]["Events"]["traces"]["levels"][1][0]["words"] = words.into();
    });
    std::fs::write(&path, short).unwrap();
    let e = Hsom::load(&path).unwrap_err().to_string();
    assert!(e.contains("traces end before a word"), "{e}");
    // a model of the paper algorithm holds none
    let paper = table1_for(2).fit(&demos).unwrap();
    let path = dir.path().join("p.txt");
    paper.save(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(!text.contains("\"traces\"") && text.contains("\"end_hits\""));
    let path = dir.path().join("t.txt");
    m.save(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    // a chunk's first bottom event (after its head of 3 words) outside the bottom level
    let bad_traces = edit_model_text(&text, |m| {
        let mut words = chunk(m);
        words[3] = 999999.into();
        m["algo"]["Events"]["traces"]["levels"][1][0]["words"] = words.into();
    });
    std::fs::write(&path, bad_traces).unwrap();
    let e = Hsom::load(&path).unwrap_err().to_string();
    assert!(e.contains("traces") && e.contains("999999"), "{e}");
    // so are traces whose first chunk places an event at a non-finite value (NaN's bits):
    // after the chunk's head (3 words) and its memory (4) bottom events
    let bad_traces = edit_model_text(&text, |m| {
        let mut words = chunk(m);
        words[3 + 4] = 2143289344u32.into();
        m["algo"]["Events"]["traces"]["levels"][1][0]["words"] = words.into();
    });
    std::fs::write(&path, bad_traces).unwrap();
    let e = Hsom::load(&path).unwrap_err().to_string();
    assert!(
        e.contains("traces") && e.contains("posture value 2143289344"),
        "{e}"
    );
    // and a traced model whose traces are gone
    let gone = edit_model_text(&text, |m| {
        m["algo"]["Events"]["traces"] = serde_json::Value::Null
    });
    std::fs::write(&path, gone).unwrap();
    let e = Hsom::load(&path).unwrap_err().to_string();
    assert!(e.contains("traces missing"), "{e}");
}
