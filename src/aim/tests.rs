use super::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn close(a: Point, b: Point, tol: f64) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= tol)
}

#[test]
fn the_kinematics_at_zero_are_the_models_offsets() {
    // every joint at 0: the offsets add up along x
    let g = Arm::Left.gripper(&[0.0; 5]);
    assert!(close(g, [0.2187, 0.113, 0.08769], 1e-9), "{g:?}");
    let g = Arm::Right.gripper(&[0.0; 5]);
    assert!(close(g, [0.2187, -0.113, 0.08787], 1e-9), "{g:?}");
    let (o, d) = camera(&[0.0, 0.0]);
    assert!(close(o, [0.05871, 0.0, 0.19014], 1e-9), "{o:?}");
    assert!(
        close(d, [0.0209435f64.cos(), 0.0, -0.0209435f64.sin()], 1e-12),
        "{d:?}"
    );
}

#[test]
fn a_reachable_target_is_pointed_at_within_the_ranges_nearest_the_held_posture() {
    let robot = Robot::UpperBody;
    let rest = crate::gesture::stand_init(robot);
    let right: crate::gesture::ArmPose = rest[8..14].try_into().unwrap();
    let held = crate::gesture::upper([0.0, 0.0], crate::gesture::library::POINT_LEFT, right);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..40 {
        let (az, el): (f64, f64) = (rng.gen_range(-5.0..55.0), rng.gen_range(-20.0..30.0));
        let r = rng.gen_range(0.5..3.0);
        let (az, el) = (az.to_radians(), el.to_radians());
        let s = Arm::Left.shoulder();
        let t = [
            s[0] + r * el.cos() * az.cos(),
            s[1] + r * el.cos() * az.sin(),
            s[2] + r * el.sin(),
        ];
        let q = point(robot, Arm::Left, &held, t).unwrap();
        let off = angle_to(s, Arm::Left.pointing(&q[2..7]), t);
        assert!(off < 1e-6, "{off} rad off at {t:?}");
        for (v, (lo, hi)) in q.iter().zip(robot.ranges()) {
            assert!((lo..=hi).contains(v));
        }
        // only the arm's four aiming joints move, and the elbow stays nearly straight
        assert_eq!(q[..2], held[..2]);
        assert_eq!(q[6..], held[6..]);
        assert!(q[5] > -0.4, "elbow bent to {} for {t:?}", q[5]);
    }
}

#[test]
fn a_target_behind_the_other_shoulder_is_refused_naming_the_closest_direction() {
    let robot = Robot::LeftArm;
    let held = crate::gesture::library::POINT_LEFT.to_vec();
    let e = point(robot, Arm::Left, &held, [-0.5, -2.0, 0.1]).unwrap_err();
    let text = e.to_string();
    assert!(text.contains("the left arm cannot aim at"), "{text}");
    assert!(
        text.contains("closest direction it reaches is azimuth"),
        "{text}"
    );
    let AimError::Unreachable { off, closest, .. } = e else {
        panic!("{e:?}")
    };
    assert!(off > 10.0, "{off}");
    assert!((Vector3::from(closest).norm() - 1.0).abs() < 1e-9);
    // too near, and not a point
    assert!(matches!(
        point(robot, Arm::Left, &held, [0.1, 0.1, 0.1]),
        Err(AimError::TooNear { .. })
    ));
    assert!(matches!(
        point(robot, Arm::Left, &held, [f64::NAN, 0.1, 0.1]),
        Err(AimError::NonFinite { .. })
    ));
    assert!(matches!(
        point(robot, Arm::Left, &held, [1e300, 0.0, 0.0]),
        Err(AimError::TooFar { .. })
    ));
    // far, but within the bound: solved as the direction
    assert!(point(robot, Arm::Left, &held, [900.0, 300.0, 100.0]).is_ok());
    assert!(matches!(
        point(robot, Arm::Right, &held, [1.0, -0.5, 0.1]),
        Err(AimError::Unsupported(_))
    ));
    assert!(matches!(
        look(robot, &held, [1.0, 0.0, 0.2]),
        Err(AimError::Unsupported(_))
    ));
}

#[test]
fn the_head_looks_at_a_target_and_refuses_one_behind_it() {
    let robot = Robot::UpperBody;
    let held = crate::gesture::stand_init(robot);
    for t in [
        [1.0, 0.5, 0.3],
        [2.0, -1.0, -0.3],
        [0.6, 0.0, 0.6],
        [0.5, 0.8, 0.0],
    ] {
        let q = look(robot, &held, t).unwrap();
        let (o, d) = camera(&q[..2]);
        assert!(angle_to(o, d, t) < 1e-6, "{t:?}");
        assert_eq!(q[2..], held[2..]);
    }
    let e = look(robot, &held, [-1.0, 0.0, 0.2]).unwrap_err();
    assert!(e.to_string().contains("the head cannot aim at"), "{e}");
    assert!(parse_point("1,2").unwrap_err().contains("need X,Y,Z"));
    assert_eq!(parse_point("1, 0.5,-2").unwrap(), [1.0, 0.5, -2.0]);
}

#[test]
fn the_held_part_is_where_the_rows_stay_near_their_apex() {
    // rise over rows 0..20, hold 20..50 (with a small drift), fall 50..70
    let rows: Vec<Vec<f64>> = (0..70)
        .map(|i| {
            let v = match i {
                0..20 => i as f64 / 20.0,
                20..50 => 1.0 + 0.01 * ((i - 20) as f64 / 30.0),
                _ => 1.0 - (i - 50) as f64 / 20.0,
            };
            vec![v, 0.0]
        })
        .collect();
    let (a, b) = held_span(&rows, 0..2);
    assert!((19..=20).contains(&a) && (50..=51).contains(&b), "{a}..{b}");
    // a posture that never moves has its apex at the start: a held part of the still rows
    let still = vec![vec![0.0, 0.0]; 5];
    assert_eq!(held_span(&still, 0..2), (0, 4));
}

#[cfg(feature = "sim")]
#[test]
fn the_kinematics_are_the_simulated_models() {
    use crate::sim::NaoArm;
    let arm = NaoArm::<14>::load_shipped(Robot::UpperBody).unwrap();
    let model = arm.model();
    let site = |n: &str| model.site_id(n).unwrap();
    let (l, r, cam) = (site("l_gripper"), site("r_gripper"), site("camera_top"));
    let mut sim = arm.sim().unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..50 {
        let q: Vec<f64> = (Robot::UpperBody.ranges().into_iter())
            .map(|(lo, hi)| rng.gen_range(lo..=hi))
            .collect();
        sim.set_posture_clamped(&q).unwrap();
        sim.forward().unwrap();
        let d = sim.data();
        assert!(close(Arm::Left.gripper(&q[2..7]), d.site_xpos(l), 1e-9));
        assert!(close(Arm::Right.gripper(&q[8..13]), d.site_xpos(r), 1e-9));
        let (o, axis) = camera(&q[..2]);
        let m = d.site_xmat(cam);
        assert!(close(o, d.site_xpos(cam), 1e-9));
        // the site frame's x-axis is the first column of its rotation (row-major)
        assert!(close(axis, [m[0], m[3], m[6]], 1e-9), "{axis:?} {m:?}");
    }
    // the left arm's model shares the frame
    let left = NaoArm::<6>::load_shipped(Robot::LeftArm).unwrap();
    let g = left.model().site_id("l_gripper").unwrap();
    let mut sim = left.sim().unwrap();
    let q = [-0.3, 0.4, -1.0, -0.2, 0.3, 0.0];
    sim.set_posture_clamped(&q).unwrap();
    sim.forward().unwrap();
    assert!(close(
        Arm::Left.gripper(&q[..5]),
        sim.data().site_xpos(g),
        1e-9
    ));
}

/// A left-arm pointing gesture as rows: rise over 40 rows, hold 40, fall 40.
fn pointing_rows() -> Vec<Vec<f64>> {
    let rest = crate::gesture::stand_init(Robot::LeftArm);
    let top = crate::gesture::library::POINT_LEFT;
    (0..120)
        .map(|i| {
            let s = match i {
                0..40 => crate::curve::minimum_jerk_at(i as f64 / 40.0),
                40..80 => 1.0,
                _ => 1.0 - crate::curve::minimum_jerk_at((i - 80) as f64 / 40.0),
            };
            rest.iter().zip(top).map(|(a, b)| a + s * (b - a)).collect()
        })
        .collect()
}

#[test]
fn an_aim_gives_via_points_along_the_held_part_and_a_new_target_moves_them() {
    let robot = Robot::LeftArm;
    let rows = pointing_rows();
    let t = [1.5, 1.0, 0.2];
    let aim = Aim {
        point_at: Some(t),
        look_at: None,
    };
    let (conditions, aiming) = Aiming::new(robot, &rows, &Conditions::default(), &aim).unwrap();
    let (a, b) = aiming.solved().span;
    // the hold, and the ends of the rise and the fall within 5 % of the apex
    assert!((30..=40).contains(&a) && (79..=90).contains(&b), "{a}..{b}");
    assert!(conditions.via.len() >= 5);
    for v in &conditions.via {
        let i = (v.phase * 119.0).round() as usize;
        assert!((a..=b).contains(&i));
        assert!(angle_to(Arm::Left.shoulder(), Arm::Left.pointing(&v.posture[..5]), t) < 1e-6);
        // the wrist and the hand as the row has them
        assert_eq!(v.posture[4..], rows[i][4..]);
    }
    let moved = [1.0, 0.2, 0.8];
    let next = aiming
        .retargeted(&Aim {
            point_at: Some(moved),
            look_at: None,
        })
        .unwrap();
    assert_eq!(next.via().len(), conditions.via.len());
    for (v, old) in next.via().iter().zip(&conditions.via) {
        assert_eq!(v.phase, old.phase);
        assert!(
            angle_to(
                Arm::Left.shoulder(),
                Arm::Left.pointing(&v.posture[..5]),
                moved
            ) < 1e-6
        );
    }
    // a look on the left arm, and a point on an aim that only looked, are refused
    let look = Aim {
        point_at: None,
        look_at: Some(t),
    };
    assert!(aiming.retargeted(&look).is_err());
    let up = Robot::UpperBody;
    let rest = crate::gesture::stand_init(up);
    let rows: Vec<Vec<f64>> = pointing_rows()
        .iter()
        .map(|r| {
            let mut q = rest.clone();
            q[2..8].copy_from_slice(r);
            q
        })
        .collect();
    let (_, looking) = Aiming::new(up, &rows, &Conditions::default(), &look).unwrap();
    assert!(matches!(
        looking.retargeted(&aim),
        Err(AimError::Unsupported(_))
    ));
}
