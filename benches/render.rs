//! Off-screen frames per second (mjv_updateScene + mjr_render + readPixels + flip) of the Nao
//! left arm from its "front" camera, at 320x240 and 640x480, with and without shadows and 4x
//! multisampling.
//!
//! `cargo bench --bench render -- --warm-up-time 1 --measurement-time 3`

use cosco_hsom::mujoco::{Data, Model};
use cosco_hsom::render::{RenderOptions, Renderer};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use std::path::Path;

const MODEL: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/models/nao_left_arm.xml");
#[allow(clippy::approx_constant)] // 1.4426 rad is the keyframe's shoulder pitch, not log2(e)
const STAND: [f64; 6] = [1.4426, 0.2245, -1.2023, -0.4173, 0.1, 0.3];

fn bench_render(c: &mut Criterion) {
    let model = Model::from_xml_path(Path::new(MODEL)).expect("models/nao_left_arm.xml loads");
    let mut data = Data::new(&model).unwrap();
    data.qpos_mut().copy_from_slice(&STAND);
    data.forward().unwrap();

    let mut group = c.benchmark_group("render nao_left_arm front");
    group.throughput(Throughput::Elements(1));
    for (width, height) in [(320, 240), (640, 480)] {
        for quality in [false, true] {
            let opts = RenderOptions {
                width,
                height,
                shadows: quality,
                multisample: quality,
                camera: Some("front".into()),
            };
            let mut renderer = Renderer::new(&model, opts).unwrap();
            let label = if quality { "shadows+msaa" } else { "plain" };
            group.bench_function(format!("{width}x{height} {label}"), |b| {
                b.iter(|| black_box(renderer.render(&data).unwrap()))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench_render);
criterion_main!(benches);
