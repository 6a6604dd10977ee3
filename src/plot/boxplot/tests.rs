use super::*;

#[test]
fn whiskers_stop_at_one_and_a_half_iqr_and_outliers_are_kept() {
    let b = boxed(&[1.0, 2.0, 3.0, 4.0, 100.0]).unwrap();
    assert_eq!((b.q1, b.median, b.q3), (2.0, 3.0, 4.0));
    assert_eq!((b.low, b.high), (1.0, 4.0));
    assert_eq!(b.outliers, vec![100.0]);
}

#[test]
fn boxplots_png_writes_a_png_and_refuses_an_empty_panel() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("b.png");
    let mut panel = BoxPanel {
        title: "t".into(),
        y_label: "rad".into(),
        categories: vec!["a".into(), "b".into()],
        series: vec![
            ("x".into(), RGBColor(0, 0, 200)),
            ("y".into(), RGBColor(200, 0, 0)),
        ],
        values: vec![
            vec![vec![1.0, 2.0, 3.0], vec![2.0, 2.5]],
            vec![vec![0.5], vec![]],
        ],
    };
    boxplots_png(&p, "title", std::slice::from_ref(&panel), 1, (400, 300)).unwrap();
    let img = image::open(&p).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (400, 340));
    assert!(img.pixels().any(|px| px.0 == [0, 0, 200]), "no box drawn");
    panel.values = vec![vec![vec![], vec![f64::NAN]]];
    let e = boxplots_png(&p, "title", &[panel], 1, (400, 300)).unwrap_err();
    assert!(matches!(e, PlotError::Empty { .. }), "{e}");
}
