use super::*;

fn solid(v: u8) -> RgbImage {
    RgbImage::from_pixel(8, 6, image::Rgb([v, v, v]))
}

#[test]
fn key_frames_are_evenly_spaced_and_include_both_ends() {
    let mut clip = Clip::new(40).unwrap();
    for i in 0..11 {
        clip.push(i as f64, solid(i as u8)).unwrap();
    }
    assert_eq!(clip.key_frames(3), vec![0, 5, 10]);
    assert_eq!(clip.key_frames(1), vec![0]);
    assert_eq!(clip.key_frames(50).len(), 11);
    assert_eq!(clip.key_frames(0), Vec::<usize>::new());
}

#[test]
fn key_frames_show_every_window() {
    let mut clip = Clip::new(40).unwrap();
    for i in 0..21 {
        clip.push(i as f64 * 0.5, solid(i as u8)).unwrap();
    }
    // evenly spaced: frames 0, 10, 20 (t = 0, 5, 10 s); no frame inside 6.0-7.5 s
    assert_eq!(clip.key_frames(3), vec![0, 10, 20]);
    // the nearest key frame (10) moves to the window's middle frame (t = 6.5 s: frame 13)
    assert_eq!(clip.key_frames_within(3, &[(6.0, 7.5)]), vec![0, 13, 20]);
    // a window a key frame already shows changes nothing; an empty window neither
    assert_eq!(
        clip.key_frames_within(3, &[(4.5, 5.5), (30.0, 31.0)]),
        vec![0, 10, 20]
    );
}

#[test]
fn contact_sheet_places_frames_in_a_grid() {
    let mut clip = Clip::new(40).unwrap();
    for i in 0..5 {
        clip.push(i as f64, solid(40 * i as u8)).unwrap();
    }
    let sheet = clip.contact_sheet(&clip.key_frames(5), 3, false).unwrap();
    assert_eq!(sheet.dimensions(), (3 * 8 + 4 * 4, 2 * 6 + 3 * 4));
    // frame 4 (value 160) is at row 1, column 1
    assert_eq!(sheet.get_pixel(4 + 12 + 1, 4 + 10 + 1).0, [160, 160, 160]);
    // gutter is white
    assert_eq!(sheet.get_pixel(0, 0).0, [255, 255, 255]);
}

#[test]
fn gif_has_one_frame_per_pushed_frame() {
    let mut clip = Clip::new(50).unwrap();
    for i in 0..3 {
        clip.push(i as f64, solid(80 * i as u8)).unwrap();
    }
    let bytes = clip.gif_bytes().unwrap();
    assert_eq!(&bytes[..6], b"GIF89a");
    use image::AnimationDecoder;
    let dec = image::codecs::gif::GifDecoder::new(std::io::Cursor::new(bytes)).unwrap();
    let frames = dec.into_frames().collect_frames().unwrap();
    assert_eq!(frames.len(), 3);
    let (num, den) = frames[1].delay().numer_denom_ms();
    assert_eq!(num / den, 50);
}

#[test]
fn bad_inputs_are_errors() {
    assert!(matches!(Clip::new(0), Err(RenderError::Invalid { .. })));
    let clip = Clip::new(40).unwrap();
    assert!(matches!(clip.gif_bytes(), Err(RenderError::NoFrames(_))));
    assert!(matches!(
        clip.contact_sheet(&clip.key_frames(3), 2, true),
        Err(RenderError::NoFrames(_))
    ));
    let mut clip = Clip::new(40).unwrap();
    clip.push(0.0, solid(0)).unwrap();
    let err = clip.push(0.1, RgbImage::new(4, 4)).unwrap_err();
    assert!(matches!(err, RenderError::FrameSize { index: 1, .. }));
    assert!(matches!(
        clip.contact_sheet(&clip.key_frames(1), 0, false),
        Err(RenderError::Invalid { .. })
    ));
}
