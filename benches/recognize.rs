//! Recognising one gesture (issue 9): a hierarchy of four gestures (the built-in
//! configs/nao-gestures.xml, 300-sample 6-D demonstrations generated here) against 1-NN DTW
//! over the same 12 training sequences; and recognition in the loop (issue 52): the first
//! push (each label's reproduction from the first posture), then every other push (a DTW
//! row per label). Prints the share of DTW cells the whole recognition skips, per label, and
//! where a recognition's time goes: the best of 15 rounds of 20 calls each (the least
//! disturbed by other work on the machine) of `recognize`, of the four labels' reproductions
//! from the query's first posture, of their four pruned DTWs with every prefix's cost (in
//! the data's units) and of 1-NN DTW.
//!
//! cargo bench --bench recognize -- --warm-up-time 1 --measurement-time 3

mod common;

use common::gestures;
use std::time::Instant;

use cosco_hsom::dtw::Band;
use cosco_hsom::nearest::NearestNeighbour;
use criterion::{black_box, criterion_group, criterion_main, BatchSize, Criterion};

fn recognize(c: &mut Criterion) {
    let cfg = cosco_hsom::app::config(None).unwrap();
    let base = gestures(4, 300);
    // four gestures: the same shapes, each label's joints scaled and shifted its own way
    let sets: Vec<(String, Vec<cosco_hsom::demos::Demonstration>)> = (0..4)
        .map(|g| {
            let demos = base[..3]
                .iter()
                .map(|d| {
                    let mut d = d.clone();
                    for r in &mut d.rows {
                        for (j, v) in r.iter_mut().enumerate() {
                            *v = *v * (1.0 + 0.2 * g as f64) + 0.1 * ((g + j) % 4) as f64;
                        }
                    }
                    d
                })
                .collect();
            (format!("g{g}"), demos)
        })
        .collect();
    let model = cfg
        .fit_model(&sets, cosco_hsom::hsom::Fit::default())
        .unwrap();
    let nn = NearestNeighbour::new(
        sets.iter()
            .flat_map(|(l, ds)| ds.iter().map(move |d| (l.clone(), d.rows.clone())))
            .collect(),
        Band::None,
    );
    let query = sets[2].1[0].rows.clone();
    println!(
        "DTW cells skipped per label: {:?}",
        model.pruning_rates(&query).unwrap()
    );
    let labels: Vec<String> = sets.iter().map(|(l, _)| l.clone()).collect();
    let reps: Vec<Vec<Vec<f64>>> = labels
        .iter()
        .map(|l| {
            model
                .branch(Some(l))
                .and_then(|b| Ok(b.reproduce(&query[0])?))
                .unwrap()
                .postures
        })
        .collect();
    let best_of = |f: &mut dyn FnMut()| {
        let mut best = f64::INFINITY;
        for _ in 0..15 {
            let t = Instant::now();
            for _ in 0..20 {
                f();
            }
            best = best.min(t.elapsed().as_secs_f64() / 20.0);
        }
        best * 1e3
    };
    let whole = best_of(&mut || {
        black_box(model.recognize(black_box(&query)).unwrap());
    });
    let reproductions = best_of(&mut || {
        for l in &labels {
            black_box(
                model
                    .branch(Some(l))
                    .and_then(|b| Ok(b.reproduce(black_box(&query[0]))?))
                    .unwrap(),
            );
        }
    });
    let dtws = best_of(&mut || {
        for r in &reps {
            black_box(cosco_hsom::dtw::prefix_pruning_rate(black_box(&query), r));
        }
    });
    let one_nn = best_of(&mut || {
        black_box(nn.classify(black_box(&query)).unwrap());
    });
    println!(
        "best of 15 x 20 calls: recognize {whole:.2} ms = 4 reproductions {reproductions:.2} ms \
         + 4 pruned DTWs {dtws:.2} ms + the rest; 1-NN DTW {one_nn:.2} ms"
    );
    let mut g = c.benchmark_group("recognize_one_gesture_300_samples");
    g.bench_function("hsom_scores", |b| {
        b.iter(|| model.scores(black_box(&query)).unwrap())
    });
    g.bench_function("hsom_with_early_decision", |b| {
        b.iter(|| model.recognize(black_box(&query)).unwrap())
    });
    g.bench_function("nn_dtw", |b| {
        b.iter(|| nn.classify(black_box(&query)).unwrap())
    });
    g.bench_function("reproduce_one_label", |b| {
        b.iter(|| {
            model
                .branch(Some("g2"))
                .and_then(|b| Ok(b.reproduce(black_box(&query[0]))?))
                .unwrap()
        })
    });
    g.finish();
    // once a model: the rise, the holds, and each label learned again without each of its
    // kept demonstrations for the envelope
    let mut g = c.benchmark_group("recognizer_calibration_4_labels");
    g.sample_size(10);
    g.bench_function("stream_calibration", |b| {
        b.iter(|| model.stream_calibration().unwrap())
    });
    g.finish();
    let cal = model.stream_calibration().unwrap();
    let mut g = c.benchmark_group("recognizer_4_labels");
    g.bench_function("first_push", |b| {
        b.iter_batched(
            || cosco_hsom::hsom::Recognizer::new(&model, cal.clone()).unwrap(),
            |mut r| {
                r.push(black_box(&query[0])).unwrap();
                r
            },
            BatchSize::SmallInput,
        )
    });
    g.bench_function("299_more_pushes", |b| {
        b.iter_batched(
            || {
                let mut r = cosco_hsom::hsom::Recognizer::new(&model, cal.clone()).unwrap();
                r.push(&query[0]).unwrap();
                r
            },
            |mut r| {
                for x in &query[1..] {
                    r.push(black_box(x)).unwrap();
                }
                r
            },
            BatchSize::SmallInput,
        )
    });
    g.finish();
}

criterion_group!(benches, recognize);
criterion_main!(benches);
