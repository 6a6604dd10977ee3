//! A caption drawn onto a rendered frame (a clip's contact sheet names what each frame shows),
//! and a mark on a point of it (the link a force pushes, with the force's direction).

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

/// Mark the pixel `at` of `frame` with a red ring of `radius` pixels and, when `toward` is
/// given, a red arrow from the ring's centre to it (a force's direction as the frame shows
/// it). Nothing is drawn outside the frame.
pub fn mark(frame: &mut image::RgbImage, at: (f64, f64), radius: u32, toward: Option<(f64, f64)>) {
    let (w, h) = frame.dimensions();
    let buf: &mut [u8] = frame.as_mut();
    let root = BitMapBackend::with_buffer(buf, (w, h)).into_drawing_area();
    let p = |(x, y): (f64, f64)| (x.round() as i32, y.round() as i32);
    let style = ShapeStyle::from(&RED).stroke_width(3);
    // drawing on an in-memory buffer of the right size cannot fail; a failure would only
    // leave the frame unmarked
    let _ = root.draw(&Circle::new(p(at), radius as i32, style));
    if let Some(to) = toward {
        let _ = root.draw(&PathElement::new(vec![p(at), p(to)], style));
        // the arrow's head: two strokes back from its tip, 30 degrees either side
        let (dx, dy) = (to.0 - at.0, to.1 - at.1);
        let len = (dx * dx + dy * dy).sqrt();
        if len > 1.0 {
            let (ux, uy) = (dx / len, dy / len);
            let head = 0.3 * len.min(40.0);
            for s in [-1.0f64, 1.0] {
                let (c, sn) = (30f64.to_radians().cos(), s * 30f64.to_radians().sin());
                let back = (
                    to.0 - head * (ux * c - uy * sn),
                    to.1 - head * (uy * c + ux * sn),
                );
                let _ = root.draw(&PathElement::new(vec![p(to), p(back)], style));
            }
        }
    }
    let _ = root.present();
}
