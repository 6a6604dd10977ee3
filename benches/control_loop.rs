//! Headless control loop: controller + physics step + 40 Hz recording over a 10 s simulated
//! gesture. Criterion's time per iteration gives the real-time factor: 10 s / time.
//!
//! `cargo bench --bench control_loop`

use std::time::Instant;

use cosco_hsom::sim::{
    Controller, ControllerConfig, KeyPose, NamedPosture, NaoArm, TargetTrajectory,
};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};

/// Simulated length of each gesture, s.
const GESTURE_SECONDS: f64 = 10.0;

/// Key poses: StandInit -> ReadingWatch -> Stand -> StandZero -> Crouch -> StandInit, each
/// transition at least 1.5 s, with holds, 10 s in total.
fn key_poses() -> Vec<KeyPose> {
    let pose = |p: NamedPosture, d: f64, h: f64| {
        KeyPose::new(&p.angles())
            .unwrap()
            .with_min_duration(d)
            .unwrap()
            .with_hold(h)
            .unwrap()
    };
    vec![
        pose(NamedPosture::ReadingWatch, 1.5, 1.0),
        pose(NamedPosture::Stand, 1.5, 0.5),
        pose(NamedPosture::StandZero, 1.5, 0.5),
        pose(NamedPosture::Crouch, 1.5, 0.5),
        pose(NamedPosture::StandInit, 1.5, 0.0),
    ]
}

/// A dense 40 Hz gesture: a waving motion around StandZero-like postures, 10 s.
fn dense_targets() -> Vec<Vec<f64>> {
    let n = (GESTURE_SECONDS * 40.0) as usize;
    (0..n)
        .map(|i| {
            let t = i as f64 / 40.0;
            let s = (std::f64::consts::TAU * 0.4 * t).sin();
            vec![
                0.3 + 0.5 * s,
                0.5 + 0.3 * s,
                -0.6 + 0.8 * s,
                -0.8 + 0.4 * s,
                0.6 * s,
                0.5 + 0.4 * s,
            ]
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let arm = NaoArm::load_default().expect("model loads");
    let ctl = Controller::new(ControllerConfig::default()).unwrap();
    let poses = key_poses();
    let dense = dense_targets();
    let first: [f64; 6] = dense[0].clone().try_into().unwrap();
    let traj = TargetTrajectory::at_rate(40.0, &dense).unwrap();
    let steps = (GESTURE_SECONDS / arm.timestep()).round() as u64;

    // one quick figure on stderr, before criterion's statistics
    let mut sim = arm.sim().unwrap();
    let start = Instant::now();
    let rec = ctl.execute(&mut sim, &poses).unwrap();
    let wall = start.elapsed().as_secs_f64();
    let simulated = rec.len() as f64 / 40.0;
    eprintln!(
        "key-pose gesture: {simulated:.1} s simulated, {} samples, {wall:.4} s wall: real-time factor {:.0}",
        rec.len(),
        simulated / wall
    );

    let mut g = c.benchmark_group("control_loop_10s");
    g.throughput(Throughput::Elements(steps));
    g.bench_function("key_poses_min_jerk_40hz", |b| {
        b.iter(|| {
            let mut sim = arm.sim().unwrap();
            ctl.execute(&mut sim, &poses).unwrap()
        })
    });
    g.bench_function("follow_dense_40hz", |b| {
        b.iter(|| {
            let mut sim = arm.sim().unwrap();
            sim.set_posture(&first).unwrap();
            ctl.follow(&mut sim, &traj).unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
