//! Off-screen rendering through the public API: real pixels, no display.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use cosco_hsom::mujoco::{Data, Model};
use cosco_hsom::render::{Clip, RenderError, RenderOptions, Renderer};
use image::RgbImage;

/// A two-joint arm over a floor, with a light and two fixed cameras.
const ARM: &str = r#"
<mujoco model="render_arm">
  <compiler autolimits="true"/>
  <visual><global offwidth="800" offheight="600"/></visual>
  <worldbody>
    <light pos="0 -1 2" dir="0 0.5 -1" castshadow="true"/>
    <geom name="floor" type="plane" size="2 2 0.1" rgba="0.6 0.6 0.65 1"/>
    <camera name="front" pos="0 -1.6 0.6" xyaxes="1 0 0 0 0.3 1"/>
    <camera name="top" pos="0 0 2.5" xyaxes="1 0 0 0 1 0"/>
    <body name="upper" pos="0 0 0.6">
      <joint name="shoulder" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0.35 0 0" size="0.05" rgba="0.9 0.2 0.1 1"/>
      <body name="lower" pos="0.35 0 0">
        <joint name="elbow" type="hinge" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.04" rgba="0.1 0.3 0.9 1"/>
      </body>
    </body>
  </worldbody>
</mujoco>
"#;

fn opts(width: usize, height: usize) -> RenderOptions {
    RenderOptions {
        width,
        height,
        shadows: false,
        multisample: false,
        camera: Some("front".into()),
    }
}

fn posed<'m>(m: &'m Model, shoulder: f64, elbow: f64) -> Data<'m> {
    let mut d = Data::new(m).unwrap();
    d.qpos_mut().copy_from_slice(&[shoulder, elbow]);
    d.forward().unwrap();
    d
}

fn variance(img: &RgbImage) -> f64 {
    let v: Vec<f64> = img.as_raw().iter().map(|&b| b as f64).collect();
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / v.len() as f64
}

/// Fraction of pixels whose colour differs by more than 30 (sum over channels).
fn changed_fraction(a: &RgbImage, b: &RgbImage) -> f64 {
    assert_eq!(a.dimensions(), b.dimensions());
    let changed = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| {
            p.0.iter()
                .zip(q.0.iter())
                .map(|(x, y)| x.abs_diff(*y) as u32)
                .sum::<u32>()
                > 30
        })
        .count();
    changed as f64 / (a.width() * a.height()) as f64
}

#[test]
fn frame_is_not_blank_and_has_the_requested_size() {
    let m = Model::from_xml_str(ARM).unwrap();
    let d = posed(&m, 0.0, 0.0);
    let mut r = Renderer::new(&m, opts(320, 240)).unwrap();
    let img = r.render(&d).unwrap();
    assert_eq!(img.dimensions(), (320, 240));
    assert!(variance(&img) > 100.0, "variance {}", variance(&img));
    // The red upper arm is in view of the front camera.
    let red = img
        .pixels()
        .filter(|p| p.0[0] > 120 && p.0[1] < 80 && p.0[2] < 80)
        .count();
    assert!(red > 100, "red pixels: {red}");
}

#[test]
fn image_is_top_down() {
    // The front camera looks slightly down at the arm above a floor: the floor (grey) fills
    // the bottom rows, the sky (black background) the top rows.
    let m = Model::from_xml_str(ARM).unwrap();
    let d = posed(&m, 0.0, 0.0);
    let mut r = Renderer::new(&m, opts(160, 120)).unwrap();
    let img = r.render(&d).unwrap();
    let row_mean = |y: u32| {
        (0..img.width())
            .map(|x| img.get_pixel(x, y).0.iter().map(|&c| c as u32).sum::<u32>())
            .sum::<u32>() as f64
            / img.width() as f64
    };
    assert!(
        row_mean(img.height() - 1) > row_mean(0) + 50.0,
        "bottom {} top {}",
        row_mean(img.height() - 1),
        row_mean(0)
    );
}

#[test]
fn two_postures_give_different_frames_and_same_posture_the_same() {
    let m = Model::from_xml_str(ARM).unwrap();
    let mut r = Renderer::new(&m, opts(320, 240)).unwrap();
    let a = r.render(&posed(&m, 0.0, 0.0)).unwrap();
    let a2 = r.render(&posed(&m, 0.0, 0.0)).unwrap();
    let b = r.render(&posed(&m, -1.2, 1.0)).unwrap();
    assert!(
        changed_fraction(&a, &a2) < 0.001,
        "same posture: {}",
        changed_fraction(&a, &a2)
    );
    assert!(
        changed_fraction(&a, &b) > 0.01,
        "different postures: {}",
        changed_fraction(&a, &b)
    );
}

#[test]
fn cameras_see_different_things() {
    let m = Model::from_xml_str(ARM).unwrap();
    let d = posed(&m, 0.0, 0.0);
    let front = Renderer::new(&m, opts(160, 120))
        .unwrap()
        .render(&d)
        .unwrap();
    let top = Renderer::new(
        &m,
        RenderOptions {
            camera: Some("top".into()),
            ..opts(160, 120)
        },
    )
    .unwrap()
    .render(&d)
    .unwrap();
    let free = Renderer::new(
        &m,
        RenderOptions {
            camera: None,
            ..opts(160, 120)
        },
    )
    .unwrap()
    .render(&d)
    .unwrap();
    assert!(changed_fraction(&front, &top) > 0.05);
    assert!(changed_fraction(&front, &free) > 0.05);
    assert!(variance(&free) > 100.0);
}

#[test]
fn size_beyond_offwidth_is_an_error_naming_the_attribute() {
    let m = Model::from_xml_str(ARM).unwrap();
    let err = Renderer::new(&m, opts(801, 600)).unwrap_err();
    assert!(
        matches!(
            err,
            RenderError::TooLarge {
                width: 801,
                height: 600,
                max_width: 800,
                max_height: 600
            }
        ),
        "{err:?}"
    );
    let text = err.to_string();
    assert!(
        text.contains("offwidth") && text.contains("offheight"),
        "{text}"
    );
    // default MJCF: 640x480
    let small =
        Model::from_xml_str("<mujoco><worldbody><geom size='0.1'/></worldbody></mujoco>").unwrap();
    assert!(Renderer::new(
        &small,
        RenderOptions {
            camera: None,
            ..opts(640, 480)
        }
    )
    .is_ok());
    assert!(matches!(
        Renderer::new(
            &small,
            RenderOptions {
                camera: None,
                ..opts(640, 481)
            }
        ),
        Err(RenderError::TooLarge { .. })
    ));
    assert!(matches!(
        Renderer::new(&m, opts(0, 10)),
        Err(RenderError::EmptySize { .. })
    ));
}

#[test]
fn unknown_camera_is_an_error_listing_the_cameras() {
    let m = Model::from_xml_str(ARM).unwrap();
    let err = Renderer::new(
        &m,
        RenderOptions {
            camera: Some("side".into()),
            ..opts(64, 48)
        },
    )
    .unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("side") && text.contains("front, top"),
        "{text}"
    );
}

#[test]
fn data_of_another_model_is_refused() {
    let m = Model::from_xml_str(ARM).unwrap();
    let other = Model::from_xml_str(ARM).unwrap();
    let mut r = Renderer::new(&m, opts(64, 48)).unwrap();
    let d = posed(&other, 0.0, 0.0);
    assert!(matches!(r.render(&d), Err(RenderError::WrongModel)));
}

#[test]
fn shadows_and_multisampling_switch_at_runtime() {
    let m = Model::from_xml_str(ARM).unwrap();
    let d = posed(&m, -0.3, 0.5);
    let mut r = Renderer::new(&m, opts(200, 150)).unwrap();
    assert!(!r.shadows() && !r.multisample());
    let plain = r.render(&d).unwrap();
    r.set_shadows(true);
    let shadowed = r.render(&d).unwrap();
    assert!(
        changed_fraction(&plain, &shadowed) > 0.002,
        "shadows changed {}",
        changed_fraction(&plain, &shadowed)
    );
    r.set_shadows(false);
    r.set_multisample(true).unwrap();
    assert!(r.multisample());
    let smooth = r.render(&d).unwrap();
    let diff = changed_fraction(&plain, &smooth);
    assert!(
        diff > 0.0 && diff < 0.2,
        "anti-aliasing changes edges only: {diff}"
    );
    r.set_multisample(false).unwrap();
    let again = r.render(&d).unwrap();
    assert!(changed_fraction(&plain, &again) < 0.001);
}

#[test]
fn renders_in_two_threads_at_once() {
    let m = Model::from_xml_str(ARM).unwrap();
    let reference = Renderer::new(&m, opts(160, 120))
        .unwrap()
        .render(&posed(&m, 0.4, -0.6))
        .unwrap();
    let frames: Vec<RgbImage> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..2)
            .map(|_| {
                let m = &m;
                s.spawn(move || {
                    let mut r = Renderer::new(m, opts(160, 120)).unwrap();
                    let d = posed(m, 0.4, -0.6);
                    let mut last = None;
                    for _ in 0..5 {
                        last = Some(r.render(&d).unwrap());
                    }
                    last.unwrap()
                })
            })
            .collect();
        hs.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for f in &frames {
        assert!(changed_fraction(f, &reference) < 0.001);
    }
}

#[test]
fn two_renderers_in_one_thread_keep_their_own_contexts() {
    let m = Model::from_xml_str(ARM).unwrap();
    let d = posed(&m, 0.0, 0.0);
    let mut small = Renderer::new(&m, opts(80, 60)).unwrap();
    let mut big = Renderer::new(&m, opts(320, 240)).unwrap();
    let s1 = small.render(&d).unwrap();
    let b1 = big.render(&d).unwrap();
    let s2 = small.render(&d).unwrap();
    assert_eq!(b1.dimensions(), (320, 240));
    assert_eq!(s1, s2);
    drop(big);
    assert_eq!(small.render(&d).unwrap(), s1);
}

#[test]
fn png_gif_and_contact_sheet_are_written() {
    let m = Model::from_xml_str(ARM).unwrap();
    let mut d = Data::new(&m).unwrap();
    let mut r = Renderer::new(&m, opts(120, 90)).unwrap();
    let mut clip = Clip::new(40).unwrap();
    d.qpos_mut()[0] = -1.0;
    for i in 0..50 {
        for _ in 0..10 {
            d.step().unwrap();
        }
        if i % 5 == 0 {
            clip.push(d.time(), r.render(&d).unwrap()).unwrap();
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("frame.png");
    r.render_to_png(&d, &png).unwrap();
    assert_eq!(image::open(&png).unwrap().to_rgb8().dimensions(), (120, 90));

    let gif = dir.path().join("clip.gif");
    clip.write_gif(&gif).unwrap();
    assert_eq!(&std::fs::read(&gif).unwrap()[..6], b"GIF89a");

    let sheet = dir.path().join("sheet.png");
    clip.write_contact_sheet(&sheet, &clip.key_frames(6), 3, true)
        .unwrap();
    let img = image::open(&sheet).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (3 * 120 + 4 * 4, 2 * 90 + 3 * 4));
    // the falling arm: first and last key frames differ
    let first = image::imageops::crop_imm(&img, 4, 4, 120, 90).to_image();
    let last = image::imageops::crop_imm(&img, 4 + 2 * 124, 4 + 94, 120, 90).to_image();
    assert!(changed_fraction(&first, &last) > 0.01);

    let bad = dir.path().join("missing").join("x.png");
    let err = r.render_to_png(&d, &bad).unwrap_err();
    assert!(err.to_string().contains("missing"), "{err}");
}

#[test]
fn nao_arm_renders_from_its_cameras_and_postures_differ() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models/nao_left_arm.xml");
    let m = Model::from_xml_path(&path).unwrap();
    #[allow(clippy::approx_constant)] // the Stand keyframe, not log2(e)
    let stand = [1.4426, 0.2245, -1.2023, -0.4173, 0.1, 0.3];
    let zero = [0.0, 0.0087, 0.0, -0.0349066, 0.0, 0.0];
    let pose = |q: &[f64; 6]| {
        let mut d = Data::new(&m).unwrap();
        d.qpos_mut().copy_from_slice(q);
        d.forward().unwrap();
        d
    };
    for camera in ["front", "side"] {
        let mut r = Renderer::new(
            &m,
            RenderOptions {
                camera: Some(camera.into()),
                ..opts(240, 180)
            },
        )
        .unwrap();
        let a = r.render(&pose(&stand)).unwrap();
        let b = r.render(&pose(&zero)).unwrap();
        assert!(variance(&a) > 100.0, "{camera}: variance {}", variance(&a));
        let diff = changed_fraction(&a, &b);
        assert!(diff > 0.01, "{camera}: postures differ by {diff}");
    }
}
