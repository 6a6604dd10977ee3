use super::*;

#[test]
fn panels_png_writes_a_nonblank_png() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("x.png");
    let mut panel = Panel::new("sine", "t (s)", "q (rad)");
    panel.series.push(Series::new(
        "demo",
        RGBColor(200, 0, 0),
        (0..100)
            .map(|i| (i as f64 * 0.1, (i as f64 * 0.1).sin()))
            .collect(),
    ));
    panel.ellipses.push(Ellipse {
        mean: (5.0, 0.0),
        cov: [[1.0, 0.3], [0.3, 0.2]],
        n_sigma: 1.0,
        color: RGBColor(0, 160, 0),
    });
    panels_png(&p, "test", &[panel], 1, (400, 300)).unwrap();
    let img = image::open(&p).unwrap().to_rgb8();
    // the title (40), the panel (300), and one row of the figure's legend below the panel
    assert_eq!(img.dimensions(), (400, 376));
    let non_white = img.pixels().filter(|px| px.0 != [255, 255, 255]).count();
    assert!(non_white > 1000, "only {non_white} drawn pixels");
    // the legend is in the strip below the panel: the series' sample in its colour
    let in_strip = (340..376)
        .flat_map(|y| (0..400).map(move |x| (x, y)))
        .filter(|&(x, y)| img.get_pixel(x, y).0 == [200, 0, 0])
        .count();
    assert!(in_strip > 10, "{in_strip} legend pixels below the panel");
}

#[test]
fn empty_panel_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("x.png");
    let err = panels_png(&p, "t", &[Panel::new("nothing", "x", "y")], 1, (200, 200)).unwrap_err();
    assert!(err.to_string().contains("nothing"), "{err}");
    assert!(!p.exists());
}

#[test]
fn ellipse_outline_matches_axis_aligned_radii() {
    let e = Ellipse {
        mean: (1.0, 2.0),
        cov: [[4.0, 0.0], [0.0, 1.0]],
        n_sigma: 2.0,
        color: BLACK,
    };
    let pts = ellipse_outline(&e, 4);
    assert!((pts[0].0 - 5.0).abs() < 1e-9 && (pts[0].1 - 2.0).abs() < 1e-9);
    assert!((pts[1].0 - 1.0).abs() < 1e-9 && (pts[1].1 - 4.0).abs() < 1e-9);
}

#[test]
fn tick_label_prints_a_tick_that_rounds_to_zero_without_a_sign() {
    use plotters::coord::ranged1d::ValueFormatter;
    let plotters = |v: f64| <RangedCoordf64 as ValueFormatter<f64>>::format(&v);
    // the key points of a range that crosses zero can land a rounding error below it, which
    // plotters alone prints with a sign
    assert_eq!(plotters(-1e-17), "-0.0");
    for v in [-1e-17, -0.0, -0.000001, 0.0, 1e-17] {
        assert_eq!(tick_label(v), "0.0", "{v}");
    }
    // everything else as plotters prints an f64 coordinate
    for (v, text) in [
        (-0.2, "-0.2"),
        (-0.0001, "-0.0001"),
        (-1.25, "-1.25"),
        (1.4, "1.4"),
        (3.0, "3.0"),
        (-10.0, "-10.0"),
    ] {
        assert_eq!(tick_label(v), text);
        assert_eq!(tick_label(v), plotters(v));
    }
}

#[test]
fn a_title_wider_than_its_one_panel_is_drawn_whole() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("x.png");
    let mut panel = Panel::new("one", "x", "y");
    panel
        .series
        .push(Series::new("", BLACK, vec![(0.0, 0.0), (1.0, 1.0)]));
    // `cosco heldout --png`'s title over its one panel of one gesture
    let title = "Held out (black), reproduced from its first sample";
    panels_png(&p, title, &[panel], 1, (420, 360)).unwrap();
    let img = image::open(&p).unwrap().to_rgb8();
    // nothing drawn in the title strip's first and last 4 pixel columns: not cut at either end
    let inked = |x: u32| (0..40).any(|y| img.get_pixel(x, y).0 != [255, 255, 255]);
    let edges: Vec<u32> = (0..4).chain(416..420).filter(|&x| inked(x)).collect();
    assert!(edges.is_empty(), "title ink at columns {edges:?}");
    // and it is there: ink in the middle of the strip
    assert!((100..320).any(inked));
}
