use super::*;
use image::AnimationDecoder;

/// A 64x48 grey gradient with a 6x6 red square whose left edge is at `x`.
fn scene(x: u32) -> RgbImage {
    RgbImage::from_fn(64, 48, |px, py| {
        if (x..x + 6).contains(&px) && (20..26).contains(&py) {
            image::Rgb([200, 30, 20])
        } else {
            let v = (60 + px * 2 + py) as u8;
            image::Rgb([v, v, v.saturating_add(10)])
        }
    })
}

/// The frames as stored: position, size, transparency, delay.
fn stored(bytes: &[u8]) -> Vec<(u16, u16, u16, u16, Option<u8>, u16)> {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::Indexed);
    let mut decoder = options.read_info(bytes).unwrap();
    let mut frames = Vec::new();
    while let Some(f) = decoder.read_next_frame().unwrap() {
        frames.push((f.left, f.top, f.width, f.height, f.transparent, f.delay));
    }
    frames
}

/// Pixels of `a` and `b` that differ by more than 16 in some channel (NeuQuant places
/// its colours near, not on, the extremes of a gradient).
fn off(a: &image::RgbaImage, b: &RgbImage) -> usize {
    a.pixels()
        .zip(b.pixels())
        .filter(|(p, q)| (0..3).any(|c| p.0[c].abs_diff(q.0[c]) > 16))
        .count()
}

#[test]
fn after_the_first_frame_only_the_changed_pixels_are_stored() {
    let frames = [scene(10), scene(10), scene(14)];
    let refs: Vec<&RgbImage> = frames.iter().collect();
    let bytes = encode(&refs, 50).unwrap();
    let t = Some(TRANSPARENT);
    assert_eq!(
        stored(&bytes),
        vec![
            (0, 0, 64, 48, t, 5),
            // nothing changes: one transparent pixel keeps the time
            (0, 0, 1, 1, t, 5),
            // the square left columns 10..14 and covers 16..20: the box of both
            (10, 20, 10, 6, t, 5),
        ]
    );
}

#[test]
fn decoded_frames_show_the_input_frames() {
    let frames = [scene(10), scene(10), scene(14), scene(40)];
    let refs: Vec<&RgbImage> = frames.iter().collect();
    let bytes = encode(&refs, 40).unwrap();
    let decoder = image::codecs::gif::GifDecoder::new(std::io::Cursor::new(bytes)).unwrap();
    let decoded = decoder.into_frames().collect_frames().unwrap();
    assert_eq!(decoded.len(), frames.len());
    for (d, f) in decoded.iter().zip(&frames) {
        assert_eq!(off(d.buffer(), f), 0);
    }
    // control: a frame shown where another was is told apart (the squares' 72 pixels)
    assert!(off(decoded[3].buffer(), &frames[2]) >= 60);
}

#[test]
fn sizes_and_delays_gif_cannot_hold_are_errors() {
    let wide = RgbImage::new(65_536, 1);
    let err = encode(&[&wide], 40).unwrap_err();
    assert!(err.to_string().contains("65536x1"), "{err}");
    let frame = scene(0);
    let err = encode(&[&frame], 700_000).unwrap_err();
    assert!(err.to_string().contains("700000 ms"), "{err}");
    assert!(matches!(encode(&[], 40), Err(RenderError::NoFrames(_))));
}
