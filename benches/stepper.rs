//! Steppers in the loop (issue 52): the time of one `step`, given the posture the encoders
//! read. The hierarchy (events algorithm, the built-in configs/nao-gestures.xml) learned from
//! three waves of the demonstrator on the Nao's left arm (6 joints, 40 Hz, as
//! tests/algorithm/stepper.rs makes them), following its plan undisturbed and re-planning with
//! the arm off its plan at phase 0.4 (its `resume` on the whole reading); the DMP and ProMP on
//! the same waves, undisturbed. The undisturbed steps are timed over whole reproductions (a
//! fresh stepper, cloned outside the timing, whenever one ends): criterion's figure is the time
//! per step. Before criterion's statistics, the median of single steps timed one by one over 20
//! undisturbed reproductions is printed.
//!
//! cargo bench --bench stepper --no-default-features -- --warm-up-time 1 --measurement-time 3

use std::time::{Duration, Instant};

use cosco_hsom::condition::Conditions;
use cosco_hsom::dmp::{DmpSettings, DmpStepper};
use cosco_hsom::hsom::HsomStepper;
use cosco_hsom::promp::{PrompSettings, PrompStepper};
use cosco_hsom::stepper::Stepper;
use criterion::{black_box, criterion_group, criterion_main, BatchSize, Criterion};

/// The demonstrator's waves (tests/common/waves.rs): seed 7, the first held out (its first
/// posture starts every reproduction), the others to learn from.
#[path = "../tests/common/waves.rs"]
mod waves;

/// `iters` undisturbed steps (the arm reads where it was sent), fresh copies of `template`
/// taken outside the timing whenever one is done; the time spent stepping.
fn undisturbed<S: Stepper + Clone>(template: &S, initial: &[f64], iters: u64) -> Duration {
    let mut spent = Duration::ZERO;
    let mut left = iters;
    while left > 0 {
        let mut s = template.clone();
        let mut read = initial.to_vec();
        let start = Instant::now();
        while left > 0 && !s.done() {
            read = s.step(black_box(&read)).unwrap();
            left -= 1;
        }
        spent += start.elapsed();
    }
    spent
}

/// The median time of one undisturbed step of `template`, each timed alone, over `runs`
/// reproductions; and the steps per reproduction.
fn median_step<S: Stepper + Clone>(template: &S, initial: &[f64], runs: usize) -> (f64, usize) {
    let mut times = Vec::new();
    let mut steps = 0;
    for _ in 0..runs {
        let mut s = template.clone();
        let mut read = initial.to_vec();
        steps = 0;
        while !s.done() {
            let start = Instant::now();
            read = s.step(black_box(&read)).unwrap();
            times.push(start.elapsed().as_secs_f64());
            steps += 1;
        }
    }
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], steps)
}

/// A copy of `template` stepped undisturbed to `phase`.
fn stepped_to<S: Stepper + Clone>(template: &S, initial: &[f64], phase: f64) -> (S, Vec<f64>) {
    let mut s = template.clone();
    let mut read = initial.to_vec();
    while s.phase() < phase && !s.done() {
        read = s.step(&read).unwrap();
    }
    (s, read)
}

fn steppers(c: &mut Criterion) {
    let demos = waves::waves(7);
    let (held, train) = (&demos[0], &demos[1..]);
    let initial = held.rows[0].clone();
    let none = Conditions::default();
    let hsom = cosco_hsom::app::config(None).unwrap().fit(train).unwrap();
    let hier = HsomStepper::new(&hsom, &initial, &none, None).unwrap();
    let dmp = DmpSettings::default().fit(train).unwrap();
    let dmp = DmpStepper::new(&dmp, &initial, &none, None).unwrap();
    let promp = PrompSettings::default().fit(train).unwrap();
    let promp = PrompStepper::new(&promp, &initial, &none, None).unwrap();
    for (name, (median, steps)) in [
        ("hierarchy", median_step(&hier, &initial, 20)),
        ("DMP", median_step(&dmp, &initial, 20)),
        ("ProMP", median_step(&promp, &initial, 20)),
    ] {
        eprintln!(
            "{name}: median undisturbed step {:.2} us ({steps} steps a reproduction)",
            median * 1e6
        );
    }
    // off the plan at phase 0.4: every joint 0.05 rad from where it was sent
    let (at, read) = stepped_to(&hier, &initial, 0.4);
    let off: Vec<f64> = read.iter().map(|v| v + 0.05).collect();
    {
        let mut s = at.clone();
        s.step(&off).unwrap();
        assert_eq!(
            s.replans(),
            at.replans() + 1,
            "the step off the plan re-plans"
        );
        eprintln!(
            "hierarchy: the re-plan at phase 0.4 reads {} postures",
            at.course().reading().len() + 1
        );
    }
    let mut g = c.benchmark_group("stepper_step_nao_wave");
    g.bench_function("hierarchy_on_plan", |b| {
        b.iter_custom(|iters| undisturbed(&hier, &initial, iters))
    });
    g.bench_function("hierarchy_replan_at_0.4", |b| {
        b.iter_batched(
            || at.clone(),
            |mut s| {
                s.step(black_box(&off)).unwrap();
                s
            },
            BatchSize::SmallInput,
        )
    });
    g.bench_function("dmp_on_plan", |b| {
        b.iter_custom(|iters| undisturbed(&dmp, &initial, iters))
    });
    g.bench_function("promp_on_plan", |b| {
        b.iter_custom(|iters| undisturbed(&promp, &initial, iters))
    });
    g.finish();
}

criterion_group!(benches, steppers);
criterion_main!(benches);
