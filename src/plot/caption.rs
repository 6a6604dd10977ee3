//! A caption drawn onto a rendered frame (a clip's contact sheet names what each frame shows).

use plotters::prelude::*;

use super::figure::register_font;

/// Draw `text` in the top-left corner of `frame` on a white box, in the shipped sans-serif
/// font at `size` pixels. The frame keeps its size; nothing is drawn on a frame too small for
/// the box.
pub fn caption(frame: &mut image::RgbImage, text: &str, size: u32) {
    register_font();
    let (w, h) = frame.dimensions();
    let box_h = size + size / 2;
    if w < 8 || h < box_h + 2 {
        return;
    }
    let box_w = (text.chars().count() as u32 * size * 6 / 10 + size).min(w);
    let buf: &mut [u8] = frame.as_mut();
    let root = BitMapBackend::with_buffer(buf, (w, h)).into_drawing_area();
    // drawing on an in-memory buffer of the right size cannot fail; a failure would only
    // leave the frame without its caption
    let _ = root.draw(&Rectangle::new(
        [(0, 0), (box_w as i32, box_h as i32)],
        WHITE.mix(0.85).filled(),
    ));
    let _ = root.draw(&Text::new(
        text.to_string(),
        (size as i32 / 3, size as i32 / 5),
        ("sans-serif", size as f64).into_font().color(&BLACK),
    ));
    let _ = root.present();
}
