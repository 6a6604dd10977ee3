//! Headless regression tests of the Nao left-arm model and its position controller.
//!
//! Figures asserted (simulated time only, never wall clock):
//! - forward kinematics of `l_wrist` / `l_gripper` = the reference chain composed here from the
//!   documented offsets and axes, within 1e-9 m, at named and 200 random postures;
//! - reach: a key-pose transition ends within 0.5 mrad of the target on every joint, 0.2 s after
//!   the planned transition time;
//! - tracking: a 0.5 Hz, 0.4 rad sine on four joints (1.3 rad/s peak) is followed with a maximum
//!   error below 0.01 rad and a lag below 10 ms;
//! - holding StandInit for 5 s drifts less than 1e-4 rad (gravity compensation on) and sags less
//!   than 0.01 rad without it;
//! - recording: 40 samples per simulated second at 40 Hz, 100 at 100 Hz.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use cosco_hsom::sim::{
    check_posture, ArmSim, Controller, ControllerConfig, Grab, Interpolation, KeyPose,
    NamedPosture, NaoArm, SimError, TargetTrajectory, JOINT_NAMES, JOINT_SPECS,
};
use nalgebra::{Matrix3, Rotation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn arm() -> NaoArm {
    NaoArm::load_default().expect("the shipped model loads")
}

// ---------- the model ----------

#[test]
fn model_has_the_six_named_joints_with_the_documented_ranges() {
    let arm = arm();
    let m = arm.model();
    assert_eq!(m.nq(), 6);
    assert_eq!(m.nu(), 6);
    // the documented table (nao-left-arm.md), written here independently of src/sim
    let doc: [(&str, f64, f64, f64); 6] = [
        ("LShoulderPitch", -2.08567, 2.08567, 1.329),
        ("LShoulderRoll", -0.314159, 1.32645, 1.7835),
        ("LElbowYaw", -2.08567, 2.08567, 1.547),
        ("LElbowRoll", -1.54462, -0.0349066, 1.532),
        ("LWristYaw", -1.82387, 1.82387, 0.4075),
        ("LHand", 0.0, 1.0, 0.292),
    ];
    assert_eq!(JOINT_NAMES, doc.map(|d| d.0));
    for (k, (name, lo, hi, tau)) in doc.into_iter().enumerate() {
        let j = m.joint_id(name).unwrap_or_else(|| panic!("joint {name}"));
        let a = m
            .actuator_id(name)
            .unwrap_or_else(|| panic!("actuator {name}"));
        assert_eq!(m.joint_range(j), Some((lo, hi)), "{name}");
        assert_eq!(m.actuator_ctrl_range(a), Some((lo, hi)), "{name}");
        assert_eq!(m.actuator_force_range(a), Some((-tau, tau)), "{name}");
        assert_eq!(m.actuator_joint(a), Some(j));
        assert_eq!(JOINT_SPECS[k].range, (lo, hi));
        assert_eq!(m.joint_qpos_adr(j), k);
    }
    assert!(m.site_id("l_wrist").is_some() && m.site_id("l_gripper").is_some());
    assert!(m.camera_id("front").is_some());
    for g in arm.servo_gains() {
        assert!(g.kp > 0.0 && g.kv > 0.0);
    }
}

#[test]
fn model_masses_are_the_documented_ones() {
    let arm = arm();
    let m = arm.model();
    for (body, mass) in [
        ("LShoulder", 0.09304),
        ("LBicep", 0.15777),
        ("LElbow", 0.06483),
        ("LForeArm", 0.07761),
        ("l_wrist", 0.18533),
    ] {
        let b = m.body_id(body).unwrap_or_else(|| panic!("body {body}"));
        assert!((m.body_mass(b) - mass).abs() < 1e-12, "{body}");
    }
}

// ---------- kinematics ----------

/// The reference chain (nao-left-arm.md), composed from the documented offsets and axes.
fn reference_fk(q: &[f64; 6]) -> (Vector3<f64>, Vector3<f64>) {
    let x = Vector3::x_axis();
    let y = Vector3::y_axis();
    let z = Vector3::z_axis();
    let shoulder = Vector3::new(0.0, 0.098, 0.100); // ShoulderOffsetY, ShoulderOffsetZ
    let elbow = Vector3::new(0.105, 0.015, 0.0); // UpperArmLength, ElbowOffsetY
    let wrist = Vector3::new(0.05595, 0.0, 0.0); // LowerArmLength
    let hand = Vector3::new(0.05775, 0.0, -0.01231); // HandOffsetX, HandOffsetZ
    let r1: Matrix3<f64> = Rotation3::from_axis_angle(&y, q[0]).into_inner(); // LShoulderPitch
    let r2 = r1 * Rotation3::from_axis_angle(&z, q[1]).into_inner(); // LShoulderRoll
    let r3 = r2 * Rotation3::from_axis_angle(&x, q[2]).into_inner(); // LElbowYaw
    let r4 = r3 * Rotation3::from_axis_angle(&z, q[3]).into_inner(); // LElbowRoll
    let r5 = r4 * Rotation3::from_axis_angle(&x, q[4]).into_inner(); // LWristYaw
    let p_elbow = shoulder + r2 * elbow;
    let p_wrist = p_elbow + r4 * wrist;
    let p_gripper = p_wrist + r5 * hand;
    (p_wrist, p_gripper)
}

fn random_posture(rng: &mut ChaCha8Rng) -> [f64; 6] {
    std::array::from_fn(|k| rng.gen_range(JOINT_SPECS[k].range.0..=JOINT_SPECS[k].range.1))
}

fn fk_error(
    sim: &mut ArmSim<'_>,
    q: &[f64; 6],
    fk: impl Fn(&[f64; 6]) -> (Vector3<f64>, Vector3<f64>),
) -> f64 {
    sim.set_posture(q).unwrap();
    let (w, g) = fk(q);
    let dw = (Vector3::from(sim.wrist_position()) - w).norm();
    let dg = (Vector3::from(sim.gripper_position()) - g).norm();
    dw.max(dg)
}

#[test]
fn forward_kinematics_matches_the_reference_chain() {
    let arm = arm();
    let mut sim = arm.sim().unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut postures: Vec<[f64; 6]> = NamedPosture::ALL.iter().map(|p| p.angles()).collect();
    postures.extend((0..200).map(|_| random_posture(&mut rng)));
    let mut worst: f64 = 0.0;
    for q in &postures {
        worst = worst.max(fk_error(&mut sim, q, reference_fk));
    }
    assert!(worst < 1e-9, "worst FK error {worst} m");
}

#[test]
fn forward_kinematics_check_fails_for_a_wrong_chain() {
    // negative control: a chain 1 mm too long in the upper arm, or a flipped roll axis, is caught
    let arm = arm();
    let mut sim = arm.sim().unwrap();
    let q = NamedPosture::ReadingWatch.angles();
    let longer = |q: &[f64; 6]| {
        let (w, g) = reference_fk(q);
        let r = Rotation3::from_axis_angle(&Vector3::y_axis(), q[0])
            * Rotation3::from_axis_angle(&Vector3::z_axis(), q[1]);
        let d = r * Vector3::new(0.001, 0.0, 0.0);
        (w + d, g + d)
    };
    assert!(fk_error(&mut sim, &q, longer) > 9e-4);
    let flipped = |q: &[f64; 6]| reference_fk(&[q[0], -q[1], q[2], q[3], q[4], q[5]]);
    assert!(fk_error(&mut sim, &q, flipped) > 1e-2);
}

#[test]
fn naoqi_signs_and_the_documented_reading_watch_wrist_position() {
    let arm = arm();
    let mut sim = arm.sim().unwrap();
    // StandZero: arm straight forward at shoulder height
    sim.set_posture(&NamedPosture::StandZero.angles()).unwrap();
    let g0 = sim.gripper_position();
    assert!(g0[0] > 0.2 && (g0[2] - 0.1).abs() < 0.02, "{g0:?}");
    // positive LShoulderPitch lowers the arm; positive LShoulderRoll moves it to the left
    let mut q = NamedPosture::StandZero.angles();
    q[0] = 0.5;
    sim.set_posture(&q).unwrap();
    assert!(sim.gripper_position()[2] < g0[2] - 0.05);
    q[0] = 0.0;
    q[1] = 0.5;
    sim.set_posture(&q).unwrap();
    assert!(sim.gripper_position()[1] > g0[1] + 0.05);
    // the documented reading-watch wrist position
    sim.set_posture(&NamedPosture::ReadingWatch.angles())
        .unwrap();
    let w = sim.wrist_position();
    for (a, b) in w.iter().zip([0.117, 0.028, 0.119]) {
        assert!((a - b).abs() < 1.5e-3, "{w:?}");
    }
}

// ---------- controller ----------

fn controller(cfg: ControllerConfig) -> Controller {
    Controller::new(cfg).unwrap()
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn controller_reaches_key_poses_within_half_a_mrad_0_2_s_after_the_planned_transition() {
    let arm = arm();
    for interpolation in [Interpolation::MinimumJerk, Interpolation::Linear] {
        let ctl = controller(ControllerConfig {
            interpolation,
            ..Default::default()
        });
        let mut sim = arm.sim().unwrap();
        let mut from = sim.posture();
        for target in [
            NamedPosture::ReadingWatch,
            NamedPosture::StandZero,
            NamedPosture::Crouch,
            NamedPosture::StandInit,
        ] {
            let q = target.angles();
            let planned = ctl.transition_duration(&from, &q, 0.0);
            let rec = ctl
                .execute(
                    &mut sim,
                    &[KeyPose::new(&q).unwrap().with_hold(0.2).unwrap()],
                )
                .unwrap();
            let err = max_abs_diff(&sim.posture(), &q);
            eprintln!("{interpolation:?} -> {target:?}: planned {planned:.3} s, error {err:.2e} rad, samples {}", rec.len());
            assert!(err < 5e-4, "{interpolation:?} -> {target:?}: {err}");
            assert!((rec.time.last().unwrap() - (planned + 0.2)).abs() <= 0.025 + 1e-9);
            from = q;
        }
    }
}

#[test]
fn transitions_respect_the_velocity_limits_scaled_by_the_speed_fraction() {
    let arm = arm();
    for fraction in [0.3, 0.8] {
        let ctl = controller(ControllerConfig {
            speed_fraction: fraction,
            record_rate_hz: 500.0,
            ..Default::default()
        });
        let mut sim = arm.sim().unwrap();
        let rec = ctl
            .execute(
                &mut sim,
                &[KeyPose::new(&NamedPosture::ReadingWatch.angles()).unwrap()],
            )
            .unwrap();
        // planned target velocity never exceeds the limit; the measured one by less than 5 %
        for (name, k) in JOINT_NAMES.iter().zip(0..6) {
            let limit = fraction * JOINT_SPECS[k].max_velocity;
            let peak_target = rec
                .target
                .windows(2)
                .map(|w| (w[1][k] - w[0][k]).abs() * 500.0)
                .fold(0.0, f64::max);
            let peak = rec
                .qpos
                .windows(2)
                .map(|w| (w[1][k] - w[0][k]).abs() * 500.0)
                .fold(0.0, f64::max);
            assert!(
                peak_target <= limit * 1.0001,
                "{name}: {peak_target} > {limit}"
            );
            assert!(peak <= limit * 1.05, "{name}: {peak} > {limit}");
        }
    }
}

#[test]
fn min_duration_and_hold_lengthen_the_motion() {
    let arm = arm();
    let ctl = controller(ControllerConfig::default());
    let mut sim = arm.sim().unwrap();
    let pose = KeyPose::new(&NamedPosture::Stand.angles())
        .unwrap()
        .with_min_duration(2.0)
        .unwrap()
        .with_hold(1.0)
        .unwrap();
    let rec = ctl.execute(&mut sim, &[pose]).unwrap();
    assert_eq!(rec.len(), 120); // 3 s at 40 Hz
                                // the minimum-jerk transition is half-way at 1 s
    let mid = &rec.target[40];
    let (a, b) = (
        NamedPosture::StandInit.angles(),
        NamedPosture::Stand.angles(),
    );
    for k in 0..6 {
        assert!((mid[k] - 0.5 * (a[k] + b[k])).abs() < 1e-12);
    }
}

#[test]
fn controller_tracks_a_moving_target_with_bounded_error_and_lag() {
    let arm = arm();
    let ctl = controller(ControllerConfig {
        record_rate_hz: 500.0,
        ..Default::default()
    });
    let mut sim = arm.sim().unwrap();
    let centre = [0.9, 0.5, -0.8, -0.8, 0.0, 0.5];
    sim.set_posture(&centre).unwrap();
    let rate = 100.0;
    let targets: Vec<Vec<f64>> = (0..400)
        .map(|i| {
            let s = 0.4 * (std::f64::consts::TAU * 0.5 * i as f64 / rate).sin();
            vec![
                centre[0] + s,
                centre[1] + 0.5 * s,
                centre[2] + s,
                centre[3] + 0.5 * s,
                centre[4] + s,
                centre[5],
            ]
        })
        .collect();
    let traj = TargetTrajectory::at_rate(rate, &targets).unwrap();
    let rec = ctl.follow(&mut sim, &traj).unwrap();
    let skip = 100; // first 0.2 s
    let err = rec.qpos[skip..]
        .iter()
        .zip(&rec.target[skip..])
        .map(|(q, t)| max_abs_diff(q, t))
        .fold(0.0, f64::max);
    // lag: the shift of the target (in 2 ms samples) that best explains the encoders
    let lag_steps = (0..25usize)
        .min_by(|&a, &b| {
            let cost = |d: usize| -> f64 {
                (skip..rec.len())
                    .map(|i| (rec.qpos[i][0] - rec.target[i - d][0]).powi(2))
                    .sum()
            };
            cost(a).total_cmp(&cost(b))
        })
        .unwrap();
    let lag = lag_steps as f64 / 500.0;
    let per_joint: Vec<f64> = (0..6)
        .map(|k| {
            rec.qpos[skip..]
                .iter()
                .zip(&rec.target[skip..])
                .map(|(q, t)| (q[k] - t[k]).abs())
                .fold(0.0, f64::max)
        })
        .collect();
    eprintln!("tracking: max error {err:.2e} rad (per joint {per_joint:?}), lag {lag:.3} s");
    assert!(err < 0.01, "max tracking error {err}");
    assert!(lag < 0.010, "lag {lag}");
}

/// A hand grabbing the arm holds every joint where it was while the targets go on; once it
/// lets go the servos pull the arm after the targets again. Appending the motion that
/// followed keeps one clock.
#[test]
fn a_grab_holds_the_arm_still_while_the_targets_go_on_then_lets_go() {
    let arm = arm();
    let ctl = controller(ControllerConfig::default());
    let centre = [0.9, 0.5, -0.8, -0.8, 0.0, 0.5];
    let ramp: Vec<Vec<f64>> = (0..120)
        .map(|i| {
            let s = 0.4 * i as f64 / 120.0;
            vec![
                centre[0] + s,
                centre[1],
                centre[2] - s,
                centre[3],
                centre[4],
                0.5,
            ]
        })
        .collect();
    let traj = TargetTrajectory::at_rate(40.0, &ramp).unwrap();
    let run = |grab: Option<Grab>| {
        let mut sim = arm.sim().unwrap();
        sim.set_posture(&ramp[0]).unwrap();
        match grab {
            Some(g) => ctl.follow_grabbed(&mut sim, &traj, g).unwrap(),
            None => ctl.follow(&mut sim, &traj).unwrap(),
        }
    };
    let free = run(None);
    let held = run(Some(Grab {
        start_s: 1.0,
        seconds: 1.0,
    }));
    assert_eq!(held.len(), free.len());
    // before the grab: the same motion
    assert!(max_abs_diff(&held.qpos[39], &free.qpos[39]) < 1e-12);
    // during it (ticks 40..80): still, while the targets moved by 0.13 rad
    for row in &held.qpos[41..80] {
        assert!(max_abs_diff(row, &held.qpos[40]) < 1e-9, "{row:?}");
    }
    assert!(max_abs_diff(&held.target[79], &held.target[40]) > 0.1);
    // after it: pulled on, towards the targets
    let lag =
        |rec: &cosco_hsom::sim::Recording, i: usize| max_abs_diff(&rec.qpos[i], &rec.target[i]);
    assert!(lag(&held, 80) > 0.1, "at release {}", lag(&held, 80));
    assert!(
        lag(&held, 119) < lag(&held, 80) / 2.0,
        "{}",
        lag(&held, 119)
    );
    // the control: without a grab the arm follows throughout
    assert!(lag(&free, 79) < 0.02, "{}", lag(&free, 79));
    let mut whole = held.clone();
    whole.append(free.clone()).unwrap();
    assert_eq!(whole.len(), 2 * free.len());
    assert!((whole.time[120] - 3.0).abs() < 1e-12 && (whole.time[239] - 5.975).abs() < 1e-9);
    let mut other = free.clone();
    other.rate_hz = 100.0;
    assert!(whole
        .append(other)
        .unwrap_err()
        .to_string()
        .contains("100 Hz"));
    let mut sim = arm.sim().unwrap();
    let e = ctl
        .follow_grabbed(
            &mut sim,
            &traj,
            Grab {
                start_s: -1.0,
                seconds: 1.0,
            },
        )
        .unwrap_err()
        .to_string();
    assert!(e.contains("grab start"), "{e}");
}

#[test]
fn holds_stand_init_against_gravity() {
    let arm = arm();
    let q = NamedPosture::StandInit.angles();
    // with gravity compensation (default): no sag, no drift
    let ctl = controller(ControllerConfig::default());
    let mut sim = arm.sim().unwrap();
    let rec = ctl.hold(&mut sim, 5.0).unwrap();
    assert_eq!(rec.len(), 200);
    let drift = rec
        .qpos
        .iter()
        .map(|r| max_abs_diff(r, &q))
        .fold(0.0, f64::max);
    eprintln!("hold with gravity compensation: max deviation {drift:.2e} rad");
    assert!(drift < 1e-4, "{drift}");
    // without: the servos sag by tau_gravity / kp, then stay put
    let ctl = controller(ControllerConfig {
        gravity_compensation: false,
        ..Default::default()
    });
    let mut sim = arm.sim().unwrap();
    let rec = ctl.hold(&mut sim, 5.0).unwrap();
    let sag = rec
        .qpos
        .iter()
        .map(|r| max_abs_diff(r, &q))
        .fold(0.0, f64::max);
    let late_drift = max_abs_diff(&rec.qpos[80], rec.qpos.last().unwrap());
    eprintln!("hold without: sag {sag:.2e} rad, drift over the last 3 s {late_drift:.2e} rad");
    assert!(sag < 0.01 && sag > 1e-4, "{sag}");
    assert!(late_drift < 1e-5, "{late_drift}");
    // and the hand stays where it was
    let g = rec.gripper.first().unwrap();
    let h = rec.gripper.last().unwrap();
    assert!((Vector3::from(*g) - Vector3::from(*h)).norm() < 2e-3);
}

// ---------- recording ----------

#[test]
fn recording_yields_40_samples_per_second_by_default_and_100_at_100_hz() {
    let arm = arm();
    for (rate, seconds, expected) in [
        (40.0, 1.0, 40),
        (40.0, 2.5, 100),
        (100.0, 1.0, 100),
        (30.0, 1.0, 30),
    ] {
        let ctl = controller(ControllerConfig {
            record_rate_hz: rate,
            ..Default::default()
        });
        let mut sim = arm.sim().unwrap();
        let t0 = sim.time();
        let rec = ctl.hold(&mut sim, seconds).unwrap();
        assert_eq!(rec.len(), expected, "{rate} Hz, {seconds} s");
        assert_eq!(rec.qpos.len(), expected);
        assert_eq!(rec.wrist.len(), expected);
        assert_eq!(rec.gripper.len(), expected);
        for (k, t) in rec.time.iter().enumerate() {
            assert!((t - k as f64 / rate).abs() < 1e-12);
        }
        assert!((sim.time() - t0 - seconds).abs() < 1e-9);
        assert_eq!(rec.joint_names, JOINT_NAMES);
    }
    assert_eq!(
        Controller::new(ControllerConfig::default())
            .unwrap()
            .config()
            .record_rate_hz,
        40.0
    );
}

#[test]
fn recorded_sites_are_the_forward_kinematics_of_the_recorded_encoders() {
    let arm = arm();
    let ctl = controller(ControllerConfig::default());
    let mut sim = arm.sim().unwrap();
    let rec = ctl
        .execute(
            &mut sim,
            &[KeyPose::new(&NamedPosture::ReadingWatch.angles()).unwrap()],
        )
        .unwrap();
    for i in 0..rec.len() {
        let q: [f64; 6] = rec.qpos[i].clone().try_into().unwrap();
        let (w, g) = reference_fk(&q);
        // samples are interpolated between 2 ms physics steps: agreement to 10 micrometres
        assert!(
            (Vector3::from(rec.wrist[i]) - w).norm() < 1e-5,
            "sample {i}"
        );
        assert!(
            (Vector3::from(rec.gripper[i]) - g).norm() < 1e-5,
            "sample {i}"
        );
    }
}

#[test]
fn encoder_noise_is_seeded_and_has_the_requested_spread() {
    let arm = arm();
    let run = |seed, std| {
        let ctl = controller(ControllerConfig {
            encoder_noise_std: std,
            seed,
            ..Default::default()
        });
        let mut sim = arm.sim().unwrap();
        ctl.hold(&mut sim, 10.0).unwrap()
    };
    let clean = run(1, 0.0);
    let a = run(1, 0.01);
    let b = run(1, 0.01);
    let c = run(2, 0.01);
    assert_eq!(a, b);
    assert_ne!(a.qpos, c.qpos);
    assert_eq!(a.gripper, clean.gripper); // sites are not noisy
    let d: Vec<f64> = a
        .qpos
        .iter()
        .zip(&clean.qpos)
        .flat_map(|(x, y)| x.iter().zip(y).map(|(p, q)| p - q))
        .collect();
    let sd = (d.iter().map(|v| v * v).sum::<f64>() / d.len() as f64).sqrt();
    assert!((sd - 0.01).abs() < 0.001, "{sd}");
}

// ---------- bad input ----------

#[test]
fn bad_postures_are_rejected_with_the_joint_value_and_range() {
    let arm = arm();
    let mut sim = arm.sim().unwrap();
    let mut q = NamedPosture::StandInit.angles();
    q[3] = 0.2;
    let e = sim.set_posture(&q).unwrap_err();
    assert!(
        matches!(e, SimError::OutOfLimit { joint: "LElbowRoll", value, range } if value == 0.2 && range == (-1.54462, -0.0349066))
    );
    let msg = e.to_string();
    assert!(
        msg.contains("LElbowRoll") && msg.contains("0.2") && msg.contains("-1.54462"),
        "{msg}"
    );
    assert!(matches!(
        KeyPose::new(&q),
        Err(SimError::OutOfLimit {
            joint: "LElbowRoll",
            ..
        })
    ));
    assert!(matches!(
        sim.set_targets(&q),
        Err(SimError::OutOfLimit { .. })
    ));

    q = NamedPosture::StandInit.angles();
    q[1] = f64::NAN;
    assert!(matches!(
        sim.set_posture(&q),
        Err(SimError::NotFinite {
            joint: "LShoulderRoll",
            ..
        })
    ));
    q[1] = f64::INFINITY;
    assert!(matches!(
        check_posture(&q),
        Err(SimError::NotFinite {
            joint: "LShoulderRoll",
            ..
        })
    ));
    assert!(matches!(
        sim.set_posture_clamped(&[f64::NAN; 6]),
        Err(SimError::NotFinite { .. })
    ));

    assert!(matches!(
        sim.set_posture(&[0.0; 5]),
        Err(SimError::WrongJointCount {
            expected: 6,
            got: 5
        })
    ));
    assert!(matches!(
        KeyPose::new(&[0.0; 7]),
        Err(SimError::WrongJointCount {
            expected: 6,
            got: 7
        })
    ));
    assert!(matches!(
        sim.step_with_targets(&[]),
        Err(SimError::WrongJointCount { got: 0, .. })
    ));
    // nothing moved after the rejected calls
    assert_eq!(sim.posture(), NamedPosture::StandInit.angles());

    // the clamped variant moves the value to the limit
    q = NamedPosture::StandInit.angles();
    q[0] = 3.0;
    sim.set_posture_clamped(&q).unwrap();
    assert_eq!(sim.posture()[0], 2.08567);
    assert_eq!(KeyPose::new_clamped(&q).unwrap().posture()[0], 2.08567);
}

#[test]
fn bad_controller_settings_and_trajectories_are_rejected() {
    for rate in [0.0, -40.0, f64::NAN, f64::INFINITY, 1e9] {
        let e = Controller::new(ControllerConfig {
            record_rate_hz: rate,
            ..Default::default()
        })
        .unwrap_err();
        assert!(
            matches!(
                e,
                SimError::InvalidParameter {
                    name: "record_rate_hz",
                    ..
                }
            ),
            "{rate}"
        );
        assert!(TargetTrajectory::at_rate(rate, &[NamedPosture::Stand.angles().to_vec()]).is_err());
    }
    for f in [0.0, -0.5, 1.5, f64::NAN] {
        assert!(matches!(
            Controller::new(ControllerConfig {
                speed_fraction: f,
                ..Default::default()
            }),
            Err(SimError::InvalidParameter {
                name: "speed_fraction",
                ..
            })
        ));
    }
    for s in [-0.1, f64::NAN, f64::INFINITY] {
        assert!(Controller::new(ControllerConfig {
            encoder_noise_std: s,
            ..Default::default()
        })
        .is_err());
        assert!(KeyPose::new(&NamedPosture::Stand.angles())
            .unwrap()
            .with_hold(s)
            .is_err());
        assert!(KeyPose::new(&NamedPosture::Stand.angles())
            .unwrap()
            .with_min_duration(s)
            .is_err());
    }
    let p = NamedPosture::Stand.angles().to_vec();
    assert!(matches!(
        TargetTrajectory::new(&[], &[]),
        Err(SimError::InvalidTrajectory(_))
    ));
    assert!(TargetTrajectory::new(&[0.0, 0.0], &[p.clone(), p.clone()]).is_err());
    assert!(TargetTrajectory::new(&[0.0, 1.0], std::slice::from_ref(&p)).is_err());
    assert!(TargetTrajectory::new(&[-1.0], std::slice::from_ref(&p)).is_err());
    let mut bad = p.clone();
    bad[4] = 2.0;
    assert!(matches!(
        TargetTrajectory::at_rate(40.0, &[p.clone(), bad]),
        Err(SimError::OutOfLimit {
            joint: "LWristYaw",
            ..
        })
    ));
    assert!(matches!(
        TargetTrajectory::at_rate(40.0, &[p[..3].to_vec()]),
        Err(SimError::WrongJointCount { got: 3, .. })
    ));
}

#[test]
fn follow_replays_one_target_per_tick() {
    let arm = arm();
    let ctl = controller(ControllerConfig::default());
    let mut sim = arm.sim().unwrap();
    let a = NamedPosture::StandInit.angles();
    let b = NamedPosture::Stand.angles();
    let targets: Vec<Vec<f64>> = (0..80)
        .map(|i| {
            (0..6)
                .map(|k| a[k] + (b[k] - a[k]) * (i as f64 / 79.0))
                .collect()
        })
        .collect();
    let traj = TargetTrajectory::at_rate(40.0, &targets)
        .unwrap()
        .with_hold(0.5)
        .unwrap();
    let rec = ctl.follow(&mut sim, &traj).unwrap();
    assert_eq!(rec.len(), 100);
    for (got, want) in rec.target.iter().zip(&targets) {
        assert!(max_abs_diff(got, want) < 1e-12);
    }
    assert!(max_abs_diff(&sim.posture(), &b) < 3e-3);
    // StandInit -> Stand in 79 ticks: LElbowRoll moves 0.5927 rad in 1.975 s
    let f = traj.peak_velocity_fractions();
    assert!(
        (f[3] - (1.01 - 0.4173) / (79.0 / 40.0) / 7.19407).abs() < 1e-9,
        "{f:?}"
    );
    // as a demonstration for the learner
    let demo = rec.to_demonstration("follow");
    assert_eq!(demo.columns, JOINT_NAMES);
    assert_eq!(demo.rows, rec.qpos);
    assert_eq!(demo.time.as_deref(), Some(&rec.time[..]));
}

#[test]
fn reset_to_restarts_time_at_a_posture() {
    let arm = arm();
    let ctl = controller(ControllerConfig::default());
    let mut sim = arm.sim().unwrap();
    ctl.hold(&mut sim, 0.5).unwrap();
    assert!(sim.time() > 0.49);
    sim.reset_to(&NamedPosture::Crouch.angles()).unwrap();
    assert_eq!(sim.time(), 0.0);
    assert_eq!(sim.posture(), NamedPosture::Crouch.angles());
    assert_eq!(sim.velocities(), [0.0; 6]);
    assert!(sim.reset_to(&[0.0; 6]).is_err()); // LElbowRoll 0 is beyond its limit
}

// ---------- loading ----------

#[test]
fn broken_mjcf_returns_mujocos_message() {
    let e = NaoArm::from_xml_str("<mujoco><worldbody><body><geom type=\"sphere\" size=\"0.1\"/><joint type=\"nonsense\"/></body></worldbody></mujoco>")
        .unwrap_err();
    let msg = e.to_string();
    eprintln!("{msg}");
    assert!(matches!(e, SimError::Mujoco(_)));
    assert!(
        msg.contains("nonsense") || msg.to_lowercase().contains("invalid"),
        "{msg}"
    );
    assert!(matches!(
        NaoArm::load("/nonexistent/arm.xml"),
        Err(SimError::Mujoco(_))
    ));
}

#[test]
fn models_that_disagree_with_the_reference_table_are_rejected() {
    let xml = std::fs::read_to_string(NaoArm::default_model_path()).unwrap();
    // a valid MJCF without the arm
    let e = NaoArm::from_xml_str(
        "<mujoco><worldbody><geom type=\"plane\" size=\"1 1 1\"/></worldbody></mujoco>",
    )
    .unwrap_err();
    assert!(
        matches!(e, SimError::Missing { kind: "joint", ref name } if name == "LShoulderPitch"),
        "{e}"
    );
    // a wrong joint range
    let wrong = xml.replace(
        "range=\"-1.82387 1.82387\" armature",
        "range=\"-1.5 1.5\" armature",
    );
    assert_ne!(wrong, xml);
    let e = NaoArm::from_xml_str(&wrong).unwrap_err();
    assert!(
        matches!(e, SimError::ModelMismatch { ref name, what: "joint range", .. } if name == "LWristYaw"),
        "{e}"
    );
    // a missing site
    let e = NaoArm::from_xml_str(&xml.replace("name=\"l_gripper\"", "name=\"hand\"")).unwrap_err();
    assert!(matches!(e, SimError::Missing { kind: "site", .. }), "{e}");
    // the original is fine
    NaoArm::from_xml_str(&xml).unwrap();
}
