//! The rendered clip shows the motion: frames change while the arm moves and stop changing
//! while it holds (off-screen OSMesa, no display needed).
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use cosco_hsom::experiment::film::frame_sources;
use cosco_hsom::experiment::{film, record_demonstrations, DemoSettings};
use cosco_hsom::gesture::{library::reading_watch, Variation};
use cosco_hsom::render::{RenderOptions, Renderer};
use cosco_hsom::sim::{NaoArm, Recording};
use image::AnimationDecoder;

fn changed_fraction(a: &image::RgbImage, b: &image::RgbImage) -> f64 {
    let changed = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| p.0.iter().zip(q.0.iter()).any(|(x, y)| x.abs_diff(*y) > 8))
        .count();
    changed as f64 / (a.width() * a.height()) as f64
}

/// The `front` camera at 160x120, without multisampling.
fn front(shadows: bool) -> RenderOptions {
    RenderOptions {
        width: 160,
        height: 120,
        shadows,
        multisample: false,
        camera: Some("front".into()),
    }
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
    let opts = front(false);
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
fn a_reused_frame_matches_a_fresh_render_and_the_gif_decodes_to_every_frame() {
    let arm = NaoArm::load_default().unwrap();
    let rec = still_gesture(&arm);
    let opts = front(true);
    let stride = 4;
    let clip = film(&arm, &rec, &opts, stride, |_, _| {}).unwrap();
    let sources = frame_sources(&rec.qpos, stride);
    assert_eq!(sources.len(), clip.len());
    let frames: Vec<_> = clip.frames().map(|(_, f)| f.clone()).collect();

    // frames of a posture within STILL_RAD of the last rendered one show that rendering, and
    // a fresh rendering of their own posture looks the same
    let mut renderer = Renderer::new(arm.model(), opts).unwrap();
    let mut sim = arm.sim().unwrap();
    let mut reused = 0;
    for (n, &(i, source)) in sources.iter().enumerate() {
        if i == source {
            continue;
        }
        reused += 1;
        sim.set_posture_clamped(&rec.qpos[i]).unwrap();
        let fresh = renderer.render(sim.data()).unwrap();
        let diff = changed_fraction(&fresh, &frames[n]);
        assert!(
            diff < 0.001,
            "reused frame {n} differs {diff:.4} from its own rendering"
        );
    }
    assert!(
        reused >= 10,
        "only {reused} frames reused: the idle start and end hold"
    );

    // the GIF holds every frame, each close to its rendering
    let gif = clip.gif_bytes().unwrap();
    let decoded = image::codecs::gif::GifDecoder::new(std::io::Cursor::new(gif))
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
    assert_eq!(decoded.len(), frames.len());
    let rgb = |k: usize| image::DynamicImage::ImageRgba8(decoded[k].buffer().clone()).into_rgb8();
    let mut worst: f64 = 0.0;
    for (k, frame) in frames.iter().enumerate() {
        worst = worst.max(changed_fraction(&rgb(k), frame));
    }
    // control: the same measure tells the arm at rest from the arm mid-gesture
    let mid = changed_fraction(&rgb(frames.len() / 2), &frames[0]);
    assert!(
        worst < 0.01,
        "a decoded frame differs {worst:.4} from its rendering"
    );
    assert!(mid > 0.01, "mid-gesture differs only {mid:.4} from rest");
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
