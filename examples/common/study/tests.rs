use super::*;

/// A summary with the given joint DTW, reversals (reproduction, demonstrations) and
/// jerk (reproduction, demonstrations); the rest plain.
fn summary(dtw: f64, rev: (f64, f64), jerk: (f64, f64)) -> HeldOutSummary {
    HeldOutSummary {
        folds: 2,
        joint_dtw_rad_per_step: dtw,
        wrist_dtw_mm: Some(10.0 * dtw),
        apex_error_rad: 0.1,
        final_error_rad: 0.01,
        duration_ratio: 1.0,
        normalized_jerk: Some(jerk.0),
        velocity_reversals: rev.0,
        demo_normalized_jerk: Some(jerk.1),
        demo_velocity_reversals: rev.1,
        swings: 0.0,
        demo_swings: 0.0,
        hold_s: 1.0,
        demo_hold_s: 1.1,
        start_speed: None,
        demo_start_speed_max: None,
        start_in_range: None,
        end_within_spread: None,
        commanded_normalized_jerk: None,
        commanded_start_speed: None,
        commanded_start_in_range: None,
        commanded_end_within_spread: None,
        coverage: None,
    }
}

fn row(
    gesture: &str,
    seed: u64,
    hsom: HeldOutSummary,
    gmr: f64,
    swings: &[(usize, usize)],
) -> GateRow {
    GateRow {
        gesture: gesture.into(),
        seed,
        paired: Some((hsom.clone(), summary(gmr, (4.0, 4.0), (100.0, 100.0)))),
        hsom,
        swings: swings.iter().map(|&(r, d)| (r, d, Some(d))).collect(),
    }
}

/// The gates name every set that fails one, and a control that breaks each (reversals
/// above, jerk above, a lost swing, a far reproduction) fails it.
#[test]
fn gates_name_the_sets_that_fail_and_the_controls_fail_them() {
    let good = vec![
        row(
            "wave",
            1,
            summary(0.10, (10.0, 10.0), (150.0, 100.0)),
            0.10,
            &[(6, 6), (6, 6)],
        ),
        row(
            "wave",
            2,
            summary(0.12, (10.5, 10.0), (180.0, 100.0)),
            0.12,
            &[(6, 6), (4, 4)],
        ),
        row(
            "salute",
            1,
            summary(0.08, (6.0, 5.5), (90.0, 100.0)),
            0.09,
            &[(0, 0), (1, 0)],
        ),
    ];
    let g = Gates::of(&good);
    assert_eq!(g.sets, 3);
    assert_eq!(g.joint_dtw, Some((0.10, 0.10)));
    assert!(g.reversals_above.is_empty() && g.jerk_above.is_empty());
    assert_eq!((g.hold_sets, g.hold_off.len()), (3, 0));
    // salute's demonstrations do not swing: no count gate for it
    assert_eq!(
        g.swings,
        vec![SwingGate {
            gesture: "wave".into(),
            hierarchy: 4,
            sequence: Some(4),
            folds: 4
        }]
    );
    let md = g.to_markdown();
    assert!(md.contains("1.00x") && md.contains("4 of 4 folds"), "{md}");
    assert!(!md.contains("not met"), "{md}");
    // the controls: one set each above the reversal and the jerk gates, a swing lost, and
    // every reproduction 20 % farther than GMM/GMR
    let mut bad = good.clone();
    bad[0].hsom.velocity_reversals = 11.5;
    bad[1].hsom.normalized_jerk = Some(201.0);
    bad[1].swings[0].0 = 5;
    // and salute's hold 30 % short
    bad[2].hsom.hold_s = 0.7 * bad[2].hsom.demo_hold_s;
    for r in &mut bad {
        let (h, g) = r.paired.as_mut().unwrap();
        h.joint_dtw_rad_per_step = 1.2 * g.joint_dtw_rad_per_step;
    }
    let g = Gates::of(&bad);
    assert_eq!(g.reversals_above, vec![("wave".to_string(), 1)]);
    assert_eq!(g.jerk_above, vec![("wave".to_string(), 2)]);
    assert_eq!(g.swings[0].hierarchy, 3);
    assert_eq!(g.hold_off, vec![("salute".to_string(), 1)]);
    let md = g.to_markdown();
    assert!(md.contains("1.20x") && md.contains("not met"), "{md}");
    assert!(
        md.contains("1 of 3 sets: wave 1") && md.contains("1 of 3 sets: wave 2"),
        "{md}"
    );
}

/// The JSON holds the study's fields and, beside them, one gates entry per configuration.
#[test]
fn the_json_holds_the_gates_beside_the_study() {
    let study = Study {
        count: 4,
        noise: 0.001,
        transition: "linear".into(),
        configs: vec![ConfigStudy {
            config: "a.xml".into(),
            rows: Vec::new(),
        }],
    };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("study.json");
    study.write_json(&path).unwrap();
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    assert_eq!(v["count"], 4);
    assert_eq!(v["configs"][0]["config"], "a.xml");
    assert_eq!(v["gates"].as_array().unwrap().len(), 1);
    assert_eq!(v["gates"][0]["sets"], 0);
    assert!(v["gates"][0]["joint_dtw"].is_null());
}
