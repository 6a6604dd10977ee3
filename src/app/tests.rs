use std::path::{Path, PathBuf};

use super::reproduce::ReproduceRequest;
use crate::condition::{Conditions, PostureArg};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/models")
        .join(name)
}

/// The CSV `cosco reproduce --model MODEL [--gesture G] --initial <rest>` writes.
#[cfg(feature = "sim")]
fn reproduced(model: &str, gesture: Option<&str>) -> Vec<u8> {
    let request = ReproduceRequest {
        model: fixture(model),
        gesture: gesture.map(String::from),
        initial: Some(PostureArg(vec![1.4, 0.3, -1.39, -1.01, 0.0, 0.25])),
        ..Default::default()
    };
    let r = request.run(&Conditions::default(), None).unwrap();
    super::reproduce::reproduction_csv(&r.columns, &r.rep).unwrap()
}

/// The fixtures were written by the simulator's builds, whose reproductions of the arm's
/// joints are held within the arm's ranges.
#[cfg(feature = "sim")]
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

/// The salute of `gestures.bin` from the fixtures' rest posture, at its own tempo or retimed
/// to `duration` seconds.
fn salute(duration: Option<f64>) -> super::Result<crate::hsom::Reproduction> {
    let request = ReproduceRequest {
        model: fixture("gestures.bin"),
        gesture: Some("salute".into()),
        initial: Some(PostureArg(vec![1.4, 0.3, -1.39, -1.01, 0.0, 0.25])),
        duration,
        ..Default::default()
    };
    Ok(request.run(&Conditions::default(), None)?.rep)
}

/// Seconds a reproduction lasts at the steps' 40 Hz.
fn seconds(rep: &crate::hsom::Reproduction) -> f64 {
    (rep.postures.len() - 1) as f64 / crate::export::DEFAULT_STEP_RATE_HZ
}

/// The mean over 201 phases of the mean joint distance between two paths, time normalised.
fn path_distance(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    let phases = (0..=200).map(|k| k as f64 / 200.0);
    let d: f64 = phases
        .map(|p| {
            let (x, y) = (crate::curve::at_phase(a, p), crate::curve::at_phase(b, p));
            x.iter().zip(&y).map(|(x, y)| (x - y).abs()).sum::<f64>() / x.len() as f64
        })
        .sum();
    d / 201.0
}

#[test]
fn a_duration_changes_the_tempo_and_keeps_the_path() {
    let own = salute(None).unwrap();
    for factor in [2.0, 3.0] {
        let asked = factor * seconds(&own);
        let rep = salute(Some(asked)).unwrap();
        assert!(
            (seconds(&rep) / asked - 1.0).abs() <= 0.05,
            "{factor}x: {} s",
            seconds(&rep)
        );
        let d = path_distance(&rep.postures, &own.postures);
        assert!(
            d <= 0.05,
            "{factor}x: {d} rad from the path at its own tempo"
        );
        assert_eq!(rep.steps, (0..rep.postures.len()).collect::<Vec<_>>());
        // the control: the reproduction at its own tempo is not of the duration asked
        assert!((seconds(&own) / asked - 1.0).abs() > 0.05);
    }
}

#[test]
fn a_duration_the_servos_cannot_follow_is_refused_naming_the_shortest_they_can() {
    let own = salute(None).unwrap();
    let e = salute(Some(0.5 * seconds(&own))).unwrap_err().to_string();
    assert!(e.contains("too fast for the left-arm's servos"), "{e}");
    let shortest: f64 = e
        .rsplit("can take is ")
        .next()
        .and_then(|s| s.trim_end_matches(" s").parse().ok())
        .unwrap_or_else(|| panic!("no shortest duration in: {e}"));
    // the shortest named is taken, and no joint then moves beyond its maximum velocity
    let rep = salute(Some(shortest)).unwrap();
    let names: Vec<String> = crate::robot::Robot::LeftArm
        .joint_names()
        .iter()
        .map(|s| s.to_string())
        .collect();
    let times = (0..rep.postures.len()).map(|k| k as f64 / 40.0).collect();
    let t = crate::export::Trajectory::new(names, times, rep.postures).unwrap();
    let limits = crate::export::limits::RobotLimits::of(crate::robot::Robot::LeftArm);
    assert!(limits.fastest(&t).unwrap().unwrap().ratio <= 1.0);
    // and a step less is refused
    assert!(salute(Some(shortest - 1.0 / 40.0)).is_err());
    for bad in [0.0, -1.0, f64::NAN, 1e9, 0.001] {
        let e = salute(Some(bad)).unwrap_err().to_string();
        assert!(e.contains("--duration"), "{bad}: {e}");
    }
}
