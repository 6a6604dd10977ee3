//! The rendered clip shows the motion: frames change while the arm moves and stop changing
//! while it holds (off-screen OSMesa, no display needed).
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use cosco_hsom::experiment::{film, record_demonstrations, DemoSettings};
use cosco_hsom::gesture::{library::reading_watch, Variation};
use cosco_hsom::render::RenderOptions;
use cosco_hsom::sim::{NaoArm, Recording};

fn changed_fraction(a: &image::RgbImage, b: &image::RgbImage) -> f64 {
    let changed = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| p.0.iter().zip(q.0.iter()).any(|(x, y)| x.abs_diff(*y) > 8))
        .count();
    changed as f64 / (a.width() * a.height()) as f64
}

/// One reading-watch demonstration with no variability and no encoder noise: 1 s of
/// stillness, the gesture, 1 s of stillness.
fn still_gesture(arm: &NaoArm) -> Recording {
    let settings = DemoSettings {
        variation: Variation::none(),
        ..DemoSettings::default()
    };
    record_demonstrations(arm, &reading_watch(), 1, 3, &settings, |_| {})
        .unwrap()
        .remove(0)
}

#[test]
fn clip_frames_change_while_the_arm_moves_and_stop_while_it_holds() {
    let arm = NaoArm::load_default().unwrap();
    let rec = still_gesture(&arm);
    let opts = RenderOptions {
        width: 160,
        height: 120,
        shadows: false,
        multisample: false,
        camera: Some("front".into()),
    };
    let stride = 4; // 10 frames per second of motion
    let clip = film(&arm, &rec, &opts, stride, |_, _| {}).unwrap();
    let frames: Vec<_> = clip.frames().map(|(_, f)| f.clone()).collect();
    assert_eq!(frames.len(), rec.len().div_ceil(stride));

    let (mut still_pairs, mut moving_pairs) = (0, 0);
    for i in 0..frames.len() - 1 {
        let (a, b) = (i * stride, (i + 1) * stride);
        // Largest joint change between the two frames' postures (rad).
        let moved = rec.qpos[a]
            .iter()
            .zip(&rec.qpos[b])
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        let diff = changed_fraction(&frames[i], &frames[i + 1]);
        if moved < 1e-4 {
            still_pairs += 1;
            assert!(
                diff < 0.001,
                "frames {i}->{} changed {diff:.4} while the arm held",
                i + 1
            );
        } else if moved > 0.05 {
            moving_pairs += 1;
            assert!(
                diff > 0.003,
                "frames {i}->{} changed only {diff:.4} while a joint moved {moved:.3} rad",
                i + 1
            );
        }
    }
    assert!(
        still_pairs >= 10,
        "only {still_pairs} still frame pairs: the clip should show the idle start and end"
    );
    assert!(moving_pairs >= 10, "only {moving_pairs} moving frame pairs");
}

#[test]
fn film_rejects_a_zero_stride_and_an_empty_recording() {
    let arm = NaoArm::load_default().unwrap();
    let rec = still_gesture(&arm);
    let opts = RenderOptions {
        width: 64,
        height: 48,
        shadows: false,
        multisample: false,
        camera: None,
    };
    let e = film(&arm, &rec, &opts, 0, |_, _| {}).unwrap_err();
    assert!(e.to_string().contains("stride"), "{e}");
    let mut empty = rec.clone();
    empty.time.clear();
    empty.qpos.clear();
    let e = film(&arm, &empty, &opts, 1, |_, _| {}).unwrap_err();
    assert!(e.to_string().contains("empty"), "{e}");
}
