use super::*;

#[test]
fn named_postures_are_within_limits() {
    for p in NamedPosture::ALL {
        check_posture(&p.angles()).unwrap();
        assert_eq!(NamedPosture::from_name(p.name()), Some(p));
    }
}

#[test]
fn clamp_moves_to_the_limit_and_rejects_nan() {
    let mut p = NamedPosture::StandInit.angles();
    p[3] = 0.5;
    assert_eq!(clamp_posture(&p).unwrap()[3], -0.0349066);
    p[3] = f64::NAN;
    assert!(matches!(
        clamp_posture(&p),
        Err(SimError::NotFinite {
            joint: "LElbowRoll",
            ..
        })
    ));
    assert!(matches!(
        check_posture(&p[..5]),
        Err(SimError::WrongJointCount {
            expected: 6,
            got: 5
        })
    ));
}
