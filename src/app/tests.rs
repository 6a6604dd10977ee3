use std::path::{Path, PathBuf};

use super::reproduce::{reproduction_csv, ReproduceRequest};
use crate::condition::{Conditions, PostureArg};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/models")
        .join(name)
}

/// The CSV `cosco reproduce --model MODEL [--gesture G] --initial <rest>` writes.
fn reproduced(model: &str, gesture: Option<&str>) -> Vec<u8> {
    let request = ReproduceRequest {
        model: fixture(model),
        gesture: gesture.map(String::from),
        initial: Some(PostureArg(vec![1.4, 0.3, -1.39, -1.01, 0.0, 0.25])),
        ..Default::default()
    };
    let r = request.run(&Conditions::default(), None).unwrap();
    reproduction_csv(&r.columns, &r.rep).unwrap()
}

#[test]
fn model_files_of_the_format_cosco_train_writes_load_and_reproduce_as_they_did() {
    let expect = |name: &str| std::fs::read(fixture(name)).unwrap();
    assert_eq!(reproduced("wave.txt", None), expect("wave-rep.csv"));
    for g in ["wave", "salute"] {
        let want = expect(&format!("gestures-{g}-rep.csv"));
        assert_eq!(reproduced("gestures.bin", Some(g)), want, "{g}");
    }
    // files of the format before the weighed score (version 26): they reproduce (above), and
    // recognition asks for them to be retrained, its thresholds being another score's
    let old = crate::hsom::GestureModel::load(&fixture("gestures.bin")).unwrap();
    let e = old.recognizer().err().unwrap();
    assert!(matches!(e, crate::hsom::GestureError::Recalibrate), "{e}");
    assert!(e.to_string().contains("retrain"), "{e}");
    // the control: another gesture's reproduction is not this one's
    assert_ne!(
        reproduced("gestures.bin", Some("salute")),
        expect("wave-rep.csv")
    );
}
