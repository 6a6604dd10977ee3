//! CoSCo-HSOM benchmarks (criterion), on data generated here.
//!
//! cargo bench --bench hsom -- --warm-up-time 1 --measurement-time 2

mod common;

use common::{gestures, gestures_of};
use cosco_hsom::config::{HsomParams, MemoryMode};
use cosco_hsom::hsom::{ActivityLevels, ActivityList};
use cosco_hsom::som::{Neighbourhood, SelfOrganizingMap, Topology};
use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn step_vs_bmu(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut map = SelfOrganizingMap::new_random(
        16,
        16,
        12,
        Topology::Orthogonal,
        &[0.0; 12],
        &[1.0; 12],
        &mut rng,
    );
    let xs: Vec<Vec<f64>> = (0..64)
        .map(|_| (0..12).map(|_| rng.gen()).collect())
        .collect();
    let mut g = c.benchmark_group("som16x16_12d");
    let mut i = 0;
    g.bench_function("bmu_scan", |b| {
        b.iter(|| {
            i = (i + 1) % xs.len();
            black_box(map.bmu(black_box(&xs[i])))
        })
    });
    g.bench_function("training_step", |b| {
        b.iter(|| {
            i = (i + 1) % xs.len();
            let (n, _) = map.bmu(&xs[i]);
            map.update(&xs[i], None, n, 0.1, 2.0, Neighbourhood::Gaussian);
        })
    });
    g.finish();
}

fn table1(c: &mut Criterion) {
    let demos = gestures(3, 300);
    let cfg = HsomParams::table1().check("table1").unwrap();
    let mut g = c.benchmark_group("table1");
    g.sample_size(10);
    g.bench_function("fit_3x300", |b| {
        b.iter(|| black_box(cfg.fit(&demos).unwrap()))
    });
    let model = cfg.fit(&demos).unwrap();
    g.bench_function("reproduce", |b| {
        b.iter(|| black_box(model.reproduce(&demos[0].rows[0]).unwrap()))
    });
    let mut p = HsomParams::table1();
    p.paper_mut().unwrap().memory_mode = MemoryMode::Levels;
    let cfg_levels = p.check("t").unwrap();
    g.bench_function("fit_3x300_activity_levels", |b| {
        b.iter(|| black_box(cfg_levels.fit(&demos).unwrap()))
    });
    g.finish();
}

/// The recommended configs/nao-gestures.xml (events): training on 3 demonstrations plus one
/// reproduction (target: under 50 ms together), and reproduction against gesture length
/// (it must stay linear); resuming a reproduction after half of it was read back.
fn events(c: &mut Criterion) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/nao-gestures.xml");
    let cfg = cosco_hsom::config::load_config(&path).unwrap();
    let demos = gestures(3, 300);
    let mut g = c.benchmark_group("events");
    g.sample_size(10);
    g.bench_function("fit_3x300_and_reproduce", |b| {
        b.iter(|| {
            let m = cfg.fit(&demos).unwrap();
            black_box(m.reproduce(&demos[0].rows[0]).unwrap())
        })
    });
    for n in [300, 600, 1200, 2400] {
        let d = gestures(3, n);
        let m = cfg.fit(&d).unwrap();
        let len = m.reproduce(&d[0].rows[0]).unwrap().postures.len();
        g.bench_with_input(
            BenchmarkId::new("reproduce", format!("{n}_samples_{len}_postures")),
            &m,
            |b, m| b.iter(|| black_box(m.reproduce(&d[0].rows[0]).unwrap())),
        );
        // resuming after half of it was read back: the plan made twice and a DTW alignment of
        // the reading with it (quadratic in the length, where reproducing is linear)
        let initial = &d[0].rows[0];
        let reading = m.reproduce(initial).unwrap().postures[..len / 2].to_vec();
        g.bench_with_input(
            BenchmarkId::new("resume_half", format!("{n}_samples_{len}_postures")),
            &m,
            |b, m| b.iter(|| black_box(m.resume(initial, &reading).unwrap())),
        );
    }
    g.finish();
}

fn lists_vs_levels(c: &mut Criterion) {
    let mut g = c.benchmark_group("stm_step");
    for side in [8usize, 16, 32, 64] {
        for height in 3usize..=6 {
            let nodes = side * side;
            let id = format!("{side}x{side}_h{height}");
            let mut lists: Vec<ActivityList> = (0..height).map(|_| ActivityList::new(4)).collect();
            let mut k = 0usize;
            g.bench_with_input(BenchmarkId::new("lists", &id), &nodes, |b, &n| {
                b.iter(|| {
                    k = (k + 7) % n;
                    for l in lists.iter_mut() {
                        l.push(((k % side) as u16, (k / side) as u16));
                    }
                    black_box(&lists);
                })
            });
            let mut levels: Vec<ActivityLevels> =
                (0..height).map(|_| ActivityLevels::new(nodes, 4)).collect();
            g.bench_with_input(BenchmarkId::new("levels", &id), &nodes, |b, &n| {
                b.iter(|| {
                    k = (k + 7) % n;
                    for l in levels.iter_mut() {
                        l.push(k);
                    }
                    black_box(&levels);
                })
            });
        }
    }
    g.finish();
}

/// Teaching a model of twenty demonstrations one more (`Hsom::update`) against training on all
/// twenty-one (the recommended configuration; 6-D gestures of 300 samples generated here).
fn update(c: &mut Criterion) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/nao-gestures.xml");
    let cfg = cosco_hsom::config::load_config(&path).unwrap();
    let demos = gestures(21, 300);
    let twenty = cfg.fit(&demos[..20]).unwrap();
    let mut g = c.benchmark_group("update");
    g.sample_size(10);
    g.bench_function("fit_21x300", |b| {
        b.iter(|| black_box(cfg.fit(&demos).unwrap()))
    });
    g.bench_function("update_20x300_with_1", |b| {
        b.iter(|| black_box(twenty.update(&demos[20..]).unwrap()))
    });
    g.finish();
}

/// Training a gesture of the upper body's 14 variables against one of the left arm's 6, on
/// the same number of demonstrations and samples, each with its recommended configuration
/// (configs/nao-gestures.xml, configs/nao-upper-body.xml): the cost of the whole upper body.
fn width(c: &mut Criterion) {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut g = c.benchmark_group("width");
    g.sample_size(10);
    for (w, config) in [(6usize, "nao-gestures.xml"), (14, "nao-upper-body.xml")] {
        let demos = gestures_of(3, 300, w);
        let cfg = cosco_hsom::config::load_config(&root.join("configs").join(config)).unwrap();
        assert_eq!(cfg.params().state_length, w, "{config}");
        g.bench_function(format!("fit_3x300_{w}_variables"), |b| {
            b.iter(|| black_box(cfg.fit(&demos).unwrap()))
        });
    }
    g.finish();
}

criterion_group!(
    benches,
    width,
    step_vs_bmu,
    table1,
    events,
    lists_vs_levels,
    update
);
criterion_main!(benches);
