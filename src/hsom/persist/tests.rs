use super::*;

/// Saving runs the loader's checks first: a model whose statistics a file could not hold
/// is refused and no file appears.
#[test]
fn saving_refuses_what_loading_would_refuse_and_writes_nothing() {
    let mut p = crate::config::HsomParams::table1();
    p.state_length = 1;
    p.action_length = 1;
    let series: Vec<Vec<Vec<f64>>> = (0..2)
        .map(|k| (0..30 + k).map(|i| vec![(i as f64 / 10.0).sin()]).collect())
        .collect();
    let mut m = p
        .check("t")
        .unwrap()
        .fit(&crate::demos::Demonstration::from_series(&series))
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    for name in ["m.bin", "m.txt"] {
        m.save(&dir.path().join(name)).unwrap();
    }
    let Hsom::Paper(paper) = &mut m else {
        panic!("Table I is the paper's algorithm")
    };
    paper.dwell[0] = 1e300;
    for name in ["bad.bin", "bad.txt"] {
        let path = dir.path().join(name);
        let e = m.save(&path).unwrap_err();
        assert!(matches!(e, PersistError::Corrupted { .. }), "{e}");
        assert!(!path.exists(), "{name} was written");
    }
}
