//! A 3x5 pixel font for labels on contact sheets (digits, lower-case letters and a few signs), so that
//! no font file or text-rendering crate is needed (ab_glyph, in the tree through plotters,
//! would redraw every contact sheet the main job writes, which stays as it is).

use image::{Rgb, RgbImage};

/// Rows of a glyph, 3 bits each, most significant bit on the left.
fn glyph(c: char) -> Option<[u8; 5]> {
    Some(match c {
        '0' => [0b111, 0b101, 0b101, 0b101, 0b111],
        '1' => [0b010, 0b110, 0b010, 0b010, 0b111],
        '2' => [0b111, 0b001, 0b111, 0b100, 0b111],
        '3' => [0b111, 0b001, 0b111, 0b001, 0b111],
        '4' => [0b101, 0b101, 0b111, 0b001, 0b001],
        '5' => [0b111, 0b100, 0b111, 0b001, 0b111],
        '6' => [0b111, 0b100, 0b111, 0b101, 0b111],
        '7' => [0b111, 0b001, 0b010, 0b010, 0b010],
        '8' => [0b111, 0b101, 0b111, 0b101, 0b111],
        '9' => [0b111, 0b101, 0b111, 0b001, 0b111],
        '.' => [0b000, 0b000, 0b000, 0b000, 0b010],
        '-' => [0b000, 0b000, 0b111, 0b000, 0b000],
        '=' => [0b000, 0b111, 0b000, 0b111, 0b000],
        ':' => [0b000, 0b010, 0b000, 0b010, 0b000],
        '#' => [0b101, 0b111, 0b101, 0b111, 0b101],
        's' => [0b000, 0b111, 0b110, 0b011, 0b111],
        't' => [0b010, 0b111, 0b010, 0b010, 0b011],
        'a' => [0b000, 0b011, 0b101, 0b101, 0b011],
        'b' => [0b100, 0b110, 0b101, 0b101, 0b110],
        'c' => [0b000, 0b011, 0b100, 0b100, 0b011],
        'd' => [0b001, 0b011, 0b101, 0b101, 0b011],
        'e' => [0b010, 0b101, 0b111, 0b100, 0b011],
        'f' => [0b011, 0b100, 0b110, 0b100, 0b100],
        'g' => [0b011, 0b101, 0b011, 0b001, 0b110],
        'h' => [0b100, 0b110, 0b101, 0b101, 0b101],
        'i' => [0b010, 0b000, 0b010, 0b010, 0b010],
        'j' => [0b001, 0b000, 0b001, 0b101, 0b010],
        'k' => [0b100, 0b101, 0b110, 0b110, 0b101],
        'l' => [0b110, 0b010, 0b010, 0b010, 0b111],
        'm' => [0b000, 0b111, 0b111, 0b101, 0b101],
        'n' => [0b000, 0b110, 0b101, 0b101, 0b101],
        'o' => [0b000, 0b010, 0b101, 0b101, 0b010],
        'p' => [0b110, 0b101, 0b110, 0b100, 0b100],
        'q' => [0b011, 0b101, 0b011, 0b001, 0b001],
        'r' => [0b000, 0b101, 0b110, 0b100, 0b100],
        'u' => [0b000, 0b101, 0b101, 0b101, 0b011],
        'v' => [0b000, 0b101, 0b101, 0b101, 0b010],
        'w' => [0b000, 0b101, 0b101, 0b111, 0b111],
        'x' => [0b000, 0b101, 0b010, 0b010, 0b101],
        'y' => [0b101, 0b101, 0b011, 0b001, 0b110],
        'z' => [0b111, 0b001, 0b010, 0b100, 0b111],
        ' ' => [0; 5],
        _ => return None,
    })
}

/// Draw `text` with its top-left corner at (`x`, `y`), each font pixel a `scale`x`scale`
/// square, on a dark box for contrast. Unknown characters are drawn as blanks; pixels outside
/// the image are skipped.
pub(crate) fn draw_label(img: &mut RgbImage, x: u32, y: u32, scale: u32, text: &str) {
    let n = text.chars().count() as u32;
    let (box_w, box_h) = ((4 * n + 1) * scale, 7 * scale);
    fill(img, x, y, box_w, box_h, Rgb([20, 20, 20]));
    for (i, c) in text.chars().enumerate() {
        let rows = glyph(c).unwrap_or([0; 5]);
        let gx = x + (1 + 4 * i as u32) * scale;
        for (r, bits) in rows.iter().enumerate() {
            for col in 0..3 {
                if bits & (0b100 >> col) != 0 {
                    fill(
                        img,
                        gx + col * scale,
                        y + (1 + r as u32) * scale,
                        scale,
                        scale,
                        Rgb([255, 255, 255]),
                    );
                }
            }
        }
    }
}

fn fill(img: &mut RgbImage, x: u32, y: u32, w: u32, h: u32, color: Rgb<u8>) {
    for yy in y..(y + h).min(img.height()) {
        for xx in x..(x + w).min(img.width()) {
            img.put_pixel(xx, yy, color);
        }
    }
}

#[cfg(test)]
mod tests;
