//! Reproduction quality on synthetic families (printed with --nocapture) with asserted bounds.

mod hsom_common;

use cosco_hsom::config::{HsomConfig, IdDecoding, ReproductionMode};
use hsom_common::*;

fn run(name: &str, demos: &[cosco_hsom::demos::Demonstration], cfg: &HsomConfig) -> (f64, f64) {
    let model = cfg.fit(&demos[1..]).unwrap();
    let init = &demos[0].rows[0];
    let mut res = Vec::new();
    for (label, mode, dec, maxl, conf) in [
        (
            "strided",
            ReproductionMode::Strided,
            IdDecoding::Round,
            None,
            0.0,
        ),
        (
            "strided-l1",
            ReproductionMode::Strided,
            IdDecoding::Round,
            Some(1),
            0.0,
        ),
        (
            "strided-l2",
            ReproductionMode::Strided,
            IdDecoding::Round,
            Some(2),
            0.0,
        ),
        (
            "strided-l3",
            ReproductionMode::Strided,
            IdDecoding::Round,
            Some(3),
            0.0,
        ),
        (
            "strided-conf1",
            ReproductionMode::Strided,
            IdDecoding::Round,
            None,
            1.0,
        ),
        (
            "strided-nearest",
            ReproductionMode::Strided,
            IdDecoding::Nearest,
            None,
            0.0,
        ),
        (
            "literal",
            ReproductionMode::Literal,
            IdDecoding::Round,
            None,
            0.0,
        ),
        (
            "reflex",
            ReproductionMode::Strided,
            IdDecoding::Round,
            Some(0),
            0.0,
        ),
    ] {
        let mut r = cfg.params().reproduction.clone();
        r.mode = mode;
        r.id_decoding = dec;
        r.max_level = maxl;
        r.confusion_threshold = conf;
        let rep = model.reproduce_with(init, &r).unwrap();
        let e = relative_dtw(&rep.postures, &demos[1..]);
        let mean_len = demos[1..].iter().map(|d| d.rows.len()).sum::<usize>() as f64
            / (demos.len() - 1) as f64;
        println!(
            "{name:<8} {label:<16} rel.DTW {e:.4}  length {} / demo mean {mean_len:.0}  stop {:?}",
            rep.postures.len(),
            rep.stop
        );
        res.push(e);
    }
    let untrained = cfg.initialise(&demos[1..]).unwrap();
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
        ("joints6", joints6(6, 9)),
    ] {
        let cfg = table1_for(demos[0].rows[0].len());
        run(name, &demos, &cfg);
    }
}
