//! Reproduction quality on synthetic families (printed with --nocapture) with asserted bounds.

use crate::hsom_common;

use cosco_hsom::config::{AlgorithmParams, HsomConfig, IdDecoding};
use hsom_common::*;

fn run(name: &str, demos: &[cosco_hsom::demos::Demonstration], cfg: &HsomConfig) -> (f64, f64) {
    let init = &demos[0].rows[0];
    let mut res = Vec::new();
    let mut cases = vec![("DEFAULT".to_string(), cfg.clone())];
    if std::env::var("HSOM_SWEEP").is_ok() {
        // the paper algorithm's ID decodings and the highest level used
        for dec in [IdDecoding::Round, IdDecoding::Floor, IdDecoding::Nearest] {
            for maxl in [Some(2), Some(3), Some(4), None] {
                let mut p = cfg.params().clone();
                if let AlgorithmParams::Paper(q) = &mut p.algorithm {
                    q.id_decoding = dec;
                }
                p.reproduction.max_level = maxl.filter(|&m| m < p.height);
                cases.push((format!("{dec:?} l{maxl:?}"), p.check("sweep").unwrap()));
            }
        }
    }
    for (label, case) in cases {
        let model = case.fit(&demos[1..]).unwrap();
        let rep = model.reproduce(init).unwrap();
        let e = relative_dtw(&rep.postures, &demos[1..]);
        let mean_len = demos[1..].iter().map(|d| d.rows.len()).sum::<usize>() as f64
            / (demos.len() - 1) as f64;
        println!(
            "{name:<8} {label:<22} rel.DTW {e:.4}  length {} / demo mean {mean_len:.0}  stop {:?}",
            rep.postures.len(),
            rep.stop
        );
        res.push(e);
    }
    let untrained = cfg
        .fit_model(&demos[1..], cosco_hsom::hsom::Fit::UNTRAINED)
        .map(|m| m.branches()[0].clone())
        .unwrap();
    let rep = untrained.reproduce(init).unwrap();
    let e_un = relative_dtw(&rep.postures, &demos[1..]);
    println!(
        "{name:<8} {:<16} rel.DTW {e_un:.4}  length {}",
        "UNTRAINED",
        rep.postures.len()
    );
    (res[0], e_un)
}

#[test]
fn measure_families() {
    for (name, demos) in [
        ("eight", figure_eight(6, 7)),
        ("stroke", stroke(6, 8)),
        ("hand", handwriting(8, 9)),
        ("joints6", joints6(6, 9)),
    ] {
        let mut cfg = table1_for(demos[0].rows[0].len());
        if let Ok(s) = std::env::var("HSOM_SEED") {
            let mut p = cfg.into_params();
            p.seed = s.parse().unwrap();
            cfg = p.check("seed").unwrap();
        }
        if let Ok(s) = std::env::var("HSOM_LF") {
            let mut p = cfg.into_params();
            p.reproduction.length_factor = s.parse().unwrap();
            cfg = p.check("lf").unwrap();
        }
        if let Ok(s) = std::env::var("HSOM_STEPS") {
            let mut p = cfg.into_params();
            p.training_steps = s.parse().unwrap();
            cfg = p.check("steps").unwrap();
        }
        let (trained, untrained) = run(name, &demos, &cfg);
        if std::env::var("HSOM_SEED").is_err() {
            assert!(
                trained < untrained,
                "{name}: trained {trained} vs untrained {untrained}"
            );
        }
        // the recommended configs/nao-gestures.xml (the events extension), stateLength adapted
        let mut p = recommended_for(demos[0].rows[0].len()).into_params();
        if let Ok(s) = std::env::var("HSOM_SEED") {
            p.seed = s.parse().unwrap();
        }
        let rec_cfg = p.check("nao-gestures.xml").unwrap();
        let (events, untrained) = run(&format!("{name}/events"), &demos, &rec_cfg);
        println!("{name:<8} events {events:.4} vs built-in Table I {trained:.4}");
        if std::env::var("HSOM_SEED").is_err() {
            assert!(
                events < untrained,
                "{name} (nao-gestures.xml): trained {events} vs untrained {untrained}"
            );
        }
    }
}
