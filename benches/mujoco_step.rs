//! mj_step through the safe layer (`Data::step`) versus a raw FFI loop, on the Nao left arm
//! (models/nao_left_arm.xml), servos driven towards the "Stand" posture.
//!
//! `cargo bench --bench mujoco_step -- --warm-up-time 1 --measurement-time 3`

use cosco_hsom::mujoco::{ffi, Data, Model};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::ffi::CString;
use std::hint::black_box;
use std::path::Path;

const MODEL: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/models/nao_left_arm.xml");
/// Steps per measured iteration.
const STEPS: u64 = 1000;
/// Servo targets: the model's "Stand" keyframe.
#[allow(clippy::approx_constant)] // 1.4426 rad is the keyframe's shoulder pitch, not log2(e)
const STAND: [f64; 6] = [1.4426, 0.2245, -1.2023, -0.4173, 0.1, 0.3];

fn bench_step(c: &mut Criterion) {
    let model = Model::from_xml_path(Path::new(MODEL)).expect("models/nao_left_arm.xml loads");
    assert_eq!(model.nu(), STAND.len());
    let mut group = c.benchmark_group("mj_step nao_left_arm");
    group.throughput(Throughput::Elements(STEPS));

    let mut data = Data::new(&model).unwrap();
    data.ctrl_mut().copy_from_slice(&STAND);
    group.bench_function("safe Data::step", |b| {
        b.iter(|| {
            for _ in 0..STEPS {
                data.step().unwrap();
            }
            black_box(data.qpos()[0])
        })
    });
    drop(data);

    // The same model loaded and stepped with the raw bindings only.
    let path = CString::new(MODEL).unwrap();
    let mut err = [0 as std::ffi::c_char; 1000];
    // Safety: NUL-terminated path, no VFS, a writable error buffer of the given size. The
    // safe layer's error hooks are installed (Model::from_xml_path ran above).
    let m = unsafe { ffi::mj_loadXML(path.as_ptr(), std::ptr::null(), err.as_mut_ptr(), 1000) };
    assert!(!m.is_null(), "raw mj_loadXML failed");
    // Safety: `m` is a valid model.
    let d = unsafe { ffi::mj_makeData(m) };
    assert!(!d.is_null());
    // Safety: `d` is valid; ctrl has nu = 6 entries.
    unsafe { std::slice::from_raw_parts_mut((*d).ctrl, STAND.len()) }.copy_from_slice(&STAND);
    group.bench_function("raw ffi::mj_step", |b| {
        b.iter(|| {
            for _ in 0..STEPS {
                // Safety: valid model and data that belong together.
                unsafe { ffi::mj_step(m, d) };
            }
            // Safety: qpos has nq >= 1 entries.
            black_box(unsafe { *(*d).qpos })
        })
    });
    // Safety: created above, freed once, data before model.
    unsafe {
        ffi::mj_deleteData(d);
        ffi::mj_deleteModel(m);
    }
    group.finish();
}

criterion_group!(benches, bench_step);
criterion_main!(benches);
