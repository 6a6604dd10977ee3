use super::*;

#[test]
fn label_draws_white_pixels_inside_its_box_only() {
    let mut img = RgbImage::new(40, 20);
    draw_label(&mut img, 2, 3, 1, "1.5s");
    let white = img.pixels().filter(|p| p.0 == [255, 255, 255]).count();
    assert!(white > 5);
    for (x, y, p) in img.enumerate_pixels() {
        if p.0 != [0, 0, 0] {
            assert!(
                (2..2 + 17).contains(&x) && (3..3 + 7).contains(&y),
                "pixel at {x},{y}"
            );
        }
    }
}

#[test]
fn label_past_the_edge_does_not_panic() {
    let mut img = RgbImage::new(8, 8);
    draw_label(&mut img, 6, 6, 3, "12.25 s");
}
